MODULE latebind
  ! Late binding: procedures are called by a name built at run time (`%"op_" + …%`) and by
  ! names read from an array. Same algorithm: latebind.py, latebind.lua.
  CONST num N := 1000000;
  CONST string NAMES{4} := ["op_1", "op_2", "op_3", "op_4"];
  VAR num acc := 0;

  PROC op_1(num x)
    acc := (acc + x + 1) MOD 99991;
  ENDPROC

  PROC op_2(num x)
    acc := (acc + 2 * x + 3) MOD 99991;
  ENDPROC

  PROC op_3(num x)
    acc := (acc * 3 + x + 5) MOD 99991;
  ENDPROC

  PROC op_4(num x)
    acc := (acc + x * x + 7) MOD 99991;
  ENDPROC

  PROC main()
    VAR num check := 0;
    FOR i FROM 1 TO N DO
      %"op_" + NumToStr(i MOD 4 + 1, 0)% i MOD 100;
    ENDFOR
    check := acc;
    FOR i FROM 1 TO N DO
      %NAMES{(i * 3) MOD 4 + 1}% i MOD 50;
    ENDFOR
    TPWrite "result: " + NumToStr(check, 0) + " " + NumToStr(acc, 0);
  ENDPROC
ENDMODULE
