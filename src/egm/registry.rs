//! EGM identities of one RAPID task and their state machine (egm-rapid.md §2–§5): EGMGetId, EGMReset, EGMGetState, the setups and activations, and the checks of EGMRun…, EGMStop, EGMStreamStart/Stop and EGMMoveL/C. Pure data: no time, no sockets, no locks.
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

use crate::config::devices::{DeviceTable, DeviceTarget};
use crate::config::moc::{ExtMotionProfile, MocConfig, MotionLevel};
use crate::config::sio::device_key;
use crate::egm::guidance::{Convergence, EgmFrameType, GuidanceError, PoseSetup, SignalSource};
use crate::egm::pathcorr::SeamProfile;
use crate::egm::servo::MinMax;
use crate::egm::types::{EgmMode, ROBOT_AXES};
use crate::io::SignalTable;
use crate::robot::Pose;
use crate::robot::units::pose_is_finite;

mod args;
mod check;
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
pub use error::{ERR_UDPUC_COMM, EgmError};
pub use plan::{
    Activation, ActivationKind, MoveActivation, MovePlan, RunPlan, Setup, SourceSpec, StreamPlan,
};

/// Most EGM identities reserved at a time in one RAPID task.
pub const MAX_IDENTITIES: usize = 4;

/// `egmstate`, with the numbers of `stdlib/egm.sys`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum EgmState {
    /// `EGM_STATE_DISCONNECTED` (1): no setup.
    Disconnected = 1,
    /// `EGM_STATE_CONNECTED` (2): set up, no EGM movement.
    Connected = 2,
    /// `EGM_STATE_RUNNING` (3): an EGM movement or stream is active.
    Running = 3,
}

impl EgmState {
    /// The RAPID value.
    pub fn value(self) -> f64 {
        f64::from(self as u8)
    }
}

/// `egmcorrstate` (RW7.15), with the numbers of `stdlib/egm.sys`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CorrState {
    /// `EGM_CORR_UNDEFINED` (0): not reserved.
    Undefined = 0,
    /// `EGM_CORR_ERROR` (1): the last EGM movement ended with an error.
    Error = 1,
    /// `EGM_CORR_STOPPED` (2): no EGM movement moves the robot.
    Stopped = 2,
    /// `EGM_CORR_RUNNING` (3): EGM moves the robot.
    Running = 3,
}

impl CorrState {
    /// The RAPID value.
    pub fn value(self) -> f64 {
        f64::from(self as u8)
    }
}

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

/// What the registry needs from the configuration.
#[derive(Clone, Debug)]
pub struct RegistryConfig {
    /// The TCP robot units the task may name as `MecUnit` (default `["ROB_1"]`).
    pub mecunits: Vec<String>,
    /// External Motion Interface Data profiles (MOC.cfg, with the built-in "default").
    pub moc: MocConfig,
    /// UdpUc and simulated devices (SIO.cfg and `--device`).
    pub devices: DeviceTable,
}

