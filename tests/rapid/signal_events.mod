MODULE signal_events
  ! Signal waits, aliases, analog/group/persistent/error interrupts. Values from the
  ! examples of the RAPID reference (named at each test).
  VAR num hits := 0;
  VAR num seen := 0;
  VAR intnum sig1int;
  VAR intnum err_interrupt;
  VAR intnum perslint;
  VAR trapdata err_data;
  VAR errdomain err_domain;
  VAR num err_number;
  VAR errtype err_type;
  VAR string err_title;
  VAR string err_str1;
  VAR signaldo alias_do;
  VAR signaldi alias_di;
  PERS num counter := 0;
  CONST string config_string := "do2";

  TRAP count_hit
    hits := hits + 1;
    seen := AOutput(ao1);
  ENDTRAP

  TRAP group_hit
    hits := hits + 1;
    seen := GOutput(go1);
  ENDTRAP

  TRAP iroutine
    hits := hits + 1;
    seen := counter;
  ENDTRAP

  TRAP trap_err
    GetTrapData err_data;
    ReadErrData err_data, err_domain, err_number, err_type \Title:=err_title \Str1:=err_str1;
    hits := hits + 1;
  ENDTRAP

  TRAP raise_ao
    SetAO ao1, 7;
  ENDTRAP

  TRAP raise_go
    SetGO go1, 5;
  ENDTRAP

  PROC test_isignalai_between_with_delta()
    ! ISignalAI example 2 (on the analog output ao1: ISignalAO takes the same arguments):
    ! each time between 0.5 and 1.5 and more than 0.1 away from the stored reference.
    hits := 0;
    SetAO ao1, 0;
    CONNECT sig1int WITH count_hit;
    ISignalAO ao1, AIO_BETWEEN, 1.5, 0.5, 0.1, sig1int;
    SetAO ao1, 1;
    Assert hits = 1;
    SetAO ao1, 1.05;
    Assert hits = 1 \Msg:="0.05 from the reference is within the delta";
    SetAO ao1, 1.2;
    Assert hits = 2;
    SetAO ao1, 2;
    Assert hits = 2 \Msg:="outside the limits";
    SetAO ao1, 1.25;
    Assert hits = 2 \Msg:="0.05 from the reference 1.2";
    IDelete sig1int;
  ENDPROC

  PROC test_isignalai_outside_dpos()
    ! ISignalAI example 3: below 0.5 or above 1.5, with a change of more than 0.1 in the
    ! positive direction.
    hits := 0;
    SetAO ao1, 0;
    CONNECT sig1int WITH count_hit;
    ISignalAO ao1, AIO_OUTSIDE, 1.5, 0.5, 0.1 \DPos, sig1int;
    SetAO ao1, 2;
    Assert hits = 1;
    SetAO ao1, 1.8;
    Assert hits = 1 \Msg:="a negative change stores a new reference, no interrupt";
    SetAO ao1, 1.85;
    Assert hits = 1;
    SetAO ao1, 2;
    Assert hits = 2 \Msg:="0.2 above the reference 1.8";
    IDelete sig1int;
  ENDPROC

  PROC test_isignalai_single_and_dneg()
    ! ISignalAI example 1: \Single, the first time between 0.5 and 1.5.
    hits := 0;
    SetAO ao1, 0;
    CONNECT sig1int WITH count_hit;
    ISignalAO \Single, ao1, AIO_BETWEEN, 1.5, 0.5, 0, sig1int;
    SetAO ao1, 1;
    SetAO ao1, 1.4;
    Assert hits = 1 \Msg:="\\Single interrupts once";
    IDelete sig1int;
    ! \DNeg with AIO_ALWAYS: only decreases of more than 1.
    hits := 0;
    CONNECT sig1int WITH count_hit;
    ISignalAO ao1, AIO_ALWAYS, 0, 0, 1 \DNeg, sig1int;
    SetAO ao1, 10;
    SetAO ao1, 5;
    Assert hits = 1 AND seen = 5;
    SetAO ao1, 4.5;
    Assert hits = 1;
    IDelete sig1int;
  ENDPROC

  PROC test_isignalai_ordered_on_an_input()
    ! Nothing in a program changes an input: the order is taken and no interrupt comes.
    hits := 0;
    CONNECT sig1int WITH count_hit;
    ISignalAI ai1, AIO_ABOVE_HIGH, 5, 0, 0, sig1int;
    WaitTime 1;
    Assert hits = 0;
    ISignalGI gi1, sig1int;
    WaitTime 1;
    Assert hits = 0;
    IDelete sig1int;
  ENDPROC

  PROC test_isignalgo_every_change()
    ! ISignalGI/GO: an interrupt on every change of the group's value.
    hits := 0;
    SetGO go1, 0;
    CONNECT sig1int WITH group_hit;
    ISignalGO go1, sig1int;
    SetGO go1, 3;
    SetGO go1, 3;
    SetGO go1, 12;
    Assert hits = 2 AND seen = 12;
    IDelete sig1int;
    hits := 0;
    CONNECT sig1int WITH group_hit;
    ISignalGO \Single, go1, sig1int;
    SetGO go1, 1;
    SetGO go1, 2;
    Assert hits = 1;
    IDelete sig1int;
  ENDPROC

  PROC test_ipers()
    ! IPers example: an interrupt each time the persistent counter changes.
    hits := 0;
    counter := 0;
    CONNECT perslint WITH iroutine;
    IPers counter, perslint;
    counter := 5;
    counter := 5;
    counter := 6;
    Assert hits = 2 AND seen = 6;
    IDelete perslint;
    counter := 7;
    Assert hits = 2;
  ENDPROC

  PROC test_ierror_readerrdata()
    ! IError example: COMMON_ERR, TYPE_ERR; ErrWrite logs in the user domain (80001).
    hits := 0;
    CONNECT err_interrupt WITH trap_err;
    IError COMMON_ERR, TYPE_ERR, err_interrupt;
    ErrWrite "Gripper", "no part";
    Assert hits = 1;
    Assert err_domain = USER_DEF_ERR AND err_number = 1 AND err_type = TYPE_ERR;
    Assert err_title = "Gripper" AND err_str1 = "no part";
    ErrWrite \W, "Gripper", "slow";
    Assert hits = 1 \Msg:="a warning is not TYPE_ERR";
    IDelete err_interrupt;
    CONNECT err_interrupt WITH trap_err;
    IError USER_DEF_ERR \ErrorId:=2, TYPE_ALL, err_interrupt;
    ErrWrite "Gripper", "no part";
    ErrWrite \W, "Gripper", "slow";
    Assert hits = 2 AND err_number = 2 AND err_type = TYPE_WARN;
    IDelete err_interrupt;
  ENDPROC

  PROC test_invertdo()
    ! InvertDO example: the value of the signal is inverted.
    SetDO do1, 0;
    InvertDO do1;
    Assert DOutput(do1) = 1;
    InvertDO do1;
    Assert DOutput(do1) = 0;
  ENDPROC

  PROC test_waitao_gt_and_waitgo()
    ! WaitAI example (on ao1): continue once the value is greater than 5; a trap sets it.
    VAR intnum t;
    VAR clock c;
    SetAO ao1, 0;
    ClkReset c;
    ClkStart c;
    CONNECT t WITH raise_ao;
    ITimer \Single, 0.5, t;
    WaitAO ao1, \GT, 5;
    Assert AOutput(ao1) = 7 AND ClkRead(c) = 0.5;
    IDelete t;
    ! WaitGI example (on go1): continue once the group has the value 5.
    SetGO go1, 0;
    CONNECT t WITH raise_go;
    ITimer \Single, 0.25, t;
    WaitGO go1, 5;
    Assert GOutput(go1) = 5;
    WaitGO go1, \NOTEQ, 0;
    WaitGO go1, \LT, 6;
    IDelete t;
  ENDPROC

  PROC test_waitai_maxtime_value_at_timeout()
    ! WaitAI with \MaxTime and \ValueAtTimeout: ERR_WAIT_MAXTIME, the value is stored.
    VAR num v := -1;
    WaitAI ai1, \GT, 5 \MaxTime:=1 \ValueAtTimeout:=v;
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_WAIT_MAXTIME;
    Assert v = 0;
    RETURN;
  ENDPROC

  PROC test_waitgi_maxtime()
    VAR num v := -1;
    WaitGI gi1, 5 \MaxTime:=0.5 \ValueAtTimeout:=v;
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_WAIT_MAXTIME AND v = 0;
    RETURN;
  ENDPROC

  PROC test_aliasio_and_validio()
    ! AliasIO example: by a signal, then by a string; ValidIO on the variable.
    Assert NOT ValidIO(alias_do) \Msg:="not connected yet";
    AliasIO do1, alias_do;
    Assert ValidIO(alias_do);
    SetDO alias_do, 1;
    Assert DOutput(do1) = 1;
    SetDO do1, 0;
    AliasIO config_string, alias_do;
    SetDO alias_do, 1;
    Assert DOutput(do2) = 1;
    SetDO do2, 0;
    Assert ValidIO(di1);
  ENDPROC

  PROC test_aliasio_errors()
    VAR num stage := 0;
    stage := 1;
    AliasIO "nosuch", alias_do;
    stage := 2;
    AliasIO "di1", alias_do;
    stage := 3;
    AliasIO "di1", alias_di;
    Assert stage = 3 AND ValidIO(alias_di);
    RETURN;
  ERROR
    IF stage = 1 THEN
      Assert ERRNO = ERR_ALIASIO_DEF;
      TRYNEXT;
    ENDIF
    IF stage = 2 THEN
      Assert ERRNO = ERR_ALIASIO_TYPE;
      TRYNEXT;
    ENDIF
    Assert FALSE \Msg:="unexpected error";
  ENDPROC

  PROC test_ivarvalue_is_accepted()
    ! No sensor interface: the order is taken, no interrupt ever comes.
    VAR num value := 0;
    hits := 0;
    CONNECT sig1int WITH count_hit;
    IVarValue "sen1:", 1, value, sig1int;
    WaitTime 0.5;
    Assert hits = 0 AND value = 0;
    IDelete sig1int;
  ENDPROC
ENDMODULE
