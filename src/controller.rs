//! The composition root of the virtual controller: the program side's `ControllerHandle`, the
//! real-time shell around the motion core (the only code that spawns threads or sleeps),
//! clocks, timing statistics and the end-of-run summary.
//!
//! Two clock modes: **virtual** (the default; deterministic, as fast as the CPU allows: robot
//! time advances only while the program waits) and **real time** (a motion thread at the
//! fixed period against the monotonic clock, optionally with SCHED_FIFO priority).
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

pub mod condition;
pub mod corrected_moves;
pub mod cycle_hook;
pub mod egm_controller;
pub mod handle;
/// The mass storage sandbox lives below the interpreter (RAPID's file instructions use it);
/// services reach it here.
pub use crate::mass_storage;
pub mod monotonic_clock;
mod motion_thread;
pub mod period_stats;
pub mod position_cell;
pub mod position_events;
pub mod priority;
pub mod program_host;
mod realtime_driver;
pub mod robtarget_query;
pub mod sample_feed;
pub mod service;
pub mod signal_script;
pub mod summary;
pub mod system_outputs;
pub mod system_state;
pub mod tasks;
pub mod tick_sink;
mod virtual_driver;

use std::time::Duration;

use crate::motion::{CoreConfig, MotionError, MotionEvent};
use crate::robot::{JointsDeg, Robot};

pub use condition::Condition;
pub use cycle_hook::CycleHook;
pub use handle::ControllerHandle;
pub use monotonic_clock::MonotonicClock;
pub use period_stats::PeriodStats;
pub use priority::RealtimeConfig;
pub use program_host::ControllerHost;
pub use summary::RunSummary;
pub use tick_sink::TickSink;

/// How robot time runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ClockMode {
    /// Deterministic virtual time, as fast as the CPU allows (the default).
    #[default]
    Virtual,
    /// Real time on a motion thread at the fixed period.
    RealTime(RealtimeConfig),
}

/// Everything needed to start a controller.
#[derive(Clone, Debug)]
pub struct ControllerConfig {
    /// The robot (model and base frame).
    pub robot: Robot,
    /// Cycle period and queue length.
    pub core: CoreConfig,
    /// Axis values at start (deg).
    pub start: JointsDeg,
    /// Virtual or real time.
    pub clock: ClockMode,
    /// Real time: how long before each deadline the motion thread stops sleeping and spins.
    pub spin: Duration,
    /// The longest a single `wait_until` may take (robot time in virtual mode, wall time in
    /// real time) before it fails with [`ControllerError::Timeout`].
    pub max_wait: Duration,
}

/// Default spin time before each deadline in real time (µs precision on a loaded machine).
pub const DEFAULT_SPIN: Duration = Duration::from_micros(200);

/// Default maximum wait: one hour.
pub const DEFAULT_MAX_WAIT: Duration = Duration::from_secs(3600);

impl ControllerConfig {
    /// Virtual time, default core settings, the robot at `start`.
    pub fn new(robot: Robot, start: JointsDeg) -> ControllerConfig {
        ControllerConfig {
            robot,
            core: CoreConfig::default(),
            start,
            clock: ClockMode::Virtual,
            spin: DEFAULT_SPIN,
            max_wait: DEFAULT_MAX_WAIT,
        }
    }
}

/// Why a controller call failed.
#[derive(Debug, thiserror::Error)]
pub enum ControllerError {
    /// The move was refused before the robot moved.
    #[error("{0}")]
    Rejected(MotionError),
    /// The robot stopped on a motion error while (or before) the program waited.
    #[error("the robot stopped: {0}")]
    Stopped(Box<MotionEvent>),
    /// The condition can never become true (the robot is idle and nothing is queued).
    #[error("waiting for {0} while no motion is queued would never end")]
    NeverSatisfied(String),
    /// The wait took longer than the configured maximum.
    #[error("the wait exceeded the maximum of {0:?}")]
    Timeout(Duration),
    /// Real-time priority could not be obtained (`RealtimeConfig::Enforce`).
    #[error("{0}")]
    Priority(String),
    /// A controller thread could not be started or has ended.
    #[error("{0}")]
    Thread(String),
    /// The start position is not usable (outside the axis ranges or not finite).
    #[error("invalid start position: {0}")]
    InvalidStart(crate::robot::KinError),
    /// A trace or plot could not be written.
    #[error("{0}")]
    Sink(String),
    /// The run was interrupted (Ctrl-C) while a move waited for room in the queue.
    #[error("the run was interrupted")]
    Interrupted,
}
