MODULE compiled_values
  ! Results and recovered errors of compiled num code: simple functions (inlined, framed),
  ! constant and variable DIV/MOD, array elements, comparisons, loops.
  VAR num data{5};
  VAR num g := 3;
  VAR num big := 2147483520;
  FUNC num f(num x)
    RETURN x * 2 + 1;
  ENDFUNC
  FUNC num inv(num x)
    RETURN 1 / x;
  ENDFUNC
  FUNC num sq(num x)
    RETURN x * x;
  ENDFUNC
  FUNC num el(num i)
    RETURN data{i};
  ENDFUNC
  FUNC num two(num a, num b)
    RETURN a MOD b + g;
  ENDFUNC
  FUNC num first(num a, num b)
    RETURN a;
  ENDFUNC
  FUNC num modk(num a)
    RETURN a MOD 7 + a DIV -3;
  ENDFUNC
  FUNC num nested(num a)
    RETURN f(a) + sq(a);
  ENDFUNC
  PROC main()
    VAR num k;
    VAR num r;
    VAR num z := 0;
    VAR num h := 0.5;
    FOR i FROM 1 TO 5 DO
      data{i} := i * 10;
    ENDFOR
    r := f(2) + inv(4) + sq(3) + el(2) + two(7, 4) + modk(-23) + nested(3);
    TPWrite "r " \Num:=r;
    r := f(data{3}) + first(data{1}, 5) + el(k + 1);
    TPWrite "r2 " \Num:=r;
    r := inv(0);
    TPWrite "after inv " \Num:=r;
    r := el(7);
    r := el(h);
    r := first(1, data{9});
    r := first(data{0}, 1);
    r := 7 MOD z;
    r := 7 DIV z;
    r := h MOD 2;
    r := 7 MOD h;
    r := -7 MOD 2 + (-7 DIV 2) * 10 + (7 DIV -2) * 100 + (-7 MOD -2) * 1000;
    TPWrite "signs " \Num:=r;
    r := big MOD 7;
    TPWrite "big mod " \Num:=r;
    r := big DIV 7;
    TPWrite "big div " \Num:=r;
    r := (big * 4) MOD 7;
    TPWrite "bigger mod " \Num:=r;
    r := -big MOD 1000;
    TPWrite "neg big mod " \Num:=r;
    r := 3E38 * 10;
    r := sq(3E20);
    r := 3E38 + 3E38;
    k := 0;
    WHILE k < 10 DO
      k := k + 3;
    ENDWHILE
    TPWrite "k " \Num:=k;
    FOR j FROM 10 TO 1 STEP -3 DO
      data{1} := data{1} + j;
    ENDFOR
    TPWrite "d1 " \Num:=data{1};
    FOR j FROM 0 TO 1 STEP 0.25 DO
      r := r + j;
    ENDFOR
    TPWrite "r3 " \Num:=r;
    FOR j FROM 1 TO 2 STEP z DO
      r := 0;
    ENDFOR
    IF r > 2 AND (NOT (r = 3)) OR r <> r THEN
      TPWrite "if1";
    ELSEIF r >= 0 THEN
      TPWrite "if2";
    ELSE
      TPWrite "if3";
    ENDIF
    TEST data{2}
    CASE 1, 20:
      TPWrite "case 20";
    DEFAULT:
      TPWrite "default";
    ENDTEST
    data{6} := 1;
    data{h} := 1;
    g := g / z;
  ERROR
    TPWrite "ERRNO " \Num:=ERRNO;
    TRYNEXT;
  ENDPROC
ENDMODULE
