//! The EGM servo law the motion core calls each tick: pure, over joint vectors in degrees, unit-tested, no I/O and no allocation per step.
//!
//! This is the discrete model of docs/egm.md, "Servo law" (each step a rapidvc choice where ABB does
//! not document one). Per step of length Ts = [`ServoParams::period`]:
//!
//! 1. e = ref − pos_cmd (selected axes; unselected axes keep their start value);
//! 2. v = k · PosCorrGain · e + speed_ref, with k the profile's Default Proportional
//!    Position Gain (1/s);
//! 3. first-order low-pass at `\LpFilter`: v_f ← v_f + α (v − v_f), α = 1 − exp(−2π·f·Ts);
//! 4. ramp-in: × min(1, t / `\RampInTime`) (linear);
//! 5. MaxSpeedDeviation: when max |v_i| exceeds it, all joints are scaled by the same factor
//!    (reported: [`ServoOutput::speed_limited`], rising edge [`ServoOutput::speed_limit_began`]);
//! 6. pos_cmd ← pos_cmd + v·Ts, clamped to start ± MaxPosDeviation (reported likewise) and
//!    to the robot's axis ranges when [`ServoParams::axis_limits`] is set (so a command never
//!    crosses a joint limit; reported as [`ServoOutput::limit_axes`]);
//! 7. `planned` = pos_cmd; `feedBack` = pos_cmd delayed by [`ServoParams::servo_delay`];
//! 8. convergence: every selected axis has ref − feedback inside its `egm_minmax` window
//!    (or the caller's own error vector, e.g. the Cartesian error in pose mode, over
//!    [`ServoParams::convergence_axes`]), held continuously for `\CondTime`; then the stop
//!    mode ends the run.
//!
//! A filter bandwidth of 0 Hz (allowed for the profile's Default Low Pass Filter Bandwidth)
//! switches the filter off (α = 1) rather than blocking all motion.
//!
//! **Reaction time.** ABB states a control lag of 10–20 ms, "usually about 20 ms" from a new
//! reference until the robot reacts (RobotStudio measured about 16 ms, a real IRB 4600 about
//! 25 ms). With the defaults (4 ms period, 20 Hz filter, 12 ms servo delay) the measured
//! position starts to move 16 ms after the step that first uses a new reference, and the
//! measured speed reaches 63 % of the commanded speed after 20 ms: two steps of filter rise
//! (α ≈ 0.39 per 4 ms step) plus the 12 ms delay. The sensor's wait for the next EGM cycle
//! (0–4 ms) comes on top, as on a real controller. Set [`ServoParams::servo_delay`] to model
//! another robot.
//!
//! **Stops** (`servo/stop.rs`). Every end decelerates from the speed of the last step —
//! all axes together, linearly — within MaxSpeedDeviation and
//! [`ServoParams::axis_accel`], and never carries an axis past the last reference (nor its
//! MaxPosDeviation bound or axis range). [`StopMode::Hold`] brakes as quickly as the
//! accelerations allow and stays there; [`StopMode::RampDown`] brakes the same way, then
//! returns to the start position along a cosine over at least `\RampOutTime` (longer when
//! MaxSpeedDeviation or the accelerations need it); [`EgmServo::halt`] (program stop,
//! errors, comm time-out) brakes over the profile's Default Ramp Time (shorter when the
//! reference is closer) and stays where that leaves the robot.
//!
//! **Speed scale** (`EgmServo::pause`, `EgmServo::resume`, `EgmServo::set_ratio`). A
//! running servo multiplies the EGM speed of step 5 by a scale in 0…1: the controller's
//! speed ratio while the program runs, 0 while it is stopped (the program stop that lets the
//! EGM run resume on start). The scale moves toward its target linearly over the profile's
//! Default Ramp Time (a full change 0 ↔ 1), and more slowly when an axis's acceleration
//! needs it (the change may add at most half of each axis's acceleration at the speed the
//! law asks for), so a stop, a start, or any series of them never jerks the robot. While the
//! run is paused the convergence timer (`\CondTime`) stands at zero: the condition must hold
//! for `\CondTime` of guided motion after the start.

use std::time::Duration;

use super::event::{EgmEvent, EventKind};
use super::types::{Joints, ROBOT_AXES};

mod stop;
use stop::{Brake, StopFrom, brake_steps, return_steps};

