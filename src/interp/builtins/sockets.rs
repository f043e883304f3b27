//! RAPID sockets: `SocketCreate`, `SocketConnect`, `SocketBind`, `SocketListen`,
//! `SocketAccept`, `SocketSend`, `SocketReceive`, `SocketSendTo`, `SocketReceiveFrom`,
//! `SocketClose`, `SocketGetStatus`, `SocketPeek`, on the host's socket table
//! (`crate::system::sockets`, reached through `Host::system`).
//!
//! A `socketdev` is the non-value record `[id]`: the socket's number in the table (0: never
//! created). Instructions that wait do so in slices of at most 20 ms, running traps and
//! noticing a stop request between them; `\Time` (default 60 s, `WAIT_MAX` for ever) counts
//! wall-clock seconds, since the peer is a real process. Every failure is an `ERR_SOCK_*`
//! error an `ERROR` handler can take (`system::sockets::SocketErrorKind` says which).
//! Message sizes: `\Str` up to 80 characters, `\RawData` and `\Data` up to 1024 bytes.

use super::rawbytes::{raw_of, raw_value};
use super::{Ctx, Registry};
use crate::functions::raw_bytes as rb;
use crate::interp::errnum;
use crate::interp::error::{ErrorKind, Exec, Unwind};
use crate::interp::value::{MAX_STRING, Value};
use crate::system::sockets::{
    Deadline, MAX_MESSAGE, SocketError, SocketErrorKind, SocketId, SocketStatus, Sockets,
    Transport, endpoint,
};

/// `\Time` when none is given (s).
const DEFAULT_TIME: f64 = 60.0;

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add(
        r"PROC SocketCreate(VAR socketdev Socket, \switch UDP)",
        create,
    );
    r.add(
        r"PROC SocketConnect(VAR socketdev Socket, string Address, num Port, \num Time)",
        connect,
    );
    r.add(
        r"PROC SocketBind(VAR socketdev Socket, string LocalAddress, num LocalPort)",
        |cx| {
            let id = socket_id(cx, 0)?;
            let ep = endpoint(cx.str(1)?, cx.f64(2)?, true).map_err(|e| sock_err(cx, e))?;
            with(cx, |s| s.bind(id, ep))?;
            Ok(Value::Absent)
        },
    );
    r.add(r"PROC SocketListen(VAR socketdev Socket)", |cx| {
        let id = socket_id(cx, 0)?;
        with(cx, |s| s.listen(id))?;
        Ok(Value::Absent)
    });
    r.add(
        r"PROC SocketAccept(VAR socketdev Socket, VAR socketdev ClientSocket, \VAR string ClientAddress, \num Time)",
        accept,
    );
    r.add(
        r"PROC SocketSend(VAR socketdev Socket, \string Str | VAR rawbytes RawData | byte Data{*}, \num NoOfBytes)",
        |cx| {
            let id = socket_id(cx, 0)?;
            let data = outgoing(cx, 1, 4)?;
            send_all(cx, &data, |s, rest, d| s.send(id, rest, d.slice()))
        },
    );
    r.add(
        r"PROC SocketReceive(VAR socketdev Socket, \VAR string Str | VAR rawbytes RawData | VAR byte Data{*}, \num ReadNoOfBytes, \VAR num NoRecBytes, \num Time)",
        receive,
    );
    r.add(
        r"PROC SocketSendTo(VAR socketdev Socket, string RemoteAddress, num RemotePort, \string Str | VAR rawbytes RawData | byte Data{*}, \num NoOfBytes)",
        |cx| {
            let id = socket_id(cx, 0)?;
            let ep = endpoint(cx.str(1)?, cx.f64(2)?, false).map_err(|e| sock_err(cx, e))?;
            let data = outgoing(cx, 3, 6)?;
            // One datagram: all or nothing.
            send_all(cx, &data, |s, rest, d| {
                s.send_to(id, ep, rest, d.slice())
                    .map(|sent| if sent { rest.len() } else { 0 })
            })
        },
    );
    r.add(
        r"PROC SocketReceiveFrom(VAR socketdev Socket, \VAR string Str | VAR rawbytes RawData | VAR byte Data{*}, \VAR num NoRecBytes, VAR string RemoteAddress, VAR num RemotePort, \num Time)",
        receive_from,
    );
    r.add(r"PROC SocketClose(VAR socketdev Socket)", |cx| {
        let id = socket_id(cx, 0)?;
        with(cx, |s| {
            s.close(id);
            Ok(())
        })?;
        set_id(cx, 0, 0)?;
        Ok(Value::Absent)
    });
    r.add(
        r"FUNC socketstatus SocketGetStatus(VAR socketdev Socket)",
        |cx| {
            let id = socket_id(cx, 0)?;
            let st = with(cx, |s| Ok(s.status(id)))?;
            Ok(Value::Num(status_number(st)))
        },
    );
    r.add(r"FUNC num SocketPeek(VAR socketdev Socket)", |cx| {
        let id = socket_id(cx, 0)?;
        let n = with(cx, |s| s.peek(id))?;
        Ok(Value::Num(n as f32))
    });
}

