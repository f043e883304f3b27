MODULE data_limits
  ! Data sizes known before the run are checked against rapidvc's limits (README, "Data
  ! limits"): at most 1,000,000 values in one declaration, 2,000,000 in the task.
  VAR num a{100000000};
  VAR num b{100000, 100000, 100000};
  VAR num c{100000, 100000};
  VAR robtarget d{100000};
  ! Each fits, both together do not.
  VAR num e{1000, 1000};
  VAR num f{1000, 1000};
  PROC main()
    TPWrite "never runs";
  ENDPROC
ENDMODULE
