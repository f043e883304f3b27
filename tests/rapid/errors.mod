MODULE errors
  VAR num tries := 0;
  VAR num undone := 0;
  VAR errnum ERR_MINE := -1;
  VAR errnum ERR_OTHER := -1;

  PROC fails_div(num d)
    VAR num r;
    r := 1 / d;
  ENDPROC

  PROC test_retry()
    VAR num d := 0;
    tries := 0;
    fails_div d;
    Assert tries = 1;
    Assert d = 1;
  ERROR
    IF ERRNO = ERR_DIVZERO THEN
      tries := tries + 1;
      d := 1;
      RETRY;
    ENDIF
  ENDPROC

  ! `ERROR (LONG_JMP_ALL_ERR)` takes every error, here one passed up from a called routine,
  ! and its handler can name the predefined errors of motion as socket servers do.
  PROC test_long_jmp_all_err()
    VAR num caught := 0;
    fails_div 0;
    Assert caught = 1 \Msg:="the division by zero reached this handler";
  ERROR (LONG_JMP_ALL_ERR)
    TEST ERRNO
    CASE ERR_MOTIONSUP, ERR_COLL_STOP:
      caught := -1;
    CASE ERR_DIVZERO:
      caught := 1;
    ENDTEST
    TRYNEXT;
  ENDPROC

  PROC test_trynext()
    VAR num r := 5;
    r := 1 / 0;
    Assert r = 5 \Msg:="TRYNEXT skips the failing statement";
  ERROR
    TRYNEXT;
  ENDPROC

  FUNC num safe_div(num a, num b)
    RETURN a / b;
  ERROR
    RETURN 0;
  ENDFUNC

  PROC test_return_from_handler()
    Assert safe_div(1, 0) = 0;
    Assert safe_div(6, 2) = 3;
  ENDPROC

  PROC raise_user()
    RAISE 12;
  ENDPROC

  PROC test_user_error_propagates()
    raise_user;
    Assert FALSE;
  ERROR
    Assert ERRNO = 12;
  ENDPROC

  PROC reraise()
    VAR num r;
    r := 1 / 0;
  ERROR
    RAISE;
  ENDPROC

  PROC test_reraise_to_caller()
    reraise;
    Assert FALSE;
  ERROR
    Assert ERRNO = ERR_DIVZERO;
  ENDPROC

  PROC test_bookerrno()
    BookErrNo ERR_MINE;
    BookErrNo ERR_OTHER;
    Assert ERR_MINE <> ERR_OTHER;
    Assert ERR_MINE > 90 \Msg:="booked numbers do not collide with user numbers";
    RAISE ERR_MINE;
  ERROR
    Assert ERRNO = ERR_MINE;
  ENDPROC

  PROC test_illegal_raise()
    RAISE 500000;
  ERROR
    Assert ERRNO = ERR_ILLRAISE;
  ENDPROC

  PROC only_divzero()
    VAR num r;
    RAISE 7;
  ERROR (ERR_DIVZERO)
    Assert FALSE \Msg:="the handler only takes ERR_DIVZERO";
  ENDPROC

  PROC test_error_number_list()
    only_divzero;
  ERROR
    Assert ERRNO = 7;
  ENDPROC

  PROC test_retry_limit()
    tries := 0;
    always_fails;
    Assert FALSE;
  ERROR
    Assert ERRNO = ERR_EXCRTYMAX;
    Assert tries = 5 \Msg:="the handler retries 4 times, the fifth RETRY is refused";
  ENDPROC

  PROC always_fails()
    RAISE 3;
  ERROR
    tries := tries + 1;
    RETRY;
  ENDPROC

  PROC with_undo()
    RAISE 4;
  UNDO
    undone := undone + 1;
  ENDPROC

  PROC test_undo_runs_when_abandoned()
    undone := 0;
    with_undo;
  ERROR
    Assert undone = 1;
  ENDPROC

  FUNC num no_return(num x)
    IF x > 0 RETURN 1;
  ENDFUNC

  PROC test_function_without_return()
    VAR num r;
    r := no_return(-1);
  ERROR
    Assert ERRNO = ERR_FNCNORET;
  ENDPROC

  PROC test_errno_in_nested_calls()
    VAR num r;
    r := safe_div(1, 0);
    Assert r = 0;
  ENDPROC
ENDMODULE
