//! Path correction in the controller (EGMMoveL/EGMMoveC): the program side [`PathCorr`] checks and submits corrected moves, the motion side [`PathCorrHook`] runs the sensor link and the corrector every motion cycle.
//!
//! # Wiring
//!
//! ```text
//! let (mut pc, hook) = pathcorr::path_correction(ctx, options, feed, log);
//! ControllerHandle::start_with_hook(config, sinks, Some(Box::new(hook)))   // or inside another hook
//! EGMMoveL / EGMMoveC → ticket = pc.submit(&mut handle, &mut registry, id, cmd, no_corr, last_move)?
//!     fine point: wait for Done(ticket.cmd_id), then pc.finish_sequence(&mut handle, &mut registry, ok)?
//!     (or pc.wait_fine(&mut handle, &mut registry, ticket)? without an interpreter)
//! other move while a sequence is open → pc.check_other_move(instruction)? (the executor refuses it anyway)
//! error, EGMStop, PP to Main → pc.abandon(&mut handle, &mut registry)
//! program end or stop → pc.program_stopped(&mut handle, &mut registry) (an event if still open)
//! events for the event log: pc.take_events()
//! ```
//!
//! In `rapidvc run` the EGM controller (`controller::egm_controller`) owns the program side and its cycle
//! hook the motion side; `ControllerHost` offers the interpreter's `EgmPathHost` through the
//! blanket implementation in `corrected_moves/egm_move_instructions.rs`.
//!
//! # What happens
//!
//! * The first EGMMoveL/EGMMoveC of a sequence asks the registry (setup with `\PathCorr` or
//!   EGMSetupLTAPP, EGMActMove, a Level 2 profile: [`crate::egm::EgmRegistry::move_start`]),
//!   checks that a RAPID move ran since the controller started and that the robot stands in
//!   a fine point ("EGM Path correction has to start and end in a fine point"), opens the
//!   data source and hands a `SeamCorrection` (the motion core's `PathCorrection`, with the
//!   `PathCorrector` of `egm::path_correction`) and a [`crate::egm::CorrectionLink`] to the hook.
//! * Every corrected move is announced to the hook before it is queued as a plain `MoveL` /
//!   `MoveC`: the planner plans it uncorrected, the executor adds the smoothed correction in
//!   the path frame each cycle (`motion::correction`) and the trace names it `EGMMoveL`.
//! * Each cycle after the tick the hook hands the device's waiting datagrams to the link,
//!   ticks it and sends the robot's state it produced to the sensor at the EGMActMove rate (`EgmRobot`; simulated seams and signals are sampled instead), gives the
//!   corrections that come back to the corrector — a rejected one (NaN: 90104; too large or
//!   too old: 90132) is an event and the previous correction stays — and pushes one
//!   path-correction sample (arc length, correction in y and z) into the output feed.
//! * The fine point ending the sequence ends it: the hook removes the correction (the robot
//!   stays on the corrected path), the registry goes back to CONNECTED. A move that is not an
//!   EGM move after a corrected fly-by point stops the robot with the same manual wording
//!   (event 90131).
//! * A sensor that stops answering for `\CommTimeout` is event 41822 and `ERR_UDPUC_COMM`:
//!   the robot stops at its next corrected cycle, the program side raises the error (and
//!   recovers the motion core so that an ERROR handler can go on).
//!
//! In virtual time with an external sensor, [`HookOptions::lockstep`] makes every cycle that
//! sent a message wait (real time) for the sensor's reply, as for EGM guidance.
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

mod correction_hook;
mod egm_move_instructions;
mod seam_correction;

use std::sync::mpsc::{self, Receiver, SyncSender, TryRecvError};

use crate::controller::sample_feed::Feed;
use crate::egm::driver::DEFAULT_REPLY_TIMEOUT;
use crate::egm::event::EgmEvent;
use crate::egm::path_correction::{PathCorrConfig, Tracker};
use crate::egm::registry::TrackerKind;
use crate::egm::{CorrectionLink, DriverContext, EgmError, EgmId, EgmRegistry, EgmSource};
use crate::robot::command::MotionCommand;

use super::ControllerError;
use super::condition::Condition;
use super::egm_controller::{DeviceSocket, LastMove};
use super::handle::ControllerHandle;

use correction_hook::Request;
pub use correction_hook::{HookOptions, NamedLogRow, PathCorrHook, Report};
use seam_correction::{CorrectedMove, SeamCorrection};

/// Requests that may wait for the hook (a sequence's moves plus begin and end).
const REQUEST_CAPACITY: usize = seam_correction::MAX_MOVES + 8;
/// Reports that may wait for the program side.
const REPORT_CAPACITY: usize = 4096;

