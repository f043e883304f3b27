MODULE Test
  VAR num case := 1;
  PROC Step()
    Stop;
  ENDPROC
ENDMODULE
