//! RAPID sockets on the host: real TCP and UDP sockets over IPv4, one table per task.
//!
//! A RAPID program names a socket by its `socketdev` variable, which holds a [`SocketId`]
//! from this table (0: never created). Every socket is non-blocking; an instruction that must
//! wait (`SocketConnect`, `SocketAccept`, `SocketSend`, `SocketReceive`, `SocketReceiveFrom`)
//! calls the matching method again and again with a short `slice`: each call tries the
//! operation, and when it cannot complete yet, blocks at most `slice` for the socket to become
//! ready (mio, one poll per socket) and tries once more. Between the calls the interpreter
//! runs traps and notices a stop request; the instruction's `\Time` is a wall-clock
//! [`Deadline`], since the peer is a real process.
//!
//! The socket's state follows ABB's `socketstatus`: created, bound, listening, connected,
//! closed. A TCP connection the peer closed (or that broke) is noticed by the instruction that
//! reads or writes it, which fails with `ERR_SOCK_CLOSED`; from then on the socket reports
//! `SOCKET_CLOSED` until the program closes it and creates (or accepts) it again. A connect
//! that fails (refused, unreachable) leaves the socket created, on a fresh operating-system
//! socket, so an `ERROR` handler can `RETRY` it.
//!
//! Limits: at most [`MAX_SOCKETS`] sockets at a time, messages of at most [`MAX_MESSAGE`]
//! bytes (the natives check the sizes of `\Str`, `\RawData` and `\Data`).

use std::collections::HashMap;
use std::io::{self, ErrorKind, Read, Write};
use std::net::{Ipv4Addr, SocketAddr, SocketAddrV4};
use std::time::{Duration, Instant};

use mio::net::{TcpListener, TcpStream, UdpSocket};
use mio::{Events, Interest, Poll, Token};
use socket2::{Domain, Socket, Type};

/// Sockets one task may have at a time (created, bound, listening or connected).
pub const MAX_SOCKETS: usize = 32;
/// The most bytes one `SocketSend`/`SocketReceive` moves (and the size of a `rawbytes`).
pub const MAX_MESSAGE: usize = 1024;
/// The longest a socket method blocks in one call.
pub const WAIT_SLICE: Duration = Duration::from_millis(20);

/// Bytes a connection reads ahead of the program (what `SocketPeek` can report).
const READ_AHEAD: usize = 64 * 1024;
/// Pending connections a listening socket queues.
const BACKLOG: i32 = 16;
/// Ids stay below 2^24 so a `num` holds them exactly.
const MAX_ID: SocketId = 1 << 24;
const TOKEN: Token = Token(0);

/// A socket of the table; 0 is no socket.
pub type SocketId = u32;

/// ABB's `socketstatus`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SocketStatus {
    /// `SOCKET_CREATED`: created (a client, or a connect under way).
    Created,
    /// `SOCKET_CONNECTED`: a TCP connection.
    Connected,
    /// `SOCKET_BOUND`: bound to a local address.
    Bound,
    /// `SOCKET_LISTENING`: waiting for connections.
    Listening,
    /// `SOCKET_CLOSED`: never created, closed, or its connection broke.
    Closed,
}

impl SocketStatus {
    /// The RAPID constant's name.
    pub fn name(self) -> &'static str {
        match self {
            SocketStatus::Created => "SOCKET_CREATED",
            SocketStatus::Connected => "SOCKET_CONNECTED",
            SocketStatus::Bound => "SOCKET_BOUND",
            SocketStatus::Listening => "SOCKET_LISTENING",
            SocketStatus::Closed => "SOCKET_CLOSED",
        }
    }
}

/// TCP (`SocketCreate`) or UDP (`SocketCreate \UDP`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Transport {
    /// A stream socket.
    Tcp,
    /// A datagram socket.
    Udp,
}

/// Which RAPID error a socket failure is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SocketErrorKind {
    /// `ERR_SOCK_CLOSED`: not created, closed, refused, or the connection broke.
    Closed,
    /// `ERR_SOCK_TIMEOUT`: the instruction's `\Time` ran out.
    Timeout,
    /// `ERR_SOCK_ADDR_INVALID`: not an IPv4 address, or not one of this host.
    AddrInvalid,
    /// `ERR_SOCK_ADDR_INUSE`: the local address and port are taken.
    AddrInUse,
    /// `ERR_SOCK_IS_BOUND`: the socket is bound (or listens) already.
    IsBound,
    /// `ERR_SOCK_IS_CONN`: the socket is connected already.
    IsConn,
    /// `ERR_SOCK_NET_UNREACH`: no route to the network or host.
    NetUnreach,
    /// `ERR_SOCK_NOT_BOUND`: the socket must be bound (or listen) first.
    NotBound,
    /// `ERR_SOCK_NOT_CONN`: the socket must be connected first.
    NotConn,
    /// `ERR_SOCK_UNSPEC`: any other failure (limits, wrong kind of socket, the system).
    Unspec,
}

