//! Trapezoidal velocity profiles of a normalised path parameter `s ∈ [0, 1]` (docs/robot.md, "Profiles and acceleration":
//! trapezoidal, triangular when the move is short).
//!
//! Every move is a geometric path `s ↦ pose/joints` plus one of these time laws, so all axes of
//! a joint move arrive together and a linear move keeps its shape while speeding up. The ramps
//! may be stretched to cover a minimum share of the path: a fly-by point decelerates over its
//! whole zone, so that the corner path (the superposition of this ramp-down and the next move's
//! ramp-up) fills the zone at speed instead of stopping.

/// Limits of one profile, all in normalised units (path fractions per second, per second²).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProfileLimits {
    /// Maximum path speed `ṡ` (infinite: unbounded).
    pub v_max: f64,
    /// Maximum path acceleration `|s̈|` (infinite: unbounded).
    pub a_max: f64,
    /// The ramp-up covers at least this share of the path (0…0.5).
    pub ramp_in: f64,
    /// The ramp-down covers at least this share of the path (0…0.5).
    pub ramp_out: f64,
}

impl ProfileLimits {
    /// Speed and acceleration limits with the shortest possible ramps.
    pub fn new(v_max: f64, a_max: f64) -> ProfileLimits {
        ProfileLimits {
            v_max,
            a_max,
            ramp_in: 0.0,
            ramp_out: 0.0,
        }
    }
}

/// A time law `t ↦ s(t)` from rest at `s = 0` to rest at `s = 1`: constant acceleration for
/// `t_up`, cruise at `v_peak`, constant deceleration for `t_down`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Profile {
    v_peak: f64,
    /// Path share covered while accelerating / decelerating.
    d_up: f64,
    d_down: f64,
    t_up: f64,
    t_cruise: f64,
    t_down: f64,
}

impl Profile {
    /// A profile that takes no time (a move that goes nowhere).
    pub const INSTANT: Profile = Profile {
        v_peak: 0.0,
        d_up: 0.0,
        d_down: 0.0,
        t_up: 0.0,
        t_cruise: 0.0,
        t_down: 0.0,
    };

    /// The fastest profile within `limits`. Limits that are not finite and positive count as
    /// unbounded; with both speed and acceleration unbounded the result is [`Self::INSTANT`].
    pub fn fastest(limits: &ProfileLimits) -> Profile {
        match top_speed(limits) {
            Some(v) => Profile::at_speed(v, limits),
            None => Profile::INSTANT,
        }
    }

