! A short real-time run for the live view test (tests/view_live.rs): joint moves for about
! three seconds with a TP line before each.
MODULE live_run
  CONST jointtarget a := [[0, 0, 0, 0, 35, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST jointtarget b := [[30, 10, 10, 20, 45, -20], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  PROC main()
    FOR k FROM 1 TO 2 DO
      TPWrite "to b " \Num:=k;
      MoveAbsJ b, v1000, fine, tool0;
      TPWrite "to a " \Num:=k;
      MoveAbsJ a, v1000, fine, tool0;
    ENDFOR
  ENDPROC
ENDMODULE
