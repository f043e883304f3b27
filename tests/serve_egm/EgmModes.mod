! rapidvc test program for `rapidvc serve` (tests/rws_clients.rs): each start runs one EGM
! session against the sensor on device "sensor", of the kind the analog output egm_mode
! selects, as the RWS client set it before starting: 1 joint (target [10,-5,20,0,40,30]),
! 2 pose (the flange to [1068.61,-30,1457.5], orientation [0.5,0,0.866025,0] in world),
! 3 path correction (a straight EGMMoveL of 400 mm along +X corrected by the sensor),
! 4 a slow joint run (MaxSpeedDeviation 10 deg/s, timed in egm_time) for stopping and
! starting it and for the speed ratio (tests/rws_egm_stop.rs).
! The PERS data tell the client what ran and how it ended.
MODULE EgmModes
    PERS num last_mode := 0;
    PERS num last_state := 0;
    PERS num egm_time := 0;
    VAR clock clk;
    VAR egmident egm1;
    CONST jointtarget home := [[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
    CONST pose world := [[0,0,0],[1,0,0,0]];
    CONST egm_minmax win := [-0.2,0.2];
    CONST egm_minmax lin := [-0.5,0.5];
    CONST egm_minmax rot := [-0.2,0.2];
    PERS tooldata tTorch := [TRUE,[[0,0,200],[1,0,0,0]],[1,[0,0,100],[1,0,0,0],0,0,0]];
    CONST robtarget pAbove := [[1000,20,600],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
    CONST robtarget pStart := [[1000,20,500],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
    CONST robtarget pEnd := [[1400,20,500],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];

    PROC main()
        VAR num mode;
        mode := AOutput(egm_mode);
        last_mode := mode;
        last_state := 0;
        EGMReset egm1;
        EGMGetId egm1;
        TEST mode
        CASE 1:
            MoveAbsJ home, v1000, fine, tool0;
            EGMSetupUC ROB_1, egm1, "default", "sensor" \Joint \CommTimeout:=5;
            EGMActJoint egm1 \J1:=win \J2:=win \J3:=win \J4:=win \J5:=win \J6:=win
                \MaxSpeedDeviation:=40;
            EGMRunJoint egm1, EGM_STOP_HOLD \J1 \J2 \J3 \J4 \J5 \J6 \CondTime:=0.5
                \RampInTime:=0.1;
        CASE 2:
            MoveAbsJ home, v1000, fine, tool0;
            EGMSetupUC ROB_1, egm1, "default", "sensor" \Pose \CommTimeout:=5;
            EGMActPose egm1 \Tool:=tool0 \WObj:=wobj0, world, EGM_FRAME_WORLD, world,
                EGM_FRAME_WORLD \x:=lin \y:=lin \z:=lin \rx:=rot \ry:=rot \rz:=rot
                \MaxSpeedDeviation:=40;
            EGMRunPose egm1, EGM_STOP_HOLD \x \y \z \rx \ry \rz \CondTime:=0.5
                \RampInTime:=0.1;
        CASE 3:
            EGMSetupUC ROB_1, egm1, "pathCorr", "sensor" \PathCorr \APTR;
            EGMActMove egm1, tTorch.tframe;
            MoveJ pAbove, v1000, z10, tTorch;
            MoveL pStart, v200, fine, tTorch;
            EGMMoveL egm1, pEnd, v100, fine, tTorch;
        CASE 4:
            MoveAbsJ home, v1000, fine, tool0;
            EGMSetupUC ROB_1, egm1, "default", "sensor" \Joint \CommTimeout:=5;
            EGMActJoint egm1 \J1:=win \J2:=win \J3:=win \J4:=win \J5:=win \J6:=win
                \MaxSpeedDeviation:=10;
            ClkReset clk;
            ClkStart clk;
            EGMRunJoint egm1, EGM_STOP_HOLD \J1 \J2 \J3 \J4 \J5 \J6 \CondTime:=0.5
                \RampInTime:=0.1;
            ClkStop clk;
            egm_time := ClkRead(clk);
        DEFAULT:
            TPWrite "egm_mode selects no session: " \Num:=mode;
        ENDTEST
        last_state := EGMGetState(egm1);
        EGMReset egm1;
    ENDPROC
ENDMODULE
