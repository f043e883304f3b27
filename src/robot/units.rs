//! Every unit and convention conversion of the crate: degrees ⇄ radians, mm ⇄ m, RAPID/EGM
//! quaternion order ⇄ nalgebra, ZYX Euler angles ⇄ quaternions, nalgebra ⇄ rs-opw's glam types.
//!
//! RAPID and EGM speak millimetres and degrees; rs-opw speaks metres and radians. No other
//! module multiplies by 1000 or calls `to_radians()`: they call these functions.

use nalgebra::{Quaternion, Translation3, UnitQuaternion, Vector3};
use rs_opw_kinematics::glam::{DQuat, DVec3};
use rs_opw_kinematics::kinematic_traits::Pose as OpwPose;

use super::{JointsDeg, Pose};

/// Millimetres per metre.
const MM_PER_M: f64 = 1000.0;

/// Degrees to radians.
#[inline]
pub fn deg_to_rad(deg: f64) -> f64 {
    deg.to_radians()
}

/// Radians to degrees.
#[inline]
pub fn rad_to_deg(rad: f64) -> f64 {
    rad.to_degrees()
}

/// Millimetres to metres.
#[inline]
pub fn mm_to_m(mm: f64) -> f64 {
    mm / MM_PER_M
}

/// Metres to millimetres.
#[inline]
pub fn m_to_mm(m: f64) -> f64 {
    m * MM_PER_M
}

/// Six axis values in degrees to radians.
#[inline]
pub fn joints_deg_to_rad(j: &JointsDeg) -> [f64; 6] {
    j.map(deg_to_rad)
}

/// Six axis values in radians to degrees.
#[inline]
pub fn joints_rad_to_deg(j: &[f64; 6]) -> JointsDeg {
    j.map(rad_to_deg)
}

/// A RAPID `orient` / EGM `EgmQuaternion` `[q1, q2, q3, q4]` = `[w, x, y, z]` as a unit
/// quaternion. The input is normalised; a zero or non-finite input gives a quaternion with NaN
/// components (which every kinematic function rejects as [`super::KinError::NotFinite`]).
pub fn quat_from_wxyz(q: [f64; 4]) -> UnitQuaternion<f64> {
    let raw = Quaternion::new(q[0], q[1], q[2], q[3]);
    let n = raw.norm();
    if n.is_finite() && n > 0.0 {
        UnitQuaternion::new_unchecked(raw / n)
    } else {
        UnitQuaternion::new_unchecked(Quaternion::new(f64::NAN, f64::NAN, f64::NAN, f64::NAN))
    }
}

/// A unit quaternion as RAPID/EGM `[q1, q2, q3, q4]` = `[w, x, y, z]`.
pub fn quat_to_wxyz(q: &UnitQuaternion<f64>) -> [f64; 4] {
    [q.w, q.i, q.j, q.k]
}

/// A pose from a RAPID position `[x, y, z]` (mm) and orientation `[w, x, y, z]`.
pub fn pose_from_pos_quat(pos_mm: [f64; 3], q_wxyz: [f64; 4]) -> Pose {
    Pose::from_parts(
        Translation3::new(pos_mm[0], pos_mm[1], pos_mm[2]),
        quat_from_wxyz(q_wxyz),
    )
}

/// A pose as RAPID position `[x, y, z]` (mm) and orientation `[w, x, y, z]`.
pub fn pose_to_pos_quat(p: &Pose) -> ([f64; 3], [f64; 4]) {
    let t = p.translation.vector;
    ([t.x, t.y, t.z], quat_to_wxyz(&p.rotation))
}

/// EGM/RAPID ZYX Euler angles in degrees to a quaternion: `q = Rz(z)·Ry(y)·Rx(x)`
/// (EGM `EgmEuler {x, y, z}`; RAPID `OrientZYX(z, y, x)` takes the same angles Z first).
pub fn quat_from_euler_zyx_deg(x_deg: f64, y_deg: f64, z_deg: f64) -> UnitQuaternion<f64> {
    // nalgebra's (roll, pitch, yaw) is exactly Rz(yaw)·Ry(pitch)·Rx(roll).
    UnitQuaternion::from_euler_angles(deg_to_rad(x_deg), deg_to_rad(y_deg), deg_to_rad(z_deg))
}

/// A quaternion to ZYX Euler angles `[x, y, z]` in degrees with `q = Rz(z)·Ry(y)·Rx(x)`
/// (y in [−90°, 90°]).
pub fn quat_to_euler_zyx_deg(q: &UnitQuaternion<f64>) -> [f64; 3] {
    let (roll, pitch, yaw) = q.euler_angles();
    [rad_to_deg(roll), rad_to_deg(pitch), rad_to_deg(yaw)]
}

