//! Subscriptions: `POST /subscription` (form `resources=1&1=/rw/panel/ctrlstate&1-p=1…`)
//! answers `201` with `<a href="ws://host/poll/N" rel="self">` and a `Location` header; the
//! client opens a WebSocket at `/poll/N` (subprotocol `robapi2_subscription`) and gets one
//! XHTML frame per event; `DELETE /subscription/N` ends it.
//!
//! Bounds: a subscription follows the controller's event broadcast from the moment it is
//! created, through its own cursor into the broadcast's fixed ring (so events between the
//! `POST` and the WebSocket are delivered, and a subscription costs no queue of its own). A
//! client that falls so far behind that the ring overtakes it, or that does not take a frame
//! within the send time-out, is disconnected with a close frame saying so; it may connect
//! again (abb_robot_client does). A subscription nobody connects to within the unclaimed
//! time, or whose session ends, is removed. Their number is capped.

use std::collections::HashMap;
use std::sync::Arc;
use std::time::{Duration, Instant};

use axum::Extension;
use axum::extract::ws::rejection::WebSocketUpgradeRejection;
use axum::extract::ws::{CloseFrame, Message, WebSocket, WebSocketUpgrade};
use axum::extract::{Path, State as AxState};
use axum::http::{HeaderMap, HeaderValue, Method, StatusCode, header};
use axum::response::{IntoResponse, Response};
use tokio::sync::broadcast::{self, error::RecvError};
use tokio::sync::watch;

use super::repr::{self, Format, Item, RwsError, State, codes};
use super::{Answer, Outcome, Rq, SessionId, Shared};
use crate::controller::service::{Event, Request, SymbolClass, SymbolPath};
use crate::signals::SignalKind;

/// What one resource of a subscription follows.
#[derive(Clone, Debug, PartialEq)]
enum Watch {
    CtrlState,
    OpMode,
    SpeedRatio,
    Exec,
    Cycle,
    Task(String),
    Pers {
        path: SymbolPath,
        given: String,
    },
    Signal {
        name: String,
        path: String,
        kind: SignalKind,
    },
    Elog(u32),
    Dipc(String),
}

#[derive(Debug)]
struct Sub {
    session: String,
    watches: Vec<Watch>,
    /// The cursor into the broadcast while no WebSocket holds it.
    rx: Option<broadcast::Receiver<Event>>,
    closed: watch::Sender<bool>,
    /// Since when no WebSocket is connected.
    unclaimed_since: Option<Instant>,
}

/// Every subscription, by number.
#[derive(Debug)]
pub(super) struct Subscriptions {
    map: HashMap<u64, Sub>,
    next: u64,
    max: usize,
}

impl Subscriptions {
    pub(super) fn new(max: usize) -> Subscriptions {
        Subscriptions {
            map: HashMap::new(),
            next: 1,
            max: max.max(1),
        }
    }

    fn remove(&mut self, id: u64) -> bool {
        match self.map.remove(&id) {
            Some(s) => {
                let _ = s.closed.send(true);
                true
            }
            None => false,
        }
    }

    /// End every subscription of a session.
    pub(super) fn close_session(&mut self, session: &str) {
        let ids: Vec<u64> = self
            .map
            .iter()
            .filter(|(_, s)| s.session == session)
            .map(|(k, _)| *k)
            .collect();
        for id in ids {
            self.remove(id);
        }
    }

    /// Remove the subscriptions nobody has connected to for `unclaimed`.
    pub(super) fn sweep(&mut self, unclaimed: Duration) {
        let ids: Vec<u64> = self
            .map
            .iter()
            .filter(|(_, s)| s.unclaimed_since.is_some_and(|t| t.elapsed() > unclaimed))
            .map(|(k, _)| *k)
            .collect();
        for id in ids {
            self.remove(id);
        }
    }
}

fn limit(msg: String) -> RwsError {
    RwsError::new(StatusCode::SERVICE_UNAVAILABLE, codes::LIMIT, msg)
}

