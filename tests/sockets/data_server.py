"""Server of tests/sockets/client.mod: plain Python sockets and struct, no packages.

Prints {"port": N} once listening on 127.0.0.1, serves one connection, checks what the
RAPID client sends, answers, closes. Prints what it got; exits 1 when something is wrong.
"""
import socket
import struct
import sys


def recv_exact(conn: socket.socket, n: int) -> bytes:
    data = b""
    while len(data) < n:
        chunk = conn.recv(n - len(data))
        if not chunk:
            raise ConnectionError(f"closed after {len(data)} of {n} bytes")
        data += chunk
    return data


def main() -> int:
    listener = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    listener.bind(("127.0.0.1", 0))
    listener.listen(1)
    listener.settimeout(60)
    print('{"port": %d}' % listener.getsockname()[1], flush=True)
    conn, _ = listener.accept()
    conn.settimeout(30)
    greeting = recv_exact(conn, 16)
    print(f"greeting {greeting!r}", flush=True)
    if greeting != b"hello from rapid":
        return 1
    conn.sendall(b"hello robot")
    raw = recv_exact(conn, 14)
    little_dint = struct.unpack("<i", raw[0:4])[0]
    network_float = struct.unpack("!f", raw[4:8])[0]
    network_uint = struct.unpack("!H", raw[8:10])[0]
    text = raw[10:13].decode("ascii")
    sint = struct.unpack("<b", raw[13:14])[0]
    got = (little_dint, network_float, network_uint, text, sint)
    print(f"numbers {got}", flush=True)
    if got != (1234567, 13.5, 65534, "abc", -3):
        return 1
    conn.sendall(struct.pack("!i", -42) + struct.pack("<f", 0.25))
    conn.close()
    listener.close()
    print("served", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
