MODULE corr
  ! Correction generators drive \Corr: CorrWrite's offset (path frame: x along the path, z the
  ! tool's z, y = z x x) is added to MoveL \Corr; CorrRead sums the connected generators.
  ! tests/run_path.rs checks the offset on the trace.
  CONST robtarget p10 := [[1100, -300, 800], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p20 := [[1100, 300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR corrdescr lateral;
  VAR corrdescr height;
  VAR intnum tick;
  VAR pos total;

  TRAP on_tick
    ! Half-way through the move the height generator lowers the tool 10 mm (path z is the
    ! tool's z, which points down).
    CorrWrite height, [0, 0, 10];
  ENDTRAP

  PROC main()
    MoveAbsJ [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v1000, fine, tool0;
    MoveL p10, v1000, fine, tool0;
    CorrCon lateral;
    CorrCon height;
    CorrWrite lateral, [0, 5, 0];
    total := CorrRead();
    TPWrite "CorrRead: " \Pos:=total;
    CONNECT tick WITH on_tick;
    ITimer \Single, 1.5, tick;
    MoveL p20, v200, fine, tool0 \Corr;
    TPWrite "at p20 \\Corr: " \Pos:=CPos();
    total := CorrRead();
    TPWrite "CorrRead: " \Pos:=total;
    CorrDiscon lateral;
    TPWrite "after CorrDiscon: " \Pos:=CorrRead();
    CorrClear;
    TPWrite "after CorrClear: " \Pos:=CorrRead();
    MoveL p10, v200, fine, tool0 \Corr;
    TPWrite "at p10, nothing connected: " \Pos:=CPos();
  ENDPROC
ENDMODULE
