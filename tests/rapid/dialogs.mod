MODULE dialogs
  ! Operator dialogs with nobody to answer (`rapidvc test` without --answers): they end by
  ! \MaxTime or a break condition, as the RAPID reference documents. Examples named.
  PERS bool stop_dialog := FALSE;
  VAR intnum t;

  TRAP set_stop
    stop_dialog := TRUE;
  ENDTRAP

  PROC test_dialogs_without_an_operator()
    ! UIClientExist example: nobody answers in `rapidvc test` without --answers.
    VAR errnum errvar;
    VAR num reg1 := 3;
    VAR btnres answer;
    Assert NOT UIClientExist();
    ! TPReadFK example 2: the \MaxTime ends the dialog, the reason in \BreakFlag.
    TPReadFK reg1, "Go to service position?", stEmpty, stEmpty, stEmpty, "Yes", "No"
      \MaxTime:=600 \DIBreak:=di1 \BreakFlag:=errvar;
    Assert errvar = ERR_TP_MAXTIME AND reg1 = 3;
    answer := UIMessageBox(\Message:="Go on?" \Buttons:=btnYesNo \DefaultBtn:=resNo
      \MaxTime:=1 \BreakFlag:=errvar);
    Assert answer = resNo AND errvar = ERR_TP_MAXTIME;
    ! No \MaxTime or break: ERR_TP_NO_CLIENT.
    TPReadNum reg1, "How many?";
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_TP_NO_CLIENT;
    RETURN;
  ENDPROC

  PROC test_break_conditions()
    VAR errnum errvar;
    VAR num reg1;
    VAR clock c;
    ! \DIPassive: di1 is 0, so the dialog is broken at once.
    TPReadFK reg1, "Passive", "A", stEmpty, stEmpty, stEmpty, stEmpty
      \DIBreak:=di1 \DIPassive \BreakFlag:=errvar;
    Assert errvar = ERR_TP_DIBREAK;
    ! \PersBoolBreak: a trap sets the persistent after 1.5 s.
    stop_dialog := FALSE;
    ClkReset c;
    ClkStart c;
    CONNECT t WITH set_stop;
    ITimer \Single, 1.5, t;
    TPReadNum reg1, "Number" \MaxTime:=60 \PersBoolBreak:=stop_dialog \BreakFlag:=errvar;
    Assert errvar = ERR_TP_PERSBOOLBREAK;
    Assert ClkRead(c) < 2 \Msg:="ended by the persistent, not \\MaxTime";
    IDelete t;
  ENDPROC

  PROC test_defaults_after_a_timeout()
    ! What UI dialogs return when nobody answers within \MaxTime.
    VAR errnum errvar;
    VAR num n;
    VAR btnres res := resOK;
    CONST listitem list{3} := [["", "Item 1"], ["", "Item 2"], ["", "Item 3"]];
    n := UINumEntry(\Message:="How many?" \InitValue:=5 \MinValue:=1 \MaxValue:=10
      \MaxTime:=1 \BreakFlag:=errvar);
    Assert n = 5 AND errvar = ERR_TP_MAXTIME;
    n := UINumTune(\Message:="Flow" , 2.5, 0.1 \MaxTime:=1 \BreakFlag:=errvar);
    Assert n = 2.5;
    n := UIListView(\Result:=res \Header:="List", list \DefaultIndex:=2 \MaxTime:=1
      \BreakFlag:=errvar);
    Assert n = 2 AND res = resUnkwn;
    UIMsgBox "Continue?" \UIActiveSignal:=do1 \MaxTime:=1 \BreakFlag:=errvar \Result:=res;
    Assert res = resUnkwn AND DOutput(do1) = 0 \Msg:="\\UIActiveSignal is reset after";
    ! Without \BreakFlag the time-out is raised.
    UIMsgBox "Continue?" \MaxTime:=1;
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_TP_MAXTIME;
    RETURN;
  ENDPROC

  PROC test_ui_limit_errors()
    ! UINumEntry's documented errors: limits the wrong way round, an initial value
    ! outside them, a fractional initial value with \AsInteger.
    VAR num n;
    VAR num stage := 0;
    stage := 1;
    n := UINumEntry(\MinValue:=5 \MaxValue:=1 \MaxTime:=1);
    stage := 2;
    n := UINumEntry(\InitValue:=11 \MinValue:=1 \MaxValue:=10 \MaxTime:=1);
    stage := 3;
    n := UINumEntry(\InitValue:=1.5 \AsInteger \MaxTime:=1);
    stage := 4;
    n := UINumTune(\Message:="x", 5, 1 \MinValue:=6 \MaxTime:=1);
    Assert stage = 4 \Msg:="not reached";
  ERROR
    TEST stage
    CASE 1:
      Assert ERRNO = ERR_UI_MAXMIN;
      TRYNEXT;
    CASE 2:
      Assert ERRNO = ERR_UI_INITVALUE;
      TRYNEXT;
    CASE 3:
      Assert ERRNO = ERR_UI_NOTINT;
      TRYNEXT;
    CASE 4:
      Assert ERRNO = ERR_UI_INITVALUE;
      RETURN;
    ENDTEST
  ENDPROC

  PROC test_tpshow()
    ! TPShow example: TPShow TP_LATEST.
    TPShow TP_LATEST;
    TPShow 7;
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_ARGVALERR;
    RETURN;
  ENDPROC
ENDMODULE
