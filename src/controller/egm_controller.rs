//! The EGM glue of the virtual controller: what each RAPID EGM instruction does to the identities ([`EgmRegistry`]), the motion core (an EGM run drives it as external guidance), the position streams (ticked by the cycle hook) and the report (trace column `egm_state`, EGM plot section, `--egm-log`).
//!
//! # Pieces
//!
//! * [`EgmController`] lives on the program's side (the interpreter's host calls it, with the
//!   [`ControllerHandle`]): it owns the registry, opens data sources, starts runs and
//!   streams, and takes back what the cycle hook reports.
//! * [`EgmHook`] runs around every motion cycle ([`crate::controller::CycleHook`]): it owns
//!   the cycle's EGM I/O (drains the devices' sockets into the machines before the tick,
//!   sends what they produced after it, `device_socket.rs`), ticks the streams, hands events
//!   and log rows out, waits for the sensor in lockstep, and returns a finished run to the
//!   program side.
//! * An EGM run is an [`crate::motion::ExternalGuidance`] whose `step` ticks the sans-IO
//!   [`crate::egm::EgmDriver`] (`run_guidance.rs`); EGMStop and a program stop reach it
//!   through atomics.
//!
//! # Decisions
//!
//! * One EGM run at a time (one motion task): a second EGMRun… while one is active is
//!   refused. Streams of other identities run alongside.
//! * An EGM run starts only when a RAPID movement ran since the controller started and the
//!   last one ended in a stop point (`fine`); otherwise
//!   [`EgmError::NoPreviousMove`] / [`EgmError::NotInFinePoint`] (fatal).
//! * `\MaxSpeedDeviation` is capped at the slowest axis' maximum speed of the robot model, so
//!   EGM never asks for an axis speed the motion core's supervision would refuse (a note is
//!   printed when that happens).
//! * EGMStop waits until the run has ended (its stop mode included); from a TRAP routine
//!   this also ends the EGMRun… the TRAP interrupted.
//! * A run started with `\NoWaitCond` that ends with an error reports it (always fatal) at
//!   EGMWaitCond, at the next EGM instruction, or at the end of the program.
//! * A program stop with the program pointer kept (`rapidvc serve`): the run pauses and
//!   goes on at the start ([`EgmController::pause_run`], `egm::servo`'s speed scale); the
//!   controller's speed ratio scales the EGM speed ([`EgmController::set_speed_ratio`]).
//! * Program end or stop: a run still active brakes to rest (`egm::servo`: from its speed,
//!   within MaxSpeedDeviation and the axis accelerations, short of the reference;
//!   [`EgmController::program_stopped`]); streams end.
//! * Lockstep (virtual time only): after each message to an external sensor the cycle waits
//!   (real time, up to the per-message time-out) for the sensor's reply.

use std::io::Write;
use std::sync::atomic::Ordering;
use std::sync::mpsc::{self, Receiver};
use std::sync::{Arc, PoisonError};
use std::time::Duration;

use crate::controller::sample_feed::{EgmTraceState, Feed};
use crate::egm::registry::{
    ActJoint, ActMove, ActPose, CorrState, EgmId, EgmRegistry, EgmState, RegistryConfig, RunArgs,
    RunPlan, SetupLtapp, SetupSignals, SetupUc, StopTarget, StreamPlan,
};
use crate::egm::servo::StopMode;
use crate::egm::session::DropCounts;
use crate::egm::{
    DriverContext, DriverOptions, EgmDriver, EgmEnd, EgmError, EgmEvent, EgmSource, EgmStream,
};
use crate::motion::{CoreMode, InstrRef};
use crate::robot::{Pose, Robot};
use crate::signals::SignalTable;

use super::{Condition, ControllerError, ControllerHandle};

mod device_socket;
mod egm_config;
mod egm_hook;
mod egm_instructions;
mod message_log_thread;
mod run_guidance;

use super::corrected_moves::{PathCorr, path_correction_for};
pub use device_socket::DeviceSocket;
pub use egm_config::{device_values, profiles, registry_config};
pub use egm_hook::EgmHook;
use egm_hook::{NamedEvent, Shared, StreamSlot};
pub use egm_instructions::{EgmParts, host_error};
use message_log_thread::Logger;
use run_guidance::{EgmGuidance, RunControl, RunStep};

