MODULE WindowsEnds
  PROC main()
    x := 1 +;
    IF x > 0 THEN
      y := 2
    ENDIF
  ENDPROC
ENDMODULE
