MODULE num_fast
  ! Statements over module num arrays and local counters that run in place when every value
  ! is a plain num (`pc := pc + 1`, `stk{sp - 1} := stk{sp - 1} MOD stk{sp}`,
  ! `reg{code{pc}} := stk{sp}`, `IF stk{sp} <> 0`): each way off that path raises the error
  ! of the statement, leaves the target unchanged, and RETRY / TRYNEXT resume at it.
  VAR num stk{4} := [1, 2, 3, 4];
  VAR num code{4} := [2, 1, 9, 1.5];
  VAR num reg{3} := [0, 0, 0];
  VAR num errs := 0;
  VAR num last := 0;

  PROC fill()
    FOR k FROM 1 TO 4 DO
      stk{k} := k;
    ENDFOR
  ENDPROC

  ! A counter stepped past the range of num: ERR_NUM_LIMIT, the counter unchanged.
  PROC test_local_step_overflow()
    VAR num x := 3E38;
    VAR num y := -3E38;
    errs := 0;
    x := x + 3E38;
    Assert errs = 1 AND x = 3E38 \Msg:="x + k past the range fails";
    y := y - 3E38;
    Assert errs = 2 AND y = -3E38 \Msg:="y - k past the range fails";
    x := x - 1E38;
    Assert x > 1E38 AND x < 3E38;
  ERROR
    IF ERRNO = ERR_NUM_LIMIT THEN
      errs := errs + 1;
      TRYNEXT;
    ENDIF
  ENDPROC

  ! The arithmetic of elements: MOD/DIV by zero, a non-integer MOD, a result out of range.
  PROC test_element_arith_errors()
    VAR num sp := 4;
    fill;
    errs := 0;
    stk{sp} := 0;
    stk{sp - 1} := stk{sp - 1} MOD stk{sp};
    Assert errs = 1 AND stk{3} = 3 \Msg:="MOD 0 fails, the target unchanged";
    stk{sp - 1} := stk{sp - 1} DIV stk{sp};
    Assert errs = 2 AND stk{3} = 3 \Msg:="DIV 0 fails";
    stk{sp - 1} := stk{sp - 1} / stk{sp};
    Assert errs = 3 AND stk{3} = 3 \Msg:="/ 0 fails";
    stk{sp} := 2.5;
    stk{sp - 1} := stk{sp - 1} MOD stk{sp};
    Assert errs = 4 AND stk{3} = 3 \Msg:="MOD of a non-integer fails";
    stk{sp} := 3E38;
    stk{sp - 1} := stk{sp} * stk{sp};
    Assert errs = 5 AND stk{3} = 3 \Msg:="a product out of range fails";
    stk{sp} := 2;
    stk{sp - 1} := stk{sp - 1} MOD stk{sp};
    Assert errs = 5 AND stk{3} = 1;
    stk{sp - 1} := stk{sp - 2} DIV stk{sp};
    Assert stk{3} = 1;
    stk{sp - 1} := stk{sp - 1} / stk{sp};
    Assert stk{3} = 0.5;
  ERROR
    IF ERRNO = ERR_DIVZERO OR ERRNO = ERR_NUM_LIMIT OR ERRNO = ERR_NOTINTVAL THEN
      errs := errs + 1;
      TRYNEXT;
    ENDIF
  ENDPROC

  ! An index read from another array: out of bounds (9), not an integer (1.5).
  PROC test_indirect_index_errors()
    VAR num pc := 1;
    VAR num sp := 2;
    fill;
    reg{code{pc}} := stk{sp};
    Assert reg{2} = 2;
    stk{sp} := reg{code{pc + 1}};
    Assert stk{2} = 0;
    errs := 0;
    last := 0;
    pc := 3;
    reg{code{pc}} := stk{sp};
    Assert errs = 1 AND last = ERR_OUTOFBND;
    stk{sp} := reg{code{pc}};
    Assert errs = 2 AND last = ERR_OUTOFBND AND stk{2} = 0;
    pc := 4;
    stk{sp} := reg{code{pc}};
    Assert errs = 3 AND last = ERR_NOTINTVAL AND stk{2} = 0;
    reg{code{pc}} := 7;
    Assert errs = 4 AND last = ERR_NOTINTVAL;
  ERROR
    errs := errs + 1;
    last := ERRNO;
    TRYNEXT;
  ENDPROC

  ! A comparison of an element whose index is off: the comparison's error; RETRY with the
  ! index mended compares again.
  PROC test_element_condition_retry()
    VAR num sp := 7;
    VAR num taken := 0;
    fill;
    errs := 0;
    IF stk{sp} <> 0 THEN
      taken := 1;
    ENDIF
    Assert errs = 1 AND taken = 1 AND sp = 4;
    WHILE stk{sp} > 2 DO
      sp := sp - 1;
    ENDWHILE
    Assert sp = 2;
  ERROR
    IF ERRNO = ERR_OUTOFBND THEN
      errs := errs + 1;
      sp := 4;
      RETRY;
    ENDIF
  ENDPROC

  ! A counter that holds no value of its own type any more is not touched in place: an
  ! element that is not a num (a string array element) is refused at check time, so the
  ! path off the fast one here is an unset optional parameter.
  PROC step_opt(\num n)
    VAR num k := 0;
    IF Present(n) THEN
      k := n;
    ENDIF
    k := k + 1;
    last := k;
  ENDPROC

  PROC test_local_step_of_optional()
    step_opt;
    Assert last = 1;
    step_opt \n:=41;
    Assert last = 42;
  ENDPROC

  ! A num TEST with a table: negative and large subjects, and -0.
  PROC test_table_dispatch_edges()
    VAR num x;
    VAR num hit;
    FOR k FROM 1 TO 6 DO
      TEST k
      CASE 1:
        x := -1;
      CASE 2:
        x := 2147483648;
      CASE 3:
        x := -2147483648;
      CASE 4:
        x := -0;
      CASE 5:
        x := 1E30;
      DEFAULT:
        x := 3;
      ENDTEST
      hit := 0;
      TEST x
      CASE -1:
        hit := 1;
      CASE 0:
        hit := 2;
      CASE 3:
        hit := 3;
      DEFAULT:
        hit := 9;
      ENDTEST
      TEST k
      CASE 1:
        Assert hit = 1;
      CASE 4:
        Assert hit = 2;
      CASE 6:
        Assert hit = 3;
      DEFAULT:
        Assert hit = 9;
      ENDTEST
    ENDFOR
  ENDPROC
ENDMODULE
