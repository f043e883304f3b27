MODULE zones
  ! Fly-by points: RAPID runs ahead of the robot up to the next stop point, so the TPWrite
  ! after a fly-by move runs while the robot is still on its way; corner paths round the
  ! points (z200 is larger than half the distance to the neighbours and is shrunk).
  CONST jointtarget home := [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p10 := [[1100, -300, 800], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p20 := [[1100, 300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p30 := [[1300, 300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p40 := [[1300, -300, 800], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR clock clk;

  PROC main()
    MoveAbsJ home, v1000, fine, tool0;
    MoveL p10, v1000, fine, tool0;
    ClkStart clk;
    MoveL p20, v500, z50, tool0;
    TPWrite "queued MoveL p20 z50 at " \Num:=ClkRead(clk);
    MoveL p30, v500, z200, tool0;
    MoveJ p40, v500, z20, tool0;
    TPWrite "queued MoveJ p40 z20 at " \Num:=ClkRead(clk);
    MoveL p10, v500, fine, tool0;
    TPWrite "reached p10 (fine) at " \Num:=ClkRead(clk);
    TPWrite "  CPos " \Pos:=CPos();
    ! \Conc: even at a fine point the program goes on at once.
    MoveL \Conc, p20, v1000, fine, tool0;
    TPWrite "MoveL \\Conc, p20 fine queued at " \Num:=ClkRead(clk);
    WaitRob \InPos;
    TPWrite "in position at " \Num:=ClkRead(clk);
  ENDPROC
ENDMODULE
