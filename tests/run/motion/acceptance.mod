MODULE acceptance
  ! Issue 4's acceptance on the default robot (IRB 2600-12/1.85): from [0,0,0,0,35,0],
  ! MoveJ p20 with tFroniusCMT and MoveJ p30 with tool0 (the EGM manual's targets) both end
  ! at [83.50, 0.08, -0.34, 0.10, 39.07, -0.14].
  CONST robtarget p20:=[[150,1320,1140],
     [0.000494947, 0.662278, -0.749217, -0.00783173], [0,0,-1,0],
     [9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
  CONST robtarget p30:=[[114.50,1005.42,1410.38],
     [0.322151, -0.601023, 0.672381, 0.287914], [0,0,-1,0],
     [9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
  CONST jointtarget jpos10:=[[0,0,0,0,35,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
  TASK PERS tooldata tFroniusCMT:=[TRUE,[[12.3313,-0.108707,416.142],
     [0.903899,-0.00320735,0.427666,0.00765917]],
     [2.6,[-111.1,24.6,386.6],[1,0,0,0],0,0,0.072]];

  PROC main()
    VAR robtarget here;
    MoveAbsJ jpos10\NoEOffs, v1000, fine, tFroniusCMT;
    joints "after MoveAbsJ jpos10";
    MoveJ p20, v1000, fine, tFroniusCMT;
    joints "after MoveJ p20, tFroniusCMT";
    here := CRobT(\Tool:=tFroniusCMT);
    TPWrite "  CRobT trans " \Pos:=here.trans;
    TPWrite "  CRobT robconf " + ValToStr(here.robconf);
    MoveAbsJ jpos10\NoEOffs, v1000, fine, tool0;
    MoveJ p30, v1000, fine, tool0;
    joints "after MoveJ p30, tool0";
    here := CRobT();
    TPWrite "  CRobT trans " \Pos:=here.trans;
  ENDPROC

  PROC joints(string what)
    VAR jointtarget j;
    VAR string s;
    j := CJointT();
    s := NumToStr(j.robax.rax_1, 2) + ", " + NumToStr(j.robax.rax_2, 2) + ", ";
    s := s + NumToStr(j.robax.rax_3, 2) + ", " + NumToStr(j.robax.rax_4, 2) + ", ";
    s := s + NumToStr(j.robax.rax_5, 2) + ", " + NumToStr(j.robax.rax_6, 2);
    TPWrite what + ": [" + s + "]";
  ENDPROC
ENDMODULE
