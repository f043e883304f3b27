MODULE interrupts
  VAR intnum tick;
  VAR intnum sig;
  VAR num ticks := 0;
  VAR num edges := 0;
  VAR clock c;

  TRAP on_tick
    ticks := ticks + 1;
  ENDTRAP

  TRAP on_edge
    edges := edges + 1;
  ENDTRAP

  TRAP on_fail
    VAR num z := 0;
    edges := 1 / z;
    edges := 99;
  ERROR
    edges := 7;
    TRYNEXT;
  ENDTRAP

  TRAP on_level
    edges := edges + 1;
    TPWrite "analog crossed: " \Num:=AOutput(ao1);
  ENDTRAP

  PROC test_timer_during_wait()
    ticks := 0;
    CONNECT tick WITH on_tick;
    ITimer 0.5, tick;
    WaitTime 2.2;
    IDelete tick;
    Assert ticks = 4 \Msg:="a 0.5 s timer fires 4 times in 2.2 s";
    WaitTime 1;
    Assert ticks = 4 \Msg:="IDelete stops it";
  ENDPROC

  PROC test_single_timer()
    ticks := 0;
    CONNECT tick WITH on_tick;
    ITimer \Single, 0.1, tick;
    WaitTime 1;
    Assert ticks = 1;
    IDelete tick;
  ENDPROC

  PROC test_signal_edge()
    edges := 0;
    Reset do1;
    CONNECT sig WITH on_edge;
    ISignalDO do1, 1, sig;
    SetDO do1, 1;
    Reset do1;
    SetDO do1, 1;
    Assert edges = 2 \Msg:="two rising edges";
    IDelete sig;
  ENDPROC

  PROC test_disable_enable()
    edges := 0;
    Reset do1;
    CONNECT sig WITH on_edge;
    ISignalDO do1, 1, sig;
    IDisable;
    SetDO do1, 1;
    Assert edges = 0 \Msg:="queued while disabled";
    IEnable;
    WaitTime 0;
    Assert edges = 1;
    IDelete sig;
  ENDPROC

  PROC test_already_connected()
    CONNECT tick WITH on_tick;
    CONNECT tick WITH on_tick;
  ERROR
    Assert ERRNO = ERR_ALRDYCNT;
    IDelete tick;
  ENDPROC

  PROC test_virtual_clock()
    ClkReset c;
    ClkStart c;
    WaitTime 10;
    ClkStop c;
    Assert ClkRead(c) = 10 \Msg:="WaitTime 10 takes 10 virtual seconds";
    WaitTime 5;
    Assert ClkRead(c) = 10;
  ENDPROC

  PROC test_wait_until_max_time()
    VAR bool late;
    WaitUntil di1 = 1 \MaxTime:=0.5 \TimeFlag:=late;
    Assert late;
    WaitUntil DInput(di1) = 1 \MaxTime:=0.5;
    Assert FALSE;
  ERROR
    Assert ERRNO = ERR_WAIT_MAXTIME;
  ENDPROC

  PROC test_wait_until_condition_from_trap()
    ticks := 0;
    CONNECT tick WITH on_tick;
    ITimer 0.3, tick;
    WaitUntil ticks >= 3;
    IDelete tick;
    Assert ticks = 3;
  ENDPROC

  PROC test_io_functions()
    SetDO do2, 1;
    Assert DOutput(do2) = 1;
    SetAO ao1, 12.5;
    Assert AOutput(ao1) = 12.5;
    SetGO go1, 200;
    Assert GOutput(go1) = 200;
    Set do1;
    Assert DOutput(do1) = 1;
    Reset do1;
    Assert DOutput(do1) = 0;
    Assert NOT TestDI(di1);
    Assert DInput(di1) = 0;
    Assert AInput(ai1) = 0;
    Assert GInput(gi1) = 0;
  ENDPROC

  PROC test_analog_limit()
    SetAO ao1, 1000;
  ERROR
    Assert ERRNO = ERR_AO_LIM;
  ENDPROC

  PROC test_pulse()
    Reset do1;
    PulseDO \PLength:=0.5, do1;
    Assert DOutput(do1) = 1;
    WaitTime 0.6;
    Assert DOutput(do1) = 0;
    SetDO \SDelay:=0.2, do2, 0;
    Assert DOutput(do2) = 1 OR DOutput(do2) = 0;
    WaitTime 0.3;
    Assert DOutput(do2) = 0;
  ENDPROC

  PROC test_wait_di_times_out()
    WaitDI di1, 1 \MaxTime:=1;
  ERROR
    Assert ERRNO = ERR_WAIT_MAXTIME;
  ENDPROC
  PROC test_trap_error_handler()
    VAR intnum t;
    edges := 0;
    CONNECT t WITH on_fail;
    ITimer \Single, 0.1, t;
    WaitTime 0.2;
    Assert edges = 99 \Msg:="the trap's handler took the error and went on";
    IDelete t;
  ENDPROC

  PROC test_analog_interrupt()
    VAR intnum a;
    edges := 0;
    SetAO ao1, 0;
    CONNECT a WITH on_level;
    ! DeltaValue 15: a new interrupt needs a change of more than 15 from the value at the
    ! last one (ABB's stored reference value), within the condition.
    ISignalAO ao1, AIO_ABOVE_HIGH, 50, 0, 15, a;
    SetAO ao1, 10;
    Assert edges = 0;
    SetAO ao1, 60;
    Assert edges = 1;
    SetAO ao1, 70;
    Assert edges = 1 \Msg:="a change of 10 is within the delta";
    SetAO ao1, 0;
    SetAO ao1, 80;
    Assert edges = 2;
    IDelete a;
  ENDPROC

  PROC test_intno_in_trap()
    VAR intnum t;
    CONNECT t WITH on_tick;
    Assert t > 0;
    IDelete t;
  ENDPROC
ENDMODULE
