//! The thin real-time shell: the motion thread that sleeps until the next cycle, takes new
//! segments and control requests, calls `Executor::tick(now)`, and publishes the setpoint,
//! events and state. The only code that sleeps; together with `controller::realtime_driver` the only
//! code that spawns threads.
//!
//! Each cycle: sleep until shortly before the deadline, spin the last stretch (to hold the
//! period within microseconds on a loaded machine), tick, hand results to non-blocking
//! bounded channels (a full channel drops and counts, never blocks), advance the deadline.

use std::sync::mpsc::{Receiver, SyncSender, TryRecvError, TrySendError};
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

use crate::motion::{
    Executor, ExternalGuidance, InstrRef, MotionError, MotionEvent, MotionState, Setpoint,
};
use crate::robot::ToolData;
use crate::time::{Clock, RobotTime};

use super::cycle_hook::CycleHook;
use super::monotonic_clock::MonotonicClock;
use super::period_stats::PeriodStats;

/// Requests from the controller handle to the motion thread (rare: sizes do not matter).
#[allow(clippy::large_enum_variant)]
pub(super) enum Control {
    /// Drop queued and active moves and brake to rest. `sent`: how many segments the handle
    /// had sent when it asked; those still in the channel are void too (they were planned
    /// from where the dropped moves would have ended, not from where the robot stops).
    Stop { sent: u64 },
    /// Leave the halted state.
    Recover,
    /// Hand the robot to external guidance.
    StartExternal {
        guidance: Box<dyn ExternalGuidance>,
        tool: ToolData,
        instr: Option<InstrRef>,
        reply: SyncSender<Result<(), MotionError>>,
    },
    /// End external guidance.
    StopExternal {
        reply: SyncSender<Option<Box<dyn ExternalGuidance>>>,
    },
    /// Hold, resume, store, restore or clear the path (`StopMove`, `StorePath`, …).
    Path {
        op: crate::motion::PathOp,
        reply: SyncSender<Result<(), crate::motion::PathOpError>>,
    },
    /// End the thread.
    Shutdown,
}

/// What the motion thread publishes after every cycle.
#[derive(Clone, Copy, Debug)]
pub(super) struct Published {
    pub state: MotionState,
    /// Segments the executor has taken from the channel so far.
    pub accepted: u64,
    /// False once the thread has ended.
    pub running: bool,
}

/// The published state and its change notification.
pub(super) struct Shared {
    pub published: Mutex<Published>,
    pub changed: Condvar,
    /// The latest setpoint's position, for services (lock-free: never blocks the cycle).
    pub position: Arc<super::position_cell::PositionCell>,
}

/// What the motion thread hands back when it ends.
pub(super) struct RtExit {
    pub stats: PeriodStats,
    pub dropped_records: u64,
    pub ticks: u64,
    pub last: Setpoint,
}

/// The motion thread's state (moved onto the thread).
pub(super) struct RtLoop {
    pub exec: Executor,
    pub clock: MonotonicClock,
    pub period: Duration,
    /// How long before the deadline sleeping stops and spinning starts.
    pub spin: Duration,
    pub segments: Receiver<crate::motion::segment::Segment>,
    pub control: Receiver<Control>,
    pub records: SyncSender<Setpoint>,
    pub recycle: SyncSender<crate::motion::segment::Segment>,
    pub events: SyncSender<MotionEvent>,
    pub shared: Arc<Shared>,
    pub hook: Option<Box<dyn CycleHook>>,
    /// Segments up to this count (sent before the latest stop) are void when they arrive.
    pub void_through: u64,
}

