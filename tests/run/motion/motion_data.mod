MODULE motion_data
  ! The current tool and work object (CTool, CWObj), the payload (GripLoad), external axis
  ! offsets (EOffsSet/EOffsOn/EOffsOff) as ORobT removes them, ReadMotor, and the settings a
  ! kinematic robot accepts without effect (ActUnit, MotionSup, SoftAct, CirPathMode).
  PERS tooldata tgrip := [TRUE, [[0, 0, 200], [1, 0, 0, 0]], [2, [0, 0, 100], [1, 0, 0, 0], 0, 0, 0]];
  PERS wobjdata wtable := [FALSE, TRUE, "", [[1000, 0, 500], [1, 0, 0, 0]], [[0, 0, 0], [1, 0, 0, 0]]];
  PERS loaddata part := [5, [0, 0, 50], [1, 0, 0, 0], 0, 0, 0];
  CONST robtarget p10 := [[100, -300, 300], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR tooldata t;
  VAR wobjdata w;
  VAR robtarget r;
  PERS loaddata l := [0.001, [0, 0, 0.001], [1, 0, 0, 0], 0, 0, 0];
  VAR string name;

  PROC main()
    MoveAbsJ [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v1000, fine, tool0;
    t := CTool();
    TPWrite "CTool after tool0: z " \Num:=t.tframe.trans.z;
    MoveL p10, v500, fine, tgrip \WObj:=wtable;
    t := CTool();
    w := CWObj();
    TPWrite "CTool: z " \Num:=t.tframe.trans.z;
    TPWrite "CWObj: uframe x " \Num:=w.uframe.trans.x;
    GripLoad part;
    GetSysData l \ObjectName:=name;
    TPWrite "GripLoad: " + name + ", mass " \Num:=l.mass;
    GripLoad load0;
    ActUnit ROB_1;
    MotionSup \On \TuneValue:=150;
    SoftAct 3, 20 \Ramp:=150;
    SoftDeact;
    CirPathMode \PathFrame;
    TPWrite "IsSyncMoveOn: " + ValToStr(IsSyncMoveOn());
    ! ReadMotor: the arm angle in radians (rapidvc's motor model, docs/robot.md).
    TPWrite "ReadMotor(1), CJointT().robax.rax_1 in rad: " \Num:=ReadMotor(1) - CJointT().robax.rax_1 * pi / 180;
    TPWrite "ReadMotor with MecUnit ROB_1, axis 5: " \Num:=Round(ReadMotor(\MecUnit:=ROB_1, 5) \Dec:=4);
    ! External axis offsets act on the extax fields: ORobT removes them.
    r := [[0, 0, 0], [1, 0, 0, 0], [0, 0, 0, 0], [100, 9E9, 9E9, 9E9, 9E9, 9E9]];
    EOffsSet [10, 20, 9E9, 9E9, 9E9, 9E9];
    TPWrite "EOffsSet 10: ORobT eax_a " \Num:=ORobT(r).extax.eax_a;
    TPWrite "ORobT with InEOffs keeps it: " \Num:=ORobT(r \InEOffs).extax.eax_a;
    EOffsOn \ExeP:=[[0, 0, 0], [1, 0, 0, 0], [0, 0, 0, 0], [130, 9E9, 9E9, 9E9, 9E9, 9E9]], r;
    TPWrite "EOffsOn 30: ORobT eax_a " \Num:=ORobT(r).extax.eax_a;
    EOffsOff;
    TPWrite "EOffsOff: ORobT eax_a " \Num:=ORobT(r).extax.eax_a;
    ! ORobT moves a point out of the program displacement frame into the object frame.
    PDispSet [[0, 0, 50], [1, 0, 0, 0]];
    TPWrite "PDisp 50: ORobT z " \Num:=ORobT(r).trans.z;
    TPWrite "ORobT with InPDisp: z " \Num:=ORobT(r \InPDisp).trans.z;
    PDispOff;
    DeactUnit ROB_1;
  ENDPROC
ENDMODULE
