MODULE Twice
  VAR num level := 0;
  PERS num LEVEL := 1;
  RECORD item
    num size;
    num Size;
  ENDRECORD
  PROC run(num a, num A)
    VAR num a;
    Stop;
  ENDPROC
  PROC Run()
    Stop;
  ENDPROC
ENDMODULE
