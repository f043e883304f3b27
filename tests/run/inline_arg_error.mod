MODULE inline_arg_error
  ! An argument fails (out of bounds) before a simple function with an unused parameter runs.
  VAR num data{3} := [1, 2, 3];
  FUNC num first(num a, num b)
    RETURN a;
  ENDFUNC
  PROC main()
    VAR num s;
    s := first(1, data{2});
    TPWrite "s " \Num:=s;
    s := first(1, data{4});
  ENDPROC
ENDMODULE