impl SocketErrorKind {
    /// The RAPID error constant (`ERRNO`) of this failure.
    pub fn err_name(self) -> &'static str {
        match self {
            SocketErrorKind::Closed => "ERR_SOCK_CLOSED",
            SocketErrorKind::Timeout => "ERR_SOCK_TIMEOUT",
            SocketErrorKind::AddrInvalid => "ERR_SOCK_ADDR_INVALID",
            SocketErrorKind::AddrInUse => "ERR_SOCK_ADDR_INUSE",
            SocketErrorKind::IsBound => "ERR_SOCK_IS_BOUND",
            SocketErrorKind::IsConn => "ERR_SOCK_IS_CONN",
            SocketErrorKind::NetUnreach => "ERR_SOCK_NET_UNREACH",
            SocketErrorKind::NotBound => "ERR_SOCK_NOT_BOUND",
            SocketErrorKind::NotConn => "ERR_SOCK_NOT_CONN",
            SocketErrorKind::Unspec => "ERR_SOCK_UNSPEC",
        }
    }
}

/// A socket failure: its RAPID error and the message for the event log.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct SocketError {
    /// Which RAPID error.
    pub kind: SocketErrorKind,
    /// What happened.
    pub message: String,
}

impl SocketError {
    /// A failure of `kind`.
    pub fn new(kind: SocketErrorKind, message: impl Into<String>) -> Self {
        SocketError {
            kind,
            message: message.into(),
        }
    }

    /// An operating-system failure while doing `what`.
    fn os(what: &str, e: &io::Error) -> Self {
        use SocketErrorKind as K;
        let (kind, why) = match e.kind() {
            ErrorKind::ConnectionRefused => (K::Closed, "refused (nothing listens there)"),
            ErrorKind::ConnectionReset
            | ErrorKind::ConnectionAborted
            | ErrorKind::BrokenPipe
            | ErrorKind::NotConnected => (K::Closed, "the connection broke"),
            ErrorKind::AddrInUse => (K::AddrInUse, "the address and port are in use"),
            ErrorKind::AddrNotAvailable => (K::AddrInvalid, "the address is not one of this host"),
            ErrorKind::NetworkUnreachable | ErrorKind::HostUnreachable => {
                (K::NetUnreach, "the network or host is unreachable")
            }
            ErrorKind::TimedOut => (K::Timeout, "timed out"),
            _ => (K::Unspec, "failed"),
        };
        SocketError::new(kind, format!("{what}: {why} ({e})"))
    }
}

fn closed() -> SocketError {
    SocketError::new(
        SocketErrorKind::Closed,
        "the socket is closed (create it with SocketCreate, or accept it with SocketAccept)",
    )
}

fn broken() -> SocketError {
    SocketError::new(
        SocketErrorKind::Closed,
        "the connection is closed (the peer closed it or it broke): close the socket with \
         SocketClose and connect or accept it again",
    )
}

fn only(transport: Transport, instruction: &str) -> SocketError {
    let msg = match transport {
        Transport::Tcp => format!(
            "{instruction} needs a TCP socket; a UDP socket (SocketCreate \\UDP) sends with \
             SocketSendTo and receives with SocketReceiveFrom"
        ),
        Transport::Udp => format!(
            "{instruction} needs a UDP socket (SocketCreate \\UDP); a TCP socket sends with \
             SocketSend and receives with SocketReceive"
        ),
    };
    SocketError::new(SocketErrorKind::Unspec, msg)
}

/// An IPv4 address as RAPID writes it (`"192.168.125.1"`); controllers take no host names.
pub fn parse_address(text: &str) -> Result<Ipv4Addr, SocketError> {
    text.parse::<Ipv4Addr>().map_err(|_| {
        SocketError::new(
            SocketErrorKind::AddrInvalid,
            format!(
                "{text:?} is not an IPv4 address (write four numbers, such as \"127.0.0.1\"; \
                 host names are not accepted)"
            ),
        )
    })
}

/// The address and port of an instruction (`SocketConnect`, `SocketBind`, `SocketSendTo`):
/// an IPv4 address and an integer port 1–65535 (0 too when `bind`: any free port).
pub fn endpoint(address: &str, port: f64, bind: bool) -> Result<SocketAddrV4, SocketError> {
    let ip = parse_address(address)?;
    let lowest = if bind { 0.0 } else { 1.0 };
    if port.fract() != 0.0 || !(lowest..=65535.0).contains(&port) {
        return Err(SocketError::new(
            SocketErrorKind::AddrInvalid,
            format!("port {port} is not an integer {lowest}–65535"),
        ));
    }
    Ok(SocketAddrV4::new(ip, port as u16))
}

/// When a blocking instruction gives up (`\Time`), on the wall clock.
#[derive(Clone, Copy, Debug)]
pub struct Deadline(Option<Instant>);

impl Deadline {
    /// `secs` seconds from now (a time beyond what the clock can hold never comes).
    pub fn after_secs(secs: f64) -> Deadline {
        let at = Duration::try_from_secs_f64(secs.max(0.0))
            .ok()
            .and_then(|d| Instant::now().checked_add(d));
        Deadline(at)
    }

    /// No deadline.
    pub fn never() -> Deadline {
        Deadline(None)
    }

    /// True once the deadline has passed.
    pub fn passed(&self) -> bool {
        self.0.is_some_and(|t| Instant::now() >= t)
    }

    /// How long the next call may block: [`WAIT_SLICE`], or less when the deadline is
    /// closer.
    pub fn slice(&self) -> Duration {
        match self.0 {
            Some(t) => t.saturating_duration_since(Instant::now()).min(WAIT_SLICE),
            None => WAIT_SLICE,
        }
    }
}

