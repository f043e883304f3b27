! A corrected EGMMoveL (the straight seam of straight.mod at v100) that a TRAP holds on its
! path with StopMove and releases with StartMove, and then slows to half speed with
! SpeedRefresh: the corrected path must not leave the seam while the path rate changes
! (run it with --device UCdevice=builtin:pathcorr:y=3,z=-2).
MODULE PathCorrHeld
  PERS tooldata tTorch := [TRUE,[[0,0,200],[1,0,0,0]],[1,[0,0,100],[1,0,0,0],0,0,0]];
  VAR egmident egmId1;
  VAR intnum tick;
  VAR num ticks := 0;
  CONST robtarget pAbove := [[1000,20,600],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  CONST robtarget pStart := [[1000,20,500],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  CONST robtarget pEnd := [[1400,20,500],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];

  PROC main()
    EGMReset egmId1;
    EGMGetId egmId1;
    EGMSetupUC ROB_1, egmId1, "pathCorr", "UCdevice" \PathCorr \APTR;
    EGMActMove egmId1, tTorch.tframe;
    MoveJ pAbove, v1000, z10, tTorch;
    MoveL pStart, v200, fine, tTorch;
    CONNECT tick WITH on_tick;
    ITimer 1, tick;
    EGMMoveL egmId1, pEnd, v100, fine, tTorch;
    IDelete tick;
    TPWrite "ticks: " \Num:=ticks;
    EGMReset egmId1;
  ENDPROC

  TRAP on_tick
    Incr ticks;
    IF ticks = 1 THEN
      StopMove;
      WaitTime 0.5;
      StartMove;
    ELSEIF ticks = 2 THEN
      SpeedRefresh 50;
    ENDIF
  ENDTRAP
ENDMODULE