/// Default Proportional Position Gain of the predefined "default" profile, 1/s.
pub const DEFAULT_KP: f64 = 5.0;
/// Default Low Pass Filter Bandwidth, Hz.
pub const DEFAULT_LP_FILTER_HZ: f64 = 20.0;
/// Default Ramp Time of the "default" profile.
pub const DEFAULT_RAMP_TIME: Duration = Duration::from_millis(500);
/// `\MaxSpeedDeviation` default, degrees/s (ABB's; users trip on it).
pub const DEFAULT_MAX_SPEED_DEVIATION: f64 = 1.0;
/// `\MaxPosDeviation` default, degrees.
pub const DEFAULT_MAX_POS_DEVIATION: f64 = 1000.0;
/// Default servo delay (see the module docs).
pub const DEFAULT_SERVO_DELAY: Duration = Duration::from_millis(12);
/// `\CondTime` default.
pub const DEFAULT_COND_TIME: Duration = Duration::from_secs(1);
/// Shortest step (keeps the servo-delay line small).
pub const MIN_PERIOD: Duration = Duration::from_micros(100);
/// Longest servo delay.
pub const MAX_SERVO_DELAY: Duration = Duration::from_secs(1);

pub use crate::egm_args::{MinMax, StopMode};

/// Parameters of one EGM run (EGMAct*, EGMRun*, the motion profile and rapidvc options).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ServoParams {
    /// Step length: the motion tick at which the servo is stepped.
    pub period: Duration,
    /// Default Proportional Position Gain of the profile, 1/s.
    pub kp: f64,
    /// `\PosCorrGain` (0 = pure velocity control).
    pub pos_corr_gain: f64,
    /// `\LpFilter`, Hz; values ≤ 0 use `default_lp_filter_hz` (as a real controller accepts).
    pub lp_filter_hz: f64,
    /// The profile's Default Low Pass Filter Bandwidth, Hz.
    pub default_lp_filter_hz: f64,
    /// `\RampInTime` (zero: full tracking from the first step).
    pub ramp_in_time: Duration,
    /// `\RampOutTime` for `RampDown`.
    pub ramp_out_time: Duration,
    /// `\MaxSpeedDeviation`, degrees/s.
    pub max_speed_deviation: f64,
    /// `\MaxPosDeviation`, degrees from the start position.
    pub max_pos_deviation: f64,
    /// Delay from commanded to measured position.
    pub servo_delay: Duration,
    /// `\CondTime`.
    pub cond_time: Duration,
    /// Convergence windows per axis (`\J1`..`\J6` of EGMActJoint).
    pub windows: [MinMax; ROBOT_AXES],
    /// Axes moved by EGM (`\J1`..`\J6` switches of EGMRunJoint).
    pub selected: [bool; ROBOT_AXES],
    /// Which entries of the convergence error are checked against `windows`; `None`: the
    /// `selected` axes. Pose mode moves every joint but checks the selected Cartesian
    /// directions (`\x`…`\rz`), so it sets this apart from `selected`.
    pub convergence_axes: Option<[bool; ROBOT_AXES]>,
    /// The robot's axis ranges `(min, max)`, degrees: the commanded position never leaves
    /// them. `None`: no axis limits (only MaxPosDeviation).
    pub axis_limits: Option<[MinMax; ROBOT_AXES]>,
    /// The robot's axis accelerations, degrees/s²: no stop decelerates an axis faster.
    /// `None`: stops are bounded by the reference only.
    pub axis_accel: Option<Joints>,
    /// How the run ends.
    pub stop_mode: StopMode,
}

impl Default for ServoParams {
    /// ABB's defaults: 4 ms, k = 5, gain 1, 20 Hz, ramps 0.5 s, 1 °/s, 1000 °, CondTime 1 s,
    /// ±0.5 ° windows, all axes, HOLD; plus rapidvc's 12 ms servo delay.
    fn default() -> Self {
        ServoParams {
            period: Duration::from_millis(4),
            kp: DEFAULT_KP,
            pos_corr_gain: 1.0,
            lp_filter_hz: DEFAULT_LP_FILTER_HZ,
            default_lp_filter_hz: DEFAULT_LP_FILTER_HZ,
            ramp_in_time: DEFAULT_RAMP_TIME,
            ramp_out_time: DEFAULT_RAMP_TIME,
            max_speed_deviation: DEFAULT_MAX_SPEED_DEVIATION,
            max_pos_deviation: DEFAULT_MAX_POS_DEVIATION,
            servo_delay: DEFAULT_SERVO_DELAY,
            cond_time: DEFAULT_COND_TIME,
            windows: [MinMax::JOINT_DEFAULT; ROBOT_AXES],
            selected: [true; ROBOT_AXES],
            convergence_axes: None,
            axis_limits: None,
            axis_accel: None,
            stop_mode: StopMode::Hold,
        }
    }
}