/// Parse one resource URI of a subscription request.
async fn watch_of(shared: &Arc<Shared>, uri: &str, priority: u8) -> Result<Watch, RwsError> {
    let (path, attr) = uri.split_once(';').unwrap_or((uri, ""));
    let segs: Vec<&str> = path.split('/').filter(|s| !s.is_empty()).collect();
    let high_ok = matches!(
        segs.as_slice(),
        ["rw", "iosystem", ..] | ["rw", "rapid", "symbol", ..]
    );
    if priority == 2 && !high_ok {
        return Err(RwsError::bad(format!(
            "{uri}: high priority (2) is only for signals and persistents"
        )));
    }
    let w = match (segs.as_slice(), attr) {
        (["rw", "panel", "ctrlstate"], "" | "state") => Watch::CtrlState,
        (["rw", "panel", "opmode"], "" | "state") => Watch::OpMode,
        (["rw", "panel", "speedratio"], "" | "state") => Watch::SpeedRatio,
        (["rw", "rapid", "execution"], "" | "ctrlexecstate") => Watch::Exec,
        (["rw", "rapid", "execution"], "rapidexeccycle") => Watch::Cycle,
        (["rw", "rapid", "tasks", task], "excstate") => Watch::Task(task.to_string()),
        (["rw", "rapid", "symbol", "data", "RAPID", rest @ ..], "value") => {
            let p = super::symbols::symbol_path(rest)?;
            let s = shared
                .ask(|reply| Request::Symbol {
                    path: p.clone(),
                    reply,
                })
                .await?;
            if s.class != SymbolClass::Pers {
                return Err(RwsError::bad(format!(
                    "{uri}: only persistents (PERS) can be subscribed"
                )));
            }
            Watch::Pers {
                path: p,
                given: rest.join("/"),
            }
        }
        (["rw", "iosystem", "signals", rest @ ..], "state") => {
            let s = super::iosystem::find(shared, rest).await?;
            Watch::Signal {
                name: s.name.clone(),
                path: super::iosystem::signal_path(&s),
                kind: s.kind,
            }
        }
        (["rw", "elog", d], "") => Watch::Elog(
            d.parse()
                .map_err(|_| RwsError::bad(format!("{uri}: no event log domain `{d}`")))?,
        ),
        (["rw", "dipc", q], "") => Watch::Dipc(q.to_string()),
        _ => {
            return Err(RwsError::unsupported(format!(
                "a subscription to `{uri}` (see docs/rws.md for the resources)"
            )));
        }
    };
    Ok(w)
}

fn ws_origin(origin: &str) -> String {
    origin.replacen("http://", "ws://", 1)
}

pub(super) async fn subscription(shared: &Arc<Shared>, rq: &Rq, rest: &[&str]) -> Outcome {
    match (rest, &rq.method) {
        ([], &Method::POST) => create(shared, rq).await,
        ([id], &Method::DELETE) => {
            let id: u64 = id
                .parse()
                .map_err(|_| RwsError::not_found(format!("no subscription {id}")))?;
            let mut reg = shared.registry();
            let mine = reg
                .subs
                .map
                .get(&id)
                .is_some_and(|s| s.session == rq.session);
            if !mine || !reg.subs.remove(id) {
                return Err(RwsError::not_found(format!("no subscription {id}")));
            }
            drop(reg);
            Ok(Answer::Ok(State::new(
                "Event",
                "",
                format!("subscription/{id}"),
            )))
        }
        _ => Err(rq.method_error()),
    }
}

