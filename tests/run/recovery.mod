MODULE recovery
  ! ERROR handlers: RETRY, TRYNEXT, RETURN, RAISE (new and re-raised), error lists, UNDO.
  VAR num divisor := 0;
  VAR errnum ERR_NOPART := -1;

  FUNC num safe(num a, num b)
    RETURN a / b;
  ERROR
    IF ERRNO = ERR_DIVZERO THEN
      TPWrite "safe: division by zero, returning 0";
      RETURN 0;
    ENDIF
    RAISE;
  ENDFUNC

  PROC retrying()
    VAR num r;
    r := 100 / divisor;
    TPWrite "retrying: result " \Num:=r;
  ERROR
    TPWrite "retrying: ERRNO = ERR_DIVZERO: " \Bool:=ERRNO = ERR_DIVZERO;
    divisor := divisor + 4;
    RETRY;
  ENDPROC

  PROC skipping()
    VAR num a{3} := [1, 2, 3];
    VAR num i := 4;
    a{i} := 10;
    TPWrite "skipping: continued after the failing statement";
  ERROR (ERR_OUTOFBND)
    TPWrite "skipping: index out of bounds";
    TRYNEXT;
  ENDPROC

  PROC pick_part()
    TPWrite "pick_part: no part";
    RAISE ERR_NOPART;
  UNDO
    TPWrite "pick_part: undo";
  ENDPROC

  PROC cell()
    pick_part;
  ERROR
    IF ERRNO = ERR_NOPART THEN
      TPWrite "cell: passing ERR_NOPART on";
      RAISE;
    ENDIF
  ENDPROC

  PROC main()
    BookErrNo ERR_NOPART;
    TPWrite "safe(1, 0) = " \Num:=safe(1, 0);
    retrying;
    skipping;
    cell;
    TPWrite "not reached";
  ERROR
    TPWrite "main: caught booked error " \Num:=ERRNO;
    TPWrite "main: ERRNO = ERR_NOPART: " \Bool:=ERRNO = ERR_NOPART;
  ENDPROC
ENDMODULE
