! args: --config events
MODULE move_do
  ! MoveLDO, MoveJDO, MoveCDO, MoveLAO/JAO/CAO, MoveLGO/JGO/CGO, MoveLSync/JSync/CSync: the
  ! signal is set (the procedure called) when the TCP reaches the ToPoint: at the point for
  ! a stop point, in the middle of the corner path for a fly-by point (RAPID reference,
  ! MoveLDO: "MoveLDO p1, v1000, z30, tool2, do1,1;" sets do1 in the middle of the corner
  ! path at p1). A trap on the signal prints where the TCP is when it changes.
  CONST robtarget p10 := [[1100, -300, 800], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p20 := [[1100, 300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p30 := [[1100, 300, 600], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget pc := [[1100, 0, 500], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR intnum on1;
  VAR intnum off1;
  VAR robtarget target;
  VAR clock clk;

  TRAP do1_changed
    TPWrite "do1 = " + NumToStr(DOutput(do1), 0) + " at " + NumToStr(ClkRead(clk), 3)
      + " s, " + NumToStr(Distance(CPos(), target.trans), 1) + " mm from the ToPoint";
  ENDTRAP

  PROC synced()
    TPWrite "synced() at " + NumToStr(Distance(CPos(), target.trans), 1)
      + " mm from the ToPoint, ao1 = " + NumToStr(AOutput(ao1), 1) + ", go1 = "
      + NumToStr(GOutput(go1), 0);
  ENDPROC

  PROC main()
    MoveAbsJ [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v1000, fine, tool0;
    MoveL p10, v1000, fine, tool0;
    CONNECT on1 WITH do1_changed;
    ISignalDO do1, 1, on1;
    CONNECT off1 WITH do1_changed;
    ISignalDO do1, 0, off1;
    ClkStart clk;
    ! A stop point: at the point (600 mm at 200 mm/s: 3 s and the ramps).
    target := p20;
    MoveLDO p20, v200, fine, tool0, do1, 1;
    TPWrite "MoveLDO done, do1 = " \Num:=DOutput(do1);
    ! A fly-by point: in the middle of the corner path, near p30 but not on it (the trap
    ! runs at the stop point of the next move, p20, and prints the distance to p30).
    target := p30;
    MoveJDO p30, v200, z50, tool0, do1, 0;
    MoveL p20, v200, fine, tool0;
    ! A circle.
    target := p10;
    MoveCDO pc, p10, v200, fine, tool0, do1, 1;
    ! Analog and group outputs, and a procedure at the point.
    MoveLAO p20, v200, z10, tool0, ao1, 42.5;
    target := p30;
    MoveJGO p30, v200, fine, tool0, go1, 9;
    TPWrite "ao1 = " \Num:=AOutput(ao1);
    TPWrite "go1 = " \Num:=GOutput(go1);
    target := p20;
    MoveLSync p20, v200, fine, tool0, "synced";
    MoveCAO pc, p10, v200, z10, tool0, ao1, 7;
    MoveJAO p20, v200, z10, tool0, ao1, 7.5;
    MoveLGO p10, v200, z10, tool0, go1, 3;
    target := p30;
    MoveJSync p30, v200, fine, tool0, "synced";
    target := p20;
    MoveCGO pc, p10, v200, z10, tool0, go1, 15;
    MoveCSync pc, p20, v200, fine, tool0, "synced";
    ! Values are checked when the instruction runs: 200 is above ao1's range 0…100.
    MoveLAO p10, v200, fine, tool0, ao1, 200;
  ERROR
    TPWrite "MoveLAO: ERR_AO_LIM " \Bool:=ERRNO = ERR_AO_LIM;
    ! A procedure that does not exist is refused before the robot moves.
    MoveLSync p10, v200, fine, tool0, "nowhere";
  ENDPROC
ENDMODULE
