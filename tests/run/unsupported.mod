MODULE unsupported
  ! What rapidvc does not simulate fails clearly at run time, pointing at the instruction:
  ! here a work object moved by a mechanical unit (coordinated motion).
  CONST robtarget p10 := [[500, 0, 600], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  PERS wobjdata wobj_table := [FALSE, FALSE, "STN1", [[0, 0, 0], [1, 0, 0, 0]], [[0, 0, 0], [1, 0, 0, 0]]];
  PROC main()
    TPWrite "before the move";
    MoveL p10, v100, fine, tool0 \WObj:=wobj_table;
    TPWrite "never printed";
  ENDPROC
ENDMODULE
