MODULE Routines
  PROC simple()
    stepDone := TRUE;
  ENDPROC

  LOCAL PROC modes(num a, INOUT num b, VAR num c, PERS num d)
    b := a;
  ENDPROC

  ! Optional parameters with and without commas, alternatives, switches, open arrays
  PROC options(num first, \switch Fast | switch Slow, \num speed \string note,
               \num level | \bool flag, num values{*}, INOUT num table{*,*},
               \num cube{*,*,*})
    IF Present(Fast) RETURN;
  ENDPROC

  FUNC num twice(num x)
    VAR num result;
    CONST num factor := 2;
    result := x * factor;
    RETURN result;
  ENDFUNC

  LOCAL FUNC bool isSmall(\num limit)
    RETURN TRUE;
  ERROR
    RETURN FALSE;
  ENDFUNC

  TRAP onSignal
    hits := hits + 1;
  ERROR (ERR_DIVZERO, 41)
    TRYNEXT;
  ENDTRAP

  LOCAL TRAP quiet
    RETURN;
  ENDTRAP

  PROC handlers()
    divide;
  BACKWARD
    undoStep;
  ERROR
    IF ERRNO = ERR_DIVZERO THEN
      RETRY;
    ENDIF
    RAISE;
  UNDO
    cleanUp;
  ENDPROC
ENDMODULE
