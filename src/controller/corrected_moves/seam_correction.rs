//! The motion core's side of one corrected sequence: [`SeamCorrection`] implements `motion::PathCorrection` with the path frame and the `PathCorrector` of `egm::path_correction`, and remembers what it applied for the feed and the sensor link.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex, TryLockError};

use nalgebra::Vector3;

use crate::egm::EgmError;
use crate::egm::event::EventKind;
use crate::egm::path_correction::{
    PathCorrConfig, PathCorrConfigError, PathCorrector, PathFrame, PathOffset, Rejection,
    Scheduled, Tracker, look_ahead_distance,
};
use crate::egm::registry::TrackerKind;
use crate::motion::{InstrRef, MotionError, PathCorrection, PathPoint};
use crate::robot::{Pose, ToolData, WobjData};
use crate::time::RobotTime;

/// Most EGMMoveL/EGMMoveC of one sequence waiting in the motion queue at a time (the queue
/// is shorter; older entries are forgotten once the robot has passed them).
pub(super) const MAX_MOVES: usize = 64;

/// Most measurements remembered for the feed's seam column.
const MAX_MEASURED: usize = 256;

/// One EGMMoveL/EGMMoveC of the sequence.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct CorrectedMove {
    /// The motion command id.
    pub id: u64,
    /// `EGMMoveL` or `EGMMoveC`.
    pub instruction: &'static str,
    /// `\NoCorr`.
    pub no_corr: bool,
    /// The tool (for the Cartesian feedback to the sensor).
    pub tool: ToolData,
    /// The work object (the frame of that feedback).
    pub wobj: WobjData,
}

/// What the correction did in the last cycle it ran.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Applied {
    /// Robot time of the cycle.
    pub time: RobotTime,
    /// Arc length along the programmed path, mm.
    pub s: f64,
    /// The offset applied, path frame, mm.
    pub offset: PathOffset,
    /// The same offset in world coordinates, mm (the corrected TCP less this is the
    /// programmed one).
    pub world: Vector3<f64>,
    /// The sensor frame origin's distance ahead of the TCP along the path, mm (≥ 0).
    pub look_ahead: f64,
    /// The motion command id of that cycle.
    pub id: u64,
}

/// The path correction of one sequence (see the module docs).
#[derive(Debug)]
pub(super) struct SeamCorrection {
    name: String,
    tracker: TrackerKind,
    sensor_frame: Pose,
    corrector: PathCorrector,
    moves: VecDeque<CorrectedMove>,
    frame: Option<PathFrame>,
    applied: Option<Applied>,
    /// Measurements scheduled for an arc length the TCP has not reached yet.
    measured: VecDeque<Scheduled>,
    /// The last measurement the TCP passed this cycle (the feed's seam value).
    measured_now: Option<PathOffset>,
    failure: Option<MotionError>,
    /// The robot left the sequence without a fine point (the robot stopped).
    left: bool,
}

impl SeamCorrection {
    /// A sequence for identity `name` with `config` (its tracker's look-ahead is updated
    /// every cycle from the sensor frame).
    pub fn new(
        name: &str,
        tracker: TrackerKind,
        sensor_frame: Pose,
        config: PathCorrConfig,
    ) -> Result<SeamCorrection, PathCorrConfigError> {
        let mut corrector = PathCorrector::new(config)?;
        corrector.start(0.0, 0.0);
        Ok(SeamCorrection {
            name: name.to_string(),
            tracker,
            sensor_frame,
            corrector,
            moves: VecDeque::with_capacity(MAX_MOVES),
            frame: None,
            applied: None,
            measured: VecDeque::with_capacity(MAX_MEASURED),
            measured_now: None,
            failure: None,
            left: false,
        })
    }

    /// Add a move of the sequence (before it is queued). False when too many wait.
    pub fn push_move(&mut self, m: CorrectedMove) -> bool {
        if self.moves.len() >= MAX_MOVES {
            return false;
        }
        self.moves.push_back(m);
        true
    }

    /// The move of the last corrected cycle (else the first one queued).
    pub fn current_move(&self) -> Option<&CorrectedMove> {
        match self.applied {
            Some(a) => self.moves.iter().find(|m| m.id == a.id),
            None => self.moves.front(),
        }
    }

    /// What the last corrected cycle applied.
    pub fn applied(&self) -> Option<Applied> {
        self.applied
    }

    /// The measurement the TCP reached in the last cycle, if any (taken).
    pub fn take_measured(&mut self) -> Option<PathOffset> {
        self.measured_now.take()
    }

    /// A sensor correction received at `now_s` (s), measured `age_s` earlier.
    pub fn measurement(&mut self, now_s: f64, pos: [f64; 3], age_s: f64) -> Result<(), Rejection> {
        let scheduled = self.corrector.measurement(now_s, pos, age_s)?;
        if self.measured.len() >= MAX_MEASURED {
            self.measured.pop_front();
        }
        while self.measured.back().is_some_and(|m| m.s >= scheduled.s) {
            self.measured.pop_back();
        }
        self.measured.push_back(scheduled);
        Ok(())
    }

    /// True once (taken) after the robot left the sequence without a fine point.
    pub fn take_left(&mut self) -> bool {
        std::mem::take(&mut self.left)
    }