/// A parameter the servo cannot run with.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ServoError {
    /// A number is NaN, infinite or outside its range.
    #[error("EGM parameter {name} = {value} is outside {range}")]
    OutOfRange {
        /// Parameter name as in RAPID.
        name: &'static str,
        /// Given value.
        value: f64,
        /// Allowed range, in words.
        range: &'static str,
    },
    /// The start position is not finite.
    #[error("the EGM start position is not finite")]
    StartNotFinite,
}

/// Phase of a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ServoPhase {
    /// Tracking the reference.
    Running,
    /// HOLD stop: braking to rest.
    Holding,
    /// RAMP_DOWN stop: braking, then returning to the start position.
    RampingDown,
    /// Program stop (or an error): the EGM speed ramps to zero.
    Halting,
    /// Finished; the robot stands still.
    Done,
}

/// What ended (or is ending) the run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EndCause {
    /// Convergence held for CondTime.
    Converged,
    /// [`EgmServo::stop`] (EGMStop, comm time-out, error).
    Stopped,
    /// [`EgmServo::halt`] (program stop).
    Halted,
}

/// The reference for one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ServoInput {
    /// Position reference, degrees.
    pub position: Joints,
    /// Speed reference (feed-forward), degrees/s.
    pub speed: Joints,
    /// Convergence error per axis to use instead of `position − feedback` (for example the
    /// Cartesian error in pose mode, mm and degrees); `None` for joint mode.
    pub convergence_error: Option<[f64; ROBOT_AXES]>,
}

impl ServoInput {
    /// A position reference with no speed reference.
    pub fn position(position: Joints) -> Self {
        ServoInput {
            position,
            speed: [0.0; ROBOT_AXES],
            convergence_error: None,
        }
    }
}

/// Result of one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ServoOutput {
    /// Commanded position (sent as `planned`), degrees.
    pub commanded: Joints,
    /// Measured position (sent as `feedBack`), degrees.
    pub feedback: Joints,
    /// Applied EGM speed, degrees/s.
    pub velocity: Joints,
    /// Phase after this step.
    pub phase: ServoPhase,
    /// Convergence criteria met in this step (`mciConvergenceMet`).
    pub convergence_met: bool,
    /// How long they have been met continuously.
    pub converged_for: Duration,
    /// Requested EGM speed as a share of MaxSpeedDeviation, percent (`utilizationRate`).
    pub utilization: f64,
    /// MaxSpeedDeviation scaled the speed in this step.
    pub speed_limited: bool,
    /// This step is the first of a limited stretch (report it).
    pub speed_limit_began: bool,
    /// The scale factor applied (1 when not limited).
    pub limit_factor: f64,
    /// Bit i set: axis i+1 was clamped by MaxPosDeviation in this step.
    pub clamped_axes: u8,
    /// This step is the first of a clamped stretch (report it).
    pub clamp_began: bool,
    /// Bit i set: axis i+1 was held at its axis limit ([`ServoParams::axis_limits`]).
    pub limit_axes: u8,
    /// This step is the first of a stretch held at an axis limit (report it).
    pub limit_began: bool,
    /// Set once the run has finished, with its cause.
    pub finished: Option<EndCause>,
}