/// What a socket is doing.
#[derive(Debug)]
enum State {
    /// Created, perhaps bound; no connection or traffic yet.
    Fresh {
        sock: Socket,
        bound: Option<SocketAddrV4>,
    },
    /// A TCP connect under way.
    Connecting {
        stream: TcpStream,
        peer: SocketAddrV4,
    },
    /// A TCP connection, with what was read ahead of the program.
    Connected {
        stream: TcpStream,
        buffer: Vec<u8>,
        eof: bool,
    },
    /// A TCP socket waiting for connections.
    Listening { listener: TcpListener },
    /// A UDP socket that sent or receives (bound by `SocketBind`, or by its first send).
    Datagram { sock: UdpSocket, bound: bool },
    /// The connection broke: closed until the program closes the socket.
    Broken,
}

/// One socket and the poll it waits on.
#[derive(Debug)]
struct Entry {
    transport: Transport,
    state: State,
    poll: Poll,
    events: Events,
}

impl Entry {
    /// Block at most `slice` for the socket to become ready.
    fn wait(&mut self, slice: Duration) -> Result<(), SocketError> {
        match self.poll.poll(&mut self.events, Some(slice)) {
            Ok(()) => Ok(()),
            Err(e) if e.kind() == ErrorKind::Interrupted => Ok(()),
            Err(e) => Err(SocketError::os("waiting for the socket", &e)),
        }
    }

    /// Try `op`; when it cannot complete yet, wait at most `slice` and try once more.
    fn attempt<T>(
        &mut self,
        slice: Duration,
        mut op: impl FnMut(&mut Entry) -> Result<Option<T>, SocketError>,
    ) -> Result<Option<T>, SocketError> {
        if let Some(v) = op(self)? {
            return Ok(Some(v));
        }
        if slice.is_zero() {
            return Ok(None);
        }
        self.wait(slice)?;
        op(self)
    }

    fn register(
        &mut self,
        source: &mut impl mio::event::Source,
        interest: Interest,
    ) -> io::Result<()> {
        self.poll.registry().register(source, TOKEN, interest)
    }
}

/// The task's sockets.
#[derive(Debug)]
pub struct Sockets {
    table: HashMap<SocketId, Entry>,
    next_id: SocketId,
}

impl Default for Sockets {
    fn default() -> Self {
        Sockets {
            table: HashMap::new(),
            next_id: 1,
        }
    }
}

fn new_socket(transport: Transport) -> Result<Socket, SocketError> {
    let what = "SocketCreate";
    let ty = match transport {
        Transport::Tcp => Type::STREAM,
        Transport::Udp => Type::DGRAM,
    };
    let sock = Socket::new(Domain::IPV4, ty, None).map_err(|e| SocketError::os(what, &e))?;
    sock.set_nonblocking(true)
        .map_err(|e| SocketError::os(what, &e))?;
    if transport == Transport::Tcp {
        // A server restarted at once may bind its port again (as std's listeners do).
        sock.set_reuse_address(true)
            .map_err(|e| SocketError::os(what, &e))?;
    }
    Ok(sock)
}

fn in_progress(e: &io::Error) -> bool {
    e.kind() == ErrorKind::WouldBlock || e.raw_os_error() == Some(libc::EINPROGRESS)
}

fn v4(addr: SocketAddr) -> SocketAddrV4 {
    match addr {
        SocketAddr::V4(a) => a,
        SocketAddr::V6(a) => SocketAddrV4::new(
            a.ip().to_ipv4_mapped().unwrap_or(Ipv4Addr::UNSPECIFIED),
            a.port(),
        ),
    }
}

/// Read what the connection has into `buffer` (up to [`READ_AHEAD`]); the end of the stream
/// or a reset sets `eof`.
fn fill(stream: &mut TcpStream, buffer: &mut Vec<u8>, eof: &mut bool) {
    let mut chunk = [0u8; 4096];
    while !*eof && buffer.len() < READ_AHEAD {
        match stream.read(&mut chunk) {
            Ok(0) => *eof = true,
            Ok(n) => buffer.extend_from_slice(chunk.get(..n).unwrap_or_default()),
            Err(e) if e.kind() == ErrorKind::WouldBlock => break,
            Err(e) if e.kind() == ErrorKind::Interrupted => {}
            Err(_) => *eof = true,
        }
    }
}

impl Sockets {
    /// `SocketCreate`: a new socket.
    pub fn create(&mut self, transport: Transport) -> Result<SocketId, SocketError> {
        let id = self.free_id()?;
        let sock = new_socket(transport)?;
        let poll = Poll::new().map_err(|e| SocketError::os("SocketCreate", &e))?;
        self.table.insert(
            id,
            Entry {
                transport,
                state: State::Fresh { sock, bound: None },
                poll,
                events: Events::with_capacity(4),
            },
        );
        self.next_id += 1;
        Ok(id)
    }

    fn free_id(&self) -> Result<SocketId, SocketError> {
        if self.table.len() >= MAX_SOCKETS {
            return Err(SocketError::new(
                SocketErrorKind::Unspec,
                format!(
                    "no socket left: a task has at most {MAX_SOCKETS} sockets at a time \
                     (close the ones it no longer needs with SocketClose)"
                ),
            ));
        }
        if self.next_id >= MAX_ID {
            return Err(SocketError::new(
                SocketErrorKind::Unspec,
                "this run has created too many sockets",
            ));
        }
        Ok(self.next_id)
    }

