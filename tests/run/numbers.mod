MODULE numbers
  ! How numbers print (TPWrite \Num, ValToStr, NumToStr): rapidvc's pinned rules.
  PROC show(num x)
    TPWrite ValToStr(x) + "  " + NumToStr(x, 2) + "  " + NumToStr(x, 3 \Exp);
  ENDPROC

  PROC main()
    show 0;
    show 1;
    show -1;
    show 0.5;
    show 2.9999999;
    show 1234567;
    show 8388608;
    show 16777216;
    show 123456.7;
    show 0.000494947;
    show 0.0000960894;
    show 9E9;
    show 1 / 3;
    TPWrite "dnum 0.1+0.2: " \Dnum:=NumToDnum(0) + 0.1 + 0.2;
    TPWrite "9E9 = 9E+09: " \Bool:=9E9 = 9E+09;
    TPWrite "16777217 as num: " + ValToStr(16777217);
    TPWrite "14 DIV -4 = " \Num:=14 DIV -4;
    TPWrite "-14 MOD 4 = " \Num:=-14 MOD 4;
  ENDPROC
ENDMODULE
