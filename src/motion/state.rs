//! What the motion core reports: the setpoint of each cycle and the observable state.

use crate::robot::{JointsDeg, Pose};

use super::event::InstrRef;
use crate::time::RobotTime;

/// The output of one motion cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Setpoint {
    /// Robot time of the cycle.
    pub time: RobotTime,
    /// Cycle number since the core started (the first tick is 1).
    pub tick: u64,
    /// Commanded axis values (deg).
    pub joints: JointsDeg,
    /// TCP of the active tool in world coordinates (mm).
    pub tcp: Pose,
    /// TCP speed (mm/s) over the last cycle.
    pub speed: f64,
    /// The robot stands still: no move in progress, or a stop point just reached.
    pub standstill: bool,
    /// The instruction being executed, if any.
    pub instr: Option<InstrRef>,
}

impl Setpoint {
    /// The setpoint of the next cycle, at `now`, if the robot stays where it is now (speed
    /// zero).
    pub fn held(&self, now: RobotTime, standstill: bool, instr: Option<InstrRef>) -> Setpoint {
        Setpoint {
            time: now,
            tick: self.tick.wrapping_add(1),
            joints: self.joints,
            tcp: self.tcp,
            speed: 0.0,
            standstill,
            instr,
        }
    }
}

/// Who moves the robot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CoreMode {
    /// Planned moves from the queue (RAPID move instructions).
    Planned,
    /// External guidance (EGM): a reference each cycle, supervised by the core.
    External,
}

/// A snapshot of the motion core.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionState {
    /// The last setpoint (at start: the initial position at time zero).
    pub setpoint: Setpoint,
    /// Moves planned but not started yet.
    pub pending: usize,
    /// True while a planned move is being executed.
    pub moving: bool,
    /// The last instruction whose move has been completed (or whose corner path began).
    pub last_done: Option<InstrRef>,
    /// True after a motion error: the robot holds its position and takes no moves until the
    /// core is recovered.
    pub halted: bool,
    /// Who moves the robot.
    pub mode: CoreMode,
    /// Events recorded so far (taken, pending or dropped).
    pub events_total: u64,
    /// The path is held (`StopMove`): the robot decelerates to rest on it and stays there
    /// until it is released.
    pub held: bool,
    /// Held by `StopMove` or a program stop, and come to rest on the path.
    pub held_at_rest: bool,
}

impl MotionState {
    /// Every planned move is complete and the robot stands still (`WaitRob \InPos`, the end of
    /// a `fine` move).
    pub fn in_position(&self) -> bool {
        !self.moving && self.pending == 0 && self.mode == CoreMode::Planned
    }

    /// True when the move with command id `id` (or a later one) is complete.
    pub fn done(&self, id: u64) -> bool {
        self.last_done.is_some_and(|d| d.id >= id)
    }
}
