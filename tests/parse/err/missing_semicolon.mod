MODULE Broken
  PROC main()
    counter := counter + 1
    MoveL spot, v100, z10, gripTool;
  ENDPROC
ENDMODULE