/// Capacity of the event channel from the cycle hook.
const EVENT_CAPACITY: usize = 1024;
/// Longest wait for a run to halt at the program's end (robot time; real seconds in real
/// time). A halt lasts at most the profile's Default Ramp Time (≤ 10 s) or the braking time
/// at the axis accelerations (well under a second); this only guards against a broken run.
const HALT_WAIT: Duration = Duration::from_secs(60);

/// What the program's last movement was (the controller glue cannot see the zones).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LastMove {
    /// No RAPID movement since the controller started.
    None,
    /// It ended in a stop point (`fine`).
    StopPoint,
    /// It was a fly-by point.
    FlyBy,
}

/// How an EGM run ended with an error.
#[derive(Clone, Debug, PartialEq)]
pub enum RunFailure {
    /// The EGM run itself (comm time-out, supervision, …).
    Egm(EgmError),
    /// The motion core stopped the robot (its event says why).
    Motion(String),
}

impl std::fmt::Display for RunFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RunFailure::Egm(e) => write!(f, "{}", e.event()),
            RunFailure::Motion(m) => f.write_str(m),
        }
    }
}

/// Why an EGM instruction failed (what RAPID sees is decided by the host: an `EgmError`
/// with [`EgmError::rapid_error`] is catchable, everything else stops the program).
#[derive(Clone, Debug, PartialEq)]
pub enum EgmFailure {
    /// Refused by the registry or the driver, or the run ended with this error.
    Egm(EgmError),
    /// Always fatal (an error after `\NoWaitCond`, a motion error, a controller error).
    Fatal(String),
}

impl EgmFailure {
    /// The RAPID error name a program may catch (`ERR_UDPUC_COMM`), `None` when fatal.
    pub fn rapid_error(&self) -> Option<&'static str> {
        match self {
            EgmFailure::Egm(e) => e.rapid_error(),
            EgmFailure::Fatal(_) => None,
        }
    }
}

impl std::fmt::Display for EgmFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EgmFailure::Egm(e) => write!(f, "{}", e.event()),
            EgmFailure::Fatal(m) => f.write_str(m),
        }
    }
}

impl From<EgmError> for EgmFailure {
    fn from(e: EgmError) -> Self {
        EgmFailure::Egm(e)
    }
}

impl From<ControllerError> for EgmFailure {
    fn from(e: ControllerError) -> Self {
        EgmFailure::Fatal(e.to_string())
    }
}

/// rapidvc's EGM options of one controller.
pub struct EgmSetup {
    /// Units, profiles (MOC.cfg) and devices (SIO.cfg, `--device`).
    pub registry: RegistryConfig,
    /// Driver options; `tick` must be the motion core's period.
    pub driver: DriverOptions,
    /// Lockstep: the per-message wait for the sensor's reply (`None`: no lockstep).
    pub lockstep: Option<Duration>,
    /// The report feed (trace `egm_state` column, EGM plot section).
    pub feed: Option<Feed>,
    /// `--egm-log`: where the CSV goes.
    pub log: Option<Box<dyn Write + Send>>,
}

impl std::fmt::Debug for EgmSetup {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EgmSetup")
            .field("driver", &self.driver)
            .field("lockstep", &self.lockstep)
            .field("log", &self.log.is_some())
            .finish_non_exhaustive()
    }
}

/// The run in progress.
#[derive(Debug)]
struct ActiveRun {
    id: EgmId,
    name: String,
    instruction: &'static str,
    control: Arc<RunControl>,
    no_wait_cond: bool,
    result: Option<Result<EgmEnd, RunFailure>>,
}

/// Counters of a finished controller.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EgmSummary {
    /// Lockstep waits for a reply.
    pub lockstep_waits: u64,
    /// Lockstep waits that timed out.
    pub lockstep_timeouts: u64,
    /// Log rows written.
    pub rows_written: u64,
    /// Log rows lost (the writer did not keep up).
    pub rows_dropped: u64,
    /// Events lost (nobody took them in time).
    pub events_dropped: u64,
    /// Datagrams the sessions of every run, stream and path correction did not use, by
    /// cause.
    pub datagrams: DropCounts,
}