async fn create(shared: &Arc<Shared>, rq: &Rq) -> Outcome {
    let ids: Vec<&str> = rq
        .form
        .iter()
        .filter(|(k, _)| k == "resources")
        .map(|(_, v)| v.as_str())
        .collect();
    if ids.is_empty() {
        return Err(RwsError::bad(
            "no `resources=` in the form: resources=1&1=/rw/panel/ctrlstate&1-p=1",
        ));
    }
    if ids.len() > shared.opts.max_subscription_resources {
        return Err(limit(format!(
            "{} resources in one subscription; at most {}",
            ids.len(),
            shared.opts.max_subscription_resources
        )));
    }
    let mut watches = Vec::with_capacity(ids.len());
    for id in ids {
        let uri = rq
            .form(id)
            .ok_or_else(|| RwsError::bad(format!("resource {id} has no `{id}=` URI")))?;
        let p = rq.form(&format!("{id}-p")).unwrap_or("1");
        let priority = match p {
            "0" => 0,
            "1" => 1,
            "2" => 2,
            _ => return Err(RwsError::bad(format!("`{id}-p={p}`: expected 0, 1 or 2"))),
        };
        watches.push(watch_of(shared, uri, priority).await?);
    }
    let id = {
        let mut reg = shared.registry();
        if reg.subs.map.len() >= reg.subs.max {
            return Err(limit(format!(
                "{} subscriptions are open, the most rapidvc serves; delete one first",
                reg.subs.max
            )));
        }
        let id = reg.subs.next;
        reg.subs.next += 1;
        let (closed, _) = watch::channel(false);
        reg.subs.map.insert(
            id,
            Sub {
                session: rq.session.clone(),
                watches,
                rx: Some(shared.handle.subscribe()),
                closed,
                unclaimed_since: Some(Instant::now()),
            },
        );
        id
    };
    // Always XHTML: abb_robot_client finds the WebSocket link in the text even with json=1.
    let ws = format!("{}/poll/{id}", ws_origin(&rq.origin));
    let body = format!(
        "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<html xmlns=\"http://www.w3.org/1999/xhtml\">\n\
         <head>\n<title>Event</title>\n<base href=\"{origin}/\"/>\n</head>\n<body>\n<div class=\"state\">\n\
         <a href=\"subscription/{id}\" rel=\"group\"></a>\n<a href=\"{ws}\" rel=\"self\"></a>\n\
         <a href=\"subscription/{id}?action=show\" rel=\"action\"></a>\n</div>\n</body>\n</html>\n",
        origin = repr::esc(&rq.origin),
        ws = repr::esc(&ws),
    );
    let mut resp = (
        StatusCode::CREATED,
        [(header::CONTENT_TYPE, HeaderValue::from_static(repr::XHTML))],
        body,
    )
        .into_response();
    if let Ok(v) = HeaderValue::from_str(&ws) {
        resp.headers_mut().insert(header::LOCATION, v);
    }
    Ok(Answer::Raw(resp))
}

/// Gives the cursor back and counts the socket off when a WebSocket ends (or never starts).
struct Claim {
    shared: Arc<Shared>,
    id: u64,
    session: String,
}

impl Drop for Claim {
    fn drop(&mut self) {
        let fresh = self.shared.handle.subscribe();
        let mut reg = self.shared.registry();
        if let Some(s) = reg.subs.map.get_mut(&self.id) {
            s.rx = Some(fresh);
            s.unclaimed_since = Some(Instant::now());
        }
        if let Some(s) = reg.sessions.get_mut(&self.session) {
            s.sockets = s.sockets.saturating_sub(1);
        }
    }
}

/// `GET /poll/{id}`: the subscription's WebSocket.
pub(super) async fn poll(
    AxState(shared): AxState<Arc<Shared>>,
    Path(id): Path<String>,
    Extension(SessionId(session)): Extension<SessionId>,
    headers: HeaderMap,
    upgrade: Result<WebSocketUpgrade, WebSocketUpgradeRejection>,
) -> Response {
    let origin = super::origin(&headers);
    let fail = |e: RwsError| e.render(Format::Xhtml, &origin);
    let Ok(id) = id.parse::<u64>() else {
        return fail(RwsError::not_found(format!("no subscription {id}")));
    };
    let upgrade = match upgrade {
        Ok(u) => u,
        Err(e) => {
            return fail(RwsError::bad(format!(
                "/poll/{id} is a WebSocket (subprotocol robapi2_subscription): {e}"
            )));
        }
    };
    let claimed = {
        let mut reg = shared.registry();
        let got = match reg.subs.map.get_mut(&id) {
            Some(s) if s.session == session => match s.rx.take() {
                Some(rx) => {
                    s.unclaimed_since = None;
                    Ok((rx, s.watches.clone(), s.closed.subscribe()))
                }
                None => Err(RwsError::new(
                    StatusCode::CONFLICT,
                    codes::LIMIT,
                    format!("subscription {id} has a WebSocket already"),
                )),
            },
            _ => Err(RwsError::not_found(format!(
                "no subscription {id} in this session"
            ))),
        };
        if got.is_ok()
            && let Some(s) = reg.sessions.get_mut(&session)
        {
            s.sockets += 1;
        }
        got
    };
    let (rx, watches, closed) = match claimed {
        Ok(c) => c,
        Err(e) => return fail(e),
    };
    let claim = Claim {
        shared: shared.clone(),
        id,
        session,
    };
    let send_timeout = shared.opts.send_timeout;
    let group = format!("{origin}/");
    upgrade
        .protocols(["robapi2_subscription"])
        .on_upgrade(move |socket| async move {
            stream(socket, rx, watches, closed, send_timeout, id, &group).await;
            drop(claim);
        })
}

