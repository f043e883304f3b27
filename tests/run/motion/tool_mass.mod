MODULE tool_mass
  ! A robot-held tool without mass is refused before the robot moves, as on a controller
  ! (tool0 and load0 carry 0.001 kg for this reason): ERR_ARGVALERR, which an ERROR handler
  ! can take; unhandled, it stops the program at the move.
  PERS tooldata tNoMass := [TRUE, [[0, 0, 100], [1, 0, 0, 0]], [0, [0, 0, 1], [1, 0, 0, 0], 0, 0, 0]];
  PERS tooldata tNegative := [TRUE, [[0, 0, 100], [1, 0, 0, 0]], [-2.5, [0, 0, 1], [1, 0, 0, 0], 0, 0, 0]];
  PERS tooldata tLight := [TRUE, [[0, 0, 100], [1, 0, 0, 0]], [0.001, [0, 0, 1], [1, 0, 0, 0], 0, 0, 0]];
  CONST jointtarget home := [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST jointtarget other := [[10, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];

  PROC main()
    MoveAbsJ home, v1000, fine, tLight;
    TPWrite "0.001 kg: moved";
    try_tool;
    MoveAbsJ other, v1000, fine, tNegative;
    TPWrite "never printed";
  ENDPROC

  PROC try_tool()
    MoveAbsJ other, v1000, fine, tNoMass;
    TPWrite "never printed";
  ERROR
    TPWrite "0 kg: ERR_ARGVALERR " \Bool:=ERRNO = ERR_ARGVALERR;
    TPWrite "the robot did not move: axis 1 at " \Num:=CJointT().robax.rax_1;
    RETURN;
  ENDPROC
ENDMODULE