/// The program side of EGM (see the module docs).
pub struct EgmController {
    registry: EgmRegistry,
    ctx: DriverContext,
    shared: Arc<Shared>,
    events_rx: Receiver<NamedEvent>,
    retired_rx: Receiver<Box<EgmGuidance>>,
    feed: Option<Feed>,
    run: Option<ActiveRun>,
    events: Vec<(String, EgmEvent)>,
    logger: Option<Logger>,
    capped_noted: bool,
    /// EGMMoveL/EGMMoveC (`controller::corrected_moves`).
    pathcorr: PathCorr,
    /// The controller's speed ratio, percent (`rapidvc serve`; 100 otherwise).
    ratio_pct: u8,
}

impl std::fmt::Debug for EgmController {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EgmController")
            .field("identities", &self.registry.names())
            .field("run", &self.run)
            .finish_non_exhaustive()
    }
}

impl EgmController {
    /// The program side and the cycle hook (for
    /// [`ControllerHandle::start_with_hook`]) of a controller moving `robot` with the I/O
    /// signals `signals`. Error: the log writer thread cannot start.
    pub fn new(
        setup: EgmSetup,
        robot: Robot,
        signals: Arc<SignalTable>,
    ) -> Result<(EgmController, EgmHook), String> {
        let shared = Arc::new(Shared::default());
        let (events_tx, events_rx) = mpsc::sync_channel(EVENT_CAPACITY);
        let (retired_tx, retired_rx) = mpsc::sync_channel(4);
        let (logger, log_tx) = match setup.log {
            Some(out) => {
                let (l, tx) = Logger::start(out)?;
                (Some(l), Some(tx))
            }
            None => (None, None),
        };
        let ctx = DriverContext {
            robot,
            signals,
            options: setup.driver,
            drops: Arc::default(),
        };
        let (pathcorr, pathcorr_hook) =
            path_correction_for(&ctx, setup.lockstep, setup.feed.clone(), log_tx.clone());
        let hook = EgmHook {
            shared: Arc::clone(&shared),
            events: events_tx,
            retired: retired_tx,
            log: log_tx,
            feed: setup.feed.clone(),
            lockstep: setup.lockstep,
            pathcorr: pathcorr_hook,
        };
        let controller = EgmController {
            registry: EgmRegistry::new(setup.registry),
            ctx,
            shared,
            events_rx,
            retired_rx,
            feed: setup.feed,
            run: None,
            events: Vec::new(),
            logger,
            capped_noted: false,
            pathcorr,
            ratio_pct: 100,
        };
        Ok((controller, hook))
    }

    /// Path correction and the registry it works with (EGMMoveL/EGMMoveC).
    pub fn path_corr(&mut self) -> (&mut PathCorr, &mut EgmRegistry) {
        (&mut self.pathcorr, &mut self.registry)
    }

    /// The registry (identities and their states).
    pub fn registry(&self) -> &EgmRegistry {
        &self.registry
    }

    /// Events since the last call: the identity's name and the event (speed limits,
    /// dropped datagrams, supervision, …).
    pub fn take_events(&mut self) -> Vec<(String, EgmEvent)> {
        while let Ok(e) = self.events_rx.try_recv() {
            self.events.push((e.name.to_string(), e.event));
        }
        self.events.extend(self.pathcorr.take_events());
        std::mem::take(&mut self.events)
    }

    // ----- identities and setups -----

    /// `EGMGetId`.
    pub fn get_id(&mut self, handle: &mut ControllerHandle, name: &str) -> Result<(), EgmFailure> {
        self.poll()?;
        let fresh = self.registry.lookup(name).is_none();
        self.registry.get_id(name)?;
        if fresh {
            self.push_state(handle, EgmTraceState::Disconnected);
        }
        Ok(())
    }

