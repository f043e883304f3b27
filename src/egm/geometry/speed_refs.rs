//! Cartesian speed references (`EgmSensor.speedRef.cartesians`) to joint speeds through a numerical TCP Jacobian, supervised near singularities.
//!
//! The Jacobian is built by central differences of the robot's own forward kinematics (the
//! same FK the rest of rapidvc uses, tool included), not by rs-opw's `jacobian` module, which
//! differentiates the bare flange in metres and radians: here every column is directly in
//! mm/deg and deg/deg of the TCP, expressed along the axes of the correction frame. Twelve FK
//! evaluations and one 6×6 LU on the stack, no allocation.

use nalgebra::{Matrix6, UnitQuaternion, Vector6};

use super::{DIRECTIONS, GuidanceError};
use crate::robot::units::rad_to_deg;
use crate::robot::{JointsDeg, Pose, Robot, SingularityKind};

/// Central-difference step (degrees): its truncation error (∝ h²) and rounding error
/// (∝ 1/h) are both far below 1e-6 of a column for arms of a few metres.
const JACOBIAN_STEP_DEG: f64 = 1e-3;

/// Joint speeds (deg/s) for a Cartesian speed reference, and why they were limited, if so.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpeedRef {
    /// Joint speeds, degrees/s, axis 1 first.
    pub joints: JointsDeg,
    /// Set when the speeds are not the exact solution.
    pub limit: Option<SpeedRefLimit>,
}

/// Why a speed reference was zeroed or scaled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SpeedRefLimit {
    /// The joints are close to a singularity (default thresholds): the speed reference is
    /// zero (the position reference still acts).
    Singularity(SingularityKind),
    /// The Jacobian could not be inverted (numerically singular): zero.
    IllConditioned,
    /// Some joint would exceed its maximum speed: every joint was scaled by `factor` (< 1),
    /// keeping the direction of motion. `joint` is the 1-based axis that set the factor.
    JointSpeed {
        /// Axis number, 1-based.
        joint: usize,
        /// The common scale factor.
        factor: f64,
    },
}

/// The 6×6 Jacobian of the TCP (`flange · tframe`) at joints `q`, expressed along the axes of
/// `frame` (a rotation from world, e.g. the correction frame's): rows x, y, z in mm per degree
/// and rx, ry, rz (angular velocity components) in degrees per degree; column j is axis j+1.
///
/// Error: [`GuidanceError::Kinematics`] with `NotFinite` when `q` is not finite.
pub fn tcp_jacobian(
    robot: &Robot,
    q: &JointsDeg,
    tframe: &Pose,
    frame: &UnitQuaternion<f64>,
) -> Result<Matrix6<f64>, GuidanceError> {
    robot.try_fk(q)?;
    let inv = frame.inverse();
    let h = JACOBIAN_STEP_DEG;
    let mut j = Matrix6::zeros();
    for (axis, mut col) in j.column_iter_mut().enumerate() {
        let mut plus = *q;
        let mut minus = *q;
        if let (Some(p), Some(m)) = (plus.get_mut(axis), minus.get_mut(axis)) {
            *p += h;
            *m -= h;
        }
        let a = robot.fk(&plus) * tframe;
        let b = robot.fk(&minus) * tframe;
        let dp = inv * (a.translation.vector - b.translation.vector) / (2.0 * h);
        let dr = inv * (a.rotation * b.rotation.inverse()).scaled_axis() / (2.0 * h);
        let v = [
            dp.x,
            dp.y,
            dp.z,
            rad_to_deg(dr.x),
            rad_to_deg(dr.y),
            rad_to_deg(dr.z),
        ];
        for (c, x) in col.iter_mut().zip(v) {
            *c = x;
        }
    }
    if j.iter().all(|v| v.is_finite()) {
        Ok(j)
    } else {
        Err(GuidanceError::NotFinite { what: "Jacobian" })
    }
}

