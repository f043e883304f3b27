! args: --config events --signal-script events/probe.sig
MODULE search_di
  ! SearchL on a digital input driven by --signal-script (events/probe.sig: di1 rises at
  ! 3.0 s, falls at 3.5 s and rises again at 6.0 s of robot time). RAPID reference, SearchL:
  ! "SearchL \Stop, di1, sp, p20, v200, tool0;" stores the position where di1 went high.
  CONST robtarget p10 := [[1100, -300, 800], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p20 := [[1100, 300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR intnum rise;
  VAR robtarget sp;
  VAR clock clk;

  TRAP on_rise
    TPWrite "di1 rose at " + NumToStr(ClkRead(clk), 3) + " s";
  ENDTRAP

  PROC main()
    ClkStart clk;
    CONNECT rise WITH on_rise;
    ISignalDI di1, 1, rise;
    MoveAbsJ [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v1000, fine, tool0;
    MoveL p10, v1000, fine, tool0;
    TPWrite "search starts at " + NumToStr(ClkRead(clk), 3) + " s";
    SearchL \Stop, di1, sp, p20, v200, tool0;
    TPWrite "found at y " + NumToStr(sp.trans.y, 1) + ", stopped at y "
      + NumToStr(CPos().y, 1) + ", " + NumToStr(ClkRead(clk), 3) + " s";
    ! WaitDI sees the scripted input too: it falls at 3.5 s and rises again at 6.0 s.
    WaitDI di1, 0;
    WaitDI di1, 1;
    TPWrite "WaitDI di1 = 1 at " + NumToStr(ClkRead(clk), 3) + " s";
  ENDPROC
ENDMODULE
