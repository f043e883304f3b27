//! `rw/panel/ctrlstate`, `rw/panel/opmode` and `rw/panel/speedratio`: read and set.

use std::sync::Arc;

use axum::http::Method;

use super::repr::{Item, RwsError, State};
use super::{Answer, Outcome, Rq, Shared};
use crate::controller::service::{CtrlState, OpMode, Request};

/// `ctrlstate` text.
pub(super) fn ctrl_text(s: CtrlState) -> &'static str {
    match s {
        CtrlState::Init => "init",
        CtrlState::MotorsOff => "motoroff",
        CtrlState::MotorsOn => "motoron",
        CtrlState::GuardStop => "guardstop",
        CtrlState::EmergencyStop => "emergencystop",
        CtrlState::EmergencyStopReset => "emergencystopreset",
        CtrlState::SysFail => "sysfail",
    }
}

/// `opmode` text.
pub(super) fn opmode_text(m: OpMode) -> &'static str {
    match m {
        OpMode::Auto => "AUTO",
        OpMode::ManualReduced => "MANR",
        OpMode::ManualFull => "MANF",
    }
}

/// A speed ratio from form text: a whole number 0–100 (`50` or `50.0`).
pub(super) fn parse_ratio(text: &str) -> Result<u8, RwsError> {
    let v: f64 = text
        .trim()
        .parse()
        .map_err(|_| RwsError::bad(format!("`speed-ratio={text}` is not a number")))?;
    if !(0.0..=100.0).contains(&v) || v.fract() != 0.0 {
        return Err(RwsError::bad(format!(
            "`speed-ratio={text}`: expected a whole number from 0 to 100"
        )));
    }
    Ok(v as u8)
}

fn one(class: &str, field: &str, value: impl ToString) -> Answer {
    Answer::Ok(
        State::new("panel", "rw/panel/", field.to_string())
            .item(Item::new(class, field).field(field, value)),
    )
}

pub(super) async fn panel(shared: &Arc<Shared>, rq: &Rq, what: &str) -> Outcome {
    match (what, &rq.method, rq.action()) {
        ("ctrlstate", &Method::GET, None) => {
            let s = shared.ask(Request::CtrlState).await?;
            Ok(one("pnl-ctrlstate", "ctrlstate", ctrl_text(s)))
        }
        ("ctrlstate", &Method::POST, Some("setctrlstate")) => {
            let on = match rq.need("ctrl-state")? {
                "motoron" => true,
                "motoroff" => false,
                v => {
                    return Err(RwsError::bad(format!(
                        "`ctrl-state={v}`: expected motoron or motoroff"
                    )));
                }
            };
            shared.ask(|reply| Request::SetMotors { on, reply }).await?;
            Ok(Answer::NoContent)
        }
        ("opmode", &Method::GET, None) => {
            let m = shared.ask(Request::OpMode).await?;
            Ok(one("pnl-opmode", "opmode", opmode_text(m)))
        }
        ("opmode", &Method::POST, Some("setopmode")) => {
            let v = rq.need("opmode")?;
            let mode = match v.to_ascii_lowercase().as_str() {
                "auto" => OpMode::Auto,
                "man" | "manr" => OpMode::ManualReduced,
                "manf" => OpMode::ManualFull,
                _ => {
                    return Err(RwsError::bad(format!(
                        "`opmode={v}`: expected auto, man or manf"
                    )));
                }
            };
            shared
                .ask(|reply| Request::SetOpMode { mode, reply })
                .await?;
            Ok(Answer::NoContent)
        }
        ("speedratio", &Method::GET, None) => {
            let r = shared.ask(Request::SpeedRatio).await?;
            Ok(one("pnl-speedratio", "speedratio", r))
        }
        ("speedratio", &Method::POST, Some("setspeedratio")) => {
            let percent = parse_ratio(rq.need("speed-ratio")?)?;
            shared
                .ask(|reply| Request::SetSpeedRatio { percent, reply })
                .await?;
            Ok(Answer::NoContent)
        }
        ("ctrlstate" | "opmode" | "speedratio", _, _) => Err(rq.unknown_action()),
        _ => Err(RwsError::not_found(format!("no resource {}", rq.path))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn speed_ratios_are_whole_percentages() {
        assert_eq!(parse_ratio("50"), Ok(50));
        assert_eq!(parse_ratio("100.0"), Ok(100));
        assert!(parse_ratio("101").is_err());
        assert!(parse_ratio("-1").is_err());
        assert!(parse_ratio("12.5").is_err());
        assert!(parse_ratio("fast").is_err());
        assert!(parse_ratio("NaN").is_err());
    }
}