/// The EGM servo state of one run.
#[derive(Clone, Debug)]
pub struct EgmServo {
    params: ServoParams,
    ts: f64,
    alpha: f64,
    start: Joints,
    commanded: Joints,
    filtered: Joints,
    delay: Vec<Joints>,
    delay_head: usize,
    steps: u64,
    phase: ServoPhase,
    cause: Option<EndCause>,
    converged_for: Duration,
    phase_start_step: u64,
    phase_from: Joints,
    phase_steps: u64,
    /// The stop's brake while it runs (`stop.rs`).
    brake: Option<Brake>,
    /// RAMP_DOWN: the shortest time from the stop to the start position.
    ramp_out: Duration,
    /// Speed of the last step, degrees/s (what a stop starts from).
    moved: Joints,
    /// The position reference of the last running step.
    reference: Option<Joints>,
    was_limited: bool,
    was_clamped: bool,
    was_at_limit: bool,
    at_limit: u8,
    /// The speed scale (module docs): this step's value, the speed ratio, paused, and the
    /// time of a full change.
    scale: f64,
    ratio: f64,
    paused: bool,
    scale_ramp: Duration,
}

/// Share of each axis's acceleration a change of the speed scale may add.
const SCALE_ACCEL_SHARE: f64 = 0.5;

impl EgmServo {
    /// Starts a run at `start` (the fine point the EGM movement begins in).
    pub fn new(params: ServoParams, start: Joints) -> Result<Self, ServoError> {
        validate(&params)?;
        if !start.iter().all(|v| v.is_finite()) {
            return Err(ServoError::StartNotFinite);
        }
        let ts = params.period.as_secs_f64();
        let lp = if params.lp_filter_hz > 0.0 {
            params.lp_filter_hz
        } else {
            params.default_lp_filter_hz
        };
        let alpha = if lp > 0.0 {
            1.0 - (-std::f64::consts::TAU * lp * ts).exp()
        } else {
            1.0
        };
        let delay_steps = delay_steps(params.servo_delay, params.period);
        Ok(EgmServo {
            params,
            ts,
            alpha,
            start,
            commanded: start,
            filtered: [0.0; ROBOT_AXES],
            delay: vec![start; delay_steps],
            delay_head: 0,
            steps: 0,
            phase: ServoPhase::Running,
            cause: None,
            converged_for: Duration::ZERO,
            phase_start_step: 0,
            phase_from: start,
            phase_steps: 1,
            brake: None,
            ramp_out: Duration::ZERO,
            moved: [0.0; ROBOT_AXES],
            reference: None,
            was_limited: false,
            was_clamped: false,
            was_at_limit: false,
            at_limit: 0,
            scale: 1.0,
            ratio: 1.0,
            paused: false,
            scale_ramp: DEFAULT_RAMP_TIME,
        })
    }

    /// The program stopped with the run going on: the EGM speed ramps to zero over `ramp`
    /// (the profile's Default Ramp Time; module docs) and the run waits for
    /// [`EgmServo::resume`]. A run already ending (EGMStop, convergence) goes on braking to
    /// rest; a RAMP_DOWN return stops where it is ([`EgmServo::halt`]).
    pub fn pause(&mut self, ramp: Duration) {
        match self.phase {
            ServoPhase::Running => {
                self.paused = true;
                self.scale_ramp = ramp;
            }
            ServoPhase::RampingDown if self.brake.is_none() => self.halt(ramp),
            _ => {}
        }
    }

    /// The program started again: the EGM speed ramps back in over `ramp`.
    pub fn resume(&mut self, ramp: Duration) {
        if self.paused {
            self.paused = false;
            self.scale_ramp = ramp;
            self.converged_for = Duration::ZERO;
        }
    }

    /// True while paused by [`EgmServo::pause`].
    pub fn is_paused(&self) -> bool {
        self.paused
    }

    /// The controller's speed ratio (0…1, from its percent): scales the EGM speed, reached
    /// over `ramp` like a pause.
    pub fn set_ratio(&mut self, ratio: f64, ramp: Duration) {
        if ratio.is_finite() {
            self.ratio = ratio.clamp(0.0, 1.0);
            self.scale_ramp = ramp;
        }
    }

    /// The speed scale of this step (module docs).
    pub fn speed_scale(&self) -> f64 {
        self.scale
    }

    /// Moves the scale one bounded step toward its target, given the speed the law asks
    /// for (`law`, degrees/s, before scaling).
    fn step_scale(&mut self, law: &Joints) {
        let target = if self.paused { 0.0 } else { self.ratio };
        let ramp = self.scale_ramp.as_secs_f64();
        let mut step = if ramp > 0.0 { self.ts / ramp } else { 1.0 };
        if let Some(accel) = self.params.axis_accel {
            for (v, a) in law.iter().zip(&accel) {
                let v = v.abs();
                if v > 0.0 && a.is_finite() && *a > 0.0 {
                    step = step.min(SCALE_ACCEL_SHARE * a * self.ts / v);
                }
            }
        }
        let c = self.scale;
        self.scale = if c < target {
            (c + step).min(target)
        } else {
            (c - step).max(target)
        };
    }

