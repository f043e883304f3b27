MODULE socket_tests
  ! Sockets on the loopback interface, written purely in RAPID: a UDP socket that sends to
  ! itself, a TCP server and client in one task, \Time time-outs and the ERR_SOCK_* errors.
  ! Ports are taken from 47000 on: SocketBind on a port in use raises ERR_SOCK_ADDR_INUSE,
  ! and the ERROR handler moves to the next port and retries.

  VAR num caught := 0;
  VAR num port := 47000;

  ! Bind `sock` to 127.0.0.1 on the first free port from `port` on.
  PROC bind_free(VAR socketdev sock)
    SocketBind sock, "127.0.0.1", port;
  ERROR
    IF ERRNO = ERR_SOCK_ADDR_INUSE AND port < 47999 THEN
      port := port + 1;
      RETRY;
    ENDIF
    RAISE;
  ENDPROC

  ! Bind `sock` (a created TCP socket) and listen on the first free port from `port` on.
  ! SocketBind reuses addresses (as a server started again at once needs), so another
  ! process may bind the same port too: whichever listens first has it, and the other's
  ! SocketListen raises ERR_SOCK_ADDR_INUSE. Then a new socket tries the next port.
  PROC listen_free(VAR socketdev sock)
    bind_free sock;
    SocketListen sock;
  ERROR
    IF ERRNO = ERR_SOCK_ADDR_INUSE AND port < 47999 THEN
      SocketClose sock;
      SocketCreate sock;
      port := port + 1;
      bind_free sock;
      RETRY;
    ENDIF
    RAISE;
  ENDPROC

  PROC test_udp_to_itself()
    ! One UDP socket bound to a port sends datagrams to that same port and receives them.
    VAR socketdev udp;
    VAR rawbytes raw;
    VAR rawbytes back;
    VAR string text;
    VAR string peer_ip;
    VAR num peer_port;
    VAR num n;
    VAR num x;
    VAR byte data{4} := [1, 2, 3, 250];
    VAR byte got{6};
    SocketCreate udp \UDP;
    Assert SocketGetStatus(udp) = SOCKET_CREATED;
    bind_free udp;
    Assert SocketGetStatus(udp) = SOCKET_BOUND;
    SocketSendTo udp, "127.0.0.1", port \Str:="hello me";
    SocketReceiveFrom udp \Str:=text \NoRecBytes:=n, peer_ip, peer_port \Time:=5;
    Assert text = "hello me";
    Assert n = 8;
    Assert peer_ip = "127.0.0.1";
    Assert peer_port = port;
    ! A datagram of packed numbers in network order.
    PackRawBytes 1234567, raw \Network, 1 \IntX:=DINT;
    PackRawBytes -0.5, raw \Network, 5 \Float4;
    SocketSendTo udp, "127.0.0.1", port \RawData:=raw;
    Assert SocketPeek(udp) = 8;
    SocketReceiveFrom udp \RawData:=back, peer_ip, peer_port \Time:=5;
    Assert RawBytesLen(back) = 8;
    UnpackRawBytes back \Network, 1, n \IntX:=DINT;
    UnpackRawBytes back \Network, 5, x \Float4;
    Assert n = 1234567;
    Assert x = -0.5;
    ! A byte array, cut to \NoOfBytes.
    SocketSendTo udp, "127.0.0.1", port \Data:=data \NoOfBytes:=3;
    SocketReceiveFrom udp \Data:=got \NoRecBytes:=n, peer_ip, peer_port \Time:=5;
    Assert n = 3;
    Assert got{1} = 1 AND got{3} = 3 AND got{4} = 0;
    SocketClose udp;
    Assert SocketGetStatus(udp) = SOCKET_CLOSED;
  ENDPROC

  PROC test_udp_receive_times_out()
    ! Nothing sent: \Time:=0.2 ends the wait with ERR_SOCK_TIMEOUT.
    VAR socketdev udp;
    VAR string text;
    VAR string peer_ip;
    VAR num peer_port;
    SocketCreate udp \UDP;
    bind_free udp;
    caught := 0;
    SocketReceiveFrom udp \Str:=text, peer_ip, peer_port \Time:=0.2;
    Assert caught = ERR_SOCK_TIMEOUT;
    SocketClose udp;
  ERROR
    caught := ERRNO;
    TRYNEXT;
  ENDPROC

  PROC test_tcp_server_and_client_in_one_task()
    ! A listening server, a client connecting to it and the accepted connection, all in
    ! this task: the connect completes without waiting for the accept (the system queues
    ! it), so one task can play both sides.
    VAR socketdev server;
    VAR socketdev client;
    VAR socketdev conn;
    VAR string peer;
    VAR string text;
    VAR rawbytes raw;
    VAR num n;
    SocketCreate server;
    listen_free server;
    Assert SocketGetStatus(server) = SOCKET_LISTENING;
    SocketCreate client;
    SocketConnect client, "127.0.0.1", port \Time:=5;
    Assert SocketGetStatus(client) = SOCKET_CONNECTED;
    SocketAccept server, conn \ClientAddress:=peer \Time:=5;
    Assert peer = "127.0.0.1";
    Assert SocketGetStatus(conn) = SOCKET_CONNECTED;
    SocketSend client \Str:="ping";
    SocketReceive conn \Str:=text \ReadNoOfBytes:=4 \Time:=5;
    Assert text = "ping";
    PackRawBytes 65535, raw, 1 \IntX:=UINT;
    SocketSend conn \RawData:=raw;
    SocketReceive client \RawData:=raw \NoRecBytes:=n \Time:=5;
    Assert n = 2;
    UnpackRawBytes raw, 1, n \IntX:=UINT;
    Assert n = 65535;
    ! Nothing more comes: \Time runs out.
    caught := 0;
    SocketReceive client \Str:=text \Time:=0.2;
    Assert caught = ERR_SOCK_TIMEOUT;
    ! The client closes: the server's next receive finds the connection closed.
    SocketClose client;
    caught := 0;
    SocketReceive conn \Str:=text \Time:=5;
    Assert caught = ERR_SOCK_CLOSED;
    Assert SocketGetStatus(conn) = SOCKET_CLOSED;
    SocketClose conn;
    SocketClose server;
  ERROR
    caught := ERRNO;
    TRYNEXT;
  ENDPROC

  PROC test_socket_errors()
    ! The documented errors of misused sockets, each an ERR_SOCK_* an ERROR handler takes.
    VAR socketdev a;
    VAR socketdev b;
    VAR string text;
    ! Not created.
    caught := 0;
    SocketSend a \Str:="x";
    Assert caught = ERR_SOCK_CLOSED;
    SocketCreate a;
    ! Not connected.
    caught := 0;
    SocketSend a \Str:="x";
    Assert caught = ERR_SOCK_NOT_CONN;
    ! Listening before binding.
    caught := 0;
    SocketListen a;
    Assert caught = ERR_SOCK_NOT_BOUND;
    ! Not an address, and not a port.
    caught := 0;
    SocketConnect a, "robot.local", 80;
    Assert caught = ERR_SOCK_ADDR_INVALID;
    caught := 0;
    SocketConnect a, "127.0.0.1", 70000;
    Assert caught = ERR_SOCK_ADDR_INVALID;
    ! Bound twice, and a second socket on the same port.
    listen_free a;
    caught := 0;
    SocketBind a, "127.0.0.1", port;
    Assert caught = ERR_SOCK_IS_BOUND;
    SocketCreate b;
    caught := 0;
    SocketBind b, "127.0.0.1", port;
    Assert caught = ERR_SOCK_ADDR_INUSE;
    ! Nobody connects: SocketAccept \Time runs out.
    SocketClose b;
    caught := 0;
    SocketAccept a, b \Time:=0.2;
    Assert caught = ERR_SOCK_TIMEOUT;
    SocketClose a;
    ! Refused: nothing listens on the port any more.
    SocketCreate a;
    caught := 0;
    SocketConnect a, "127.0.0.1", port \Time:=5;
    Assert caught = ERR_SOCK_CLOSED;
    Assert SocketGetStatus(a) = SOCKET_CREATED;
    SocketClose a;
    ! Closing a closed socket does nothing.
    SocketClose a;
    Assert SocketGetStatus(a) = SOCKET_CLOSED;
  ERROR
    caught := ERRNO;
    TRYNEXT;
  ENDPROC
ENDMODULE
