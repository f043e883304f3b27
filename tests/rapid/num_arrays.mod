MODULE num_arrays
  ! Elements of num arrays read and written through computed indexes (the shapes of a stack
  ! machine: `s{sp - 1} := s{sp - 1} + s{sp}`, `r{code{pc}}`), their errors, and the order
  ! in which the value and the index of an assignment are evaluated.
  VAR num stk{4} := [1, 2, 3, 4];
  VAR num code{3} := [3, 1, 2];
  VAR num calls := 0;
  VAR num grid{2, 3};
  VAR bool going := TRUE;

  FUNC num bump()
    calls := calls + 1;
    RETURN calls;
  ENDFUNC

  PROC reset()
    FOR k FROM 1 TO 4 DO
      stk{k} := k;
    ENDFOR
  ENDPROC

  PROC test_computed_index_reads_and_writes()
    VAR num sp := 4;
    VAR num loc{3} := [10, 20, 30];
    reset;
    stk{sp - 1} := stk{sp - 1} + stk{sp};
    Assert stk{3} = 7;
    stk{sp - 2} := stk{sp - 1} * stk{sp};
    Assert stk{2} = 28;
    Assert stk{code{1}} = 7;
    stk{code{2}} := stk{code{3}} - 1;
    Assert stk{1} = 27;
    loc{sp - 1} := loc{sp - 3} + loc{code{3}};
    Assert loc{3} = 30;
    Assert loc{sp - 2} = 20;
    stk{sp} := loc{sp - 1} MOD 7;
    Assert stk{4} = 2;
  ENDPROC

  ! The value is computed before the index of the target (each call of `bump` counts).
  PROC test_value_before_target_index()
    VAR num a{4} := [0, 0, 0, 0];
    calls := 0;
    a{bump() + 1} := bump();
    Assert a{3} = 1 \Msg:="the value is computed first";
    reset;
    calls := 0;
    stk{bump()} := stk{bump() + 1} + 100;
    Assert stk{2} = 102 \Msg:="stk{2} := stk{2} + 100";
    Assert stk{1} = 1;
    Assert calls = 2;
  ENDPROC

  PROC test_computed_index_out_of_bounds()
    VAR num sp := 4;
    VAR num got := 0;
    VAR num x;
    x := stk{sp + 1};
    Assert got = 1 \Msg:="a read outside the bounds fails";
    stk{sp + 1} := 5;
    Assert got = 2 \Msg:="a write outside the bounds fails";
    stk{sp - 4} := stk{sp};
    Assert got = 3 \Msg:="index 0 is outside the bounds";
  ERROR
    IF ERRNO = ERR_OUTOFBND THEN
      got := got + 1;
      TRYNEXT;
    ENDIF
  ENDPROC

  PROC test_computed_index_not_an_integer()
    VAR num sp := 4;
    VAR num got := 0;
    VAR num x;
    x := stk{sp / 8};
    Assert got = 1;
    stk{sp / 8} := 1;
    Assert got = 2;
  ERROR
    IF ERRNO = ERR_NOTINTVAL THEN
      got := got + 1;
      TRYNEXT;
    ENDIF
  ENDPROC

  ! RETRY runs the failing statement again, with the index evaluated anew.
  PROC test_computed_index_retry()
    VAR num sp := 9;
    VAR num x;
    reset;
    x := stk{sp - 4};
    Assert x = stk{1};
    Assert sp = 5;
  ERROR
    IF ERRNO = ERR_OUTOFBND THEN
      sp := sp - 4;
      RETRY;
    ENDIF
  ENDPROC

  ! A 2-D array indexed with computed indexes takes the general path.
  PROC test_two_dimensions()
    VAR num i := 1;
    grid{i + 1, i + 2} := 6;
    Assert grid{2, 3} = 6;
    grid{i, i + 1} := grid{i + 1, i + 2} - 1;
    Assert grid{1, 2} = 5;
  ENDPROC

  ! TEST on a num: integer cases from a table, a non-integer subject matching none, and a
  ! CASE listed twice taking the first.
  PROC test_num_test_dispatch()
    VAR num hits{4};
    VAR num op;
    FOR k FROM 0 TO 5 DO
      op := k;
      TEST op
      CASE 1:
        hits{1} := hits{1} + 1;
      CASE 2, 3:
        hits{2} := hits{2} + op;
      CASE 3:
        hits{3} := hits{3} + 1;
      DEFAULT:
        hits{4} := hits{4} + 1;
      ENDTEST
    ENDFOR
    Assert hits{1} = 1;
    Assert hits{2} = 5;
    Assert hits{3} = 0;
    Assert hits{4} = 3;
    op := 1.5;
    TEST op
    CASE 1, 2:
      hits{1} := 0;
    DEFAULT:
      hits{4} := 0;
    ENDTEST
    Assert hits{1} = 1 AND hits{4} = 0;
  ENDPROC

  ! WHILE on a bool variable, set from inside the loop.
  PROC test_while_bool_variable()
    VAR num n := 0;
    going := TRUE;
    WHILE going DO
      n := n + 1;
      IF n >= 5 going := FALSE;
    ENDWHILE
    Assert n = 5;
  ENDPROC
ENDMODULE
