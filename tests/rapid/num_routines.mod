MODULE num_routines
  ! Routines on `num`s only that call such routines (num value parameters, num routine
  ! data, num module data) run on the interpreter's num frame slab: these pin that errors
  ! reach the handlers of their callers, RETURN ends them from inside an IF, module data and
  ! array elements are read and written, ERR_FNCNORET is raised, and late binding reaches
  ! them as elsewhere.
  VAR num calls := 0;
  VAR num tab{5} := [1, 2, 3, 4, 5];
  VAR num hits := 0;

  FUNC num fib(num n)
    IF n < 2 RETURN n;
    RETURN fib(n - 1) + fib(n - 2);
  ENDFUNC

  FUNC num down_div(num n, num d)
    IF n = 0 RETURN 1 / d;
    RETURN down_div(n - 1, d) + 1;
  ENDFUNC

  FUNC num no_return(num n)
    VAR num k := 2;
    IF n > 0 THEN
      k := k + fib(n);
      RETURN k;
    ENDIF
  ENDFUNC

  PROC bump(num k)
    calls := calls + k;
    tab{k} := tab{k} * 10 + fib(2);
  ENDPROC

  PROC count_down(num n)
    IF n <= 0 RETURN;
    hits := hits + 1;
    count_down n - 1;
  ENDPROC

  FUNC num pick(num i)
    RETURN tab{i + 0} + fib(1);
  ENDFUNC

  PROC test_recursion_and_returns()
    Assert fib(15) = 610;
    hits := 0;
    count_down 7;
    Assert hits = 7;
    Assert no_return(5) = 7;
  ENDPROC

  PROC test_module_data()
    tab := [1, 2, 3, 4, 5];
    calls := 0;
    bump 2;
    bump 5;
    Assert calls = 7;
    Assert tab{2} = 21 AND tab{5} = 51 AND tab{1} = 1;
    Assert pick(3) = 4;
  ENDPROC

  ! An error deep in a recursion reaches the handler of the first caller that has one.
  PROC test_error_from_deep_recursion()
    VAR num r := 0;
    VAR num d := 0;
    r := down_div(20, d);
    Assert r = 21 \Msg:="RETRY with d = 1";
    Assert d = 1;
  ERROR
    IF ERRNO = ERR_DIVZERO THEN
      d := 1;
      RETRY;
    ENDIF
  ENDPROC

  PROC test_index_out_of_bounds()
    VAR num caught := 0;
    VAR num r := 0;
    r := pick(6);
    Assert caught = 1;
  ERROR
    IF ERRNO = ERR_ILLDIM THEN
      caught := 1;
      TRYNEXT;
    ENDIF
  ENDPROC

  PROC test_index_write_out_of_bounds()
    VAR num caught := 0;
    calls := 0;
    bump 6;
    Assert caught = 1;
    Assert calls = 6 \Msg:="the statement before the failing one ran";
  ERROR
    IF ERRNO = ERR_ILLDIM THEN
      caught := 1;
      TRYNEXT;
    ENDIF
  ENDPROC

  PROC test_func_without_return()
    VAR num caught := 0;
    VAR num r := 0;
    r := no_return(0);
    Assert caught = 1;
  ERROR
    IF ERRNO = ERR_FNCNORET THEN
      caught := 1;
      TRYNEXT;
    ENDIF
  ENDPROC

  PROC test_late_bound()
    calls := 0;
    tab := [1, 2, 3, 4, 5];
    FOR i FROM 1 TO 3 DO
      %"bu" + "mp"% i;
    ENDFOR
    Assert calls = 6;
    Assert tab{3} = 31;
  ENDPROC

  ! WHILE loops run on the slab too (a routine with loops that calls such routines).
  VAR num sdata{9} := [5, 3, 9, 1, 7, 2, 8, 6, 4];

  PROC qsort(num lo, num hi)
    VAR num i;
    VAR num j;
    VAR num pivot;
    VAR num t;
    IF lo >= hi RETURN;
    pivot := sdata{(lo + hi) DIV 2};
    i := lo;
    j := hi;
    WHILE i <= j DO
      WHILE sdata{i} < pivot DO
        i := i + 1;
      ENDWHILE
      WHILE sdata{j} > pivot DO
        j := j - 1;
      ENDWHILE
      IF i <= j THEN
        t := sdata{i};
        sdata{i} := sdata{j};
        sdata{j} := t;
        i := i + 1;
        j := j - 1;
      ENDIF
    ENDWHILE
    qsort lo, j;
    qsort i, hi;
  ENDPROC

  ! RETURN from inside a WHILE ends the routine.
  FUNC num find(num x)
    VAR num i := 1;
    WHILE i <= 5 DO
      IF tab{i} = x RETURN i + fib(0);
      i := i + 1;
    ENDWHILE
    RETURN -1;
  ENDFUNC

  ! The condition of a WHILE fails (an index out of bounds) after some rounds.
  FUNC num run_off(num k)
    VAR num i := 1;
    WHILE tab{i} > k DO
      i := i + 1 + fib(0);
    ENDWHILE
    RETURN i;
  ENDFUNC

  ! `local + constant` beyond the range of num.
  FUNC num grow(num n)
    RETURN n + 3E38 + fib(0);
  ENDFUNC

  PROC test_while_on_slab()
    qsort 1, 9;
    FOR i FROM 1 TO 9 DO
      Assert sdata{i} = i;
    ENDFOR
    sdata := [9, 9, 1, 1, 5, 5, 2, 2, 7];
    qsort 1, 9;
    Assert sdata{1} = 1 AND sdata{2} = 1 AND sdata{3} = 2 AND sdata{4} = 2;
    Assert sdata{5} = 5 AND sdata{6} = 5 AND sdata{7} = 7 AND sdata{8} = 9 AND sdata{9} = 9;
    tab := [1, 2, 3, 4, 5];
    Assert find(4) = 4;
    Assert find(6) = -1;
    Assert run_off(2) = 1;
  ENDPROC

  PROC test_while_condition_error()
    VAR num caught := 0;
    VAR num r := 0;
    tab := [1, 2, 3, 4, 5];
    r := run_off(0);
    Assert caught = 1;
    Assert r = 0;
  ERROR
    IF ERRNO = ERR_ILLDIM THEN
      caught := 1;
      TRYNEXT;
    ENDIF
  ENDPROC

  PROC test_local_plus_constant_limit()
    VAR num caught := 0;
    VAR num r := 0;
    r := grow(1);
    Assert r = 3E38;
    r := grow(3E38);
    Assert caught = 1;
  ERROR
    IF ERRNO = ERR_NUM_LIMIT THEN
      caught := 1;
      TRYNEXT;
    ENDIF
  ENDPROC
ENDMODULE