    /// `EGMReset` (harmless when `name` is not reserved). A run of the identity brakes
    /// (the EGMRun… waiting for it returns); a stream ends.
    pub fn reset(&mut self, handle: &mut ControllerHandle, name: &str) -> Result<(), EgmFailure> {
        self.poll()?;
        let Some(id) = self.registry.lookup(name) else {
            return Ok(());
        };
        match self.registry.reset(id) {
            StopTarget::Run => {
                if let Some(run) = self.run.as_ref().filter(|r| r.id == id) {
                    run.control.halt();
                }
            }
            StopTarget::Stream => {
                self.remove_stream(id);
            }
            StopTarget::Move | StopTarget::Nothing => {}
        }
        self.push_state(handle, EgmTraceState::Disconnected);
        Ok(())
    }

    /// `EGMGetState(name \CorrectionState)`: the RAPID values of `egmstate` and
    /// `egmcorrstate`.
    pub fn state(&mut self, name: &str) -> Result<(EgmState, CorrState), EgmFailure> {
        self.poll()?;
        Ok(match self.registry.lookup(name) {
            Some(id) => self.registry.state(id),
            None => (EgmState::Disconnected, CorrState::Undefined),
        })
    }

    /// `EGMSetupUC`.
    pub fn setup_uc(
        &mut self,
        handle: &mut ControllerHandle,
        name: &str,
        args: &SetupUc,
    ) -> Result<(), EgmFailure> {
        let id = self.reserved(name, "EGMSetupUC")?;
        self.registry.setup_uc(id, args)?;
        self.push_state(handle, EgmTraceState::Connected);
        Ok(())
    }

    /// `EGMSetupAI`, `EGMSetupAO`, `EGMSetupGI`.
    pub fn setup_signals(
        &mut self,
        handle: &mut ControllerHandle,
        name: &str,
        args: &SetupSignals,
    ) -> Result<(), EgmFailure> {
        let id = self.reserved(name, args.instruction())?;
        let signals = Arc::clone(&self.ctx.signals);
        self.registry.setup_signals(id, args, &signals)?;
        self.push_state(handle, EgmTraceState::Connected);
        Ok(())
    }

    /// `EGMSetupLTAPP`.
    pub fn setup_ltapp(
        &mut self,
        handle: &mut ControllerHandle,
        name: &str,
        args: &SetupLtapp,
    ) -> Result<(), EgmFailure> {
        let id = self.reserved(name, "EGMSetupLTAPP")?;
        self.registry.setup_ltapp(id, args)?;
        self.push_state(handle, EgmTraceState::Connected);
        Ok(())
    }

    /// The signal table (for the interpreter to resolve signal arguments).
    pub fn signals(&self) -> &Arc<SignalTable> {
        &self.ctx.signals
    }

    // ----- activations -----

    /// `EGMActJoint` (with `\StreamStart` the stream starts).
    pub fn act_joint(
        &mut self,
        handle: &mut ControllerHandle,
        name: &str,
        args: &ActJoint,
    ) -> Result<(), EgmFailure> {
        let id = self.reserved(name, "EGMActJoint")?;
        if let Some(plan) = self.registry.act_joint(id, args)? {
            self.start_stream(handle, plan)?;
        }
        Ok(())
    }

    /// `EGMActPose` (with `\StreamStart` the stream starts).
    pub fn act_pose(
        &mut self,
        handle: &mut ControllerHandle,
        name: &str,
        args: &ActPose,
    ) -> Result<(), EgmFailure> {
        let id = self.reserved(name, "EGMActPose")?;
        if let Some(plan) = self.registry.act_pose(id, args)? {
            self.start_stream(handle, plan)?;
        }
        Ok(())
    }

    /// `EGMActMove`.
    pub fn act_move(&mut self, name: &str, args: &ActMove) -> Result<(), EgmFailure> {
        let id = self.reserved(name, "EGMActMove")?;
        self.registry.act_move(id, args)?;
        Ok(())
    }

    // ----- runs -----

