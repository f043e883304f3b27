MODULE stopmove
  ! StopMove in a TRAP (an ITimer) decelerates the robot on its path and holds it there;
  ! StartMove resumes the interrupted MoveL; SpeedRefresh changes the speed of the ongoing
  ! move. tests/run_path.rs checks the trace (on the line, within the accelerations).
  CONST robtarget p10 := [[1100, -300, 800], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p20 := [[1100, 300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR intnum hold;
  VAR intnum slow;
  VAR clock clk;
  VAR num y_held;

  TRAP on_hold
    StopMove;
    y_held := Round(CPos().y);
    TPWrite "held at y " \Num:=y_held;
    TPWrite "IsStopMoveAct: " + ValToStr(IsStopMoveAct(\FromMoveTask));
    TPWrite "from another task: " + ValToStr(IsStopMoveAct(\FromNonMoveTask));
    WaitTime 1;
    TPWrite "after 1 s still at y " \Num:=Round(CPos().y);
    StartMove;
  ENDTRAP

  TRAP on_slow
    SpeedRefresh 50;
    TPWrite "CSpeedOverride: " \Num:=CSpeedOverride();
  ENDTRAP

  PROC main()
    MoveAbsJ [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v1000, fine, tool0;
    MoveL p10, v1000, fine, tool0;
    ClkStart clk;
    CONNECT hold WITH on_hold;
    ITimer \Single, 1, hold;
    MoveL p20, v200, fine, tool0;
    TPWrite "p20 reached at " \Num:=ClkRead(clk);
    TPWrite "IsStopMoveAct: " + ValToStr(IsStopMoveAct(\FromMoveTask));
    ClkReset clk;
    ClkStart clk;
    CONNECT slow WITH on_slow;
    ITimer \Single, 1, slow;
    MoveL p10, v200, fine, tool0;
    TPWrite "p10 reached at " \Num:=ClkRead(clk);
    SpeedRefresh 100;
    ! A StopMove at rest holds the moves queued after it until StartMove.
    StopMove \Quick;
    MoveL p20, v1000, z10, tool0 \WObj:=wobj0;
    WaitTime 0.5;
    TPWrite "queued behind StopMove, y " \Num:=Round(CPos().y);
    StopMoveReset;
    TPWrite "after StopMoveReset: " + ValToStr(IsStopMoveAct());
    StartMove;
    MoveL p10, v1000, fine, tool0;
    TPWrite "back at p10, y " \Num:=Round(CPos().y);
  ENDPROC
ENDMODULE
