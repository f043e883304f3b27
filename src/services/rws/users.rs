//! `users` (register a client), `users/rmmp` (remote mastering in manual mode), `rw/dipc`
//! (external message queues to and from RAPID's RMQ) and `logout`.

use std::sync::Arc;
use std::time::Duration;

use axum::http::{HeaderValue, Method, StatusCode, header};
use axum::response::IntoResponse;
use tokio::sync::broadcast::error::RecvError;

use super::repr::{Item, RwsError, State, codes};
use super::{Answer, Outcome, RmmpPolicy, Rq, Shared, auth};
use crate::controller::service::{DipcMessage, Event, Request};

/// The longest `timeout=` of a queue read, in seconds.
const MAX_READ_WAIT_S: f64 = 60.0;

fn empty(status: StatusCode) -> Answer {
    Answer::Raw(
        (
            status,
            [(header::CONTENT_TYPE, HeaderValue::from_static("text/plain"))],
            "",
        )
            .into_response(),
    )
}

fn no_session() -> RwsError {
    RwsError::new(
        StatusCode::UNAUTHORIZED,
        codes::UNAUTHORIZED,
        "the session has ended",
    )
}

pub(super) async fn users(shared: &Arc<Shared>, rq: &Rq, rest: &[&str]) -> Outcome {
    match (rest, &rq.method, rq.action()) {
        ([], &Method::POST, None) => {
            let fields = ["username", "application", "location", "ulocale"]
                .map(|k| rq.form(k).unwrap_or_default().to_string());
            let mut reg = shared.registry();
            let s = reg.sessions.get_mut(&rq.session).ok_or_else(no_session)?;
            s.registered = Some(fields);
            Ok(empty(StatusCode::CREATED))
        }
        ([], &Method::POST, Some("set-locale")) => match rq.need("type")? {
            "remote" => Ok(Answer::NoContent),
            "local" => Err(RwsError::new(
                StatusCode::FORBIDDEN,
                codes::NOT_ALLOWED,
                "a local login needs the enabling device of a FlexPendant, which rapidvc has not",
            )),
            t => Err(RwsError::bad(format!(
                "`type={t}`: expected local or remote"
            ))),
        },
        (["rmmp"], &Method::POST, None) => {
            let privilege = rq.need("privilege")?;
            if !matches!(privilege, "modify" | "exec") {
                return Err(RwsError::bad(format!(
                    "`privilege={privilege}`: expected modify or exec"
                )));
            }
            let mut reg = shared.registry();
            let s = reg.sessions.get_mut(&rq.session).ok_or_else(no_session)?;
            if shared.opts.rmmp == RmmpPolicy::Grant {
                s.rmmp = Some(privilege.to_string());
            }
            Ok(empty(StatusCode::ACCEPTED))
        }
        (["rmmp"], &Method::POST, Some("cancel")) => {
            let mut reg = shared.registry();
            if let Some(s) = reg.sessions.get_mut(&rq.session) {
                s.rmmp = None;
            }
            Ok(Answer::NoContent)
        }
        (["rmmp"], &Method::GET, None) => {
            let mut reg = shared.registry();
            let s = reg.sessions.get_mut(&rq.session).ok_or_else(no_session)?;
            let [alias, application, location, _] = s.registered.clone().unwrap_or_default();
            Ok(Answer::Ok(
                State::new("users", "users/", "rmmp").item(
                    Item::new("user-rmmp", "rmmp")
                        .field("userid", &rq.session)
                        .field("alias", alias)
                        .field("location", location)
                        .field("application", application)
                        .field("privilege", s.rmmp.clone().unwrap_or_else(|| "none".into()))
                        .field("rmmpheldbyme", s.rmmp.is_some()),
                ),
            ))
        }
        (["rmmp", "poll"], &Method::GET, None) => {
            let mut reg = shared.registry();
            let s = reg.sessions.get_mut(&rq.session).ok_or_else(no_session)?;
            let status = match (&s.rmmp, shared.opts.rmmp) {
                (Some(_), _) => "GRANTED",
                (None, RmmpPolicy::Deny) => "REJECTED",
                (None, RmmpPolicy::Grant) => "NONE",
            };
            Ok(Answer::Ok(
                State::new("users", "users/", "rmmp/poll").item(
                    Item::new("user-rmmp-poll", "poll")
                        .field("code", 0)
                        .field("status", status),
                ),
            ))
        }
        ([] | ["rmmp"] | ["rmmp", "poll"], _, _) => Err(rq.unknown_action()),
        _ => Err(RwsError::not_found(format!("no resource {}", rq.path))),
    }
}