    /// `EGMRunJoint`: starts the run (the caller waits with [`EgmController::run_done`]
    /// unless `\NoWaitCond`). `axes` are `\J1` … `\J7`; `last` what the program's last
    /// movement was; `instr` names the instruction in the trace.
    pub fn run_joint(
        &mut self,
        handle: &mut ControllerHandle,
        name: &str,
        args: &RunArgs,
        axes: [bool; 7],
        last: LastMove,
        instr: Option<InstrRef>,
    ) -> Result<(), EgmFailure> {
        let id = self.prepare_run(handle, name, "EGMRunJoint", last)?;
        let plan = self.registry.run_joint(id, args, axes)?;
        self.start_run(handle, plan, instr)
    }

    /// `EGMRunPose`: as [`EgmController::run_joint`] with the direction switches `\x` …
    /// `\rz` and `\Offset`.
    #[allow(clippy::too_many_arguments)]
    pub fn run_pose(
        &mut self,
        handle: &mut ControllerHandle,
        name: &str,
        args: &RunArgs,
        directions: [bool; 6],
        offset: Option<Pose>,
        last: LastMove,
        instr: Option<InstrRef>,
    ) -> Result<(), EgmFailure> {
        let id = self.prepare_run(handle, name, "EGMRunPose", last)?;
        let plan = self.registry.run_pose(id, args, directions, offset)?;
        self.start_run(handle, plan, instr)
    }

    /// True while a run of `name` is active (EGMWaitCond and EGMStop wait for false).
    pub fn run_active(&mut self, name: &str) -> Result<bool, EgmFailure> {
        self.poll_reports();
        Ok(self
            .run
            .as_ref()
            .is_some_and(|r| r.name.eq_ignore_ascii_case(name) && r.result.is_none()))
    }

    /// The EGMRun… waiting for `name`: `Ok(true)` once its run ended well (the result is
    /// taken), `Ok(false)` while it runs, the run's error once it ended with one. `fatal`:
    /// every error is fatal (EGMWaitCond after `\NoWaitCond`).
    pub fn run_done(&mut self, name: &str, fatal: bool) -> Result<bool, EgmFailure> {
        self.poll_reports();
        let Some(run) = self
            .run
            .as_ref()
            .filter(|r| r.name.eq_ignore_ascii_case(name))
        else {
            return Ok(true);
        };
        if run.result.is_none() {
            return Ok(false);
        }
        let fatal = fatal || run.no_wait_cond;
        self.take_result(fatal).map(|_| true)
    }

    /// `EGMStop Mode \RampOutTime`: a stream ends at once; a run is asked to stop (wait for
    /// [`EgmController::run_active`] to become false).
    pub fn stop(
        &mut self,
        handle: &mut ControllerHandle,
        name: &str,
        mode: StopMode,
        ramp_out: Option<Duration>,
    ) -> Result<(), EgmFailure> {
        let id = self.reserved(name, "EGMStop")?;
        match self.registry.stop(id)? {
            StopTarget::Run => {
                if let Some(run) = self.run.as_ref().filter(|r| r.id == id) {
                    run.control.stop(mode, ramp_out);
                }
            }
            StopTarget::Stream => {
                self.remove_stream(id);
                self.push_state(handle, EgmTraceState::Connected);
            }
            StopTarget::Move | StopTarget::Nothing => {}
        }
        Ok(())
    }

    /// After EGMStop's wait: a stopped `\NoWaitCond` run's result is taken here (its error,
    /// if any, is fatal); a run some EGMRun… waits for keeps its result for that wait.
    pub fn stop_done(&mut self, name: &str) -> Result<(), EgmFailure> {
        self.poll_reports();
        let ours = self
            .run
            .as_ref()
            .is_some_and(|r| r.name.eq_ignore_ascii_case(name) && r.no_wait_cond);
        if ours && self.run.as_ref().is_some_and(|r| r.result.is_some()) {
            self.take_result(true)?;
        }
        Ok(())
    }

    // ----- streams -----

    /// `EGMStreamStart \SampleRate`.
    pub fn stream_start(
        &mut self,
        handle: &mut ControllerHandle,
        name: &str,
        sample_rate_ms: Option<f64>,
    ) -> Result<(), EgmFailure> {
        let id = self.reserved(name, "EGMStreamStart")?;
        let plan = self.registry.stream_start(id, sample_rate_ms)?;
        self.start_stream(handle, plan)
    }

