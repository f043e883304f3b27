//! EGM identities of one RAPID task and their state machine (docs/egm.md, "Identities and states"): EGMGetId, EGMReset, EGMGetState, the setups and activations, and the checks of EGMRun…, EGMStop, EGMStreamStart/Stop and EGMMoveL/C. Pure data: no time, no sockets, no locks.
//!
//! # How the controller and the interpreter use it
//!
//! One [`EgmRegistry`] per motion task (rapidvc runs one). Every instruction maps to one call;
//! a refused instruction returns an [`EgmError`] whose [`EgmError::event`] and
//! [`EgmError::rapid_error`] say what RAPID sees.
//!
//! | RAPID | call | state afterwards |
//! |---|---|---|
//! | `EGMGetId id` | [`EgmRegistry::get_id`] (idempotent per variable name) | DISCONNECTED / corr STOPPED |
//! | `EGMReset id` | [`EgmRegistry::reset`] (harmless when not reserved) | released: DISCONNECTED / UNDEFINED |
//! | `EGMGetState(id \CorrectionState)` | [`EgmRegistry::state`] | — |
//! | `EGMSetupUC/AI/AO/GI/LTAPP` | [`EgmRegistry::setup_uc`], [`EgmRegistry::setup_signals`], [`EgmRegistry::setup_ltapp`] | CONNECTED |
//! | `EGMActJoint`, `EGMActPose`, `EGMActMove` | [`EgmRegistry::act_joint`], [`EgmRegistry::act_pose`], [`EgmRegistry::act_move`] | CONNECTED (RUNNING with `\StreamStart`) |
//! | `EGMRunJoint`, `EGMRunPose` | [`EgmRegistry::run_joint`], [`EgmRegistry::run_pose`] → a [`RunPlan`] for [`crate::egm::EgmDriver::start`]; when the driver finishes (or fails to start): [`EgmRegistry::run_finished`] | RUNNING, then CONNECTED |
//! | `EGMStop` | [`EgmRegistry::stop`] → what to stop | CONNECTED once the run ends |
//! | `EGMWaitCond` | [`EgmRegistry::is_running`] | — |
//! | `EGMStreamStart` / `EGMStreamStop` | [`EgmRegistry::stream_start`] → a [`StreamPlan`] for [`crate::egm::EgmStream::start`]; [`EgmRegistry::stream_stop`] | RUNNING / CONNECTED |
//! | `EGMMoveL`, `EGMMoveC` | [`EgmRegistry::move_start`] → a [`MovePlan`]; at the fine point ending the sequence: [`EgmRegistry::move_finished`] | RUNNING, then CONNECTED |
//! | PP to Main | [`EgmRegistry::abandon_all`] (reservations survive) | CONNECTED |
//!
//! The controller checks what the registry cannot see — the movement starts in a fine point,
//! a RAPID move ran since the controller started — and reports them with
//! [`EgmError::NotInFinePoint`] and [`EgmError::NoPreviousMove`].
//!
//! # Decisions (rapidvc's where ABB documents none)
//!
//! * Identities are named by their RAPID variable (compared case-insensitively): pass a name
//!   unique in the task, e.g. `module/routine/variable` for a local variable.
//! * Profiles (ExtConfigName) and devices are resolved at setup, so a missing one is reported
//!   on the setup line. A new setup replaces the old one and clears the activations.
//! * Argument values (`\SampleRate`, windows, deviations) are checked at the activation that
//!   carries them; a `\SampleRate` that is not a positive multiple of 4 ms (24 ms for
//!   EGMActMove) is an error, not rounded. EGMRun… checks the mode: a run that does not fit
//!   the setup or the activation is the fatal event 41826 "EGM mode mismatch".
//! * Path correction (EGMMoveL/C) needs a Level 2 profile: event 50452 otherwise.
//! * `\J7` (7-axis robots), `\DataToSensor` and `\DataFromSensor` are not supported.
//! * Defaults: [`defaults`].

