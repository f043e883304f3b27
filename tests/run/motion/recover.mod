MODULE recover
  ! Motion errors are RAPID errors that ERROR handlers can take: ERR_OUTSIDE_REACH for a
  ! position nothing reaches, ERR_ROBLIMIT for axis limits and an unreachable programmed
  ! configuration. After each, the robot moves on.
  CONST jointtarget home := [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget pfar := [[3000, 0, 1000], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  ! Reachable, but not with axis 1 in its first quadrant (the target lies at y < 0).
  CONST robtarget pconf := [[1100, -300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST jointtarget jlimit := [[0, 0, 90, 0, 30, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR jointtarget jt;
  VAR errnum err;

  PROC main()
    MoveAbsJ home, v1000, fine, tool0;
    try_move pfar, "pfar";
    try_move pconf, "pconf";
    MoveAbsJ jlimit, v1000, fine, tool0;
    TPWrite "never printed";
  ERROR
    TPWrite "main: ERRNO = ERR_ROBLIMIT: " \Bool:=ERRNO = ERR_ROBLIMIT;
    ConfJ \Off;
    MoveJ pconf, v1000, fine, tool0;
    jt := CalcJointT(pfar, tool0 \ErrorNumber:=err);
    TPWrite "CalcJointT pfar: ERR_OUTSIDE_REACH " \Bool:=err = ERR_OUTSIDE_REACH;
    TPWrite "ConfJ \\Off: pconf reached at " \Pos:=CPos();
  ENDPROC

  PROC try_move(robtarget p, string name)
    MoveJ p, v1000, fine, tool0;
    TPWrite name + ": after the move";
  ERROR
    IF ERRNO = ERR_OUTSIDE_REACH THEN
      TPWrite name + ": ERR_OUTSIDE_REACH";
    ELSEIF ERRNO = ERR_ROBLIMIT THEN
      TPWrite name + ": ERR_ROBLIMIT";
    ENDIF
    ! TRYNEXT goes on after the move that failed.
    TRYNEXT;
  ENDPROC
ENDMODULE
