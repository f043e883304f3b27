MODULE slab_error
  ! An unhandled error deep in a recursion of `num` routines (run on the num frame slab):
  ! the error points at the failing operation and the call stack shows every call.
  FUNC num down(num n)
    IF n = 0 RETURN 1 DIV n;
    RETURN down(n - 1) + 1;
  ENDFUNC

  PROC main()
    VAR num r;
    r := down(3);
  ENDPROC
ENDMODULE
