MODULE strings
  PROC test_concat_and_len()
    VAR string s := "abc";
    s := s + "def";
    Assert s = "abcdef";
    Assert StrLen(s) = 6;
    Assert StrLen("") = 0;
    Assert "a""b" = "a" + """" + "b" \Msg:="doubled quotes";
    Assert StrLen("\41\\") = 2 \Msg:="character codes and backslashes";
  ENDPROC

  PROC test_80_characters()
    VAR string s := "0123456789012345678901234567890123456789";
    s := s + s;
    Assert StrLen(s) = 80;
    s := s + "x";
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_STRTOOLNG;
    Assert StrLen(s) = 80;
  ENDPROC

  PROC test_search_functions()
    Assert StrPart("robotics", 3, 3) = "bot";
    Assert StrFind("a,b;c", 1, ",;") = 2;
    Assert StrFind("abc", 1, "xyz") = 4 \Msg:="not found: length + 1";
    Assert StrFind("aab", 1, "a" \NotInSet) = 3;
    Assert StrMatch("hello world", 1, "wor") = 7;
    Assert StrMemb("a1", 2, STR_DIGIT);
    Assert StrMap("abc", "abc", "xyz") = "xyz";
  ENDPROC

  PROC test_strpart_out_of_bounds()
    VAR string s;
    s := StrPart("abc", 2, 5);
  ERROR
    Assert ERRNO = ERR_OUTOFBND;
  ENDPROC

  PROC test_number_text()
    Assert NumToStr(0.38521, 3) = "0.385";
    Assert NumToStr(2, 2) = "2.00";
    Assert NumToStr(1234.5, 0) = "1235";
    Assert ValToStr(23) = "23";
    Assert ValToStr(1.141367) = "1.14137";
    Assert ValToStr(9E9) = "9E+09";
    Assert ValToStr(TRUE) = "TRUE";
  ENDPROC

  PROC test_val_to_str_records()
    VAR pos p := [1817.3, 905.17, 879.11];
    VAR orient o := [0.96593, 0, 0.25882, 0];
    Assert ValToStr(p) = "[1817.3,905.17,879.11]";
    Assert ValToStr(o) = "[0.96593,0,0.25882,0]";
    Assert ValToStr("q""x") = """q""""x""" \Msg:="strings come back quoted";
  ENDPROC

  PROC test_str_to_val()
    VAR num n;
    VAR bool b;
    VAR pos p;
    VAR string s;
    Assert StrToVal("3.25", n);
    Assert n = 3.25;
    Assert StrToVal("true", b);
    Assert b;
    Assert StrToVal("[1,2,3]", p);
    Assert p.y = 2;
    Assert NOT StrToVal("abc", n);
    Assert n = 3.25 \Msg:="a failed conversion leaves the value";
    Assert StrToVal("""hi""", s);
    Assert s = "hi";
  ENDPROC

  PROC test_byte_text()
    Assert ByteToStr(255 \Hex) = "FF";
    Assert StrToByte("1010" \Bin) = 10;
  ENDPROC
  ! A string variable is written in place when it alone holds its text: a copy taken
  ! before must keep the old text, whatever way the variable is written next.
  VAR string shared_g := "g";
  PERS string shared_p := "p";
  VAR string shared_a{2};

  PROC test_copies_keep_their_text()
    VAR string s := "ab";
    VAR string t;
    VAR string u;
    t := s;
    s := s + "c";
    Assert t = "ab" \Msg:="a copy taken before an append";
    Assert s = "abc";
    u := s;
    s := "x";
    Assert u = "abc" \Msg:="a copy taken before a constant is written";
    s := s + s + NumToStr(12, 0) + StrPart(u, 2, 2);
    Assert s = "xx12bc";
    u := s;
    s := StrPart(s, 3, 1);
    Assert u = "xx12bc" \Msg:="a copy taken before StrPart is written";
    Assert s = "1";
    u := s;
    s := NumToStr(7.5, 1);
    Assert u = "1" \Msg:="a copy taken before NumToStr is written";
    Assert s = "7.5";
  ENDPROC

  PROC test_copies_in_globals_arrays_and_arguments_keep_their_text()
    VAR string s := "a";
    shared_a{1} := s;
    shared_g := s;
    s := s + "b";
    Assert shared_a{1} = "a";
    Assert shared_g = "a";
    shared_a{2} := shared_g;
    shared_g := shared_g + "z";
    Assert shared_a{2} = "a";
    Assert shared_g = "az";
    shared_p := "p";
    s := shared_p;
    shared_p := shared_p + "q";
    Assert s = "p" \Msg:="a PERS written in place";
    Assert shared_p = "pq";
    Assert keeps_argument(s) = "p!";
    Assert s = "p" \Msg:="an IN argument is a copy";
  ENDPROC

  FUNC string keeps_argument(string x)
    VAR string y;
    y := x;
    y := y + "!";
    RETURN y;
  ENDFUNC

  PROC append_through(INOUT string x)
    x := x + "!";
  ENDPROC

  PROC test_inout_string_is_written_through()
    VAR string s := "go";
    VAR string t;
    t := s;
    append_through s;
    Assert s = "go!" \Msg:="INOUT writes the caller's variable";
    Assert t = "go" \Msg:="a copy taken before the call";
    append_through shared_g;
    Assert StrPart(shared_g, StrLen(shared_g), 1) = "!";
  ENDPROC

  PROC test_string_test_reads_in_place()
    VAR string w := "b";
    VAR num hit := 0;
    TEST w + "c"
    CASE "bc":
      hit := 1;
    DEFAULT:
      hit := 2;
    ENDTEST
    Assert hit = 1;
    w := "";
    TEST w
    CASE "":
      hit := 3;
    ENDTEST
    Assert hit = 3;
  ENDPROC

  PROC test_append_that_fails_keeps_the_old_text()
    VAR string s := "ab";
    VAR string t := "xy";
    VAR string long := "0123456789012345678901234567890123456789012345678901234567890123456789012345";
    VAR num tries := 0;
    s := s + "c" + StrPart(t, 5, 1);
    Assert tries = 1;
    Assert s = "abcw" \Msg:="the retried append happened once";
    s := s + "!" + long;
    Assert FALSE \Msg:="not reached";
  ERROR
    tries := tries + 1;
    IF tries = 1 THEN
      Assert ERRNO = ERR_OUTOFBND;
      Assert s = "ab" \Msg:="a failed StrPart leaves the appended-to string as it was";
      t := "xyzvw";
      RETRY;
    ENDIF
    Assert ERRNO = ERR_STRTOOLNG;
    Assert s = "abcw" \Msg:="a too long result leaves the string as it was";
  ENDPROC

  FUNC string rewrites_shared_g()
    shared_g := "changed";
    RETURN "r";
  ENDFUNC

  PROC test_append_reads_the_string_before_the_other_operands()
    VAR string s := "ab";
    VAR string t;
    s := s + NumToStr(StrLen(s), 0) + StrPart(s, 1, 1);
    Assert s = "ab2a" \Msg:="the operands read the string as it was";
    t := s;
    s := s + s;
    Assert s = "ab2aab2a";
    Assert t = "ab2a";
    shared_g := "a";
    shared_g := shared_g + rewrites_shared_g();
    Assert shared_g = "ar" \Msg:="the string is read before a function changes it";
    shared_g := "a";
    shared_g := shared_g + "b" + rewrites_shared_g() + shared_g;
    Assert shared_g = "abrchanged";
  ENDPROC

  PROC test_append_to_a_copy_in_a_loop()
    VAR string s := "";
    VAR string snaps{3};
    FOR i FROM 1 TO 3 DO
      s := s + NumToStr(i, 0) + ",";
      snaps{i} := s;
    ENDFOR
    s := s + "end";
    Assert snaps{1} = "1," \Msg:="each copy keeps the text it was given";
    Assert snaps{2} = "1,2,";
    Assert snaps{3} = "1,2,3,";
    Assert s = "1,2,3,end";
    shared_p := "p";
    shared_p := shared_p + "1" + NumToStr(2, 0);
    Assert shared_p = "p12" \Msg:="a PERS appended in place";
  ENDPROC

  ! One-character reads and one-operand appends run a byte-indexed fast path while the
  ! text is ASCII; the character positions of text after a non-ASCII character, copies,
  ! errors and the 80-character limit behave as everywhere else.
  PROC test_one_character_reads_and_appends()
    VAR string s := "a\C5b7";
    VAR string c;
    VAR string d;
    VAR string r := "";
    VAR num k := 3;
    FOR i FROM 1 TO StrLen(s) DO
      c := StrPart(s, i, 1);
      r := r + c;
    ENDFOR
    Assert r = s \Msg:="the text rebuilt a character at a time";
    Assert StrLen(s) = 4 \Msg:="StrLen counts characters";
    c := StrPart(s, k, 1);
    Assert c = "b" \Msg:="a position after a non-ASCII character counts characters";
    c := StrPart(s, 2, 1);
    Assert c = "\C5";
    d := c;
    c := StrPart(s, 1, 1);
    Assert d = "\C5" \Msg:="a copy taken before a one-character StrPart";
    Assert c = "a";
    c := StrPart(c, 1, 1);
    Assert c = "a" \Msg:="a character of the target itself";
    d := r;
    r := r + c;
    Assert d = s \Msg:="a copy taken before a one-operand append";
    Assert r = s + "a";
    r := r + "\C5";
    Assert StrLen(r) = 6;
    Assert StrFind(r, 3, "\C5") = 6 \Msg:="StrFind counts characters";
    Assert StrMatch(r, 1, "b7") = 3;
  ENDPROC

  PROC test_one_character_read_past_the_end()
    VAR string s := "ab";
    VAR string c := "x";
    VAR num k := 3;
    c := StrPart(s, k, 1);
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_OUTOFBND;
    Assert c = "x" \Msg:="a failed read leaves the target as it was";
  ENDPROC

  PROC test_one_operand_append_at_the_limit()
    VAR string s := "012345678901234567890123456789012345678901234567890123456789012345678901234567";
    VAR string c := "9";
    VAR string u;
    s := s + c;
    Assert StrLen(s) = 79;
    u := "\C5" + s;
    Assert StrLen(u) = 80 \Msg:="80 characters in 81 bytes";
    s := s + c;
    Assert StrLen(s) = 80;
    s := s + c;
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_STRTOOLNG;
    Assert StrLen(s) = 80 \Msg:="a too long result leaves the string as it was";
  ENDPROC

  FUNC num word_kind(string w)
    TEST w
    CASE "red", "green", "a_colour_with_a_long_name":
      RETURN 1;
    CASE "one", "two":
      RETURN 2;
    DEFAULT:
      RETURN 0;
    ENDTEST
  ENDFUNC

  PROC test_string_test_compares_whole_texts()
    Assert word_kind("red") = 1;
    Assert word_kind("rod") = 0 \Msg:="same length, other text";
    Assert word_kind("re") = 0 \Msg:="a prefix";
    Assert word_kind("reds") = 0;
    Assert word_kind("a_colour_with_a_long_name") = 1;
    Assert word_kind("a_colour_with_a_long_namE") = 0;
    Assert word_kind("two") = 2;
    Assert word_kind("") = 0;
  ENDPROC
ENDMODULE