    /// `EGMStreamStop`.
    pub fn stream_stop(
        &mut self,
        handle: &mut ControllerHandle,
        name: &str,
    ) -> Result<(), EgmFailure> {
        let id = self.reserved(name, "EGMStreamStop")?;
        if self.registry.stream_stop(id)? {
            self.remove_stream(id);
            self.push_state(handle, EgmTraceState::Connected);
        }
        Ok(())
    }

    // ----- program end -----

    /// The program ended or stopped: a run still active brakes to rest and this waits for
    /// it; streams end. Returns the error of a `\NoWaitCond`
    /// run nobody waited for.
    pub fn program_stopped(&mut self, handle: &mut ControllerHandle) -> Result<(), EgmFailure> {
        self.shared.rapid_stopped.store(true, Ordering::Relaxed);
        self.poll_reports();
        let mut result = Ok(());
        if let Some(run) = &self.run {
            if run.result.is_none() {
                run.control.halt();
                // The halt is bounded by itself (at most the profile's ramp time, or the
                // braking time at the axis accelerations): `--max-time` must not cut it short.
                let waited = handle.wait_until_within(
                    Condition::Predicate(Box::new(|st| st.mode == CoreMode::Planned)),
                    HALT_WAIT,
                );
                if let Err(e) = waited {
                    result = Err(EgmFailure::from(e));
                }
                // The hook hands the run back right after the cycle it ended in.
                self.poll_reports();
            }
            if self.run.as_ref().is_some_and(|r| r.no_wait_cond) {
                if let Err(e) = self.take_result(true) {
                    result = result.and(Err(e));
                }
            } else {
                self.run = None;
            }
        }
        if let Some(e) = self.pathcorr.program_stopped(handle, &mut self.registry) {
            self.events.push(e);
        }
        self.registry.abandon_all();
        self.streams().clear();
        result
    }

    /// The program stopped with the program pointer kept (`rapidvc serve`): a run going on
    /// pauses (its EGM speed ramps to zero over the profile's Default Ramp Time, the
    /// session goes on telling the sensor RAPID_STOPPED) until [`EgmController::resume_run`].
    /// Returns true when a run was paused.
    pub fn pause_run(&mut self) -> bool {
        self.shared.rapid_stopped.store(true, Ordering::Relaxed);
        self.poll_reports();
        match self.run.as_ref().filter(|r| r.result.is_none()) {
            Some(run) => {
                run.control.set_paused(true);
                true
            }
            None => false,
        }
    }

    /// The program started again: a paused run goes on.
    pub fn resume_run(&mut self) {
        self.shared.rapid_stopped.store(false, Ordering::Relaxed);
        if let Some(run) = &self.run {
            run.control.set_paused(false);
        }
    }

    /// What the controller's panel and program state are (`rapidvc serve`): every
    /// `EgmRobot` from the next cycle on reports MOTORS_ON or MOTORS_OFF, and a position
    /// stream RAPID_RUNNING or RAPID_STOPPED (a run's own state follows
    /// [`EgmController::pause_run`] and [`EgmController::resume_run`]).
    pub fn set_controller_state(&mut self, program_running: bool, motors_on: bool) {
        self.shared
            .rapid_stopped
            .store(!program_running, Ordering::Relaxed);
        self.shared.motors_off.store(!motors_on, Ordering::Relaxed);
    }

    /// The controller's speed ratio (1–100 %): scales the EGM speed of the run going on and
    /// of every later one (`egm::servo`, "Speed scale").
    pub fn set_speed_ratio(&mut self, percent: u8) {
        self.ratio_pct = percent.clamp(1, 100);
        if let Some(run) = &self.run {
            run.control.set_ratio(self.ratio_pct);
        }
    }

    /// End: wait for the log writer (call after [`ControllerHandle::finish`], which drops the
    /// cycle hook and with it the writer's input).
    pub fn finish(self) -> Result<EgmSummary, String> {
        let mut summary = EgmSummary {
            lockstep_waits: self.shared.lockstep_waits.load(Ordering::Relaxed),
            lockstep_timeouts: self.shared.lockstep_timeouts.load(Ordering::Relaxed),
            rows_dropped: self.shared.rows_dropped.load(Ordering::Relaxed),
            events_dropped: self.shared.events_dropped.load(Ordering::Relaxed),
            rows_written: 0,
            datagrams: self.ctx.drops.snapshot(),
        };
        if let Some(l) = self.logger {
            summary.rows_written = l.finish()?;
        }
        Ok(summary)
    }