    /// The parameters.
    pub fn params(&self) -> &ServoParams {
        &self.params
    }

    /// The start position.
    pub fn start(&self) -> &Joints {
        &self.start
    }

    /// The current phase.
    pub fn phase(&self) -> ServoPhase {
        self.phase
    }

    /// The servo delay in whole steps.
    pub fn delay_steps(&self) -> usize {
        self.delay.len()
    }

    /// Ends the run with `mode` (EGMStop, a comm time-out or an error); `ramp_out` is the
    /// `RampDown` duration (the profile's Default Ramp Time when the stop is not from RAPID).
    /// Ignored once the run is already ending.
    pub fn stop(&mut self, mode: StopMode, ramp_out: Duration) {
        if self.phase == ServoPhase::Running {
            self.begin_stop(mode, ramp_out, EndCause::Stopped);
        }
    }

    /// Program stop: the EGM speed ramps to zero over `ramp_time` (shorter when the
    /// reference is closer, longer when the accelerations need it) and the robot stays
    /// there. A brake under way (HOLD, or RAMP_DOWN before its return) goes on: it is already
    /// the shortest stop; a RAMP_DOWN return stops where it is, short of the start position.
    pub fn halt(&mut self, ramp_time: Duration) {
        match self.phase {
            ServoPhase::Running => {
                self.cause = Some(EndCause::Halted);
                self.begin_brake(ServoPhase::Halting, ramp_time, self.reference);
            }
            ServoPhase::Holding => {
                self.cause = Some(EndCause::Halted);
                self.phase = ServoPhase::Halting;
            }
            ServoPhase::RampingDown if self.brake.is_some() => {
                self.cause = Some(EndCause::Halted);
                self.phase = ServoPhase::Halting;
            }
            ServoPhase::RampingDown => {
                self.cause = Some(EndCause::Halted);
                self.begin_brake(ServoPhase::Halting, ramp_time, Some(self.start));
            }
            ServoPhase::Halting | ServoPhase::Done => {}
        }
    }

    fn begin_stop(&mut self, mode: StopMode, ramp_out: Duration, cause: EndCause) {
        self.cause = Some(cause);
        self.ramp_out = ramp_out;
        match mode {
            StopMode::Hold => {
                self.begin_brake(ServoPhase::Holding, Duration::ZERO, self.reference);
            }
            StopMode::RampDown => {
                self.begin_brake(ServoPhase::RampingDown, Duration::ZERO, self.reference);
            }
        }
    }

    /// Enters `phase` with a brake from the last step's speed (nominally over `nominal`)
    /// that stops short of `reference`.
    fn begin_brake(&mut self, phase: ServoPhase, nominal: Duration, reference: Option<Joints>) {
        let from = StopFrom {
            at: &self.commanded,
            speed: &self.moved,
            start: &self.start,
            reference: reference.as_ref(),
        };
        let steps = brake_steps(&self.params, self.ts, &from, nominal);
        self.brake = Some(Brake::new(self.moved, steps));
        self.enter(phase, steps);
    }

    fn enter(&mut self, phase: ServoPhase, steps: u64) {
        self.phase = phase;
        self.phase_start_step = self.steps;
        self.phase_from = self.commanded;
        self.phase_steps = steps.max(1);
    }

    /// One step of the brake; `true` once the robot is at rest.
    fn brake_step(&mut self, velocity: &mut Joints) -> (u8, bool) {
        let Some(brake) = self.brake.as_mut() else {
            return (0, true);
        };
        let (v, done) = brake.step();
        *velocity = v;
        if done {
            self.brake = None;
        }
        (self.integrate(&v), done)
    }

