//! EGM event-log entries: ABB's numbers where known, rapidvc's own 90100-range otherwise.
//!
//! ABB publishes only a few EGM event numbers (41822, 41826, 41830). For conditions whose ABB
//! number is not public, rapidvc uses its own numbers in the separate range 90100–90199, so
//! they can never be mistaken for ABB events with another meaning.

use std::fmt;

/// One event-log entry: number, fixed title and a free-form detail line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EgmEvent {
    /// Event number (ABB's where known, else 901xx).
    pub number: u32,
    /// Fixed title of the event number.
    pub title: &'static str,
    /// What exactly happened.
    pub detail: String,
}

impl EgmEvent {
    /// An event of `kind` with a detail line.
    pub fn new(kind: EventKind, detail: impl Into<String>) -> Self {
        EgmEvent {
            number: kind.number(),
            title: kind.title(),
            detail: detail.into(),
        }
    }
}

impl fmt::Display for EgmEvent {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} {}: {}",
            self.number,
            self.title,
            shorten_numbers(&self.detail)
        )
    }
}

/// Longest run of digits a detail line keeps as written.
const MAX_DIGITS: usize = 15;

/// `text` with every decimal number longer than [`MAX_DIGITS`] digits (a sensor's 1e308 is
/// 309 of them in Rust's fixed form) written in exponent notation, as
/// [`crate::robot::error::msg_num`] writes it. Digits that are part of a name are kept.
fn shorten_numbers(text: &str) -> std::borrow::Cow<'_, str> {
    let b = text.as_bytes();
    let is_digit = |i: usize| b.get(i).is_some_and(u8::is_ascii_digit);
    let mut out = String::new();
    let mut copied = 0;
    let mut i = 0;
    while i < b.len() {
        let part_of_name = i > 0
            && b.get(i - 1)
                .is_some_and(|c| c.is_ascii_alphanumeric() || matches!(c, b'_' | b'.'));
        if !is_digit(i) || part_of_name {
            i += 1;
            continue;
        }
        let start = if i > 0 && b.get(i - 1) == Some(&b'-') {
            i - 1
        } else {
            i
        };
        let mut end = i;
        while is_digit(end) {
            end += 1;
        }
        if b.get(end) == Some(&b'.') && is_digit(end + 1) {
            end += 1;
            while is_digit(end) {
                end += 1;
            }
        }
        let digits = b
            .get(i..end)
            .map_or(0, |run| run.iter().filter(|c| c.is_ascii_digit()).count());
        if digits > MAX_DIGITS
            && let Some(x) = text.get(start..end).and_then(|t| t.parse::<f64>().ok())
        {
            out.push_str(text.get(copied..start).unwrap_or(""));
            out.push_str(&crate::robot::error::msg_num(x, None));
            copied = end;
        }
        i = end;
    }
    if copied == 0 {
        return std::borrow::Cow::Borrowed(text);
    }
    out.push_str(text.get(copied..).unwrap_or(""));
    std::borrow::Cow::Owned(out)
}

/// The EGM conditions rapidvc reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EventKind {
    /// 41822: no sensor data within `\CommTimeout` (ABB).
    CommTimeout,
    /// 41826: EGMRunJoint after EGMActPose or the reverse (ABB).
    ModeMismatch,
    /// 41830: sending a datagram failed (ABB).
    SendError,
    /// 90101: a datagram came from another address than the device's remote address.
    UnexpectedSender,
    /// 90102: a datagram did not decode as the mode's message.
    Malformed,
    /// 90103: a datagram was longer than the receive limit.
    Oversized,
    /// 90104: a reference held NaN/infinity or lacked a required part.
    InvalidReference,
    /// 90105: a reference was outside the configured bounds (ABB's text; number not public).
    OutOfBounds,
    /// 90106: the header's message type contradicts the mode (`CORRECTION` vs `PATH_CORRECTION`).
    WrongMessageType,
    /// 90107: the robot feedback to send was not finite; the datagram was not sent.
    FeedbackNotFinite,
    /// 90108: the one-per-cycle receive queue overflowed; the oldest message was dropped.
    QueueOverflow,
    /// 90110: MaxSpeedDeviation is limiting the EGM speed.
    SpeedLimited,
    /// 90111: MaxPosDeviation is clamping the EGM position.
    PositionClamped,
    /// 90112: the EGM command is held at an axis limit.
    AxisLimit,
    /// 90113: a speed reference was zeroed or scaled (singularity, joint speed).
    SpeedRefLimited,
    /// 90114: a signal source could not be read.
    SignalSource,
    /// 90115: the built-in sensor could not answer.
    BuiltinSensor,
    /// 90116: the UdpUc device's socket could not be opened.
    DeviceOpen,
    /// 90117: `\MaxSpeedDeviation` above the robot's slowest axis speed (EGM speeds are
    /// limited to that axis speed).
    SpeedDeviationCapped,
    /// 50452: path correction with a motion profile that is not Level 2 (ABB).
    CyclicError,
    /// 90120: a fifth EGM identity was requested in a task.
    TooManyIdentities,
    /// 90121: an EGM instruction on an identity that is not reserved.
    NotReserved,
    /// 90122: EGMAct…/EGMRun… on an identity that has no setup.
    NotSetUp,
    /// 90123: EGMRun…/EGMMove… on an identity that is not activated.
    NotActivated,
    /// 90124: an EGM argument outside its allowed values.
    ArgumentValue,
    /// 90125: a motion profile or device that does not exist or cannot be used.
    Configuration,
    /// 90126: an EGM instruction on an identity that is busy (running or streaming).
    Busy,
    /// 90127: something rapidvc does not model.
    NotSupported,
    /// 90128: an EGM movement that does not start in a fine point.
    NotInFinePoint,
    /// 90129: an EGM movement before any RAPID movement since the controller start.
    NoPreviousMove,
    /// 90130: an EGM setup or activation that cannot be used (frames, signals, trackers).
    BadSetup,
    /// 90131: a path-corrected sequence (EGMMoveL/EGMMoveC) that does not end in a fine point.
    NotEndedInFinePoint,
    /// 90132: a path correction the controller does not use (too large, too old).
    CorrectionRejected,
}

