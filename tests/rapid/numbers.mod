MODULE numbers
  ! num is single precision; dnum is double; DIV and MOD truncate toward zero.

  PROC test_literal_rounding()
    VAR num x;
    x := 9E9;
    Assert x = 9E9 \Msg:="9E9 survives a round trip";
    x := 9E+09;
    Assert x = 9E9;
    Assert 16777217 = 16777216 \Msg:="num rounds 16777217 to single precision";
    x := 8388607;
    Assert x + 1 = 8388608;
    Assert .5 + .25 = 0.75;
  ENDPROC

  PROC test_single_precision()
    VAR num a := 0.1;
    VAR dnum d := 0.1;
    Assert a * 3 <> 0.3 OR a * 3 = 0.3;
    Assert d + 0.2 = 0.3 OR TRUE;
    Assert NumToDnum(a) <> 0.1 \Msg:="0.1 as num is not 0.1 as dnum";
    d := 4503599627370496;
    Assert d + 1 > d \Msg:="dnum keeps integers beyond 2^24";
  ENDPROC

  PROC test_div_mod()
    Assert 14 DIV 4 = 3;
    Assert 14 MOD 4 = 2;
    Assert -14 DIV 4 = -3 \Msg:="DIV truncates toward zero";
    Assert -14 MOD 4 = -2 \Msg:="MOD takes the sign of the dividend";
    Assert 14 MOD -4 = 2;
    Assert 7 / 2 = 3.5;
  ENDPROC

  PROC test_div_by_zero_is_caught()
    VAR num z := 0;
    VAR num r := 1;
    r := 10 / z;
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_DIVZERO;
    Assert r = 1;
    RETURN;
  ENDPROC

  PROC test_mod_needs_integers()
    VAR num r;
    r := 7.5 MOD 2;
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_NOTINTVAL;
  ENDPROC

  PROC test_math_functions()
    Assert Abs(-3) = 3;
    Assert Round(2.5) = 3;
    Assert Round(-2.5) = -3;
    Assert Round(1.23456 \Dec:=2) = 1.23;
    Assert Trunc(1.789 \Dec:=1) = 1.7;
    Assert Sqrt(16) = 4;
    Assert Pow(2, 10) = 1024;
    Assert Sin(90) = 1;
    Assert Cos(180) = -1;
    Assert Abs(ATan2(1, 1) - 45) < 0.0001;
    Assert Abs(Exp(0) - 1) < 0.000001;
  ENDPROC

  PROC test_sqrt_of_negative()
    VAR num r;
    r := Sqrt(-1);
  ERROR
    Assert ERRNO = ERR_ARGVALERR;
  ENDPROC

  PROC test_dnum_mixing()
    VAR dnum big := 123456789012;
    VAR num small := 2;
    big := big * small;
    Assert big = 246913578024;
    Assert DnumToNum(NumToDnum(3)) = 3;
  ENDPROC

  PROC test_incr_decr_add_clear()
    VAR num n := 1;
    VAR dnum d := 1;
    Incr n;
    Assert n = 2;
    Decr n;
    Decr n;
    Assert n = 0;
    Add n, 5;
    Assert n = 5;
    Add d, -3;
    Assert d = -2;
    Clear n;
    Assert n = 0;
  ENDPROC
ENDMODULE
