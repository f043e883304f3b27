! args: --max-steps 1000
MODULE runaway
  ! An endless loop is stopped by the operation budget (--max-steps).
  PROC main()
    VAR num n := 0;
    WHILE TRUE DO
      n := n + 1;
    ENDWHILE
  ENDPROC
ENDMODULE