    /// `SocketGetStatus`.
    pub fn status(&self, id: SocketId) -> SocketStatus {
        let Some(e) = self.table.get(&id) else {
            return SocketStatus::Closed;
        };
        match &e.state {
            State::Fresh { bound: None, .. } | State::Connecting { .. } => SocketStatus::Created,
            State::Fresh { bound: Some(_), .. } => SocketStatus::Bound,
            State::Connected { .. } => SocketStatus::Connected,
            State::Listening { .. } => SocketStatus::Listening,
            State::Datagram { bound: true, .. } => SocketStatus::Bound,
            State::Datagram { bound: false, .. } => SocketStatus::Created,
            State::Broken => SocketStatus::Closed,
        }
    }

    /// TCP or UDP, for a socket of the table.
    pub fn transport(&self, id: SocketId) -> Option<Transport> {
        self.table.get(&id).map(|e| e.transport)
    }

    /// The local address of a bound, listening, connected or sending socket.
    pub fn local_address(&self, id: SocketId) -> Option<SocketAddrV4> {
        let e = self.table.get(&id)?;
        let addr = match &e.state {
            State::Fresh { sock, .. } => sock.local_addr().ok()?.as_socket()?,
            State::Connecting { stream, .. } | State::Connected { stream, .. } => {
                stream.local_addr().ok()?
            }
            State::Listening { listener } => listener.local_addr().ok()?,
            State::Datagram { sock, .. } => sock.local_addr().ok()?,
            State::Broken => return None,
        };
        Some(v4(addr))
    }

    /// `SocketClose`: the socket goes away (closing a closed socket does nothing).
    pub fn close(&mut self, id: SocketId) {
        self.table.remove(&id);
    }

    fn entry(&mut self, id: SocketId) -> Result<&mut Entry, SocketError> {
        match self.table.get_mut(&id) {
            None => Err(closed()),
            Some(Entry {
                state: State::Broken,
                ..
            }) => Err(broken()),
            Some(e) => Ok(e),
        }
    }

    /// `SocketBind`: bind a created socket to a local address.
    pub fn bind(&mut self, id: SocketId, addr: SocketAddrV4) -> Result<(), SocketError> {
        let e = self.entry(id)?;
        match &mut e.state {
            State::Fresh { sock, bound } => {
                if let Some(b) = bound {
                    return Err(SocketError::new(
                        SocketErrorKind::IsBound,
                        format!("the socket is bound to {b} already"),
                    ));
                }
                sock.bind(&addr.into()).map_err(|err| {
                    let mut e = SocketError::os(&format!("SocketBind to {addr}"), &err);
                    if e.kind == SocketErrorKind::AddrInvalid {
                        // Programs written for a controller bind its LAN address.
                        e.message.push_str(
                            "; rapidvc runs on this computer: bind one of its addresses, \
                             such as \"127.0.0.1\" or \"0.0.0.0\" (every interface)",
                        );
                    }
                    e
                })?;
                let local = sock.local_addr().ok().and_then(|a| a.as_socket());
                *bound = Some(local.map_or(addr, v4));
                Ok(())
            }
            State::Listening { .. } | State::Datagram { .. } => Err(SocketError::new(
                SocketErrorKind::IsBound,
                "the socket is bound already (a UDP socket that sent is bound by its first \
                 SocketSendTo)",
            )),
            State::Connecting { .. } | State::Connected { .. } => Err(SocketError::new(
                SocketErrorKind::IsConn,
                "the socket is connected (or connecting); only a created socket can be bound",
            )),
            State::Broken => Err(broken()),
        }
    }

    /// `SocketListen`: a bound TCP socket starts to accept connections (again: nothing).
    pub fn listen(&mut self, id: SocketId) -> Result<(), SocketError> {
        let e = self.entry(id)?;
        if e.transport == Transport::Udp {
            return Err(only(Transport::Tcp, "SocketListen"));
        }
        match std::mem::replace(&mut e.state, State::Broken) {
            State::Fresh {
                sock,
                bound: Some(addr),
            } => {
                if let Err(err) = sock.listen(BACKLOG) {
                    e.state = State::Fresh {
                        sock,
                        bound: Some(addr),
                    };
                    return Err(SocketError::os(&format!("SocketListen on {addr}"), &err));
                }
                let mut listener = TcpListener::from_std(sock.into());
                e.register(&mut listener, Interest::READABLE)
                    .map_err(|err| SocketError::os("SocketListen", &err))?;
                e.state = State::Listening { listener };
                Ok(())
            }
            other => {
                let result = match &other {
                    State::Listening { .. } => Ok(()),
                    State::Fresh { bound: None, .. } => Err(SocketError::new(
                        SocketErrorKind::NotBound,
                        "the socket is not bound: SocketBind it to a local address and port first",
                    )),
                    _ => Err(SocketError::new(
                        SocketErrorKind::IsConn,
                        "the socket is connected (or connecting); only a bound socket can listen",
                    )),
                };
                e.state = other;
                result
            }
        }
    }

