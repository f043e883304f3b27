MODULE data_limits_routine
  ! A routine's data on top of the module data must fit in the task's 2,000,000 values.
  VAR num e{1000, 1000};
  VAR string names{500000};
  PROC main()
    VAR bool flags{1000, 500};
    VAR num n;
    TPWrite "never runs";
  ENDPROC
ENDMODULE
