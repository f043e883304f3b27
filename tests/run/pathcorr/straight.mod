! The acceptance case of path correction: a straight EGMMoveL of 400 mm at v10 along +X with
! the torch pointing down, corrected by a sensor that reports a constant seam offset (run it
! with --device UCdevice=builtin:pathcorr:y=3,z=-2, or a real sensor on UCdevice).
MODULE PathCorrStraight
  PERS tooldata tTorch := [TRUE,[[0,0,200],[1,0,0,0]],[1,[0,0,100],[1,0,0,0],0,0,0]];
  VAR egmident egmId1;
  CONST robtarget pAbove := [[1000,20,600],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  CONST robtarget pStart := [[1000,20,500],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  CONST robtarget pEnd := [[1400,20,500],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];

  PROC main()
    VAR egmstate st;
    EGMReset egmId1;
    EGMGetId egmId1;
    EGMSetupUC ROB_1, egmId1, "pathCorr", "UCdevice" \PathCorr \APTR;
    EGMActMove egmId1, tTorch.tframe;
    MoveJ pAbove, v1000, z10, tTorch;
    MoveL pStart, v200, fine, tTorch;
    EGMMoveL egmId1, pEnd, v10, fine, tTorch;
    st := EGMGetState(egmId1);
    TPWrite "state after the fine point: " \Num:=st;
    EGMReset egmId1;
  ENDPROC
ENDMODULE
