//! Trapezoidal velocity profiles of a normalised path parameter `s ∈ [0, 1]` (robot.md §9:
//! equal acceleration and deceleration, triangular when the move is short).
//!
//! Every move is a geometric path `s ↦ pose/joints` plus one of these time laws, so all axes of
//! a joint move arrive together and a linear move keeps its shape while speeding up.

/// A trapezoidal time law `t ↦ s(t)` from rest at `s = 0` to rest at `s = 1`.
///
/// Accelerates at `acc` for `t_acc`, cruises at `v_peak`, decelerates at `acc` for `t_acc`.
/// All quantities are normalised: `v_peak` is in path fractions per second.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trapezoid {
    duration: f64,
    t_acc: f64,
    v_peak: f64,
    acc: f64,
}

impl Trapezoid {
    /// A profile that takes no time (a move that goes nowhere).
    pub const INSTANT: Trapezoid = Trapezoid {
        duration: 0.0,
        t_acc: 0.0,
        v_peak: 0.0,
        acc: 0.0,
    };

    /// The time-optimal profile for the unit distance under `ṡ ≤ v_max` and `|s̈| ≤ a_max`.
    ///
    /// Limits that are infinite, NaN or not positive are treated as "no limit" when infinite
    /// and as "cannot move" (an infinite duration is avoided: the result is [`Self::INSTANT`])
    /// only when both are unbounded.
    pub fn fastest(v_max: f64, a_max: f64) -> Trapezoid {
        let v = sane_limit(v_max);
        let a = sane_limit(a_max);
        match (v, a) {
            (None, None) => Trapezoid::INSTANT,
            // No acceleration limit: constant velocity.
            (Some(v), None) => Trapezoid {
                duration: 1.0 / v,
                t_acc: 0.0,
                v_peak: v,
                acc: 0.0,
            },
            // No velocity limit: triangle.
            (None, Some(a)) => Trapezoid::triangle(a),
            (Some(v), Some(a)) => {
                if v * v / a >= 1.0 {
                    Trapezoid::triangle(a)
                } else {
                    let t_acc = v / a;
                    Trapezoid {
                        duration: 1.0 / v + t_acc,
                        t_acc,
                        v_peak: v,
                        acc: a,
                    }
                }
            }
        }
    }

    fn triangle(a: f64) -> Trapezoid {
        let t_acc = (1.0 / a).sqrt();
        Trapezoid {
            duration: 2.0 * t_acc,
            t_acc,
            v_peak: a * t_acc,
            acc: a,
        }
    }

    /// A profile lasting `duration` seconds that accelerates at `a_max` and then cruises
    /// (the slowest cruise that still fits). A `duration` shorter than the fastest triangle for
    /// `a_max` gives that triangle (the move never violates the acceleration limit).
    pub fn with_duration(duration: f64, a_max: f64) -> Trapezoid {
        if !(duration.is_finite() && duration > 0.0) {
            return Trapezoid::INSTANT;
        }
        let Some(a) = sane_limit(a_max) else {
            return Trapezoid {
                duration,
                t_acc: 0.0,
                v_peak: 1.0 / duration,
                acc: 0.0,
            };
        };
        let disc = duration * duration - 4.0 / a;
        if disc <= 0.0 {
            return Trapezoid::triangle(a);
        }
        let t_acc = (duration - disc.sqrt()) / 2.0;
        let v_peak = 1.0 / (duration - t_acc);
        Trapezoid {
            duration,
            t_acc,
            v_peak,
            acc: if t_acc > 0.0 { v_peak / t_acc } else { 0.0 },
        }
    }

    /// Total duration in seconds.
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// Duration of the acceleration ramp (and of the deceleration ramp) in seconds.
    pub fn ramp_time(&self) -> f64 {
        self.t_acc
    }

    /// Peak path speed (fractions of the path per second).
    pub fn peak_speed(&self) -> f64 {
        self.v_peak
    }

    /// Path acceleration (fractions of the path per second²).
    pub fn acceleration(&self) -> f64 {
        self.acc
    }

