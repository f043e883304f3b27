//! Pure geometry of EGM position guidance: frame types, the pose-mode target pipeline (sensor pose → TCP → flange → IK nearest), convergence errors, Cartesian feedback, speed references and signal sources.
//!
//! Everything here is math over the virtual robot ([`crate::robot`]) and the I/O table
//! ([`crate::signals`]): no time, no sockets, no servo state. The motion core builds a
//! [`PoseGuidance`] once when `EGMRunPose` starts (frames frozen there) and calls it every
//! EGM cycle; the servo law itself (`egm::servo`) works on the joint vectors it returns.
//!
//! # The frame model (docs/egm.md, "Frames in pose mode"; rapidvc's documented choice)
//!
//! * `base(WORLD)` = identity, `base(BASE)` = the robot base in world, `base(WOBJ)` = user
//!   frame · object frame of `\WObj`, `base(TOOL)` = the **tool0 (flange)** pose frozen at the
//!   start of `EGMRun` (the manual's frame table says "relative to tool0"; the frame does not
//!   follow the moving robot). [`base_of`].
//! * Sensor frame `F_s = base(SensFrType) · SensorFrame`, correction frame
//!   `F_c = base(CorrFrType) · CorrFrame`, both computed once in [`PoseGuidance::new`].
//! * The sensor pose `S` is the TCP target in `F_s`: the TCP in world is `F_s · S`.
//! * `\Offset` is added on top of that target **in `F_c`**: its translation is added along
//!   the axes of `F_c`, its rotation is applied about the axes of `F_c` around the TCP point
//!   (so a pure rotation offset does not move the TCP position).
//! * Selection (`\x \y \z \rx \ry \rz` of `EGMRunPose`): directions not selected keep the value
//!   the TCP had in `F_c` at the start. Positions are chosen per component; rotations per
//!   ZYX Euler angle in `F_c` when only some rotations are selected (the same convention as
//!   signal sources and the wire), exactly the start or target orientation otherwise.
//! * The TCP target becomes a flange target ([`crate::robot::flange_target`]) and joints by
//!   IK **closest to the current joints** ([`crate::robot::Robot::ik_nearest`]); the result is
//!   supervised: outside reach, axis limits and singularities are errors carrying a
//!   [`KinError`] (→ ABB events 50050, 50027, 50026 via [`GuidanceError::event`]). A joint
//!   target beyond a limit is never returned.
//! * Only a robot-held tool with a fixed work object is supported; a stationary tool (with a
//!   robot-held work object) and a work object moved by a mechanical unit are reported as not
//!   supported.
//!
//! # Real-time notes
//!
//! Nothing here panics for any input (the lint wall below forbids `unwrap`, `expect`,
//! panicking indexing and `panic!`); NaN or infinite input gives an error. The per-cycle
//! functions do not allocate, with one accepted exception: rs-opw-kinematics' IK returns its
//! (≤ 8) solutions in a small `Vec`, so [`PoseGuidance::joint_target`] makes one small heap
//! allocation per call. Everything else (FK, the Jacobian, signal reads) stays on the stack.
#![deny(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

mod convergence;
mod pose_frames;
mod signal_sources;
mod speed_refs;

use crate::robot::KinError;
use crate::signals::{IoError, SignalKind};

pub use convergence::{Convergence, pose_error};
pub use pose_frames::{FeedbackMode, PoseGuidance, PoseSetup, base_of, feedback_in_wobj};
pub use signal_sources::SignalSource;
pub use speed_refs::{SpeedRef, SpeedRefLimit, tcp_jacobian};

/// Number of Cartesian directions (x, y, z, rx, ry, rz) and of robot axes.
pub const DIRECTIONS: usize = 6;

pub use crate::egm_args::EgmFrameType;