impl RtLoop {
    /// Run cycles until shut down (or until the handle is gone).
    pub fn run(mut self) -> RtExit {
        let mut stats = PeriodStats::new();
        let mut dropped_records = 0u64;
        let mut accepted = 0u64;
        let mut ticks = 0u64;
        let mut deadline = self.clock.now().saturating_add(self.period);
        let mut last_wake: Option<RobotTime> = None;
        loop {
            self.sleep_until(deadline);
            let woke = self.clock.now();
            if let Some(prev) = last_wake {
                let actual = woke.saturating_since(prev);
                let error = actual.abs_diff(self.period);
                stats.record(error);
            }
            last_wake = Some(woke);

            let stop = self.take_inputs(&mut accepted);
            if let Some(h) = self.hook.as_mut() {
                h.before_tick(deadline, &mut self.exec);
            }
            let sp = self.exec.tick(deadline);
            if let Some(h) = self.hook.as_mut() {
                h.after_tick(&sp, &mut self.exec);
            }
            ticks += 1;
            self.shared
                .position
                .store(sp.time.as_secs_f64(), &sp.joints);
            if let Err(TrySendError::Full(_)) = self.records.try_send(sp) {
                dropped_records += 1;
            }
            self.hand_out();
            self.publish(accepted, true);
            if stop {
                break;
            }
            deadline = deadline.saturating_add(self.period);
            let now = self.clock.now();
            if now > deadline {
                // A whole period lost (the machine stalled us): skip the missed cycles.
                stats.record_overrun();
                let behind = now.saturating_since(deadline).as_nanos();
                let period = self.period.as_nanos().max(1);
                let skip = u32::try_from(behind / period + 1).unwrap_or(u32::MAX);
                deadline = deadline.saturating_add(self.period.saturating_mul(skip));
            }
        }
        self.publish(accepted, false);
        RtExit {
            stats,
            dropped_records,
            ticks,
            last: *self.exec.setpoint(),
        }
    }

    /// Sleep until `SPIN` before the deadline, then spin.
    fn sleep_until(&self, deadline: RobotTime) {
        loop {
            let now = self.clock.now();
            if now >= deadline {
                return;
            }
            let remaining = deadline.saturating_since(now);
            if remaining > self.spin {
                std::thread::sleep(remaining - self.spin);
            } else {
                std::hint::spin_loop();
            }
        }
    }

    /// New segments (while the queue has room) and control requests. True: shut down.
    fn take_inputs(&mut self, accepted: &mut u64) -> bool {
        while self.exec.has_space() {
            match self.segments.try_recv() {
                Ok(seg) => {
                    *accepted += 1;
                    if self.exec.is_halted() || *accepted <= self.void_through {
                        // Moves sent before the handle saw the error, or before a stop, are void.
                        let _ = self.recycle.try_send(seg);
                    } else if let Err(seg) = self.exec.push(seg) {
                        let _ = self.recycle.try_send(seg);
                    }
                }
                Err(TryRecvError::Empty) | Err(TryRecvError::Disconnected) => break,
            }
        }
        loop {
            match self.control.try_recv() {
                Ok(Control::Stop { sent }) => {
                    self.void_through = self.void_through.max(sent);
                    self.exec.stop();
                }
                Ok(Control::Recover) => self.exec.recover(),
                Ok(Control::StartExternal {
                    guidance,
                    tool,
                    instr,
                    reply,
                }) => {
                    let _ = reply.try_send(self.exec.start_external(guidance, tool, instr));
                }
                Ok(Control::StopExternal { reply }) => {
                    let _ = reply.try_send(self.exec.stop_external());
                }
                Ok(Control::Path { op, reply }) => {
                    let _ = reply.try_send(self.exec.path_op(op));
                }
                Ok(Control::Shutdown) | Err(TryRecvError::Disconnected) => return true,
                Err(TryRecvError::Empty) => return false,
            }
        }
    }

    /// Finished segments back to the planner, events to the handle.
    fn hand_out(&mut self) {
        while let Some(seg) = self.exec.take_done() {
            let _ = self.recycle.try_send(seg);
        }
        while let Some(e) = self.exec.take_event() {
            let _ = self.events.try_send(e);
        }
    }

    /// Publish the state without ever blocking the cycle: if the handle holds the lock right
    /// now, this cycle's state is skipped (the next cycle publishes again).
    fn publish(&self, accepted: u64, running: bool) {
        if let Ok(mut p) = self.shared.published.try_lock() {
            *p = Published {
                state: self.exec.state(),
                accepted,
                running,
            };
            drop(p);
            self.shared.changed.notify_all();
        } else if !running {
            if let Ok(mut p) = self.shared.published.lock() {
                p.running = false;
            }
            self.shared.changed.notify_all();
        }
    }
}
