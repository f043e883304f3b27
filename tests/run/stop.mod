MODULE stop
  ! Stop halts the program (exit 0); nothing after it runs.
  PROC main()
    TPWrite "working";
    Stop;
    TPWrite "never printed";
  ENDPROC
ENDMODULE