    /// `SocketConnect`: start or continue connecting to `peer`; true once connected. A
    /// connect that fails leaves the socket created (on a fresh system socket), so it can
    /// be tried again.
    pub fn connect(
        &mut self,
        id: SocketId,
        peer: SocketAddrV4,
        slice: Duration,
    ) -> Result<bool, SocketError> {
        let e = self.entry(id)?;
        if e.transport == Transport::Udp {
            return Err(only(Transport::Tcp, "SocketConnect"));
        }
        let what = format!("SocketConnect to {peer}");
        match &e.state {
            State::Connected { .. } => {
                return Err(SocketError::new(
                    SocketErrorKind::IsConn,
                    "the socket is connected already",
                ));
            }
            State::Listening { .. } => {
                return Err(SocketError::new(
                    SocketErrorKind::IsBound,
                    "the socket listens for connections; a listening socket cannot connect",
                ));
            }
            State::Connecting { peer: p, .. } if *p != peer => {
                // Another address than the attempt under way: start over.
                e.state = State::Fresh {
                    sock: new_socket(Transport::Tcp)?,
                    bound: None,
                };
            }
            _ => {}
        }
        if let State::Fresh { .. } = e.state {
            let State::Fresh { sock, bound } = std::mem::replace(&mut e.state, State::Broken)
            else {
                return Err(broken());
            };
            match sock.connect(&peer.into()) {
                Ok(()) => {}
                Err(err) if in_progress(&err) => {}
                Err(err) => {
                    e.state = State::Fresh {
                        sock: new_socket(Transport::Tcp)?,
                        bound: None,
                    };
                    let _ = bound;
                    return Err(SocketError::os(&what, &err));
                }
            }
            let mut stream = TcpStream::from_std(sock.into());
            e.register(&mut stream, Interest::READABLE | Interest::WRITABLE)
                .map_err(|err| SocketError::os(&what, &err))?;
            e.state = State::Connecting { stream, peer };
        }
        let done = e.attempt(slice, |e| {
            let State::Connecting { stream, .. } = &mut e.state else {
                return Ok(Some(()));
            };
            let failed = match stream.take_error() {
                Ok(Some(err)) => Some(err),
                Ok(None) => match stream.peer_addr() {
                    Ok(_) => None,
                    Err(err) if err.kind() == ErrorKind::NotConnected || in_progress(&err) => {
                        return Ok(None);
                    }
                    Err(err) => Some(err),
                },
                Err(err) => Some(err),
            };
            if let Some(err) = failed {
                e.state = State::Fresh {
                    sock: new_socket(Transport::Tcp)?,
                    bound: None,
                };
                return Err(SocketError::os(&what, &err));
            }
            if let State::Connecting { stream, .. } = std::mem::replace(&mut e.state, State::Broken)
            {
                e.state = State::Connected {
                    stream,
                    buffer: Vec::new(),
                    eof: false,
                };
            }
            Ok(Some(()))
        })?;
        Ok(done.is_some())
    }

    /// `SocketAccept`: the next connection of a listening socket, as a new connected socket
    /// with the client's address; `None` when none came within `slice`.
    pub fn accept(
        &mut self,
        id: SocketId,
        slice: Duration,
    ) -> Result<Option<(SocketId, SocketAddrV4)>, SocketError> {
        let new_id = self.free_id()?;
        let e = self.entry(id)?;
        if e.transport == Transport::Udp {
            return Err(only(Transport::Tcp, "SocketAccept"));
        }
        match &e.state {
            State::Listening { .. } => {}
            State::Fresh { bound, .. } => {
                return Err(SocketError::new(
                    SocketErrorKind::NotBound,
                    if bound.is_some() {
                        "the socket is bound but does not listen: SocketListen first"
                    } else {
                        "the socket does not listen: SocketBind and SocketListen first"
                    },
                ));
            }
            _ => {
                return Err(SocketError::new(
                    SocketErrorKind::IsConn,
                    "the socket is connected; SocketAccept needs a listening socket",
                ));
            }
        }
        let got = e.attempt(slice, |e| {
            let State::Listening { listener } = &mut e.state else {
                return Ok(None);
            };
            match listener.accept() {
                Ok(c) => Ok(Some(c)),
                Err(err)
                    if err.kind() == ErrorKind::WouldBlock
                        || err.kind() == ErrorKind::Interrupted
                        || err.kind() == ErrorKind::ConnectionAborted =>
                {
                    Ok(None)
                }
                Err(err) => Err(SocketError::os("SocketAccept", &err)),
            }
        })?;
        let Some((mut stream, addr)) = got else {
            return Ok(None);
        };
        let poll = Poll::new().map_err(|err| SocketError::os("SocketAccept", &err))?;
        let mut entry = Entry {
            transport: Transport::Tcp,
            state: State::Broken,
            poll,
            events: Events::with_capacity(4),
        };
        entry
            .register(&mut stream, Interest::READABLE | Interest::WRITABLE)
            .map_err(|err| SocketError::os("SocketAccept", &err))?;
        entry.state = State::Connected {
            stream,
            buffer: Vec::new(),
            eof: false,
        };
        self.table.insert(new_id, entry);
        self.next_id += 1;
        Ok(Some((new_id, v4(addr))))
    }

