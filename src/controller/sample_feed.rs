//! The controller's side channel into the outputs: EGM samples, EGM state changes and
//! path-correction samples, pushed around the motion cycle (no allocation, never blocking) and
//! consumed by the trace and plot sinks in robot-time order. The controller owns this stream of
//! plain rows; the outputs (`crate::output`, which re-exports these types) only subscribe and
//! read it, so the controller never names an output.
//!
//! # Wiring
//!
//! ```
//! # fn main() -> Result<(), String> {
//! # let dir = std::env::temp_dir();
//! use rapidvc::output::{Feed, PlotRecorder, TraceColumns, TraceWriter};
//!
//! let mut feed = Feed::new();
//! // Every consumer subscribes before the feed is handed to the producer.
//! let trace = TraceWriter::with_feed(Vec::new(), None, TraceColumns::EGM_AND_PATHCORR, feed.subscribe());
//! let plot = PlotRecorder::new(&dir.join("run.svg"), "run", None)?.with_feed(feed.subscribe());
//! // `trace` and `plot` go into the controller's sinks, `feed` (or a clone) into the EGM
//! // driver, which calls `feed.push_egm_sample(…)` from its cycle hook's `after_tick`.
//! # let _ = (trace, plot, feed);
//! # Ok(())
//! # }
//! ```
//!
//! # What to push
//!
//! - Position guidance and streaming (`EGMRunJoint`, `EGMRunPose`, `EGMStreamStart`): one
//!   [`Feed::push_egm_sample`] per EGM cycle, with the state `RUNNING`.
//! - Path correction (`EGMMoveL`, `EGMMoveC`): one [`Feed::push_pathcorr_sample`] per motion
//!   cycle, and the state changes with [`Feed::push_egm_state`].
//! - Every state change outside a cycle (setup → `CONNECTED`, end of a movement →
//!   `CONNECTED`, `EGMReset` → `DISCONNECTED`): [`Feed::push_egm_state`].
//!
//! # Alignment with the trace rows
//!
//! Both clock modes run the cycle hook's `after_tick` before the setpoint reaches the sinks, so
//! everything pushed for robot time `t` is in the feed when the row for `t` is written. A sink
//! takes the items with time ≤ its row's time; an item stamped with a later time waits for its
//! row. Push in time order (one producer thread); an item pushed out of order is taken with the
//! next row.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver, SyncSender, TrySendError};

use crate::time::RobotTime;

/// Items buffered per consumer (≈ 32 s of one EGM and one path-correction sample per 4 ms
/// cycle). Only matters in real time, where the recorder thread may lag the motion thread.
pub const FEED_CAPACITY: usize = 16_384;

/// `egmstate` as the trace and plot show it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EgmTraceState {
    /// `EGM_STATE_DISCONNECTED`: no setup.
    Disconnected,
    /// `EGM_STATE_CONNECTED`: set up, no EGM movement.
    Connected,
    /// `EGM_STATE_RUNNING`: an EGM movement or stream is active.
    Running,
}

impl EgmTraceState {
    /// The text in the trace's `egm_state` column: `DISCONNECTED`, `CONNECTED`, `RUNNING`.
    pub fn as_str(self) -> &'static str {
        match self {
            EgmTraceState::Disconnected => "DISCONNECTED",
            EgmTraceState::Connected => "CONNECTED",
            EgmTraceState::Running => "RUNNING",
        }
    }
}

/// What the six numbers of an EGM sample are.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EgmAxes {
    /// Joint mode: axis 1 … 6 in degrees.
    Joint,
    /// Pose mode: x, y, z in mm and rx, ry, rz in degrees (Euler ZYX), in the correction frame.
    Pose,
}

/// One EGM cycle: what the sensor asked for and where the robot is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EgmSample {
    /// Robot time of the cycle.
    pub t: RobotTime,
    /// Joint or pose values.
    pub axes: EgmAxes,
    /// The sensor's reference in use this cycle; `None` before the first reference.
    pub reference: Option<[f64; 6]>,
    /// The feedback sent to the sensor (same axes and units as `reference`).
    pub feedback: [f64; 6],
    /// The identity's state.
    pub state: EgmTraceState,
    /// `MaxSpeedDeviation` scaled the EGM speed this cycle.
    pub speed_limited: bool,
}

