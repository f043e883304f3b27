! rapidvc: the example of section 9.3.6.3 of the EGM manual ("Using EGM Path Correction with
! different protocol types"), transcribed as printed. Repaired (OCR and layout
! damage): the "]" missing at the end of tEGM and tLaser, the OCR'd name "eqmId1"
! (egmId1), "\SampleRate:=50" in EGMActMove (48: the rate is a multiple of 24 ms, as in the
! RobotWare 7 edition of this example), "\Wobj" written "\WObj" like everywhere else, and
! the device names "Optsim"/"wglsim" in two comments ("OptSim"/"wg1sim", as in the code).
! The manual uses p100 ... p180 without declaring them and has no main routine; both are
! added below, marked "not in the manual".
MODULE EGM_PATHCORR
! Used tool
PERS tooldata tEGM:=[TRUE,[[148.62,0.25,326.31],
     [0.833900724,0,0.551914471,0]], [1,[0,0,100],
     [1,0,0,0],0,0,0]];
! Sensor tool, has to be calibrated
PERS tooldata
     tLaser:=[TRUE,[[148.619609537,50.250017146,326.310337954],
     [0.390261856,-0.58965743,-0.58965629,0.390263064]],
     [1, [-0.920483747, -0.000000536, -0.390780849],
     [1,0,0,0],0,0,0]];
