//! Real time: the executor runs on its own motion thread (`controller::motion_thread`) against the
//! monotonic clock; planning stays on the caller's thread; a recorder thread feeds the sinks.

use std::sync::mpsc::{self, Receiver, SyncSender};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::Duration;

use crate::motion::segment::Segment;
use crate::motion::{Executor, MotionEvent, Planner, Setpoint};

use super::ControllerError;
use super::cycle_hook::CycleHook;
use super::monotonic_clock::MonotonicClock;
use super::motion_thread::{Control, Published, RtExit, RtLoop, Shared};
use super::priority::{RealtimeConfig, make_current_thread_realtime};
use super::tick_sink::TickSink;

/// Setpoints buffered for the recorder thread (≈ 65 s at 4 ms).
const RECORD_BUFFER: usize = 16_384;
/// Events buffered between the motion thread and the handle.
const EVENT_BUFFER: usize = 1024;

/// The real-time driver of a controller handle.
pub(super) struct RealTimeDriver {
    pub planner: Planner,
    pub segments: Option<SyncSender<Segment>>,
    pub control: SyncSender<Control>,
    pub recycle: Receiver<Segment>,
    pub events: Receiver<MotionEvent>,
    pub shared: Arc<Shared>,
    pub submitted: u64,
    rt: Option<JoinHandle<RtExit>>,
    recorder: Option<JoinHandle<Vec<Box<dyn TickSink>>>>,
}

/// What the real-time run reports when it ends.
pub(super) struct RealTimeEnd {
    pub exit: RtExit,
    pub sinks: Vec<Box<dyn TickSink>>,
}

impl RealTimeDriver {
    /// Start the motion and recorder threads. With [`RealtimeConfig::Enforce`] the motion
    /// thread must obtain SCHED_FIFO priority or the start fails.
    pub fn start(
        planner: Planner,
        exec: Executor,
        queue_capacity: usize,
        spin: Duration,
        rt_config: RealtimeConfig,
        mut sinks: Vec<Box<dyn TickSink>>,
        hook: Option<Box<dyn CycleHook>>,
    ) -> Result<RealTimeDriver, ControllerError> {
        let period = exec.period();
        let (seg_tx, seg_rx) = mpsc::sync_channel::<Segment>(1);
        let (ctl_tx, ctl_rx) = mpsc::sync_channel::<Control>(16);
        let (rec_tx, rec_rx) = mpsc::sync_channel::<Setpoint>(RECORD_BUFFER);
        let (recycle_tx, recycle_rx) = mpsc::sync_channel::<Segment>(queue_capacity + 8);
        let (ev_tx, ev_rx) = mpsc::sync_channel::<MotionEvent>(EVENT_BUFFER);
        let initial = *exec.setpoint();
        let shared = Arc::new(Shared {
            published: Mutex::new(Published {
                state: exec.state(),
                accepted: 0,
                running: true,
            }),
            changed: Condvar::new(),
            position: Arc::new(super::position_cell::PositionCell::new(&initial.joints)),
        });

        let recorder = std::thread::Builder::new()
            .name("rapidvc-recorder".into())
            .spawn(move || {
                for s in &mut sinks {
                    s.record(&initial);
                }
                while let Ok(sp) = rec_rx.recv() {
                    for s in &mut sinks {
                        s.record(&sp);
                    }
                }
                sinks
            })
            .map_err(|e| {
                ControllerError::Thread(format!("cannot start the recorder thread: {e}"))
            })?;

        let (ready_tx, ready_rx) = mpsc::sync_channel::<Result<(), String>>(1);
        let rt_loop = RtLoop {
            exec,
            clock: MonotonicClock::new(),
            period,
            spin,
            segments: seg_rx,
            control: ctl_rx,
            records: rec_tx,
            recycle: recycle_tx,
            events: ev_tx,
            shared: Arc::clone(&shared),
            hook,
            void_through: 0,
        };
        let rt = std::thread::Builder::new()
            .name("rapidvc-motion".into())
            .spawn(move || {
                let prio = match rt_config {
                    RealtimeConfig::Enforce => make_current_thread_realtime(),
                    RealtimeConfig::Ignore => Ok(()),
                };
                let failed = prio.is_err();
                let _ = ready_tx.send(prio);
                if failed {
                    // Dropping the loop closes the record channel: the recorder ends too.
                    return RtExit {
                        stats: super::period_stats::PeriodStats::new(),
                        dropped_records: 0,
                        ticks: 0,
                        last: *rt_loop.exec.setpoint(),
                    };
                }
                let mut rt_loop = rt_loop;
                rt_loop.clock = MonotonicClock::new();
                rt_loop.run()
            })
            .map_err(|e| ControllerError::Thread(format!("cannot start the motion thread: {e}")))?;
        let mut driver = RealTimeDriver {
            planner,
            segments: Some(seg_tx),
            control: ctl_tx,
            recycle: recycle_rx,
            events: ev_rx,
            shared,
            submitted: 0,
            rt: Some(rt),
            recorder: Some(recorder),
        };
        match ready_rx.recv() {
            Ok(Ok(())) => Ok(driver),
            Ok(Err(msg)) => {
                let _ = driver.stop();
                Err(ControllerError::Priority(msg))
            }
            Err(_) => {
                let _ = driver.stop();
                Err(ControllerError::Thread(
                    "the motion thread ended at start".into(),
                ))
            }
        }
    }

    /// Lock the published state (the motion thread only ever try-locks it).
    pub fn published(&self) -> MutexGuard<'_, Published> {
        self.shared
            .published
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Give finished segments back to the planner.
    pub fn recycle(&mut self) {
        while let Ok(seg) = self.recycle.try_recv() {
            self.planner.recycle(seg);
        }
    }

    /// Stop the threads and collect what they hand back.
    pub fn stop(&mut self) -> Result<RealTimeEnd, ControllerError> {
        let _ = self.control.send(Control::Shutdown);
        self.segments = None;
        let exit = self
            .rt
            .take()
            .ok_or_else(|| ControllerError::Thread("the controller was already stopped".into()))?
            .join()
            .map_err(|_| ControllerError::Thread("the motion thread panicked".into()))?;
        let sinks = self
            .recorder
            .take()
            .ok_or_else(|| ControllerError::Thread("the recorder was already stopped".into()))?
            .join()
            .map_err(|_| ControllerError::Thread("the recorder thread panicked".into()))?;
        Ok(RealTimeEnd { exit, sinks })
    }
}

impl Drop for RealTimeDriver {
    fn drop(&mut self) {
        if self.rt.is_some() {
            let _ = self.stop();
        }
    }
}
