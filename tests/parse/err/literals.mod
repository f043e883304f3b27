MODULE Literals
  PROC main()
    s := "unterminated;
    s := "bad \q escape";
    s := "short \4";
    n := 1E39;
    n := 2 + 1E400;
    n := 0xFFFFFFFFFFFFFFFFFFFF;
    n := 12abc;
  ENDPROC
ENDMODULE
