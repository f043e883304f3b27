MODULE recursion
  ! Recursion: naive Fibonacci, and a recursive quicksort of pseudo-random numbers in a
  ! module array (a linear congruential generator whose products stay exact in num).
  ! Same algorithm: recursion.py, recursion.lua.
  CONST num N := 240;
  VAR num data{2000};

  FUNC num fib(num n)
    IF n < 2 RETURN n;
    RETURN fib(n - 1) + fib(n - 2);
  ENDFUNC

  PROC qsort(num lo, num hi)
    VAR num i;
    VAR num j;
    VAR num pivot;
    VAR num t;
    IF lo >= hi RETURN;
    pivot := data{(lo + hi) DIV 2};
    i := lo;
    j := hi;
    WHILE i <= j DO
      WHILE data{i} < pivot DO
        i := i + 1;
      ENDWHILE
      WHILE data{j} > pivot DO
        j := j - 1;
      ENDWHILE
      IF i <= j THEN
        t := data{i};
        data{i} := data{j};
        data{j} := t;
        i := i + 1;
        j := j - 1;
      ENDIF
    ENDWHILE
    qsort lo, j;
    qsort i, hi;
  ENDPROC

  PROC main()
    VAR num f := 0;
    VAR num seed := 1;
    VAR num check := 0;
    FOR r FROM 1 TO N DO
      f := f + fib(20 + r MOD 3);
      FOR i FROM 1 TO 2000 DO
        seed := (seed * 251 + 7 + r) MOD 65521;
        data{i} := seed;
      ENDFOR
      qsort 1, 2000;
      FOR i FROM 1 TO 2000 STEP 50 DO
        check := (check + data{i} * (i MOD 7)) MOD 1000000;
      ENDFOR
    ENDFOR
    TPWrite "result: " + NumToStr(f, 0) + " " + NumToStr(check, 0);
  ENDPROC
ENDMODULE
