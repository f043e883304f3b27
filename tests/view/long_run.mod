! A ten-minute run for the view's size and load-time figures (tests/view_browser.rs):
! joint moves between four positions, linear moves in a square around each, fly-by and fine
! points, a TP line per round.
MODULE long_run
  CONST jointtarget j1 := [[0, 10, 20, 0, 50, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST jointtarget j2 := [[40, 0, 30, 20, 40, -30], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST jointtarget j3 := [[-35, 20, 10, -20, 60, 45], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST jointtarget j4 := [[10, -10, 40, 60, -40, 90], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR robtarget p;

  PROC square(jointtarget start)
    MoveAbsJ start, v500, fine, tool0;
    p := CRobT(\Tool:=tool0);
    MoveL Offs(p, 150, 0, 0), v200, z20, tool0;
    MoveL Offs(p, 150, 150, 0), v200, z20, tool0;
    MoveL Offs(p, 0, 150, -100), v200, z20, tool0;
    MoveL p, v200, fine, tool0;
    WaitTime 0.5;
  ENDPROC

  PROC main()
    ConfL \Off;
    FOR round FROM 1 TO 27 DO
      TPWrite "round " \Num:=round;
      square j1;
      square j2;
      square j3;
      square j4;
    ENDFOR
  ENDPROC
ENDMODULE
