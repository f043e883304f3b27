MODULE builtins
  ! One line per built-in function, so their results are pinned.
  VAR clock clk;
  VAR num arr{2, 3};
  VAR errnum ERR_A := -1;
  VAR errnum ERR_B := -1;

  PROC main()
    VAR robtarget t := [[100, 200, 300], [1, 0, 0, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
    VAR pose a := [[10, 0, 0], [0.70711, 0, 0, 0.70711]];
    VAR num n := 1;
    VAR dnum d := 2;
    VAR bool ok;
    TPWrite "Abs " \Num:=Abs(-2.5);
    TPWrite "AbsDnum " \Dnum:=AbsDnum(-d);
    TPWrite "Round " \Num:=Round(3.14159 \Dec:=3);
    TPWrite "Trunc " \Num:=Trunc(-3.99);
    TPWrite "RoundDnum " \Dnum:=RoundDnum(2.345678901234 \Dec:=10);
    TPWrite "Sqrt " \Num:=Sqrt(2);
    TPWrite "Pow " \Num:=Pow(1.5, 3);
    TPWrite "Exp " \Num:=Exp(1);
    TPWrite "Sin Cos Tan " + ValToStr(Sin(30)) + " " + ValToStr(Cos(60)) + " " + ValToStr(Tan(45));
    TPWrite "ASin ACos ATan ATan2 " + ValToStr(ASin(0.5)) + " " + ValToStr(ACos(0.5)) + " " + ValToStr(ATan(1)) + " " + ValToStr(ATan2(-1, -1));
    TPWrite "Dim " \Num:=Dim(arr, 2);
    TPWrite "NumToStr " + NumToStr(1234.5678, 2) + " " + NumToStr(0.000123, 2 \Exp);
    TPWrite "DnumToStr " + DnumToStr(d / 3, 12);
    TPWrite "StrLen " \Num:=StrLen("robot");
    TPWrite "StrPart " + StrPart("controller", 4, 4);
    TPWrite "StrFind " \Num:=StrFind("a-b", 1, "-");
    TPWrite "StrMatch " \Num:=StrMatch("abcabc", 2, "abc");
    TPWrite "StrMemb " \Bool:=StrMemb("x9", 2, STR_DIGIT);
    TPWrite "StrMap " + StrMap("Hello", STR_LOWER, STR_UPPER);
    ok := StrToVal("[1,2,3]", a.trans);
    TPWrite "StrToVal " \Pos:=a.trans;
    TPWrite "ValToStr " + ValToStr(t.trans) + ValToStr(TRUE) + ValToStr("q");
    Incr n;
    Add n, 10;
    Decr n;
    TPWrite "Incr Add Decr " \Num:=n;
    Clear n;
    TPWrite "Clear " \Num:=n;
    ClkReset clk;
    ClkStart clk;
    WaitTime 1.25;
    ClkStop clk;
    TPWrite "ClkRead " \Num:=ClkRead(clk);
    t := Offs(t, 1, 2, 3);
    TPWrite "Offs " \Pos:=t.trans;
    t := RelTool(t, 0, 0, 10 \Rz:=90);
    TPWrite "RelTool " \Pos:=t.trans;
    TPWrite "RelTool rot " \Orient:=t.rot;
    TPWrite "OrientZYX " \Orient:=OrientZYX(90, 0, 0);
    TPWrite "EulerZYX " \Num:=EulerZYX(\Z, OrientZYX(30, 20, 10));
    TPWrite "PoseMult " + ValToStr(PoseMult(a, a));
    TPWrite "PoseInv " + ValToStr(PoseInv(a));
    TPWrite "PoseVect " \Pos:=PoseVect(a, [1, 0, 0]);
    TPWrite "NOrient " \Orient:=NOrient([0, 0, 0, 2]);
    TPWrite "Distance " \Num:=Distance([0, 0, 0], [1, 1, 1]);
    BookErrNo ERR_A;
    BookErrNo ERR_B;
    TPWrite "BookErrNo " \Num:=ERR_B - ERR_A;
    TPWrite "Present: see routines.mod; Dim of a 2x3 array: " \Num:=Dim(arr, 1) * Dim(arr, 2);
  ENDPROC
ENDMODULE