    /// A profile lasting `duration` seconds (or the fastest one, if that is slower): the
    /// highest ramp acceleration allowed and the slowest cruise that fits.
    pub fn with_duration(duration: f64, limits: &ProfileLimits) -> Profile {
        let fastest = Profile::fastest(limits);
        if !(duration.is_finite() && duration > fastest.duration()) {
            return fastest;
        }
        let v_top = if fastest.v_peak > 0.0 {
            fastest.v_peak
        } else {
            // Unbounded limits: any speed is allowed.
            f64::MAX
        };
        // duration(v) = (1 + d_up(v) + d_down(v)) / v is strictly decreasing on (0, v_top], so
        // bisect for v. 200 halvings reach the f64 resolution from any start.
        let (mut lo, mut hi) = (0.0_f64, v_top.min(3.0 / duration));
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if Profile::at_speed(mid, limits).duration() > duration {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Profile::at_speed(hi, limits)
    }

    /// The profile cruising at `v` (which must not exceed the top speed of `limits`).
    fn at_speed(v: f64, limits: &ProfileLimits) -> Profile {
        if !(v.is_finite() && v > 0.0) {
            return Profile::INSTANT;
        }
        let natural = match bounded(limits.a_max) {
            Some(a) => v * v / (2.0 * a),
            None => 0.0,
        };
        let d_up = natural.max(clamp_share(limits.ramp_in));
        let d_down = natural.max(clamp_share(limits.ramp_out));
        let cruise = (1.0 - d_up - d_down).max(0.0);
        Profile {
            v_peak: v,
            d_up,
            d_down,
            t_up: 2.0 * d_up / v,
            t_cruise: cruise / v,
            t_down: 2.0 * d_down / v,
        }
    }

    /// Total duration in seconds.
    pub fn duration(&self) -> f64 {
        self.t_up + self.t_cruise + self.t_down
    }

    /// Duration of the ramp-up in seconds.
    pub fn ramp_up_time(&self) -> f64 {
        self.t_up
    }

    /// Duration of the ramp-down in seconds.
    pub fn ramp_down_time(&self) -> f64 {
        self.t_down
    }

    /// Peak (cruise) path speed in path fractions per second.
    pub fn peak_speed(&self) -> f64 {
        self.v_peak
    }

    /// `s(t)`, clamped to `[0, 1]`; a zero-length profile is at 1 for every `t > 0`.
    pub fn position(&self, t: f64) -> f64 {
        let total = self.duration();
        if total <= 0.0 {
            return if t > 0.0 { 1.0 } else { 0.0 };
        }
        if t <= 0.0 {
            return 0.0;
        }
        if t >= total {
            return 1.0;
        }
        let s = if t < self.t_up {
            0.5 * self.v_peak / self.t_up * t * t
        } else if t <= self.t_up + self.t_cruise {
            self.d_up + self.v_peak * (t - self.t_up)
        } else {
            let r = total - t;
            1.0 - 0.5 * self.v_peak / self.t_down * r * r
        };
        s.clamp(0.0, 1.0)
    }

    /// `ṡ(t)` (zero outside the profile).
    pub fn velocity(&self, t: f64) -> f64 {
        let total = self.duration();
        if t <= 0.0 || t >= total {
            0.0
        } else if t < self.t_up {
            self.v_peak * t / self.t_up
        } else if t <= self.t_up + self.t_cruise {
            self.v_peak
        } else {
            self.v_peak * (total - t) / self.t_down
        }
    }
}

/// The highest cruise speed the limits allow (the ramps never overlap because each covers at
/// most half the path): `min(v_max, √a_max)`. `None` when both are unbounded.
fn top_speed(limits: &ProfileLimits) -> Option<f64> {
    match (bounded(limits.v_max), bounded(limits.a_max)) {
        (None, None) => None,
        (Some(v), None) => Some(v),
        (None, Some(a)) => Some(a.sqrt()),
        (Some(v), Some(a)) => Some(v.min(a.sqrt())),
    }
}

/// A usable limit: finite and positive; `None` means unbounded. Callers validate user data
/// (NaN, negative speeds) before building limits.
fn bounded(x: f64) -> Option<f64> {
    (x.is_finite() && x > 0.0).then_some(x)
}

fn clamp_share(x: f64) -> f64 {
    if x.is_finite() {
        x.clamp(0.0, 0.5)
    } else {
        0.0
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]
mod tests {
    use super::*;

    fn check_shape(p: &Profile) {
        let n = 4000;
        let mut prev = 0.0;
        for i in 0..=n {
            let t = p.duration() * f64::from(i) / f64::from(n);
            let s = p.position(t);
            assert!(s + 1e-12 >= prev, "monotonic");
            assert!(p.velocity(t) <= p.peak_speed() + 1e-12);
            prev = s;
        }
        assert!((p.position(p.duration()) - 1.0).abs() < 1e-12);
        let e = 1e-9;
        for t in [p.ramp_up_time(), p.duration() - p.ramp_down_time()] {
            assert!((p.position(t - e) - p.position(t + e)).abs() < 1e-6);
        }
    }

    #[test]
    fn fastest_reaches_cruise() {
        let p = Profile::fastest(&ProfileLimits::new(2.0, 20.0));
        assert!((p.ramp_up_time() - 0.1).abs() < 1e-12);
        assert!((p.duration() - 0.6).abs() < 1e-12);
        assert!((p.velocity(0.3) - 2.0).abs() < 1e-12);
        check_shape(&p);
    }

    #[test]
    fn fastest_triangle() {
        let p = Profile::fastest(&ProfileLimits::new(100.0, 4.0));
        assert!((p.duration() - 1.0).abs() < 1e-12);
        assert!((p.position(0.5) - 0.5).abs() < 1e-12);
        check_shape(&p);
    }

    #[test]
    fn stretched_ramps_cover_the_zone() {
        let limits = ProfileLimits {
            v_max: 2.0,
            a_max: 20.0,
            ramp_in: 0.0,
            ramp_out: 0.3,
        };
        let p = Profile::fastest(&limits);
        // The ramp-down covers 30 % of the path at the same peak speed.
        assert!((p.peak_speed() - 2.0).abs() < 1e-12);
        assert!((p.ramp_down_time() - 0.3).abs() < 1e-12);
        assert!((p.position(p.duration() - p.ramp_down_time()) - 0.7).abs() < 1e-12);
        check_shape(&p);
    }

    #[test]
    fn with_duration_slows_down() {
        let limits = ProfileLimits::new(2.0, 20.0);
        let slow = Profile::with_duration(2.0, &limits);
        assert!((slow.duration() - 2.0).abs() < 1e-9);
        assert!(slow.peak_speed() < 2.0);
        check_shape(&slow);
        // Shorter than possible: the fastest profile.
        let fast = Profile::with_duration(0.1, &limits);
        assert_eq!(fast, Profile::fastest(&limits));
        // No acceleration limit: constant speed.
        let c = Profile::with_duration(4.0, &ProfileLimits::new(f64::INFINITY, f64::INFINITY));
        assert!((c.position(1.0) - 0.25).abs() < 1e-9);
    }

    #[test]
    fn degenerate_inputs() {
        let none = ProfileLimits::new(f64::INFINITY, f64::INFINITY);
        assert_eq!(Profile::fastest(&none), Profile::INSTANT);
        assert_eq!(Profile::INSTANT.position(0.0), 0.0);
        assert_eq!(Profile::INSTANT.position(0.004), 1.0);
        let c = Profile::fastest(&ProfileLimits::new(0.5, f64::INFINITY));
        assert!((c.duration() - 2.0).abs() < 1e-12);
        let nan = ProfileLimits {
            ramp_in: f64::NAN,
            ..ProfileLimits::new(1.0, 1.0)
        };
        check_shape(&Profile::fastest(&nan));
    }
}
