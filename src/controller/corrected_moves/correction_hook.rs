//! The motion side of path correction: [`PathCorrHook`], a `CycleHook` that installs each corrected sequence into the executor (keeping a typed handle on it), carries its sensor link's datagrams and ticks the link every cycle, feeds measurements to the corrector and path-correction samples to the output feed.

use std::sync::Arc;
use std::sync::mpsc::{Receiver, SyncSender, TryRecvError, TrySendError};
use std::time::Duration;

use crate::controller::cycle_hook::CycleHook;
use crate::controller::egm_controller::DeviceSocket;
use crate::controller::sample_feed::{EgmTraceState, Feed, FeedItem, PathCorrSample};
use crate::egm::CorrectionLink;
use crate::egm::driver::CorrectionInput;
use crate::egm::event::EgmEvent;
use crate::egm::message_log::LogRow;
use crate::motion::{Executor, Setpoint};
use crate::robot::{ToolData, WobjData};
use crate::time::RobotTime;

use super::seam_correction::{SeamCorrection, SeamSlot, SharedSeam, rejection_kind, with_seam};
use crate::egm::path_correction::Rejection;

/// Rejected corrections are reported at most this often.
pub const REJECTION_REPEAT: Duration = Duration::from_secs(1);

/// From the program side to the hook.
pub(super) enum Request {
    /// Start a corrected sequence: install the correction, start exchanging with the sensor.
    Begin(Box<(SeamCorrection, CorrectionLink, DeviceSocket, Arc<str>)>),
    /// A move of the running sequence (sent before the move is queued).
    Move(Box<super::seam_correction::CorrectedMove>),
    /// The sequence ended (its fine point was reached, or it was abandoned).
    End,
}

/// From the hook to the program side.
#[derive(Debug)]
pub enum Report {
    /// An event for the event log (rejected corrections, session events) of the identity.
    Event(Arc<str>, EgmEvent),
    /// The sensor failed (`ERR_UDPUC_COMM`); the robot stops at its next corrected cycle.
    Failed(crate::egm::EgmError),
    /// The robot left the sequence without a fine point and stopped (its motion error
    /// reaches the program): the sequence is over.
    Left,
    /// The sequence ended; the link comes back for its statistics, the device's socket to
    /// be closed off the cycle.
    Ended(Box<(CorrectionLink, DeviceSocket)>),
}

/// One EGM message log row of an identity (for `--egm-log`).
pub type NamedLogRow = (Arc<str>, LogRow);

/// Options of the motion side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HookOptions {
    /// Virtual time driven by an external sensor: after each message to it, wait (real time,
    /// at most `reply_timeout`) for its reply before the next cycle.
    pub lockstep: bool,
    /// The lockstep wait for one reply.
    pub reply_timeout: Duration,
}

/// The motion side of path correction (see the module docs of `controller::corrected_moves`).
pub struct PathCorrHook {
    requests: Receiver<Request>,
    reports: SyncSender<Report>,
    feed: Option<Feed>,
    log: Option<SyncSender<NamedLogRow>>,
    options: HookOptions,
    link: Option<(CorrectionLink, DeviceSocket)>,
    /// The running sequence's correction (also installed in the executor).
    seam: Option<SeamSlot>,
    name: Arc<str>,
    dropped: u64,
    last_rejection: Option<RobotTime>,
    rejections_held: u32,
}

impl std::fmt::Debug for PathCorrHook {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PathCorrHook")
            .field("active", &self.link.is_some())
            .field("dropped_reports", &self.dropped)
            .finish_non_exhaustive()
    }
}

impl PathCorrHook {
    pub(super) fn new(
        requests: Receiver<Request>,
        reports: SyncSender<Report>,
        feed: Option<Feed>,
        log: Option<SyncSender<NamedLogRow>>,
        options: HookOptions,
    ) -> PathCorrHook {
        PathCorrHook {
            requests,
            reports,
            feed,
            log,
            options,
            link: None,
            seam: None,
            name: Arc::from(""),
            dropped: 0,
            last_rejection: None,
            rejections_held: 0,
        }
    }

    /// Reports and log rows lost because their reader did not keep up.
    pub fn dropped(&self) -> u64 {
        self.dropped
    }

    fn report(&mut self, r: Report) {
        if let Err(TrySendError::Full(_)) = self.reports.try_send(r) {
            self.dropped = self.dropped.saturating_add(1);
        }
    }

    /// The event of a rejected correction, at most one per [`REJECTION_REPEAT`] (a sensor
    /// that keeps sending bad values is reported once a second, with a count).
    fn rejection(&mut self, now: RobotTime, r: &Rejection) -> Option<EgmEvent> {
        if self
            .last_rejection
            .is_some_and(|t| now.saturating_since(t) < REJECTION_REPEAT)
        {
            self.rejections_held = self.rejections_held.saturating_add(1);
            return None;
        }
        let more = match std::mem::take(&mut self.rejections_held) {
            0 => String::new(),
            n => format!(" ({n} more since the last report)"),
        };
        self.last_rejection = Some(now);
        Some(EgmEvent::new(
            rejection_kind(r),
            format!("{r}; the previous correction stays in force{more}"),
        ))
    }

    fn event(&mut self, e: EgmEvent) {
        let name = Arc::clone(&self.name);
        self.report(Report::Event(name, e));
    }

