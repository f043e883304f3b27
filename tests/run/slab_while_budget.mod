! args: --max-steps 300
MODULE slab_while_budget
  ! The operation budget stops an endless WHILE in a `num` routine run on the num frame
  ! slab at the same step as elsewhere, with the call stack.
  VAR num n := 0;

  PROC spin(num k)
    WHILE k > 0 DO
      n := n + 1;
    ENDWHILE
    spin k - 1;
  ENDPROC

  PROC main()
    spin 1;
  ENDPROC
ENDMODULE
