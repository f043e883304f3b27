! rapidvc: the example of section 9.3.6.1 of the EGM manual ("Using EGM Position Guidance
! with an UdpUc device"), transcribed as printed. Repaired (OCR and layout
! damage): a stray "</pre>" after THEN, comment lines that had lost their "!" when the
! page was wrapped, and the typo "executeion" in a comment.
MODULE EGM_test
VAR egmident egmID1;
VAR egmstate egmSt1;
! limits for cartesian convergence: +-1 mm
CONST egm_minmax egm_minmax_lin1:=[-1,1];
! limits for orientation convergence: +-2 degrees
CONST egm_minmax egm_minmax_rot1:=[-2,2];
! Start position
CONST jointtarget
     jpos10:=[[0,0,0,0,40,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
! Used tool
TASK PERS tooldata tFroniusCMT:=[TRUE,[[12.3313,-0.108707,416.142],
     [0.903899, -0.00320735, 0.427666, 0.00765917]],
     [2.6,[-111.1,24.6,386.6],[1,0,0,0],0,0,0.072]];
! corr-frame: wobj, sens-frame: wobj
TASK PERS wobjdata wobj_EGM1:=[FALSE,TRUE,"",
     [[150,1320,1140],[1,0,0,0]], [[0,0,0],[1,0,0,0]]];
! Correction frame offset: none
VAR pose corr_frame_offs:=[[0,0,0],[1,0,0,0]];
PROC main()
! Move to start position. Fine point is demanded.
MoveAbsJ jpos10\NoEOffs, v1000, fine, tFroniusCMT;
testuc;
ENDPROC
PROC testuc()
EGMReset egmID1;
EGMGetId egmID1;
egmSt1:=EGMGetState(egmID1);
TPWrite "EGM state: "\Num:=egmSt1;
IF egmSt1 <= EGM_STATE_CONNECTED THEN
! Set up the EGM data source: UdpUc server using device "EGMsensor:" and
! configuration "default"
EGMSetupUC ROB_1, egmID1, "default", "EGMsensor:"\pose;
ENDIF
! Correction frame is the World coordinate system and the sensor measurements are relative
! to the tool frame of the used tool (tFroniusCMT)
EGMActPose egmID1\Tool:=tFroniusCMT, corr_frame_offs,
     EGM_FRAME_WORLD, tFroniusCMT.tframe, EGM_FRAME_TOOL
     \x:=egm_minmax_lin1 \y:=egm_minmax_lin1 \z:=egm_minmax_lin1
     \rx:=egm_minmax_rot1 \ry:=egm_minmax_rot1 \rz:=egm_minmax_rot1
     \LpFilter:=20;
! Run: the convergence condition has to be fulfilled during 2 seconds before RAPID
! execution continues to the next instruction
EGMRunPose egmID1, EGM_STOP_HOLD \x \y \z \CondTime:=2
     \RampInTime:=0.05;
egmSt1:=EGMGetState(egmID1);
IF egmSt1 = EGM_STATE_CONNECTED THEN
TPWrite "Reset EGM instance egmID1";
EGMReset egmID1;
ENDIF
ENDPROC
ENDMODULE
