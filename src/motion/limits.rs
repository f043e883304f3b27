//! Pure limit functions over named constants: acceleration models the robot data does not
//! give, zone sizes, override factors and per-cycle axis-speed checks.

use crate::robot::{JointsDeg, RobotModel};

use super::segment::Sample;
use super::settings::MotionSettings;

/// Time (s) the TCP needs to reach the model's maximum TCP speed: the Cartesian acceleration
/// is `vmax_tcp / TCP_RAMP_S`. ABB publishes no figure; 0.25 s matches the main-axis ramp of
/// the robot models (`robot::models`), e.g. 22.4 m/s² on the IRB 2600.
pub const TCP_RAMP_S: f64 = 0.25;

/// Zones smaller than this (mm) give no corner path (a pure reorientation, or a zone the
/// robot crosses within one cycle).
pub const MIN_ZONE_MM: f64 = 0.01;

/// Moves shorter than this TCP distance (mm) count as pure reorientations.
pub const MIN_PATH_MM: f64 = 1e-6;

/// A linear or circular move may be slowed down at most this much below its programmed speed
/// to keep every axis within its speed limit; beyond that the path runs too close to a
/// singularity and is refused (event 50026).
pub const MAX_SLOWDOWN: f64 = 50.0;

/// Relative slack of the per-cycle axis-speed supervision (float noise).
pub const SPEED_SUPERVISION_SLACK: f64 = 1e-6;

/// The speed override factor of `VelSet` (0…1].
pub fn override_factor(s: &MotionSettings) -> f64 {
    let f = s.velset.override_pct / 100.0;
    if f.is_finite() && f > 0.0 {
        f.min(1.0)
    } else {
        1.0
    }
}

/// The acceleration factor of `AccSet` (0…1].
pub fn accel_factor(s: &MotionSettings) -> f64 {
    let f = s.accset.acc_pct / 100.0;
    if f.is_finite() && f > 0.0 {
        f.min(1.0)
    } else {
        1.0
    }
}

/// The programmed TCP speed after `VelSet` and the model's `vmax`, mm/s.
pub fn effective_tcp_speed(v_tcp: f64, s: &MotionSettings, model: &RobotModel) -> f64 {
    let mut v = v_tcp * override_factor(s);
    if s.velset.max_tcp.is_finite() && s.velset.max_tcp > 0.0 {
        v = v.min(s.velset.max_tcp);
    }
    v.min(model.vmax_tcp)
}

/// Cartesian acceleration of the TCP (mm/s²) after `AccSet`, `PathAccLim` and `WorldAccLim`.
pub fn tcp_accel(model: &RobotModel, s: &MotionSettings) -> f64 {
    let mut a = model.vmax_tcp / TCP_RAMP_S * accel_factor(s);
    for lim in [s.path_acc_lim, s.world_acc_lim].into_iter().flatten() {
        if lim.is_finite() && lim > 0.0 {
            a = a.min(lim);
        }
    }
    a
}

/// Reorientation acceleration (deg/s²) after `AccSet`: the slowest wrist axis's acceleration.
pub fn ori_accel(model: &RobotModel, s: &MotionSettings) -> f64 {
    let wrist = model
        .max_accel
        .iter()
        .skip(3)
        .copied()
        .fold(f64::INFINITY, f64::min);
    wrist * accel_factor(s)
}

/// Axis speed limits (deg/s) after `VelSet`.
pub fn axis_speeds(model: &RobotModel, s: &MotionSettings) -> JointsDeg {
    let f = override_factor(s);
    model.max_speed.map(|v| v * f)
}

/// Axis acceleration limits (deg/s²) after `AccSet`.
pub fn axis_accels(model: &RobotModel, s: &MotionSettings) -> JointsDeg {
    let f = accel_factor(s);
    model.max_accel.map(|a| a * f)
}

/// The zone radius actually used at a fly-by point: the programmed one, reduced to half the
/// path length of each neighbouring move (docs/robot.md, "Zones and corner paths").
pub fn zone_radius(programmed: f64, len_before: f64, len_after: f64) -> f64 {
    if programmed.is_nan() || len_before.is_nan() || len_after.is_nan() {
        return 0.0;
    }
    let z = programmed.min(len_before / 2.0).min(len_after / 2.0);
    if z.is_finite() && z >= MIN_ZONE_MM {
        z
    } else {
        0.0
    }
}

/// The worst axis speed of a sampled motion, relative to each axis's limit: `(ratio, sample
/// index, axis index)`. `from` is where the motion starts; `dt` the cycle in seconds.
/// Ratio ≤ 1 means every axis stays within its limit.
pub fn worst_speed_ratio(
    from: &JointsDeg,
    samples: &[Sample],
    dt: f64,
    max_speed: &JointsDeg,
) -> (f64, usize, usize) {
    let mut worst = (0.0, 0, 0);
    let mut prev = from;
    for (k, s) in samples.iter().enumerate() {
        let (r, axis) = step_speed_ratio(prev, &s.q, dt, max_speed);
        if r > worst.0 {
            worst = (r, k, axis);
        }
        prev = &s.q;
    }
    worst
}

/// The largest `|Δq| / dt / max_speed` of one step and its axis index. NaN steps count as
/// infinitely fast.
pub fn step_speed_ratio(
    a: &JointsDeg,
    b: &JointsDeg,
    dt: f64,
    max_speed: &JointsDeg,
) -> (f64, usize) {
    let mut worst = (0.0, 0);
    for (i, ((x, y), vmax)) in a.iter().zip(b).zip(max_speed).enumerate() {
        let v = (y - x).abs() / dt;
        let r = if v.is_nan() { f64::INFINITY } else { v / vmax };
        if r > worst.0 {
            worst = (r, i);
        }
    }
    worst
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]
mod tests {
    use super::*;
    use crate::robot::{Pose, default_model};

    #[test]
    fn zones_are_halved() {
        assert_eq!(zone_radius(50.0, 400.0, 300.0), 50.0);
        assert_eq!(zone_radius(50.0, 60.0, 300.0), 30.0);
        assert_eq!(zone_radius(50.0, 400.0, 0.0), 0.0);
        assert_eq!(zone_radius(f64::NAN, 400.0, 300.0), 0.0);
    }

    #[test]
    fn overrides() {
        let m = default_model();
        let mut s = MotionSettings::default();
        assert_eq!(effective_tcp_speed(1000.0, &s, m), 1000.0);
        assert_eq!(effective_tcp_speed(7000.0, &s, m), 5000.0);
        s.velset.override_pct = 50.0;
        s.accset.acc_pct = 25.0;
        assert_eq!(effective_tcp_speed(1000.0, &s, m), 500.0);
        assert_eq!(axis_speeds(m, &s)[0], m.max_speed[0] / 2.0);
        assert_eq!(axis_accels(m, &s)[0], m.max_accel[0] / 4.0);
        assert!(tcp_accel(m, &s) > 0.0 && ori_accel(m, &s) > 0.0);
    }

    #[test]
    fn speed_ratio() {
        let s = |q: JointsDeg| Sample {
            q,
            tcp: Pose::identity(),
        };
        let max = [100.0; 6];
        let samples = [
            s([0.2, 0.0, 0.0, 0.0, 0.0, 0.0]),
            s([0.2, 0.0, 0.8, 0.0, 0.0, 0.0]),
        ];
        let (r, k, axis) = worst_speed_ratio(&[0.0; 6], &samples, 0.004, &max);
        assert!((r - 2.0).abs() < 1e-9 && k == 1 && axis == 2);
    }
}
