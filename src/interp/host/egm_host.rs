//! The EGM capability of a host ([`EgmHost`]): what the EGM instructions ask of the controller. A host without EGM (the deterministic [`super::VirtualHost`] of `rapidvc test`) returns `None` from [`super::Host::egm`], and the instructions stop the program with "… is not supported by this controller".
//!
//! The requests are the shared EGM vocabulary of [`crate::egm_args`]: plain data that the
//! natives fill from RAPID values and the controller hands to the EGM registry (the
//! interpreter never names `egm`). Identities are passed by name (see
//! [`crate::interp::builtins`]'s egm natives): the same variable always maps to the same
//! identity.

use crate::egm_args::{
    ActJoint, ActMove, ActPose, CorrState, EgmState, RunArgs, SetupLtapp, SetupSignals, SetupUc,
    StopMode,
};
use crate::robot::Pose;
use crate::signals::SignalId;
use crate::source::Span;

use super::HostError;

/// EGMRunJoint or EGMRunPose with its switches.
#[derive(Clone, Debug, PartialEq)]
pub enum EgmRun {
    /// `EGMRunJoint … \J1 … \J7`.
    Joint {
        /// Mode, `\NoWaitCond`, `\CondTime`, ramps, `\PosCorrGain`.
        args: RunArgs,
        /// `\J1` … `\J7`.
        axes: [bool; 7],
    },
    /// `EGMRunPose … \x … \rz \Offset`.
    Pose {
        /// Mode, `\NoWaitCond`, `\CondTime`, ramps, `\PosCorrGain`.
        args: RunArgs,
        /// `\x \y \z \rx \ry \rz`.
        directions: [bool; 6],
        /// `\Offset`.
        offset: Option<Pose>,
    },
}

impl EgmRun {
    /// The shared arguments.
    pub fn args(&self) -> &RunArgs {
        match self {
            EgmRun::Joint { args, .. } | EgmRun::Pose { args, .. } => args,
        }
    }
}

/// A controller that runs EGM. `ident` is the identity's name (a task-unique name of the
/// `egmident` variable). Errors with [`HostError::errno`] set are catchable RAPID errors
/// (`ERR_UDPUC_COMM`); the others stop the program.
pub trait EgmHost {
    /// `EGMGetId`.
    fn egm_get_id(&mut self, ident: &str) -> Result<(), HostError>;
    /// `EGMReset`.
    fn egm_reset(&mut self, ident: &str) -> Result<(), HostError>;
    /// `EGMGetState`: execution and correction state.
    fn egm_get_state(&mut self, ident: &str) -> Result<(EgmState, CorrState), HostError>;
    /// The I/O signal of a signal argument of EGMSetupAI/AO/GI, `\DOToSensor`,
    /// `\DIFromSensor`.
    fn egm_signal(&mut self, name: &str) -> Result<SignalId, HostError>;
    /// `EGMSetupUC`.
    fn egm_setup_uc(&mut self, ident: &str, args: &SetupUc) -> Result<(), HostError>;
    /// `EGMSetupAI`, `EGMSetupAO`, `EGMSetupGI`.
    fn egm_setup_signals(&mut self, ident: &str, args: &SetupSignals) -> Result<(), HostError>;
    /// `EGMSetupLTAPP`.
    fn egm_setup_ltapp(&mut self, ident: &str, args: &SetupLtapp) -> Result<(), HostError>;
    /// `EGMActJoint`.
    fn egm_act_joint(&mut self, ident: &str, args: &ActJoint) -> Result<(), HostError>;
    /// `EGMActPose`.
    fn egm_act_pose(&mut self, ident: &str, args: &ActPose) -> Result<(), HostError>;
    /// `EGMActMove`.
    fn egm_act_move(&mut self, ident: &str, args: &ActMove) -> Result<(), HostError>;
    /// Starts `EGMRunJoint`/`EGMRunPose` at `span`; the native then waits with
    /// [`EgmHost::egm_run_done`] unless `\NoWaitCond`.
    fn egm_run(&mut self, ident: &str, run: &EgmRun, span: Span) -> Result<(), HostError>;
    /// True once the run of `ident` has ended (its result is then taken: an error is
    /// returned here, always fatal when `fatal`).
    fn egm_run_done(&mut self, ident: &str, fatal: bool) -> Result<bool, HostError>;
    /// True while a run of `ident` is active (nothing is taken).
    fn egm_run_active(&mut self, ident: &str) -> Result<bool, HostError>;
    /// `EGMStop` (the native then waits for [`EgmHost::egm_run_active`] to turn false and
    /// calls [`EgmHost::egm_stop_done`]).
    fn egm_stop(
        &mut self,
        ident: &str,
        mode: StopMode,
        ramp_out: Option<f64>,
    ) -> Result<(), HostError>;
    /// After EGMStop's wait.
    fn egm_stop_done(&mut self, ident: &str) -> Result<(), HostError>;
    /// `EGMStreamStart \SampleRate` (ms).
    fn egm_stream_start(&mut self, ident: &str, sample_rate: Option<f64>) -> Result<(), HostError>;
    /// `EGMStreamStop`.
    fn egm_stream_stop(&mut self, ident: &str) -> Result<(), HostError>;
    /// The program ended or stopped: an active run ramps out, streams end.
    fn egm_program_stopped(&mut self) -> Result<(), HostError>;
}