    /// `SocketSend`: write some of `data` to the connection; how many bytes went (0 when
    /// the connection could take none within `slice`).
    pub fn send(
        &mut self,
        id: SocketId,
        data: &[u8],
        slice: Duration,
    ) -> Result<usize, SocketError> {
        let e = self.entry(id)?;
        if e.transport == Transport::Udp {
            return Err(only(Transport::Tcp, "SocketSend"));
        }
        if data.is_empty() {
            return Ok(0);
        }
        let sent = e.attempt(slice, |e| {
            let State::Connected { stream, .. } = &mut e.state else {
                return Err(not_connected());
            };
            match stream.write(data) {
                Ok(n) => Ok(Some(n)),
                Err(err)
                    if err.kind() == ErrorKind::WouldBlock
                        || err.kind() == ErrorKind::Interrupted =>
                {
                    Ok(None)
                }
                Err(err) => {
                    e.state = State::Broken;
                    Err(SocketError::os("SocketSend", &err))
                }
            }
        })?;
        Ok(sent.unwrap_or(0))
    }

    /// `SocketReceive`: once the connection has at least `min` bytes, up to `max` of them;
    /// `None` while it has fewer. The end of the stream before `min` bytes is
    /// `ERR_SOCK_CLOSED` (bytes that came before it are dropped with the connection).
    pub fn receive(
        &mut self,
        id: SocketId,
        min: usize,
        max: usize,
        slice: Duration,
    ) -> Result<Option<Vec<u8>>, SocketError> {
        let e = self.entry(id)?;
        if e.transport == Transport::Udp {
            return Err(only(Transport::Tcp, "SocketReceive"));
        }
        let min = min.max(1);
        e.attempt(slice, |e| {
            let State::Connected {
                stream,
                buffer,
                eof,
            } = &mut e.state
            else {
                return Err(not_connected());
            };
            fill(stream, buffer, eof);
            if buffer.len() >= min {
                let n = max.clamp(1, buffer.len());
                return Ok(Some(buffer.drain(..n).collect()));
            }
            if *eof {
                let had = buffer.len();
                e.state = State::Broken;
                return Err(SocketError::new(
                    SocketErrorKind::Closed,
                    if had == 0 {
                        "the peer closed the connection".to_string()
                    } else {
                        format!(
                            "the peer closed the connection after {had} of the {min} bytes to \
                             read"
                        )
                    },
                ));
            }
            Ok(None)
        })
    }

    /// `SocketPeek`: how many bytes a receive would get now (TCP: read ahead so far; UDP:
    /// the size of the next datagram).
    pub fn peek(&mut self, id: SocketId) -> Result<usize, SocketError> {
        let e = self.entry(id)?;
        if e.transport == Transport::Udp {
            to_datagram(e, "SocketPeek", false)?;
            let sock = datagram(e, "SocketPeek")?;
            let mut buf = vec![0u8; 65_536];
            return match sock.peek_from(&mut buf) {
                Ok((n, _)) => Ok(n),
                Err(err)
                    if err.kind() == ErrorKind::WouldBlock
                        || err.kind() == ErrorKind::Interrupted =>
                {
                    Ok(0)
                }
                Err(err) => Err(SocketError::os("SocketPeek", &err)),
            };
        }
        let State::Connected {
            stream,
            buffer,
            eof,
        } = &mut e.state
        else {
            return Err(not_connected());
        };
        fill(stream, buffer, eof);
        if buffer.is_empty() && *eof {
            e.state = State::Broken;
            return Err(SocketError::new(
                SocketErrorKind::Closed,
                "the peer closed the connection",
            ));
        }
        Ok(buffer.len())
    }

    /// `SocketSendTo`: send one datagram; false when the socket could not take it within
    /// `slice`.
    pub fn send_to(
        &mut self,
        id: SocketId,
        peer: SocketAddrV4,
        data: &[u8],
        slice: Duration,
    ) -> Result<bool, SocketError> {
        let e = self.entry(id)?;
        if e.transport == Transport::Tcp {
            return Err(only(Transport::Udp, "SocketSendTo"));
        }
        to_datagram(e, "SocketSendTo", true)?;
        let what = format!("SocketSendTo {peer}");
        let sent = e.attempt(slice, |e| {
            let sock = datagram(e, "SocketSendTo")?;
            match sock.send_to(data, SocketAddr::V4(peer)) {
                Ok(_) => Ok(Some(())),
                Err(err)
                    if err.kind() == ErrorKind::WouldBlock
                        || err.kind() == ErrorKind::Interrupted =>
                {
                    Ok(None)
                }
                Err(err) => Err(SocketError::os(&what, &err)),
            }
        })?;
        Ok(sent.is_some())
    }

    /// `SocketReceiveFrom`: the next datagram (cut to `max` bytes) and its sender; `None`
    /// when none came within `slice`.
    pub fn receive_from(
        &mut self,
        id: SocketId,
        max: usize,
        slice: Duration,
    ) -> Result<Option<(Vec<u8>, SocketAddrV4)>, SocketError> {
        let e = self.entry(id)?;
        if e.transport == Transport::Tcp {
            return Err(only(Transport::Udp, "SocketReceiveFrom"));
        }
        to_datagram(e, "SocketReceiveFrom", false)?;
        e.attempt(slice, |e| {
            let sock = datagram(e, "SocketReceiveFrom")?;
            let mut buf = vec![0u8; max.max(1)];
            match sock.recv_from(&mut buf) {
                Ok((n, from)) => {
                    buf.truncate(n);
                    Ok(Some((buf, v4(from))))
                }
                Err(err)
                    if err.kind() == ErrorKind::WouldBlock
                        || err.kind() == ErrorKind::Interrupted =>
                {
                    Ok(None)
                }
                Err(err) => Err(SocketError::os("SocketReceiveFrom", &err)),
            }
        })
    }
}