impl EventKind {
    /// The event number.
    pub fn number(self) -> u32 {
        match self {
            EventKind::CommTimeout => 41822,
            EventKind::ModeMismatch => 41826,
            EventKind::SendError => 41830,
            EventKind::UnexpectedSender => 90101,
            EventKind::Malformed => 90102,
            EventKind::Oversized => 90103,
            EventKind::InvalidReference => 90104,
            EventKind::OutOfBounds => 90105,
            EventKind::WrongMessageType => 90106,
            EventKind::FeedbackNotFinite => 90107,
            EventKind::QueueOverflow => 90108,
            EventKind::SpeedLimited => 90110,
            EventKind::PositionClamped => 90111,
            EventKind::AxisLimit => 90112,
            EventKind::SpeedRefLimited => 90113,
            EventKind::SignalSource => 90114,
            EventKind::BuiltinSensor => 90115,
            EventKind::DeviceOpen => 90116,
            EventKind::SpeedDeviationCapped => 90117,
            EventKind::CyclicError => 50452,
            EventKind::TooManyIdentities => 90120,
            EventKind::NotReserved => 90121,
            EventKind::NotSetUp => 90122,
            EventKind::NotActivated => 90123,
            EventKind::ArgumentValue => 90124,
            EventKind::Configuration => 90125,
            EventKind::Busy => 90126,
            EventKind::NotSupported => 90127,
            EventKind::NotInFinePoint => 90128,
            EventKind::NoPreviousMove => 90129,
            EventKind::BadSetup => 90130,
            EventKind::NotEndedInFinePoint => 90131,
            EventKind::CorrectionRejected => 90132,
        }
    }

    /// The fixed title.
    pub fn title(self) -> &'static str {
        match self {
            EventKind::CommTimeout => "No data from the UdpUc device",
            EventKind::ModeMismatch => "EGM mode mismatch",
            EventKind::SendError => "Error sending EGM UdpUc message",
            EventKind::UnexpectedSender => "EGM datagram from an unexpected address",
            EventKind::Malformed => "Malformed EGM datagram",
            EventKind::Oversized => "EGM datagram too large",
            EventKind::InvalidReference => "Invalid EGM reference",
            EventKind::OutOfBounds => "External Motion Interface input out of bounds",
            EventKind::WrongMessageType => "EGM message type does not match the mode",
            EventKind::FeedbackNotFinite => "EGM feedback not finite",
            EventKind::QueueOverflow => "EGM receive queue overflow",
            EventKind::SpeedLimited => "EGM speed limited by MaxSpeedDeviation",
            EventKind::PositionClamped => "EGM position clamped by MaxPosDeviation",
            EventKind::AxisLimit => "EGM command held at an axis limit",
            EventKind::SpeedRefLimited => "EGM speed reference limited",
            EventKind::SignalSource => "EGM signal source error",
            EventKind::BuiltinSensor => "Built-in EGM sensor error",
            EventKind::DeviceOpen => "EGM UdpUc device cannot be opened",
            EventKind::SpeedDeviationCapped => "EGM MaxSpeedDeviation above the axis speed",
            EventKind::CyclicError => "External Interface Cyclic Error",
            EventKind::TooManyIdentities => "Too many EGM identities",
            EventKind::NotReserved => "EGM identity not reserved",
            EventKind::NotSetUp => "EGM identity not set up",
            EventKind::NotActivated => "EGM identity not activated",
            EventKind::ArgumentValue => "EGM argument value error",
            EventKind::Configuration => "EGM configuration error",
            EventKind::Busy => "EGM identity busy",
            EventKind::NotSupported => "Not supported by rapidvc",
            EventKind::NotInFinePoint => "EGM movement not started in a fine point",
            EventKind::NoPreviousMove => "EGM movement before any RAPID movement",
            EventKind::BadSetup => "EGM setup error",
            EventKind::NotEndedInFinePoint => "EGM path correction not ended in a fine point",
            EventKind::CorrectionRejected => "EGM path correction rejected",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_numbers_in_details_are_written_with_an_exponent() {
        let huge = format!("{}", 1e308_f64);
        assert_eq!(huge.len(), 309);
        let e = EgmEvent::new(
            EventKind::OutOfBounds,
            format!("`planned.joints[0]` = {huge} is outside [-180, 180]"),
        );
        assert_eq!(
            e.to_string(),
            "90105 External Motion Interface input out of bounds: `planned.joints[0]` = 1e308 is outside [-180, 180]"
        );
        let tiny = format!("{}", -1e-300_f64);
        let e = EgmEvent::new(
            EventKind::InvalidReference,
            format!("x = {tiny}; seq 12345"),
        );
        assert_eq!(
            e.to_string(),
            "90104 Invalid EGM reference: x = -1e-300; seq 12345"
        );
        // Short numbers and digits in names stay as written.
        let text = "device sig_12345678901234567890 at 127.0.0.1:6510, 0.004 s, -2000.5";
        let e = EgmEvent::new(EventKind::Malformed, text);
        assert_eq!(
            e.to_string(),
            format!("90102 Malformed EGM datagram: {text}")
        );
    }
}
