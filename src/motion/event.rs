//! Motion errors and the event log entries of the motion core, with their ABB event numbers
//! and the RAPID errors a program can catch.

use std::fmt;

use crate::events::EventKind;
pub use crate::events::Severity;
use crate::robot::error::msg_num;
use crate::robot::{ConfData, KinError};
use crate::source::Span;

use crate::time::RobotTime;

/// Which RAPID instruction a segment, an event or a trace row belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct InstrRef {
    /// The command id the interpreter gave it.
    pub id: u64,
    /// `MoveJ`, `MoveL`, …
    pub name: &'static str,
    /// The RAPID instruction.
    pub source: Option<Span>,
}

/// Where on a move the planner found a problem.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PathPlace {
    /// At the programmed target.
    Target,
    /// At the circle point of a MoveC.
    CirPoint,
    /// On the way, at this share of the path (0…1).
    Along(f64),
    /// In the corner path towards this move.
    Corner,
    /// Found by the per-cycle supervision while moving.
    Cycle,
}

impl fmt::Display for PathPlace {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PathPlace::Target => f.write_str("at the target"),
            PathPlace::CirPoint => f.write_str("at the circle point"),
            PathPlace::Along(s) => write!(f, "at {} % of the path", msg_num(s * 100.0, Some(0))),
            PathPlace::Corner => f.write_str("in the corner path"),
            PathPlace::Cycle => f.write_str("while moving"),
        }
    }
}

/// Why the motion core refused, stopped or warned about a move.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MotionError {
    /// A pose is unreachable, an axis leaves its range, or the path meets a singularity.
    #[error("{error} ({place})")]
    Kinematics {
        /// What the kinematics reported.
        error: KinError,
        /// Where.
        place: PathPlace,
    },
    /// ConfL\On: the straight path ends in another arm configuration than the programmed one.
    #[error(
        "the linear path reaches the target in configuration {reached}, not the programmed {wanted} (use ConfL\\Off, MoveJ, or correct the robconf)"
    )]
    ConfigurationChanged {
        /// The programmed confdata.
        wanted: ConfData,
        /// What the path ends in.
        reached: ConfData,
    },
    /// MoveC: start, circle point and target do not define a circle.
    #[error("circle uncertain: {reason}")]
    CircleUncertain {
        /// What is wrong with the three points.
        reason: &'static str,
    },
    /// A fly-by point became a stop point because the next move was not planned in time
    /// (or its corner path could not be built).
    #[error("corner path failure: {reason}; the fly-by point became a stop point")]
    CornerPathFailure {
        /// Why.
        reason: &'static str,
    },
    /// An axis would exceed its maximum speed (per-cycle supervision).
    #[error(
        "joint {joint} speed {}°/s exceeds its maximum {}°/s",
        msg_num(*speed, Some(1)), msg_num(*max, Some(1))
    )]
    JointSpeed {
        /// Axis number, 1-based.
        joint: usize,
        /// The speed asked for (deg/s).
        speed: f64,
        /// The model's maximum (deg/s).
        max: f64,
    },
    /// An argument of the move is not usable.
    #[error("invalid {what}: {}", msg_num(*value, None))]
    InvalidData {
        /// Which argument.
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// A feature rapidvc does not implement.
    #[error("{what} is not supported by rapidvc")]
    NotSupported {
        /// What.
        what: &'static str,
    },
    /// The motion core stopped after an error and takes no moves until it is recovered.
    #[error("motion is stopped after an error")]
    Halted,
    /// The robot is under external guidance (EGM); planned moves wait until it ends.
    #[error("the robot is under external guidance")]
    ExternalGuidance,
    /// External guidance may only start at a stop point.
    #[error("external guidance must start at a fine point (the robot is moving)")]
    NotAtStopPoint,
    /// Path correction stopped the robot (`motion::correction`): the sensor stopped
    /// answering, a corrected sequence that does not end in a fine point, … The event
    /// comes from the correction's owner (EGM).
    #[error("{detail}")]
    PathCorrection {
        /// Event-log number.
        number: u32,
        /// Event-log title.
        title: &'static str,
        /// What happened.
        detail: String,
        /// The RAPID error a handler can catch (`ERR_UDPUC_COMM`), if any.
        rapid_error: Option<&'static str>,
    },
    /// Not an error: a position event of a move fired in this cycle (`TriggIO`, `MoveLDO`,
    /// …); `key` is the one its caller gave ([`crate::robot::trigger::PathTrigger`]).
    #[error("position event {key}")]
    Trigger {
        /// The caller's key.
        key: u64,
    },
}

