MODULE MainModule
    ! The program `rapidvc serve` runs in the RWS tests (tests/rws.rs, tests/rws_clients.rs):
    ! data of every class for the symbol resources, and a main routine that counts its cycles
    ! and copies the input DI1 (set over RWS) to the output DO_ECHO, so a test sees the
    ! program running and a signal set by RAPID.
    PERS num counter := 0;
    PERS num arr{3} := [1,2,3];
    PERS jointtarget jt := [[0,0,0,0,30,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    PERS num cycles := 0;
    PERS num opmode_seen := 0;
    VAR num v := 5;
    CONST num c := 3;

    PERS bool reached := FALSE;
    CONST jointtarget far := [[30,0,0,0,30,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    CONST jointtarget home := [[0,0,0,0,30,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    PERS num move_time := 0;
    VAR clock clk;

    ! `--entry moves`: to `home`, then one slow joint move to `far` (timed in `move_time`),
    ! then `reached` (a stop during the move, and a start after it, must bring the robot to
    ! `far`).
    PROC moves()
        reached := FALSE;
        MoveAbsJ home, v1000, fine, tool0;
        ClkReset clk;
        ClkStart clk;
        MoveAbsJ far, v200, fine, tool0;
        ClkStop clk;
        move_time := ClkRead(clk);
        reached := TRUE;
    ENDPROC

    ! `--entry shuttle`, run forever: fly-by moves between `home` and `far`, so the next
    ! cycle's moves are already on their way to the robot when a stop comes.
    PROC shuttle()
        MoveAbsJ far, v500, z10, tool0;
        MoveAbsJ home, v500, z10, tool0;
    ENDPROC

    ! `--entry line`: a fast straight line with a fly-by corner into a second one, for a stop
    ! in the middle of it (the robot must stay on the path while it stops and after it starts).
    CONST robtarget line_a := [[900,-300,800],[0,0,1,0],[-1,0,-1,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    CONST robtarget line_b := [[900,300,800],[0,0,1,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    CONST robtarget line_c := [[1200,300,800],[0,0,1,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    PROC line()
        reached := FALSE;
        MoveJ line_a, v1000, fine, tool0;
        MoveL line_b, v1000, z100, tool0;
        MoveL line_c, v1000, fine, tool0;
        reached := TRUE;
    ENDPROC

    PROC main()
        cycles := cycles + 1;
        SetDO DO_ECHO, DI1;
        opmode_seen := OpMode();
        WaitTime 0.05;
    ENDPROC
ENDMODULE
