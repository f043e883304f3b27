MODULE Conditions
  PROC main()
    IF ready
      Stop;
    ENDIF
    WHILE busy
      Wait;
    ENDWHILE
    FOR i 1 TO 3 DO
    ENDFOR
    IF ready WHILE busy DO ENDWHILE
  ENDPROC
ENDMODULE