/// The `socketstatus` constants of `stdlib/socket.sys`.
fn status_number(st: SocketStatus) -> f32 {
    match st {
        SocketStatus::Created => 1.0,
        SocketStatus::Connected => 2.0,
        SocketStatus::Bound => 3.0,
        SocketStatus::Listening => 4.0,
        SocketStatus::Closed => 5.0,
    }
}

/// The socket number in `socketdev` argument `i` (0: none).
fn socket_id(cx: &Ctx<'_>, i: usize) -> Exec<SocketId> {
    let v = cx.value(i)?;
    match v.fields() {
        Some([Value::Num(x)]) if x.fract() == 0.0 && *x >= 0.0 => Ok(*x as SocketId),
        Some([Value::Num(_)]) => Ok(0),
        _ => Err(cx.it.type_bug(cx.span, "socketdev", v)),
    }
}

fn set_id(cx: &mut Ctx<'_>, i: usize, id: SocketId) -> Exec<()> {
    cx.set(i, Value::Record(Box::new([Value::Num(id as f32)])))
}

/// A socket failure as its RAPID error.
fn sock_err(cx: &Ctx<'_>, e: SocketError) -> Unwind {
    match errnum::by_name(e.kind.err_name()) {
        Some(d) => cx.error(d.num, e.message),
        None => cx.it.fatal(ErrorKind::Host, cx.span, e.message),
    }
}

/// Run `f` on the host's sockets.
fn with<T>(cx: &mut Ctx<'_>, f: impl FnOnce(&mut Sockets) -> Result<T, SocketError>) -> Exec<T> {
    let r = cx.host().system().map(|sys| f(&mut sys.sockets));
    outcome(cx, r)
}

/// [`with`] for a call that may block for up to [`crate::system::sockets::WAIT_SLICE`]:
/// the host lets its other tasks run meanwhile (`Host::system_blocking`).
fn with_blocking<T>(
    cx: &mut Ctx<'_>,
    f: impl FnOnce(&mut Sockets) -> Result<T, SocketError>,
) -> Exec<T> {
    let mut f = Some(f);
    let mut r = None;
    // The other tasks may run meanwhile: they see this task's shared persistents, and this
    // task sees what they wrote (as around any wait).
    cx.it.publish_shared();
    cx.host().system_blocking(&mut |sys| {
        if let Some(f) = f.take() {
            r = Some(f(&mut sys.sockets));
        }
    });
    cx.it.fetch_shared();
    outcome(cx, r)
}

/// The RAPID side of a sockets call: its value, its RAPID error, or "not supported" when
/// the host has no sockets (`None`).
fn outcome<T>(cx: &mut Ctx<'_>, r: Option<Result<T, SocketError>>) -> Exec<T> {
    match r {
        Some(Ok(v)) => Ok(v),
        Some(Err(e)) => Err(sock_err(cx, e)),
        None => {
            let msg = format!(
                "`{}` is not supported by this controller (it has no sockets)",
                cx.name()
            );
            Err(cx.it.fatal(ErrorKind::Unsupported, cx.span, msg))
        }
    }
}