/// `GET logout`: the session and its subscriptions end, the cookies are cleared.
pub(super) fn logout(shared: &Arc<Shared>, rq: &Rq) -> Outcome {
    if rq.method != Method::GET {
        return Err(rq.method_error());
    }
    {
        let mut reg = shared.registry();
        reg.sessions.close(&rq.session);
        reg.subs.close_session(&rq.session);
    }
    let mut resp = State::new("logout", "", "logout").render(rq.format, &rq.origin);
    for name in [auth::HTTP_SESSION, auth::ABBCX] {
        if let Ok(v) = HeaderValue::from_str(&format!("{name}=; path=/; Max-Age=0")) {
            resp.headers_mut().append(header::SET_COOKIE, v);
        }
    }
    Ok(Answer::Raw(resp))
}

fn number<T: std::str::FromStr>(rq: &Rq, key: &str, default: &str) -> Result<T, RwsError> {
    let v = rq.form(key).unwrap_or(default);
    v.trim()
        .parse()
        .map_err(|_| RwsError::bad(format!("`{key}={v}` is not a whole number")))
}

fn message_item(queue: &str, m: &DipcMessage) -> Item {
    Item::new("dipc-read-li", queue.to_string())
        .field("dipc-src-queue-name", &m.source)
        .field("dipc-cmd", m.cmd)
        .field("dipc-userdef", m.userdef)
        .field("dipc-msgtype", m.msgtype)
        .field("dipc-data", &m.data)
        .field("queue-name", queue)
}

pub(super) async fn dipc(shared: &Arc<Shared>, rq: &Rq, rest: &[&str]) -> Outcome {
    match (rest, &rq.method, rq.action()) {
        ([], &Method::POST, Some("dipc-create")) => {
            let queue = rq.need("dipc-queue-name")?.to_string();
            let size: u32 = number(rq, "dipc-queue-size", "4440")?;
            let max_message: u32 = number(rq, "dipc-max-msg-size", "444")?;
            let created = shared
                .ask(|reply| Request::DipcCreate {
                    queue: queue.clone(),
                    size,
                    max_message,
                    reply,
                })
                .await?;
            if created {
                Ok(empty(StatusCode::CREATED))
            } else {
                Err(RwsError::new(
                    StatusCode::BAD_REQUEST,
                    codes::DIPC_EXISTS,
                    format!("the queue `{queue}` exists"),
                ))
            }
        }
        ([target], &Method::POST, Some("dipc-send")) => {
            let message = DipcMessage {
                source: rq.need("dipc-src-queue-name")?.to_string(),
                cmd: number(rq, "dipc-cmd", "111")?,
                userdef: number(rq, "dipc-userdef", "1")?,
                msgtype: number(rq, "dipc-msgtype", "1")?,
                data: rq.need("dipc-data")?.to_string(),
            };
            let target = target.to_string();
            shared
                .ask(|reply| Request::DipcSend {
                    target,
                    message,
                    reply,
                })
                .await?;
            Ok(Answer::NoContent)
        }
        ([queue], &Method::GET, Some("dipc-read")) => {
            let wait: f64 = match rq.query("timeout") {
                None => 0.0,
                Some(t) => t
                    .parse::<f64>()
                    .ok()
                    .filter(|t| t.is_finite() && *t >= 0.0)
                    .ok_or_else(|| RwsError::bad(format!("`timeout={t}` is not a time in s")))?
                    .min(MAX_READ_WAIT_S),
            };
            let queue = queue.to_string();
            let mut st = State::new("dipc", "rw/dipc/", format!("{queue}?action=dipc-read"));
            if let Some(m) = read(shared, &queue, Duration::from_secs_f64(wait)).await? {
                st = st.item(message_item(&queue, &m));
            }
            Ok(Answer::Ok(st))
        }
        ([] | [_], _, _) => Err(rq.unknown_action()),
        _ => Err(RwsError::not_found(format!("no resource {}", rq.path))),
    }
}

/// The oldest message of `queue`, waiting up to `wait` for one to arrive.
async fn read(
    shared: &Arc<Shared>,
    queue: &str,
    wait: Duration,
) -> Result<Option<DipcMessage>, RwsError> {
    // Listen before the first read, so a message arriving in between is not missed.
    let mut events = shared.handle.subscribe();
    let deadline = tokio::time::Instant::now() + wait;
    loop {
        let q = queue.to_string();
        if let Some(m) = shared
            .ask(|reply| Request::DipcRead { queue: q, reply })
            .await?
        {
            return Ok(Some(m));
        }
        loop {
            match tokio::time::timeout_at(deadline, events.recv()).await {
                Err(_) => return Ok(None),
                Ok(Ok(Event::Dipc { queue: q, .. })) if q.eq_ignore_ascii_case(queue) => break,
                Ok(Ok(_)) => {}
                // Missed events: read again, something may have arrived.
                Ok(Err(RecvError::Lagged(_))) => break,
                Ok(Err(RecvError::Closed)) => {
                    return Err(RwsError::from(
                        crate::controller::service::ServiceError::Gone,
                    ));
                }
            }
        }
    }
}
