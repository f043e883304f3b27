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
ENDMODULE
