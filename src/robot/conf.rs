//! ABB `confdata [cf1, cf4, cf6, cfx]`: quarter revolutions of axes 1, 4, 6 and the arm
//! configuration number, computed exactly as docs/robot.md, "Configuration", describes.

use std::fmt;

use super::JointsDeg;
use super::singularity::SingularityFactors;

/// A robot configuration as in a RAPID `robtarget`'s `robconf`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct ConfData {
    /// Quarter revolution of axis 1.
    pub cf1: i32,
    /// Quarter revolution of axis 4.
    pub cf4: i32,
    /// Quarter revolution of axis 6.
    pub cf6: i32,
    /// Arm configuration 0…7 (docs/robot.md, "Configuration"):
    /// `4·[wrist centre behind axis 1] + 2·[wrist centre behind the lower arm] + [axis 5 < 0]`.
    pub cfx: i32,
}

impl ConfData {
    /// `[cf1, cf4, cf6, cfx]`.
    pub const fn new(cf1: i32, cf4: i32, cf6: i32, cfx: i32) -> ConfData {
        ConfData { cf1, cf4, cf6, cfx }
    }

    /// As the RAPID array `[cf1, cf4, cf6, cfx]`.
    pub const fn to_array(self) -> [i32; 4] {
        [self.cf1, self.cf4, self.cf6, self.cfx]
    }

    /// From the RAPID array `[cf1, cf4, cf6, cfx]`.
    pub const fn from_array(a: [i32; 4]) -> ConfData {
        ConfData::new(a[0], a[1], a[2], a[3])
    }
}

impl fmt::Display for ConfData {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{},{},{},{}]", self.cf1, self.cf4, self.cf6, self.cfx)
    }
}

/// Snap distance (deg) for the quarter rule: an angle within this of a multiple of 90° is
/// treated as exactly that multiple, so IK float noise (~1e-12°) around −90°, −180°, … cannot
/// flip the quadrant. 1e-6° is far below anything a robot or a robtarget resolves (a 9-digit
/// RAPID quaternion resolves ~1e-7 rad ≈ 6e-6°) and far above f64 noise.
pub const CONF_SNAP_EPS_DEG: f64 = 1e-6;

/// How far (deg) outside the programmed quadrant an IK solution of axis 1, 4 or 6 may lie and
/// still count as the programmed configuration under ConfJ\On (docs/robot.md, "Configuration checks"). Exactly matching
/// solutions always win; this slack only absorbs targets taught right at a quadrant boundary
/// whose stored orientation was rounded (e.g. axis 6 taught at −0.001° gives cf6 = −1, but the
/// rounded quaternion solves to +0.0004°). ABB does not publish its tolerance.
pub const CONF_QUADRANT_SLACK_DEG: f64 = 0.5;

/// The quarter-revolution rule of RRM p.153 (docs/robot.md, "Configuration"), `θ` in degrees:
/// `trunc(θ/90)` for θ ≥ 0 and `trunc(θ/90 − 1)` for θ < 0. At exact negative multiples of 90°
/// this is one less than `floor(θ/90)` (−90° → −2, −180° → −3). Angles within
/// [`CONF_SNAP_EPS_DEG`] of a multiple of 90° are snapped onto it first. Non-finite input gives
/// 0 (callers reject such joints before).
pub fn quarter(theta_deg: f64) -> i32 {
    if !theta_deg.is_finite() {
        return 0;
    }
    let q = theta_deg / 90.0;
    let nearest = q.round();
    let q = if ((q - nearest) * 90.0).abs() <= CONF_SNAP_EPS_DEG {
        nearest
    } else {
        q
    };
    let cf = if q >= 0.0 {
        q.trunc()
    } else {
        (q - 1.0).trunc()
    };
    // Axis values are bounded by the limits (±400°), so this never saturates in practice.
    cf as i32
}

/// The closed range of angles (deg) whose quarter is `cf` (boundaries included).
pub fn quadrant_range(cf: i32) -> (f64, f64) {
    // cf ≥ 0 covers [90·cf, 90·cf + 90); cf < 0 covers (90·cf, 90·cf + 90] except that cf = −1
    // stops short of 0. Closed on both ends here: the boundaries belong to either side.
    let lo = f64::from(cf) * 90.0;
    (lo, lo + 90.0)
}

/// Distance (deg) from `theta` to the quadrant `cf` (0 inside).
pub fn quadrant_distance(theta_deg: f64, cf: i32) -> f64 {
    let (lo, hi) = quadrant_range(cf);
    if theta_deg < lo {
        lo - theta_deg
    } else if theta_deg > hi {
        theta_deg - hi
    } else {
        0.0
    }
}

/// A shoulder factor |r| at most this (mm) counts as zero for the cfx bit.
pub const CFX_ZERO_SHOULDER_MM: f64 = 1e-6;
/// An elbow factor |sin(q3m + ψ3)| at most this counts as zero for the cfx bit.
pub const CFX_ZERO_ELBOW_SIN: f64 = 1e-12;
/// Axis 5 within this (deg) of 0° counts as zero for the cfx bit.
pub const CFX_ZERO_WRIST_DEG: f64 = CONF_SNAP_EPS_DEG;