    fn end(&mut self, now: RobotTime, exec: &mut Executor) {
        // The correction object is dropped here, outside the cycle's hot path; it holds no
        // heap memory worth handing back.
        drop(exec.set_path_correction(None));
        self.seam = None;
        if let Some((mut link, socket)) = self.link.take() {
            link.finish();
            self.forward(&mut link);
            self.report(Report::Ended(Box::new((link, socket))));
        }
        if let Some(f) = &self.feed {
            f.push_egm_state(now, EgmTraceState::Connected);
        }
    }

    /// Events of the link to the program side, log rows to the log writer.
    fn forward(&mut self, link: &mut CorrectionLink) {
        while let Some(e) = link.poll_event() {
            self.event(e);
        }
        while let Some(row) = link.pop_log() {
            if let Some(log) = &self.log
                && let Err(TrySendError::Full(_)) = log.try_send((Arc::clone(&self.name), row))
            {
                self.dropped = self.dropped.saturating_add(1);
            }
        }
    }
}

impl CycleHook for PathCorrHook {
    fn before_tick(&mut self, now: RobotTime, exec: &mut Executor) {
        loop {
            match self.requests.try_recv() {
                Ok(Request::Begin(b)) => {
                    if self.link.is_some() {
                        self.end(now, exec);
                    }
                    let (seam, link, socket, name) = *b;
                    let seam: SeamSlot = Arc::new(std::sync::Mutex::new(seam));
                    let shared = SharedSeam(Arc::clone(&seam));
                    drop(exec.set_path_correction(Some(Box::new(shared))));
                    self.seam = Some(seam);
                    self.link = Some((link, socket));
                    self.name = name;
                    self.last_rejection = None;
                    self.rejections_held = 0;
                    if let Some(f) = &self.feed {
                        f.push_egm_state(now, EgmTraceState::Running);
                    }
                }
                Ok(Request::Move(m)) => {
                    let pushed = self
                        .seam
                        .as_ref()
                        .and_then(|seam| with_seam(seam, |s| s.push_move(*m)));
                    if pushed == Some(false) {
                        self.event(EgmEvent::new(
                            crate::egm::EventKind::Busy,
                            "too many EGMMoveL/EGMMoveC queued in one corrected sequence",
                        ));
                    }
                }
                Ok(Request::End) => self.end(now, exec),
                Err(TryRecvError::Empty) | Err(TryRecvError::Disconnected) => break,
            }
        }
    }

    fn after_tick(&mut self, sp: &Setpoint, _exec: &mut Executor) {
        let Some((mut link, mut socket)) = self.link.take() else {
            return;
        };
        let now = sp.time;
        let Some(slot) = self.seam.take() else {
            self.link = Some((link, socket));
            return;
        };
        // Only this thread (the motion cycle's) ever locks the slot.
        let mut guard = match slot.try_lock() {
            Ok(g) => g,
            Err(std::sync::TryLockError::Poisoned(p)) => p.into_inner(),
            Err(std::sync::TryLockError::WouldBlock) => {
                self.seam = Some(Arc::clone(&slot));
                self.link = Some((link, socket));
                return;
            }
        };
        let seam: &mut SeamCorrection = &mut guard;
        let applied = seam.applied();
        let fresh = applied.filter(|a| a.time == sp.time);
        let look_ahead = match seam.sensing() {
            crate::egm::path_correction::Tracker::Latr { look_ahead } => look_ahead,
            crate::egm::path_correction::Tracker::Aptr => 0.0,
        };
        // Borrowed, not cloned: nothing here allocates per cycle.
        let (default_tool, default_wobj) = (ToolData::tool0(), WobjData::wobj0());
        let (tool, wobj) = match seam.current_move() {
            Some(m) => (&m.tool, &m.wobj),
            None => (&default_tool, &default_wobj),
        };
        socket.receive(now, &mut link);
        let tick = link.tick(
            now,
            &CorrectionInput {
                commanded: sp.joints,
                tool,
                wobj,
                tcp_s: applied.map_or(0.0, |a| a.s),
                look_ahead,
            },
        );
        socket.send(now, &mut link);
        let mut rejected = None;
        if let Some(c) = tick.correction
            && let Err(r) = seam.measurement(c.received_at.as_secs_f64(), c.pos, c.age_s())
        {
            rejected = self.rejection(now, &r);
        }
        if let Some(err) = &tick.failed {
            seam.fail(err);
        }
        let measured = seam.take_measured();
        let left = seam.take_left();
        drop(guard);
        self.seam = Some(slot);
        if let (Some(a), Some(f)) = (fresh, &self.feed) {
            f.push(FeedItem::PathCorr(PathCorrSample {
                t: sp.time,
                s_mm: a.s,
                programmed_yz: [0.0, 0.0],
                corrected_yz: [a.offset.y, a.offset.z],
                measured_yz: measured.map(|m| [m.y, m.z]),
                offset_world: Some([a.world.x, a.world.y, a.world.z]),
            }));
        }
        if let Some(e) = rejected {
            self.event(e);
        }
        if left {
            self.report(Report::Left);
        }
        if let Some(err) = tick.failed {
            self.event(err.event());
            self.report(Report::Failed(err));
        }
        self.forward(&mut link);
        if self.options.lockstep {
            socket.wait_reply(now, self.options.reply_timeout, &mut link);
        }
        self.link = Some((link, socket));
    }
}
