! args: --entry start --cycles 2
MODULE entry
  ! --entry picks the start procedure; --cycles runs it again (module data keep their values).
  VAR num cycle := 0;
  PROC start()
    cycle := cycle + 1;
    TPWrite "cycle " \Num:=cycle;
  ENDPROC
ENDMODULE
