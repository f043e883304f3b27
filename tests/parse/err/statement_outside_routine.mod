MODULE Loose
  VAR num count := 0;
  count := count + 1;
  MoveL spot, v100, fine, tool0;
  PROC main()
    count := 2;
  ENDPROC
ENDMODULE
