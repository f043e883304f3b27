MODULE tpwrite
  ! TPWrite with every optional value, TPErase and ErrWrite.
  PROC main()
    VAR pos p := [1817.3, 905.17, 879.11];
    VAR orient o := [0.96593, 0, 0.25882, 0];
    VAR dnum d := 1234567890.125;
    TPErase;
    TPWrite "plain text";
    TPWrite "num: " \Num:=23;
    TPWrite "num: " \Num:=1.141367;
    TPWrite "dnum: " \Dnum:=d;
    TPWrite "bool: " \Bool:=TRUE;
    TPWrite "pos: " \Pos:=p;
    TPWrite "orient: " \Orient:=o;
    TPWrite "comma before the option", \Num:=-0.5;
    ErrWrite "Header", "reason one" \RL2:="reason two";
    ErrWrite \W, "Warning", "only a warning";
  ENDPROC
ENDMODULE
