MODULE MainModule
    ! The program `rapidvc serve` runs in tests/rws_clients.rs for the resources abb_librws
    ! and abb_egm_rws_managers read: a tool and a work object of its own, and a main routine
    ! that moves the robot with them and writes where the robot is, as RAPID computes it
    ! (CRobT for each tool and work object), into persistents the test compares with the
    ! robtargets served over RWS.
    PERS tooldata tGrip := [TRUE,[[10,-20,150],[0.9659258,0,0.258819,0]],[2,[0,0,50],[1,0,0,0],0,0,0]];
    PERS wobjdata wTable := [FALSE,TRUE,"",[[800,-300,200],[0.7071068,0,0,0.7071068]],[[20,30,0],[0.9961947,0,0,0.0871557]]];
    PERS num notATool := 1;
    PERS robtarget rt_t0_w0 := [[0,0,0],[1,0,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    PERS robtarget rt_t0_wt := [[0,0,0],[1,0,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    PERS robtarget rt_tg_w0 := [[0,0,0],[1,0,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    PERS robtarget rt_tg_wt := [[0,0,0],[1,0,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    PERS bool done := FALSE;
    CONST jointtarget there := [[20,-10,15,30,40,-25],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];

    PROC main()
        MoveAbsJ there, v1000, fine, tGrip \WObj:=wTable;
        rt_t0_w0 := CRobT(\Tool:=tool0 \WObj:=wobj0);
        rt_t0_wt := CRobT(\Tool:=tool0 \WObj:=wTable);
        rt_tg_w0 := CRobT(\Tool:=tGrip \WObj:=wobj0);
        rt_tg_wt := CRobT(\Tool:=tGrip \WObj:=wTable);
        done := TRUE;
        WaitTime 0.1;
    ENDPROC
ENDMODULE
