MODULE sysdata
  ! The active system data follow the moves: after a move, GetSysData reads its tool and
  ! work object (wobj0 when the move names none); SetSysData sets them until the next move;
  ! the payload changes only by SetSysData. GetSysData example of ABB's "RAPID Instructions,
  ! Functions and Data types": the active tool's value and name.
  PERS tooldata tGripper := [TRUE, [[0, 0, 150], [1, 0, 0, 0]], [2, [0, 0, 50], [1, 0, 0, 0], 0, 0, 0]];
  PERS wobjdata wobjTable := [FALSE, TRUE, "", [[600, 0, 300], [1, 0, 0, 0]], [[0, 0, 0], [1, 0, 0, 0]]];
  PERS loaddata box := [1.5, [0, 0, 30], [1, 0, 0, 0], 0, 0, 0];
  PERS tooldata curtoolvalue := [TRUE, [[0, 0, 0], [1, 0, 0, 0]], [0.001, [0, 0, 0.001], [1, 0, 0, 0], 0, 0, 0]];
  PERS wobjdata curwobj := [FALSE, TRUE, "", [[0, 0, 0], [1, 0, 0, 0]], [[0, 0, 0], [1, 0, 0, 0]]];
  PERS loaddata curload := [0.001, [0, 0, 0.001], [1, 0, 0, 0], 0, 0, 0];
  CONST jointtarget home := [[0, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST jointtarget other := [[10, 10, 10, 0, 70, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];

  PROC show()
    VAR string tool;
    VAR string wobj;
    VAR string load;
    GetSysData curtoolvalue \ObjectName:=tool;
    GetSysData curwobj \ObjectName:=wobj;
    GetSysData curload \ObjectName:=load;
    TPWrite "active: " + tool + ", " + wobj + ", " + load + "; TCP z in the tool frame " \Num:=curtoolvalue.tframe.trans.z;
  ENDPROC

  PROC main()
    show;
    MoveAbsJ home, v1000, fine, tGripper \WObj:=wobjTable;
    show;
    SetSysData box;
    SetSysData tool0;
    show;
    MoveAbsJ other, v1000, fine, tGripper;
    show;
  ENDPROC
ENDMODULE
