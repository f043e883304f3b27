MODULE cmd_server
  ! A command server on a TCP socket, driven by tests/sockets/cmd_client.py (plain Python
  ! socket module) in tests/sockets_python.rs. One client; one command per message and one
  ! reply per command, as text:
  !   move X,Y,Z    MoveL to [X,Y,Z] (mm, tool pointing down): "ok", or "error N" with the
  !                 RAPID error number when the robot cannot go there
  !   pos           "pos X Y Z": where the robot is (CRobT, mm, one decimal)
  !   set do1 V     SetDO do1, V: "ok"
  !   get do1       "do1 V"
  !   quit          "bye"; the server closes the connection and ends
  ! Anything else gets "error unknown command". The server listens on 127.0.0.1 at port
  ! server_port (the test writes it to the --pers file; without one the program ends).
  CONST robtarget home := [[1100, 0, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR socketdev server;
  VAR socketdev client;
  PERS num server_port := 0;
  VAR bool running := TRUE;

  PROC main()
    VAR string peer;
    VAR string cmd;
    IF server_port = 0 THEN
      TPWrite "no port: run with --pers holding server_port";
      RETURN;
    ENDIF
    MoveJ home, v1000, fine, tool0;
    SocketCreate server;
    SocketBind server, "127.0.0.1", server_port;
    SocketListen server;
    TPWrite "listening";
    SocketAccept server, client \ClientAddress:=peer \Time:=30;
    TPWrite "client from " + peer;
    WHILE running DO
      SocketReceive client \Str:=cmd \Time:=30;
      TPWrite "> " + cmd;
      SocketSend client \Str:=handle(cmd);
    ENDWHILE
    SocketClose client;
    SocketClose server;
  ENDPROC

  ! The reply to one command.
  FUNC string handle(string cmd)
    VAR num sp;
    VAR string word;
    VAR string rest := "";
    VAR pos p;
    VAR robtarget t;
    VAR num v;
    sp := StrFind(cmd, 1, " ");
    word := StrPart(cmd, 1, sp - 1);
    IF sp < StrLen(cmd) rest := StrPart(cmd, sp + 1, StrLen(cmd) - sp);
    TEST word
    CASE "move":
      IF NOT StrToVal("[" + rest + "]", p) RETURN "error not a position: " + rest;
      t := home;
      t.trans := p;
      MoveL t, v1000, fine, tool0;
      RETURN "ok";
    CASE "pos":
      t := CRobT(\Tool:=tool0 \WObj:=wobj0);
      RETURN "pos " + NumToStr(t.trans.x, 1) + " " + NumToStr(t.trans.y, 1) + " " + NumToStr(t.trans.z, 1);
    CASE "set":
      IF StrPart(rest, 1, 4) <> "do1 " OR StrLen(rest) < 5 RETURN "error unknown signal";
      IF NOT StrToVal(StrPart(rest, 5, StrLen(rest) - 4), v) RETURN "error not a value";
      SetDO do1, v;
      RETURN "ok";
    CASE "get":
      IF rest <> "do1" RETURN "error unknown signal";
      RETURN "do1 " + NumToStr(DOutput(do1), 0);
    CASE "quit":
      running := FALSE;
      RETURN "bye";
    DEFAULT:
      RETURN "error unknown command";
    ENDTEST
  ERROR
    ! An unreachable target, a bad signal value: the client gets the error number.
    RETURN "error " + NumToStr(ERRNO, 0);
  ENDFUNC
ENDMODULE
