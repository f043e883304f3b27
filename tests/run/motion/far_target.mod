MODULE far_target
  ! A MoveL/MoveC point at 9E9 or 3E38, or a program displacement of 1E30, is outside reach
  ! (ABB event 50050, ERR_OUTSIDE_REACH, catchable), not "a move lasting longer than 15
  ! minutes"; event texts write such numbers with an exponent.
  CONST jointtarget home := [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p9e9 := [[9E9, 0, 1000], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget pnear := [[1000, 0, 1000], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget pcir := [[1000, 3E38, 1000], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];

  PROC main()
    MoveAbsJ home, v1000, fine, tool0;
    try_linear;
    try_circle;
    PDispSet [[1E30, 0, 0], [1, 0, 0, 0]];
    MoveL pnear, v1000, fine, tool0;
    TPWrite "never printed";
  ENDPROC

  PROC try_linear()
    MoveL p9e9, v1000, fine, tool0;
  ERROR
    TPWrite "MoveL to 9E9: ERR_OUTSIDE_REACH " \Bool:=ERRNO = ERR_OUTSIDE_REACH;
    RETURN;
  ENDPROC

  PROC try_circle()
    MoveC pcir, pnear, v1000, fine, tool0;
  ERROR
    TPWrite "MoveC through 3E38: ERR_OUTSIDE_REACH " \Bool:=ERRNO = ERR_OUTSIDE_REACH;
    RETURN;
  ENDPROC
ENDMODULE
