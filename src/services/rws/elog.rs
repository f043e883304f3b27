//! The event log: `rw/elog/{domain}` (every entry, newest first unless `order=fifo`; from a
//! sequence number with `elogseqnum=`), `rw/elog/{domain}/{seq}` (one entry) and
//! `rw/elog/{domain}?action=clear`.

use std::sync::Arc;

use axum::http::Method;

use super::repr::{Item, RwsError, State};
use super::{Answer, Outcome, Rq, Shared};
use crate::controller::service::{ElogEntry, ElogSeverity, Request};

/// A time stamp as RobotWare writes it: `2024-05-01 T  12:00:00` (two spaces after the `T`,
/// which abb_robot_client's format string expects), UTC.
pub(super) fn tstamp(seconds: f64) -> String {
    let secs = if seconds.is_finite() {
        seconds.floor() as i64
    } else {
        0
    };
    chrono::DateTime::from_timestamp(secs, 0)
        .unwrap_or_default()
        .format("%Y-%m-%d T  %H:%M:%S")
        .to_string()
}

fn msgtype(s: ElogSeverity) -> u8 {
    match s {
        ElogSeverity::Info => 1,
        ElogSeverity::Warning => 2,
        ElogSeverity::Error => 3,
    }
}

fn entry_item(domain: u32, e: &ElogEntry, class: &str) -> Item {
    Item::new(class, format!("/rw/elog/{domain}/{}", e.seq))
        .link("self", format!("{domain}/{}", e.seq))
        .field("msgtype", msgtype(e.severity))
        .field("code", e.code)
        .field("src-name", "rapidvc")
        .field("tstamp", tstamp(e.timestamp))
        .field("title", &e.title)
        .field("desc", &e.description)
        .field("conseqs", "")
        .field("causes", "")
        .field("actions", "")
        .field("argc", 0)
}

fn domain_of(text: &str) -> Result<u32, RwsError> {
    text.parse()
        .map_err(|_| RwsError::not_found(format!("no event log domain `{text}`")))
}

pub(super) async fn elog(shared: &Arc<Shared>, rq: &Rq, rest: &[&str]) -> Outcome {
    match (rest, &rq.method, rq.action()) {
        ([d], &Method::GET, None) => {
            let domain = domain_of(d)?;
            let mut entries = shared.ask(|reply| Request::Elog { domain, reply }).await?;
            if let Some(from) = rq.query("elogseqnum") {
                let from: u64 = from
                    .parse()
                    .map_err(|_| RwsError::bad(format!("`elogseqnum={from}` is not a number")))?;
                entries.retain(|e| e.seq >= from);
            }
            match rq.query("order").unwrap_or("lifo") {
                "lifo" => entries.reverse(),
                "fifo" => {}
                o => return Err(RwsError::bad(format!("`order={o}`: expected lifo or fifo"))),
            }
            let mut st = State::new("Elog", "rw/elog/", domain.to_string());
            for e in &entries {
                st = st.item(entry_item(domain, e, "elog-message-li"));
            }
            Ok(Answer::Ok(st))
        }
        ([d, seq], &Method::GET, None) => {
            let domain = domain_of(d)?;
            let entries = shared.ask(|reply| Request::Elog { domain, reply }).await?;
            let e = seq
                .parse::<u64>()
                .ok()
                .and_then(|n| entries.iter().find(|e| e.seq == n))
                .ok_or_else(|| RwsError::not_found(format!("no event {domain}/{seq}")))?;
            Ok(Answer::Ok(
                State::new("Elog", "rw/elog/", format!("{domain}/{seq}")).item(entry_item(
                    domain,
                    e,
                    "elog-message",
                )),
            ))
        }
        ([d], &Method::POST, Some("clear")) => {
            let domain = domain_of(d)?;
            shared
                .ask(|reply| Request::ClearElog { domain, reply })
                .await?;
            Ok(Answer::NoContent)
        }
        ([_] | [_, _], _, _) => Err(rq.unknown_action()),
        _ => Err(RwsError::not_found(format!("no resource {}", rq.path))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_stamps_have_two_spaces_after_the_t() {
        assert_eq!(tstamp(0.0), "1970-01-01 T  00:00:00");
        assert_eq!(tstamp(1_714_564_800.7), "2024-05-01 T  12:00:00");
        assert_eq!(tstamp(f64::NAN), "1970-01-01 T  00:00:00");
    }
}
