MODULE loops
  ! WHILE loops: Collatz chain lengths of 1 to 3000 (every value stays below 2^24, exact in
  ! num) and Euclid's greatest common divisor over a grid, N rounds. Same algorithm:
  ! loops.py, loops.lua.
  CONST num N := 48;

  FUNC num collatz(num n)
    VAR num x;
    VAR num steps := 0;
    x := n;
    WHILE x <> 1 DO
      IF x MOD 2 = 0 THEN
        x := x DIV 2;
      ELSE
        x := 3 * x + 1;
      ENDIF
      steps := steps + 1;
    ENDWHILE
    RETURN steps;
  ENDFUNC

  FUNC num gcd(num a, num b)
    VAR num x;
    VAR num y;
    VAR num t;
    x := a;
    y := b;
    WHILE y <> 0 DO
      t := x MOD y;
      x := y;
      y := t;
    ENDWHILE
    RETURN x;
  ENDFUNC

  PROC main()
    VAR num total := 0;
    VAR num g := 0;
    VAR num round := 1;
    VAR num k;
    VAR num i;
    VAR num j;
    WHILE round <= N DO
      k := 1;
      WHILE k <= 3000 DO
        total := (total + collatz(k)) MOD 1000000;
        k := k + 1;
      ENDWHILE
      i := 1;
      WHILE i <= 150 DO
        j := 1;
        WHILE j <= 150 DO
          g := (g + gcd(i * 7 + round, j * 3)) MOD 1000000;
          j := j + 1;
        ENDWHILE
        i := i + 1;
      ENDWHILE
      round := round + 1;
    ENDWHILE
    TPWrite "result: " + NumToStr(total, 0) + " " + NumToStr(g, 0);
  ENDPROC
ENDMODULE
