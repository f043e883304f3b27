//! The seam for external guidance (EGM): a per-cycle reference source that moves the robot
//! instead of the planner, under the core's supervision (axis ranges and speeds).

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
/// The shell that starts the guidance keeps its own typed handle on it (the object is shared,
/// e.g. behind a lock only the motion thread takes) to hand it the newest sensor data before
/// a tick and read its outputs after it; the core knows it only through this trait.
pub trait ExternalGuidance: Send {
    /// The reference for the cycle at `now`, given the axis values of the previous cycle.
    fn step(&mut self, now: RobotTime, current: &JointsDeg) -> GuidanceStep;
}