/// One path-correction cycle, in the path frame (mm; x along the path, corrections in y, z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathCorrSample {
    /// Robot time of the cycle.
    pub t: RobotTime,
    /// Arc length along the programmed path since the correction started (mm).
    pub s_mm: f64,
    /// The programmed path's y, z (mm).
    pub programmed_yz: [f64; 2],
    /// The corrected path's y, z: programmed plus the correction applied this cycle (mm).
    pub corrected_yz: [f64; 2],
    /// The seam as the sensor measured it at `s_mm` (mm); `None` when no measurement
    /// refers to this point.
    pub measured_yz: Option<[f64; 2]>,
    /// The correction applied, in world coordinates (mm): the corrected TCP less this is the
    /// programmed one (the 3D view draws both paths). `None` when the producer does not
    /// know it.
    pub offset_world: Option<[f64; 3]>,
}

impl PathCorrSample {
    /// The correction applied: corrected − programmed (mm).
    pub fn correction(&self) -> [f64; 2] {
        let [cy, cz] = self.corrected_yz;
        let [py, pz] = self.programmed_yz;
        [cy - py, cz - pz]
    }
}

/// Anything pushed into a [`Feed`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FeedItem {
    /// An EGM cycle.
    Egm(EgmSample),
    /// The EGM state changed outside an EGM movement (setup, `EGMReset`, …).
    EgmState(RobotTime, EgmTraceState),
    /// A path-correction cycle.
    PathCorr(PathCorrSample),
}

impl FeedItem {
    /// The robot time the item belongs to.
    pub fn time(&self) -> RobotTime {
        match self {
            FeedItem::Egm(s) => s.t,
            FeedItem::EgmState(t, _) => *t,
            FeedItem::PathCorr(s) => s.t,
        }
    }
}

/// The producer's handle: cheap to clone (clone it before the run; cloning allocates),
/// `Send`, and every push is allocation-free and never blocks. When a consumer's buffer is
/// full the item is dropped for that consumer and counted ([`Feed::dropped`]).
#[derive(Clone, Debug, Default)]
pub struct Feed {
    subscribers: Vec<SyncSender<FeedItem>>,
    dropped: Arc<AtomicU64>,
}

impl Feed {
    /// A feed with no consumers yet.
    pub fn new() -> Feed {
        Feed::default()
    }

    /// A new consumer with a buffer of [`FEED_CAPACITY`] items. Subscribe every consumer
    /// before handing the feed (or its clones) to the producer: a clone made earlier does not
    /// reach consumers subscribed later.
    pub fn subscribe(&mut self) -> FeedRx {
        self.subscribe_with_capacity(FEED_CAPACITY)
    }

    /// [`Feed::subscribe`] with a chosen buffer size (at least 1).
    pub fn subscribe_with_capacity(&mut self, capacity: usize) -> FeedRx {
        let (tx, rx) = mpsc::sync_channel(capacity.max(1));
        self.subscribers.push(tx);
        FeedRx { rx, pending: None }
    }

    /// True when nobody listens (pushing is then a no-op).
    pub fn is_unused(&self) -> bool {
        self.subscribers.is_empty()
    }

    /// Items dropped so far because a consumer's buffer was full (summed over consumers).
    pub fn dropped(&self) -> u64 {
        self.dropped.load(Ordering::Relaxed)
    }

    /// Push any item.
    pub fn push(&self, item: FeedItem) {
        for tx in &self.subscribers {
            if let Err(TrySendError::Full(_)) = tx.try_send(item) {
                self.dropped.fetch_add(1, Ordering::Relaxed);
            }
            // A disconnected consumer has finished: nothing to do.
        }
    }

    /// One EGM cycle at robot time `t` (call it once per EGM message or per motion cycle while
    /// an EGM movement or stream runs; the cycle hook's `after_tick` is the place, with
    /// `t = sp.time`). `reference` is `None` before the sensor's first reference.
    pub fn push_egm_sample(
        &self,
        t: RobotTime,
        axes: EgmAxes,
        reference: Option<[f64; 6]>,
        feedback: [f64; 6],
        state: EgmTraceState,
        speed_limited: bool,
    ) {
        self.push(FeedItem::Egm(EgmSample {
            t,
            axes,
            reference,
            feedback,
            state,
            speed_limited,
        }));
    }