/// The arm configuration number from the three det-J factors (docs/robot.md, "Configuration"). A factor of
/// zero — within [`CFX_ZERO_SHOULDER_MM`], [`CFX_ZERO_ELBOW_SIN`], [`CFX_ZERO_WRIST_DEG`], i.e.
/// exactly on the singularity up to float noise — counts as positive ("in front of" /
/// "axis 5 positive").
pub fn cfx_of(f: &SingularityFactors) -> i32 {
    let [s, e, w] = cfx_bits(f);
    4 * i32::from(s) + 2 * i32::from(e) + i32::from(w)
}

/// The three cfx bits (shoulder, elbow, wrist), `true` = negative factor.
fn cfx_bits(f: &SingularityFactors) -> [bool; 3] {
    [
        f.shoulder_mm < -CFX_ZERO_SHOULDER_MM,
        f.elbow_sin < -CFX_ZERO_ELBOW_SIN,
        f.wrist_deg < -CFX_ZERO_WRIST_DEG,
    ]
}

/// True when factors `f` are in arm configuration `cfx`, where a factor that is zero (within
/// the tolerances above) matches either value of its bit: on a singularity both
/// configurations meet.
pub fn cfx_compatible(f: &SingularityFactors, cfx: i32) -> bool {
    if !(0..8).contains(&cfx) {
        return false;
    }
    let want = [cfx & 4 != 0, cfx & 2 != 0, cfx & 1 != 0];
    let zero = [
        f.shoulder_mm.abs() <= CFX_ZERO_SHOULDER_MM,
        f.elbow_sin.abs() <= CFX_ZERO_ELBOW_SIN,
        f.wrist_deg.abs() <= CFX_ZERO_WRIST_DEG,
    ];
    let have = cfx_bits(f);
    (0..3).all(|i| zero[i] || have[i] == want[i])
}

/// confdata of a joint vector whose singularity factors are `f`.
pub fn conf_from(q: &JointsDeg, f: &SingularityFactors) -> ConfData {
    ConfData {
        cf1: quarter(q[0]),
        cf4: quarter(q[3]),
        cf6: quarter(q[5]),
        cfx: cfx_of(f),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_rule_examples() {
        // docs/robot.md, "Configuration".
        assert_eq!(quarter(83.5), 0);
        assert_eq!(quarter(0.103), 0);
        assert_eq!(quarter(-0.136), -1);
        assert_eq!(quarter(90.0), 1);
        assert_eq!(quarter(180.0), 2);
        assert_eq!(quarter(-90.0), -2);
        assert_eq!(quarter(-180.0), -3);
        assert_eq!(quarter(0.0), 0);
        assert_eq!(quarter(-0.0), 0);
        assert_eq!(quarter(-89.9), -1);
        assert_eq!(quarter(-90.1), -2);
        assert_eq!(quarter(359.9), 3);
        assert_eq!(quarter(-359.9), -4);
        assert_eq!(quarter(400.0), 4);
        assert_eq!(quarter(f64::NAN), 0);
    }

    #[test]
    fn quarter_snaps_float_noise() {
        assert_eq!(quarter(-180.0 + 1e-10), -3);
        assert_eq!(quarter(-180.0 - 1e-10), -3);
        assert_eq!(quarter(-90.0 + 1e-9), -2);
        assert_eq!(quarter(90.0 - 1e-9), 1);
        assert_eq!(quarter(-1e-12), 0);
        // Beyond the snap distance the rule applies as is.
        assert_eq!(quarter(-180.0 + 1e-4), -2);
        assert_eq!(quarter(-1e-4), -1);
    }

    #[test]
    fn quadrant_ranges_agree_with_the_rule() {
        for cf in -5..5 {
            let (lo, hi) = quadrant_range(cf);
            assert_eq!(hi - lo, 90.0);
            assert_eq!(quarter((lo + hi) / 2.0), cf);
        }
        assert_eq!(quadrant_distance(-0.2, 0), 0.2);
        assert_eq!(quadrant_distance(10.0, 0), 0.0);
        assert_eq!(quadrant_distance(-95.0, -1), 5.0);
    }

    #[test]
    fn cfx_table() {
        // docs/robot.md, "Configuration", all eight rows.
        let f = |s: f64, e: f64, w: f64| SingularityFactors {
            shoulder_mm: s,
            elbow_sin: e,
            wrist_deg: w,
        };
        let rows = [
            (f(1.0, 0.5, 10.0), 0),
            (f(1.0, 0.5, -10.0), 1),
            (f(1.0, -0.5, 10.0), 2),
            (f(1.0, -0.5, -10.0), 3),
            (f(-1.0, 0.5, 10.0), 4),
            (f(-1.0, 0.5, -10.0), 5),
            (f(-1.0, -0.5, 10.0), 6),
            (f(-1.0, -0.5, -10.0), 7),
            (f(0.0, 0.0, 0.0), 0),
        ];
        for (factors, cfx) in rows {
            assert_eq!(cfx_of(&factors), cfx, "{factors:?}");
            assert!(cfx_compatible(&factors, cfx));
        }
        // On the wrist singularity both wrist configurations match; elsewhere only one.
        let singular = f(1.0, 0.5, -1e-9);
        assert_eq!(cfx_of(&singular), 0);
        assert!(cfx_compatible(&singular, 0) && cfx_compatible(&singular, 1));
        assert!(!cfx_compatible(&singular, 2));
        assert!(!cfx_compatible(&f(1.0, 0.5, 10.0), 1));
        assert!(!cfx_compatible(&f(1.0, 0.5, 10.0), 8));
        assert!(!cfx_compatible(&f(1.0, 0.5, 10.0), -1));
    }
}