fn not_connected() -> SocketError {
    SocketError::new(
        SocketErrorKind::NotConn,
        "the socket is not connected (SocketConnect, or SocketAccept on a listening socket, \
         connects it)",
    )
}

/// Turn a created UDP socket into one that can move datagrams; receiving needs it bound
/// (`sending`: the first send binds it to a free port).
fn to_datagram(e: &mut Entry, instruction: &str, sending: bool) -> Result<(), SocketError> {
    if !matches!(e.state, State::Fresh { .. }) {
        return Ok(());
    }
    let State::Fresh { sock, bound } = std::mem::replace(&mut e.state, State::Broken) else {
        return Err(broken());
    };
    if bound.is_none() && !sending {
        e.state = State::Fresh { sock, bound };
        return Err(SocketError::new(
            SocketErrorKind::NotBound,
            format!(
                "{instruction}: the UDP socket is not bound (SocketBind it to a local port, or \
                 send with SocketSendTo first)"
            ),
        ));
    }
    let mut udp = UdpSocket::from_std(sock.into());
    e.register(&mut udp, Interest::READABLE | Interest::WRITABLE)
        .map_err(|err| SocketError::os(instruction, &err))?;
    e.state = State::Datagram {
        sock: udp,
        bound: bound.is_some(),
    };
    Ok(())
}