    /// One step with the reference in force.
    pub fn step(&mut self, input: &ServoInput) -> ServoOutput {
        self.steps += 1;
        self.at_limit = 0;
        let mut utilization = 0.0;
        let mut limit_factor = 1.0;
        let mut clamped_axes = 0u8;
        let mut velocity = [0.0; ROBOT_AXES];
        let before = self.commanded;
        match self.phase {
            ServoPhase::Running => {
                let k = self.params.kp * self.params.pos_corr_gain;
                for i in 0..ROBOT_AXES {
                    let selected = self.params.selected.get(i).copied().unwrap_or(false);
                    let raw = if selected {
                        let r = input.position.get(i).copied().unwrap_or(0.0);
                        let c = self.commanded.get(i).copied().unwrap_or(0.0);
                        let s = input.speed.get(i).copied().unwrap_or(0.0);
                        let v = k * (r - c) + s;
                        // The session never passes non-finite references; stay finite anyway.
                        if v.is_finite() { v } else { 0.0 }
                    } else {
                        0.0
                    };
                    if let Some(f) = self.filtered.get_mut(i) {
                        *f += self.alpha * (raw - *f);
                    }
                }
                if input.position.iter().all(|r| r.is_finite()) {
                    self.reference = Some(input.position);
                }
                let ramp = ramp_in(self.steps, self.ts, self.params.ramp_in_time);
                for (v, f) in velocity.iter_mut().zip(&self.filtered) {
                    *v = ramp * f;
                }
                let peak = velocity.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let msd = self.params.max_speed_deviation;
                utilization = if msd > 0.0 { 100.0 * peak / msd } else { 0.0 };
                if peak > msd {
                    limit_factor = if peak > 0.0 { msd / peak } else { 0.0 };
                    for v in &mut velocity {
                        *v *= limit_factor;
                    }
                }
                self.step_scale(&velocity);
                if self.scale < 1.0 {
                    for v in &mut velocity {
                        *v *= self.scale;
                    }
                }
                clamped_axes = self.integrate(&velocity);
            }
            ServoPhase::Holding | ServoPhase::Halting => {
                let (clamped, done) = self.brake_step(&mut velocity);
                clamped_axes = clamped;
                if done {
                    self.finish();
                }
            }
            ServoPhase::RampingDown if self.brake.is_some() => {
                let (clamped, done) = self.brake_step(&mut velocity);
                clamped_axes = clamped;
                if done {
                    // Back to the start within what is left of \RampOutTime, or longer.
                    let braked = self.params.period.saturating_mul(
                        u32::try_from(self.steps - self.phase_start_step).unwrap_or(u32::MAX),
                    );
                    let left = self.ramp_out.saturating_sub(braked);
                    let steps =
                        return_steps(&self.params, self.ts, &self.commanded, &self.start, left);
                    self.enter(ServoPhase::RampingDown, steps);
                }
            }
            ServoPhase::RampingDown => {
                let s = self.phase_progress();
                let shape = 0.5 * (1.0 - (std::f64::consts::PI * s).cos());
                for i in 0..ROBOT_AXES {
                    let from = self.phase_from.get(i).copied().unwrap_or(0.0);
                    let to = self.start.get(i).copied().unwrap_or(0.0);
                    let target = if s >= 1.0 {
                        to
                    } else {
                        from + (to - from) * shape
                    };
                    if let (Some(c), Some(v)) = (self.commanded.get_mut(i), velocity.get_mut(i)) {
                        *v = (target - *c) / self.ts;
                        *c = target;
                    }
                }
                self.at_limit = self.hold_in_axis_limits();
                self.filtered = [0.0; ROBOT_AXES];
                if s >= 1.0 {
                    self.finish();
                }
            }
            ServoPhase::Done => {}
        }
        for ((m, c), b) in self.moved.iter_mut().zip(&self.commanded).zip(&before) {
            *m = (c - b) / self.ts;
        }
        let feedback = self.push_delay();
        let convergence_met = self.convergence(input, &feedback);
        if convergence_met && !self.paused {
            self.converged_for = self.converged_for.saturating_add(self.params.period);
        } else {
            self.converged_for = Duration::ZERO;
        }
        if self.phase == ServoPhase::Running
            && convergence_met
            && !self.paused
            && self.converged_for >= self.params.cond_time
        {
            let (mode, ramp) = (self.params.stop_mode, self.params.ramp_out_time);
            self.begin_stop(mode, ramp, EndCause::Converged);
        }
        let speed_limited = limit_factor < 1.0;
        let speed_limit_began = speed_limited && !self.was_limited;
        self.was_limited = speed_limited;
        let clamped = clamped_axes != 0;
        let clamp_began = clamped && !self.was_clamped;
        self.was_clamped = clamped;
        let limit_axes = self.at_limit;
        let at_limit = limit_axes != 0;
        let limit_began = at_limit && !self.was_at_limit;
        self.was_at_limit = at_limit;
        ServoOutput {
            commanded: self.commanded,
            feedback,
            velocity,
            phase: self.phase,
            convergence_met,
            converged_for: self.converged_for,
            utilization,
            speed_limited,
            speed_limit_began,
            limit_factor,
            clamped_axes,
            clamp_began,
            limit_axes,
            limit_began,
            finished: (self.phase == ServoPhase::Done)
                .then_some(self.cause)
                .flatten(),
        }
    }

