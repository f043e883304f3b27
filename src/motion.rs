//! The sans-IO motion core: trapezoidal profiles, the planner for
//! MoveAbsJ/MoveJ/MoveL/MoveC with zones and corner paths, and the fixed-rate
//! `MotionCore::tick(now)` that plays the planned samples under supervision.
//!
//! Nothing here sleeps, spawns threads, opens sockets or reads the operating system's clock;
//! `controller::motion_thread` drives the core, and tests drive it by hand with a [`crate::time::VirtualClock`].
//!
//! Design: every move is planned completely when it is queued (the inverse kinematics of every
//! cycle of a linear move included), so errors surface before the robot moves and the cycle
//! itself only copies preplanned samples, checks them and hands over into corner paths.
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

pub mod brake;
pub mod core;
pub mod correction;
pub mod event;
pub mod executor;
pub mod external_guidance;
pub mod limits;
pub mod planner;
pub mod profile;
pub mod segment;
pub mod settings;
pub mod state;

pub use self::core::{EnqueueError, MotionCore};
pub use crate::time::{Clock, RobotTime, VirtualClock, VirtualClockHandle};
pub use correction::{PathCorrection, PathPoint};
pub use event::{InstrRef, MotionError, MotionEvent, PathPlace, Severity};
pub use executor::{Executor, PathOp, PathOpError};
pub use external_guidance::{ExternalGuidance, GuidanceStep};
pub use planner::Planner;
pub use settings::{AccSet, CoreConfig, MotionSettings, SingArea, VelSet};
pub use state::{CoreMode, MotionState, Setpoint};
