! rapidvc test program: a joint-mode EGM session against an external sensor on device
! "sensor" (the test points it at a client with --device). The sensor's target is
! [10,-5,20,0,40,30]; the program prints the EGM states and where the robot ends.
MODULE JointSession
VAR egmident egm1;
VAR jointtarget jt;
CONST jointtarget home := [[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
CONST egm_minmax win := [-0.2,0.2];
PROC main()
  MoveAbsJ home, v1000, fine, tool0;
  EGMReset egm1;
  EGMGetId egm1;
  TPWrite "state after EGMGetId: "\Num:=EGMGetState(egm1);
  EGMSetupUC ROB_1, egm1, "default", "sensor" \Joint \CommTimeout:=5;
  TPWrite "state after EGMSetupUC: "\Num:=EGMGetState(egm1);
  EGMActJoint egm1 \J1:=win \J2:=win \J3:=win \J4:=win \J5:=win \J6:=win
    \MaxSpeedDeviation:=40;
  EGMRunJoint egm1, EGM_STOP_HOLD \J1 \J2 \J3 \J4 \J5 \J6 \CondTime:=0.5 \RampInTime:=0.1;
  TPWrite "state after EGMRunJoint: "\Num:=EGMGetState(egm1);
  jt := CJointT();
  TPWrite "joints: " + ValToStr(jt.robax);
  EGMReset egm1;
  TPWrite "state after EGMReset: "\Num:=EGMGetState(egm1);
ENDPROC
ENDMODULE
