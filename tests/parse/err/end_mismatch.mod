MODULE Mismatch
  PROC moveIt()
    Stop;
  ENDFUNC
  FUNC num value()
    RETURN 1;
  ENDPROC
  TRAP onEvent
    Stop;
  ENDTRAP
ENDMODULE
