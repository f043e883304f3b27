MODULE Stray
  PROC main()
    x := 1;
    ENDIF
    y := 2;
  ENDPROC
  PROC other()
    ELSE
  ENDPROC
ENDMODULE
