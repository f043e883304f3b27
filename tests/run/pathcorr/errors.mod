! Path-correction errors a program can meet, one procedure each (run with --entry).
MODULE PathCorrErrors
  PERS tooldata tTorch := [TRUE,[[0,0,200],[1,0,0,0]],[1,[0,0,100],[1,0,0,0],0,0,0]];
  VAR egmident egmId1;
  CONST robtarget pStart := [[1000,20,500],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  CONST robtarget pMid := [[1100,20,500],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  CONST robtarget pEnd := [[1200,20,500],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];

  PROC setup()
    EGMGetId egmId1;
    EGMSetupUC ROB_1, egmId1, "pathCorr", "UCdevice" \PathCorr \APTR \CommTimeout:=0.5;
  ENDPROC

  ! EGMMoveL without EGMActMove.
  PROC no_act_move()
    setup;
    MoveJ pStart, v1000, fine, tTorch;
    EGMMoveL egmId1, pEnd, v10, fine, tTorch;
  ENDPROC

  ! The corrected sequence starts from a fly-by point.
  PROC start_not_fine()
    setup;
    EGMActMove egmId1, tTorch.tframe;
    MoveJ pStart, v1000, z10, tTorch;
    EGMMoveL egmId1, pEnd, v10, fine, tTorch;
  ENDPROC

  ! The corrected sequence does not end in a fine point.
  PROC end_not_fine()
    setup;
    EGMActMove egmId1, tTorch.tframe;
    MoveJ pStart, v1000, fine, tTorch;
    EGMMoveL egmId1, pMid, v100, z5, tTorch;
    MoveL pEnd, v100, fine, tTorch;
  ENDPROC

  ! The sensor stops answering: ERR_UDPUC_COMM, handled.
  PROC silent_sensor()
    setup;
    EGMActMove egmId1, tTorch.tframe;
    MoveJ pStart, v1000, fine, tTorch;
    EGMMoveL egmId1, pEnd, v10, fine, tTorch;
    TPWrite "not reached";
  ERROR
    IF ERRNO = ERR_UDPUC_COMM THEN
      TPWrite "ERR_UDPUC_COMM handled";
      MoveL pStart, v100, fine, tTorch;
      TPWrite "moved on";
      RETURN;
    ENDIF
  ENDPROC

  ! \NoCorr on the last move: the correction ramps out.
  PROC no_corr()
    setup;
    EGMActMove egmId1, tTorch.tframe \SampleRate:=24;
    MoveJ pStart, v1000, fine, tTorch;
    EGMMoveL egmId1, pMid, v20, z5, tTorch;
    EGMMoveL egmId1, pEnd, v20, fine, tTorch \NoCorr;
  ENDPROC

  ! A sample rate that is not a multiple of 24 ms (the manual's printed 50).
  PROC bad_rate()
    setup;
    EGMActMove egmId1, tTorch.tframe \SampleRate:=50;
  ENDPROC
ENDMODULE
