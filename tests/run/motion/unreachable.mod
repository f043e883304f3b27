MODULE unreachable
  ! A target 3 m away: the move is refused before the robot moves, with ABB event 50050,
  ! and the unhandled ERR_OUTSIDE_REACH stops the program at the instruction.
  CONST robtarget pfar := [[3000, 0, 1000], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  PROC main()
    MoveAbsJ [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v1000, fine, tool0;
    TPWrite "moving to pfar";
    MoveL pfar, v1000, fine, tool0;
    TPWrite "never printed";
  ENDPROC
ENDMODULE
