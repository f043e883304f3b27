! rapidvc test program: EGM failure modes, one entry routine each (--entry).
MODULE Failures
VAR egmident id;
VAR egmident other;
CONST jointtarget home := [[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
CONST jointtarget away := [[5,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
PROC setup()
  EGMGetId id;
  EGMSetupUC ROB_1, id, "default", "sensor" \Joint;
  EGMActJoint id \MaxSpeedDeviation:=20;
ENDPROC
! The first movement after the controller started may not be an EGM movement.
PROC no_move()
  setup;
  EGMRunJoint id, EGM_STOP_HOLD \J1;
ENDPROC
! An EGM movement must start in a fine point.
PROC fly_by()
  MoveAbsJ away, v1000, z50, tool0;
  setup;
  EGMRunJoint id, EGM_STOP_HOLD \J1;
ENDPROC
! EGMRunPose on a joint activation: fatal 41826, no ERROR handler catches it.
PROC mismatch()
  MoveAbsJ home, v1000, fine, tool0;
  setup;
  EGMRunPose id, EGM_STOP_HOLD \x;
ERROR
  TPWrite "caught";
ENDPROC
! A setup on an identity nobody reserved.
PROC not_reserved()
  EGMSetupUC ROB_1, other, "default", "sensor" \Joint;
ENDPROC
! A profile that does not exist.
PROC no_profile()
  EGMGetId id;
  EGMSetupUC ROB_1, id, "fast", "sensor" \Joint;
ENDPROC
! \NoWaitCond, EGMWaitCond, EGMStop; the program ends with a run active: it ramps out.
PROC no_wait()
  MoveAbsJ home, v1000, fine, tool0;
  setup;
  EGMRunJoint id, EGM_STOP_HOLD \NoWaitCond \J1 \CondTime:=0.2;
  TPWrite "running: "\Num:=EGMGetState(id);
  EGMWaitCond id;
  TPWrite "after EGMWaitCond: "\Num:=EGMGetState(id);
  EGMRunJoint id, EGM_STOP_HOLD \NoWaitCond \J1 \CondTime:=9E9;
  WaitTime 0.5;
  EGMStop id, EGM_STOP_HOLD;
  TPWrite "after EGMStop: "\Num:=EGMGetState(id);
  EGMRunJoint id, EGM_STOP_RAMP_DOWN \NoWaitCond \J1 \CondTime:=9E9;
  WaitTime 0.5;
  TPWrite "ends while running: "\Num:=EGMGetState(id);
ENDPROC
! A position stream to device "sensor" during ordinary motion.
PROC stream()
  MoveAbsJ home, v1000, fine, tool0;
  EGMGetId id;
  EGMSetupUC ROB_1, id, "default", "sensor" \Joint;
  EGMStreamStart id \SampleRate:=8;
  TPWrite "streaming: "\Num:=EGMGetState(id);
  MoveAbsJ away, v100, fine, tool0;
  EGMStreamStop id;
  TPWrite "stopped: "\Num:=EGMGetState(id);
  EGMActJoint id \StreamStart;
  TPWrite "streaming again: "\Num:=EGMGetState(id);
  MoveAbsJ home, v100, fine, tool0;
  EGMReset id;
  TPWrite "reset: "\Num:=EGMGetState(id);
ENDPROC
ENDMODULE
