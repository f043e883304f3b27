MODULE trap_wait
  ! Traps run while a socket instruction waits: a 0.1 s timer fires during a
  ! SocketReceiveFrom that waits 1 s for a datagram nobody sends, which then ends with
  ! ERR_SOCK_TIMEOUT. Run by tests/sockets_python.rs (real time, as every program with
  ! sockets).
  VAR intnum tick;
  VAR num ticks := 0;

  PROC main()
    VAR socketdev udp;
    VAR string text;
    VAR string peer;
    VAR num peer_port;
    VAR clock clk;
    CONNECT tick WITH on_tick;
    ITimer 0.1, tick;
    SocketCreate udp \UDP;
    ! Port 0: any free port.
    SocketBind udp, "127.0.0.1", 0;
    ClkStart clk;
    SocketReceiveFrom udp \Str:=text, peer, peer_port \Time:=1;
    TPWrite "a datagram came: " + text;
  ERROR
    IF ERRNO = ERR_SOCK_TIMEOUT THEN
      ClkStop clk;
      IDelete tick;
      SocketClose udp;
      TPWrite "time-out after about 1 s: " \Bool:=ClkRead(clk) >= 0.9 AND ClkRead(clk) < 3;
      TPWrite "the timer fired during the wait: " \Bool:=ticks >= 3;
      RETURN;
    ENDIF
    RAISE;
  ENDPROC

  TRAP on_tick
    Incr ticks;
  ENDTRAP
ENDMODULE
