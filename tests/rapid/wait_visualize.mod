MODULE wait_visualize
  ! The FlexPendant message of WaitUntil, WaitDI and WaitDO (\Visualize, \Header,
  ! \Message | \MsgArray, \Wrap, \Icon, \Image, \VisualizeTime, \UIActiveSignal): the wait
  ! itself is unchanged, the box is shown once the wait has lasted \VisualizeTime, and
  ! \UIActiveSignal is 1 while it is shown (a timer TRAP looks at it during the wait).
  VAR num n := 0;
  VAR bool late;
  VAR num active_seen := -1;
  VAR intnum tick;
  VAR string lines{2} := ["Put a part", "in the feeder"];

  TRAP look
    active_seen := DOutput(do2);
  ENDTRAP

  PROC test_waituntil_visualized()
    CONNECT tick WITH look;
    ITimer \Single, 0.6, tick;
    WaitUntil n > 2 \MaxTime:=1 \TimeFlag:=late \Visualize \Header:="Feeder" \MsgArray:=lines \Wrap \Icon:=iconInfo \Image:="part.png" \VisualizeTime:=0.5 \UIActiveSignal:=do2;
    IDelete tick;
    Assert late;
    Assert active_seen = 1 \Msg:="the active signal is 1 while the message is shown";
    Assert DOutput(do2) = 0 \Msg:="and 0 once the wait has ended";
  ENDPROC

  PROC test_not_shown_before_visualize_time()
    CONNECT tick WITH look;
    ITimer \Single, 0.2, tick;
    active_seen := -1;
    WaitUntil n > 2 \MaxTime:=0.4 \TimeFlag:=late \Visualize \Message:="later" \VisualizeTime:=10 \UIActiveSignal:=do2;
    IDelete tick;
    Assert late;
    Assert active_seen = 0;
  ENDPROC

  PROC test_waitdi_waitdo_visualized()
    SetDO do1, 1;
    WaitDO do1, 1 \MaxTime:=0.2 \TimeFlag:=late \Visualize \Header:="Clamp" \Message:="closing";
    Assert NOT late;
    WaitDI di1, 1 \MaxTime:=0.2 \TimeFlag:=late \Visualize \Message:="Waiting for di1";
    Assert late;
    SetDO do1, 0;
  ENDPROC

  PROC test_bad_visualize_time()
    VAR num caught := 0;
    WaitUntil n > 2 \MaxTime:=0.2 \TimeFlag:=late \Visualize \VisualizeTime:=-1;
    Assert caught = ERR_ARGVALERR;
  ERROR
    caught := ERRNO;
    TRYNEXT;
  ENDPROC
ENDMODULE
