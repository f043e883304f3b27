//! The EGM side of every motion cycle ([`EgmHook`], a [`CycleHook`]): it carries the datagrams of the EGM machines (before the tick the running run's device socket is drained into its driver; after it the driver's `EgmRobot` goes out), ticks the position streams with the cycle's setpoint, hands the run's events and log rows out (event channel, `--egm-log` writer, output feed), waits for the sensor's reply in lockstep, and hands a run that ended back to the program side.
//!
//! Runs on the motion thread in real time and inline in virtual time. It never blocks
//! (bounded channels with `try_send`, `try_lock` on the run slot and the stream list) except
//! for the lockstep wait, the controller loop's policy for virtual time driven by an
//! external sensor, where the cycle runs on the program's thread anyway.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::SyncSender;
use std::sync::{Arc, Mutex, MutexGuard, TryLockError};
use std::time::Duration;

use crate::controller::CycleHook;
use crate::controller::sample_feed::{EgmAxes, EgmTraceState, Feed};
use crate::egm::EgmMode;
use crate::egm::message_log::LogRow;
use crate::egm::registry::EgmId;
use crate::egm::types::RapidExecState;
use crate::egm::{EgmEvent, EgmStream};
use crate::motion::{Executor, Setpoint};
use crate::time::RobotTime;

use super::device_socket::DeviceSocket;
use super::run_guidance::{EgmGuidance, RunSlot};

/// A running position stream.
#[derive(Debug)]
pub(crate) struct StreamSlot {
    pub id: EgmId,
    pub name: Arc<str>,
    pub stream: EgmStream,
    /// Its device's socket.
    pub socket: DeviceSocket,
}

/// What the program side and the hook share.
#[derive(Debug, Default)]
pub(crate) struct Shared {
    /// The EGM run (the executor steps it through a `RunStep`).
    pub run: Arc<RunSlot>,
    /// The running streams (the hook only ever `try_lock`s).
    pub streams: Mutex<Vec<StreamSlot>>,
    /// True while the program is stopped or has ended (streams report RAPID_STOPPED).
    pub rapid_stopped: AtomicBool,
    /// True while the controller's motors are off (every `EgmRobot` says MOTORS_OFF).
    pub motors_off: AtomicBool,
    /// Lockstep: waits for a reply, and waits that ended without one.
    pub lockstep_waits: AtomicU64,
    /// Lockstep waits that timed out.
    pub lockstep_timeouts: AtomicU64,
    /// Events lost because the program side did not take them in time.
    pub events_dropped: AtomicU64,
    /// Log rows lost because the log writer did not keep up.
    pub rows_dropped: AtomicU64,
}

/// An event of an EGM identity.
#[derive(Clone, Debug)]
pub(crate) struct NamedEvent {
    pub name: Arc<str>,
    pub event: EgmEvent,
}

/// One `--egm-log` row.
pub(crate) type NamedRow = (Arc<str>, LogRow);

/// The cycle hook (see the module docs).
pub struct EgmHook {
    pub(crate) shared: Arc<Shared>,
    pub(crate) events: SyncSender<NamedEvent>,
    pub(crate) retired: SyncSender<Box<EgmGuidance>>,
    pub(crate) log: Option<SyncSender<NamedRow>>,
    pub(crate) feed: Option<Feed>,
    pub(crate) lockstep: Option<Duration>,
    /// EGMMoveL/EGMMoveC (`controller::corrected_moves`).
    pub(crate) pathcorr: crate::controller::corrected_moves::PathCorrHook,
}

impl std::fmt::Debug for EgmHook {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EgmHook")
            .field("lockstep", &self.lockstep)
            .finish_non_exhaustive()
    }
}

impl EgmHook {
    fn event(&self, name: &Arc<str>, event: EgmEvent) {
        let e = NamedEvent {
            name: Arc::clone(name),
            event,
        };
        if self.events.try_send(e).is_err() {
            self.shared.events_dropped.fetch_add(1, Ordering::Relaxed);
        }
    }

    fn row(&self, name: &Arc<str>, row: LogRow) {
        if let Some(log) = &self.log
            && log.try_send((Arc::clone(name), row)).is_err()
        {
            self.shared.rows_dropped.fetch_add(1, Ordering::Relaxed);
        }
    }

