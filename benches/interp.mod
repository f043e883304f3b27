MODULE bench
  ! The interpreter benchmark: a loop of arithmetic, array indexing and a function call.
  ! benches/interp.py runs the same algorithm in CPython; benches/interp.rs times both.
  CONST num ITERATIONS := 10000000;
  VAR num data{100};

  FUNC num f(num x)
    RETURN x * 2 + 1;
  ENDFUNC

  PROC main()
    VAR num acc := 0;
    VAR num k;
    FOR i FROM 1 TO ITERATIONS DO
      k := i MOD 100 + 1;
      data{k} := (data{k} + f(k)) MOD 1000;
      acc := (acc + data{k}) MOD 65536;
    ENDFOR
    TPWrite "acc: " \Num:=acc;
  ENDPROC
ENDMODULE
