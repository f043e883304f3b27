! rapidvc test program: a pose-mode EGM session against an external sensor on device
! "sensor". Correction and sensor frame are the world frame and the tool is tool0, so the
! sensor's target is the flange in world coordinates: [1068.61,-30,1457.5] with the start
! orientation [0.5,0,0.866025,0]. The program prints the EGM states and where the robot ends.
MODULE PoseSession
VAR egmident egm1;
VAR robtarget p;
CONST jointtarget home := [[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
CONST pose world := [[0,0,0],[1,0,0,0]];
CONST egm_minmax lin := [-0.5,0.5];
CONST egm_minmax rot := [-0.2,0.2];
PROC main()
  MoveAbsJ home, v1000, fine, tool0;
  EGMReset egm1;
  EGMGetId egm1;
  TPWrite "state after EGMGetId: "\Num:=EGMGetState(egm1);
  EGMSetupUC ROB_1, egm1, "default", "sensor" \Pose \CommTimeout:=5;
  TPWrite "state after EGMSetupUC: "\Num:=EGMGetState(egm1);
  EGMActPose egm1 \Tool:=tool0 \WObj:=wobj0, world, EGM_FRAME_WORLD, world, EGM_FRAME_WORLD
    \x:=lin \y:=lin \z:=lin \rx:=rot \ry:=rot \rz:=rot \MaxSpeedDeviation:=40;
  EGMRunPose egm1, EGM_STOP_HOLD \x \y \z \rx \ry \rz \CondTime:=0.5 \RampInTime:=0.1;
  TPWrite "state after EGMRunPose: "\Num:=EGMGetState(egm1);
  p := CRobT(\Tool:=tool0 \WObj:=wobj0);
  TPWrite "pos: " + ValToStr(p.trans);
  TPWrite "orient: " + ValToStr(p.rot);
  EGMReset egm1;
  TPWrite "state after EGMReset: "\Num:=EGMGetState(egm1);
ENDPROC
ENDMODULE
