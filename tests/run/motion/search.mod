! args: --config events
MODULE search
  ! SearchL, SearchC, SearchExtJ and MoveExtJ. The searched signal is do1, set by a TRAP on
  ! an ITimer while the robot moves (no RAPID instruction sets an input). Numbers: p10 → p20
  ! is 600 mm at 200 mm/s; the timer fires 1.5 s after the search starts, about 280 mm on
  ! (the ramp-up takes a little time).
  CONST robtarget p10 := [[1100, -300, 800], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p20 := [[1100, 300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget pc := [[1100, 0, 500], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR intnum tick;
  VAR intnum tick2;
  VAR robtarget sp;
  VAR robtarget here;
  VAR jointtarget jp;
  VAR num errors := 0;

  TRAP set_do1
    SetDO do1, 1;
  ENDTRAP

  TRAP pulse_do1
    ! Two rising edges 0.5 s apart.
    PulseDO \PLength:=0.25, do1;
  ENDTRAP

  PROC show(string what)
    here := CRobT(\Tool:=tool0);
    TPWrite what + ": search point y " + NumToStr(sp.trans.y, 1) + ", robot at y "
      + NumToStr(here.trans.y, 1);
  ENDPROC

  PROC main()
    MoveAbsJ [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v1000, fine, tool0;
    MoveL p10, v1000, fine, tool0;
    ! RAPID reference, SearchL example: "SearchL \Stop, di2, sp, p10, v100, probe;" stops
    ! as quickly as possible when di2 goes high; the robot ends a little past sp.
    CONNECT tick WITH set_do1;
    ITimer \Single, 1.5, tick;
    SearchL \Stop, do1, sp, p20, v200, tool0;
    show "SearchL \\Stop";
    ! \PStop and \SStop brake the same way on the virtual robot.
    SetDO do1, 0;
    MoveL p10, v1000, fine, tool0;
    ITimer \Single, 1.5, tick;
    SearchL \PStop, do1, sp, p20, v200, tool0;
    show "SearchL \\PStop";
    ! Without a stop switch the robot goes on to the ToPoint (a flying search).
    SetDO do1, 0;
    MoveL p10, v1000, fine, tool0;
    ITimer \Single, 1.5, tick;
    SearchL do1, sp, p20, v200, tool0;
    show "SearchL (flying)";
    ! \NegFlank: do1 is 1 now and goes to 0; SearchC with \SStop.
    CONNECT tick2 WITH pulse_do1;
    ITimer \Single, 1, tick2;
    SearchC \SStop, do1 \NegFlank, sp, pc, p10, v200, tool0;
    show "SearchC \\SStop \\NegFlank";
    ! Let the pulse end (do1 back to 1).
    WaitTime 0.5;
    ! Errors: the signal is already high at the start of a positive-flank search.
    SetDO do1, 1;
    SearchL \Stop, do1, sp, p20, v200, tool0;
    ! \HighLevel with the signal already high: found at once, the robot does not move.
    SearchL \Stop, do1 \HighLevel, sp, p20, v200, tool0;
    show "SearchL \\HighLevel";
    ! No change before the ToPoint.
    SetDO do1, 0;
    MoveL p10, v1000, fine, tool0;
    SearchL \Stop, do1, sp, p20, v200, tool0;
    ! \Sup with two rising edges.
    SetDO do1, 0;
    MoveL p10, v1000, fine, tool0;
    ITimer 1, tick2;
    SearchL \Sup, do1, sp, p20, v100, tool0;
    IDelete tick2;
    TPWrite "errors handled: " \Num:=errors;
    ! SearchExtJ and MoveExtJ: the virtual robot has no external axes; nothing moves.
    SetDO do1, 1;
    SearchExtJ \Stop, do1 \HighLevel, jp, [[9E9, 9E9, 9E9, 9E9, 9E9, 9E9], [100, 9E9, 9E9, 9E9, 9E9, 9E9]], v200;
    TPWrite "SearchExtJ \\HighLevel: axis 1 at " \Num:=Round(jp.robax.rax_1 \Dec:=2);
    MoveExtJ [[9E9, 9E9, 9E9, 9E9, 9E9, 9E9], [100, 9E9, 9E9, 9E9, 9E9, 9E9]], v200, fine;
    TPWrite "MoveExtJ done, axis 1 at " \Num:=Round(CJointT().robax.rax_1 \Dec:=2);
    SetDO do1, 0;
    SearchExtJ \Stop, do1, jp, [[9E9, 9E9, 9E9, 9E9, 9E9, 9E9], [100, 9E9, 9E9, 9E9, 9E9, 9E9]], v200;
  ERROR
    errors := errors + 1;
    IF ERRNO = ERR_SIGSUPSEARCH THEN
      TPWrite "ERR_SIGSUPSEARCH";
      TRYNEXT;
    ELSEIF ERRNO = ERR_WHLSEARCH THEN
      here := CRobT(\Tool:=tool0);
      TPWrite "ERR_WHLSEARCH, robot at y " \Num:=Round(here.trans.y \Dec:=1);
      TRYNEXT;
    ENDIF
  ENDPROC
ENDMODULE
