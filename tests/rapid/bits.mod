MODULE bits
  ! Bit operations, number bases and digit strings. The values are those of the examples of
  ! ABB's "RAPID Instructions, Functions and Data types" (named at each test) where the
  ! manual has one; the others follow from the bit definitions.

  CONST num parity_bit := 8;

  ! BitSet example: bit 8 of 2 set gives 130.
  PROC test_bitset_byte()
    VAR byte data1 := 2;
    BitSet data1, parity_bit;
    Assert data1 = 130;
    BitSet data1, parity_bit;
    Assert data1 = 130 \Msg:="setting a set bit changes nothing";
    BitSet data1, 1;
    Assert data1 = 131;
  ENDPROC

  ! BitClear example: bit 8 of 130 cleared gives 2.
  PROC test_bitclear_byte()
    VAR byte data1 := 130;
    BitClear data1, parity_bit;
    Assert data1 = 2;
    BitClear data1, 1;
    Assert data1 = 2 \Msg:="clearing a clear bit changes nothing";
  ENDPROC

  ! BitSet and BitClear take a dnum variable too (bits 1 to 52).
  PROC test_bitset_bitclear_dnum()
    VAR dnum mydnum := 0;
    BitSet mydnum, 52;
    Assert mydnum = 2251799813685248;
    BitSet mydnum, 1;
    Assert mydnum = 2251799813685249;
    BitClear mydnum, 52;
    Assert mydnum = 1;
  ENDPROC

  PROC test_bitset_range()
    VAR byte data1 := 0;
    BitSet data1, 9;
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_ARGVALERR;
    Assert data1 = 0;
  ENDPROC

  PROC test_bitset_not_a_byte()
    VAR byte data1 := 256;
    BitSet data1, 1;
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_ARGVALERR;
  ENDPROC

  ! BitCheck example: IF BitCheck(data1, parity_bit) with data1 = 130.
  PROC test_bitcheck()
    VAR byte data1 := 130;
    Assert BitCheck(data1, parity_bit);
    Assert NOT BitCheck(data1, 1);
    Assert BitCheck(data1, 2);
  ENDPROC

  PROC test_bitcheck_dnum()
    VAR dnum mydnum := 4503599627370495;
    Assert BitCheckDnum(mydnum, 52);
    Assert BitCheckDnum(mydnum, 1);
    Assert NOT BitCheckDnum(2, 1);
  ENDPROC

  PROC test_bitcheck_range()
    VAR bool b;
    b := BitCheck(1, 0);
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_ARGVALERR;
  ENDPROC

  ! BitAnd example: 38 AND 34 = 34.
  PROC test_bitand()
    VAR byte data1 := 38;
    VAR byte data2 := 34;
    VAR byte data3;
    data3 := BitAnd(data1, data2);
    Assert data3 = 34;
    Assert BitAnd(255, 0) = 0;
  ENDPROC

  ! BitOr example: 39 OR 162 = 167.
  PROC test_bitor()
    Assert BitOr(39, 162) = 167;
    Assert BitOr(0, 0) = 0;
  ENDPROC

  ! BitXOr example: 39 XOR 162 = 133.
  PROC test_bitxor()
    Assert BitXOr(39, 162) = 133;
    Assert BitXOr(255, 255) = 0;
  ENDPROC

  ! BitNeg example: NOT 38 = 217.
  PROC test_bitneg()
    Assert BitNeg(38) = 217;
    Assert BitNeg(0) = 255;
  ENDPROC

  ! BitLSh example: 38 shifted left 3 steps = 48 (the bits beyond 8 are lost).
  PROC test_bitlsh()
    Assert BitLSh(38, 3) = 48;
    Assert BitLSh(1, 7) = 128;
    Assert BitLSh(128, 1) = 0;
  ENDPROC

  ! BitRSh example: 38 shifted right 3 steps = 4.
  PROC test_bitrsh()
    Assert BitRSh(38, 3) = 4;
    Assert BitRSh(1, 1) = 0;
  ENDPROC

  PROC test_shift_range()
    VAR byte b;
    b := BitLSh(1, 9);
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_ARGVALERR;
  ENDPROC

  PROC test_byte_operand_range()
    VAR byte b;
    b := BitAnd(300, 1);
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_ARGVALERR;
  ENDPROC

  ! The Dnum forms work on 52 bits (0 to 4503599627370495).
  PROC test_bitanddnum()
    Assert BitAndDnum(5, 3) = 1;
    Assert BitAndDnum(4503599627370495, 2251799813685248) = 2251799813685248;
  ENDPROC

  PROC test_bitordnum()
    Assert BitOrDnum(5, 3) = 7;
    Assert BitOrDnum(2251799813685248, 1) = 2251799813685249;
  ENDPROC

  PROC test_bitxordnum()
    Assert BitXOrDnum(5, 3) = 6;
  ENDPROC

  PROC test_bitnegdnum()
    Assert BitNegDnum(0) = 4503599627370495;
    Assert BitNegDnum(4503599627370495) = 0;
  ENDPROC

  PROC test_bitlshdnum()
    Assert BitLShDnum(5, 2) = 20;
    Assert BitLShDnum(1, 51) = 2251799813685248;
    Assert BitLShDnum(2251799813685248, 1) = 0 \Msg:="bit 53 is lost";
  ENDPROC

  PROC test_bitrshdnum()
    Assert BitRShDnum(20, 2) = 5;
    Assert BitRShDnum(4503599627370495, 52) = 0;
  ENDPROC

  PROC test_dnum_operand_range()
    VAR dnum d;
    d := BitAndDnum(-1, 1);
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_ARGVALERR;
  ENDPROC

  ! DecToHex and HexToDec examples: "99999999" <-> "5F5E0FF".
  PROC test_dectohex()
    Assert DecToHex("99999999") = "5F5E0FF";
    Assert DecToHex("0") = "0";
    Assert DecToHex("9223372036854775807") = "7FFFFFFFFFFFFFFF";
  ENDPROC

  PROC test_hextodec()
    Assert HexToDec("5F5E0FF") = "99999999";
    Assert HexToDec("ff") = "255";
    Assert HexToDec("7FFFFFFFFFFFFFFF") = "9223372036854775807";
  ENDPROC

  PROC test_hex_errors()
    VAR string s;
    s := HexToDec("XYZ");
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_ARGVALERR;
  ENDPROC

  ! StrDigCalc example: "10" OpAdd "20" = "30".
  PROC test_strdigcalc()
    VAR stringdig str1 := "10";
    VAR stringdig str2 := "20";
    VAR stringdig res;
    res := StrDigCalc(str1, OpAdd, str2);
    Assert res = "30";
    Assert StrDigCalc("4294967295", OpSub, "1") = "4294967294";
    Assert StrDigCalc("65535", OpMult, "65537") = "4294967295";
    Assert StrDigCalc("7", OpDiv, "2") = "3";
    Assert StrDigCalc("7", OpMod, "2") = "1";
  ENDPROC

  PROC test_strdigcalc_negative()
    VAR stringdig res;
    res := StrDigCalc("1", OpSub, "2");
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_CALC_NEG;
  ENDPROC

  PROC test_strdigcalc_overflow()
    VAR stringdig res;
    res := StrDigCalc("4294967295", OpAdd, "1");
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_CALC_OVERFLOW;
  ENDPROC

  PROC test_strdigcalc_divzero()
    VAR stringdig res;
    res := StrDigCalc("1", OpDiv, "0");
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_CALC_DIVZERO;
  ENDPROC

  PROC test_stringdig_operands()
    VAR num errs := 0;
    VAR stringdig res;
    res := StrDigCalc("1x", OpAdd, "1");
    res := StrDigCalc("4294967296", OpAdd, "1");
    Assert errs = 2;
  ERROR
    IF ERRNO = ERR_INT_NOTVAL AND errs = 0 THEN
      errs := 1;
      TRYNEXT;
    ELSEIF ERRNO = ERR_INT_MAXVAL AND errs = 1 THEN
      errs := 2;
      TRYNEXT;
    ENDIF
    Assert FALSE \Msg:="wrong error";
  ENDPROC

  ! StrDigCmp example: "1234" LT "1256".
  PROC test_strdigcmp()
    VAR stringdig digits1 := "1234";
    VAR stringdig digits2 := "1256";
    Assert StrDigCmp(digits1, LT, digits2);
    Assert StrDigCmp(digits1, LTEQ, digits2);
    Assert NOT StrDigCmp(digits1, EQ, digits2);
    Assert StrDigCmp(digits1, NOTEQ, digits2);
    Assert NOT StrDigCmp(digits1, GTEQ, digits2);
    Assert NOT StrDigCmp(digits1, GT, digits2);
    Assert StrDigCmp("4294967295", GT, "0");
    Assert StrDigCmp("007", EQ, "7");
  ENDPROC

  PROC test_strdigcmp_error()
    VAR bool b;
    b := StrDigCmp("-1", LT, "1");
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_INT_NOTVAL;
  ENDPROC

  ! StrOrder examples: "FIRST" before "SECOND"; a string before its extension.
  PROC test_strorder()
    Assert StrOrder("FIRST", "SECOND", STR_UPPER);
    Assert StrOrder("FIRST", "FIRSTB", STR_UPPER);
    Assert NOT StrOrder("FIRSTB", "FIRST", STR_UPPER);
    Assert StrOrder("SAME", "SAME", STR_UPPER);
    Assert StrOrder("B", "A", "BA") \Msg:="the order given decides";
    Assert StrOrder("Z", "a", STR_UPPER) \Msg:="characters outside the order come last";
  ENDPROC

  ! TestAndSet example: a persistent bool as a semaphore around TP output.
  PERS bool tproutine_inuse := FALSE;

  PROC test_testandset()
    WaitUntil TestAndSet(tproutine_inuse);
    Assert tproutine_inuse;
    Assert NOT TestAndSet(tproutine_inuse) \Msg:="taken: the second test fails";
    tproutine_inuse := FALSE;
    Assert TestAndSet(tproutine_inuse);
    tproutine_inuse := FALSE;
  ENDPROC
ENDMODULE
