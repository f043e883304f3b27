MODULE Names
  ! Instruction, function and type names are not reserved
  VAR bool switch := FALSE;
  VAR num num := 1;
  VAR num IFx := 0;
  VAR num ENDIFy := 0;
  VAR num toolbox := 0;
  VAR num dOne := 0;
  RECORD pair
    num left;
    num right;
  ENDRECORD
  PROC Stop2()
    IFx := IFx + ENDIFy;
    switch := NOT switch;
    Reset output;
    Present := 1;
  ENDPROC
ENDMODULE
