//! `rw/iosystem/signals`: every signal, one signal by name (`…/signals/{signal}`) or by
//! network and device (`…/signals/{network}/{device}/{signal}`; signals without a device are
//! under `Local/DRV_1`), read and set.

use std::sync::Arc;

use axum::http::Method;

use super::repr::{Item, RwsError, State};
use super::{Answer, Outcome, Rq, Shared};
use crate::controller::service::{Request, SignalInfo};
use crate::signals::SignalKind;

/// The logical value as RobotWare writes it: integers for digital and group signals.
pub(super) fn lvalue_text(s: &SignalInfo) -> String {
    if s.kind == SignalKind::Ai || s.kind == SignalKind::Ao {
        super::num(s.value)
    } else {
        format!("{}", s.value.round() as i64)
    }
}

/// `network/device/name`.
pub(super) fn signal_path(s: &SignalInfo) -> String {
    format!("{}/{}/{}", s.network, s.device, s.name)
}

fn signal_item(s: &SignalInfo, class: &str) -> Item {
    Item::new(class, signal_path(s))
        .link("self", format!("signals/{}", signal_path(s)))
        .field("name", &s.name)
        .field("type", s.kind.as_str())
        .field("category", "")
        .field("lvalue", lvalue_text(s))
        .field("lstate", "not simulated")
        .field("unitnm", &s.device)
}

/// A value written over RWS, checked against the signal's kind.
pub(super) fn parse_lvalue(kind: SignalKind, text: &str) -> Result<f64, RwsError> {
    let v: f64 = text
        .trim()
        .parse()
        .ok()
        .filter(|v: &f64| v.is_finite())
        .ok_or_else(|| RwsError::bad(format!("`lvalue={text}` is not a number")))?;
    match kind {
        SignalKind::Di | SignalKind::Do if v != 0.0 && v != 1.0 => Err(RwsError::bad(format!(
            "`lvalue={text}`: a digital signal is 0 or 1"
        ))),
        SignalKind::Gi | SignalKind::Go if v < 0.0 || v.fract() != 0.0 => Err(RwsError::bad(
            format!("`lvalue={text}`: a group signal is a whole number from 0"),
        )),
        _ => Ok(v),
    }
}

/// The signal named by the path segments (`[name]` or `[network, device, name]`, the last
/// possibly with `;state`), checked against its network and device.
pub(super) async fn find(shared: &Arc<Shared>, rest: &[&str]) -> Result<SignalInfo, RwsError> {
    let (net_dev, last) = match rest {
        [name] => (None, *name),
        [net, dev, name] => (Some((*net, *dev)), *name),
        _ => {
            return Err(RwsError::not_found(format!(
                "no signal resource `{}`: use signals/{{signal}} or signals/{{network}}/{{device}}/{{signal}}",
                rest.join("/")
            )));
        }
    };
    let name = last.split(';').next().unwrap_or(last).to_string();
    let s = shared
        .ask(|reply| Request::Signal {
            name: name.clone(),
            reply,
        })
        .await?;
    if let Some((net, dev)) = net_dev
        && !(s.network.eq_ignore_ascii_case(net) && s.device.eq_ignore_ascii_case(dev))
    {
        return Err(RwsError::not_found(format!(
            "the signal `{name}` is on {}/{}, not on {net}/{dev}",
            s.network, s.device
        )));
    }
    Ok(s)
}

pub(super) async fn signals(shared: &Arc<Shared>, rq: &Rq, rest: &[&str]) -> Outcome {
    match (rest, &rq.method, rq.action()) {
        ([], &Method::GET, None) => {
            let list = shared.ask(Request::Signals).await?;
            let mut st = State::new("io", "rw/iosystem/", "signals");
            for s in &list {
                st = st.item(signal_item(s, "ios-signal-li"));
            }
            Ok(Answer::Ok(st))
        }
        ([_, ..], &Method::GET, None) => {
            let s = find(shared, rest).await?;
            Ok(Answer::Ok(
                State::new("io", "rw/iosystem/", format!("signals/{}", signal_path(&s)))
                    .item(signal_item(&s, "ios-signal")),
            ))
        }
        ([_, ..], &Method::POST, Some("set")) => {
            let s = find(shared, rest).await?;
            if let Some(state) = rq.form("lstate") {
                return Err(RwsError::unsupported(format!(
                    "`lstate={state}` (simulated signals)"
                )));
            }
            let mode = rq.form("mode").unwrap_or("value");
            if mode != "value" {
                return Err(RwsError::unsupported(format!(
                    "`mode={mode}` (only mode=value)"
                )));
            }
            let value = parse_lvalue(s.kind, rq.need("lvalue")?)?;
            shared
                .ask(|reply| Request::SetSignal {
                    name: s.name.clone(),
                    value,
                    reply,
                })
                .await?;
            Ok(Answer::NoContent)
        }
        _ => Err(rq.unknown_action()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_values_fit_the_signal_kind() {
        assert_eq!(parse_lvalue(SignalKind::Do, "1"), Ok(1.0));
        assert!(parse_lvalue(SignalKind::Do, "2").is_err());
        assert!(parse_lvalue(SignalKind::Di, "on").is_err());
        assert_eq!(parse_lvalue(SignalKind::Ao, "2.5"), Ok(2.5));
        assert!(parse_lvalue(SignalKind::Ao, "inf").is_err());
        assert_eq!(parse_lvalue(SignalKind::Go, "12"), Ok(12.0));
        assert!(parse_lvalue(SignalKind::Go, "1.5").is_err());
        assert!(parse_lvalue(SignalKind::Go, "-1").is_err());
    }
}