    fn finish(&mut self) {
        self.phase = ServoPhase::Done;
        self.brake = None;
        self.filtered = [0.0; ROBOT_AXES];
    }

    /// Progress 0..=1 through a timed phase.
    fn phase_progress(&self) -> f64 {
        let elapsed = (self.steps - self.phase_start_step) as f64;
        (elapsed / self.phase_steps as f64).min(1.0)
    }

    /// pos_cmd += v·Ts, clamped to start ± MaxPosDeviation; returns the clamped-axes mask.
    fn integrate(&mut self, velocity: &Joints) -> u8 {
        let mut mask = 0u8;
        let mpd = self.params.max_pos_deviation;
        for i in 0..ROBOT_AXES {
            let v = velocity.get(i).copied().unwrap_or(0.0);
            let start = self.start.get(i).copied().unwrap_or(0.0);
            if let Some(c) = self.commanded.get_mut(i) {
                let next = *c + v * self.ts;
                let bounded = next.clamp(start - mpd, start + mpd);
                if bounded != next {
                    mask |= 1 << i;
                    // Stop the filter winding up against the bound.
                    if let Some(f) = self.filtered.get_mut(i) {
                        *f = 0.0;
                    }
                }
                *c = bounded;
            }
        }
        self.at_limit |= self.hold_in_axis_limits();
        mask
    }

    /// Keeps the commanded position inside the axis limits; returns the mask of held axes.
    fn hold_in_axis_limits(&mut self) -> u8 {
        let Some(limits) = self.params.axis_limits else {
            return 0;
        };
        let mut mask = 0u8;
        for (i, (c, l)) in self.commanded.iter_mut().zip(&limits).enumerate() {
            let bounded = c.clamp(l.min, l.max);
            if bounded != *c {
                mask |= 1 << i;
                *c = bounded;
                if let Some(f) = self.filtered.get_mut(i) {
                    *f = 0.0;
                }
            }
        }
        mask
    }

    /// Pushes the commanded position into the delay line and returns the delayed one.
    fn push_delay(&mut self) -> Joints {
        let len = self.delay.len();
        match self.delay.get_mut(self.delay_head) {
            Some(slot) => {
                let out = *slot;
                *slot = self.commanded;
                self.delay_head = (self.delay_head + 1) % len.max(1);
                out
            }
            None => self.commanded,
        }
    }

    fn convergence(&self, input: &ServoInput, feedback: &Joints) -> bool {
        let axes = self.params.convergence_axes.unwrap_or(self.params.selected);
        let mut any = false;
        for i in 0..ROBOT_AXES {
            if !axes.get(i).copied().unwrap_or(false) {
                continue;
            }
            any = true;
            let error = match &input.convergence_error {
                Some(e) => e.get(i).copied().unwrap_or(0.0),
                None => {
                    input.position.get(i).copied().unwrap_or(0.0)
                        - feedback.get(i).copied().unwrap_or(0.0)
                }
            };
            let window = self
                .params
                .windows
                .get(i)
                .copied()
                .unwrap_or(MinMax::JOINT_DEFAULT);
            if !window.contains(error) {
                return false;
            }
        }
        // No axis selected: "no movement, RAPID continues" — trivially converged.
        any || axes.iter().all(|s| !s)
    }
}

