MODULE data_recursion
  ! Recursion with large routine data stops at the task's data limit with ERR_DATA_LIMIT at
  ! the call (here unhandled), long before the memory runs out.
  PROC deep(num n)
    VAR num a{1000, 1000};
    a{n, n} := n;
    deep n + 1;
  ENDPROC
  PROC main()
    deep 1;
  ENDPROC
ENDMODULE
