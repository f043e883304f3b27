//! Motion errors and events as the program and the user see them: RAPID errors carrying the
//! ABB event number and title, and event-log lines naming the RAPID instruction.

use crate::interp::HostError;
use crate::interp::errnum;
use crate::motion::{MotionError, MotionEvent};
use crate::robot::KinError;
use crate::source::SourceMap;

use super::super::ControllerError;

/// `"{number} {title}: {details}"`, without repeating the title at the start of the details.
fn headline(event: Option<(u32, &str)>, title: &str, details: &str) -> String {
    let lower_title = title.to_ascii_lowercase();
    let rest = details
        .get(..lower_title.len())
        .filter(|head| head.eq_ignore_ascii_case(&lower_title))
        .and_then(|_| details.get(lower_title.len()..))
        .map(|r| r.trim_start_matches(':').trim_start())
        .filter(|r| !r.is_empty())
        .unwrap_or(details);
    match event {
        Some((n, t)) => format!("{n} {t}: {rest}"),
        None => format!("{title}: {rest}"),
    }
}

/// ` (MoveL at prog.mod:12:5)` for an event of an instruction with a known source.
fn place(event: &MotionEvent, lines: Option<&SourceMap>) -> String {
    match (&event.instr, lines) {
        (Some(i), Some(map)) => match i.source {
            Some(span) => format!(" ({} at {})", i.name, map.location(span)),
            None => format!(" ({})", i.name),
        },
        (Some(i), None) => format!(" ({})", i.name),
        _ => String::new(),
    }
}

/// One event-log line: `50024 Corner path failure: … (MoveL at prog.mod:7:5)`.
pub fn describe_event(e: &MotionEvent, lines: Option<&SourceMap>) -> String {
    let details = e.error.to_string();
    let mut s = headline(e.error.event(), e.error.title(), &details);
    s.push_str(&place(e, lines));
    s
}

/// The RAPID error for a motion error: `ERR_OUTSIDE_REACH`, `ERR_ROBLIMIT` (and
/// `ERR_ARGVALERR` for unusable motion data) can be handled by the program; anything else
/// stops it. The message starts with the ABB event number and title; when the error belongs
/// to an earlier instruction than the one running (`event`), it names that instruction.
pub fn motion_error(
    e: &MotionError,
    event: Option<&MotionEvent>,
    lines: Option<&SourceMap>,
) -> HostError {
    let mut text = headline(e.event(), e.title(), &e.to_string());
    if let Some(ev) = event {
        text.push_str(&place(ev, lines));
    }
    let errno = match e {
        MotionError::InvalidData { .. } => Some(errnum::ERR_ARGVALERR),
        _ => e
            .rapid_error_name()
            .and_then(errnum::by_name)
            .map(|d| d.num),
    };
    match errno {
        Some(n) => HostError::rapid(n, text),
        None => HostError::fatal(text),
    }
}

/// The RAPID error for a kinematic failure of `CalcJointT`, `CRobT`, `CalcRobT`.
pub fn kin_error(e: &KinError) -> HostError {
    let (n, title) = e.event();
    let text = headline(Some((n, title)), title, &e.to_string());
    match errnum::by_name(e.rapid_error_name()) {
        Some(d) => HostError::rapid(d.num, text),
        None => HostError::fatal(text),
    }
}

/// The error for a wait that ended because the robot stopped, when no event says why.
pub(super) fn stopped_error(e: ControllerError) -> HostError {
    match e {
        ControllerError::Stopped(ev) => motion_error(&ev.error, Some(&ev), None),
        other => HostError::fatal(other.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn headlines_do_not_repeat_the_title() {
        let e = KinError::OutsideReach {
            position: [1.0, 2.0, 3.0],
        };
        let h = kin_error(&e);
        assert_eq!(h.errno, Some(errnum::ERR_OUTSIDE_REACH));
        assert!(
            h.message
                .starts_with("50050 Position outside reach: flange at [1.00, 2.00, 3.00]"),
            "{}",
            h.message
        );
        let m = MotionError::CornerPathFailure { reason: "late" };
        let h = motion_error(&m, None, None);
        assert_eq!(h.errno, None);
        assert_eq!(
            h.message,
            "50024 Corner path failure: late; the fly-by point became a stop point"
        );
        let m = MotionError::InvalidData {
            what: "speeddata v_tcp (mm/s)",
            value: -1.0,
        };
        assert_eq!(
            motion_error(&m, None, None).errno,
            Some(errnum::ERR_ARGVALERR)
        );
    }
}
