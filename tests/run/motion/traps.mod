MODULE traps
  ! Traps run while the program waits for the robot at a fine point; the robot keeps moving.
  CONST robtarget p10 := [[1100, -300, 800], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p20 := [[1100, 300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR intnum tick;
  VAR clock clk;

  TRAP on_tick
    TPWrite "trap at " + NumToStr(ClkRead(clk), 3) + " s, TCP y " \Num:=Round(CPos().y);
  ENDTRAP

  PROC main()
    MoveAbsJ [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v1000, fine, tool0;
    MoveL p10, v1000, fine, tool0;
    ClkStart clk;
    CONNECT tick WITH on_tick;
    ITimer 0.75, tick;
    MoveL p20, v200, fine, tool0;
    IDelete tick;
    TPWrite "p20 reached at " \Num:=ClkRead(clk);
  ENDPROC
ENDMODULE
