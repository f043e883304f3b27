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
        write!(f, "{} {}: {}", self.number, self.title, self.detail)
    }
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
        }
    }
}
