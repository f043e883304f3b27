MODULE data_client
  ! A RAPID client of tests/sockets/data_server.py (plain Python sockets and struct) in
  ! tests/sockets_python.rs: a greeting as text, then numbers packed with PackRawBytes in
  ! both byte orders, which Python's struct module unpacks; the server answers with numbers
  ! packed by struct, which UnpackRawBytes reads. The server's port comes in server_port
  ! (the test writes it to the --pers file).
  PERS num server_port := 0;

  PROC main()
    VAR socketdev sock;
    VAR string text;
    VAR rawbytes raw;
    VAR num n;
    VAR num f;
    VAR num received;
    VAR bool connected := FALSE;
    IF server_port = 0 THEN
      TPWrite "no port: run with --pers holding server_port";
      RETURN;
    ENDIF
    SocketCreate sock;
    SocketConnect sock, "127.0.0.1", server_port \Time:=10;
    connected := TRUE;
    TPWrite "status " \Num:=SocketGetStatus(sock);
    SocketSend sock \Str:="hello from rapid";
    SocketReceive sock \Str:=text \ReadNoOfBytes:=11 \Time:=10;
    TPWrite "server says: " + text;
    PackRawBytes 1234567, raw, 1 \IntX:=DINT;
    PackRawBytes 13.5, raw \Network, 5 \Float4;
    PackRawBytes 65534, raw \Network, 9 \IntX:=UINT;
    PackRawBytes "abc", raw, 11 \ASCII;
    PackRawBytes -3, raw, 14 \IntX:=SINT;
    SocketSend sock \RawData:=raw;
    ClearRawBytes raw;
    SocketReceive sock \RawData:=raw \ReadNoOfBytes:=8 \NoRecBytes:=received \Time:=10;
    UnpackRawBytes raw \Network, 1, n \IntX:=DINT;
    UnpackRawBytes raw, 5, f \Float4;
    TPWrite "received " \Num:=received;
    TPWrite "network DINT " \Num:=n;
    TPWrite "little-endian float " \Num:=f;
    ! The server closes the connection: the next receive says so.
    SocketReceive sock \Str:=text \Time:=10;
    TPWrite "unexpected: " + text;
  ERROR
    ! A refused connect is ERR_SOCK_CLOSED too: that one stops the program.
    IF ERRNO = ERR_SOCK_CLOSED AND connected THEN
      TPWrite "the server closed the connection";
      SocketClose sock;
      RETURN;
    ENDIF
    RAISE;
  ENDPROC
ENDMODULE