/// rapidvc's options of path correction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathCorrOptions {
    /// Limits, smoothing and absolute/incremental mode; the tracker is set per sequence from
    /// the setup (`\APTR` / `\LATR`).
    pub corrector: PathCorrConfig,
    /// The motion side's options.
    pub hook: HookOptions,
}

impl Default for PathCorrOptions {
    fn default() -> Self {
        PathCorrOptions {
            corrector: PathCorrConfig::aptr(),
            hook: HookOptions {
                lockstep: false,
                reply_timeout: DEFAULT_REPLY_TIMEOUT,
            },
        }
    }
}

/// The program side and the motion side of path correction for one controller; the
/// motion side goes into the controller's cycle hook. `feed` reaches the trace and plot,
/// `log` the EGM message log writer.
pub fn path_correction(
    ctx: DriverContext,
    options: PathCorrOptions,
    feed: Option<Feed>,
    log: Option<SyncSender<NamedLogRow>>,
) -> (PathCorr, PathCorrHook) {
    let (req_tx, req_rx) = mpsc::sync_channel(REQUEST_CAPACITY);
    let (rep_tx, rep_rx) = mpsc::sync_channel(REPORT_CAPACITY);
    let hook = PathCorrHook::new(req_rx, rep_tx, feed, log, options.hook);
    let pc = PathCorr {
        ctx,
        options,
        requests: req_tx,
        reports: rep_rx,
        active: None,
        failed: None,
        left: false,
        events: Vec::new(),
        last_link: None,
    };
    (pc, hook)
}

/// [`path_correction`] with the EGM options of a controller: `lockstep` is the per-message
/// wait for an external sensor's reply (`None`: no lockstep).
pub fn path_correction_for(
    ctx: &DriverContext,
    lockstep: Option<std::time::Duration>,
    feed: Option<Feed>,
    log: Option<SyncSender<NamedLogRow>>,
) -> (PathCorr, PathCorrHook) {
    let mut options = PathCorrOptions::default();
    if let Some(t) = lockstep {
        options.hook.lockstep = true;
        options.hook.reply_timeout = t;
    }
    path_correction(ctx.clone(), options, feed, log)
}

/// Why a corrected move failed.
#[derive(Debug, thiserror::Error)]
pub enum PathCorrError {
    /// Refused by EGM (the registry or the sensor): see [`EgmError::rapid_error`].
    #[error(transparent)]
    Egm(#[from] EgmError),
    /// Refused or stopped by the motion core.
    #[error(transparent)]
    Controller(#[from] ControllerError),
}

impl PathCorrError {
    /// The RAPID error a handler can catch (`ERR_UDPUC_COMM`, a motion error's name), or
    /// `None` for a fatal error.
    pub fn rapid_error(&self) -> Option<&'static str> {
        match self {
            PathCorrError::Egm(e) => e.rapid_error(),
            PathCorrError::Controller(ControllerError::Rejected(e)) => e.rapid_error_name(),
            PathCorrError::Controller(ControllerError::Stopped(ev)) => ev.error.rapid_error_name(),
            PathCorrError::Controller(_) => None,
        }
    }

    /// The event-log line (number, title, detail).
    pub fn event_text(&self) -> String {
        match self {
            PathCorrError::Egm(e) => e.event().to_string(),
            PathCorrError::Controller(ControllerError::Stopped(ev)) => ev.to_string(),
            PathCorrError::Controller(e) => e.to_string(),
        }
    }
}

/// A corrected move that was queued.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Ticket {
    /// The motion command id.
    pub cmd_id: u64,
    /// It ends in a fine point: call [`PathCorr::wait_fine`].
    pub fine: bool,
}

#[derive(Debug)]
struct Active {
    id: EgmId,
    name: String,
}

/// The program side of path correction (see the module docs).
pub struct PathCorr {
    ctx: DriverContext,
    options: PathCorrOptions,
    requests: SyncSender<Request>,
    reports: Receiver<Report>,
    active: Option<Active>,
    failed: Option<EgmError>,
    /// The robot left the running sequence without a fine point (already an error).
    left: bool,
    events: Vec<(String, EgmEvent)>,
    last_link: Option<Box<CorrectionLink>>,
}

impl std::fmt::Debug for PathCorr {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PathCorr")
            .field("active", &self.active)
            .field("failed", &self.failed)
            .finish_non_exhaustive()
    }
}

impl PathCorr {
    /// True while a corrected sequence runs (its fine point not reached yet).
    pub fn is_active(&self) -> bool {
        self.active.is_some()
    }

