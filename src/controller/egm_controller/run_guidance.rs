//! One EGM run (EGMRunJoint/EGMRunPose) as the motion core's external guidance: the driver is ticked inside the motion cycle (no I/O there: the cycle hook carries its datagrams before and after), and the program side reaches it only through lock-free requests (EGMStop, program stop).
//!
//! The run lives in one slot ([`RunSlot`]) that the executor's guidance ([`RunStep`]) and the
//! cycle hook both reach, typed: the executor steps it inside the cycle, the hook drains the
//! device's socket into it before the cycle and sends, reports and waits (lockstep) after.
//! Both run on the same thread one after the other, so the slot's lock is never contended
//! there; the program side fills the slot before it hands the run to the executor and the
//! hook empties it when the run retired.

use std::sync::atomic::{AtomicBool, AtomicU8, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, TryLockError};
use std::time::Duration;

use crate::egm::registry::EgmId;
use crate::egm::servo::StopMode;
use crate::egm::{EgmDriver, EgmTick};
use crate::motion::{ExternalGuidance, GuidanceStep};
use crate::robot::JointsDeg;
use crate::time::RobotTime;

use super::device_socket::DeviceSocket;

const NONE: u8 = 0;
const STOP_HOLD: u8 = 1;
const STOP_RAMP_DOWN: u8 = 2;
const HALT: u8 = 3;

/// Requests from the program side to a running EGM run (set by the interpreter's thread,
/// taken by the motion cycle; atomics only).
#[derive(Debug, Default)]
pub(crate) struct RunControl {
    request: AtomicU8,
    /// `\RampOutTime` of an EGMStop in ns; `u64::MAX`: none given.
    ramp_out_ns: AtomicU64,
    /// The program is stopped with the run going on (a level, not a request: the last word
    /// of any series of stops and starts counts).
    paused: AtomicBool,
    /// The controller's speed ratio, percent (0: not set, 100 %).
    ratio_pct: AtomicU8,
}

/// A request taken by the cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Request {
    Stop(StopMode, Option<Duration>),
    Halt,
}

impl RunControl {
    /// `EGMStop Mode \RampOutTime`.
    pub(crate) fn stop(&self, mode: StopMode, ramp_out: Option<Duration>) {
        let ns = ramp_out.map_or(u64::MAX, |d| {
            u64::try_from(d.as_nanos()).unwrap_or(u64::MAX - 1)
        });
        self.ramp_out_ns.store(ns, Ordering::Release);
        let r = match mode {
            StopMode::Hold => STOP_HOLD,
            StopMode::RampDown => STOP_RAMP_DOWN,
        };
        self.request.store(r, Ordering::Release);
    }

    /// Program stop: the run brakes to rest.
    pub(crate) fn halt(&self) {
        self.request.store(HALT, Ordering::Release);
    }

    /// Pause (`true`, the program stopped) or resume the run (`egm::servo`, "Speed scale").
    pub(crate) fn set_paused(&self, paused: bool) {
        self.paused.store(paused, Ordering::Release);
    }

    /// True while the program side wants the run paused.
    pub(crate) fn paused(&self) -> bool {
        self.paused.load(Ordering::Acquire)
    }

    /// The controller's speed ratio in percent (1–100).
    pub(crate) fn set_ratio(&self, percent: u8) {
        self.ratio_pct
            .store(percent.clamp(1, 100), Ordering::Release);
    }

    /// The speed ratio as a share (0.01–1).
    pub(crate) fn ratio(&self) -> f64 {
        match self.ratio_pct.load(Ordering::Acquire) {
            0 => 1.0,
            p => f64::from(p.min(100)) / 100.0,
        }
    }

    /// The pending request, if any (taken once).
    pub(crate) fn take(&self) -> Option<Request> {
        let r = self.request.swap(NONE, Ordering::AcqRel);
        let ramp = || match self.ramp_out_ns.load(Ordering::Acquire) {
            u64::MAX => None,
            ns => Some(Duration::from_nanos(ns)),
        };
        match r {
            STOP_HOLD => Some(Request::Stop(StopMode::Hold, ramp())),
            STOP_RAMP_DOWN => Some(Request::Stop(StopMode::RampDown, ramp())),
            HALT => Some(Request::Halt),
            _ => None,
        }
    }
}

/// One EGM run: the driver, its device's socket, and what the hook reports of it.
#[derive(Debug)]
pub(crate) struct EgmGuidance {
    /// The identity (to tell the registry when the run is over).
    pub id: EgmId,
    /// The identity's name, shared with reports and log rows without allocating.
    pub name: Arc<str>,
    /// The driver.
    pub driver: EgmDriver,
    /// Its device's socket (none for the built-in sensor and signals).
    pub socket: DeviceSocket,
    /// The executor stepped it (it is the running external guidance).
    pub stepped: bool,
    /// Requests from the program side.
    pub control: Arc<RunControl>,
    /// MaxSpeedDeviation limited the speed since the hook last looked.
    pub speed_limited: bool,
    /// The last tick's result.
    pub last: Option<EgmTick>,
    /// The speed ratio the driver was last given.
    pub ratio: f64,
}

/// Where the running EGM run lives (see the module docs).
pub(crate) type RunSlot = Mutex<Option<EgmGuidance>>;

/// The executor's external guidance of the run in a [`RunSlot`].
pub(crate) struct RunStep(pub Arc<RunSlot>);

impl ExternalGuidance for RunStep {
    fn step(&mut self, now: RobotTime, current: &JointsDeg) -> GuidanceStep {
        // The hook and the executor run one after the other on this thread; the program side
        // holds the lock only while the run is not in the executor. So this never fails.
        let mut slot = match self.0.try_lock() {
            Ok(slot) => slot,
            Err(TryLockError::Poisoned(p)) => p.into_inner(),
            Err(TryLockError::WouldBlock) => return GuidanceStep::Hold,
        };
        match slot.as_mut() {
            Some(run) => run.step(now, current),
            None => GuidanceStep::Finished,
        }
    }
}

impl EgmGuidance {
    /// The run's step of the cycle at `now`: the program side's requests, then the driver's
    /// tick.
    fn step(&mut self, now: RobotTime, current: &JointsDeg) -> GuidanceStep {
        self.stepped = true;
        match self.control.take() {
            Some(Request::Stop(mode, ramp)) => self.driver.stop(mode, ramp),
            Some(Request::Halt) => self.driver.halt(),
            None => {}
        }
        let ratio = self.control.ratio();
        if ratio != self.ratio {
            self.ratio = ratio;
            self.driver.set_speed_ratio(ratio);
        }
        match (self.control.paused(), self.driver.is_paused()) {
            (true, false) => self.driver.pause(),
            (false, true) => self.driver.resume(),
            _ => {}
        }
        if self.driver.is_finished() {
            return GuidanceStep::Finished;
        }
        let t = self.driver.tick(now, current);
        self.speed_limited |= t.speed_limited;
        let q = t.joints_cmd;
        self.last = Some(t);
        GuidanceStep::MoveTo(q)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_are_taken_once() {
        let c = RunControl::default();
        assert_eq!(c.take(), None);
        c.stop(StopMode::RampDown, Some(Duration::from_millis(300)));
        assert_eq!(
            c.take(),
            Some(Request::Stop(
                StopMode::RampDown,
                Some(Duration::from_millis(300))
            ))
        );
        assert_eq!(c.take(), None);
        c.stop(StopMode::Hold, None);
        assert_eq!(c.take(), Some(Request::Stop(StopMode::Hold, None)));
        c.halt();
        assert_eq!(c.take(), Some(Request::Halt));
    }
}
