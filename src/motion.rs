//! The sans-IO motion core: robot time and clocks, trapezoidal profiles, the planner for
//! MoveAbsJ/MoveJ/MoveL/MoveC with zones, and the fixed-rate `MotionCore::tick(now)`.
//!
//! Nothing here sleeps, spawns threads, opens sockets or reads the operating system's clock;
//! `controller::rt` drives the core, and tests drive it by hand with a [`clock::VirtualClock`].
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

pub mod clock;
pub mod profile;

pub use clock::{Clock, RobotTime, VirtualClock, VirtualClockHandle};