    /// Events reported since the last call (rejected corrections, session events, 41822),
    /// with the identity's name.
    pub fn take_events(&mut self) -> Vec<(String, EgmEvent)> {
        self.pump();
        std::mem::take(&mut self.events)
    }

    /// The link of the last sequence that ended (its session statistics).
    pub fn last_link(&self) -> Option<&CorrectionLink> {
        self.last_link.as_deref()
    }

    fn pump(&mut self) {
        loop {
            match self.reports.try_recv() {
                Ok(Report::Event(name, e)) => self.events.push((name.to_string(), e)),
                Ok(Report::Failed(e)) => {
                    self.failed.get_or_insert(e);
                }
                Ok(Report::Ended(ended)) => {
                    let (link, socket) = *ended;
                    // The device's socket closes here, off the motion cycle.
                    drop(socket);
                    self.last_link = Some(Box::new(link));
                }
                Ok(Report::Left) => self.left = true,
                Err(TryRecvError::Empty) | Err(TryRecvError::Disconnected) => return,
            }
        }
    }

    fn send(&mut self, r: Request) -> Result<(), PathCorrError> {
        self.requests.send(r).map_err(|_| {
            PathCorrError::Controller(ControllerError::Thread(
                "the motion side of path correction has stopped".into(),
            ))
        })
    }

    /// `EGMMoveL` / `EGMMoveC` of identity `id`: `cmd` is the `MoveL` / `MoveC` with the
    /// instruction's ToPoint (CirPoint), Speed, Zone, Tool, `\WObj`, `\TLoad` and the active
    /// program displacement; `no_corr` is `\NoCorr`. Starts a sequence when none runs and
    /// queues the move; for a fine point call [`PathCorr::wait_fine`] next.
    pub fn submit(
        &mut self,
        handle: &mut ControllerHandle,
        registry: &mut EgmRegistry,
        id: EgmId,
        cmd: MotionCommand,
        no_corr: bool,
        last: LastMove,
    ) -> Result<Ticket, PathCorrError> {
        let instruction = match &cmd {
            MotionCommand::MoveL(_) => "EGMMoveL",
            MotionCommand::MoveC(_) => "EGMMoveC",
            _ => {
                return Err(EgmError::Unsupported {
                    instruction: "EGMMoveL",
                    what: "a path-corrected movement that is not linear or circular",
                }
                .into());
            }
        };
        self.pump();
        if let Some(e) = self.failed.take() {
            self.abandon(handle, registry);
            return Err(e.into());
        }
        if self.left {
            // The robot already stopped on that (the program handled its error).
            self.abandon(handle, registry);
        }
        let args = cmd.args().clone();
        if !args.tool.robhold {
            return Err(EgmError::Unsupported {
                instruction,
                what: "path correction with a stationary tool (the sensor must be mounted on the robot)",
            }
            .into());
        }
        if let Some(a) = &self.active
            && a.id != id
        {
            return Err(EgmError::Busy {
                name: a.name.clone(),
                instruction,
                activity: "correcting the path (one sensor per robot: end its sequence in a fine point first)",
            }
            .into());
        }
        let plan = registry.move_start(id, instruction)?;
        if self.active.is_none() {
            if let Err(e) = self.begin(handle, &plan, instruction, last) {
                registry.move_finished(id, false);
                return Err(e);
            }
            self.active = Some(Active {
                id,
                name: plan.name.clone(),
            });
        }
        self.send(Request::Move(Box::new(CorrectedMove {
            id: args.id,
            instruction,
            no_corr,
            tool: args.tool,
            wobj: args.wobj.clone(),
        })))?;
        if let Err(e) = handle.submit(cmd) {
            self.pump();
            let err = self.failure_or(e);
            self.abandon(handle, registry);
            return Err(err);
        }
        Ok(Ticket {
            cmd_id: args.id,
            fine: args.zone.finep,
        })
    }

    /// Start a sequence: the fine-point checks, the source, the corrector and the link.
    fn begin(
        &mut self,
        handle: &mut ControllerHandle,
        plan: &crate::egm::registry::MovePlan,
        instruction: &'static str,
        last: LastMove,
    ) -> Result<(), PathCorrError> {
        let st = handle.state();
        if last == LastMove::None {
            return Err(EgmError::NoPreviousMove { instruction }.into());
        }
        if last == LastMove::FlyBy || !st.in_position() {
            return Err(EgmError::PathCorrFinePoint {
                name: plan.name.clone(),
                instruction,
                start: true,
            }
            .into());
        }
        let mut config = self.options.corrector;
        config.tracker = match plan.tracker {
            TrackerKind::Aptr => Tracker::Aptr,
            TrackerKind::Latr => Tracker::Latr { look_ahead: 0.0 },
        };
        let seam = SeamCorrection::new(&plan.name, plan.tracker, plan.sensor_frame, config)
            .map_err(|e| EgmError::BadSetup {
                instruction,
                detail: e.to_string(),
            })?;
        let socket = DeviceSocket::open(&plan.source)?;
        let link = CorrectionLink::start(
            st.setpoint.time,
            &self.ctx,
            plan,
            EgmSource::new(&plan.source),
            &st.setpoint.joints,
        )?;
        let name: std::sync::Arc<str> = std::sync::Arc::from(plan.name.as_str());
        self.send(Request::Begin(Box::new((seam, link, socket, name))))
    }