/// Why a guidance computation or setup failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum GuidanceError {
    /// The target is outside reach, beyond an axis limit or close to a singularity (or the
    /// joints given were not finite). [`GuidanceError::event`] gives the ABB event.
    #[error(transparent)]
    Kinematics(#[from] KinError),
    /// An input (sensor pose, frame, offset, joints, speed, signal value) is NaN or infinite.
    #[error("EGM {what} is not a finite number")]
    NotFinite {
        /// Which input.
        what: &'static str,
    },
    /// `EGM_FRAME_JOINT` given as the correction or sensor frame type of a pose-mode setup.
    #[error(
        "{which} frame type EGM_FRAME_JOINT is for joint mode; EGMActPose takes EGM_FRAME_BASE, EGM_FRAME_TOOL, EGM_FRAME_WOBJ or EGM_FRAME_WORLD"
    )]
    JointFrameInPoseMode {
        /// `"correction"` or `"sensor"`.
        which: &'static str,
    },
    /// A setup rapidvc does not model (named in the message).
    #[error("{0} is not supported by rapidvc")]
    Unsupported(&'static str),
    /// A robot-held tool with a robot-held work object (or the reverse).
    #[error(
        "tool and work object cannot be used together for EGM: a robot-held tool needs a fixed work object, a stationary tool a robot-held one"
    )]
    InconsistentFrames,
    /// A convergence window that is not `min ≤ max` with finite numbers.
    #[error("egm_minmax window for {direction} is invalid: min {min}, max {max}")]
    BadWindow {
        /// `x`, `y`, `z`, `rx`, `ry`, `rz` (or `J1`…`J6`).
        direction: &'static str,
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
    },
    /// An EGMSetupAI/AO/GI without any signal argument.
    #[error("{instruction} needs at least one signal argument")]
    NoSignals {
        /// `EGMSetupAI`, `EGMSetupAO` or `EGMSetupGI`.
        instruction: &'static str,
    },
    /// A signal of the wrong kind for the setup instruction (e.g. an AI in EGMSetupAO).
    #[error("signal `{name}` is a {found} signal, but {instruction} takes {expected} signals")]
    WrongSignalKind {
        /// Signal name.
        name: String,
        /// The setup instruction.
        instruction: &'static str,
        /// Kind the instruction takes.
        expected: SignalKind,
        /// Kind of the signal.
        found: SignalKind,
    },
    /// A signal error (unknown name or id).
    #[error(transparent)]
    Signal(#[from] IoError),
}

impl GuidanceError {
    /// The kinematic error inside, if any.
    pub fn kin_error(&self) -> Option<&KinError> {
        match self {
            GuidanceError::Kinematics(k) => Some(k),
            _ => None,
        }
    }

    /// The ABB event number and title for a run-time error: the [`KinError::event`] of a
    /// kinematic error (50050 outside reach, 50027 joint out of range, 50026 close to
    /// singularity), and 50050 for non-finite input (as [`KinError::NotFinite`]). `None` for
    /// setup errors, which the interpreter reports as RAPID errors.
    pub fn event(&self) -> Option<(u32, &'static str)> {
        match self {
            GuidanceError::Kinematics(k) => Some(k.event()),
            GuidanceError::NotFinite { .. } => Some(KinError::NotFinite.event()),
            _ => None,
        }
    }
}

/// Name of direction `i` (0 = x … 5 = rz), for messages.
pub(crate) fn direction_name(i: usize) -> &'static str {
    const NAMES: [&str; DIRECTIONS] = ["x", "y", "z", "rx", "ry", "rz"];
    NAMES.get(i).copied().unwrap_or("?")
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::panic)]

    use super::*;

    #[test]
    fn frame_type_values_match_egm_sys() {
        assert_eq!(EgmFrameType::Base.value(), 1);
        assert_eq!(EgmFrameType::Tool.value(), 2);
        assert_eq!(EgmFrameType::Wobj.value(), 3);
        assert_eq!(EgmFrameType::World.value(), 4);
        assert_eq!(EgmFrameType::Joint.value(), 5);
        for v in 1..=5u8 {
            assert_eq!(EgmFrameType::from_value(f64::from(v)).unwrap().value(), v);
        }
        assert_eq!(EgmFrameType::from_value(0.0), None);
        assert_eq!(EgmFrameType::from_value(2.5), None);
        assert_eq!(EgmFrameType::from_value(f64::NAN), None);
        assert_eq!(EgmFrameType::World.to_string(), "EGM_FRAME_WORLD");
    }

    #[test]
    fn egm_sys_declares_the_same_numbers() {
        let sys = include_str!("../../stdlib/egm.sys");
        for t in [
            EgmFrameType::Base,
            EgmFrameType::Tool,
            EgmFrameType::Wobj,
            EgmFrameType::World,
            EgmFrameType::Joint,
        ] {
            let line = format!("CONST egmframetype {} := {};", t.rapid_name(), t.value());
            assert!(sys.contains(&line), "missing `{line}` in stdlib/egm.sys");
        }
    }

    #[test]
    fn events() {
        let e = GuidanceError::from(KinError::OutsideReach { position: [0.0; 3] });
        assert_eq!(e.event(), Some((50050, "Position outside reach")));
        assert!(e.kin_error().is_some());
        let e = GuidanceError::NotFinite {
            what: "sensor pose",
        };
        assert_eq!(e.event().unwrap().0, 50050);
        assert_eq!(e.to_string(), "EGM sensor pose is not a finite number");
        assert_eq!(GuidanceError::InconsistentFrames.event(), None);
        assert_eq!(direction_name(4), "ry");
        assert_eq!(direction_name(9), "?");
    }
}
