! rapidvc test program: a joint-mode EGM session against a hostile sensor on device "sensor".
! Phase 1: the sensor's target [10,-5,20,0,40,30] arrives amid garbage (random, truncated and
! oversized datagrams, NaN references, references beyond an axis limit, a second sender on
! another port asking for [-40,...]): the run must converge on the real target.
! Phase 2: the sensor asks for [-10,5,10,0,35,-20], then falls silent: ERR_UDPUC_COMM (event
! 41822); the ERROR handler retries, the sensor answers again and the run converges.
MODULE Hostile
VAR egmident egm1;
VAR jointtarget jt;
VAR num corr;
CONST jointtarget home := [[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
PROC main()
  MoveAbsJ home, v1000, fine, tool0;
  EGMGetId egm1;
  EGMSetupUC ROB_1, egm1, "default", "sensor" \Joint \CommTimeout:=1;
  EGMActJoint egm1 \MaxSpeedDeviation:=40;
  EGMRunJoint egm1, EGM_STOP_HOLD \J1 \J2 \J3 \J4 \J5 \J6 \CondTime:=0.5 \RampInTime:=0.1;
  jt := CJointT();
  TPWrite "phase 1: " + ValToStr(jt.robax);
  EGMRunJoint egm1, EGM_STOP_HOLD \J1 \J2 \J3 \J4 \J5 \J6 \CondTime:=0.5 \RampInTime:=0.1;
  jt := CJointT();
  TPWrite "phase 2: " + ValToStr(jt.robax);
  TPWrite "state: "\Num:=EGMGetState(egm1 \CorrectionState:=corr);
  TPWrite "corr: "\Num:=corr;
ERROR
  IF ERRNO = ERR_UDPUC_COMM THEN
    TPWrite "ERR_UDPUC_COMM, state "\Num:=EGMGetState(egm1 \CorrectionState:=corr);
    TPWrite "corr: "\Num:=corr;
    RETRY;
  ENDIF
ENDPROC
ENDMODULE
