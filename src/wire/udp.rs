//! Thin UDP transport for one EGM device: one socket, sends only to the configured remote, drains replies without blocking.
//!
//! It makes no protocol decisions: it does not decode, filter or time anything. The socket is
//! non-blocking; [`UdpTransport::drain`] reads every waiting datagram (bounded per call, so a
//! flood cannot stall a cycle) and hands each with its source address to the caller, usually
//! straight into [`crate::egm::EgmSession::handle_datagram`]. Datagrams of any size are read
//! whole (64 KiB buffer) so the session can see and reject oversized ones.

use std::io;
use std::net::{IpAddr, Ipv4Addr, Ipv6Addr, SocketAddr, UdpSocket};
use std::time::{Duration, Instant};

/// Receive buffer: the largest UDP payload.
const RECV_BUFFER: usize = 65_536;
/// Default bound on datagrams read per [`UdpTransport::drain`] call.
pub const DEFAULT_DRAIN_LIMIT: usize = 64;

/// One UDP socket bound for a device, talking to one remote address.
#[derive(Debug)]
pub struct UdpTransport {
    socket: UdpSocket,
    remote: SocketAddr,
    buf: Vec<u8>,
}

impl UdpTransport {
    /// Binds `local` and sends to `remote` only. The socket is non-blocking.
    pub fn bind(local: SocketAddr, remote: SocketAddr) -> io::Result<Self> {
        let socket = UdpSocket::bind(local)?;
        socket.set_nonblocking(true)?;
        Ok(UdpTransport {
            socket,
            remote,
            buf: vec![0; RECV_BUFFER],
        })
    }

    /// Binds as a UdpUc device does: to `local_port` (0 = ephemeral) on the loopback
    /// interface when `remote` is loopback, else on every interface of `remote`'s family.
    pub fn for_device(local_port: u16, remote: SocketAddr) -> io::Result<Self> {
        let ip: IpAddr = match (remote.ip().is_loopback(), remote.ip()) {
            (true, IpAddr::V4(_)) => Ipv4Addr::LOCALHOST.into(),
            (true, IpAddr::V6(_)) => Ipv6Addr::LOCALHOST.into(),
            (false, IpAddr::V4(_)) => Ipv4Addr::UNSPECIFIED.into(),
            (false, IpAddr::V6(_)) => Ipv6Addr::UNSPECIFIED.into(),
        };
        UdpTransport::bind(SocketAddr::new(ip, local_port), remote)
    }

    /// The bound local address.
    pub fn local_addr(&self) -> io::Result<SocketAddr> {
        self.socket.local_addr()
    }

    /// The remote address every datagram goes to.
    pub fn remote(&self) -> SocketAddr {
        self.remote
    }

    /// Sends one datagram to the remote address.
    pub fn send(&self, datagram: &[u8]) -> io::Result<()> {
        self.send_to(datagram, self.remote)
    }

    /// Sends one datagram to `to` (the protocol machine names the address; for an EGM
    /// device it is the remote address).
    pub fn send_to(&self, datagram: &[u8], to: SocketAddr) -> io::Result<()> {
        let sent = self.socket.send_to(datagram, to)?;
        if sent == datagram.len() {
            Ok(())
        } else {
            Err(io::Error::other(format!(
                "sent {sent} of {} bytes",
                datagram.len()
            )))
        }
    }

    /// Reads one waiting datagram without blocking; `None` when none is waiting.
    pub fn try_recv(&mut self) -> io::Result<Option<(SocketAddr, &[u8])>> {
        loop {
            match self.socket.recv_from(&mut self.buf) {
                Ok((len, src)) => return Ok(Some((src, self.buf.get(..len).unwrap_or(&[])))),
                Err(e) if e.kind() == io::ErrorKind::WouldBlock => return Ok(None),
                // ICMP "port unreachable" from an earlier send (a sensor not started yet)
                // surfaces here on some systems; it is not a datagram, keep reading.
                Err(e) if is_icmp_echo(&e) => continue,
                Err(e) => return Err(e),
            }
        }
    }

    /// Reads up to `limit` waiting datagrams, calling `on_datagram(source, bytes)` for each;
    /// returns how many were read.
    pub fn drain(
        &mut self,
        limit: usize,
        mut on_datagram: impl FnMut(SocketAddr, &[u8]),
    ) -> io::Result<usize> {
        let mut count = 0;
        while count < limit {
            match self.try_recv()? {
                Some((src, bytes)) => {
                    on_datagram(src, bytes);
                    count += 1;
                }
                None => break,
            }
        }
        Ok(count)
    }

