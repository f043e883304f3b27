//! Robot time, the controller's one clock type: [`RobotTime`] (nanoseconds since the controller started), every conversion to and from it — `Duration`s, seconds as RAPID numbers, milliseconds and `EgmClock` seconds/microseconds on the EGM wire — and the clocks that produce it ([`Clock`], the [`VirtualClock`]; the monotonic clock is the controller's).
//!
//! A leaf module: every layer may use it (`docs/architecture.md`, "Time"). The motion core,
//! the EGM protocol machines, the controller, the outputs and the interpreter's host all
//! take robot time as a value handed in; none of them reads the operating system's clock
//! (only `controller::monotonic_clock` does). Spans of time (a period, a time-out) stay
//! [`Duration`]s; points in time are [`RobotTime`]s.

use std::fmt;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// A point in robot time: nanoseconds since the controller started.
///
/// Robot time is injected into the motion core (`tick(now)`) and the EGM machines and never
/// read from the operating system inside them, so a test or a virtual-time run decides what
/// "now" is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct RobotTime(pub u64);

impl RobotTime {
    /// The start of robot time.
    pub const ZERO: RobotTime = RobotTime(0);

    /// The last representable time (about 584 years).
    pub const MAX: RobotTime = RobotTime(u64::MAX);

    /// From nanoseconds.
    pub const fn from_nanos(ns: u64) -> RobotTime {
        RobotTime(ns)
    }

    /// From milliseconds (saturating).
    pub const fn from_millis(ms: u64) -> RobotTime {
        RobotTime(ms.saturating_mul(1_000_000))
    }

    /// Nanoseconds since the start.
    pub const fn as_nanos(self) -> u64 {
        self.0
    }

    /// The time elapsed since the start, as a [`Duration`].
    pub const fn since_start(self) -> Duration {
        Duration::from_nanos(self.0)
    }

    /// From a duration since the start (saturating at [`RobotTime::MAX`]).
    pub fn from_duration(d: Duration) -> RobotTime {
        RobotTime(u64::try_from(d.as_nanos()).unwrap_or(u64::MAX))
    }

    /// Seconds since the start (RAPID's `num` seconds, the path corrector's clock).
    pub fn as_secs_f64(self) -> f64 {
        self.since_start().as_secs_f64()
    }

    /// From seconds since the start, rounded to the nearest nanosecond; negative or
    /// non-finite values give [`RobotTime::ZERO`], huge ones saturate.
    pub fn from_secs_f64(s: f64) -> RobotTime {
        RobotTime::from_duration(secs(s))
    }

    /// `self + s` seconds (a RAPID duration; see [`secs`]), saturating.
    pub fn after_secs(self, s: f64) -> RobotTime {
        self.saturating_add(secs(s))
    }

    /// `self + d`, saturating.
    pub fn saturating_add(self, d: Duration) -> RobotTime {
        RobotTime(self.0.saturating_add(RobotTime::from_duration(d).0))
    }

    /// `self − d`, saturating at [`RobotTime::ZERO`].
    pub fn saturating_sub(self, d: Duration) -> RobotTime {
        RobotTime(self.0.saturating_sub(RobotTime::from_duration(d).0))
    }

    /// The duration from `earlier` to `self` (zero if `earlier` is later).
    pub fn saturating_since(self, earlier: RobotTime) -> Duration {
        Duration::from_nanos(self.0.saturating_sub(earlier.0))
    }

    /// `header.tm` of an EGM message: milliseconds since the start, wrapping at 2³².
    pub fn wire_ms(self) -> u32 {
        wire_ms(self.since_start())
    }

    /// An `EgmClock` of the EGM wire: whole seconds and the remaining microseconds.
    pub fn egm_clock(self) -> (u64, u64) {
        egm_clock(self.since_start())
    }

    /// The time an `EgmClock` (seconds, microseconds) stands for (saturating).
    pub fn from_egm_clock(sec: u64, usec: u64) -> RobotTime {
        RobotTime::from_duration(duration_from_egm_clock(sec, usec))
    }
}

impl std::ops::Add<Duration> for RobotTime {
    type Output = RobotTime;

    /// `self + d`, saturating (as [`RobotTime::saturating_add`]).
    fn add(self, d: Duration) -> RobotTime {
        self.saturating_add(d)
    }
}

impl std::ops::AddAssign<Duration> for RobotTime {
    /// `self = self + d`, saturating.
    fn add_assign(&mut self, d: Duration) {
        *self = self.saturating_add(d);
    }
}

impl std::ops::Sub for RobotTime {
    type Output = Duration;

    /// The duration from `earlier` to `self`, zero if `earlier` is later (as
    /// [`RobotTime::saturating_since`]).
    fn sub(self, earlier: RobotTime) -> Duration {
        self.saturating_since(earlier)
    }
}

impl fmt::Display for RobotTime {
    /// Seconds with millisecond resolution, e.g. `12.344 s`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let d = self.since_start();
        write!(f, "{}.{:03} s", d.as_secs(), d.subsec_millis())
    }
}

/// A duration in seconds as RAPID passes it (a `num`), rounded to the nearest nanosecond;
/// negative or non-finite values give zero, huge ones saturate.
pub fn secs(s: f64) -> Duration {
    if s.is_finite() && s > 0.0 {
        Duration::try_from_secs_f64(s).unwrap_or(Duration::MAX)
    } else {
        Duration::ZERO
    }
}

/// `header.tm` for a clock that counts `d` since its start: milliseconds, wrapping at 2³²
/// (a sensor's own clock; the controller's is [`RobotTime::wire_ms`]).
pub fn wire_ms(d: Duration) -> u32 {
    (d.as_millis() % (1u128 << 32)) as u32
}

/// An `EgmClock` (whole seconds, remaining microseconds) for `d` since the clock's start.
pub fn egm_clock(d: Duration) -> (u64, u64) {
    (d.as_secs(), u64::from(d.subsec_micros()))
}

/// The duration an `EgmClock` stands for (saturating on overflow).
pub fn duration_from_egm_clock(sec: u64, usec: u64) -> Duration {
    Duration::from_secs(sec).saturating_add(Duration::from_micros(usec))
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
    fn wire_conversions() {
        let t = RobotTime::from_millis(4_294_967_297);
        assert_eq!(t.wire_ms(), 1, "header.tm wraps at 2^32 ms");
        let t = RobotTime::from_nanos(12_345_678_901);
        assert_eq!(t.egm_clock(), (12, 345_678));
        assert_eq!(
            RobotTime::from_egm_clock(12, 345_678),
            RobotTime(12_345_678_000)
        );
        assert_eq!(RobotTime::from_egm_clock(u64::MAX, 1), RobotTime::MAX);
        assert_eq!(
            RobotTime(9).saturating_sub(Duration::from_nanos(10)),
            RobotTime::ZERO
        );
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