/// Joint speeds (deg/s) that move the TCP of `tframe` at `cartesian` = [vx, vy, vz (mm/s),
/// ωx, ωy, ωz (deg/s)] along the axes of `frame`, at joints `q`.
///
/// * An all-zero reference gives zero speeds without any computation.
/// * Close to a singularity ([`Robot::near_singularity`]) the result is zero with
///   [`SpeedRefLimit::Singularity`]; a Jacobian LU cannot solve gives zero with
///   [`SpeedRefLimit::IllConditioned`].
/// * When a joint would exceed the model's maximum axis speed, all joints are scaled by the
///   same factor ([`SpeedRefLimit::JointSpeed`]).
///
/// Errors: [`GuidanceError::NotFinite`] for a non-finite reference,
/// [`GuidanceError::Kinematics`] for non-finite joints.
pub fn joint_speed_ref(
    robot: &Robot,
    q: &JointsDeg,
    tframe: &Pose,
    frame: &UnitQuaternion<f64>,
    cartesian: &[f64; DIRECTIONS],
) -> Result<SpeedRef, GuidanceError> {
    if !cartesian.iter().all(|v| v.is_finite()) {
        return Err(GuidanceError::NotFinite {
            what: "speed reference",
        });
    }
    robot.try_fk(q)?;
    let zero = |limit| SpeedRef {
        joints: [0.0; DIRECTIONS],
        limit,
    };
    if cartesian.iter().all(|v| *v == 0.0) {
        return Ok(zero(None));
    }
    if let Some(kind) = robot.near_singularity(q) {
        return Ok(zero(Some(SpeedRefLimit::Singularity(kind))));
    }
    let j = tcp_jacobian(robot, q, tframe, frame)?;
    let rhs = Vector6::from_column_slice(cartesian);
    let Some(sol) = j.lu().solve(&rhs) else {
        return Ok(zero(Some(SpeedRefLimit::IllConditioned)));
    };
    if !sol.iter().all(|v| v.is_finite()) {
        return Ok(zero(Some(SpeedRefLimit::IllConditioned)));
    }
    let mut joints = [0.0; DIRECTIONS];
    for (o, s) in joints.iter_mut().zip(sol.iter()) {
        *o = *s;
    }
    // The largest ratio of requested to maximum axis speed.
    let worst = joints
        .iter()
        .zip(&robot.model().max_speed)
        .enumerate()
        .map(|(i, (v, max))| (i, v.abs() / max))
        .max_by(|a, b| a.1.total_cmp(&b.1));
    let limit = match worst {
        Some((i, ratio)) if ratio > 1.0 => {
            let factor = 1.0 / ratio;
            for v in &mut joints {
                *v *= factor;
            }
            Some(SpeedRefLimit::JointSpeed {
                joint: i + 1,
                factor,
            })
        }
        _ => None,
    };
    Ok(SpeedRef { joints, limit })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::panic)]

    use super::*;
    use crate::robot::KinError;
    use crate::robot::units::pose_from_pos_quat;

    const Q: JointsDeg = [20.0, 10.0, 5.0, 30.0, 50.0, -40.0];

    fn tframe() -> Pose {
        pose_from_pos_quat([12.3, -0.1, 416.1], [0.9039, -0.0032, 0.4277, 0.0077])
    }

    #[test]
    fn jacobian_predicts_small_motions() {
        let r = Robot::default();
        let frame = UnitQuaternion::from_euler_angles(0.3, -0.2, 1.0);
        let j = tcp_jacobian(&r, &Q, &tframe(), &frame).unwrap();
        let dq = [0.01, -0.02, 0.015, 0.03, -0.01, 0.02];
        let mut q2 = Q;
        for (a, d) in q2.iter_mut().zip(&dq) {
            *a += d;
        }
        let a = r.fk(&Q) * tframe();
        let b = r.fk(&q2) * tframe();
        let inv = frame.inverse();
        let dp = inv * (b.translation.vector - a.translation.vector);
        let dr = inv * (b.rotation * a.rotation.inverse()).scaled_axis();
        let pred = j * Vector6::from_column_slice(&dq);
        let got = [
            dp.x,
            dp.y,
            dp.z,
            dr.x.to_degrees(),
            dr.y.to_degrees(),
            dr.z.to_degrees(),
        ];
        for (p, g) in pred.iter().zip(&got) {
            assert!((p - g).abs() < 1e-3, "{pred} vs {got:?}");
        }
        // Axis 1 turns everything about world z: its rotation column is (0, 0, 1) in world.
        let jw = tcp_jacobian(&r, &Q, &tframe(), &UnitQuaternion::identity()).unwrap();
        assert!((jw[(5, 0)] - 1.0).abs() < 1e-9 && jw[(3, 0)].abs() < 1e-9);
        assert!(tcp_jacobian(&r, &[f64::NAN; 6], &tframe(), &frame).is_err());
    }

    #[test]
    fn speed_ref_reproduces_the_cartesian_speed() {
        let r = Robot::default();
        let frame = UnitQuaternion::identity();
        let v = [50.0, -20.0, 10.0, 2.0, 0.0, -3.0];
        let s = joint_speed_ref(&r, &Q, &tframe(), &frame, &v).unwrap();
        assert_eq!(s.limit, None);
        let j = tcp_jacobian(&r, &Q, &tframe(), &frame).unwrap();
        let back = j * Vector6::from_column_slice(&s.joints);
        for (a, b) in back.iter().zip(&v) {
            assert!((a - b).abs() < 1e-6, "{back}");
        }
        // Moving the TCP straight up with a fixed orientation moves the wrist centre straight
        // up too, so its azimuth (axis 1) does not change.
        let s =
            joint_speed_ref(&r, &Q, &tframe(), &frame, &[0.0, 0.0, 10.0, 0.0, 0.0, 0.0]).unwrap();
        assert!(s.joints[0].abs() < 1e-9, "{:?}", s.joints);
    }

    #[test]
    fn limits_and_errors() {
        let r = Robot::default();
        let frame = UnitQuaternion::identity();
        let zero = joint_speed_ref(&r, &Q, &tframe(), &frame, &[0.0; 6]).unwrap();
        assert_eq!(zero.joints, [0.0; 6]);
        assert_eq!(zero.limit, None);
        let wrist = [20.0, 10.0, 5.0, 30.0, 0.5, -40.0];
        let s = joint_speed_ref(
            &r,
            &wrist,
            &tframe(),
            &frame,
            &[10.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        )
        .unwrap();
        assert_eq!(s.joints, [0.0; 6]);
        assert_eq!(
            s.limit,
            Some(SpeedRefLimit::Singularity(SingularityKind::Wrist))
        );
        // 10 m/s is far beyond the axes: scaled so the fastest axis is at its maximum.
        let s = joint_speed_ref(
            &r,
            &Q,
            &tframe(),
            &frame,
            &[10000.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        )
        .unwrap();
        match s.limit {
            Some(SpeedRefLimit::JointSpeed { joint, factor }) => {
                assert!(factor < 1.0);
                let max = r.model().max_speed[joint - 1];
                assert!((s.joints[joint - 1].abs() - max).abs() < 1e-9);
                for (v, m) in s.joints.iter().zip(&r.model().max_speed) {
                    assert!(v.abs() <= m + 1e-9);
                }
            }
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            joint_speed_ref(
                &r,
                &Q,
                &tframe(),
                &frame,
                &[f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0]
            ),
            Err(GuidanceError::NotFinite { .. })
        ));
        assert_eq!(
            joint_speed_ref(&r, &[f64::NAN; 6], &tframe(), &frame, &[1.0; 6]),
            Err(GuidanceError::Kinematics(KinError::NotFinite))
        );
    }
}
