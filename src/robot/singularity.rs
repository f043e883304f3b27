//! Singularity factors of an OPW arm (the three factors of det J, docs/robot.md, "Singularities") and the
//! "close to singularity" detectors built on them.
//!
//! For b = 0, `|det J| = |r · c2 · k · sin(q3m + ψ3) · sin J5|` with
//! `r = a1 + c2·sin J2 + k·sin(J2 + q3m + ψ3)` (the radial distance of the wrist centre from
//! axis 1), `q3m = J3 + 90°`, `k = √(a2² + c3²)`, `ψ3 = atan2(a2, c3)`.

use std::fmt;

use super::JointsDeg;
use super::model::OpwParams;
use super::units::{deg_to_rad, m_to_mm, rad_to_deg};

/// The signed det-J factors of one joint vector. Their signs are the cfx bits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SingularityFactors {
    /// r: signed radial distance (mm) of the wrist centre from axis 1; positive in front.
    pub shoulder_mm: f64,
    /// sin(q3m + ψ3): 0 with the arm fully stretched or folded; positive when the wrist
    /// centre is in front of the lower arm.
    pub elbow_sin: f64,
    /// Axis 5 in degrees (the wrist is singular where sin J5 = 0).
    pub wrist_deg: f64,
}

impl SingularityFactors {
    /// The factors of `q` (ABB axis values, degrees) on an arm with geometry `p`.
    pub fn of(p: &OpwParams, q: &JointsDeg) -> SingularityFactors {
        let q2 = deg_to_rad(q[1]);
        // q3m = J3 + 90° (the model's −90° offset on axis 3, docs/robot.md, "Axis values").
        let q3m = deg_to_rad(q[2] + 90.0);
        let psi3 = p.psi3();
        let elbow = q3m + psi3;
        let r = p.a1 + p.c2 * q2.sin() + p.k() * (q2 + elbow).sin();
        SingularityFactors {
            shoulder_mm: m_to_mm(r),
            elbow_sin: elbow.sin(),
            wrist_deg: q[4],
        }
    }

    /// Distance (deg) of axis 5 from the nearest wrist singularity (a multiple of 180°).
    pub fn wrist_distance_deg(&self) -> f64 {
        let w = self.wrist_deg.rem_euclid(180.0);
        w.min(180.0 - w)
    }

    /// The elbow angle's distance (deg) from a stretched or folded arm.
    pub fn elbow_distance_deg(&self) -> f64 {
        rad_to_deg(self.elbow_sin.abs().min(1.0).asin())
    }
}

/// Which of the three singularities a pose is close to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SingularityKind {
    /// Wrist centre on axis 1.
    Shoulder,
    /// Arm fully stretched or folded.
    Elbow,
    /// Axes 4 and 6 collinear (axis 5 at 0°).
    Wrist,
}

impl fmt::Display for SingularityKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            SingularityKind::Shoulder => "shoulder singularity (wrist centre on axis 1)",
            SingularityKind::Elbow => "elbow singularity (arm stretched or folded)",
            SingularityKind::Wrist => "wrist singularity (axes 4 and 6 aligned)",
        })
    }
}

/// Thresholds of the "close to singularity" detectors. ABB publishes none; the defaults are:
///
/// * shoulder: wrist centre within [`SHOULDER_THRESHOLD_MM`] = 10 mm of axis 1;
/// * elbow: |sin(q3m + ψ3)| below [`ELBOW_THRESHOLD_SIN`] = 0.01 (≈ 0.57° from stretched);
/// * wrist: axis 5 within [`WRIST_THRESHOLD_DEG`] = 3° of 0° (the ±3° zone one secondary source
///   gives for ABB event 50026).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SingularityThresholds {
    /// Shoulder: minimum |r| in mm.
    pub shoulder_mm: f64,
    /// Elbow: minimum |sin(q3m + ψ3)|.
    pub elbow_sin: f64,
    /// Wrist: minimum distance of axis 5 from 0°/±180°, in degrees.
    pub wrist_deg: f64,
}

/// Default shoulder threshold (mm).
pub const SHOULDER_THRESHOLD_MM: f64 = 10.0;
/// Default elbow threshold (|sin|).
pub const ELBOW_THRESHOLD_SIN: f64 = 0.01;
/// Default wrist threshold (deg).
pub const WRIST_THRESHOLD_DEG: f64 = 3.0;

impl Default for SingularityThresholds {
    fn default() -> Self {
        SingularityThresholds {
            shoulder_mm: SHOULDER_THRESHOLD_MM,
            elbow_sin: ELBOW_THRESHOLD_SIN,
            wrist_deg: WRIST_THRESHOLD_DEG,
        }
    }
}

impl SingularityThresholds {
    /// The singularity the factors are closest to, relative to its threshold, if any is
    /// within its threshold. Non-finite factors count as no singularity (the caller rejects
    /// non-finite joints elsewhere).
    pub fn check(&self, f: &SingularityFactors) -> Option<SingularityKind> {
        let ratios = [
            (
                f.shoulder_mm.abs() / self.shoulder_mm,
                SingularityKind::Shoulder,
            ),
            (f.elbow_sin.abs() / self.elbow_sin, SingularityKind::Elbow),
            (
                f.wrist_distance_deg() / self.wrist_deg,
                SingularityKind::Wrist,
            ),
        ];
        ratios
            .into_iter()
            .filter(|(ratio, _)| *ratio < 1.0)
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, kind)| kind)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const IRB2600_185: OpwParams = OpwParams {
        a1: 0.150,
        a2: -0.115,
        b: 0.0,
        c1: 0.445,
        c2: 0.900,
        c3: 0.795,
        c4: 0.085,
    };

    #[test]
    fn stretched_elbow_of_the_2600() {
        // docs/robot.md, "Singularities": J3 = −90° − ψ3 = −81.77°.
        let j3 = -90.0 - rad_to_deg(IRB2600_185.psi3());
        assert!((j3 - -81.77).abs() < 0.005, "{j3}");
        let f = SingularityFactors::of(&IRB2600_185, &[0.0, 0.0, j3, 0.0, 30.0, 0.0]);
        assert!(f.elbow_sin.abs() < 1e-12);
        assert_eq!(
            SingularityThresholds::default().check(&f),
            Some(SingularityKind::Elbow)
        );
    }

    #[test]
    fn zero_pose_factors() {
        let f = SingularityFactors::of(&IRB2600_185, &[0.0; 6]);
        // r = a1 + k·sin(90° + ψ3) = a1 + c3 = 945 mm.
        assert!((f.shoulder_mm - 945.0).abs() < 1e-9);
        assert!(f.elbow_sin > 0.98);
        assert_eq!(f.wrist_deg, 0.0);
        assert_eq!(
            SingularityThresholds::default().check(&f),
            Some(SingularityKind::Wrist)
        );
        let f = SingularityFactors::of(&IRB2600_185, &[0.0, 0.0, 0.0, 0.0, 40.0, 0.0]);
        assert_eq!(SingularityThresholds::default().check(&f), None);
    }

    #[test]
    fn wrist_distance_wraps() {
        let f = |w| SingularityFactors {
            shoulder_mm: 100.0,
            elbow_sin: 0.5,
            wrist_deg: w,
        };
        assert_eq!(f(-2.0).wrist_distance_deg(), 2.0);
        assert_eq!(f(179.0).wrist_distance_deg(), 1.0);
        assert_eq!(f(90.0).wrist_distance_deg(), 90.0);
        assert!(f(f64::NAN).wrist_distance_deg().is_nan());
        assert_eq!(SingularityThresholds::default().check(&f(f64::NAN)), None);
    }
}
