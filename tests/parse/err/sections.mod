MODULE Sections
  PROC main()
    Stop;
  UNDO
    Stop;
  ERROR
    RETRY;
  ERROR
    TRYNEXT;
  BACKWARD
    Stop;
  ENDPROC
ENDMODULE
