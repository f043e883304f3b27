MODULE Unclosed
  PROC first()
    IF ready THEN
      WHILE busy DO
        Wait;
    ENDIF
  ENDPROC
  PROC second()
    FOR i FROM 1 TO 3 DO
      Step i;
  PROC third()
    TEST mode
    CASE 1:
      Stop;
  ENDPROC
