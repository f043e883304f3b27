MODULE limits
  ! The task's data limit (2,000,000 values: module data plus every call in progress) is
  ! checked at each call: a call that would go over it raises ERR_DATA_LIMIT, which the
  ! caller's ERROR handler can take, instead of the run aborting when memory runs out.
  VAR num depth := 0;
  ! 400,000 values of module data (plus the stdlib's few hundred).
  VAR num big{400000};

  PROC deep(num n)
    ! 1,000,000 values per call: with the module data, the second call does not fit.
    VAR num a{1000, 1000};
    depth := n;
    a{1000, 1000} := n;
    deep n + 1;
  ENDPROC

  PROC test_recursion_with_large_routine_data()
    depth := 0;
    deep 1;
    Assert FALSE \Msg:="the recursion must end with ERR_DATA_LIMIT";
  ERROR
    Assert ERRNO = ERR_DATA_LIMIT;
    Assert depth = 1 \Msg:="one call of 1,000,000 values fits beside the module data";
  ENDPROC

  FUNC num copies(num a{*}, num n)
    ! Each call holds a copy of the array (an IN parameter is passed by value).
    depth := n;
    RETURN copies(a, n + 1);
  ENDFUNC

  PROC test_recursion_with_arrays_passed_by_value()
    VAR num x;
    depth := 0;
    x := copies(big, 1);
    Assert FALSE \Msg:="the recursion must end with ERR_DATA_LIMIT";
  ERROR
    Assert ERRNO = ERR_DATA_LIMIT;
    ! 400,000 of module data, then 400,001 per call: 4 calls would hold 2,000,004.
    Assert depth = 3;
  ENDPROC

  FUNC num simple_copies(num a{*}, num n)
    RETURN simple_copies(a, n + 1);
  ENDFUNC

  PROC test_simple_function_with_array_argument()
    VAR num x;
    x := simple_copies(big, 1) + 1;
    Assert FALSE \Msg:="the recursion must end with ERR_DATA_LIMIT";
  ERROR
    Assert ERRNO = ERR_DATA_LIMIT;
  ENDPROC

  PROC test_the_limit_is_released_after_the_calls()
    ! A call's data is given back when it returns: two calls of 1,000,000 values one
    ! after the other fit.
    depth := 0;
    deep_once;
    deep_once;
    Assert depth = 2;
  ENDPROC

  PROC deep_once()
    VAR num a{1000, 1000};
    depth := depth + 1;
  ENDPROC
ENDMODULE
