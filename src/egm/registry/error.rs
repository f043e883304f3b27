//! `EgmError`: every way an EGM instruction or an EGM run can fail, with its event-log entry and, where a RAPID `ERROR` handler can catch it, the RAPID error name.
//!
//! The interpreter maps an error to RAPID as follows: [`EgmError::rapid_error`] `Some(name)`
//! → raise that `ERRNO` (recoverable in normal mode; always fatal after `\NoWaitCond`, which
//! the interpreter knows); `None` → a fatal execution error that stops the program. In both
//! cases [`EgmError::event`] is the event-log entry to show (ABB's number where one is
//! public, rapidvc's 901xx otherwise; see [`crate::egm::event`]).

use std::time::Duration;

use super::configuration::{DeviceError, UnknownProfile};
use crate::egm::event::{EgmEvent, EventKind};
use crate::egm::geometry::GuidanceError;
use crate::egm::latency::fmt_duration;
use crate::egm::servo::ServoError;

/// The RAPID error of every UdpUc communication failure.
pub const ERR_UDPUC_COMM: &str = "ERR_UDPUC_COMM";

/// Why an EGM instruction was refused or an EGM run ended with an error.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EgmError {
    /// EGMGetId with all identities of the task in use.
    #[error(
        "EGMGetId {name}: at most {max} EGM identities can be reserved per task ({in_use} are reserved); release one with EGMReset"
    )]
    TooManyIdentities {
        /// The variable asking.
        name: String,
        /// The limit (4).
        max: usize,
        /// The names in use, comma-separated.
        in_use: String,
    },
    /// An instruction on an identity that is not reserved (never, or released by EGMReset).
    #[error("{instruction}: the EGM identity is not reserved; call EGMGetId first")]
    NotReserved {
        /// The instruction.
        instruction: &'static str,
    },
    /// EGMAct…/EGMRun…/EGMStreamStart/EGMMove… before any setup.
    #[error(
        "{instruction} {name}: the identity has no data source; run EGMSetupUC, EGMSetupAI, EGMSetupAO, EGMSetupGI or EGMSetupLTAPP first"
    )]
    NotSetUp {
        /// The identity's variable name.
        name: String,
        /// The instruction.
        instruction: &'static str,
    },
    /// EGMRun…/EGMMove… before the activation it needs.
    #[error("{instruction} {name}: the identity is not activated; run {needs} first")]
    NotActivated {
        /// The identity's variable name.
        name: String,
        /// The instruction.
        instruction: &'static str,
        /// The activation instruction(s) it needs.
        needs: &'static str,
    },
    /// 41826: the instruction does not fit the setup or the activation.
    #[error("{instruction} {name}: {detail}")]
    ModeMismatch {
        /// The identity's variable name.
        name: String,
        /// The instruction.
        instruction: &'static str,
        /// What does not fit.
        detail: String,
    },
    /// A `\SampleRate` that is not a positive multiple of 4 ms (24 ms for EGMActMove).
    #[error(
        "{instruction}: \\SampleRate:={value} is not allowed; use a multiple of {multiple} ms ({multiple}, {}, {}, …)",
        multiple * 2,
        multiple * 3
    )]
    SampleRate {
        /// The instruction.
        instruction: &'static str,
        /// The value given, ms.
        value: f64,
        /// The required multiple, ms.
        multiple: u64,
    },
    /// A numeric argument outside its allowed range, or not a number.
    #[error("{instruction}: {argument} = {value} is not allowed; it must be {range}")]
    Argument {
        /// The instruction.
        instruction: &'static str,
        /// The argument, as written in RAPID (`\CondTime`).
        argument: &'static str,
        /// The value.
        value: f64,
        /// The allowed values, in words.
        range: &'static str,
    },
    /// An argument combination the instruction does not take.
    #[error("{instruction}: {detail}")]
    BadSetup {
        /// The instruction.
        instruction: &'static str,
        /// What is wrong.
        detail: String,
    },
    /// ExtConfigName names no External Motion Interface Data profile.
    #[error("{instruction}: {source}")]
    UnknownProfile {
        /// The instruction.
        instruction: &'static str,
        /// The profiles that exist.
        source: UnknownProfile,
    },
    /// The device cannot be used (not configured, unsupported type).
    #[error("{instruction}: {source}")]
    Device {
        /// The instruction.
        instruction: &'static str,
        /// Why.
        source: DeviceError,
    },
    /// The built-in sensor's pattern or a simulated seam does not fit the setup.
    #[error("{instruction}: device \"{device}\": {detail}")]
    BadDevice {
        /// The instruction.
        instruction: &'static str,
        /// The device name.
        device: String,
        /// What is wrong.
        detail: String,
    },
    /// 50452: path correction with a motion profile that is not Level 2.
    #[error(
        "{instruction} {name}: path correction needs an External Motion Interface Data profile of Level 2, but \"{profile}\" has Level {level}; define one in MOC.cfg (`-name \"pathCorr\" -ext_motion_level 2`)"
    )]
    PathCorrLevel {
        /// The identity's variable name.
        name: String,
        /// The instruction.
        instruction: &'static str,
        /// The profile name.
        profile: String,
        /// Its level.
        level: u8,
    },
    /// The identity is running or streaming and the instruction cannot change that.
    #[error("{instruction} {name}: the identity is {activity}")]
    Busy {
        /// The identity's variable name.
        name: String,
        /// The instruction.
        instruction: &'static str,
        /// What it is doing ("running EGMRunJoint", "streaming").
        activity: &'static str,
    },
    /// Something rapidvc does not model (named).
    #[error("{instruction}: {what} is not supported by rapidvc")]
    Unsupported {
        /// The instruction.
        instruction: &'static str,
        /// What.
        what: &'static str,
    },
    /// A setup, activation or start the guidance geometry refuses (frames, signals, tools).
    #[error("{instruction}: {source}")]
    Guidance {
        /// The instruction.
        instruction: &'static str,
        /// Why.
        source: GuidanceError,
    },
    /// An EGM movement that does not start in a fine point (checked by the controller).
    #[error(
        "{instruction}: an EGM movement must start in a fine point; end the movement before it with `fine`"
    )]
    NotInFinePoint {
        /// The instruction.
        instruction: &'static str,
    },
    /// A path-corrected sequence that does not start (`start`) or end in a fine point
    /// (checked by the controller); the text is the manual's (EGM manual §9.3.1.3).
    #[error(
        "{instruction} {name}: EGM Path correction has to start and end in a fine point; {}",
        if *start {
            "the movement before the first EGMMoveL/EGMMoveC must end with `fine`"
        } else {
            "end the last EGMMoveL/EGMMoveC of the sequence with `fine` before other movements"
        }
    )]
    PathCorrFinePoint {
        /// The identity's variable name.
        name: String,
        /// The instruction that found it.
        instruction: &'static str,
        /// True: the sequence does not start in a fine point; false: it does not end in one.
        start: bool,
    },
    /// An EGM movement before any RAPID movement since the controller started (checked by
    /// the controller).
    #[error(
        "{instruction}: the first movement after a controller start cannot be an EGM movement; run a RAPID move (e.g. MoveAbsJ) first"
    )]
    NoPreviousMove {
        /// The instruction.
        instruction: &'static str,
    },
    /// 41822: no valid sensor message within `\CommTimeout` (`ERR_UDPUC_COMM`).
    #[error(
        "no data from UdpUc device \"{device}\" within \\CommTimeout {}",
        fmt_duration(*timeout)
    )]
    CommTimeout {
        /// The device name.
        device: String,
        /// The time-out.
        timeout: Duration,
    },
    /// 41830: a datagram could not be sent (`ERR_UDPUC_COMM`).
    #[error("error sending EGM message to UdpUc device \"{device}\": {reason}")]
    SendFailed {
        /// The device name.
        device: String,
        /// The operating system's reason.
        reason: String,
    },
    /// 90116: the device's socket could not be opened (`ERR_UDPUC_COMM`).
    #[error("UdpUc device \"{device}\" cannot be opened on local port {local_port}: {reason}")]
    DeviceOpen {
        /// The device name.
        device: String,
        /// The Local Port Number (0: any).
        local_port: u16,
        /// The operating system's reason.
        reason: String,
    },
    /// The guidance stopped: the reference is outside reach, beyond an axis limit, close to
    /// a singularity, or not finite (50050, 50027, 50026).
    #[error("EGM guidance stopped: {0}")]
    Supervision(GuidanceError),
    /// A signal of a signal source could not be read.
    #[error("EGM signal source: {0}")]
    Signal(GuidanceError),
    /// The in-process built-in sensor could not answer.
    #[error("built-in EGM sensor on device \"{device}\": {reason}")]
    Sensor {
        /// The device name.
        device: String,
        /// Why.
        reason: String,
    },
    /// The servo parameters derived from the arguments cannot be used.
    #[error("{instruction}: {source}")]
    Servo {
        /// The instruction.
        instruction: &'static str,
        /// Why.
        source: ServoError,
    },
}

