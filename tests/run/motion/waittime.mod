MODULE waittime
  ! The robot moves on while the program waits: WaitTime runs on the controller's clock.
  ! WaitRob \ZeroSpeed and \InPos wait for the robot; WaitTime \InPos waits for it first.
  CONST jointtarget home := [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p10 := [[1100, -300, 800], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p20 := [[1100, 300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR clock clk;

  PROC main()
    MoveAbsJ home, v1000, fine, tool0;
    MoveL p10, v1000, fine, tool0;
    ClkStart clk;
    MoveL p20, v100, z10, tool0;
    TPWrite "MoveL p20 queued at " \Num:=ClkRead(clk);
    WaitTime 2;
    TPWrite "after WaitTime 2 the TCP is at " \Pos:=CPos();
    WaitRob \InPos;
    TPWrite "WaitRob \\InPos ends at " \Num:=ClkRead(clk);
    TPWrite "  CPos " \Pos:=CPos();
    MoveL p10, v1000, z10, tool0;
    WaitTime \InPos, 0.5;
    TPWrite "WaitTime \\InPos, 0.5 ends at " \Num:=ClkRead(clk);
    TPWrite "  CPos " \Pos:=CPos();
  ENDPROC
ENDMODULE
