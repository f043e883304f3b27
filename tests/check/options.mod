MODULE options
  ! Names of RobotWare options rapidvc does not have: `rapidvc check` names the option of
  ! each (tests/cli/check_options.toml), and still reports a name nobody knows as such.
  PERS wztemporary wz_home := [0];
  CONST robtarget p10 := [[500, 0, 400], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];

  PROC main()
    VAR bool in_force;
    MoveJ p10, v1000, z10, tool0;
    ArcRefresh;
    FCDeact;
    in_force := FCIsForceMode();
    SyncMoveUndo;
    NoSuchInstruction;
  ENDPROC
ENDMODULE
