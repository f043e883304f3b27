//! The seam for external guidance (EGM): a per-cycle reference source that moves the robot
//! instead of the planner, under the core's supervision (axis ranges and speeds).

use std::any::Any;

use crate::robot::JointsDeg;

use crate::time::RobotTime;

/// What external guidance asks for in one cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GuidanceStep {
    /// Command these axis values this cycle.
    MoveTo(JointsDeg),
    /// Keep the current position.
    Hold,
    /// Guidance is over; the core returns to planned moves at the current position.
    Finished,
}

/// A source of per-cycle references, e.g. the EGM servo law (`egm::servo`).
///
/// `step` runs inside the motion cycle: it must not block, sleep, allocate or panic.
/// Anything expensive belongs in the code that feeds it (the EGM session), outside the cycle.
///
/// The shell that owns the core reaches the running guidance between cycles with
/// `MotionCore::guidance_as::<T>()` (or `Executor::guidance_as`) to hand it the newest sensor
/// reference before a tick and read its outputs after it (`Any` makes the downcast possible).
pub trait ExternalGuidance: Any + Send {
    /// The reference for the cycle at `now`, given the axis values of the previous cycle.
    fn step(&mut self, now: RobotTime, current: &JointsDeg) -> GuidanceStep;
}