/// Call `step` until it gives a value, running traps and noticing a stop request between
/// the calls; `ERR_SOCK_TIMEOUT` once `deadline` has passed (`time`: the `\Time` in s).
fn wait<T>(
    cx: &mut Ctx<'_>,
    deadline: Deadline,
    time: f64,
    mut step: impl FnMut(&mut Sockets, &Deadline) -> Result<Option<T>, SocketError>,
) -> Exec<T> {
    // What can be done at once (data already there, room to send) is done without waiting
    // and without handing the processor to the other tasks.
    if let Some(v) = with(cx, |s| step(s, &Deadline::after_secs(0.0)))? {
        return Ok(v);
    }
    loop {
        if let Some(v) = with_blocking(cx, |s| step(s, &deadline))? {
            return Ok(v);
        }
        if deadline.passed() {
            return Err(cx.error(
                errnum::ERR_SOCK_TIMEOUT,
                format!("{} did not complete within {time} s (\\Time)", cx.name()),
            ));
        }
        // Traps and a stop request, without letting the program's clock run; in real time
        // the run's time limit (--max-time) ends the wait as it ends any other.
        let now = cx.now();
        cx.wait_host(Some(now), 1.0, |_| Ok(false))?;
        cx.host().check_time_limit().map_err(|e| cx.host_err(e))?;
    }
}

/// Hand `data` to `step` until all of it went (`step` returns how many bytes of the rest
/// it sent).
fn send_all(
    cx: &mut Ctx<'_>,
    data: &[u8],
    mut step: impl FnMut(&mut Sockets, &[u8], &Deadline) -> Result<usize, SocketError>,
) -> Exec<Value> {
    let mut sent = 0;
    wait(cx, Deadline::never(), f64::INFINITY, |s, d| {
        let rest = data.get(sent..).unwrap_or_default();
        sent += step(s, rest, d)?;
        Ok((sent >= data.len()).then_some(()))
    })?;
    Ok(Value::Absent)
}

/// `\Time` (argument `i`): the deadline and the seconds.
fn time_arg(cx: &Ctx<'_>, i: usize) -> Exec<(Deadline, f64)> {
    let t = cx.opt_f64(i)?.unwrap_or(DEFAULT_TIME);
    if t.is_nan() || t < 0.0 {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("\\Time:={t} is not a time (0 s or more; WAIT_MAX waits for ever)"),
        ));
    }
    Ok((Deadline::after_secs(t), t))
}

fn create(cx: &mut Ctx<'_>) -> Exec<Value> {
    let old = socket_id(cx, 0)?;
    let transport = if cx.present(1) {
        Transport::Udp
    } else {
        Transport::Tcp
    };
    let id = with(cx, |s| {
        let st = s.status(old);
        if st != SocketStatus::Closed {
            return Err(SocketError::new(
                SocketErrorKind::Unspec,
                format!(
                    "the socket is created already ({}): close it with SocketClose before \
                     creating it again",
                    st.name()
                ),
            ));
        }
        // What is left of a broken connection goes.
        s.close(old);
        s.create(transport)
    })?;
    set_id(cx, 0, id)?;
    Ok(Value::Absent)
}

fn connect(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = socket_id(cx, 0)?;
    let ep = endpoint(cx.str(1)?, cx.f64(2)?, false).map_err(|e| sock_err(cx, e))?;
    let (deadline, t) = time_arg(cx, 3)?;
    wait(cx, deadline, t, |s, d| {
        s.connect(id, ep, d.slice()).map(|done| done.then_some(()))
    })?;
    Ok(Value::Absent)
}

fn accept(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = socket_id(cx, 0)?;
    let old = socket_id(cx, 1)?;
    with(cx, |s| {
        let st = s.status(old);
        if st != SocketStatus::Closed {
            return Err(SocketError::new(
                SocketErrorKind::IsConn,
                format!(
                    "the client socket is in use ({}): close it with SocketClose before \
                     accepting a connection into it",
                    st.name()
                ),
            ));
        }
        s.close(old);
        Ok(())
    })?;
    let (deadline, t) = time_arg(cx, 3)?;
    let (new, from) = wait(cx, deadline, t, |s, d| s.accept(id, d.slice()))?;
    set_id(cx, 1, new)?;
    if cx.present(2) {
        cx.set(2, Value::str(&from.ip().to_string()))?;
    }
    Ok(Value::Absent)
}

