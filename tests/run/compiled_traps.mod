MODULE compiled_traps
  ! Traps between statements of compiled loops (an armed interrupt polls every statement):
  ! the trap changes data the loop reads, and fails once inside a simple function.
  VAR intnum timer;
  VAR num scale := 1;
  VAR num hits := 0;
  VAR num data{4} := [1, 2, 3, 4];
  FUNC num f(num x)
    RETURN x * scale + 1;
  ENDFUNC
  FUNC num g(num x)
    RETURN 10 / (x - 3);
  ENDFUNC
  TRAP on_timer
    hits := hits + 1;
    scale := scale * 2;
    TPWrite "trap " \Num:=hits;
  ENDTRAP
  PROC main()
    VAR num acc;
    CONNECT timer WITH on_timer;
    ITimer 0.5, timer;
    FOR i FROM 1 TO 6 DO
      acc := (acc + f(data{i MOD 4 + 1})) MOD 1000;
      WaitTime 0.3;
      TPWrite "acc " \Num:=acc;
    ENDFOR
    IDelete timer;
    acc := g(hits);
  ENDPROC
ENDMODULE
