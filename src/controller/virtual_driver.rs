//! Virtual time: the motion core runs on the caller's thread, and robot time advances one
//! cycle at a time only while the program side waits (a full queue, a fine point, `WaitTime`,
//! `WaitRob`). Deterministic: the same commands give the same cycles, bit for bit.

use std::time::Duration;

use crate::motion::{MotionCore, MotionEvent, Setpoint};
use crate::time::{RobotTime, VirtualClock, VirtualClockHandle};

use super::cycle_hook::CycleHook;
use super::tick_sink::TickSink;

/// The virtual-time driver of a controller handle.
pub(super) struct VirtualDriver {
    pub core: MotionCore,
    clock: VirtualClockHandle,
    period: Duration,
    pub sinks: Vec<Box<dyn TickSink>>,
    pub hook: Option<Box<dyn CycleHook>>,
    pub ticks: u64,
}

impl VirtualDriver {
    pub fn new(
        core: MotionCore,
        period: Duration,
        sinks: Vec<Box<dyn TickSink>>,
        hook: Option<Box<dyn CycleHook>>,
    ) -> VirtualDriver {
        let (_clock, handle) = VirtualClock::with_handle();
        VirtualDriver {
            core,
            clock: handle,
            period,
            sinks,
            hook,
            ticks: 0,
        }
    }

    /// The current robot time.
    pub fn now(&self) -> RobotTime {
        self.clock.now()
    }

    /// One cycle: advance the clock, tick, feed the sinks, collect events.
    pub fn tick(&mut self, events: &mut Vec<MotionEvent>) -> Setpoint {
        let now = self.clock.advance(self.period);
        if let Some(h) = self.hook.as_mut() {
            h.before_tick(now, self.core.executor_mut());
        }
        let sp = self.core.tick(now);
        if let Some(h) = self.hook.as_mut() {
            h.after_tick(&sp, self.core.executor_mut());
        }
        self.ticks += 1;
        for s in &mut self.sinks {
            s.record(&sp);
        }
        while let Some(e) = self.core.take_event() {
            events.push(e);
        }
        sp
    }
}