    /// Stop the robot at the next corrected cycle with `error` (the sensor failed).
    pub fn fail(&mut self, error: &EgmError) {
        let event = error.event();
        self.failure = Some(MotionError::PathCorrection {
            number: event.number,
            title: event.title,
            detail: event.detail,
            rapid_error: error.rapid_error(),
        });
    }

    fn tracker(&self, look_ahead: f64) -> Tracker {
        match self.tracker {
            TrackerKind::Aptr => Tracker::Aptr,
            TrackerKind::Latr => Tracker::Latr { look_ahead },
        }
    }

    /// The tracker with the current look-ahead (for the simulated seam sensors).
    pub fn sensing(&self) -> Tracker {
        self.tracker(self.applied.map_or(0.0, |a| a.look_ahead))
    }
}

/// The sequence's correction, shared by the executor (which calls it inside the cycle, through
/// [`SharedSeam`]) and the path-correction hook (which reaches it, typed, around the cycle).
/// Both run on the motion thread one after the other, so the lock is never contended.
pub(super) type SeamSlot = Arc<Mutex<SeamCorrection>>;

/// Runs `f` on the correction in `slot`: `None` only if another thread held it, which the
/// motion thread's sole ownership rules out.
pub(super) fn with_seam<R>(slot: &SeamSlot, f: impl FnOnce(&mut SeamCorrection) -> R) -> Option<R> {
    match slot.try_lock() {
        Ok(mut seam) => Some(f(&mut seam)),
        Err(TryLockError::Poisoned(p)) => Some(f(&mut p.into_inner())),
        Err(TryLockError::WouldBlock) => None,
    }
}

/// The executor's handle on a [`SeamSlot`].
pub(super) struct SharedSeam(pub SeamSlot);

impl PathCorrection for SharedSeam {
    fn corrects(&self, instr: &InstrRef) -> bool {
        with_seam(&self.0, |s| s.corrects(instr)).unwrap_or(false)
    }

    fn offset(&mut self, now: RobotTime, point: &PathPoint) -> Result<Vector3<f64>, MotionError> {
        with_seam(&self.0, |s| s.offset(now, point)).unwrap_or_else(|| Ok(Vector3::zeros()))
    }

    fn leave(&mut self, now: RobotTime, instr: &InstrRef) -> Result<(), MotionError> {
        with_seam(&self.0, |s| s.leave(now, instr)).unwrap_or(Ok(()))
    }

    fn rename(&self, instr: &InstrRef) -> &'static str {
        with_seam(&self.0, |s| s.rename(instr)).unwrap_or(instr.name)
    }
}

impl PathCorrection for SeamCorrection {
    fn corrects(&self, instr: &InstrRef) -> bool {
        self.moves.iter().any(|m| m.id == instr.id)
    }

    fn offset(&mut self, now: RobotTime, point: &PathPoint) -> Result<Vector3<f64>, MotionError> {
        if let Some(e) = self.failure.take() {
            return Err(e);
        }
        // The robot plays moves in order: the ones before this one are done.
        while self.moves.front().is_some_and(|m| m.id < point.instr.id) {
            self.moves.pop_front();
        }
        let no_corr = self
            .moves
            .iter()
            .find(|m| m.id == point.instr.id)
            .is_some_and(|m| m.no_corr);
        self.corrector.set_enabled(!no_corr);
        let tool_z = point.tcp.rotation * Vector3::z();
        let frame = PathFrame::new(point.step, tool_z, self.frame.as_ref());
        self.frame = Some(frame);
        let tcp = point.tcp.translation.vector;
        let sensor = (point.flange * self.sensor_frame).translation.vector;
        let look_ahead = look_ahead_distance(&frame, &tcp, &sensor).max(0.0);
        self.corrector.set_look_ahead(look_ahead);
        let t = now.as_secs_f64();
        let offset = self.corrector.step(t, point.s);
        self.measured_now = None;
        while let Some(m) = self.measured.front().copied() {
            if m.s > point.s {
                break;
            }
            self.measured_now = Some(m.offset);
            self.measured.pop_front();
        }
        let world = frame.to_world(offset);
        self.applied = Some(Applied {
            time: now,
            s: point.s,
            offset,
            world,
            look_ahead,
            id: point.instr.id,
        });
        Ok(world)
    }

    fn leave(&mut self, _now: RobotTime, instr: &InstrRef) -> Result<(), MotionError> {
        self.left = true;
        let error = EgmError::PathCorrFinePoint {
            name: self.name.clone(),
            instruction: instr.name,
            start: false,
        };
        let event = error.event();
        Err(MotionError::PathCorrection {
            number: event.number,
            title: event.title,
            detail: event.detail,
            rapid_error: None,
        })
    }

    fn rename(&self, instr: &InstrRef) -> &'static str {
        self.moves
            .iter()
            .find(|m| m.id == instr.id)
            .map_or(instr.name, |m| m.instruction)
    }
}

/// The event of a rejected correction: 90104 for a non-finite value, 90132 otherwise.
pub(super) fn rejection_kind(r: &Rejection) -> EventKind {
    match r {
        Rejection::NotFinite { .. } => EventKind::InvalidReference,
        _ => EventKind::CorrectionRejected,
    }
}
