MODULE user_module
  ! The controller's USER system module: reg1 … reg5 and the stopwatch clock1 exist without
  ! a declaration, as on a controller delivered with ABB's user.sys. A name the program
  ! declares itself (reg3 here) is the program's.
  VAR num reg3 := 7;

  PROC test_registers_and_clock_exist()
    reg1 := 1;
    Incr reg2;
    Assert reg1 = 1;
    Assert reg2 = 1;
    Assert reg4 = 0;
    Assert reg5 = 0;
    Assert reg3 = 7 \Msg:="the program's own reg3";
    ClkReset clock1;
    ClkStart clock1;
    WaitTime 0.5;
    ClkStop clock1;
    Assert ClkRead(clock1) = 0.5;
  ENDPROC

  PROC test_registers_start_at_zero_in_every_test()
    Assert reg1 = 0;
    Assert reg2 = 0;
  ENDPROC
ENDMODULE
