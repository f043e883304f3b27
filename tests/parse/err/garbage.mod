garbage before the first unit
MODULE Junk
  PROC main()
    x := 1 $ 2;
    y := #;
    MoveL @spot, v100;
  ENDPROC
ENDMODULE
trailing junk ;
