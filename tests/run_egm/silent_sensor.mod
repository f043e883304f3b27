! rapidvc test program: a joint-mode EGM session whose configured sensor on device "sensor"
! never answers (\CommTimeout 0.3 s). The run must end with ERR_UDPUC_COMM (event 41822)
! with the robot where it started — also when another process on the sensor's host (another
! port) answers every message with its own target: only the configured address and port
! may steer.
MODULE SilentSensor
VAR egmident egm1;
VAR jointtarget jt;
CONST jointtarget home := [[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
PROC main()
  MoveAbsJ home, v1000, fine, tool0;
  EGMGetId egm1;
  EGMSetupUC ROB_1, egm1, "default", "sensor" \Joint \CommTimeout:=0.3;
  EGMActJoint egm1 \MaxSpeedDeviation:=40;
  EGMRunJoint egm1, EGM_STOP_HOLD \J1 \J2 \J3 \J4 \J5 \J6 \CondTime:=0.5 \RampInTime:=0.1;
  TPWrite "converged";
ERROR
  IF ERRNO = ERR_UDPUC_COMM THEN
    jt := CJointT();
    TPWrite "ERR_UDPUC_COMM at " + ValToStr(jt.robax);
    TRYNEXT;
  ENDIF
ENDPROC
ENDMODULE
