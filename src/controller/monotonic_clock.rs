//! The monotonic clock: robot time from the operating system's steady clock. The only reader
//! of `Instant::now` in the crate.

use std::time::{Duration, Instant};

use crate::time::{Clock, RobotTime};

/// Robot time since the clock was created, from `std::time::Instant`.
#[derive(Clone, Copy, Debug)]
pub struct MonotonicClock {
    origin: Instant,
}

impl MonotonicClock {
    /// A clock reading [`RobotTime::ZERO`] now.
    pub fn new() -> MonotonicClock {
        MonotonicClock {
            origin: Instant::now(),
        }
    }

    /// Time elapsed since the clock was created.
    pub fn elapsed(&self) -> Duration {
        self.origin.elapsed()
    }
}

impl Default for MonotonicClock {
    fn default() -> Self {
        MonotonicClock::new()
    }
}

impl Clock for MonotonicClock {
    fn now(&self) -> RobotTime {
        RobotTime::from_duration(self.origin.elapsed())
    }
}
