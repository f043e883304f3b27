//! What a blocked program waits for: the conditions of `ControllerHandle::wait_until`.

use std::fmt;

use crate::motion::MotionState;
use crate::time::RobotTime;

/// A condition on the motion state that a waiting program needs before it continues.
pub enum Condition {
    /// Every submitted move is complete and the robot stands still (a `fine` point reached,
    /// `WaitRob \InPos`).
    InPos,
    /// The robot is not moving right now: idle, or at a stop point (`WaitRob \ZeroSpeed`).
    Standstill,
    /// The move with this command id is complete (for a fly-by point: its corner began).
    Done(u64),
    /// Robot time has reached this instant (`WaitTime`): ends on the first cycle at or after it.
    TimeReached(RobotTime),
    /// Any predicate on the state (evaluated after every cycle).
    Predicate(Box<dyn FnMut(&MotionState) -> bool + Send>),
}

impl fmt::Debug for Condition {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Condition::InPos => f.write_str("InPos"),
            Condition::Standstill => f.write_str("Standstill"),
            Condition::Done(id) => write!(f, "Done({id})"),
            Condition::TimeReached(t) => write!(f, "TimeReached({t})"),
            Condition::Predicate(_) => f.write_str("Predicate"),
        }
    }
}

impl Condition {
    /// True when the condition holds in `state`.
    pub fn met(&mut self, state: &MotionState) -> bool {
        match self {
            Condition::InPos => state.in_position(),
            Condition::Standstill => state.setpoint.standstill,
            Condition::Done(id) => state.done(*id),
            Condition::TimeReached(t) => state.setpoint.time >= *t,
            Condition::Predicate(p) => p(state),
        }
    }

    /// True when only motion can make the condition true (so an idle robot never will).
    pub fn depends_on_motion_only(&self) -> bool {
        matches!(
            self,
            Condition::InPos | Condition::Standstill | Condition::Done(_)
        )
    }
}
