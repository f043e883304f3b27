MODULE Cell
  ! SEMISTATIC: follows the shared count of the motion task.
  PERS num shared := 0;
  VAR num seen := 0;

  PROC main()
    WHILE TRUE DO
      WaitUntil shared > seen;
      seen := shared;
      TPWrite "cell: shared is " + NumToStr(seen, 0);
    ENDWHILE
  ENDPROC
ENDMODULE
