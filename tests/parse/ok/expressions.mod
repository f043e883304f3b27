MODULE Expressions
  PROC precedence()
    ! Multiplicative binds tighter than additive, additive than relational
    r := a + b * c - d / e;
    r := a DIV b MOD c * d;
    r := a - b - c;
    ok := a + 1 < b * 2;
    ! AND binds tighter than OR and XOR; NOT takes the whole AND chain after it
    ok := a OR b AND c XOR d;
    ok := NOT a AND b;
    ok := NOT a = b;
    ok := NOT a AND b OR c;
    ok := (NOT a) AND (NOT b);
    IF NOT Check(a) AND Check(b) THEN
    ENDIF
    ! A sign starts a simple expression, also after a relational operator
    IF x = -1 THEN
    ENDIF
    r := -a + b;
    r := -a * b;
    r := a * -b;
    r := a / -b * c;
    r := a - -b;
    r := +a;
    spot := [-1, +0.5, -x];
    Move -x;
    ! Parentheses are kept
    r := (a + b) * c;
  ENDPROC

  PROC primaries()
    ! Literals
    n := 1 + 1.5 + 1. + .5 + 9E+09 + 9E9 + 1e-3 + 2.5E2 + 0xFF + 0b101 + 0o17;
    s := "plain" + "" + "quote "" inside" + "back\\slash" + "\41\42";
    s := "a" + "b";
    ok := TRUE OR false;
    ! Names, components, elements, function calls
    n := spot.trans.x;
    n := grid{1, 2} + cube{1, 2, 3};
    n := shelves{2}.corner.y;
    n := Dim(grid, 1);
    n := Offs(spot, 0, 0, 10).trans.z;
    n := Now();
    pose1 := CRobT(\Tool:=gripTool \WObj:=wobj0);
    s := Format("x"\Width:=4, \Fill:="0");
    n := Pick(\First \Second);
    ! Aggregates
    spot := [[1, 2, 3], [1, 0, 0, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
    spot := [[x, y, z + 1], rot, conf, ext];
    mixed := [TRUE, "text", -2.5, [1, [2, 3]]];
  ENDPROC
ENDMODULE