! Displacement used
VAR pose PP := [[0,-3,2],[1,0,0,0]];
VAR egmident egmId1;
! Not in the manual (rapidvc): the targets of the path, which the manual leaves undeclared.
! A seam along +y in front of the default robot (IRB 2600-12/1.85), 1000 mm out at
! z = 500 mm, with tool tEGM pointing straight down ([0,0,1,0]): approach p100 -> p110 ->
! p120, seam start p130 (fine), p140, p150, a half circle through p160 to p165, seam end p170
! (fine), retract p180. Configuration [0,0,-1,1] for all. Running along +y puts the
! look-ahead sensor tLaser (50 mm beside tEGM's TCP, along the flange's y axis) 50 mm ahead of
! the TCP on the straight parts, as a laser seam tracker is mounted.
CONST robtarget p100:=[[1000,50,700],[0,0,1,0],[0,0,-1,1],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
CONST robtarget p110:=[[1000,50,600],[0,0,1,0],[0,0,-1,1],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
CONST robtarget p120:=[[1000,50,520],[0,0,1,0],[0,0,-1,1],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
CONST robtarget p130:=[[1000,50,500],[0,0,1,0],[0,0,-1,1],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
CONST robtarget p140:=[[1000,150,500],[0,0,1,0],[0,0,-1,1],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
CONST robtarget p150:=[[1000,250,500],[0,0,1,0],[0,0,-1,1],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
CONST robtarget p160:=[[950,300,500],[0,0,1,0],[0,0,-1,1],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
CONST robtarget p165:=[[1000,350,500],[0,0,1,0],[0,0,-1,1],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
CONST robtarget p170:=[[1000,450,500],[0,0,1,0],[0,0,-1,1],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
CONST robtarget p180:=[[1000,450,650],[0,0,1,0],[0,0,-1,1],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
! Protocol: LTAPP
! Example for a look ahead sensor, e.g. Laser Tracker
PROC Part_2_EGM_OT_Pth_1()
  EGMGetId egmId1;
  ! Set up the EGM data source: LTAPP server using device "OptSim",
  ! configuration "pathCorr", joint type 1 and look ahead sensor.
  EGMSetupLTAPP ROB_1, egmId1, "pathCorr", "OptSim", 1\LATR;
  ! Activate EGM and define the sensor frame.
  ! Correction frame is always the path frame.
  EGMActMove egmId1, tLaser.tframe\SampleRate:=48;
  ! Move to a suitable approach position.
  MoveJ p100,v1000,z10,tEGM\WObj:=wobj0;
  MoveL p110, v1000, z100, tEGM\WObj:=wobj0;
  MoveL p120, v1000, z100, tEGM\WObj:=wobj0;
  ! Activate displacement (not necessary but possible)
  PDispSet PP;
  ! Move to the start point. Fine point is demanded.
  MoveL p130, v10, fine, tEGM\WObj:=wobj0;
  ! movements with path corrections.
  EGMMoveL egmId1, p140, v10, z5, tEGM\WObj:=wobj0;
  EGMMoveL egmId1, p150, v10, z5, tEGM\WObj:=wobj0;
  EGMMoveC egmId1, p160, p165, v10, z5, tEGM\WObj:=wobj0;
  ! Last path correction movement has to end with a fine point.
  EGMMoveL egmId1, p170, v10, fine, tEGM\WObj:=wobj0;
  ! Move to a safe position after path correction.
  MoveL p180, v1000, z10, tEGM\WObj:=wobj0;
  ! Release the EGM identity for reuse.
EGMReset egmId1;
ENDPROC
! Protocol: LTAPP
! Example for an at point sensor, e.g. Weldguide
PROC Part_2_EGM_WG_Pth_1()
 EGMGetId egmId1;
 ! Set up the EGM data source: LTAPP server using device "wg1sim",
  ! configuration "pathCorr", joint type 1 and at point sensor.
 EGMSetupLTAPP ROB_1, egmId1, "pathCorr", "wg1sim", 1\APTR;
  ! Activate EGM and define the sensor frame,
  ! which is the tool frame for at point trackers.
  ! Correction frame is always the path frame.
 EGMActMove egmId1, tEGM.tframe\SampleRate:=48;
  ! Move to a suitable approach position.
 MoveJ p100,v1000,z10,tEGM\WObj:=wobj0;
 MoveL p110,v1000,z100,tEGM\WObj:=wobj0;
 MoveL p120, v1000, fine, tEGM\WObj:=wobj0;
  ! Activate displacement (not necessary but possible)
 PDispSet PP;
  ! Move to the start point. Fine point is demanded.
 MoveL p130, v10, fine, tEGM\WObj:=wobj0;
  ! movements with path corrections.
 EGMMoveL egmId1, p140, v10, z5, tEGM\WObj:=wobj0;
 EGMMoveL egmId1, p150, v10, z5, tEGM\WObj:=wobj0;
 EGMMoveC egmId1, p160, p165, v10, z5, tEGM\WObj:=wobj0;
  ! Last path correction movement has to end with a fine point.
 EGMMoveL egmId1, p170, v10, fine, tEGM\WObj:=wobj0;
 ! Move to a safe position after path correction.
 MoveL p180, v1000, z10, tEGM\WObj:=wobj0;
  ! Release the EGM identity for reuse.
 EGMReset egmId1;
ENDPROC
! Protocol: UdpUc
! Example for an at point sensor, e.g. Weldguide
PROC Part_2_EGM_UDPUC_Pth_1()
 EGMGetId egmId1;
 EGMSetupUC ROB_1, egmId1, "pathCorr", "UCdevice"\PathCorr\APTR;
 EGMActMove egmId1, tEGM.tframe\SampleRate:=48;
 ! Move to a suitable approach position.
 MoveJ p100,v1000,z10,tEGM\WObj:=wobj0;
 MoveL p110,v1000,z100,tEGM\WObj:=wobj0;
 MoveL p120, v1000, fine, tEGM\WObj:=wobj0;
  ! Activate displacement (not necessary but possible)
 PDispSet PP;
  ! Move to the start point. Fine point is demanded.
 MoveL p130, v10, fine, tEGM\WObj:=wobj0;
  ! movements with path corrections.
 EGMMoveL egmId1, p140, v10, z5, tEGM\WObj:=wobj0;
 EGMMoveL egmId1, p150, v10, z5, tEGM\WObj:=wobj0;
EGMMoveC egmId1, p160, p165, v10, z5, tEGM\WObj:=wobj0;
! Last path correction movement has to end with a fine point.
EGMMoveL egmId1, p170, v10, fine, tEGM\WObj:=wobj0;
! Move to a safe position after path correction.
MoveL p180,v1000,z10,tEGM\WObj:=wobj0;
! Release the EGM identity for reuse.
EGMReset egmId1;
ENDPROC
! Not in the manual (rapidvc): the manual has no main routine; run the three examples in
! turn (the two LTAPP ones need LTAPP sensor devices "OptSim" and "wg1sim").
PROC main()
  Part_2_EGM_OT_Pth_1;
  Part_2_EGM_WG_Pth_1;
  Part_2_EGM_UDPUC_Pth_1;
ENDPROC
ENDMODULE
