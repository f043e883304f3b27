MODULE storepath
  ! Path recovery as the RAPID reference shows it: in an ERROR handler StopMove, StorePath,
  ! move away and back, RestoPath, StartMoveRetry; in a TRAP StorePath (the robot stops on the
  ! path), a detour, RestoPath, StartMove; and ClearPath dropping a held move. The
  ! interrupted MoveL continues where it stopped (tests/run_path.rs checks the trace).
  CONST robtarget p10 := [[1100, -300, 800], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p20 := [[1100, 300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p30 := [[1100, 300, 600], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR num divisor := 0;
  VAR num x;
  VAR intnum detour;

  PROC with_error()
    VAR robtarget here;
    MoveL p20, v200, z10, tool0;
    WaitTime 1;
    ! ERR_DIVZERO while the robot is on its way to p20.
    x := 1 / divisor;
    MoveL p30, v200, fine, tool0;
    TPWrite "p30 reached, y " \Num:=Round(CPos().y);
  ERROR
    IF ERRNO = ERR_DIVZERO THEN
      StopMove;
      StorePath;
      here := CRobT();
      TPWrite "stored at y " \Num:=Round(here.trans.y);
      MoveL Offs(here, -100, 0, 0), v500, fine, tool0;
      TPWrite "away at x " \Num:=Round(CPos().x);
      MoveL here, v500, fine, tool0;
      RestoPath;
      divisor := 2;
      StartMoveRetry;
    ENDIF
  ENDPROC

  TRAP on_detour
    VAR robtarget p1;
    StorePath;
    p1 := CRobT();
    TPWrite "trap stored at y " \Num:=Round(p1.trans.y);
    MoveL Offs(p1, 0, 0, 100), v500, fine, tool0;
    MoveL p1, v500, fine, tool0;
    RestoPath;
    StartMove;
  ENDTRAP

  PROC with_trap()
    CONNECT detour WITH on_detour;
    ITimer \Single, 1, detour;
    MoveL p10, v200, fine, tool0;
    TPWrite "p10 reached, y " \Num:=Round(CPos().y);
  ENDPROC

  PROC main()
    MoveAbsJ [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v1000, fine, tool0;
    MoveL p10, v1000, fine, tool0;
    with_error;
    with_trap;
    ! ClearPath: the held move to p20 is dropped; the robot goes on from where it stopped.
    MoveL p20, v200, z10, tool0;
    WaitTime 1;
    StopMove;
    ClearPath;
    StartMove;
    TPWrite "cleared at y " \Num:=Round(CPos().y);
    MoveL Offs(CRobT(), 0, 0, -100), v200, fine, tool0;
    TPWrite "after ClearPath at z " \Num:=Round(CPos().z);
  ENDPROC
ENDMODULE