use std::time::Duration;

use crate::egm::geometry::{Convergence, EgmFrameType, GuidanceError, PoseSetup, SignalSource};
use crate::egm::path_correction::SeamProfile;
use crate::egm::servo::MinMax;
use crate::egm::types::{EgmMode, ROBOT_AXES};
use crate::robot::Pose;
use crate::robot::units::pose_is_finite;
use crate::signals::SignalTable;

mod activate;
mod args;
mod check;
pub mod configuration;
mod movement;
mod setup;
use check::{
    bad, builtin_pattern, check_streamable, check_tracker_uc, check_window, describe_mode,
    opt_seconds, profile_ramp, resolve_common, sample_rate, seconds, udp_spec,
};
pub mod defaults;
mod error;
mod plan;

pub use args::{
    ActCommon, ActJoint, ActMove, ActPose, RunArgs, SetupLtapp, SetupSignals, SetupUc, TrackerKind,
    frame_type_from_value, stop_mode_from_value, stop_mode_value,
};
pub use configuration::{
    DeviceError, DeviceTarget, Devices, MotionLevel, MotionProfile, Profiles, UnknownProfile,
    Unlisted, device_key,
};
pub use error::{ERR_UDPUC_COMM, EgmError};
pub use plan::{
    Activation, ActivationKind, MoveActivation, MovePlan, RunPlan, Setup, SourceSpec, StreamPlan,
};

/// Most EGM identities reserved at a time in one RAPID task.
pub const MAX_IDENTITIES: usize = 4;

pub use crate::egm_args::{CorrState, EgmState};

/// A reserved identity: a slot and the reservation's generation, so an identity released by
/// EGMReset is never mistaken for a later one in the same slot.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct EgmId {
    slot: u8,
    generation: u32,
}

impl EgmId {
    /// An opaque number for storing the identity in a RAPID `egmident` variable.
    pub fn to_raw(self) -> u64 {
        (u64::from(self.generation) << 8) | u64::from(self.slot)
    }

    /// The identity of [`EgmId::to_raw`]'s number (any number is accepted; a wrong one is
    /// simply not reserved).
    pub fn from_raw(raw: u64) -> EgmId {
        EgmId {
            slot: (raw & 0xff) as u8,
            generation: u32::try_from(raw >> 8).unwrap_or(u32::MAX),
        }
    }
}

/// What EGMStop (or EGMReset) has to end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopTarget {
    /// Nothing is active.
    Nothing,
    /// An EGMRunJoint/EGMRunPose: call [`crate::egm::EgmDriver::stop`], then
    /// [`EgmRegistry::run_finished`] when it finishes.
    Run,
    /// A position stream: drop the [`crate::egm::EgmStream`] (the registry already shows
    /// CONNECTED).
    Stream,
    /// A path-corrected sequence: end the corrections (the registry already shows
    /// CONNECTED).
    Move,
}

/// What an identity is doing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Activity {
    Idle,
    Run(&'static str),
    Stream,
    Move,
}

impl Activity {
    fn describe(self) -> &'static str {
        match self {
            Activity::Idle => "idle",
            Activity::Run("EGMRunPose") => "running EGMRunPose",
            Activity::Run(_) => "running EGMRunJoint",
            Activity::Stream => "streaming (EGMStreamStop ends it)",
            Activity::Move => "running a path-corrected movement",
        }
    }
}

#[derive(Clone, Debug)]
struct Identity {
    name: String,
    generation: u32,
    setup: Option<Setup>,
    activation: Option<Activation>,
    act_move: Option<MoveActivation>,
    activity: Activity,
    corr: CorrState,
}