/// The bytes of `\Str | \RawData | \Data` (arguments `first` … `first + 2`), cut to
/// `\NoOfBytes` (argument `count`).
fn outgoing(cx: &Ctx<'_>, first: usize, count: usize) -> Exec<Vec<u8>> {
    let name = cx.name().to_string();
    let mut bytes = if cx.present(first) {
        let s = cx.str(first)?;
        if s.is_empty() {
            Vec::new()
        } else {
            rb::text_bytes("\\Str", s).map_err(|e| cx.rt(e))?
        }
    } else if cx.present(first + 1) {
        raw_of(cx, first + 1)?
    } else if cx.present(first + 2) {
        match cx.value(first + 2)? {
            Value::Array(a) => a
                .data
                .iter()
                .map(|v| {
                    rb::byte_of("\\Data", v.as_f64().unwrap_or(f64::NAN)).map_err(|e| cx.rt(e))
                })
                .collect::<Exec<Vec<u8>>>()?,
            other => return Err(cx.it.type_bug(cx.span, "byte array", other)),
        }
    } else {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("{name} needs the data to send: \\Str, \\RawData or \\Data"),
        ));
    };
    if let Some(n) = cx.opt_f64(count)? {
        if n.fract() != 0.0 || n < 1.0 || n > bytes.len() as f64 {
            return Err(cx.error(
                errnum::ERR_ARGVALERR,
                format!(
                    "\\NoOfBytes:={n} is not 1 to the {} bytes of the data",
                    bytes.len()
                ),
            ));
        }
        bytes.truncate(n as usize);
    }
    if bytes.len() > MAX_MESSAGE {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!(
                "{name} sends at most {MAX_MESSAGE} bytes at a time, not {}",
                bytes.len()
            ),
        ));
    }
    Ok(bytes)
}

/// Where received bytes go: `\Str | \RawData | \Data` (arguments `first` … `first + 2`).
#[derive(Clone, Copy)]
enum Sink {
    Str,
    Raw,
    Data,
}

/// The sink and how many bytes it takes (80 for a string, 1024 for `rawbytes`, the array's
/// size up to 1024 for `\Data`).
fn incoming(cx: &Ctx<'_>, first: usize) -> Exec<(Sink, usize)> {
    if cx.present(first) {
        Ok((Sink::Str, MAX_STRING))
    } else if cx.present(first + 1) {
        Ok((Sink::Raw, MAX_MESSAGE))
    } else if cx.present(first + 2) {
        match cx.value(first + 2)? {
            Value::Array(a) => Ok((Sink::Data, a.data.len().min(MAX_MESSAGE))),
            other => Err(cx.it.type_bug(cx.span, "byte array", other)),
        }
    } else {
        Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!(
                "{} needs a place for the data: \\Str, \\RawData or \\Data",
                cx.name()
            ),
        ))
    }
}

fn store(cx: &mut Ctx<'_>, first: usize, sink: Sink, bytes: &[u8]) -> Exec<()> {
    match sink {
        Sink::Str => cx.set(first, Value::str(&rb::bytes_text(bytes))),
        Sink::Raw => cx.set(first + 1, raw_value(bytes)),
        Sink::Data => {
            let mut v = cx.value(first + 2)?.clone();
            if let Value::Array(a) = &mut v {
                for (slot, b) in a.data.iter_mut().zip(bytes) {
                    *slot = Value::Num(f32::from(*b));
                }
            }
            cx.set(first + 2, v)
        }
    }
}

fn receive(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = socket_id(cx, 0)?;
    let (sink, cap) = incoming(cx, 1)?;
    let (min, max) = match cx.opt_f64(4)? {
        Some(n) if n.fract() == 0.0 && n >= 1.0 && n <= cap as f64 => (n as usize, n as usize),
        Some(n) => {
            return Err(cx.error(
                errnum::ERR_ARGVALERR,
                format!("\\ReadNoOfBytes:={n} is not 1 to the {cap} bytes the data can hold"),
            ));
        }
        None => (1, cap),
    };
    let (deadline, t) = time_arg(cx, 6)?;
    let bytes = wait(cx, deadline, t, |s, d| s.receive(id, min, max, d.slice()))?;
    store(cx, 1, sink, &bytes)?;
    if cx.present(5) {
        cx.set(5, Value::Num(bytes.len() as f32))?;
    }
    Ok(Value::Absent)
}

fn receive_from(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = socket_id(cx, 0)?;
    let (sink, cap) = incoming(cx, 1)?;
    let (deadline, t) = time_arg(cx, 7)?;
    let (bytes, from) = wait(cx, deadline, t, |s, d| s.receive_from(id, cap, d.slice()))?;
    store(cx, 1, sink, &bytes)?;
    if cx.present(4) {
        cx.set(4, Value::Num(bytes.len() as f32))?;
    }
    cx.set(5, Value::str(&from.ip().to_string()))?;
    cx.set(6, Value::Num(f32::from(from.port())))?;
    Ok(Value::Absent)
}
