MODULE unsupported
  ! Motion instructions check today and fail clearly at run time until the virtual robot exists.
  CONST robtarget p10 := [[500, 0, 600], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  PROC main()
    TPWrite "before the move";
    MoveL p10, v100, fine, tool0 \WObj:=wobj0;
    TPWrite "never printed";
  ENDPROC
ENDMODULE
