MODULE sema_errors
  ! Problems found before anything runs: exit code 2, every problem reported.
  CONST num LIMIT := 10;
  VAR num count;

  FUNC num twice(num x)
    x := x * 2;
    RETURN x;
  ENDFUNC

  FUNC num nothing()
    count := 1;
  ENDFUNC

  PROC main()
    VAR string s;
    LIMIT := 11;
    s := 3;
    count := undeclared + 1;
    MoveJ p10, v100, fine, tool0 \Speed:=5;
    Frobnicate 1, 2;
    count := twice();
    count := Abs(1, 2);
    TPWrite "x" \Num:=1 \Bool:=TRUE;
    RETURN 5;
  ENDPROC
ENDMODULE
