MODULE unknown_routines
  ! Three kinds of call that reach no routine, each told apart by `rapidvc check`
  ! (tests/cli/check_unknown_routines.toml): the program's own routine that no loaded module
  ! declares, an instruction of base RobotWare that rapidvc does not implement, and one of a
  ! RobotWare option.

  PROC main()
    VAR num torque;
    FooBarBaz 1;
    torque := MyOwnTorque(2);
    TuneServo ROB_1, 1, 100;
    ArcRefresh;
  ENDPROC
ENDMODULE
