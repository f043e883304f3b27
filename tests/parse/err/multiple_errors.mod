MODULE Several
  VAR num ok := 1;
  VAR num broken := ;
  PROC first()
    x := 1 +;
    y := 2;
    MoveL spot v100, z10, gripTool;
  ENDPROC
  PROC second()
    IF a > THEN
      z := 3;
    ENDIF
    WHILE TRUE
      z := 4;
    ENDWHILE
  ENDPROC
  FUNC num third(num a
    RETURN a;
  ENDFUNC
ENDMODULE
