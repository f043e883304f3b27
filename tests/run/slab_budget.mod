! args: --max-steps 500
MODULE slab_budget
  ! The operation budget stops a runaway recursion of `num` routines (run on the num frame
  ! slab) at the same step as elsewhere, with the call stack.
  VAR num depth := 0;

  FUNC num spin(num n)
    depth := depth + 1;
    RETURN spin(n + 1) + 1;
  ENDFUNC

  PROC main()
    VAR num r;
    r := spin(1);
  ENDPROC
ENDMODULE
