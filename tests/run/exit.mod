MODULE leave
  ! EXIT ends execution from any depth.
  PROC deep()
    TPWrite "leaving from deep";
    EXIT;
  ENDPROC
  PROC main()
    deep;
    TPWrite "never printed";
  ENDPROC
ENDMODULE
