MODULE run_motion
  ! Virtual-time speed of `rapidvc run`: several simulated minutes of mixed MoveJ/MoveL with
  ! fine points and fly-by zones in front of the default robot, tool pointing down. The
  ! end-of-run summary on stderr gives the real-time factor (simulated s per wall s):
  !   cargo build --release && ./target/release/rapidvc run benches/run_motion.mod
  CONST num ROUNDS := 40;
  CONST pos corners{8} := [[850, -450, 650], [1300, -350, 1250], [1050, 450, 900],
    [900, 0, 1200], [1350, 400, 700], [950, -200, 1000], [1200, 150, 1300], [1000, 350, 650]];
  CONST speeddata speeds{4} := [v500, v1000, v1500, v2000];
  CONST zonedata zones{4} := [fine, z10, z50, z10];
  VAR robtarget target := [[0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR num moves := 0;
  CONST jointtarget home := [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];

  PROC main()
    ConfJ \Off;
    ConfL \Off;
    MoveAbsJ home, v1000, fine, tool0;
    FOR r FROM 1 TO ROUNDS DO
      FOR i FROM 1 TO 8 DO
        target.trans := corners{i};
        ! Turn the tool about the vertical a little differently each time.
        target.rot := OrientZYX((r * 7 + i * 11) MOD 60 - 30, 0, 180);
        IF (r + i) MOD 2 = 0 THEN
          MoveJ target, speeds{(r + i) MOD 4 + 1}, zones{i MOD 4 + 1}, tool0;
        ELSE
          MoveL target, speeds{(r * i) MOD 4 + 1}, zones{(r + i) MOD 4 + 1}, tool0;
        ENDIF
        Incr moves;
      ENDFOR
    ENDFOR
    MoveAbsJ home, v1000, fine, tool0;
    TPWrite "moves: " \Num:=moves;
  ENDPROC
ENDMODULE