    /// `s(t)`, clamped to `[0, 1]` outside `[0, duration]`.
    pub fn position(&self, t: f64) -> f64 {
        if t <= 0.0 || self.duration <= 0.0 {
            return if self.duration <= 0.0 || t > 0.0 {
                1.0
            } else {
                0.0
            };
        }
        if t >= self.duration {
            return 1.0;
        }
        let s = if t < self.t_acc {
            0.5 * self.acc * t * t
        } else if t <= self.duration - self.t_acc {
            0.5 * self.acc * self.t_acc * self.t_acc + self.v_peak * (t - self.t_acc)
        } else {
            let r = self.duration - t;
            1.0 - 0.5 * self.acc * r * r
        };
        s.clamp(0.0, 1.0)
    }

    /// `ṡ(t)` (zero outside `[0, duration]`).
    pub fn velocity(&self, t: f64) -> f64 {
        if t <= 0.0 || t >= self.duration {
            0.0
        } else if t < self.t_acc {
            self.acc * t
        } else if t <= self.duration - self.t_acc {
            self.v_peak
        } else {
            self.acc * (self.duration - t)
        }
    }
}

/// A usable limit: finite and positive; `None` for "unbounded" (infinite). NaN and
/// non-positive values count as unbounded too, so callers must validate their inputs first.
fn sane_limit(x: f64) -> Option<f64> {
    (x.is_finite() && x > 0.0).then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_shape(p: &Trapezoid) {
        let n = 2000;
        let mut prev = 0.0;
        for i in 0..=n {
            let t = p.duration() * f64::from(i) / f64::from(n);
            let s = p.position(t);
            assert!(s + 1e-12 >= prev, "monotonic");
            assert!(p.velocity(t) <= p.peak_speed() + 1e-12);
            prev = s;
        }
        assert!((p.position(p.duration()) - 1.0).abs() < 1e-12);
        // Continuity at the ramp ends.
        let e = 1e-9;
        for t in [p.ramp_time(), p.duration() - p.ramp_time()] {
            assert!((p.position(t - e) - p.position(t + e)).abs() < 1e-6);
        }
    }

    #[test]
    fn fastest_reaches_cruise() {
        let p = Trapezoid::fastest(2.0, 20.0);
        assert!((p.ramp_time() - 0.1).abs() < 1e-12);
        assert!((p.duration() - 0.6).abs() < 1e-12);
        assert!((p.velocity(0.3) - 2.0).abs() < 1e-12);
        check_shape(&p);
    }

    #[test]
    fn fastest_triangle() {
        let p = Trapezoid::fastest(100.0, 4.0);
        assert!((p.duration() - 1.0).abs() < 1e-12);
        assert!((p.position(0.5) - 0.5).abs() < 1e-12);
        check_shape(&p);
    }

    #[test]
    fn stretched_keeps_acceleration() {
        let fast = Trapezoid::fastest(2.0, 20.0);
        let slow = Trapezoid::with_duration(2.0, 20.0);
        assert!((slow.acceleration() - 20.0).abs() < 1e-9);
        assert!(slow.peak_speed() < fast.peak_speed());
        check_shape(&slow);
        // Too short: falls back to the fastest triangle.
        let t = Trapezoid::with_duration(0.1, 4.0);
        assert!((t.duration() - 1.0).abs() < 1e-12);
        // No acceleration limit: constant speed.
        let c = Trapezoid::with_duration(4.0, f64::INFINITY);
        assert!((c.position(1.0) - 0.25).abs() < 1e-12);
    }

    #[test]
    fn degenerate_inputs() {
        assert_eq!(
            Trapezoid::fastest(f64::INFINITY, f64::INFINITY),
            Trapezoid::INSTANT
        );
        assert_eq!(Trapezoid::with_duration(f64::NAN, 1.0), Trapezoid::INSTANT);
        assert_eq!(Trapezoid::INSTANT.position(0.0), 1.0);
        assert_eq!(Trapezoid::INSTANT.position(1.0), 1.0);
        let c = Trapezoid::fastest(0.5, f64::INFINITY);
        assert!((c.duration() - 2.0).abs() < 1e-12);
    }
}
