MODULE inline_error
  ! An error inside an inlined simple function: its frame is in the call stack.
  VAR num data{3};
  FUNC num inv(num x)
    RETURN 10 / (x - 2);
  ENDFUNC
  PROC work(num n)
    VAR num acc;
    FOR i FROM 1 TO n DO
      acc := acc + inv(i);
    ENDFOR
  ENDPROC
  PROC main()
    work 5;
  ENDPROC
ENDMODULE