/// A nalgebra unit quaternion to glam.
#[inline]
pub fn quat_to_glam(q: &UnitQuaternion<f64>) -> DQuat {
    DQuat::from_xyzw(q.i, q.j, q.k, q.w)
}

/// A glam quaternion to a nalgebra unit quaternion (normalised; NaN when degenerate).
#[inline]
pub fn quat_from_glam(q: DQuat) -> UnitQuaternion<f64> {
    quat_from_wxyz([q.w, q.x, q.y, q.z])
}

/// A pose in mm to rs-opw's pose in metres. `None` when the pose is not finite (rs-opw panics
/// on such poses, so they never reach it).
pub fn pose_to_opw(p: &Pose) -> Option<OpwPose> {
    let t = p.translation.vector;
    let tr = DVec3::new(mm_to_m(t.x), mm_to_m(t.y), mm_to_m(t.z));
    OpwPose::try_from_parts(tr, quat_to_glam(&p.rotation)).ok()
}

/// rs-opw's pose in metres to a pose in mm.
pub fn pose_from_opw(p: &OpwPose) -> Pose {
    let t = p.translation;
    Pose::from_parts(
        Translation3::from(Vector3::new(m_to_mm(t.x), m_to_mm(t.y), m_to_mm(t.z))),
        quat_from_glam(p.rotation),
    )
}

/// True when every component of the pose (translation and quaternion) is finite.
pub fn pose_is_finite(p: &Pose) -> bool {
    p.translation.vector.iter().all(|v| v.is_finite())
        && p.rotation.coords.iter().all(|v| v.is_finite())
}

/// A pose whose every component is NaN: what [`super::Robot::fk`] returns for non-finite axes.
pub fn nan_pose() -> Pose {
    Pose::from_parts(
        Translation3::new(f64::NAN, f64::NAN, f64::NAN),
        UnitQuaternion::new_unchecked(Quaternion::new(f64::NAN, f64::NAN, f64::NAN, f64::NAN)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_and_lengths() {
        assert!((deg_to_rad(180.0) - std::f64::consts::PI).abs() < 1e-15);
        assert!((rad_to_deg(std::f64::consts::FRAC_PI_2) - 90.0).abs() < 1e-12);
        assert_eq!(mm_to_m(1500.0), 1.5);
        assert_eq!(m_to_mm(0.085), 85.0);
        let j = joints_rad_to_deg(&joints_deg_to_rad(&[1.0, -2.0, 3.0, 400.0, -5.0, 6.0]));
        assert!((j[3] - 400.0).abs() < 1e-12);
    }

    #[test]
    fn quaternion_order_is_w_first() {
        let q = quat_from_wxyz([0.7, 0.0, 0.7, 0.0]);
        // 90° about +y.
        let v = q * Vector3::x();
        assert!((v - Vector3::new(0.0, 0.0, -1.0)).norm() < 1e-12);
        let w = quat_to_wxyz(&q);
        assert!((w[0] - w[2]).abs() < 1e-12 && w[1] == 0.0);
        assert!(quat_from_wxyz([0.0; 4]).w.is_nan());
        assert!(quat_from_wxyz([f64::INFINITY, 0.0, 0.0, 0.0]).w.is_nan());
    }

    #[test]
    fn euler_zyx_matches_rz_ry_rx() {
        let (x, y, z) = (10.0, -20.0, 30.0);
        let q = quat_from_euler_zyx_deg(x, y, z);
        let rz = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), deg_to_rad(z));
        let ry = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), deg_to_rad(y));
        let rx = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), deg_to_rad(x));
        assert!(q.angle_to(&(rz * ry * rx)) < 1e-12);
        let back = quat_to_euler_zyx_deg(&q);
        assert!((back[0] - x).abs() < 1e-9 && (back[1] - y).abs() < 1e-9);
        assert!((back[2] - z).abs() < 1e-9);
    }

    #[test]
    fn glam_round_trip_and_nan() {
        let p = pose_from_pos_quat([100.0, -200.0, 300.0], [0.5, 0.5, -0.5, 0.5]);
        let o = pose_to_opw(&p).unwrap();
        assert!((o.translation.x - 0.1).abs() < 1e-15);
        let back = pose_from_opw(&o);
        assert!((back.translation.vector - p.translation.vector).norm() < 1e-9);
        assert!(back.rotation.angle_to(&p.rotation) < 1e-12);
        assert!(pose_to_opw(&nan_pose()).is_none());
        assert!(!pose_is_finite(&nan_pose()));
        assert!(pose_is_finite(&p));
    }
}