    // ----- internals -----

    fn reserved(&mut self, name: &str, instruction: &'static str) -> Result<EgmId, EgmFailure> {
        self.poll()?;
        self.registry
            .lookup(name)
            .ok_or(EgmFailure::Egm(EgmError::NotReserved { instruction }))
    }

    /// Takes what the hook reported; a `\NoWaitCond` run that failed and that nobody waits
    /// for is reported here (fatal).
    fn poll(&mut self) -> Result<(), EgmFailure> {
        self.poll_reports();
        let failed = self
            .run
            .as_ref()
            .is_some_and(|r| r.no_wait_cond && matches!(r.result, Some(Err(_))));
        if failed {
            self.take_result(true)?;
        }
        Ok(())
    }

    fn poll_reports(&mut self) {
        while let Ok(e) = self.events_rx.try_recv() {
            self.events.push((e.name.to_string(), e.event));
        }
        while let Ok(g) = self.retired_rx.try_recv() {
            let result = match g.driver.outcome() {
                Some(Ok(end)) => Ok(*end),
                Some(Err(e)) => Err(RunFailure::Egm(e.clone())),
                None => Err(RunFailure::Motion(format!(
                    "{}: the motion core stopped the robot during the EGM movement of {} (see the motion event)",
                    g.driver.instruction(),
                    g.name
                ))),
            };
            self.registry.run_finished(g.id, result.is_ok());
            if let Some(run) = self.run.as_mut().filter(|r| r.id == g.id) {
                run.result = Some(result);
            }
        }
    }

    /// Takes the finished run's result (fatal: every error is fatal).
    fn take_result(&mut self, fatal: bool) -> Result<(), EgmFailure> {
        let Some(run) = self.run.take() else {
            return Ok(());
        };
        match run.result {
            None => {
                self.run = Some(run);
                Ok(())
            }
            Some(Ok(_)) => Ok(()),
            Some(Err(RunFailure::Egm(e))) if !fatal => {
                // A catchable error still goes into the event log (41822, …), also when an
                // ERROR handler deals with it.
                self.events.push((run.name.clone(), e.event()));
                Err(EgmFailure::Egm(e))
            }
            Some(Err(RunFailure::Egm(e))) => Err(EgmFailure::Fatal(format!(
                "{} (after {} \\NoWaitCond every EGM error stops the program)",
                e.event(),
                run.instruction
            ))),
            Some(Err(RunFailure::Motion(m))) => Err(EgmFailure::Fatal(m)),
        }
    }

    /// The checks before a run: one run at a time, a RAPID move ran, it ended in a fine
    /// point, the robot stands still and is not halted.
    fn prepare_run(
        &mut self,
        handle: &mut ControllerHandle,
        name: &str,
        instruction: &'static str,
        last: LastMove,
    ) -> Result<EgmId, EgmFailure> {
        let id = self.reserved(name, instruction)?;
        if let Some(run) = &self.run {
            return Err(EgmFailure::Egm(EgmError::BadSetup {
                instruction,
                detail: format!(
                    "the EGM movement of {} is still active (one EGM movement at a time per motion task; finish it with EGMWaitCond or EGMStop)",
                    run.name
                ),
            }));
        }
        match last {
            LastMove::None => {
                return Err(EgmFailure::Egm(EgmError::NoPreviousMove { instruction }));
            }
            LastMove::FlyBy => {
                return Err(EgmFailure::Egm(EgmError::NotInFinePoint { instruction }));
            }
            LastMove::StopPoint => {}
        }
        let st = handle.wait_until(Condition::InPos)?;
        if st.halted {
            return Err(EgmFailure::Fatal(format!(
                "{instruction}: the robot is stopped after a motion error"
            )));
        }
        Ok(id)
    }