/// The event to log when [`ServoOutput::speed_limit_began`] is set.
pub fn speed_limit_event(params: &ServoParams, output: &ServoOutput) -> EgmEvent {
    let requested = output.utilization / 100.0 * params.max_speed_deviation;
    EgmEvent::new(
        EventKind::SpeedLimited,
        format!(
            "requested {requested:.3} deg/s, MaxSpeedDeviation is {} deg/s: all joints scaled by {:.4}; raise \\MaxSpeedDeviation in EGMActJoint/EGMActPose if the robot is too slow",
            params.max_speed_deviation, output.limit_factor
        ),
    )
}

/// The event to log when [`ServoOutput::limit_began`] is set.
pub fn axis_limit_event(params: &ServoParams, output: &ServoOutput) -> EgmEvent {
    let axes: Vec<String> = (0..ROBOT_AXES)
        .filter(|i| output.limit_axes & (1 << i) != 0)
        .map(|i| {
            let range = params
                .axis_limits
                .and_then(|l| l.get(i).copied())
                .map(|l| format!(" ({} to {} deg)", l.min, l.max))
                .unwrap_or_default();
            format!("J{}{range}", i + 1)
        })
        .collect();
    EgmEvent::new(
        EventKind::AxisLimit,
        format!(
            "{} held at the axis limit; the EGM command does not cross it",
            axes.join(", ")
        ),
    )
}

/// The event to log when [`ServoOutput::clamp_began`] is set.
pub fn pos_clamp_event(params: &ServoParams, output: &ServoOutput) -> EgmEvent {
    let axes: Vec<String> = (0..ROBOT_AXES)
        .filter(|i| output.clamped_axes & (1 << i) != 0)
        .map(|i| format!("J{}", i + 1))
        .collect();
    EgmEvent::new(
        EventKind::PositionClamped,
        format!(
            "{} held at {} deg from the start position (\\MaxPosDeviation)",
            axes.join(", "),
            params.max_pos_deviation
        ),
    )
}

fn ramp_in(steps: u64, ts: f64, ramp: Duration) -> f64 {
    let total = ramp.as_secs_f64();
    if total <= 0.0 {
        1.0
    } else {
        (steps as f64 * ts / total).min(1.0)
    }
}

fn delay_steps(delay: Duration, period: Duration) -> usize {
    let p = period.as_nanos().max(1);
    let steps = (delay.as_nanos() + p / 2) / p;
    usize::try_from(steps).unwrap_or(0)
}

fn validate(p: &ServoParams) -> Result<(), ServoError> {
    let check = |name: &'static str, value: f64, ok: bool, range: &'static str| {
        if value.is_finite() && ok {
            Ok(())
        } else {
            Err(ServoError::OutOfRange { name, value, range })
        }
    };
    let period = p.period.as_secs_f64();
    check(
        "period",
        period,
        p.period >= MIN_PERIOD,
        "[0.1 ms, ∞) (a motion tick)",
    )?;
    check("ext_motion_Kp", p.kp, p.kp >= 0.0, "[0, ∞)")?;
    check(
        "\\PosCorrGain",
        p.pos_corr_gain,
        p.pos_corr_gain >= 0.0,
        "[0, ∞)",
    )?;
    check("\\LpFilter", p.lp_filter_hz, true, "finite numbers")?;
    check(
        "ext_motion_filter_bandwidth",
        p.default_lp_filter_hz,
        p.default_lp_filter_hz >= 0.0,
        "[0, ∞) Hz",
    )?;
    check(
        "\\MaxSpeedDeviation",
        p.max_speed_deviation,
        p.max_speed_deviation >= 0.0,
        "[0, ∞) deg/s",
    )?;
    check(
        "\\MaxPosDeviation",
        p.max_pos_deviation,
        p.max_pos_deviation >= 0.0,
        "[0, ∞) deg",
    )?;
    let delay = p.servo_delay.as_secs_f64();
    check(
        "servo delay",
        delay,
        p.servo_delay <= MAX_SERVO_DELAY,
        "[0, 1] s",
    )?;
    for w in &p.windows {
        check("egm_minmax.min", w.min, w.min <= w.max, "≤ max")?;
        check("egm_minmax.max", w.max, true, "finite numbers")?;
    }
    for a in p.axis_accel.iter().flatten() {
        check("axis acceleration", *a, *a > 0.0, "(0, ∞) deg/s²")?;
    }
    for l in p.axis_limits.iter().flatten() {
        check("axis limit min", l.min, l.min <= l.max, "≤ max")?;
        check("axis limit max", l.max, true, "finite numbers")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests;