    /// The corrected move `ticket` ends in a fine point: wait until the robot stands there,
    /// then end the sequence (CONNECTED). A sensor failure meanwhile is its error
    /// (`ERR_UDPUC_COMM`); the motion core is recovered so the program may go on.
    pub fn wait_fine(
        &mut self,
        handle: &mut ControllerHandle,
        registry: &mut EgmRegistry,
        ticket: Ticket,
    ) -> Result<(), PathCorrError> {
        let waited = handle.wait_until(Condition::Done(ticket.cmd_id));
        self.pump();
        match waited {
            Ok(_) => {
                self.end(registry, true)?;
                match self.failed.take() {
                    Some(e) => Err(e.into()),
                    None => Ok(()),
                }
            }
            Err(e) => {
                let err = self.failure_or(e);
                self.abandon(handle, registry);
                Err(err)
            }
        }
    }

    /// The fine point of the last move of a sequence was reached (`ok`; a sensor failure
    /// reported meanwhile is the error), or waiting for it failed (the sequence is
    /// abandoned, see [`PathCorr::abandon`]).
    pub fn finish_sequence(
        &mut self,
        handle: &mut ControllerHandle,
        registry: &mut EgmRegistry,
        ok: bool,
    ) -> Result<(), PathCorrError> {
        self.pump();
        if !ok {
            self.abandon(handle, registry);
            return Ok(());
        }
        self.end(registry, true)?;
        match self.failed.take() {
            Some(e) => Err(e.into()),
            None => Ok(()),
        }
    }

    /// The program ended or stopped: a sequence still open is abandoned; it did not end in
    /// a fine point, which is returned as the event to log.
    pub fn program_stopped(
        &mut self,
        handle: &mut ControllerHandle,
        registry: &mut EgmRegistry,
    ) -> Option<(String, EgmEvent)> {
        self.pump();
        if self.left {
            // Already reported as the error that stopped the robot.
            self.abandon(handle, registry);
            return None;
        }
        let a = self.active.as_ref()?;
        let name = a.name.clone();
        let error = EgmError::PathCorrFinePoint {
            name: name.clone(),
            instruction: "EGMMoveL",
            start: false,
        };
        self.abandon(handle, registry);
        Some((name, error.event()))
    }

    /// The sensor's failure if one was reported (then the motion core is recovered: the
    /// program may handle `ERR_UDPUC_COMM`), else `e`.
    fn failure_or(&mut self, e: ControllerError) -> PathCorrError {
        match self.failed.take() {
            Some(f) => PathCorrError::Egm(f),
            None => PathCorrError::Controller(e),
        }
    }

    fn end(&mut self, registry: &mut EgmRegistry, ok: bool) -> Result<(), PathCorrError> {
        if let Some(a) = self.active.take() {
            registry.move_finished(a.id, ok);
            self.send(Request::End)?;
        }
        Ok(())
    }

    /// Another (not path-corrected) move instruction is about to be queued: refused while a
    /// corrected sequence is open (it did not end in a fine point).
    pub fn check_other_move(&mut self, instruction: &'static str) -> Result<(), PathCorrError> {
        match &self.active {
            Some(a) => Err(EgmError::PathCorrFinePoint {
                name: a.name.clone(),
                instruction,
                start: false,
            }
            .into()),
            None => Ok(()),
        }
    }

    /// End a running sequence without its fine point (EGMStop, EGMReset, PP to Main, an
    /// error): the correction is removed, a halted motion core is recovered, the identity
    /// goes back to CONNECTED with correction state ERROR.
    pub fn abandon(&mut self, handle: &mut ControllerHandle, registry: &mut EgmRegistry) {
        self.failed = None;
        self.left = false;
        if self.active.is_some() {
            // Ignore a dead motion side: there is nothing left to stop.
            let _ = self.end(registry, false);
            if handle.state().halted {
                handle.recover();
            }
        }
    }
}

#[cfg(test)]
mod tests;