    /// Waits up to `timeout` for one datagram (for lockstep mode and tests).
    pub fn recv_timeout(&mut self, timeout: Duration) -> io::Result<Option<(SocketAddr, &[u8])>> {
        if timeout.is_zero() {
            return self.try_recv();
        }
        self.socket.set_nonblocking(false)?;
        self.socket.set_read_timeout(Some(timeout))?;
        let result = loop {
            match self.socket.recv_from(&mut self.buf) {
                Ok((len, src)) => break Ok(Some((src, len))),
                Err(e)
                    if e.kind() == io::ErrorKind::WouldBlock
                        || e.kind() == io::ErrorKind::TimedOut =>
                {
                    break Ok(None);
                }
                Err(e) if is_icmp_echo(&e) => continue,
                Err(e) => break Err(e),
            }
        };
        let restore = self.socket.set_nonblocking(true);
        let got = result?;
        restore?;
        Ok(got.map(|(src, len)| (src, self.buf.get(..len).unwrap_or(&[]))))
    }

    /// Waits up to `timeout` (real time) for a datagram `on_datagram` takes (returns true
    /// for), handing it every datagram that arrives meanwhile; returns whether one was taken
    /// before the time ran out. For the controller's lockstep wait.
    pub fn wait_for(
        &mut self,
        timeout: Duration,
        mut on_datagram: impl FnMut(SocketAddr, &[u8]) -> bool,
    ) -> io::Result<bool> {
        let start = Instant::now();
        let deadline = start.checked_add(timeout).unwrap_or(start);
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return Ok(false);
            }
            match self.recv_timeout(left)? {
                Some((src, bytes)) => {
                    if on_datagram(src, bytes) {
                        return Ok(true);
                    }
                }
                None => return Ok(false),
            }
        }
    }
}

fn is_icmp_echo(e: &io::Error) -> bool {
    matches!(
        e.kind(),
        io::ErrorKind::ConnectionRefused | io::ErrorKind::ConnectionReset
    )
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::*;

    #[test]
    fn sends_to_remote_and_drains_everything_waiting() {
        let peer = UdpSocket::bind("127.0.0.1:0").unwrap();
        peer.set_read_timeout(Some(Duration::from_secs(2))).unwrap();
        let mut t = UdpTransport::for_device(0, peer.local_addr().unwrap()).unwrap();
        let local = t.local_addr().unwrap();
        assert!(local.ip().is_loopback());
        assert_eq!(t.remote(), peer.local_addr().unwrap());
        assert!(t.try_recv().unwrap().is_none(), "nothing yet, no blocking");
        t.send(b"robot").unwrap();
        let mut buf = [0u8; 64];
        let (n, from) = peer.recv_from(&mut buf).unwrap();
        assert_eq!((&buf[..n], from), (&b"robot"[..], local));
        for i in 0..3u8 {
            peer.send_to(&[i], local).unwrap();
        }
        let big = vec![7u8; 2000];
        peer.send_to(&big, local).unwrap();
        let first = t.recv_timeout(Duration::from_secs(2)).unwrap().unwrap();
        assert_eq!(first.1, &[0]);
        let mut got = Vec::new();
        // The rest may need a moment on a loaded machine.
        for _ in 0..200 {
            t.drain(DEFAULT_DRAIN_LIMIT, |src, bytes| {
                assert_eq!(src, peer.local_addr().unwrap());
                got.push(bytes.len());
            })
            .unwrap();
            if got.len() == 3 {
                break;
            }
            std::thread::sleep(Duration::from_millis(5));
        }
        assert_eq!(got, vec![1, 1, 2000], "oversized datagrams arrive whole");
        assert!(t.recv_timeout(Duration::from_millis(20)).unwrap().is_none());
        assert!(t.try_recv().unwrap().is_none(), "non-blocking again");
    }

    #[test]
    fn drain_is_bounded() {
        let peer = UdpSocket::bind("127.0.0.1:0").unwrap();
        let mut t = UdpTransport::for_device(0, peer.local_addr().unwrap()).unwrap();
        let local = t.local_addr().unwrap();
        for _ in 0..5 {
            peer.send_to(b"x", local).unwrap();
        }
        let mut total = 0;
        for _ in 0..200 {
            let n = t.drain(2, |_, _| {}).unwrap();
            assert!(n <= 2);
            total += n;
            if total == 5 {
                break;
            }
            std::thread::sleep(Duration::from_millis(2));
        }
        assert_eq!(total, 5);
    }
}