/// What the registry needs from the configuration, as plain values (the controller converts
/// its configuration: `controller::egm_controller::registry_config`).
#[derive(Clone, Debug, Default)]
pub struct RegistryConfig {
    /// The TCP robot units the task may name as `MecUnit` (default `["ROB_1"]`).
    pub mecunits: Vec<String>,
    /// External Motion Interface Data profiles (MOC.cfg, with the built-in "default").
    pub profiles: Profiles,
    /// UdpUc and simulated devices (SIO.cfg and `--device`).
    pub devices: Devices,
}

impl RegistryConfig {
    /// A configuration for the unit `ROB_1`.
    pub fn new(profiles: Profiles, devices: Devices) -> RegistryConfig {
        RegistryConfig {
            mecunits: vec!["ROB_1".to_string()],
            profiles,
            devices,
        }
    }
}

/// The EGM identities of one RAPID task (see the module docs).
#[derive(Clone, Debug)]
pub struct EgmRegistry {
    config: RegistryConfig,
    slots: [Option<Identity>; MAX_IDENTITIES],
    generation: u32,
}

const JOINT_WINDOW_ARGS: [&str; 7] = ["\\J1", "\\J2", "\\J3", "\\J4", "\\J5", "\\J6", "\\J7"];
const POSE_WINDOW_ARGS: [&str; 6] = ["\\x", "\\y", "\\z", "\\rx", "\\ry", "\\rz"];

impl EgmRegistry {
    /// An empty registry.
    pub fn new(config: RegistryConfig) -> EgmRegistry {
        EgmRegistry {
            config,
            slots: std::array::from_fn(|_| None),
            generation: 0,
        }
    }

    /// The configuration.
    pub fn config(&self) -> &RegistryConfig {
        &self.config
    }

    // ----- identities -----

    /// `EGMGetId`: reserves an identity for the variable `name`; the same name again returns
    /// the same identity without changing it.
    pub fn get_id(&mut self, name: &str) -> Result<EgmId, EgmError> {
        if let Some(id) = self.lookup(name) {
            return Ok(id);
        }
        let Some(slot) = self.slots.iter().position(Option::is_none) else {
            return Err(EgmError::TooManyIdentities {
                name: name.to_string(),
                max: MAX_IDENTITIES,
                in_use: self.names().join(", "),
            });
        };
        self.generation = self.generation.wrapping_add(1);
        let generation = self.generation;
        let id = EgmId {
            slot: u8::try_from(slot).unwrap_or(u8::MAX),
            generation,
        };
        if let Some(s) = self.slots.get_mut(slot) {
            *s = Some(Identity {
                name: name.to_string(),
                generation,
                setup: None,
                activation: None,
                act_move: None,
                activity: Activity::Idle,
                corr: CorrState::Stopped,
            });
        }
        Ok(id)
    }

    /// The identity reserved for `name`, if any.
    pub fn lookup(&self, name: &str) -> Option<EgmId> {
        self.slots.iter().enumerate().find_map(|(slot, s)| {
            let i = s.as_ref()?;
            i.name.eq_ignore_ascii_case(name).then(|| EgmId {
                slot: u8::try_from(slot).unwrap_or(u8::MAX),
                generation: i.generation,
            })
        })
    }

    /// The names of the reserved identities.
    pub fn names(&self) -> Vec<String> {
        self.slots
            .iter()
            .flatten()
            .map(|i| i.name.clone())
            .collect()
    }

    /// The variable name of `id`, while reserved.
    pub fn name_of(&self, id: EgmId) -> Option<&str> {
        self.get(id).map(|i| i.name.as_str())
    }

    /// `EGMReset`: releases `id` (nothing happens when it is not reserved) and says what was
    /// active, for the controller to end.
    pub fn reset(&mut self, id: EgmId) -> StopTarget {
        let target = self
            .get(id)
            .map_or(StopTarget::Nothing, |i| stop_target(i.activity));
        if self.get(id).is_some()
            && let Some(slot) = self.slots.get_mut(usize::from(id.slot))
        {
            *slot = None;
        }
        target
    }

