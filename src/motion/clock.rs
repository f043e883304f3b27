//! Robot time as a value: `RobotTime` (nanoseconds), the `Clock` trait and the virtual clock
//! with its handle (the monotonic clock lives in `controller::monotonic_clock`, the only reader of
//! the operating system's clock).

use std::fmt;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// A point in robot time: nanoseconds since the controller started.
///
/// Robot time is injected into the motion core (`tick(now)`) and never read from the operating
/// system inside it, so a test or a virtual-time run decides what "now" is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct RobotTime(pub u64);

impl RobotTime {
    /// The start of robot time.
    pub const ZERO: RobotTime = RobotTime(0);

    /// From nanoseconds.
    pub const fn from_nanos(ns: u64) -> RobotTime {
        RobotTime(ns)
    }

    /// Nanoseconds since the start.
    pub const fn as_nanos(self) -> u64 {
        self.0
    }

    /// The time elapsed since the start, as a [`Duration`].
    pub const fn since_start(self) -> Duration {
        Duration::from_nanos(self.0)
    }

    /// From a duration since the start (saturating at `u64::MAX` ns, about 584 years).
    pub fn from_duration(d: Duration) -> RobotTime {
        RobotTime(u64::try_from(d.as_nanos()).unwrap_or(u64::MAX))
    }

    /// Seconds since the start.
    pub fn as_secs_f64(self) -> f64 {
        self.since_start().as_secs_f64()
    }

    /// From seconds since the start; negative or non-finite values give [`RobotTime::ZERO`],
    /// huge ones saturate.
    pub fn from_secs_f64(s: f64) -> RobotTime {
        if s.is_finite() && s > 0.0 {
            Duration::try_from_secs_f64(s)
                .map(RobotTime::from_duration)
                .unwrap_or(RobotTime(u64::MAX))
        } else {
            RobotTime::ZERO
        }
    }

    /// `self + d`, saturating.
    pub fn saturating_add(self, d: Duration) -> RobotTime {
        RobotTime(self.0.saturating_add(RobotTime::from_duration(d).0))
    }

    /// The duration from `earlier` to `self` (zero if `earlier` is later).
    pub fn saturating_since(self, earlier: RobotTime) -> Duration {
        Duration::from_nanos(self.0.saturating_sub(earlier.0))
    }
}

impl fmt::Display for RobotTime {
    /// Seconds with millisecond resolution, e.g. `12.344 s`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let d = self.since_start();
        write!(f, "{}.{:03} s", d.as_secs(), d.subsec_millis())
    }
}

/// A source of robot time.
pub trait Clock: Send + Sync {
    /// The current robot time.
    fn now(&self) -> RobotTime;
}

/// A clock that only moves when told to, through its [`VirtualClockHandle`].
///
/// Clones share the same time. This is the clock of deterministic (virtual-time) runs and of
/// every test that drives the motion core by hand.
#[derive(Clone, Debug, Default)]
pub struct VirtualClock {
    ns: Arc<AtomicU64>,
}

/// The control side of a [`VirtualClock`]: advances or sets its time.
#[derive(Clone, Debug)]
pub struct VirtualClockHandle {
    ns: Arc<AtomicU64>,
}

impl VirtualClock {
    /// A virtual clock at [`RobotTime::ZERO`].
    pub fn new() -> VirtualClock {
        VirtualClock::default()
    }

    /// A virtual clock and its handle.
    pub fn with_handle() -> (VirtualClock, VirtualClockHandle) {
        let clock = VirtualClock::new();
        let handle = clock.handle();
        (clock, handle)
    }

    /// A handle that moves this clock.
    pub fn handle(&self) -> VirtualClockHandle {
        VirtualClockHandle {
            ns: Arc::clone(&self.ns),
        }
    }
}

impl Clock for VirtualClock {
    fn now(&self) -> RobotTime {
        RobotTime(self.ns.load(Ordering::Acquire))
    }
}

impl VirtualClockHandle {
    /// Move the clock forward by `d` (saturating) and return the new time.
    pub fn advance(&self, d: Duration) -> RobotTime {
        let step = RobotTime::from_duration(d).0;
        let mut cur = self.ns.load(Ordering::Acquire);
        loop {
            let next = cur.saturating_add(step);
            match self
                .ns
                .compare_exchange_weak(cur, next, Ordering::AcqRel, Ordering::Acquire)
            {
                Ok(_) => return RobotTime(next),
                Err(seen) => cur = seen,
            }
        }
    }

    /// Set the clock to `t` (tests may move it backwards; the motion core tolerates that).
    pub fn set(&self, t: RobotTime) {
        self.ns.store(t.0, Ordering::Release);
    }

    /// The clock's current time.
    pub fn now(&self) -> RobotTime {
        RobotTime(self.ns.load(Ordering::Acquire))
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]
mod tests {
    use super::*;

    #[test]
    fn virtual_clock_moves_only_when_told() {
        let (clock, handle) = VirtualClock::with_handle();
        assert_eq!(clock.now(), RobotTime::ZERO);
        assert_eq!(
            handle.advance(Duration::from_millis(4)),
            RobotTime(4_000_000)
        );
        assert_eq!(clock.clone().now(), RobotTime(4_000_000));
        handle.set(RobotTime(1));
        assert_eq!(clock.now(), RobotTime(1));
        handle.set(RobotTime(u64::MAX - 1));
        assert_eq!(handle.advance(Duration::from_secs(1)), RobotTime(u64::MAX));
    }

    #[test]
    fn conversions() {
        let t = RobotTime::from_secs_f64(1.5);
        assert_eq!(t, RobotTime(1_500_000_000));
        assert_eq!(t.as_secs_f64(), 1.5);
        assert_eq!(t.to_string(), "1.500 s");
        assert_eq!(RobotTime::from_secs_f64(-3.0), RobotTime::ZERO);
        assert_eq!(RobotTime::from_secs_f64(f64::NAN), RobotTime::ZERO);
        assert_eq!(RobotTime::from_secs_f64(1e30), RobotTime(u64::MAX));
        assert_eq!(
            t.saturating_add(Duration::from_millis(4)),
            RobotTime(1_504_000_000)
        );
        assert_eq!(RobotTime(5).saturating_since(RobotTime(9)), Duration::ZERO);
    }
}
