//! Smoothing the applied correction towards its target within a speed and an acceleration
//! limit, braking so it arrives without overshoot.

use super::{EPS_MM, PathOffset, positive};

/// How fast the applied correction may change.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmoothingLimits {
    /// Largest correction speed, mm/s (`f64::INFINITY`: no limit). Default 20.
    pub max_speed: f64,
    /// Largest correction acceleration, mm/s² (`f64::INFINITY`: a pure rate limit).
    /// Default 200.
    pub max_accel: f64,
}

impl Default for SmoothingLimits {
    fn default() -> Self {
        SmoothingLimits {
            max_speed: 20.0,
            max_accel: 200.0,
        }
    }
}

/// Moves the applied offset towards a target within [`SmoothingLimits`] (module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Smoother {
    limits: SmoothingLimits,
    applied: PathOffset,
    velocity: PathOffset,
}

impl Smoother {
    /// At zero offset, at rest.
    pub fn new(limits: SmoothingLimits) -> Self {
        Smoother {
            limits,
            applied: PathOffset::ZERO,
            velocity: PathOffset::ZERO,
        }
    }

    /// The applied offset, mm.
    pub fn applied(&self) -> PathOffset {
        self.applied
    }

    /// The correction velocity, mm/s.
    pub fn velocity(&self) -> PathOffset {
        self.velocity
    }

    /// Back to zero offset, at rest.
    pub fn reset(&mut self) {
        self.applied = PathOffset::ZERO;
        self.velocity = PathOffset::ZERO;
    }

    /// Advance by `dt` seconds towards `target`; returns the applied offset. A non-finite
    /// target, a `dt` that is not positive and finite, or limits that are not positive
    /// (NaN included) leave the offset where it is.
    pub fn step(&mut self, target: PathOffset, dt: f64) -> PathOffset {
        let SmoothingLimits {
            max_speed: vmax,
            max_accel: amax,
        } = self.limits;
        if !target.is_finite()
            || !positive(dt)
            || !dt.is_finite()
            || !positive(vmax)
            || !positive(amax)
        {
            return self.applied;
        }
        let error = target.sub(self.applied);
        let dist = error.norm();
        let wanted = if dist > EPS_MM {
            let brake = if amax.is_finite() {
                braking_speed(dist, amax * dt * dt) / dt
            } else {
                f64::INFINITY
            };
            let speed = vmax.min(brake).min(dist / dt);
            error.scale(speed / dist)
        } else {
            PathOffset::ZERO
        };
        let mut dv = wanted.sub(self.velocity);
        let dv_max = amax * dt;
        let dv_norm = dv.norm();
        if dv_norm > dv_max {
            dv = dv.scale(dv_max / dv_norm);
        }
        let velocity = self.velocity.add(dv);
        let applied = self.applied.add(velocity.scale(dt));
        if !velocity.is_finite() || !applied.is_finite() {
            // Only reachable with absurd magnitudes; hold rather than emit NaN.
            self.velocity = PathOffset::ZERO;
            return self.applied;
        }
        self.velocity = velocity;
        self.applied = applied;
        // Land exactly. Braking along the exact curve arrives with a speed of at most
        // `dv_max`, so the next step can bring the velocity to zero.
        if target.sub(applied).norm() <= EPS_MM && velocity.norm() <= dv_max {
            self.applied = target;
        }
        self.applied
    }
}

/// The largest step `u` (a distance per step) from which steps `u, u − q, u − 2q, …` (all
/// positive ones) cover exactly `dist`, where `q = a·dt²` is the largest change of step
/// length. With `u = q·(n + f)`, `n` whole and `0 ≤ f ≤ 1`, the steps sum to
/// `q·((n + 1)·f + n(n + 1)/2)`; after one step the same holds with `n − 1`, so following
/// this speed brakes to rest exactly at the target.
fn braking_speed(dist: f64, q: f64) -> f64 {
    if !positive(q) || !q.is_finite() {
        return f64::INFINITY;
    }
    let d = dist / q;
    if !d.is_finite() {
        return f64::INFINITY;
    }
    let n = (((1.0 + 8.0 * d).sqrt() - 1.0) / 2.0).floor().max(0.0);
    let f = ((d - n * (n + 1.0) / 2.0) / (n + 1.0)).clamp(0.0, 1.0);
    q * (n + f)
}