impl EgmError {
    /// The event-log entry (number, title, this error's text as detail).
    pub fn event(&self) -> EgmEvent {
        let detail = self.to_string();
        if let EgmError::Supervision(e) | EgmError::Signal(e) = self
            && let Some((number, title)) = e.event()
        {
            return EgmEvent {
                number,
                title,
                detail,
            };
        }
        let kind = match self {
            EgmError::Supervision(_) => EventKind::BadSetup,
            EgmError::Signal(_) => EventKind::SignalSource,
            EgmError::TooManyIdentities { .. } => EventKind::TooManyIdentities,
            EgmError::NotReserved { .. } => EventKind::NotReserved,
            EgmError::NotSetUp { .. } => EventKind::NotSetUp,
            EgmError::NotActivated { .. } => EventKind::NotActivated,
            EgmError::ModeMismatch { .. } => EventKind::ModeMismatch,
            EgmError::SampleRate { .. } | EgmError::Argument { .. } => EventKind::ArgumentValue,
            EgmError::BadSetup { .. } | EgmError::Guidance { .. } | EgmError::Servo { .. } => {
                EventKind::BadSetup
            }
            EgmError::UnknownProfile { .. }
            | EgmError::Device { .. }
            | EgmError::BadDevice { .. } => EventKind::Configuration,
            EgmError::PathCorrLevel { .. } => EventKind::CyclicError,
            EgmError::Busy { .. } => EventKind::Busy,
            EgmError::Unsupported { .. } => EventKind::NotSupported,
            EgmError::NotInFinePoint { .. } => EventKind::NotInFinePoint,
            EgmError::PathCorrFinePoint { start: true, .. } => EventKind::NotInFinePoint,
            EgmError::PathCorrFinePoint { start: false, .. } => EventKind::NotEndedInFinePoint,
            EgmError::NoPreviousMove { .. } => EventKind::NoPreviousMove,
            EgmError::CommTimeout { .. } => EventKind::CommTimeout,
            EgmError::SendFailed { .. } => EventKind::SendError,
            EgmError::DeviceOpen { .. } => EventKind::DeviceOpen,
            EgmError::Sensor { .. } => EventKind::BuiltinSensor,
        };
        EgmEvent::new(kind, detail)
    }

    /// The RAPID error a program can catch (`ERR_UDPUC_COMM` for every UdpUc communication
    /// failure); `None` for a fatal error that stops the program.
    pub fn rapid_error(&self) -> Option<&'static str> {
        match self {
            EgmError::CommTimeout { .. }
            | EgmError::SendFailed { .. }
            | EgmError::DeviceOpen { .. } => Some(ERR_UDPUC_COMM),
            _ => None,
        }
    }

    /// True when the program must stop (no RAPID error to catch).
    pub fn is_fatal(&self) -> bool {
        self.rapid_error().is_none()
    }
}
