MODULE MainModule
  ! The motion task of a controller served over RWS: one cycle moves the robot, counts in a
  ! shared persistent, then answers one message that arrives in its RAPID message queue
  ! (RMQ_T_ROB1) from outside (rw/dipc).
  PERS num shared := 0;
  PERS num answered := 0;
  VAR rmqmessage msg;
  VAR rmqheader header;
  VAR rmqslot sender;
  VAR string text;
  CONST jointtarget home := [[0, 0, 0, 0, 30, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST jointtarget away := [[20, 0, 0, 0, 30, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];

  PROC main()
    MoveAbsJ away, v500, fine, tool0;
    MoveAbsJ home, v500, fine, tool0;
    shared := shared + 1;
    RMQReadWait msg \TimeOut:=WAIT_MAX;
    RMQGetMsgHeader msg \Header:=header \SenderId:=sender;
    RMQGetMsgData msg, text;
    TPWrite "robot: " + text + " (a " + header.datatype + ") from " + RMQGetSlotName(sender);
    answered := answered + 1;
    RMQSendMessage sender, "got " + text \UserDef:=7;
  ENDPROC
ENDMODULE