impl RegistryConfig {
    /// A configuration for the unit `ROB_1`.
    pub fn new(moc: MocConfig, devices: DeviceTable) -> RegistryConfig {
        RegistryConfig {
            mecunits: vec!["ROB_1".to_string()],
            moc,
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

    // ----- setups -----

    /// `EGMSetupUC`.
    pub fn setup_uc(&mut self, id: EgmId, args: &SetupUc) -> Result<(), EgmError> {
        let instruction = "EGMSetupUC";
        self.check_idle(id, instruction)?;
        self.check_mecunit(instruction, &args.mecunit)?;
        let profile = self.profile(instruction, &args.profile)?;
        check_tracker_uc(instruction, args.mode, args.tracker)?;
        let comm_timeout = match args.comm_timeout {
            None => defaults::COMM_TIMEOUT,
            Some(s) => seconds(instruction, "\\CommTimeout", s, false)?,
        };
        let source = self.resolve_uc(instruction, &args.device, args.mode)?;
        self.store_setup(
            id,
            Setup {
                instruction,
                mecunit: args.mecunit.clone(),
                profile,
                mode: args.mode,
                tracker: args.tracker,
                comm_timeout,
                source,
            },
        );
        Ok(())
    }

    /// `EGMSetupAI`, `EGMSetupAO`, `EGMSetupGI` (by `args.kind`); the signals are checked
    /// against `table` (they must exist and be of the instruction's kind; at least one).
    pub fn setup_signals(
        &mut self,
        id: EgmId,
        args: &SetupSignals,
        table: &SignalTable,
    ) -> Result<(), EgmError> {
        let instruction = args.instruction();
        self.check_idle(id, instruction)?;
        self.check_mecunit(instruction, &args.mecunit)?;
        let profile = self.profile(instruction, &args.profile)?;
        match (args.mode, args.tracker) {
            (EgmMode::PathCorr, Some(TrackerKind::Aptr))
            | (EgmMode::Joint | EgmMode::Pose, None) => {}
            (EgmMode::PathCorr, Some(TrackerKind::Latr)) => {
                return Err(bad(
                    instruction,
                    "\\LATR does not exist for signal sources (removed in RobotWare 7.1); use \\APTR",
                ));
            }
            (EgmMode::PathCorr, None) => {
                return Err(bad(instruction, "\\PathCorr needs \\APTR"));
            }
            (_, Some(_)) => {
                return Err(bad(instruction, "\\APTR is only allowed with \\PathCorr"));
            }
        }
        let source =
            SignalSource::new(table, args.kind, args.mapping, args.ext).map_err(|source| {
                EgmError::Guidance {
                    instruction,
                    source,
                }
            })?;
        self.store_setup(
            id,
            Setup {
                instruction,
                mecunit: args.mecunit.clone(),
                profile,
                mode: args.mode,
                tracker: args.tracker,
                comm_timeout: defaults::COMM_TIMEOUT,
                source: SourceSpec::Signals {
                    kind: args.kind,
                    source,
                },
            },
        );
        Ok(())
    }

    /// `EGMSetupLTAPP`: only the simulated LTAPP devices (or a `builtin` device with a seam
    /// pattern) work; the LTAPP protocol is not public.
    pub fn setup_ltapp(&mut self, id: EgmId, args: &SetupLtapp) -> Result<(), EgmError> {
        let instruction = "EGMSetupLTAPP";
        self.check_idle(id, instruction)?;
        self.check_mecunit(instruction, &args.mecunit)?;
        let profile = self.profile(instruction, &args.profile)?;
        if !args.joint_type.is_finite() {
            return Err(EgmError::Argument {
                instruction,
                argument: "JointType",
                value: args.joint_type,
                range: "a number",
            });
        }
        let device = device_key(&args.device).to_string();
        let seam_text = match self.config.devices.resolve_device(&args.device) {
            Ok(DeviceTarget::Ltapp { seam, .. }) => seam,
            Ok(DeviceTarget::Builtin { pattern }) => {
                pattern.unwrap_or_else(|| "const:y=0,z=0".to_string())
            }
            Ok(DeviceTarget::Udp { .. }) => {
                return Err(EgmError::Unsupported {
                    instruction,
                    what: "an LTAPP sensor on a UdpUc device (the LTAPP protocol is not public; rapidvc simulates the LTAPP devices OptSim and wg1sim, and `--device NAME=builtin:SEAM` makes any name a simulated seam sensor)",
                });
            }
            Err(source) => {
                return Err(EgmError::Device {
                    instruction,
                    source,
                });
            }
        };
        let seam = SeamProfile::parse(&seam_text).map_err(|e| EgmError::BadDevice {
            instruction,
            device: device.clone(),
            detail: e.to_string(),
        })?;
        self.store_setup(
            id,
            Setup {
                instruction,
                mecunit: args.mecunit.clone(),
                profile,
                mode: EgmMode::PathCorr,
                tracker: Some(args.tracker),
                comm_timeout: defaults::COMM_TIMEOUT,
                source: SourceSpec::Ltapp {
                    device,
                    joint_type: args.joint_type,
                    seam,
                },
            },
        );
        Ok(())
    }

    // ----- activations -----

    /// `EGMActJoint`; with `\StreamStart` the identity starts streaming and the plan of the
    /// stream is returned.
    pub fn act_joint(
        &mut self,
        id: EgmId,
        args: &ActJoint,
    ) -> Result<Option<StreamPlan>, EgmError> {
        let instruction = "EGMActJoint";
        let setup = self.setup_for_activation(id, instruction)?;
        if args.windows.get(6).copied().flatten().is_some() {
            return Err(EgmError::Unsupported {
                instruction,
                what: "\\J7 (rapidvc models 6-axis robots)",
            });
        }
        let mut windows = [defaults::JOINT_WINDOW; ROBOT_AXES];
        for (i, (slot, given)) in windows.iter_mut().zip(&args.windows).enumerate() {
            if let Some(w) = given {
                check_window(
                    instruction,
                    JOINT_WINDOW_ARGS.get(i).copied().unwrap_or("\\J"),
                    w,
                )?;
                *slot = *w;
            }
        }
        let activation = resolve_common(
            instruction,
            &args.common,
            &setup,
            ActivationKind::Joint { windows },
        )?;
        self.store_activation(id, activation, args.common.stream_start)
    }

    /// `EGMActPose`; with `\StreamStart` the identity starts streaming and the plan of the
    /// stream is returned.
    pub fn act_pose(&mut self, id: EgmId, args: &ActPose) -> Result<Option<StreamPlan>, EgmError> {
        let instruction = "EGMActPose";
        let setup = self.setup_for_activation(id, instruction)?;
        for (t, which) in [(args.corr_type, "correction"), (args.sens_type, "sensor")] {
            if t == EgmFrameType::Joint {
                return Err(EgmError::Guidance {
                    instruction,
                    source: GuidanceError::JointFrameInPoseMode { which },
                });
            }
        }
        for (p, argument) in [
            (&args.corr_frame, "CorrFrame"),
            (&args.sensor_frame, "SensorFrame"),
        ] {
            if !pose_is_finite(p) {
                return Err(EgmError::BadSetup {
                    instruction,
                    detail: format!("{argument} is not a finite pose"),
                });
            }
        }
        for (i, w) in args.windows.iter().enumerate() {
            if let Some(w) = w {
                check_window(
                    instruction,
                    POSE_WINDOW_ARGS.get(i).copied().unwrap_or("\\x"),
                    w,
                )?;
            }
        }
        let windows = Convergence::with_overrides(args.windows.map(|w| w.map(|m| (m.min, m.max))))
            .map_err(|source| EgmError::Guidance {
                instruction,
                source,
            })?;
        let tool = args.common.tool.unwrap_or_default();
        let wobj = args.common.wobj.clone().unwrap_or_default();
        let frames = PoseSetup {
            tool,
            wobj,
            corr_frame: args.corr_frame,
            corr_type: args.corr_type,
            sensor_frame: args.sensor_frame,
            sens_type: args.sens_type,
            offset: None,
            selection: [true; ROBOT_AXES],
        };
        let activation = resolve_common(
            instruction,
            &args.common,
            &setup,
            ActivationKind::Pose {
                frames: Box::new(frames),
                windows,
            },
        )?;
        self.store_activation(id, activation, args.common.stream_start)
    }

    /// `EGMActMove`.
    pub fn act_move(&mut self, id: EgmId, args: &ActMove) -> Result<(), EgmError> {
        let instruction = "EGMActMove";
        self.setup_for_activation(id, instruction)?;
        if !pose_is_finite(&args.sensor_frame) {
            return Err(bad(instruction, "SensorFrame is not a finite pose"));
        }
        let sample_period = sample_rate(
            instruction,
            args.sample_rate,
            defaults::MOVE_SAMPLE_RATE_MS,
            defaults::MOVE_SAMPLE_RATE_MULTIPLE_MS,
        )?;
        if let Some(i) = self.get_mut(id) {
            i.act_move = Some(MoveActivation {
                sensor_frame: args.sensor_frame,
                sample_period,
            });
        }
        Ok(())
    }

    // ----- movements -----

    /// `EGMRunJoint`: checks the request and marks the identity RUNNING; `axes` are the
    /// switches `\J1` … `\J7`. Call [`EgmRegistry::run_finished`] when the run ends or its
    /// driver cannot start.
    pub fn run_joint(
        &mut self,
        id: EgmId,
        args: &RunArgs,
        axes: [bool; 7],
    ) -> Result<RunPlan, EgmError> {
        let instruction = "EGMRunJoint";
        if axes.get(6).copied().unwrap_or(false) {
            return Err(EgmError::Unsupported {
                instruction,
                what: "\\J7 (rapidvc models 6-axis robots)",
            });
        }
        let mut selection = [false; ROBOT_AXES];
        for (s, a) in selection.iter_mut().zip(&axes) {
            *s = *a;
        }
        self.plan_run(id, instruction, args, selection, None)
    }

    /// `EGMRunPose`: checks the request and marks the identity RUNNING; `directions` are the
    /// switches `\x \y \z \rx \ry \rz`. Call [`EgmRegistry::run_finished`] when the run ends
    /// or its driver cannot start.
    pub fn run_pose(
        &mut self,
        id: EgmId,
        args: &RunArgs,
        directions: [bool; 6],
        offset: Option<Pose>,
    ) -> Result<RunPlan, EgmError> {
        let instruction = "EGMRunPose";
        if let Some(o) = &offset
            && !pose_is_finite(o)
        {
            return Err(bad(instruction, "\\Offset is not a finite pose"));
        }
        self.plan_run(id, instruction, args, directions, offset)
    }

    /// The run of `id` ended: CONNECTED, with correction state STOPPED (`ok`) or ERROR. A
    /// stream the run replaced ends too. Nothing happens when no run is active.
    pub fn run_finished(&mut self, id: EgmId, ok: bool) {
        if let Some(i) = self.get_mut(id)
            && matches!(i.activity, Activity::Run(_))
        {
            i.activity = Activity::Idle;
            i.corr = if ok {
                CorrState::Stopped
            } else {
                CorrState::Error
            };
        }
    }

    /// `EGMStop`: what is active and must be ended. A stream or a corrected movement is
    /// marked ended at once; a run stays RUNNING until [`EgmRegistry::run_finished`].
    pub fn stop(&mut self, id: EgmId) -> Result<StopTarget, EgmError> {
        let i = self.get_mut(id).ok_or(EgmError::NotReserved {
            instruction: "EGMStop",
        })?;
        let target = stop_target(i.activity);
        if matches!(i.activity, Activity::Stream | Activity::Move) {
            i.activity = Activity::Idle;
            i.corr = CorrState::Stopped;
        }
        Ok(target)
    }

    /// `EGMStreamStart \SampleRate`: checks and marks the identity RUNNING (correction state
    /// STOPPED).
    pub fn stream_start(
        &mut self,
        id: EgmId,
        sample_rate_ms: Option<f64>,
    ) -> Result<StreamPlan, EgmError> {
        let instruction = "EGMStreamStart";
        let i = self.reserved(id, instruction)?;
        let setup = i.setup.as_ref().ok_or_else(|| EgmError::NotSetUp {
            name: i.name.clone(),
            instruction,
        })?;
        check_streamable(instruction, setup)?;
        if i.activity != Activity::Idle {
            return Err(busy(i, instruction));
        }
        let period = sample_rate(
            instruction,
            sample_rate_ms,
            defaults::SAMPLE_RATE_MS,
            defaults::SAMPLE_RATE_MULTIPLE_MS,
        )?;
        let plan = stream_plan(id, i, setup, period);
        if let Some(i) = self.get_mut(id) {
            i.activity = Activity::Stream;
        }
        Ok(plan)
    }

    /// `EGMStreamStop` (also after a stream failed to start): CONNECTED again; returns whether
    /// a stream was active.
    pub fn stream_stop(&mut self, id: EgmId) -> Result<bool, EgmError> {
        let i = self.get_mut(id).ok_or(EgmError::NotReserved {
            instruction: "EGMStreamStop",
        })?;
        if i.activity == Activity::Stream {
            i.activity = Activity::Idle;
            i.corr = CorrState::Stopped;
            Ok(true)
        } else {
            Ok(false)
        }
    }

    /// `EGMMoveL` / `EGMMoveC` (`instruction`): checks the path-correction request (setup
    /// with `\PathCorr` or EGMSetupLTAPP, EGMActMove, a Level 2 profile) and marks the
    /// identity RUNNING. Further moves of the same sequence get the same plan.
    pub fn move_start(
        &mut self,
        id: EgmId,
        instruction: &'static str,
    ) -> Result<MovePlan, EgmError> {
        let i = self.reserved(id, instruction)?;
        let setup = i.setup.as_ref().ok_or_else(|| EgmError::NotSetUp {
            name: i.name.clone(),
            instruction,
        })?;
        if setup.mode != EgmMode::PathCorr {
            return Err(EgmError::ModeMismatch {
                name: i.name.clone(),
                instruction,
                detail: format!(
                    "the identity is set up for {} guidance by {}; {instruction} needs a path-correction setup (EGMSetupUC … \\PathCorr, or EGMSetupLTAPP)",
                    setup.mode, setup.instruction
                ),
            });
        }
        let act = i.act_move.ok_or_else(|| EgmError::NotActivated {
            name: i.name.clone(),
            instruction,
            needs: "EGMActMove",
        })?;
        if setup.profile.level != MotionLevel::Path {
            return Err(EgmError::PathCorrLevel {
                name: i.name.clone(),
                instruction,
                profile: setup.profile.name.clone(),
                level: setup.profile.level.number(),
            });
        }
        if !matches!(i.activity, Activity::Idle | Activity::Move) {
            return Err(busy(i, instruction));
        }
        let plan = MovePlan {
            id,
            name: i.name.clone(),
            tracker: setup.tracker.unwrap_or(TrackerKind::Aptr),
            sensor_frame: act.sensor_frame,
            sample_period: act.sample_period,
            source: setup.source.clone(),
            comm_timeout: setup.comm_timeout,
            profile: setup.profile.clone(),
        };
        if let Some(i) = self.get_mut(id) {
            i.activity = Activity::Move;
            i.corr = CorrState::Running;
        }
        Ok(plan)
    }

    /// The fine point ending a corrected sequence was reached (`ok`), or it ended with an
    /// error: CONNECTED.
    pub fn move_finished(&mut self, id: EgmId, ok: bool) {
        if let Some(i) = self.get_mut(id)
            && i.activity == Activity::Move
        {
            i.activity = Activity::Idle;
            i.corr = if ok {
                CorrState::Stopped
            } else {
                CorrState::Error
            };
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

    fn check_mecunit(&self, instruction: &'static str, unit: &str) -> Result<(), EgmError> {
        if self
            .config
            .mecunits
            .iter()
            .any(|u| u.eq_ignore_ascii_case(unit))
        {
            Ok(())
        } else {
            Err(EgmError::BadSetup {
                instruction,
                detail: format!(
                    "MecUnit {unit} is not a TCP robot of this task (this task moves {})",
                    self.config.mecunits.join(", ")
                ),
            })
        }
    }

    fn profile(&self, instruction: &'static str, name: &str) -> Result<ExtMotionProfile, EgmError> {
        self.config
            .moc
            .profile(name)
            .cloned()
            .map_err(|source| EgmError::UnknownProfile {
                instruction,
                source,
            })
    }

    fn resolve_uc(
        &self,
        instruction: &'static str,
        device: &str,
        mode: EgmMode,
    ) -> Result<SourceSpec, EgmError> {
        let name = device_key(device).to_string();
        match self.config.devices.resolve_device(device) {
            Ok(DeviceTarget::Udp { remote, local_port }) => Ok(udp_spec(name, remote, local_port)),
            Ok(DeviceTarget::Builtin { pattern }) => {
                let pattern = builtin_pattern(instruction, &name, pattern.as_deref(), mode)?;
                Ok(SourceSpec::Builtin {
                    device: name,
                    pattern,
                })
            }
            Ok(DeviceTarget::Ltapp { .. }) => Err(EgmError::BadDevice {
                instruction,
                device: name,
                detail: "is a simulated LTAPP seam sensor; set it up with EGMSetupLTAPP"
                    .to_string(),
            }),
            Err(source) => Err(EgmError::Device {
                instruction,
                source,
            }),
        }
    }

    fn store_setup(&mut self, id: EgmId, setup: Setup) {
        if let Some(i) = self.get_mut(id) {
            i.setup = Some(setup);
            i.activation = None;
            i.act_move = None;
            i.corr = CorrState::Stopped;
        }
    }

    /// The setup an activation refers to; the identity must be idle.
    fn setup_for_activation(
        &self,
        id: EgmId,
        instruction: &'static str,
    ) -> Result<Setup, EgmError> {
        let i = self.reserved(id, instruction)?;
        let setup = i.setup.clone().ok_or_else(|| EgmError::NotSetUp {
            name: i.name.clone(),
            instruction,
        })?;
        if i.activity != Activity::Idle {
            return Err(busy(i, instruction));
        }
        Ok(setup)
    }

    fn store_activation(
        &mut self,
        id: EgmId,
        activation: Activation,
        stream_start: bool,
    ) -> Result<Option<StreamPlan>, EgmError> {
        let plan = {
            let i = self.reserved(id, activation.instruction)?;
            match (&i.setup, stream_start) {
                (Some(setup), true) => {
                    check_streamable(activation.instruction, setup)?;
                    let mut plan = stream_plan(id, i, setup, activation.sample_period);
                    plan.tool = activation.tool;
                    plan.wobj = activation.wobj.clone();
                    Some(plan)
                }
                _ => None,
            }
        };
        if let Some(i) = self.get_mut(id) {
            i.activation = Some(activation);
            if plan.is_some() {
                i.activity = Activity::Stream;
            }
        }
        Ok(plan)
    }

    fn plan_run(
        &mut self,
        id: EgmId,
        instruction: &'static str,
        args: &RunArgs,
        selection: [bool; ROBOT_AXES],
        offset: Option<Pose>,
    ) -> Result<RunPlan, EgmError> {
        let pose_run = instruction == "EGMRunPose";
        let i = self.reserved(id, instruction)?;
        let setup = i.setup.as_ref().ok_or_else(|| EgmError::NotSetUp {
            name: i.name.clone(),
            instruction,
        })?;
        let wanted = if pose_run {
            EgmMode::Pose
        } else {
            EgmMode::Joint
        };
        if setup.mode != wanted {
            return Err(EgmError::ModeMismatch {
                name: i.name.clone(),
                instruction,
                detail: format!(
                    "EGM mode mismatch: the identity is set up for {} by {}; {instruction} needs {}",
                    describe_mode(setup.mode),
                    setup.instruction,
                    describe_mode(wanted)
                ),
            });
        }
        let needs = if pose_run {
            "EGMActPose"
        } else {
            "EGMActJoint"
        };
        let act = i
            .activation
            .as_ref()
            .ok_or_else(|| EgmError::NotActivated {
                name: i.name.clone(),
                instruction,
                needs,
            })?;
        let stops_stream = match i.activity {
            Activity::Idle => false,
            Activity::Stream => true,
            Activity::Run(_) | Activity::Move => return Err(busy(i, instruction)),
        };
        let (windows, pose) = match (&act.kind, pose_run) {
            (ActivationKind::Joint { windows }, false) => (*windows, None),
            (ActivationKind::Pose { frames, windows }, true) => {
                let mut w = [MinMax::JOINT_DEFAULT; ROBOT_AXES];
                for (slot, (min, max)) in w.iter_mut().zip(windows.windows()) {
                    *slot = MinMax {
                        min: *min,
                        max: *max,
                    };
                }
                let pose = PoseSetup {
                    offset,
                    selection,
                    ..(**frames).clone()
                };
                (w, Some(pose))
            }
            _ => {
                return Err(EgmError::ModeMismatch {
                    name: i.name.clone(),
                    instruction,
                    detail: format!(
                        "EGM mode mismatch: the identity is activated by {}; {instruction} needs {needs}",
                        act.instruction
                    ),
                });
            }
        };
        let ramp_default = profile_ramp(&setup.profile);
        let cond_time = opt_seconds(
            instruction,
            "\\CondTime",
            args.cond_time,
            defaults::COND_TIME,
        )?;
        let ramp_in_time =
            opt_seconds(instruction, "\\RampInTime", args.ramp_in_time, ramp_default)?;
        let ramp_out_time = opt_seconds(
            instruction,
            "\\RampOutTime",
            args.ramp_out_time,
            ramp_default,
        )?;
        let pos_corr_gain = args.pos_corr_gain.unwrap_or(defaults::POS_CORR_GAIN);
        if !(pos_corr_gain.is_finite() && pos_corr_gain >= 0.0) {
            return Err(EgmError::Argument {
                instruction,
                argument: "\\PosCorrGain",
                value: pos_corr_gain,
                range: "a number ≥ 0 (0 to 1 in ABB's manual)",
            });
        }
        let plan = RunPlan {
            id,
            name: i.name.clone(),
            instruction,
            mode: wanted,
            source: setup.source.clone(),
            profile: setup.profile.clone(),
            comm_timeout: setup.comm_timeout,
            sample_period: act.sample_period,
            tool: act.tool,
            wobj: act.wobj.clone(),
            tload: act.tload,
            pose,
            windows,
            selection,
            stop_mode: args.stop_mode,
            no_wait_cond: args.no_wait_cond,
            cond_time,
            ramp_in_time,
            ramp_out_time,
            pos_corr_gain,
            lp_filter_hz: act.lp_filter_hz.unwrap_or(setup.profile.filter_bandwidth),
            max_speed_deviation: act.max_speed_deviation,
            max_pos_deviation: act.max_pos_deviation,
            do_to_sensor: act.do_to_sensor,
            di_from_sensor: act.di_from_sensor,
            stops_stream,
        };
        if let Some(i) = self.get_mut(id) {
            i.activity = Activity::Run(instruction);
            i.corr = CorrState::Running;
        }
        Ok(plan)
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
