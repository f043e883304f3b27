! args: --max-time 60
MODULE wait_forever
  ! Waiting for a signal nobody sets ends at the virtual time limit (--max-time).
  PROC main()
    TPWrite "waiting for di1";
    WaitDI di1, 1;
  ENDPROC
ENDMODULE
