MODULE sema_errors2
  ! More problems found before running: parameter modes, types, records, arrays, handlers.
  CONST num K := 3;
  VAR num arr{2, 2};
  VAR clock c1;
  VAR clock c2;
  PERS pos ppos := [0, 0, 0];

  PROC change(VAR num n)
    n := n + 1;
  ENDPROC

  PROC keep(PERS pos p)
  ENDPROC

  PROC main()
    VAR pos p;
    VAR robtarget t;
    change K;
    change 1 + 2;
    keep p;
    keep ppos.x;
    keep tool0.tframe.trans;
    p.w := 1;
    arr{1} := 2;
    p := [1, 2];
    t.trans := "far";
    c1 := c2;
    tool0.robhold := FALSE;
    SetDO no_such_signal, 1;
    IF 1 THEN
    ENDIF
    RETRY;
    GOTO nowhere;
    TPWrite "x" \Colour:=1;
    FOR i FROM 1 TO 3 DO
      i := 2;
    ENDFOR
    ERRNO := 5;
    TPWrite ValToStr(arr);
  ENDPROC
ENDMODULE
