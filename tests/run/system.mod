! args: --date=2030-06-14T23:59:58 --max-time 400000
MODULE system_run
  ! The controller's system side in a run: the calendar from --date on virtual time, a text
  ! table, the event log (ErrLog), the system's values, and WarmStart (not possible inside a
  ! run: the program stops with a clear error).
  PROC main()
    VAR num weekdays;
    weekdays := TextTabGet("rapidvc_weekday");
    TPWrite CDate() + " " + CTime() + " " + TextGet(weekdays, GetTime(\WDay));
    WaitTime 2;
    TPWrite CDate() + " " + CTime() + " " + TextGet(weekdays, GetTime(\WDay));
    WaitTime 2 * 86400 + 3600 + 61;
    TPWrite CDate() + " " + CTime() + " " + TextGet(weekdays, GetTime(\WDay));
    ErrLog 5210 \W, "Part missing", "No part at station 2.", "Check the feeder.", ERRSTR_EMPTY, ERRSTR_UNUSED;
    ErrLog 4800 \I, "arg1", "arg2", ERRSTR_EMPTY, ERRSTR_EMPTY, ERRSTR_EMPTY;
    TPWrite "serial " + GetSysInfo(\SerialNo) + ", robot " + GetSysInfo(\RobotType) + ", " + GetTaskName();
    TPWrite "max TCP speed " \Num:=MaxRobSpeed();
    WarmStart;
    TPWrite "not reached";
  ENDPROC
ENDMODULE
