MODULE moves
  ! MoveJ, MoveL and MoveC in front of the robot with the tool pointing down; CPos and CRobT
  ! read where the robot is after each stop point.
  CONST jointtarget home := [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p10 := [[1100, -300, 800], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget p20 := [[1100, 300, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget c30 := [[1300, 0, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR clock clk;

  PROC main()
    MoveAbsJ home, v1000, fine, tool0;
    ClkStart clk;
    MoveJ p10, v1000, fine, tool0;
    show "MoveJ p10";
    MoveL p20, v500, fine, tool0;
    show "MoveL p20";
    MoveC c30, p10, v500, fine, tool0;
    show "MoveC c30, p10";
    MoveL Offs(p10, 0, 0, 200), v200, fine, tool0 \WObj:=wobj0;
    show "MoveL up 200";
  ENDPROC

  PROC show(string what)
    VAR robtarget t;
    t := CRobT(\Tool:=tool0 \WObj:=wobj0);
    TPWrite what + " at " \Num:=ClkRead(clk);
    TPWrite "  CPos " \Pos:=CPos();
    TPWrite "  conf " + ValToStr(t.robconf);
  ENDPROC
ENDMODULE
