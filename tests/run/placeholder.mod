MODULE placeholder
  ! A placeholder left in a program is a warning; running into it stops the program.
  PROC main()
    TPWrite "before";
    <SMT>
    TPWrite "never printed";
  ENDPROC
ENDMODULE