    /// Events and log rows of the run.
    fn drain_run(&self, g: &mut EgmGuidance) {
        while let Some(e) = g.driver.poll_event() {
            self.event(&g.name, e);
        }
        while let Some(row) = g.driver.pop_log() {
            self.row(&g.name, row);
        }
    }

    /// One feed sample per motion cycle of a run: the reference in use and the measured
    /// position, in joints or in the correction frame.
    fn feed_run(&self, sp: &Setpoint, g: &mut EgmGuidance) {
        if let Some(feed) = &self.feed {
            let (reference, feedback) = g.driver.tracking();
            let axes = match g.driver.mode() {
                EgmMode::Pose => EgmAxes::Pose,
                _ => EgmAxes::Joint,
            };
            feed.push_egm_sample(
                sp.time,
                axes,
                reference,
                feedback,
                if g.driver.is_paused() {
                    EgmTraceState::Connected
                } else {
                    EgmTraceState::Running
                },
                std::mem::take(&mut g.speed_limited),
            );
        }
    }

    fn tick_streams(&self, sp: &Setpoint) {
        let Ok(mut streams) = self.shared.streams.try_lock() else {
            return;
        };
        let exec = if self.shared.rapid_stopped.load(Ordering::Relaxed) {
            RapidExecState::Stopped
        } else {
            RapidExecState::Running
        };
        let now = sp.time;
        let motors_on = !self.shared.motors_off.load(Ordering::Relaxed);
        for s in streams.iter_mut() {
            s.stream.set_motors(motors_on);
            s.socket.receive(now, &mut s.stream);
            s.stream.tick(now, &sp.joints, exec);
            s.socket.send(now, &mut s.stream);
            while let Some(e) = s.stream.poll_event() {
                self.event(&s.name, e);
            }
            while let Some(row) = s.stream.pop_log() {
                if let Some(feed) = &self.feed {
                    feed.push_egm_sample(
                        row.send_time,
                        EgmAxes::Joint,
                        None,
                        row.feedback,
                        EgmTraceState::Running,
                        false,
                    );
                }
                self.row(&s.name, row);
            }
        }
    }
}

/// The run slot without waiting: `None` only while the program side holds it (then the
/// run is not in the executor yet).
fn try_slot(slot: &RunSlot) -> Option<MutexGuard<'_, Option<EgmGuidance>>> {
    match slot.try_lock() {
        Ok(g) => Some(g),
        Err(TryLockError::Poisoned(p)) => Some(p.into_inner()),
        Err(TryLockError::WouldBlock) => None,
    }
}

impl CycleHook for EgmHook {
    fn before_tick(&mut self, now: RobotTime, exec: &mut Executor) {
        self.pathcorr.before_tick(now, exec);
        if let Some(mut slot) = try_slot(&self.shared.run)
            && let Some(g) = slot.as_mut()
        {
            g.driver
                .set_motors(!self.shared.motors_off.load(Ordering::Relaxed));
            g.socket.receive(now, &mut g.driver);
        }
    }

    fn after_tick(&mut self, sp: &Setpoint, exec: &mut Executor) {
        self.pathcorr.after_tick(sp, exec);
        // The executor's guidance of a run that ended is only a handle on the slot.
        let retired = exec.take_retired().is_some();
        if let Some(mut slot) = try_slot(&self.shared.run)
            && let Some(g) = slot.as_mut()
        {
            g.socket.send(sp.time, &mut g.driver);
            if retired {
                self.drain_run(g);
                if let Some(feed) = &self.feed {
                    feed.push_egm_state(sp.time, EgmTraceState::Connected);
                }
                // At most one run exists at a time and the program side takes it before
                // starting another, so the channel (capacity 4) has room.
                if let Some(g) = slot.take() {
                    let _ = self.retired.try_send(Box::new(g));
                }
            } else if g.stepped {
                self.feed_run(sp, g);
                self.drain_run(g);
                if let Some(timeout) = self.lockstep
                    && let Some(came) = g.socket.wait_reply(sp.time, timeout, &mut g.driver)
                {
                    self.shared.lockstep_waits.fetch_add(1, Ordering::Relaxed);
                    if !came {
                        self.shared
                            .lockstep_timeouts
                            .fetch_add(1, Ordering::Relaxed);
                    }
                }
            }
        }
        self.tick_streams(sp);
    }
}
