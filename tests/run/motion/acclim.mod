MODULE acclim
  ! PathAccLim and WorldAccLim bound the TCP acceleration of linear moves (m/s²);
  ! tests/run_path.rs measures it on the trace of each timed move.
  CONST robtarget p10 := [[1100, -300, 800], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p20 := [[1100, 300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR clock clk;

  PROC timed(robtarget target, string what)
    ClkReset clk;
    ClkStart clk;
    MoveL target, v1000, fine, tool0;
    ClkStop clk;
    TPWrite what + ": " \Num:=ClkRead(clk);
  ENDPROC

  PROC main()
    MoveAbsJ [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v1000, fine, tool0;
    MoveL p10, v1000, fine, tool0;
    timed p20, "no limit";
    PathAccLim TRUE \AccMax:=2, TRUE \DecelMax:=1;
    timed p10, "PathAccLim 2, 1";
    PathAccLim FALSE, FALSE;
    WorldAccLim \On:=4;
    timed p20, "WorldAccLim 4";
    WorldAccLim \Off;
    timed p10, "no limit again";
  ENDPROC
ENDMODULE
