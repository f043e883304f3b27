MODULE BadDecls
  ! TASK VAR at module level is valid (tests/parse/ok/declarations.mod); in a routine it is not.
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
