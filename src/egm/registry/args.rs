//! The arguments of the EGM setup, activation and movement instructions as the interpreter
//! passes them. They are the shared EGM vocabulary of [`crate::egm_args`] (the interpreter
//! fills them without naming `egm`); this module re-exports them for the registry and adds
//! the conversions that report an [`EgmError`].

pub use crate::egm_args::{
    ActCommon, ActJoint, ActMove, ActPose, RunArgs, SetupLtapp, SetupSignals, SetupUc, TrackerKind,
};
use crate::egm_args::{ArgumentError, EgmFrameType, StopMode};

use super::EgmError;

impl From<ArgumentError> for EgmError {
    fn from(e: ArgumentError) -> EgmError {
        EgmError::Argument {
            instruction: e.instruction,
            argument: e.argument,
            value: e.value,
            range: e.range,
        }
    }
}

/// The `egmstopmode` of a RAPID value (`EGM_STOP_HOLD` = 1, `EGM_STOP_RAMP_DOWN` = 2 in
/// `stdlib/egm.sys`).
pub fn stop_mode_from_value(instruction: &'static str, value: f64) -> Result<StopMode, EgmError> {
    Ok(StopMode::from_value(instruction, value)?)
}

/// The RAPID value of a stop mode.
pub fn stop_mode_value(mode: StopMode) -> f64 {
    mode.value()
}

/// The `egmframetype` of a RAPID value (`EGM_FRAME_BASE` = 1 … `EGM_FRAME_JOINT` = 5).
pub fn frame_type_from_value(
    instruction: &'static str,
    argument: &'static str,
    value: f64,
) -> Result<EgmFrameType, EgmError> {
    Ok(EgmFrameType::from_argument(instruction, argument, value)?)
}
