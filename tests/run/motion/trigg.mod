! args: --config events
MODULE trigg
  ! TriggIO, TriggEquip, TriggInt, TriggSpeed with TriggL, TriggJ, TriggC: position events at
  ! a distance (mm) before the ToPoint, after the start point (\Start), or a time before the
  ! ToPoint (\Time), fired in the motion cycle where the TCP gets there (4 ms cycles: at
  ! 200 mm/s the TCP moves 0.8 mm per cycle). Traps print where the TCP is.
  CONST robtarget p10 := [[1100, -300, 800], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p20 := [[1100, 300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p30 := [[1100, 300, 600], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget pc := [[1100, 0, 500], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR intnum on1;
  VAR intnum off1;
  VAR intnum on2;
  VAR intnum at_point;
  VAR intnum sample;
  VAR triggdata gunon;
  VAR triggdata gunoff;
  VAR triggdata start20;
  VAR triggdata time02;
  VAR triggdata equip;
  VAR triggdata int10;
  VAR triggdata flow;
  VAR triggdata flowoff;
  VAR triggdata group;
  VAR triggdata unset;
  VAR robtarget origin;
  VAR robtarget target;
  VAR clock clk;

  TRAP report
    TPWrite NumToStr(ClkRead(clk), 3) + " s: do1 = " + NumToStr(DOutput(do1), 0) + ", do2 = "
      + NumToStr(DOutput(do2), 0) + ", " + NumToStr(Distance(CPos(), origin.trans), 1)
      + " mm from the start, " + NumToStr(Distance(CPos(), target.trans), 1) + " mm before the ToPoint";
  ENDTRAP

  TRAP trigg_int
    TPWrite "TriggInt: " + NumToStr(Distance(CPos(), target.trans), 1) + " mm before the ToPoint";
  ENDTRAP

  TRAP speed_sample
    TPWrite "ao1 = " + NumToStr(AOutput(ao1), 2) + " at " + NumToStr(ClkRead(clk), 2) + " s";
  ENDTRAP

  PROC main()
    MoveAbsJ [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v1000, fine, tool0;
    MoveL p10, v1000, fine, tool0;
    CONNECT on1 WITH report;
    ISignalDO do1, 1, on1;
    CONNECT off1 WITH report;
    ISignalDO do1, 0, off1;
    CONNECT on2 WITH report;
    ISignalDO do2, 1, on2;
    CONNECT at_point WITH trigg_int;
    ClkStart clk;
    ! RAPID reference, TriggIO example: "TriggIO gunon, 10 \DOp:=gun, 1; TriggL p1, v500,
    ! gunon, z50, gun1;" sets gun 10 mm before p1 (here 100 mm, with do1).
    TriggIO gunon, 100 \DOp:=do1, 1;
    ! \Start: 20 mm after the start point.
    TriggIO start20, 20 \Start \DOp:=do2, 1;
    ! TriggInt example: "TriggInt trigg1, 5, intno1;" 5 mm before the point (here 10 mm).
    TriggInt int10, 10, at_point;
    origin := p10;
    target := p20;
    TriggL p20, v200, gunon \T2:=start20 \T3:=int10, fine, tool0;
    ! \Time: 0.2 s before the ToPoint (40 mm at 200 mm/s, on the constant-speed part).
    TriggIO time02, 0.2 \Time \DOp:=do1, 0;
    origin := p20;
    target := p10;
    TriggL p10, v200, time02, fine, tool0;
    ! TriggEquip: the output is set EquipLag (0.1 s) earlier, so equipment with that lag acts
    ! 50 mm before the point: 50 + 20 mm before it.
    TriggEquip equip, 50, 0.1 \DOp:=do1, 1;
    target := p20;
    origin := p10;
    TriggJ p20, v200, equip, fine, tool0;
    ! An event in the corner path of a fly-by point: 10 mm before p30.
    TriggIO gunoff, 10 \DOp:=do1, 0;
    target := p30;
    origin := p20;
    TriggL p30, v200, gunoff, z50, tool0;
    MoveL p20, v200, fine, tool0;
    ! TriggC with a group output at the end point.
    TriggIO group, 0 \GOp:=go1, 5;
    TriggC pc, p10, v200, group, fine, tool0;
    TPWrite "go1 = " \Num:=GOutput(go1);
    ! TriggSpeed: ao1 = 0.05 × TCP speed (mm/s) origin 0 mm after the start, 0 after the end
    ! (RAPID reference: "TriggSpeed glueflow, 0, 0.05, glue_ao, 0.8 \DipLag:=0.04;").
    TriggSpeed flow, 0 \Start, 0, ao1, 0.05 \DipLag:=0.04;
    TriggSpeed flowoff, 0, 0, ao1, 0;
    CONNECT sample WITH speed_sample;
    ClkReset clk;
    ClkStart clk;
    ITimer 1, sample;
    TriggL p20, v200, flow \T2:=flowoff, fine, tool0;
    IDelete sample;
    TPWrite "after the move ao1 = " \Num:=AOutput(ao1);
    ! A triggdata no Trigg instruction defined.
    TriggL p10, v200, unset, fine, tool0;
  ERROR
    TPWrite "undefined triggdata: ERR_ARGVALERR " \Bool:=ERRNO = ERR_ARGVALERR;
    ! An interrupt that is not connected.
    IDelete at_point;
    TriggInt int10, 10, at_point;
  ENDPROC
ENDMODULE
