MODULE control
  VAR num calls := 0;

  FUNC bool side(bool b)
    calls := calls + 1;
    RETURN b;
  ENDFUNC

  PROC test_if_elseif()
    VAR num x := 2;
    VAR string r;
    IF x = 1 THEN
      r := "one";
    ELSEIF x = 2 THEN
      r := "two";
    ELSE
      r := "many";
    ENDIF
    Assert r = "two";
    IF x = 2 r := "compact";
    Assert r = "compact";
  ENDPROC

  PROC test_not_binds_loosely()
    VAR num a := 1;
    VAR num b := 2;
    Assert NOT a = b \Msg:="NOT a = b is NOT (a = b)";
    Assert NOT (TRUE AND FALSE);
    Assert NOT TRUE AND FALSE \Msg:="NOT applies to the conjunction: NOT (TRUE AND FALSE)";
    Assert TRUE XOR FALSE;
    Assert a = -1 + 2 \Msg:="a sign after a relational operator";
  ENDPROC

  PROC test_no_short_circuit()
    calls := 0;
    IF side(FALSE) AND side(TRUE) THEN
    ENDIF
    Assert calls = 2 \Msg:="AND evaluates both operands";
    calls := 0;
    IF side(TRUE) OR side(TRUE) THEN
    ENDIF
    Assert calls = 2 \Msg:="OR evaluates both operands";
  ENDPROC

  PROC test_while()
    VAR num i := 0;
    WHILE i < 10 DO
      i := i + 1;
    ENDWHILE
    Assert i = 10;
  ENDPROC

  PROC test_for()
    VAR num s := 0;
    FOR i FROM 1 TO 5 DO
      s := s + i;
    ENDFOR
    Assert s = 15;
    s := 0;
    FOR i FROM 10 TO 1 STEP -3 DO
      s := s + i;
    ENDFOR
    Assert s = 10 + 7 + 4 + 1;
    s := 0;
    FOR i FROM 3 TO 1 DO
      s := s * 10 + i;
    ENDFOR
    Assert s = 321 \Msg:="the default step is -1 when start > end";
    s := 0;
    FOR i FROM 0 TO 1 STEP 0.25 DO
      s := s + 1;
    ENDFOR
    Assert s = 5;
  ENDPROC

  PROC test_test_case()
    VAR string r;
    FOR k FROM 1 TO 4 DO
      TEST k
      CASE 1, 2:
        r := r + "a";
      CASE 3:
        r := r + "b";
      DEFAULT:
        r := r + "c";
      ENDTEST
    ENDFOR
    Assert r = "aabc";
  ENDPROC

  PROC test_test_case_table()
    ! Integer constant cases (a jump table): a CASE listed twice goes to the first,
    ! a fraction or a value outside the range to the DEFAULT, negative values too.
    VAR string r;
    VAR num xs{8} := [-2, 0, 1, 2, 2.5, 5, 7, 1000];
    FOR k FROM 1 TO 8 DO
      TEST xs{k}
      CASE -2:
        r := r + "m";
      CASE 0, 2:
        r := r + "z";
      CASE 1, 2, 5:
        r := r + "o";
      CASE 7:
        r := r + "s";
      DEFAULT:
        r := r + "-";
      ENDTEST
    ENDFOR
    Assert r = "mzoz-os-";
  ENDPROC

  PROC test_test_case_strings()
    ! String cases against a local, a global-like array element and a computed string.
    CONST string words{4} := ["red", "Red", "blue", ""];
    VAR string w;
    VAR string r;
    FOR k FROM 1 TO 4 DO
      w := words{k};
      TEST w
      CASE "red", "blue":
        r := r + "c";
      CASE "":
        r := r + "e";
      DEFAULT:
        r := r + "-";
      ENDTEST
      TEST words{k}
      CASE "Red":
        r := r + "R";
      DEFAULT:
        r := r + ".";
      ENDTEST
    ENDFOR
    Assert r = "c.-Rc.e.";
  ENDPROC

  PROC test_goto()
    VAR num i := 0;
    again:
    i := i + 1;
    IF i < 3 GOTO again;
    Assert i = 3;
    FOR k FROM 1 TO 10 DO
      IF k = 4 GOTO out;
    ENDFOR
    Assert FALSE;
    out:
    Assert i = 3;
  ENDPROC

  PROC test_exit_ends_the_program()
    EXIT;
    Assert FALSE \Msg:="EXIT ends execution";
  ENDPROC
ENDMODULE
