MODULE Cell
  ! SEMISTATIC: counts the parts the robot reports over the RAPID message queue.
  PERS num parts := 0;
  PERS bool cell_lock := FALSE;
  PERS tasks rob_cell{2} := [["T_ROB1"], ["T_CELL"]];
  TASK PERS num visits := 100;
  VAR syncident sync_start;
  VAR syncident sync_end;
  VAR intnum part_int;
  VAR num counted := 0;
  VAR num number;
  VAR num mec;
  VAR rmqmessage msg;
  VAR rmqheader header;
  VAR rmqslot sender;
  VAR num part;
  VAR num tag;
  VAR string request;

  PROC main()
    TPWrite "cell: " + GetTaskName(\TaskNo:=number) + " is task " + NumToStr(number, 0) + ", moves the robot: " + ValToStr(TaskRunRob());
    CONNECT part_int WITH on_part;
    IRMQMessage part, part_int;
    WaitSyncTask sync_start, rob_cell;
    TPWrite "cell: in sync";
    WaitUntil counted >= 3;
    ! Take the lock the robot also uses, to read the shared count undisturbed.
    WaitTestAndSet cell_lock;
    TPWrite "cell: shared parts = " + NumToStr(parts, 0) + ", my visits = " + NumToStr(visits, 0);
    cell_lock := FALSE;
    RMQReadWait msg \TimeOut:=10;
    RMQGetMsgHeader msg \Header:=header \SenderId:=sender;
    RMQGetMsgData msg, request;
    TPWrite "cell: " + request + " (a " + header.datatype + ") from " + RMQGetSlotName(sender);
    RMQSendMessage sender, counted;
    WaitSyncTask sync_end, rob_cell;
    TPWrite "cell: done";
  ENDPROC

  TRAP on_part
    RMQGetMessage msg;
    RMQGetMsgHeader msg \UserDef:=tag;
    RMQGetMsgData msg, part;
    counted := counted + 1;
    TPWrite "cell: part " + NumToStr(part, 0) + " (move " + NumToStr(tag, 0) + ")";
  ENDTRAP
ENDMODULE
