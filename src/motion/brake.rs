//! Braking to rest from the speed the axes have: all axes together and linearly, so the joint path keeps its direction and no axis speeds up. Pure step arithmetic shared by the executor's stops and the EGM servo's.
//!
//! A brake from speed `v₀` over `n` steps of `dt` moves at `v₀ · (1 − k/n)` in step
//! `k = 1 … n` (at rest in step `n`), changes each axis's speed by `|v₀,i| / n` per step, and
//! covers `|v₀,i| · dt · (n − 1) / 2`.

use crate::robot::JointsDeg;

/// Most steps of one brake (keeps the arithmetic finite for absurd inputs).
const MAX_STEPS: f64 = 1.0e9;
/// Relative slack for rounding step counts (a bound met exactly is met).
const ROUNDING: f64 = 1.0e-9;

/// A linear deceleration of all axes together from `from` (deg/s) to rest.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Brake {
    from: JointsDeg,
    steps: u64,
    taken: u64,
}

impl Brake {
    /// A brake from the speed `from` over `steps` steps (at least one).
    pub fn new(from: JointsDeg, steps: u64) -> Brake {
        Brake {
            from,
            steps: steps.max(1),
            taken: 0,
        }
    }

    /// The speed of the next step, and whether it is the last one (its speed is zero).
    pub fn step(&mut self) -> (JointsDeg, bool) {
        self.taken = self.taken.saturating_add(1).min(self.steps);
        let left = (self.steps - self.taken) as f64 / self.steps as f64;
        let mut v = [0.0; 6];
        for (v, f) in v.iter_mut().zip(&self.from) {
            *v = f * left;
        }
        (v, self.taken >= self.steps)
    }

    /// Steps in all.
    pub fn steps(&self) -> u64 {
        self.steps
    }
}

/// The fewest steps of `dt` seconds in which a brake from `speed` keeps every axis within
/// its acceleration `accel` (deg/s²); at least one. Axes without a finite positive
/// acceleration do not bound it.
pub fn fewest_steps(speed: &JointsDeg, accel: &JointsDeg, dt: f64) -> u64 {
    let mut least = 1.0f64;
    for (v, a) in speed.iter().zip(accel) {
        if v.is_finite() && *a > 0.0 && a.is_finite() {
            least = least.max(count(v.abs() / (a * dt)));
        }
    }
    least as u64
}

/// The most steps of `dt` seconds a brake from `speed` (deg/s, one axis) may take without
/// covering more than `room` degrees; at least one.
pub fn most_steps(speed: f64, room: f64, dt: f64) -> u64 {
    let speed = speed.abs();
    if !(speed > 0.0 && speed.is_finite()) {
        return MAX_STEPS as u64;
    }
    let n = (1.0 + 2.0 * room.max(0.0) / (speed * dt) * (1.0 + ROUNDING)).floor();
    count(n) as u64
}

/// A step count from a real number of steps: rounded up (a count a hair above a whole
/// number, from rounding, is that number), at least 1, at most `MAX_STEPS` (NaN counts
/// as 1).
pub fn count(steps: f64) -> f64 {
    if steps.is_nan() {
        return 1.0;
    }
    (steps * (1.0 - ROUNDING)).ceil().clamp(1.0, MAX_STEPS)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::*;

    #[test]
    fn a_brake_slows_every_axis_evenly_to_rest() {
        let mut b = Brake::new([10.0, -5.0, 0.0, 0.0, 0.0, 0.0], 4);
        let speeds: Vec<f64> = (0..4).map(|_| b.step().0[0]).collect();
        assert_eq!(speeds, [7.5, 5.0, 2.5, 0.0]);
        assert_eq!(b.step(), ([0.0; 6], true), "stays at rest");
    }

    #[test]
    fn step_bounds() {
        // 100 deg/s at 700 deg/s² in 4 ms steps: 35.7 → 36 steps.
        assert_eq!(
            fewest_steps(&[100.0, 0.0, 0.0, 0.0, 0.0, 0.0], &[700.0; 6], 0.004),
            36
        );
        assert_eq!(
            fewest_steps(&[2.8, 0.0, 0.0, 0.0, 0.0, 0.0], &[700.0; 6], 0.004),
            1
        );
        assert_eq!(fewest_steps(&[f64::NAN; 6], &[700.0; 6], 0.004), 1);
        // 10 deg/s with 0.2° of room: (n − 1)·0.02 ≤ 0.2 → 11 steps.
        assert_eq!(most_steps(10.0, 0.2, 0.004), 11);
        assert_eq!(most_steps(-10.0, 0.0, 0.004), 1);
        assert_eq!(count(125.00000000001), 125.0);
    }
}
