! args: --max-steps 1230
MODULE inline_budget
  ! The operation budget counts the RETURN of every simple function call.
  FUNC num f(num x)
    RETURN x + 1;
  ENDFUNC
  PROC main()
    VAR num acc;
    WHILE TRUE DO
      acc := f(acc) + f(1);
      IF acc > 100 acc := 0;
    ENDWHILE
  ENDPROC
ENDMODULE
