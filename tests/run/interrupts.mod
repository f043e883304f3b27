MODULE interrupts
  ! Traps run between statements and during waits, in virtual time.
  VAR intnum timer;
  VAR intnum edge;
  VAR clock c;

  TRAP on_timer
    TPWrite "timer at " \Num:=ClkRead(c);
  ENDTRAP

  TRAP on_edge
    TPWrite "do1 went high at " \Num:=ClkRead(c);
  ENDTRAP

  PROC main()
    ClkStart c;
    CONNECT timer WITH on_timer;
    ITimer 1.5, timer;
    CONNECT edge WITH on_edge;
    ISignalDO do1, 1, edge;
    WaitTime 2;
    SetDO do1, 1;
    TPWrite "set do1 at " \Num:=ClkRead(c);
    WaitTime 2;
    IDelete timer;
    WaitTime 5;
    TPWrite "end at " \Num:=ClkRead(c);
  ENDPROC
ENDMODULE