impl MotionError {
    /// The ABB event log number and title where one is known (docs/robot.md, "Errors and events"). Events without a
    /// verified ABB number return `None`.
    ///
    /// * kinematics: [`KinError::event`] (50050, 50027, 50026);
    /// * a configuration change under ConfL\On: 50050 "Position outside reach" (as
    ///   `KinError::ConfigurationUnreachable`);
    /// * corner path failure: 50024;
    /// * circle uncertain: 50063 (ABB's number as remembered, **unverified**).
    pub fn event(&self) -> Option<(u32, &'static str)> {
        let kind = match self {
            MotionError::Kinematics { error, .. } => error.event_kind(),
            MotionError::ConfigurationChanged { .. } => EventKind::OutsideReach,
            MotionError::CircleUncertain { .. } => EventKind::CircleUncertain,
            MotionError::CornerPathFailure { .. } => EventKind::CornerPathFailure,
            MotionError::PathCorrection { number, title, .. } => return Some((*number, title)),
            MotionError::JointSpeed { .. } | MotionError::Trigger { .. } => return None,
            MotionError::InvalidData { .. }
            | MotionError::NotSupported { .. }
            | MotionError::Halted
            | MotionError::ExternalGuidance
            | MotionError::NotAtStopPoint => return None,
        };
        Some((kind.number(), kind.title()))
    }

    /// The RAPID error an `ERROR` handler can catch, where one applies.
    pub fn rapid_error_name(&self) -> Option<&'static str> {
        match self {
            MotionError::Kinematics { error, .. } => Some(error.rapid_error_name()),
            MotionError::ConfigurationChanged { .. } | MotionError::JointSpeed { .. } => {
                Some("ERR_ROBLIMIT")
            }
            MotionError::PathCorrection { rapid_error, .. } => *rapid_error,
            _ => None,
        }
    }

    /// A short title for logs: the ABB title when there is one.
    pub fn title(&self) -> &'static str {
        match self.event() {
            Some((_, title)) => title,
            None => match self {
                MotionError::JointSpeed { .. } => "Joint speed error",
                MotionError::InvalidData { .. } => "Invalid motion data",
                MotionError::NotSupported { .. } => "Not supported",
                MotionError::Halted => "Motion stopped",
                MotionError::ExternalGuidance => "External guidance active",
                MotionError::NotAtStopPoint => "Not in a stop point",
                MotionError::Trigger { .. } => "Position event",
                _ => "Motion error",
            },
        }
    }
}

/// One entry of the motion core's event log.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionEvent {
    /// When (robot time).
    pub time: RobotTime,
    /// How serious.
    pub severity: Severity,
    /// The instruction concerned.
    pub instr: Option<InstrRef>,
    /// What happened.
    pub error: MotionError,
}

impl fmt::Display for MotionEvent {
    /// `50050 Position outside reach: … (MoveL #12)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some((number, title)) = self.error.event() {
            write!(f, "{number} {title}: {}", self.error)?;
        } else {
            write!(f, "{}: {}", self.error.title(), self.error)?;
        }
        if let Some(i) = &self.instr {
            write!(f, " ({} #{})", i.name, i.id)?;
        }
        Ok(())
    }
}

/// A bounded event log that never allocates once created: when it is full, new events are
/// counted and dropped (old ones are kept, since the first error is the one that matters).
#[derive(Debug)]
pub struct EventLog {
    items: std::collections::VecDeque<MotionEvent>,
    capacity: usize,
    dropped: u64,
    total: u64,
}

impl EventLog {
    /// A log holding up to `capacity` events.
    pub fn with_capacity(capacity: usize) -> EventLog {
        EventLog {
            items: std::collections::VecDeque::with_capacity(capacity.max(1)),
            capacity: capacity.max(1),
            dropped: 0,
            total: 0,
        }
    }

    /// Record an event (dropped and counted when the log is full).
    pub fn push(&mut self, e: MotionEvent) {
        self.total = self.total.saturating_add(1);
        if self.items.len() < self.capacity {
            self.items.push_back(e);
        } else {
            self.dropped = self.dropped.saturating_add(1);
        }
    }

    /// Take the oldest event.
    pub fn pop(&mut self) -> Option<MotionEvent> {
        self.items.pop_front()
    }

    /// The events not yet taken, oldest first.
    pub fn iter(&self) -> impl Iterator<Item = &MotionEvent> {
        self.items.iter()
    }

    /// Events dropped because the log was full.
    pub fn dropped(&self) -> u64 {
        self.dropped
    }

    /// Events ever recorded (taken, pending or dropped).
    pub fn total(&self) -> u64 {
        self.total
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn huge_numbers_are_written_with_an_exponent() {
        let e = MotionError::InvalidData {
            what: "speeddata v_tcp (mm/s)",
            value: 1e308,
        };
        assert_eq!(e.to_string(), "invalid speeddata v_tcp (mm/s): 1e308");
        let e = MotionError::JointSpeed {
            joint: 2,
            speed: 3e38,
            max: 175.0,
        };
        assert_eq!(
            e.to_string(),
            "joint 2 speed 3e38°/s exceeds its maximum 175.0°/s"
        );
        assert_eq!(PathPlace::Along(0.32).to_string(), "at 32 % of the path");
    }
}
