//! How an EGM run comes to rest, whatever ends it: pure step counts for a stop that starts from the speed the robot has, stays within MaxSpeedDeviation and the axis accelerations, and does not carry the robot past the last reference.
//!
//! **Brake** ([`Brake`], every stop): all axes decelerate together and linearly from the
//! speed of the last step, `v_k = v₀ · (1 − k/n)` for steps `k = 1 … n`, so the joint path
//! keeps its direction, no axis gets faster and none exceeds MaxSpeedDeviation. The number of
//! steps `n` ([`brake_steps`]) is the nominal one of the cause (the profile's Default Ramp
//! Time for a program stop, an error or a comm time-out; the shortest possible for a HOLD
//! stop), but
//! * never fewer than the axis accelerations allow: `|v₀,i| / n ≤ a_i · Ts` for every axis;
//! * never so many that an axis moving towards the last reference passes it, or passes the
//!   MaxPosDeviation bound or its axis range: the `n`-step brake covers
//!   `|v₀,i| · Ts · (n − 1) / 2`. An axis that already moves away from the reference (pure
//!   velocity control, a speed reference) brakes as early as its acceleration allows.
//!
//! Where the two conflict (a reference closer than the braking distance at the axis's
//! acceleration, which the control law itself never produces) the acceleration wins.
//!
//! **Return** (`EGM_STOP_RAMP_DOWN`, after the brake): a cosine from rest to rest back to
//! the start position over at least `\RampOutTime`, and as long as MaxSpeedDeviation and the
//! axis accelerations need: the cosine over `T` peaks at `π·D / (2T)` and `π²·D / (2T²)`
//! for a distance `D` ([`return_steps`]); the step differences of a sampled cosine stay
//! below both peaks.

use std::f64::consts::PI;
use std::time::Duration;

use super::ServoParams;
use crate::egm::types::{Joints, ROBOT_AXES};
pub(super) use crate::motion::brake::Brake;
use crate::motion::brake::{count, fewest_steps, most_steps};

/// Where a stop starts: the commanded position, the speed of the last step, the start of
/// the run and the reference in force (none before one arrived).
pub(super) struct StopFrom<'a> {
    /// Commanded position, degrees.
    pub at: &'a Joints,
    /// Speed of the last step, degrees/s.
    pub speed: &'a Joints,
    /// The run's start position (the MaxPosDeviation centre), degrees.
    pub start: &'a Joints,
    /// The last position reference, degrees.
    pub reference: Option<&'a Joints>,
}

/// Steps of the brake from `from.speed` to rest (module docs): `nominal` (at least one
/// step) within the acceleration and distance bounds of `p`, with steps of `ts` seconds.
pub(super) fn brake_steps(p: &ServoParams, ts: f64, from: &StopFrom<'_>, nominal: Duration) -> u64 {
    let least = p.axis_accel.map_or(1, |a| fewest_steps(from.speed, &a, ts));
    let mut most = u64::MAX;
    for (i, v) in from.speed.iter().enumerate().take(ROBOT_AXES) {
        most = most.min(most_steps(*v, room(p, i, v.signum(), from), ts));
    }
    (count(nominal.as_secs_f64() / ts) as u64)
        .min(most)
        .max(least)
}

/// How far axis `i`, moving in direction `dir`, may still travel: to the last reference
/// (nothing when it already moves away from it), the MaxPosDeviation bound and its range.
fn room(p: &ServoParams, i: usize, dir: f64, from: &StopFrom<'_>) -> f64 {
    let c = from.at.get(i).copied().unwrap_or(0.0);
    let mut room = f64::INFINITY;
    if let Some(r) = from.reference.and_then(|r| r.get(i).copied()) {
        room = ((r - c) * dir).max(0.0);
    }
    let start = from.start.get(i).copied().unwrap_or(c);
    let deviation = (start + dir * p.max_pos_deviation - c) * dir;
    room = room.min(deviation.max(0.0));
    if let Some(l) = p.axis_limits.and_then(|l| l.get(i).copied()) {
        let to_limit = if dir > 0.0 { l.max - c } else { c - l.min };
        room = room.min(to_limit.max(0.0));
    }
    room
}

/// Steps of the cosine return from `from` to `to` (module docs): at least `min_time`, and
/// long enough for MaxSpeedDeviation and the axis accelerations of `p`.
pub(super) fn return_steps(
    p: &ServoParams,
    ts: f64,
    from: &Joints,
    to: &Joints,
    min_time: Duration,
) -> u64 {
    let mut time = min_time.as_secs_f64();
    let mut farthest = 0.0f64;
    for i in 0..ROBOT_AXES {
        let d = (to.get(i).copied().unwrap_or(0.0) - from.get(i).copied().unwrap_or(0.0)).abs();
        if !d.is_finite() {
            continue;
        }
        farthest = farthest.max(d);
        if let Some(a) = p.axis_accel.and_then(|a| a.get(i).copied()) {
            time = time.max(PI * (d / (2.0 * a)).sqrt());
        }
    }
    if p.max_speed_deviation > 0.0 {
        time = time.max(PI * farthest / (2.0 * p.max_speed_deviation));
    }
    count(time / ts) as u64
}
