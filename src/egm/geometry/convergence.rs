//! Pose-mode convergence: the per-direction error "ordered minus actual" in the correction frame and the `egm_minmax` windows of `EGMActPose`.
//!
//! Joint-mode windows live with the servo law (`egm::servo::MinMax`, ±0.5° per joint); this
//! is the pose-mode counterpart, whose errors the motion core passes to the servo as its
//! convergence error vector. [`Convergence::met`] works for any six errors, joint errors
//! included.

use super::{DIRECTIONS, GuidanceError, direction_name};
use crate::robot::Pose;
use crate::robot::units::{pose_is_finite, rad_to_deg};

/// The pose-mode convergence error between the ordered and the actual TCP (both in world),
/// expressed in the correction frame `corr` (world): `[x, y, z]` = ordered − actual position
/// along the axes of `corr` (mm); `[rx, ry, rz]` = the components along the axes of `corr` of
/// the rotation vector of ordered · actualᵀ (degrees), i.e. the rotation that turns the actual
/// orientation into the ordered one. The sign convention is "ordered minus actual"
/// throughout, which matters for asymmetric windows.
///
/// Error: [`GuidanceError::NotFinite`] when any pose is not finite.
pub fn pose_error(
    corr: &Pose,
    ordered: &Pose,
    actual: &Pose,
) -> Result<[f64; DIRECTIONS], GuidanceError> {
    if !(pose_is_finite(corr) && pose_is_finite(ordered) && pose_is_finite(actual)) {
        return Err(GuidanceError::NotFinite {
            what: "convergence pose",
        });
    }
    let inv = corr.rotation.inverse();
    let d = inv * (ordered.translation.vector - actual.translation.vector);
    let r = inv * (ordered.rotation * actual.rotation.inverse()).scaled_axis();
    Ok([
        d.x,
        d.y,
        d.z,
        rad_to_deg(r.x),
        rad_to_deg(r.y),
        rad_to_deg(r.z),
    ])
}

/// The six `egm_minmax` convergence windows `(min, max)` of a pose-mode movement, x, y, z in
/// mm and rx, ry, rz in degrees. A direction has converged when min ≤ ordered − actual ≤ max.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Convergence {
    windows: [(f64, f64); DIRECTIONS],
}

impl Default for Convergence {
    fn default() -> Self {
        Convergence::POSE_DEFAULT
    }
}

impl Convergence {
    /// `EGMActPose`'s defaults: ±1 mm for x, y, z and ±0.5° for rx, ry, rz.
    pub const POSE_DEFAULT: Convergence = Convergence {
        windows: [
            (-1.0, 1.0),
            (-1.0, 1.0),
            (-1.0, 1.0),
            (-0.5, 0.5),
            (-0.5, 0.5),
            (-0.5, 0.5),
        ],
    };

    /// Windows `(min, max)` for x, y, z, rx, ry, rz; each must be finite with min ≤ max
    /// ([`GuidanceError::BadWindow`] otherwise).
    pub fn new(windows: [(f64, f64); DIRECTIONS]) -> Result<Convergence, GuidanceError> {
        for (i, &(min, max)) in windows.iter().enumerate() {
            if !(min.is_finite() && max.is_finite() && min <= max) {
                return Err(GuidanceError::BadWindow {
                    direction: direction_name(i),
                    min,
                    max,
                });
            }
        }
        Ok(Convergence { windows })
    }

    /// The defaults with the windows given as `Some` replaced (the optional `\x … \rz`
    /// arguments of `EGMActPose`).
    pub fn with_overrides(
        overrides: [Option<(f64, f64)>; DIRECTIONS],
    ) -> Result<Convergence, GuidanceError> {
        let mut w = Convergence::POSE_DEFAULT.windows;
        for (slot, o) in w.iter_mut().zip(overrides) {
            if let Some(o) = o {
                *slot = o;
            }
        }
        Convergence::new(w)
    }

    /// The windows `(min, max)`.
    pub fn windows(&self) -> &[(f64, f64); DIRECTIONS] {
        &self.windows
    }

