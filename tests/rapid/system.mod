MODULE system
  ! The controller's system side as `rapidvc test` has it: the calendar starts at
  ! 2025-01-01 00:00:00 (a Wednesday) and runs on virtual time, the system's values are
  ! rapidvc's own (docs/rapid.md, "The controller's system side"). Examples of ABB's "RAPID
  ! Instructions, Functions and Data types" are named where a test follows one.

  PERS tooldata tGripper := [TRUE, [[0, 0, 100], [1, 0, 0, 0]], [1, [0, 0, 50], [1, 0, 0, 0], 0, 0, 0]];
  PERS tooldata curtoolvalue := [TRUE, [[0, 0, 0], [1, 0, 0, 0]], [0, [0, 0, 0], [1, 0, 0, 0], 0, 0, 0]];
  PERS wobjdata wobjTable := [FALSE, TRUE, "", [[500, 0, 200], [1, 0, 0, 0]], [[0, 0, 0], [1, 0, 0, 0]]];
  PERS wobjdata curwobj := [FALSE, TRUE, "", [[0, 0, 0], [1, 0, 0, 0]], [[0, 0, 0], [1, 0, 0, 0]]];
  PERS loaddata box := [2.5, [0, 0, 40], [1, 0, 0, 0], 0, 0, 0];
  PERS loaddata curload := [0.001, [0, 0, 0.001], [1, 0, 0, 0], 0, 0, 0];
  VAR num trap_level := -1;
  VAR num undo_saw := -1;
  VAR intnum timer_int;
  ! `TASK VAR` and `TASK CONST`, as a controller backup declares them in a system module:
  ! plain task data.
  TASK VAR num task_counter := 1;
  TASK CONST num TASK_STEP := 2;

  PROC test_task_var_and_const()
    task_counter := task_counter + TASK_STEP;
    Assert task_counter >= 3;
  ENDPROC

  ! CDate and CTime examples: the date and time as text.
  PROC test_cdate_ctime()
    Assert CDate() = "2025-01-01";
    Assert CTime() = "00:00:00";
    WaitTime 3661.5;
    Assert CTime() = "01:01:01";
    ! `rapidvc test` lets a test wait one virtual day at most: up to midnight.
    WaitTime 86400 - 3661.5;
    Assert CDate() = "2025-01-02";
    Assert CTime() = "00:00:00";
  ENDPROC

  ! GetTime example: IF GetTime(\WDay) < 6 AND GetTime(\Hour) >= 7 ... (a production window).
  PROC test_gettime()
    Assert GetTime(\WDay) = 3 \Msg:="2025-01-01 is a Wednesday";
    Assert GetTime(\Hour) = 0;
    WaitTime 7 * 3600 + 5 * 60 + 9;
    Assert GetTime(\Hour) = 7;
    Assert GetTime(\Min) = 5;
    Assert GetTime(\Sec) = 9;
    Assert GetTime(\WDay) < 6 AND GetTime(\Hour) >= 7 AND GetTime(\Hour) < 17;
    WaitTime 86400 - (7 * 3600 + 5 * 60 + 9);
    Assert GetTime(\WDay) = 4 \Msg:="Thursday";
    Assert GetTime(\Hour) = 0;
  ENDPROC

  PROC test_gettime_needs_a_part()
    VAR num x;
    x := GetTime();
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_ARGVALERR;
  ENDPROC

  PROC test_getsysinfo()
    Assert GetSysInfo(\SerialNo) = "rapidvc-0000";
    Assert StrPart(GetSysInfo(\SWVersion), 1, 10) = "6.08.00.00";
    Assert GetSysInfo(\SWVersionName) = "6.08.00.00";
    Assert GetSysInfo(\RobotType) = "IRB 2600-12/1.85";
    Assert GetSysInfo(\CtrlId) = "rapidvc";
    Assert GetSysInfo(\LanIp) = "127.0.0.1";
    Assert GetSysInfo(\CtrlLang) = "en";
    Assert GetSysInfo(\SystemName) = "rapidvc";
  ENDPROC

  ! IsSysId example: IF NOT IsSysId("6400-1234") THEN ... a program bound to one system.
  PROC test_issysid()
    Assert NOT IsSysId("6400-1234");
    Assert IsSysId(GetSysInfo(\SerialNo));
  ENDPROC

  ! RobOS example: IF RobOS() THEN ... real controller ELSE ... virtual controller.
  PROC test_modes()
    Assert NOT RobOS() \Msg:="a virtual controller";
    Assert OpMode() = OP_AUTO;
    Assert OpMode() <> OP_MAN_PROG AND OpMode() <> OP_MAN_TEST;
    Assert RunMode() = RUN_CONT_CYCLE;
    Assert RunMode(\Main) = RUN_CONT_CYCLE;
    Assert NOT NonMotionMode();
    Assert NOT NonMotionMode(\Main);
    Assert NOT PPMovedInManMode();
  ENDPROC

  ! GetTaskName example: the name and number of the current task.
  PROC test_gettaskname()
    VAR num taskno := 0;
    VAR string taskname;
    taskname := GetTaskName(\TaskNo:=taskno);
    Assert taskname = "T_ROB1";
    Assert taskno = 1;
    taskno := 0;
    Assert GetTaskName(\MecTaskNo:=taskno) = "T_ROB1";
    Assert taskno = 1;
  ENDPROC

  ! RobName example: the robot of the task, "" in a task without one.
  PROC test_mech_units()
    Assert RobName() = "ROB_1";
    Assert GetMecUnitName(ROB_1) = "ROB_1";
    Assert IsMechUnitActive(ROB_1);
    Assert MaxRobSpeed() > 1000;
  ENDPROC

  ! GetNextMechUnit example: list every mechanical unit.
  PROC test_getnextmechunit()
    VAR num listno := 0;
    VAR string name := "";
    VAR string names := "";
    VAR bool tcprob;
    VAR num axes;
    VAR mecunit unit;
    WHILE GetNextMechUnit(listno, name \MecRef:=unit \TCPRob:=tcprob \NoOfAxes:=axes) DO
      names := names + name + ";";
      Assert tcprob;
      Assert axes = 6;
      Assert GetMecUnitName(unit) = name;
    ENDWHILE
    Assert names = "ROB_1;";
    Assert listno = 1;
  ENDPROC

  TRAP note_level
    trap_level := ExecLevel();
  ENDTRAP

  ! ExecHandler example: IF ExecHandler() = HANDLER_UNDO THEN ... (cleaning up in an UNDO
  ! handler); HANDLER_ERR in an ERROR handler, HANDLER_NONE elsewhere.
  PROC test_exechandler()
    VAR num seen := -1;
    Assert ExecHandler() = HANDLER_NONE;
    seen := handler_of_error();
    Assert seen = HANDLER_ERR;
    handler_in_undo;
  ERROR
    ! handler_in_undo leaves with ERR_DIVZERO after its UNDO handler ran.
    Assert ERRNO = ERR_DIVZERO;
    Assert undo_saw = HANDLER_UNDO;
    Assert ExecHandler() = HANDLER_ERR;
    RETURN;
  ENDPROC

  FUNC num handler_of_error()
    VAR num zero := 0;
    VAR num x;
    x := 1 / zero;
    RETURN HANDLER_NONE;
  ERROR
    RETURN ExecHandler();
  ENDFUNC

  PROC handler_in_undo()
    VAR num zero := 0;
    VAR num x;
    x := 1 / zero;
  UNDO
    undo_saw := ExecHandler();
  ENDPROC

  ! EventType example: rapidvc runs no event routines, so code never runs as one.
  PROC test_eventtype()
    Assert EventType() = EVENT_NONE;
  ENDPROC

  ! ExecLevel: LEVEL_NORMAL in routines, LEVEL_TRAP in a TRAP.
  PROC test_execlevel()
    Assert ExecLevel() = LEVEL_NORMAL;
    CONNECT timer_int WITH note_level;
    ITimer \Single, 0.1, timer_int;
    WaitTime 0.2;
    IDelete timer_int;
    Assert trap_level = LEVEL_TRAP;
  ENDPROC

  PROC big_routine(INOUT num inside)
    VAR num data{1000};
    inside := ProgMemFree();
  ENDPROC

  ! ProgMemFree: the free data memory in bytes shrinks while a routine with data runs.
  PROC test_progmemfree()
    VAR num before;
    VAR num inside;
    before := ProgMemFree();
    Assert before > 1000000;
    big_routine inside;
    Assert inside < before;
    Assert before - inside >= 1000 * 8;
    Assert ProgMemFree() = before;
  ENDPROC

  ! TextGet and TextTabGet example: a text of an installed table.
  PROC test_text_tables()
    VAR num text_res_no;
    text_res_no := TextTabGet("rapidvc_weekday");
    Assert TextGet(text_res_no, 1) = "Monday";
    Assert TextGet(text_res_no, GetTime(\WDay)) = "Wednesday";
    Assert NOT TextTabFreeToUse("rapidvc_weekday");
    Assert TextTabFreeToUse("my_texts");
  ENDPROC

  PROC test_text_errors()
    VAR num errs := 0;
    VAR num n;
    VAR string s;
    n := TextTabGet("no_such_table");
    s := TextGet(TextTabGet("rapidvc_weekday"), 8);
    Assert errs = 2;
  ERROR
    Assert ERRNO = ERR_TXTNOEXIST;
    errs := errs + 1;
    TRYNEXT;
  ENDPROC

  ! GetSysData example: the active tool's value and name.
  PROC test_getsysdata()
    VAR string curtoolname;
    GetSysData curtoolvalue \ObjectName:=curtoolname;
    Assert curtoolname = "tool0";
    Assert curtoolvalue.tload.mass = tool0.tload.mass;
    GetSysData curwobj;
    Assert curwobj.ufprog;
    GetSysData curload;
    Assert curload = load0;
  ENDPROC

  ! SetSysData examples: activate a tool, by the object or by name.
  PROC test_setsysdata()
    VAR string name;
    SetSysData tGripper;
    GetSysData curtoolvalue \ObjectName:=name;
    Assert name = "tGripper";
    Assert curtoolvalue.tframe.trans.z = 100;
    SetSysData tool0 \ObjectName:="tGripper";
    GetSysData curtoolvalue \ObjectName:=name;
    Assert name = "tGripper";
    SetSysData wobjTable;
    GetSysData curwobj \ObjectName:=name;
    Assert name = "wobjTable";
    Assert curwobj.uframe.trans.x = 500;
    SetSysData box;
    GetSysData curload \ObjectName:=name;
    Assert name = "box" AND curload.mass = 2.5;
    SetSysData tool0;
    SetSysData wobj0;
    SetSysData load0;
  ENDPROC

  PROC test_setsysdata_unknown_name()
    SetSysData tool0 \ObjectName:="no_such_tool";
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_REFUNKDAT;
  ENDPROC

  ! ErrLog example: a user message 5210 with its own text, here a warning.
  PROC test_errlog()
    ErrLog 5210 \W, "User error", "Argument 2", ERRSTR_EMPTY, ERRSTR_EMPTY, ERRSTR_UNUSED;
    ErrLog 4800, "a", "b", "c", "d", "e";
  ENDPROC

  PROC test_errlog_number()
    ErrLog 100, "a", "b", "c", "d", "e";
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_ARGVALERR;
  ENDPROC

  ! SkipWarn example: an ERROR handler that keeps its warning out of the event log.
  PROC test_skipwarn()
    VAR num x := 0;
    x := 1 / x;
  ERROR
    IF ERRNO = ERR_DIVZERO THEN
      SkipWarn;
      RETURN;
    ENDIF
    Assert FALSE;
  ENDPROC

  PROC test_savecfgdata_without_a_place()
    SaveCfgData "SYSPAR", EIO_DOMAIN;
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_CFG_WRITEFILE;
  ENDPROC
ENDMODULE