fn datagram<'a>(e: &'a mut Entry, instruction: &str) -> Result<&'a mut UdpSocket, SocketError> {
    match &mut e.state {
        State::Datagram { sock, .. } => Ok(sock),
        State::Fresh { .. } => Err(SocketError::new(
            SocketErrorKind::NotBound,
            format!("{instruction}: the UDP socket is not bound"),
        )),
        _ => Err(broken()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LOCAL: Ipv4Addr = Ipv4Addr::LOCALHOST;

    fn wait_for<T>(mut f: impl FnMut() -> Result<Option<T>, SocketError>) -> T {
        let deadline = Deadline::after_secs(5.0);
        loop {
            if let Some(v) = f().unwrap() {
                return v;
            }
            assert!(!deadline.passed(), "nothing within 5 s");
        }
    }

    /// A listening server on a free port of 127.0.0.1 and a connected client.
    fn pair(s: &mut Sockets) -> (SocketId, SocketId, SocketId) {
        let server = s.create(Transport::Tcp).unwrap();
        s.bind(server, SocketAddrV4::new(LOCAL, 0)).unwrap();
        assert_eq!(s.status(server), SocketStatus::Bound);
        s.listen(server).unwrap();
        assert_eq!(s.status(server), SocketStatus::Listening);
        let addr = s.local_address(server).unwrap();
        let client = s.create(Transport::Tcp).unwrap();
        assert_eq!(s.status(client), SocketStatus::Created);
        let mut connected = false;
        let mut accepted = None;
        let deadline = Deadline::after_secs(5.0);
        while !connected || accepted.is_none() {
            if !connected {
                connected = s.connect(client, addr, WAIT_SLICE).unwrap();
            }
            if accepted.is_none() {
                accepted = s.accept(server, WAIT_SLICE).unwrap();
            }
            assert!(!deadline.passed());
        }
        let (conn, from) = accepted.unwrap();
        assert_eq!(from.ip(), &LOCAL);
        assert_eq!(s.status(client), SocketStatus::Connected);
        assert_eq!(s.status(conn), SocketStatus::Connected);
        (server, client, conn)
    }

    #[test]
    fn tcp_round_trip_and_peer_close() {
        let mut s = Sockets::default();
        let (_server, client, conn) = pair(&mut s);
        let mut sent = 0;
        while sent < 5 {
            sent += s.send(client, &b"hello"[sent..], WAIT_SLICE).unwrap();
        }
        // At least 5 bytes asked for: all five come together.
        let got = wait_for(|| s.receive(conn, 5, 1024, WAIT_SLICE));
        assert_eq!(got, b"hello");
        assert_eq!(s.peek(conn).unwrap(), 0);
        s.close(client);
        assert_eq!(s.status(client), SocketStatus::Closed);
        let err = wait_for(|| match s.receive(conn, 1, 10, WAIT_SLICE) {
            Ok(_) => Ok(None),
            Err(e) => Ok(Some(e)),
        });
        assert_eq!(err.kind, SocketErrorKind::Closed);
        assert_eq!(s.status(conn), SocketStatus::Closed);
        assert_eq!(
            s.send(conn, b"x", WAIT_SLICE).unwrap_err().kind,
            SocketErrorKind::Closed
        );
    }

    #[test]
    fn a_refused_connect_leaves_the_socket_created() {
        let mut s = Sockets::default();
        // A port nobody listens on: bind one, then give it up.
        let probe = s.create(Transport::Tcp).unwrap();
        s.bind(probe, SocketAddrV4::new(LOCAL, 0)).unwrap();
        let addr = s.local_address(probe).unwrap();
        s.close(probe);
        let c = s.create(Transport::Tcp).unwrap();
        let err = wait_for(|| match s.connect(c, addr, WAIT_SLICE) {
            Ok(true) => panic!("connected to a closed port"),
            Ok(false) => Ok(None),
            Err(e) => Ok(Some(e)),
        });
        assert_eq!(err.kind, SocketErrorKind::Closed, "{err}");
        assert!(err.message.contains("refused"), "{err}");
        assert_eq!(s.status(c), SocketStatus::Created);
    }

    #[test]
    fn states_are_checked() {
        let mut s = Sockets::default();
        let t = s.create(Transport::Tcp).unwrap();
        assert_eq!(s.listen(t).unwrap_err().kind, SocketErrorKind::NotBound);
        assert_eq!(
            s.accept(t, Duration::ZERO).unwrap_err().kind,
            SocketErrorKind::NotBound
        );
        assert_eq!(
            s.send(t, b"x", Duration::ZERO).unwrap_err().kind,
            SocketErrorKind::NotConn
        );
        s.bind(t, SocketAddrV4::new(LOCAL, 0)).unwrap();
        assert_eq!(
            s.bind(t, SocketAddrV4::new(LOCAL, 0)).unwrap_err().kind,
            SocketErrorKind::IsBound
        );
        let taken = s.local_address(t).unwrap();
        let other = s.create(Transport::Tcp).unwrap();
        s.listen(t).unwrap();
        assert_eq!(
            s.bind(other, taken).unwrap_err().kind,
            SocketErrorKind::AddrInUse
        );
        assert_eq!(
            s.receive(12345, 1, 1, Duration::ZERO).unwrap_err().kind,
            SocketErrorKind::Closed
        );
        let u = s.create(Transport::Udp).unwrap();
        assert_eq!(
            s.send(u, b"x", Duration::ZERO).unwrap_err().kind,
            SocketErrorKind::Unspec
        );
        assert_eq!(
            s.receive_from(u, 10, Duration::ZERO).unwrap_err().kind,
            SocketErrorKind::NotBound
        );
        // An address of another machine (the controller's default LAN address).
        let far = s.create(Transport::Tcp).unwrap();
        let err = s
            .bind(far, SocketAddrV4::new(Ipv4Addr::new(192, 0, 2, 1), 0))
            .unwrap_err();
        assert_eq!(err.kind, SocketErrorKind::AddrInvalid, "{err}");
        assert!(err.message.contains("127.0.0.1"), "{err}");
        assert_eq!(s.status(far), SocketStatus::Created);
        assert_eq!(
            parse_address("localhost").unwrap_err().kind,
            SocketErrorKind::AddrInvalid
        );
        assert_eq!(
            parse_address("10.0.0.7").unwrap(),
            Ipv4Addr::new(10, 0, 0, 7)
        );
    }

    #[test]
    fn udp_datagrams_keep_their_bounds() {
        let mut s = Sockets::default();
        let rx = s.create(Transport::Udp).unwrap();
        s.bind(rx, SocketAddrV4::new(LOCAL, 0)).unwrap();
        let to = s.local_address(rx).unwrap();
        let tx = s.create(Transport::Udp).unwrap();
        assert!(wait_for(|| s
            .send_to(tx, to, b"one", WAIT_SLICE)
            .map(|b| b.then_some(true))));
        assert!(wait_for(|| s
            .send_to(tx, to, b"two!", WAIT_SLICE)
            .map(|b| b.then_some(true))));
        assert_eq!(s.status(tx), SocketStatus::Created);
        let from = s.local_address(tx).unwrap();
        let start = Instant::now();
        while s.peek(rx).unwrap() == 0 {
            assert!(start.elapsed() < Duration::from_secs(5));
        }
        assert_eq!(s.peek(rx).unwrap(), 3);
        let (a, f) = wait_for(|| s.receive_from(rx, 1024, WAIT_SLICE));
        assert_eq!((a.as_slice(), f.port()), (&b"one"[..], from.port()));
        // A datagram longer than asked for is cut.
        let (b, _) = wait_for(|| s.receive_from(rx, 2, WAIT_SLICE));
        assert_eq!(b, b"tw");
    }

    #[test]
    fn a_wait_ends_within_its_slice_and_the_table_has_a_limit() {
        let mut s = Sockets::default();
        let (_server, _client, conn) = pair(&mut s);
        let start = Instant::now();
        assert_eq!(
            s.receive(conn, 1, 10, Duration::from_millis(30)).unwrap(),
            None
        );
        assert!(start.elapsed() < Duration::from_secs(2));
        let d = Deadline::after_secs(0.05);
        assert!(d.slice() <= Duration::from_millis(50));
        assert!(Deadline::after_secs(1e300).slice() == WAIT_SLICE);
        assert!(!Deadline::never().passed());
        while s.table.len() < MAX_SOCKETS {
            s.create(Transport::Udp).unwrap();
        }
        let err = s.create(Transport::Tcp).unwrap_err();
        assert_eq!(err.kind, SocketErrorKind::Unspec);
        assert!(err.message.contains("at most 32"), "{err}");
    }
}
