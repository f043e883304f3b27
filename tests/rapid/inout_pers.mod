MODULE inout_pers_tests
  ! A part of a persistent passed to an INOUT parameter (a real controller backup does
  ! `Incr counts{i};` on a TASK PERS array): the update reaches the persistent.
  PERS num counts{3} := [1, 2, 3];
  PERS pos where := [1, 2, 3];

  PROC bump(INOUT num n)
    n := n + 10;
  ENDPROC

  PROC test_inout_reaches_a_persistent_element()
    counts := [1, 2, 3];
    Incr counts{2};
    Assert counts{2} = 3;
    bump counts{3};
    Assert counts{3} = 13;
  ENDPROC

  PROC test_inout_reaches_a_persistent_component()
    where := [1, 2, 3];
    bump where.y;
    Assert where.y = 12;
    Assert where.x = 1;
  ENDPROC
ENDMODULE