    fn start_run(
        &mut self,
        handle: &mut ControllerHandle,
        mut plan: RunPlan,
        instr: Option<InstrRef>,
    ) -> Result<(), EgmFailure> {
        let id = plan.id;
        let cap = self
            .ctx
            .robot
            .model()
            .max_speed
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        if plan.max_speed_deviation > cap {
            if !self.capped_noted {
                self.capped_noted = true;
                self.events.push((
                    plan.name.clone(),
                    EgmEvent {
                        number: 0,
                        title: "note",
                        detail: format!(
                            "{}: \\MaxSpeedDeviation {} °/s is above the robot's slowest axis speed; EGM speeds are limited to {cap} °/s",
                            plan.instruction, plan.max_speed_deviation
                        ),
                    },
                ));
            }
            plan.max_speed_deviation = cap;
        }
        let stream = if plan.stops_stream {
            self.take_stream(id)
        } else {
            None
        };
        let opened = match stream {
            Some(s) => Ok((s.stream.into_source(), s.socket)),
            None => DeviceSocket::open(&plan.source).map(|s| (EgmSource::new(&plan.source), s)),
        };
        let (source, socket) = match opened {
            Ok(s) => s,
            Err(e) => {
                self.registry.run_finished(id, false);
                return Err(e.into());
            }
        };
        let now = handle.now();
        let current = handle.state().setpoint.joints;
        let driver = match EgmDriver::start(now, &self.ctx, &plan, source, &current) {
            Ok(d) => d,
            Err(e) => {
                self.registry.run_finished(id, false);
                return Err(e.into());
            }
        };
        let control = Arc::new(RunControl::default());
        control.set_ratio(self.ratio_pct);
        let guidance = EgmGuidance {
            id,
            name: Arc::from(plan.name.as_str()),
            driver,
            socket,
            stepped: false,
            control: Arc::clone(&control),
            speed_limited: false,
            last: None,
            ratio: 1.0,
        };
        let slot = &self.shared.run;
        *slot.lock().unwrap_or_else(PoisonError::into_inner) = Some(guidance);
        let step = Box::new(RunStep(Arc::clone(slot)));
        if let Err(e) = handle.start_external(step, plan.tool, instr) {
            slot.lock().unwrap_or_else(PoisonError::into_inner).take();
            self.registry.run_finished(id, false);
            return Err(e.into());
        }
        self.run = Some(ActiveRun {
            id,
            name: plan.name.clone(),
            instruction: plan.instruction,
            control,
            no_wait_cond: plan.no_wait_cond,
            result: None,
        });
        self.push_state(handle, EgmTraceState::Running);
        Ok(())
    }

    fn start_stream(
        &mut self,
        handle: &mut ControllerHandle,
        plan: StreamPlan,
    ) -> Result<(), EgmFailure> {
        let started = DeviceSocket::open(&plan.source).and_then(|socket| {
            let now = handle.now();
            let current = handle.state().setpoint.joints;
            let source = EgmSource::new(&plan.source);
            EgmStream::start(now, &self.ctx, &plan, source, &current).map(|s| (s, socket))
        });
        match started {
            Ok((stream, socket)) => {
                self.streams().push(StreamSlot {
                    id: plan.id,
                    name: Arc::from(plan.name.as_str()),
                    stream,
                    socket,
                });
                self.push_state(handle, EgmTraceState::Running);
                Ok(())
            }
            Err(e) => {
                let _ = self.registry.stream_stop(plan.id);
                Err(e.into())
            }
        }
    }

    fn streams(&self) -> std::sync::MutexGuard<'_, Vec<StreamSlot>> {
        self.shared
            .streams
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }

    fn take_stream(&mut self, id: EgmId) -> Option<StreamSlot> {
        let mut streams = self.streams();
        let i = streams.iter().position(|s| s.id == id)?;
        Some(streams.swap_remove(i))
    }

    fn remove_stream(&mut self, id: EgmId) {
        drop(self.take_stream(id));
    }

    fn push_state(&self, handle: &mut ControllerHandle, state: EgmTraceState) {
        if let Some(feed) = &self.feed {
            feed.push_egm_state(handle.now(), state);
        }
    }
}

#[cfg(test)]
mod tests;