async fn close(socket: &mut WebSocket, code: u16, reason: String) {
    let _ = socket
        .send(Message::Close(Some(CloseFrame {
            code,
            reason: reason.into(),
        })))
        .await;
}

async fn stream(
    mut socket: WebSocket,
    mut rx: broadcast::Receiver<Event>,
    watches: Vec<Watch>,
    mut closed: watch::Receiver<bool>,
    send_timeout: Duration,
    id: u64,
    base: &str,
) {
    loop {
        tokio::select! {
            _ = closed.changed() => {
                close(&mut socket, 1000, format!("subscription {id} was deleted")).await;
                return;
            }
            ev = rx.recv() => match ev {
                Ok(e) => {
                    for frame in frames(&watches, &e, id, base) {
                        match tokio::time::timeout(send_timeout, socket.send(Message::Text(frame.into()))).await {
                            Ok(Ok(())) => {}
                            Ok(Err(_)) => return,
                            Err(_) => {
                                close(&mut socket, 1008, format!(
                                    "the client did not take an event within {} s", send_timeout.as_secs_f64()
                                )).await;
                                return;
                            }
                        }
                    }
                }
                Err(RecvError::Lagged(n)) => {
                    close(&mut socket, 1008, format!(
                        "{n} events were lost: the client reads more slowly than the controller changes"
                    )).await;
                    return;
                }
                Err(RecvError::Closed) => {
                    close(&mut socket, 1001, "the controller has stopped".into()).await;
                    return;
                }
            },
            msg = socket.recv() => match msg {
                None | Some(Err(_)) | Some(Ok(Message::Close(_))) => return,
                Some(Ok(_)) => {}
            },
        }
    }
}

