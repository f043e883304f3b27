MODULE progdisp_tests
  ! `progdisp` is base RobotWare's record of a program displacement and the external-axis
  ! offsets (components pdisp: pose, eoffs: extjoint); real programs declare it.
  PROC test_progdisp_is_a_record_of_pose_and_extjoint()
    VAR progdisp pd := [[[10, 20, 30], [1, 0, 0, 0]], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
    VAR pose p;
    p := pd.pdisp;
    Assert p.trans.y = 20;
    pd.eoffs.eax_a := 5;
    Assert pd.eoffs.eax_a = 5;
    Assert pd.eoffs.eax_b = 9E9;
  ENDPROC
ENDMODULE
