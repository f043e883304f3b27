MODULE BadDecls
  TASK VAR num notPers := 1;
  VAR num tooMany{2, 2, 2, 2};
  PROC main(num open{*,*,*,*})
    LOCAL VAR num hidden;
    PERS num kept := 1;
    TASK CONST num c := 1;
    Stop;
    VAR num late;
    IF TRUE THEN
      VAR num inside;
    ENDIF
  ENDPROC
ENDMODULE