    /// The EGM state changed at `t` without an EGM cycle (e.g. `EGMSetupUC` → CONNECTED,
    /// `EGMReset` → DISCONNECTED). The trace's `egm_state` column holds the last state pushed
    /// (by this or by [`Feed::push_egm_sample`]) until the next one.
    pub fn push_egm_state(&self, t: RobotTime, state: EgmTraceState) {
        self.push(FeedItem::EgmState(t, state));
    }

    /// One path-correction cycle at robot time `t`, in the path frame (mm): arc length `s_mm`,
    /// the programmed and corrected path's y, z, and the sensor's seam measurement at `s_mm`
    /// if there is one.
    pub fn push_pathcorr_sample(
        &self,
        t: RobotTime,
        s_mm: f64,
        programmed_yz: [f64; 2],
        corrected_yz: [f64; 2],
        measured_yz: Option<[f64; 2]>,
    ) {
        self.push(FeedItem::PathCorr(PathCorrSample {
            t,
            s_mm,
            programmed_yz,
            corrected_yz,
            measured_yz,
            offset_world: None,
        }));
    }
}

/// A consumer's end of a [`Feed`] (owned by a trace or plot sink).
#[derive(Debug)]
pub struct FeedRx {
    rx: Receiver<FeedItem>,
    /// An item taken from the channel whose row has not come yet.
    pending: Option<FeedItem>,
}

impl FeedRx {
    /// Hand every item stamped at or before `now` to `f`, in push order.
    pub fn drain_until(&mut self, now: RobotTime, mut f: impl FnMut(FeedItem)) {
        loop {
            let Some(item) = self.pending.take().or_else(|| self.rx.try_recv().ok()) else {
                return;
            };
            if item.time() > now {
                self.pending = Some(item);
                return;
            }
            f(item);
        }
    }

    /// Hand every item buffered so far to `f` (at the end of a run).
    pub fn drain_all(&mut self, f: impl FnMut(FeedItem)) {
        self.drain_until(RobotTime(u64::MAX), f);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(ms: u64) -> RobotTime {
        RobotTime::from_nanos(ms * 1_000_000)
    }

    #[test]
    fn items_wait_for_their_row_and_overflow_is_counted() {
        let mut feed = Feed::new();
        assert!(feed.is_unused());
        let mut a = feed.subscribe_with_capacity(3);
        let mut b = feed.subscribe();
        let producer = feed.clone();
        producer.push_egm_state(t(0), EgmTraceState::Connected);
        producer.push_pathcorr_sample(t(4), 1.0, [0.0; 2], [0.5, -0.5], None);
        producer.push_egm_sample(
            t(8),
            EgmAxes::Joint,
            None,
            [0.0; 6],
            EgmTraceState::Running,
            true,
        );
        producer.push_egm_state(t(12), EgmTraceState::Disconnected);
        assert_eq!(producer.dropped(), 1, "a holds 3 items");
        let mut seen = Vec::new();
        a.drain_until(t(4), |i| seen.push(i.time()));
        assert_eq!(seen, [t(0), t(4)]);
        a.drain_until(t(6), |i| seen.push(i.time()));
        assert_eq!(seen.len(), 2, "the t = 8 ms item waits");
        a.drain_all(|i| seen.push(i.time()));
        assert_eq!(seen, [t(0), t(4), t(8)]);
        let mut all = 0;
        b.drain_all(|_| all += 1);
        assert_eq!(all, 4);
        drop(b);
        producer.push_egm_state(t(16), EgmTraceState::Connected);
        assert_eq!(
            producer.dropped(),
            1,
            "a finished consumer is not an overflow"
        );
        let s = PathCorrSample {
            t: t(0),
            s_mm: 0.0,
            programmed_yz: [1.0, 2.0],
            corrected_yz: [4.0, 0.0],
            measured_yz: None,
            offset_world: None,
        };
        assert_eq!(s.correction(), [3.0, -2.0]);
    }
}
