MODULE Logger
  ! STATIC: starts with the system and logs the shared part count to HOME:/cell.log.
  PERS num parts := 0;
  VAR iodev log;
  VAR num last := -1;
  VAR clock clk;

  PROC logger()
    ClkStart clk;
    Open "HOME:" \File:="cell.log", log \Write;
    Write log, "cell log of task " + GetTaskName();
    Close log;
    WHILE TRUE DO
      IF parts <> last THEN
        Open "HOME:" \File:="cell.log", log \Append;
        Write log, "t=" + NumToStr(ClkRead(clk), 2) + " parts=" + NumToStr(parts, 0);
        Close log;
        TPWrite "logged " + NumToStr(parts, 0) + " parts";
        last := parts;
      ENDIF
      WaitTime 0.1;
    ENDWHILE
  ENDPROC
ENDMODULE
