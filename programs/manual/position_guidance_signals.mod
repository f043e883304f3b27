! rapidvc: the example of section 9.3.6.2 of the EGM manual ("Using EGM Position Guidance
! with signals as input"), transcribed as printed. Repaired (OCR and layout
! damage): comment lines that had lost their "!" when the page was wrapped, the OCR'd
! names "eqmID1"/"eqmID2" (egmID1/egmID2) and "ao MoveY" (ao_MoveY), and two LaTeX artefacts
! that replaced "\x:=egm_minmax_lin1 \y:=egm_minmax_lin1 \z:=egm_minmax_lin1".
! The analog output signals ao_MoveX ... ao_RotZ are I/O signals of the controller's I/O
! configuration, not RAPID data; they are not declared here.
MODULE EGM_test
VAR egmident egmID1;
VAR egmident egmID2;
CONST egm_minmax egm_minmax_lin1:=[-1,1];
CONST egm_minmax egm_minmax_rot1:=[-2,2];
CONST egm_minmax egm_minmax_joint1:=[-0.1,0.1];
CONST robtarget p20:=[[150,1320,1140],
     [0.000494947, 0.662278, -0.749217, -0.00783173], [0,0,-1,0],
     [9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
CONST robtarget p30:=[[114.50,1005.42,1410.38],
     [0.322151, -0.601023, 0.672381, 0.287914], [0,0,-1,0],
     [9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
CONST jointtarget
     jpos10:=[[0,0,0,0,35,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
CONST pose posecor:=[[1200,400,900],[1,0,0,0]];
CONST pose posesens:=[[12.3313,-0.108707,416.142],
     [0.903899,-0.00320735,0.427666,0.00765917]];
! corr-frame: world, sens-frame: world
VAR pose posecor0:=[[0,0,0],[1,0,0,0]];
VAR pose posesen0:=[[0,0,0],[1,0,0,0]];
TASK PERS tooldata tFroniusCMT:=[TRUE,[[12.3313,-0.108707,416.142],
     [0.903899,-0.00320735,0.427666,0.00765917]],
     [2.6,[-111.1,24.6,386.6],[1,0,0,0],0,0,0.072]];
TASK PERS loaddata load1:=[5,[0,1,0],[1,0,0,0],0,0,0];
! corr-frame: wobj, sens-frame: wobj
TASK PERS wobjdata
     wobj_EGM1:=[FALSE,TRUE,"",[[150,1320,1140],[1,0,0,0]],
     [[0,0,0],[1,0,0,0]]];
VAR pose posecor1:=[[0,0,0],[1,0,0,0]];
VAR pose posesen1:=[[0,0,0],[1,0,0,0]];
TASK PERS wobjdata
           wobj_EGM2:=[FALSE,TRUE,"",[[0,1000,1000],[1,0,0,0]],
           [[0,0,0],[1,0,0,0]]];
VAR pose posecor2:=[[150,320,0],[1,0,0,0]];
VAR pose posesen2:=[[150,320,0],[1,0,0,0]];
PROC main()
MoveAbsJ jpos10\NoEOffs, v1000, fine, tFroniusCMT;
testAO;
ENDPROC
PROC testAO()
! Get two different EGM identities. They will be used for two different EGM setups.
EGMGetId egmID1;
EGMGetId egmID2;
! Set up the EGM data source: Analog output signals and configuration "default"
! One guidance using Pose mode and one using Joint mode
EGMSetupAO ROB_1,egmID1,"default" \Pose \aoR1x:=ao_MoveX
            \aoR2y:=ao_MoveY \aoR3z:=ao_MoveZ \aoR5ry:=ao_RotY
            \aoR6rz:=ao_RotZ;
EGMSetupAO ROB_1,egmID2,"default" \Joint \aoR1x:=ao_MoveX
           \aoR2y:=ao_MoveY \aoR3z:=ao_MoveZ \aoR4rx:=ao_RotX
           \aoR5ry:=ao_RotY \aoR6rz:=ao_RotZ;
! Move to the starting point - fine point is needed.
MoveJ p30, v1000, fine, tool0;
! Set the signals
SetAO ao_MoveX, 150;
SetAO ao_MoveY, 1320;
SetAO ao_MoveZ, 900;
! Correction frame is the World coordinate system and the sensor measurements are also relative to the world frame
! No offset is defined (posecor0 and posesen0)
EGMActPose egmID1 \Tool:=tFroniusCMT \WObj:=wobj0 \TLoad:=load1,
           posecor0, EGM_FRAME_WORLD, posesen0, EGM_FRAME_WORLD
           \x:=egm_minmax_lin1 \y:=egm_minmax_lin1 \z:=egm_minmax_lin1
           \rx:=egm_minmax_rot1 \ry:=egm_minmax_rot1 \rz:=egm_minmax_rot1
           \LpFilter:=20 \SampleRate:=16 \MaxPosDeviation:=1000;
! Run: keep the end position without returning to the start position
EGMRunPose egmID1,
           EGM_STOP_HOLD\x\y\z\RampInTime:=0.05\PosCorrGain:=1;
! Move to the starting point - fine point is needed.
MoveJ p20, v1000, fine, tFroniusCMT;
! Set the signals
SetAO ao_MoveX, 150;
SetAO ao_MoveY, 1320;
SetAO ao_MoveZ, 1100;
! Run with the same frame definitions: ramp down to the start position after having reached
! the EGM end position
EGMRunPose egmID1,
     EGM_STOP_RAMP_DOWN\x\y\z\RampInTime:=0.05\PosCorrGain:=1;
! Move to the starting point - fine point is needed.
MoveJ p30, v1000, fine, tool0;
! Set the signals
SetAO ao_MoveX, 50;
SetAO ao_MoveY, -20;
SetAO ao_MoveZ, -20;
! Correction frame is the Work object wobj_EGM1 and the sensor measurements are also
! relative to the same work object. No offset is defined (posecor1 and posesen1)
EGMActPose egmID1 \Tool:=tFroniusCMT \WObj:=wobj_EGM1 \TLoad:=load1,
     posecor1, EGM_FRAME_WOBJ, posesen1, EGM_FRAME_WOBJ
     \x:=egm_minmax_lin1 \y:=egm_minmax_lin1 \z:=egm_minmax_lin1
     \rx:=egm_minmax_rot1 \ry:=egm_minmax_rot1 \rz:=egm_minmax_rot1
     \LpFilter:=20;
! Run: keep the end position without returning to the start position
EGMRunPose egmID1,
     EGM_STOP_HOLD\x\y\z\RampInTime:=0.05\PosCorrGain:=1;
! Move to the starting point - fine point is needed.
MoveJ p20, v1000, fine, tFroniusCMT;
! Set the signals
SetAO ao_MoveX, 0;
SetAO ao_MoveY, 0;
SetAO ao_MoveZ, 0;
! Correction frame is the Work object wobj_EGM2 and the sensor measurements are also
! relative to the same work object. This time an offset is defined for the correction frame
! (posecor2), and for the sensor frame (posesen2)
EGMActPose egmID1 \Tool:=tFroniusCMT \WObj:=wobj_EGM2 \TLoad:=load1,
     posecor2, EGM_FRAME_WOBJ, posesen2, EGM_FRAME_WOBJ
     \x:=egm_minmax_lin1 \y:=egm_minmax_lin1 \z:=egm_minmax_lin1
     \rx:=egm_minmax_rot1 \ry:=egm_minmax_rot1 \rz:=egm_minmax_rot1
     \LpFilter:=20;
! Run: keep the end position without returning to the start position
EGMRunPose egmID1,
     EGM_STOP_HOLD\x\y\z\RampInTime:=0.05\PosCorrGain:=1;
! Move to the starting point - fine point is needed.
MoveJ p20, v1000, fine, tFroniusCMT;
! Set the signals
SetAO ao_MoveX, 0;
SetAO ao_MoveY, 0;
SetAO ao_MoveZ, 0;
! Correction frame is of tool type and the sensor measurements are relative to the work
! object wobj_EGM2. This time an offset is defined for the correction frame (posecor2), and
! for the sensor frame (posesen2)
EGMActPose egmID1 \Tool:=tFroniusCMT \WObj:=wobj_EGM2, posecor2,
     EGM_FRAME_TOOL, posesen2, EGM_FRAME_WOBJ \x:=egm_minmax_lin1
     \y:=egm_minmax_lin1 \z:=egm_minmax_lin1 \rx:=egm_minmax_rot1
     \ry:=egm_minmax_rot1 \rz:=egm_minmax_rot1 \LpFilter:=20;
EGMRunPose egmID1,
     EGM_STOP_HOLD\x\y\z\RampInTime:=0.05\PosCorrGain:=1;
! Move to the starting point - fine point is needed.
MoveJ p20, v1000, fine, tFroniusCMT\TLoad:=load1;
! Set the signals
SetAO ao_MoveX, 150;
SetAO ao_MoveY, 1320;
SetAO ao_MoveZ, 1100;
! Same as last, but with tool0 and wobj0
EGMActPose egmID1, posecor2, EGM_FRAME_TOOL, posesen2,
     EGM_FRAME_WOBJ \x:=egm_minmax_lin1 \y:=egm_minmax_lin1
     \z:=egm_minmax_lin1 \rx:=egm_minmax_rot1 \ry:=egm_minmax_rot1
     \rz:=egm_minmax_rot1 \LpFilter:=20;
! Run: keep the end position without returning to the start position
EGMRunPose egmID1,
     EGM_STOP_HOLD\x\y\z\RampInTime:=0.05\PosCorrGain:=1;
! Move to the starting point - fine point is needed.
MoveJ p20, v1000, fine, tFroniusCMT\TLoad:=load1;
! Set the signals
SetAO ao_MoveX, 70;
SetAO ao_MoveY, -5;
SetAO ao_MoveZ, 0;
SetAO ao_RotX, 0;
SetAO ao_RotY, 0;
SetAO ao_RotZ, 0;
! Joint guidance for joints 2-6
EGMActJoint egmID2 \J2:=egm_minmax_joint1 \J3:=egm_minmax_joint1
     \J4:=egm_minmax_joint1 \J5:=egm_minmax_joint1
     \J6:=egm_minmax_joint1 \LpFilter:=20;
! Run: keep the end position without returning to the start position
EGMRunJoint egmID2, EGM_STOP_HOLD \J2 \J3 \J4 \J5 \J6 \CondTime:=0.1
     \RampInTime:=0.05 \PosCorrGain:=1;
EGMReset egmID1;
EGMReset egmID2;
ENDPROC
ENDMODULE