/// The XHTML frames `event` makes for a subscription with `watches` (one per matching
/// resource), each on one line: abb_robot_client matches them with `.*`, which stops at a
/// line end.
fn frames(watches: &[Watch], event: &Event, id: u64, base: &str) -> Vec<String> {
    let mut out = Vec::new();
    for w in watches {
        let items: Vec<Item> = match (w, event) {
            (Watch::CtrlState, Event::CtrlState(s)) => vec![
                Item::new("pnl-ctrlstate-ev", "ctrlstate")
                    .link("self", "/rw/panel/ctrlstate")
                    .field("ctrlstate", super::panel::ctrl_text(*s)),
            ],
            (Watch::OpMode, Event::OpMode(m)) => vec![
                Item::new("pnl-opmode-ev", "opmode")
                    .link("self", "/rw/panel/opmode")
                    .field("opmode", super::panel::opmode_text(*m)),
            ],
            (Watch::SpeedRatio, Event::SpeedRatio(r)) => vec![
                Item::new("pnl-speedratio-ev", "speedratio")
                    .link("self", "/rw/panel/speedratio")
                    .field("speedratio", r),
            ],
            (Watch::Exec, Event::Execution { state, .. }) => vec![
                Item::new("rap-ctrlexecstate-ev", "ctrlexecstate")
                    .link("self", "/rw/rapid/execution;ctrlexecstate")
                    .field("ctrlexecstate", super::execution::exec_text(*state)),
            ],
            (Watch::Cycle, Event::Execution { cycle, .. }) => vec![
                Item::new("rap-execcycle-ev", "rapidexeccycle")
                    .link("self", "/rw/rapid/execution;rapidexeccycle")
                    .field("rapidexeccycle", super::execution::cycle_text(*cycle)),
            ],
            (Watch::Task(t), Event::Task(info)) if info.name.eq_ignore_ascii_case(t) => vec![
                Item::new("rap-execstate-ev", "execstatechange")
                    .link("self", format!("/rw/rapid/tasks/{};excstate", info.name))
                    .field("task-name", &info.name)
                    .field(
                        "pgmtaskexec-state",
                        super::execution::exc_long(info.exec_state),
                    ),
            ],
            (Watch::Pers { path, given }, Event::Pers { path: p, value })
                if p.task.eq_ignore_ascii_case(&path.task)
                    && p.name.eq_ignore_ascii_case(&path.name)
                    && path.module.as_ref().is_none_or(|m| {
                        p.module
                            .as_ref()
                            .is_some_and(|pm| pm.eq_ignore_ascii_case(m))
                    }) =>
            {
                vec![
                    Item::new("rap-value-ev", "value")
                        .link("self", format!("/rw/rapid/symbol/data/RAPID/{given};value")),
                    Item::new("rap-data", super::symbols::symburl(p)).field("value", value),
                ]
            }
            (Watch::Signal { name, path, kind }, Event::Signal { name: n, value })
                if n.eq_ignore_ascii_case(name) =>
            {
                let info = crate::controller::service::SignalInfo {
                    name: name.clone(),
                    kind: *kind,
                    value: *value,
                    network: String::new(),
                    device: String::new(),
                };
                vec![
                    Item::new("ios-signalstate-ev", name.clone())
                        .link("self", format!("/rw/iosystem/signals/{path};state"))
                        .field("lvalue", super::iosystem::lvalue_text(&info))
                        .field("lstate", "not simulated")
                        .field("quality", "good"),
                ]
            }
            (Watch::Elog(d), Event::Elog(domain, e)) if d == domain => vec![
                Item::new("elog-message-ev", "message")
                    .link("self", format!("/rw/elog/{d}/{}", e.seq))
                    .field("seqnum", e.seq),
            ],
            (Watch::Dipc(q), Event::Dipc { queue, message }) if queue.eq_ignore_ascii_case(q) => {
                vec![
                    Item::new("dipc-msg-ev", queue.clone())
                        .link("self", format!("/rw/dipc/{queue}"))
                        .field("dipc-data", &message.data)
                        .field("dipc-userdef", message.userdef)
                        .field("dipc-cmd", message.cmd)
                        .field("dipc-msgtype", message.msgtype)
                        .field("dipc-src-queue-name", &message.source),
                ]
            }
            _ => continue,
        };
        let mut f = format!(
            "<?xml version=\"1.0\" encoding=\"utf-8\"?><html xmlns=\"http://www.w3.org/1999/xhtml\">\
             <head><title>Event</title><base href=\"{}\"/></head><body><div class=\"state\">\
             <a href=\"subscription/{id}\" rel=\"group\"></a><ul>",
            repr::esc(base)
        );
        for i in &items {
            repr::item_xhtml(&mut f, i);
        }
        f.retain(|c| c != '\n');
        f.push_str("</ul></div></body></html>");
        out.push(f);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::controller::service::{ElogEntry, ElogSeverity};

    #[test]
    fn frames_match_what_the_clients_look_for() {
        let watches = vec![
            Watch::Signal {
                name: "DO1".into(),
                path: "Local/DRV_1/DO1".into(),
                kind: SignalKind::Do,
            },
            Watch::Exec,
            Watch::Pers {
                path: SymbolPath {
                    task: "T_ROB1".into(),
                    module: None,
                    name: "n".into(),
                },
                given: "T_ROB1/n".into(),
            },
            Watch::Elog(0),
        ];
        let f = frames(
            &watches,
            &Event::Signal {
                name: "do1".into(),
                value: 1.0,
            },
            3,
            "http://h/",
        );
        assert_eq!(f.len(), 1);
        let f0 = f.first().map(String::as_str).unwrap_or_default();
        assert!(f0.contains("li class=\"ios-signalstate-ev\""));
        assert!(f0.contains(
            "<a href=\"/rw/iosystem/signals/Local/DRV_1/DO1;state\" rel=\"self\"></a><span class=\"lvalue\">1</span>"
        ));
        assert!(!f0.contains('\n'));
        let p = frames(
            &watches,
            &Event::Pers {
                path: SymbolPath {
                    task: "T_ROB1".into(),
                    module: Some("M".into()),
                    name: "N".into(),
                },
                value: "[1,2]".into(),
            },
            3,
            "http://h/",
        );
        let p0 = p.first().map(String::as_str).unwrap_or_default();
        assert!(p0.contains("li class=\"rap-data\""));
        assert!(p0.contains("/rw/rapid/symbol/data/RAPID/T_ROB1/n;value\" rel=\"self\"></a>"));
        assert!(p0.contains("<span class=\"value\">[1,2]</span>"));
        let e = frames(
            &watches,
            &Event::Elog(
                0,
                ElogEntry {
                    seq: 7,
                    severity: ElogSeverity::Info,
                    code: 10010,
                    title: "t".into(),
                    description: "d".into(),
                    timestamp: 0.0,
                },
            ),
            3,
            "http://h/",
        );
        assert!(
            e.first()
                .is_some_and(|f| f.contains("<span class=\"seqnum\">7</span>"))
        );
        assert!(frames(&watches, &Event::SpeedRatio(5), 3, "http://h/").is_empty());
    }
}
