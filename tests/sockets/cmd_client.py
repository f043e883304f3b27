"""Client of tests/sockets/server.mod: plain Python sockets, no packages.

Usage: cmd_client.py PORT. Sends the commands, checks each reply, prints them; exits 1 on
the first wrong reply.
"""
import socket
import sys
import time


def main() -> int:
    port = int(sys.argv[1])
    deadline = time.monotonic() + 20
    while True:
        try:
            conn = socket.create_connection(("127.0.0.1", port), timeout=5)
            break
        except OSError:
            if time.monotonic() > deadline:
                print("no server", flush=True)
                return 1
            time.sleep(0.1)
    conn.settimeout(30)

    def ask(cmd: str) -> str:
        conn.sendall(cmd.encode("ascii"))
        reply = conn.recv(1024).decode("latin-1")
        print(f"{cmd} -> {reply}", flush=True)
        return reply

    checks = [
        ("pos", lambda r: r == "pos 1100.0 0.0 800.0"),
        ("move 1000,200,700", lambda r: r == "ok"),
        ("pos", lambda r: r == "pos 1000.0 200.0 700.0"),
        ("move 9000,0,0", lambda r: r.startswith("error ")),
        ("pos", lambda r: r == "pos 1000.0 200.0 700.0"),
        ("get do1", lambda r: r == "do1 0"),
        ("set do1 1", lambda r: r == "ok"),
        ("get do1", lambda r: r == "do1 1"),
        ("set do1 7", lambda r: r.startswith("error ")),
        ("set di9 1", lambda r: r == "error unknown signal"),
        ("jump", lambda r: r == "error unknown command"),
        ("quit", lambda r: r == "bye"),
    ]
    for cmd, ok in checks:
        if not ok(ask(cmd)):
            print(f"wrong reply to {cmd!r}", flush=True)
            return 1
    # The server closed its side after "bye".
    if conn.recv(1024) != b"":
        print("the server did not close the connection", flush=True)
        return 1
    print("all replies right", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
