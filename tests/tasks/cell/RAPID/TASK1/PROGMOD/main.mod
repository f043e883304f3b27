MODULE MainModule
  ! This task's own: the other tasks have their own `visits`.
  TASK PERS num visits := 0;
  VAR clock clk;
  VAR syncident sync_start;
  VAR syncident sync_end;
  VAR rmqslot cell;
  VAR rmqmessage answer;
  VAR num counted;
  VAR num number;
  VAR num motion_number;
  CONST jointtarget home := [[0, 0, 0, 0, 30, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST jointtarget pick := [[20, 10, 10, 0, 40, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];

  PROC main()
    ClkStart clk;
    TPWrite "robot: " + GetTaskName(\TaskNo:=number) + " is task " + NumToStr(number, 0);
    TPWrite "robot: moves the robot: " + ValToStr(TaskRunRob()) + ", mechanical units: " + ValToStr(TaskRunMec());
    MoveAbsJ home, v1000, fine, tool0;
    WaitSyncTask sync_start, rob_cell;
    TPWrite "robot: in sync with the cell at " + NumToStr(ClkRead(clk), 3) + " s";
    RMQFindSlot cell, "T_CELL";
    FOR i FROM 1 TO 3 DO
      MoveAbsJ pick, v1000, fine, tool0;
      WaitTestAndSet cell_lock;
      parts := parts + 1;
      visits := visits + 1;
      cell_lock := FALSE;
      RMQSendMessage cell, parts \UserDef:=i;
      MoveAbsJ home, v1000, fine, tool0;
    ENDFOR
    RMQSendWait cell, "report", answer, counted \TimeOut:=10;
    RMQGetMsgData answer, counted;
    TPWrite "robot: the cell counted " + NumToStr(counted, 0) + " parts, I made " + NumToStr(visits, 0);
    WaitSyncTask sync_end, rob_cell;
    TPWrite "robot: done";
  ENDPROC
ENDMODULE
