MODULE strings
  ! String building: each round joins ten numbers into a line, walks it backwards one
  ! character at a time to build its reverse (counting the sevens), and searches the
  ! reverse. Same algorithm: strings.py, strings.lua.
  CONST num N := 150000;

  PROC main()
    VAR string s;
    VAR string r;
    VAR string c;
    VAR num total := 0;
    VAR num sevens := 0;
    FOR round FROM 1 TO N DO
      s := "";
      FOR i FROM 1 TO 10 DO
        s := s + NumToStr((round * i) MOD 997, 0) + ",";
      ENDFOR
      r := "";
      FOR k FROM StrLen(s) TO 1 STEP -1 DO
        c := StrPart(s, k, 1);
        IF c = "7" THEN
          sevens := sevens + 1;
        ENDIF
        r := r + c;
      ENDFOR
      total := (total + StrLen(r) + StrFind(r, 1, "9")) MOD 1000000;
    ENDFOR
    TPWrite "result: " + NumToStr(total, 0) + " " + NumToStr(sevens, 0);
  ENDPROC
ENDMODULE
