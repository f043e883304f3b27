//! Configuration of the motion core (cycle period, queue length) and the modal motion settings
//! RAPID changes with `VelSet`, `AccSet` and `SingArea`.

use std::time::Duration;

/// Fixed settings of a motion core.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoreConfig {
    /// The motion cycle (4 ms on an IRC5).
    pub period: Duration,
    /// Planned moves that may wait in the queue (RAPID runs this far ahead of the robot).
    pub queue_capacity: usize,
    /// Events kept until they are taken.
    pub event_capacity: usize,
}

/// The default motion cycle: 4 ms (250 Hz), as on an IRC5 (docs/robot.md, "Motion cycle").
pub const DEFAULT_PERIOD: Duration = Duration::from_millis(4);

/// Default queue length (moves planned ahead of the robot).
pub const DEFAULT_QUEUE_CAPACITY: usize = 8;

/// Shortest and longest motion cycle the core accepts (other values are clamped).
pub const PERIOD_RANGE: (Duration, Duration) =
    (Duration::from_micros(100), Duration::from_millis(100));

/// Longest queue and event log the core accepts (larger values are clamped).
pub const MAX_CAPACITY: usize = 4096;

impl CoreConfig {
    /// The configuration with every value in its supported range: the period within
    /// [`PERIOD_RANGE`], the queue and event log between 1 and [`MAX_CAPACITY`].
    pub fn sanitized(&self) -> CoreConfig {
        CoreConfig {
            period: self.period.clamp(PERIOD_RANGE.0, PERIOD_RANGE.1),
            queue_capacity: self.queue_capacity.clamp(1, MAX_CAPACITY),
            event_capacity: self.event_capacity.clamp(1, MAX_CAPACITY),
        }
    }
}

impl Default for CoreConfig {
    fn default() -> Self {
        CoreConfig {
            period: DEFAULT_PERIOD,
            queue_capacity: DEFAULT_QUEUE_CAPACITY,
            event_capacity: 256,
        }
    }
}

/// `VelSet Override, Max`: programmed speeds are scaled by `override_pct` % and the TCP speed
/// is capped at `max_tcp` mm/s. The override scales axis speeds of joint moves too.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VelSet {
    /// Speed override in percent (0 < x ≤ 100; larger values are accepted and cut to 100).
    pub override_pct: f64,
    /// Maximum TCP speed (mm/s).
    pub max_tcp: f64,
}

impl Default for VelSet {
    /// `VelSet 100, 5000` (the controller's start-up values).
    fn default() -> Self {
        VelSet {
            override_pct: 100.0,
            max_tcp: 5000.0,
        }
    }
}

/// `AccSet Acc, Ramp`: acceleration in percent of the normal value. `Ramp` (jerk) is accepted
/// and has no effect: the profile has no jerk limit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AccSet {
    /// Acceleration and deceleration in percent of normal (0 < x ≤ 100).
    pub acc_pct: f64,
    /// Rate of change of acceleration in percent (accepted, no effect).
    pub ramp_pct: f64,
}

impl Default for AccSet {
    fn default() -> Self {
        AccSet {
            acc_pct: 100.0,
            ramp_pct: 100.0,
        }
    }
}

/// `SingArea`: how linear and circular moves behave near singular arm configurations.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SingArea {
    /// `SingArea \Off`: a linear or circular path that runs into any singularity is refused
    /// before the robot moves (event 50026).
    #[default]
    Off,
    /// `SingArea \Wrist`: the path may pass close to the wrist singularity; the move is slowed
    /// down so that axes 4 and 6 stay within their speed limits (the TCP keeps its path; the
    /// model does not trade orientation accuracy for speed as ABB does).
    Wrist,
    /// `SingArea \LockAxis4`: accepted and treated as `\Wrist`.
    LockAxis4,
}

/// The modal motion settings that apply to moves planned from now on.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MotionSettings {
    /// `VelSet`.
    pub velset: VelSet,
    /// `AccSet`.
    pub accset: AccSet,
    /// `SingArea`.
    pub singarea: SingArea,
    /// `PathAccLim`: the TCP acceleration along linear and circular paths is at most this
    /// (mm/s²). The profile accelerates and decelerates alike, so the smaller of `\AccMax`
    /// and `\DecelMax` applies to both.
    pub path_acc_lim: Option<f64>,
    /// `WorldAccLim \On`: the TCP acceleration in world coordinates is at most this (mm/s²);
    /// applied to linear and circular paths like `path_acc_lim`.
    pub world_acc_lim: Option<f64>,
}