    /// True when every selected direction's error lies in its window (bounds included). A NaN
    /// error never lies in a window. With nothing selected the criteria are trivially met
    /// (no movement, RAPID continues).
    pub fn met(&self, errors: &[f64; DIRECTIONS], selection: &[bool; DIRECTIONS]) -> bool {
        self.windows
            .iter()
            .zip(errors)
            .zip(selection)
            .filter(|(_, sel)| **sel)
            .all(|((&(min, max), &e), _)| e >= min && e <= max)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::panic)]

    use super::*;
    use crate::robot::units::{nan_pose, pose_from_pos_quat, quat_from_euler_zyx_deg};

    #[test]
    fn error_is_ordered_minus_actual_in_the_correction_frame() {
        // F_c: 90° about z, so its x axis is world y and its y axis is world −x.
        let corr = pose_from_pos_quat([100.0, 0.0, 0.0], [1.0, 0.0, 0.0, 1.0]);
        let actual = pose_from_pos_quat([0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]);
        let q = quat_from_euler_zyx_deg(0.0, 0.0, 2.0); // 2° about world z
        let ordered = pose_from_pos_quat([-3.0, 5.0, 1.0], [q.w, q.i, q.j, q.k]);
        let e = pose_error(&corr, &ordered, &actual).unwrap();
        let want = [5.0, 3.0, 1.0, 0.0, 0.0, 2.0];
        for (a, b) in e.iter().zip(&want) {
            assert!((a - b).abs() < 1e-5, "{e:?}");
        }
        // Swapping ordered and actual flips the sign.
        let back = pose_error(&corr, &actual, &ordered).unwrap();
        for (a, b) in e.iter().zip(&back) {
            assert!((a + b).abs() < 1e-9);
        }
        // A rotation about world x is about F_c's −y.
        let q = quat_from_euler_zyx_deg(1.0, 0.0, 0.0);
        let ordered = pose_from_pos_quat([0.0; 3], [q.w, q.i, q.j, q.k]);
        let e = pose_error(&corr, &ordered, &actual).unwrap();
        assert!((e[4] + 1.0).abs() < 1e-5 && e[3].abs() < 1e-5, "{e:?}");
        assert!(pose_error(&corr, &nan_pose(), &actual).is_err());
        assert!(pose_error(&nan_pose(), &actual, &actual).is_err());
    }

    #[test]
    fn windows_with_asymmetric_bounds() {
        let c = Convergence::with_overrides([
            Some((-0.1, 0.2)),
            None,
            None,
            None,
            None,
            Some((0.0, 1.0)),
        ])
        .unwrap();
        let sel = [true; 6];
        assert!(c.met(&[0.15, 0.9, -0.9, 0.4, -0.4, 0.5], &sel));
        // −0.15 is outside [−0.1, 0.2] although |−0.15| < 0.2: the sign matters.
        assert!(!c.met(&[-0.15, 0.0, 0.0, 0.0, 0.0, 0.5], &sel));
        assert!(
            c.met(&[0.2, 1.0, -1.0, 0.5, -0.5, 0.0], &sel),
            "bounds included"
        );
        assert!(!c.met(&[0.0, 0.0, 0.0, 0.0, 0.0, -0.01], &sel));
        // Unselected directions are not checked.
        assert!(c.met(
            &[5.0, 0.0, 0.0, 0.0, 0.0, 0.5],
            &[false, true, true, true, true, true]
        ));
        assert!(c.met(&[f64::NAN; 6], &[false; 6]));
        assert!(!c.met(&[f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.5], &sel));
    }

    #[test]
    fn defaults_and_bad_windows() {
        assert_eq!(Convergence::default(), Convergence::POSE_DEFAULT);
        assert_eq!(Convergence::POSE_DEFAULT.windows()[0], (-1.0, 1.0));
        assert_eq!(Convergence::POSE_DEFAULT.windows()[5], (-0.5, 0.5));
        let mut w = *Convergence::POSE_DEFAULT.windows();
        w[3] = (1.0, -1.0);
        assert_eq!(
            Convergence::new(w),
            Err(GuidanceError::BadWindow {
                direction: "rx",
                min: 1.0,
                max: -1.0
            })
        );
        w[3] = (f64::NEG_INFINITY, 0.0);
        assert!(Convergence::new(w).is_err());
        w[3] = (0.0, f64::NAN);
        assert!(Convergence::new(w).is_err());
    }
}
