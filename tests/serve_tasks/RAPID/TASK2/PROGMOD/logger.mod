MODULE Logger
  ! STATIC: counts from boot, whatever the NORMAL task does.
  TASK PERS num ticks := 0;

  PROC logger()
    WHILE TRUE DO
      ticks := ticks + 1;
      WaitTime 0.05;
    ENDWHILE
  ENDPROC
ENDMODULE