    /// `EGMGetState(id \CorrectionState)`: the execution and correction states.
    pub fn state(&self, id: EgmId) -> (EgmState, CorrState) {
        let Some(i) = self.get(id) else {
            return (EgmState::Disconnected, CorrState::Undefined);
        };
        match (i.activity, &i.setup) {
            (Activity::Run(_) | Activity::Move, _) => (EgmState::Running, CorrState::Running),
            (Activity::Stream, _) => (EgmState::Running, CorrState::Stopped),
            (Activity::Idle, Some(_)) => (EgmState::Connected, i.corr),
            (Activity::Idle, None) => (EgmState::Disconnected, i.corr),
        }
    }

    /// The setup of `id`.
    pub fn setup(&self, id: EgmId) -> Option<&Setup> {
        self.get(id)?.setup.as_ref()
    }

    /// The EGMActJoint/EGMActPose activation of `id`.
    pub fn activation(&self, id: EgmId) -> Option<&Activation> {
        self.get(id)?.activation.as_ref()
    }

    /// The EGMActMove activation of `id`.
    pub fn move_activation(&self, id: EgmId) -> Option<&MoveActivation> {
        self.get(id)?.act_move.as_ref()
    }

    /// True while an EGMRunJoint/EGMRunPose of `id` is active (`EGMWaitCond` waits for
    /// this to become false).
    pub fn is_running(&self, id: EgmId) -> bool {
        matches!(self.get(id).map(|i| i.activity), Some(Activity::Run(_)))
    }

    /// True while `id` streams.
    pub fn is_streaming(&self, id: EgmId) -> bool {
        matches!(self.get(id).map(|i| i.activity), Some(Activity::Stream))
    }

    /// PP to Main (or PP to a routine): every active run, stream and corrected movement is
    /// abandoned (the controller drops their drivers); reservations, setups and activations
    /// stay.
    pub fn abandon_all(&mut self) {
        for i in self.slots.iter_mut().flatten() {
            if i.activity != Activity::Idle {
                i.activity = Activity::Idle;
                i.corr = CorrState::Stopped;
            }
        }
    }

    // ----- internals -----

    fn get(&self, id: EgmId) -> Option<&Identity> {
        self.slots
            .get(usize::from(id.slot))?
            .as_ref()
            .filter(|i| i.generation == id.generation)
    }

    fn get_mut(&mut self, id: EgmId) -> Option<&mut Identity> {
        self.slots
            .get_mut(usize::from(id.slot))?
            .as_mut()
            .filter(|i| i.generation == id.generation)
    }

    fn reserved(&self, id: EgmId, instruction: &'static str) -> Result<&Identity, EgmError> {
        self.get(id).ok_or(EgmError::NotReserved { instruction })
    }

    fn check_idle(&self, id: EgmId, instruction: &'static str) -> Result<(), EgmError> {
        let i = self.reserved(id, instruction)?;
        if i.activity == Activity::Idle {
            Ok(())
        } else {
            Err(busy(i, instruction))
        }
    }
}

fn stop_target(a: Activity) -> StopTarget {
    match a {
        Activity::Idle => StopTarget::Nothing,
        Activity::Run(_) => StopTarget::Run,
        Activity::Stream => StopTarget::Stream,
        Activity::Move => StopTarget::Move,
    }
}

fn busy(i: &Identity, instruction: &'static str) -> EgmError {
    EgmError::Busy {
        name: i.name.clone(),
        instruction,
        activity: i.activity.describe(),
    }
}

fn stream_plan(id: EgmId, i: &Identity, setup: &Setup, sample_period: Duration) -> StreamPlan {
    let act = i.activation.as_ref();
    StreamPlan {
        id,
        name: i.name.clone(),
        mode: setup.mode,
        source: setup.source.clone(),
        sample_period,
        tool: act.map(|a| a.tool).unwrap_or_default(),
        wobj: act.map(|a| a.wobj.clone()).unwrap_or_default(),
    }
}

#[cfg(test)]
mod tests;
