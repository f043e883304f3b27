MODULE Operators
  PROC main()
    ok := a AND NOT b;
    ok := a OR NOT b;
    ok := a < b < c;
    ok := a = b <> c;
  ENDPROC
ENDMODULE
