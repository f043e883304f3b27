! One minute of motion in real time, to measure the motion cycle's period error with and
! without a live view connected (README, "Seeing the robot"):
!   rapidvc run benches/view_live.mod --realtime
!   rapidvc run benches/view_live.mod --view-live      (then open the printed URL, or not)
MODULE view_live
  CONST jointtarget a := [[0, 0, 0, 0, 35, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST jointtarget b := [[40, 15, 10, 30, 50, -40], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST jointtarget c := [[-30, -10, 30, -20, 60, 60], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  PROC main()
    FOR k FROM 1 TO 6 DO
      TPWrite "round " \Num:=k;
      MoveAbsJ b, v300, z50, tool0;
      MoveAbsJ c, v300, z50, tool0;
      MoveAbsJ a, v300, fine, tool0;
    ENDFOR
  ENDPROC
ENDMODULE
