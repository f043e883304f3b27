MODULE settings
  ! Modal motion settings: VelSet and AccSet slow the robot down, program displacement moves
  ! the targets of later moves, CalcRobT and CalcJointT are pure kinematics.
  CONST jointtarget home := [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p10 := [[1100, -300, 800], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p20 := [[1100, 300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR clock clk;
  VAR robtarget t;
  VAR jointtarget j;

  PROC main()
    MoveAbsJ home, v1000, fine, tool0;
    MoveL p10, v1000, fine, tool0;
    timed "MoveL p20, v500";
    MoveL p20, v500, fine, tool0;
    timed "";
    VelSet 50, 5000;
    timed "VelSet 50: MoveL p10, v500";
    MoveL p10, v500, fine, tool0;
    timed "";
    VelSet 100, 200;
    timed "VelSet 100, 200: MoveL p20, v500";
    MoveL p20, v500, fine, tool0;
    timed "";
    VelSet 100, 5000;
    AccSet 20, 10;
    timed "AccSet 20, 10: MoveL p10, v500";
    MoveL p10, v500, fine, tool0;
    timed "";
    AccSet 100, 100;
    SingArea \Wrist;
    ConfL \Off;
    PDispSet [[0, 0, 100], [1, 0, 0, 0]];
    MoveL p10, v500, fine, tool0;
    ! CPos and CRobT read positions as programmed, in the displaced frame.
    TPWrite "PDispSet z+100, MoveL p10: CPos " \Pos:=CPos();
    t := CRobT();
    TPWrite "  CRobT " \Pos:=t.trans;
    PDispOff;
    TPWrite "PDispOff: CRobT " \Pos:=CRobT().trans;
    PDispOn \ExeP:=Offs(p10, 0, 50, 0), p10, tool0;
    MoveL p20, v500, fine, tool0;
    TPWrite "PDispOn y+50, MoveL p20: CPos " \Pos:=CPos();
    PDispOff;
    TPWrite "PDispOff: CPos " \Pos:=CPos();
    j := CalcJointT(p20, tool0);
    TPWrite "CalcJointT p20 axis 1 " \Num:=j.robax.rax_1;
    t := CalcRobT(j, tool0);
    TPWrite "CalcRobT back " \Pos:=t.trans;
    TPWrite "  robconf " + ValToStr(t.robconf);
  ENDPROC

  PROC timed(string what)
    IF what = "" THEN
      TPWrite "  took " \Num:=ClkRead(clk);
    ELSE
      TPWrite what;
      ClkReset clk;
      ClkStart clk;
    ENDIF
  ENDPROC
ENDMODULE
