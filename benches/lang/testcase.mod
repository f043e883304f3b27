MODULE testcase
  ! TEST/CASE: a small stack machine whose opcodes are dispatched by TEST on a num runs a
  ! loop program, and a word classifier dispatches by TEST on strings. Same algorithm:
  ! testcase.py, testcase.lua.
  CONST num N := 750;

  ! The machine's program (registers: 1 = i, 2 = acc):
  ! 1 LOAD 2, LOAD 1, LOAD 1, MUL, ADD, PUSH 10007, MOD, STORE 2  (acc := (acc + i * i) MOD 10007)
  ! 14 LOAD 1, PUSH 1, SUB, DUP, STORE 1, JNZ 1, HALT            (i := i - 1 until it is 0)
  VAR num code{24} := [2, 2, 2, 1, 2, 1, 6, 4, 1, 10007, 7, 3, 2, 2, 1, 1, 1, 5, 9, 3, 1, 8, 1, 0];
  VAR num stack{16};
  VAR num reg{4};
  CONST string VOCAB{10} := ["red", "one", "square", "blue", "three", "tree", "green", "circle", "two", "sky"];

  FUNC num run(num n)
    VAR num pc := 1;
    VAR num sp := 0;
    VAR num op;
    VAR bool going := TRUE;
    reg{1} := n;
    reg{2} := 0;
    WHILE going DO
      op := code{pc};
      pc := pc + 1;
      TEST op
      CASE 1:
        ! PUSH constant
        sp := sp + 1;
        stack{sp} := code{pc};
        pc := pc + 1;
      CASE 2:
        ! LOAD register
        sp := sp + 1;
        stack{sp} := reg{code{pc}};
        pc := pc + 1;
      CASE 3:
        ! STORE register
        reg{code{pc}} := stack{sp};
        sp := sp - 1;
        pc := pc + 1;
      CASE 4:
        ! ADD
        stack{sp - 1} := stack{sp - 1} + stack{sp};
        sp := sp - 1;
      CASE 5:
        ! SUB
        stack{sp - 1} := stack{sp - 1} - stack{sp};
        sp := sp - 1;
      CASE 6:
        ! MUL
        stack{sp - 1} := stack{sp - 1} * stack{sp};
        sp := sp - 1;
      CASE 7:
        ! MOD
        stack{sp - 1} := stack{sp - 1} MOD stack{sp};
        sp := sp - 1;
      CASE 8:
        ! JNZ address (pops)
        IF stack{sp} <> 0 THEN
          pc := code{pc};
        ELSE
          pc := pc + 1;
        ENDIF
        sp := sp - 1;
      CASE 9:
        ! DUP
        sp := sp + 1;
        stack{sp} := stack{sp - 1};
      DEFAULT:
        ! HALT
        going := FALSE;
      ENDTEST
    ENDWHILE
    RETURN reg{2};
  ENDFUNC

  FUNC num classify(string w)
    TEST w
    CASE "red", "green", "blue":
      RETURN 1;
    CASE "circle", "square":
      RETURN 2;
    CASE "one", "two", "three":
      RETURN 3;
    DEFAULT:
      RETURN 0;
    ENDTEST
  ENDFUNC

  PROC main()
    VAR num check := 0;
    VAR num words := 0;
    FOR k FROM 1 TO N DO
      check := (check + run(1000 + k MOD 7)) MOD 1000000;
    ENDFOR
    FOR k FROM 1 TO 500 * N DO
      words := words + classify(VOCAB{k MOD 10 + 1}) * (k MOD 3);
    ENDFOR
    TPWrite "result: " + NumToStr(check, 0) + " " + NumToStr(words, 0);
  ENDPROC
ENDMODULE
