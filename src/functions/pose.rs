//! Pose math behind OrientZYX, EulerZYX, PoseMult, PoseInv, PoseVect, NOrient, Offs, RelTool, Distance and the vector functions.
//!
//! Plain types: positions are `[x, y, z]` in mm ([`Pos`]), orientations are RAPID `orient`
//! quaternions `[q1, q2, q3, q4]` = `[w, x, y, z]` ([`Quat`]), angles are degrees. All
//! arithmetic is `f64`; the interpreter narrows results to `num`.
//!
//! # Decisions (pinned by the tests below)
//!
//! * **ZYX Euler angles** as on the EGM wire: `OrientZYX(z, y, x)` is the rotation
//!   `Rz(z)·Ry(y)·Rx(x)`: rotate about z, then about the new y, then about the new x
//!   (equivalently x, y, z about the fixed axes). The quaternion it returns has `q1 ≥ 0`.
//!   `OrientZYX(90, 0, 0) = [0.707107, 0, 0, 0.707107]`.
//! * **EulerZYX** returns one of those angles, in degrees: z and x in −180…180, y in
//!   −90…90. At the gimbal lock (y = ±90) x is reported as 0 and the whole rotation about
//!   the vertical goes into z.
//! * **Orientation inputs are normalised** before use by every function except
//!   `orient * orient`; a zero or non-finite quaternion is `ERR_ILLQUAT`.
//! * **`orient * orient`** ([`orient_mult`]) is the plain Hamilton product of the two
//!   quaternions as given (the linking of rotations, RRM p.102): no normalisation, no sign
//!   change, never an error.
//! * **PoseMult / PoseInv / RelTool** return the product quaternion as computed (no sign
//!   canonicalisation: `q` and `−q` are the same rotation).
//! * **RelTool** `\Rx \Ry \Rz`: the rotations are applied in the tool frame, first about x,
//!   then about the new y, then about the new z (`rot · Rx · Ry · Rz`); the displacement
//!   `dx, dy, dz` is along the axes of the *original* tool orientation.
//! * **Offs** adds `dx, dy, dz` to the position in the frame the robtarget is written in.
//! * **`pos * pos`** is the cross product ([`cross_prod`]).

use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};

use super::math::sin_cos_deg;
use super::{RtError, RtResult};

/// A position `[x, y, z]` in mm (RAPID `pos`).
pub type Pos = [f64; 3];

/// An orientation `[q1, q2, q3, q4]` = `[w, x, y, z]` (RAPID `orient`).
pub type Quat = [f64; 4];

/// A frame: a position and an orientation (RAPID `pose`, or the first two components of a
/// `robtarget`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Translation in mm.
    pub trans: Pos,
    /// Rotation as `[w, x, y, z]`.
    pub rot: Quat,
}

impl Pose {
    /// The identity pose `[[0,0,0],[1,0,0,0]]`.
    pub const IDENTITY: Pose = Pose {
        trans: [0.0, 0.0, 0.0],
        rot: [1.0, 0.0, 0.0, 0.0],
    };
}

/// Which angle [`euler_zyx`] returns (`\X`, `\Y` or `\Z`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EulerAxis {
    /// Rotation about x (the last of the three).
    X,
    /// Rotation about y.
    Y,
    /// Rotation about z (the first of the three).
    Z,
}

// moves to robot::units at merge
/// Degrees to radians.
pub(crate) fn deg_to_rad(deg: f64) -> f64 {
    deg.to_radians()
}

// moves to robot::units at merge
/// Radians to degrees.
pub(crate) fn rad_to_deg(rad: f64) -> f64 {
    rad.to_degrees()
}

/// The normalised rotation of `q`, or `ERR_ILLQUAT`.
fn unit(func: &'static str, q: &Quat) -> RtResult<UnitQuaternion<f64>> {
    let raw = Quaternion::new(q[0], q[1], q[2], q[3]);
    let norm = raw.norm();
    if !norm.is_finite() || norm == 0.0 {
        return Err(RtError::IllQuat { func });
    }
    Ok(UnitQuaternion::new_unchecked(raw / norm))
}

fn quat_of(u: &UnitQuaternion<f64>) -> Quat {
    [u.w + 0.0, u.i + 0.0, u.j + 0.0, u.k + 0.0]
}

fn vec_of(p: &Pos) -> Vector3<f64> {
    Vector3::new(p[0], p[1], p[2])
}

fn pos_of(v: &Vector3<f64>) -> Pos {
    [v.x + 0.0, v.y + 0.0, v.z + 0.0]
}

fn finite(func: &'static str, values: &[f64]) -> RtResult<()> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(RtError::arg(func, "an argument is not a finite number"))
    }
}

/// Rotation of `deg` degrees about a unit axis (0 = x, 1 = y, 2 = z), with exact half-angle
/// trigonometry in degrees (so 180 degrees gives exactly `[0, …, 1, …]`).
fn axis_rotation(func: &'static str, axis: usize, deg: f64) -> RtResult<Quat> {
    let (s, c) = sin_cos_deg(func, deg / 2.0)?;
    let mut q = [c, 0.0, 0.0, 0.0];
    if let Some(slot) = q.get_mut(axis + 1) {
        *slot = s;
    }
    Ok(q)
}

/// Hamilton product `a ⊗ b` (the rotation `a` followed by `b` in `a`'s frame).
fn hamilton(a: &Quat, b: &Quat) -> Quat {
    let [aw, ax, ay, az] = *a;
    let [bw, bx, by, bz] = *b;
    [
        aw * bw - ax * bx - ay * by - az * bz + 0.0,
        aw * bx + ax * bw + ay * bz - az * by + 0.0,
        aw * by - ax * bz + ay * bw + az * bx + 0.0,
        aw * bz + ax * by - ay * bx + az * bw + 0.0,
    ]
}

/// `OrientZYX(ZAngle, YAngle, XAngle)`: the orientation `Rz(z)·Ry(y)·Rx(x)`, with `q1 ≥ 0`.
pub fn orient_zyx(z: f64, y: f64, x: f64) -> RtResult<Quat> {
    finite("OrientZYX", &[z, y, x])?;
    let qz = axis_rotation("OrientZYX", 2, z)?;
    let qy = axis_rotation("OrientZYX", 1, y)?;
    let qx = axis_rotation("OrientZYX", 0, x)?;
    let q = hamilton(&hamilton(&qz, &qy), &qx);
    let q = match unit("OrientZYX", &q) {
        Ok(u) => quat_of(&u),
        Err(e) => return Err(e),
    };
    Ok(if q[0] < 0.0 { q.map(|c| -c + 0.0) } else { q })
}

/// The three ZYX angles `[z, y, x]` in degrees of an orientation (see the module doc for
/// ranges and the gimbal lock).
pub fn euler_zyx_all(q: &Quat) -> RtResult<[f64; 3]> {
    let r: Matrix3<f64> = unit("EulerZYX", q)?.to_rotation_matrix().into_inner();
    let (r00, r01, r10, r11) = (r[(0, 0)], r[(0, 1)], r[(1, 0)], r[(1, 1)]);
    let (r20, r21, r22) = (r[(2, 0)], r[(2, 1)], r[(2, 2)]);
    let cos_y = (r00 * r00 + r10 * r10).sqrt();
    let y = (-r20).atan2(cos_y);
    // Gimbal lock: cos(y) ≈ 0, z and x rotate about the same axis.
    let (z, x) = if cos_y < 1e-12 {
        ((-r01).atan2(r11), 0.0)
    } else {
        (r10.atan2(r00), r21.atan2(r22))
    };
    Ok([
        rad_to_deg(z) + 0.0,
        rad_to_deg(y) + 0.0,
        rad_to_deg(x) + 0.0,
    ])
}

/// `EulerZYX(\X | \Y | \Z, Rotation)`: one ZYX angle in degrees.
pub fn euler_zyx(axis: EulerAxis, q: &Quat) -> RtResult<f64> {
    let [z, y, x] = euler_zyx_all(q)?;
    Ok(match axis {
        EulerAxis::X => x,
        EulerAxis::Y => y,
        EulerAxis::Z => z,
    })
}

/// `orient * orient`: the Hamilton product of the quaternions as given.
pub fn orient_mult(a: &Quat, b: &Quat) -> Quat {
    hamilton(a, b)
}

/// `NOrient(Rotation)`: the quaternion scaled to length 1 (sign kept); zero or non-finite
/// is `ERR_ILLQUAT`.
pub fn norient(q: &Quat) -> RtResult<Quat> {
    Ok(quat_of(&unit("NOrient", q)?))
}

/// `PoseMult(Pose1, Pose2)`: the frame `Pose2` expressed in `Pose1`'s parent frame
/// (`trans = t1 + R1·t2`, `rot = q1 ⊗ q2`).
pub fn pose_mult(p1: &Pose, p2: &Pose) -> RtResult<Pose> {
    finite("PoseMult", &[p1.trans, p2.trans].concat())?;
    let q1 = unit("PoseMult", &p1.rot)?;
    let q2 = unit("PoseMult", &p2.rot)?;
    let t = vec_of(&p1.trans) + q1 * vec_of(&p2.trans);
    Ok(Pose {
        trans: pos_of(&t),
        rot: quat_of(&(q1 * q2)),
    })
}

/// `PoseInv(Pose)`: the inverse frame (`rot = q⁻¹`, `trans = −R⁻¹·t`).
pub fn pose_inv(p: &Pose) -> RtResult<Pose> {
    finite("PoseInv", &p.trans)?;
    let inv = unit("PoseInv", &p.rot)?.inverse();
    let t = -(inv * vec_of(&p.trans));
    Ok(Pose {
        trans: pos_of(&t),
        rot: quat_of(&inv),
    })
}

/// `PoseVect(Pose, Pos)`: a position given in the frame `Pose`, expressed in the frame's
/// parent (`t + R·v`).
pub fn pose_vect(p: &Pose, v: &Pos) -> RtResult<Pos> {
    finite("PoseVect", &[p.trans, *v].concat())?;
    let q = unit("PoseVect", &p.rot)?;
    Ok(pos_of(&(vec_of(&p.trans) + q * vec_of(v))))
}

/// `Offs(Point, XOffset, YOffset, ZOffset)`: the position displaced in the point's own
/// frame (the other robtarget components are unchanged; the interpreter copies them).
pub fn offs(trans: &Pos, dx: f64, dy: f64, dz: f64) -> Pos {
    [trans[0] + dx, trans[1] + dy, trans[2] + dz]
}

/// `RelTool(Point, Dx, Dy, Dz \Rx \Ry \Rz)`: displacement `d` along the axes of the tool
/// orientation, then rotations about the tool's x, new y, new z (degrees; pass 0 for an
/// omitted rotation). Returns the new position and orientation.
pub fn rel_tool(point: &Pose, d: &Pos, rx: f64, ry: f64, rz: f64) -> RtResult<Pose> {
    finite("RelTool", &[point.trans, *d, [rx, ry, rz]].concat())?;
    let q = unit("RelTool", &point.rot)?;
    let t = vec_of(&point.trans) + q * vec_of(d);
    let r = hamilton(
        &hamilton(
            &axis_rotation("RelTool", 0, rx)?,
            &axis_rotation("RelTool", 1, ry)?,
        ),
        &axis_rotation("RelTool", 2, rz)?,
    );
    Ok(Pose {
        trans: pos_of(&t),
        rot: hamilton(&quat_of(&q), &r),
    })
}

/// `Distance(Point1, Point2)`: Euclidean distance in mm.
pub fn distance(a: &Pos, b: &Pos) -> f64 {
    (vec_of(a) - vec_of(b)).norm()
}

/// `VectMagn(Vector)`: the length of a vector.
pub fn vect_magn(v: &Pos) -> f64 {
    vec_of(v).norm()
}

/// `DotProd(Vector1, Vector2)`.
pub fn dot_prod(a: &Pos, b: &Pos) -> f64 {
    vec_of(a).dot(&vec_of(b))
}

/// `CrossProd(Vector1, Vector2)`, also `pos * pos`.
pub fn cross_prod(a: &Pos, b: &Pos) -> Pos {
    pos_of(&vec_of(a).cross(&vec_of(b)))
}

#[cfg(test)]
mod tests {
    use super::*;

    const EPS: f64 = 1e-9;

    fn close(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < EPS)
    }

    /// Same rotation (q or −q).
    fn same_rot(a: &Quat, b: &Quat) -> bool {
        close(a, b) || close(&a.map(|c| -c), b)
    }

    const H: f64 = std::f64::consts::FRAC_1_SQRT_2;

    #[test]
    fn orient_zyx_hand_values() {
        assert!(close(
            &orient_zyx(90.0, 0.0, 0.0).unwrap(),
            &[H, 0.0, 0.0, H]
        ));
        assert!(close(
            &orient_zyx(0.0, 90.0, 0.0).unwrap(),
            &[H, 0.0, H, 0.0]
        ));
        assert!(close(
            &orient_zyx(0.0, 0.0, 90.0).unwrap(),
            &[H, H, 0.0, 0.0]
        ));
        assert_eq!(orient_zyx(0.0, 0.0, 0.0).unwrap(), [1.0, 0.0, 0.0, 0.0]);
        // 180 degrees: exact, q1 = 0.
        assert_eq!(orient_zyx(180.0, 0.0, 0.0).unwrap(), [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(orient_zyx(0.0, 180.0, 0.0).unwrap(), [0.0, 0.0, 1.0, 0.0]);
        // q1 >= 0 even for angles whose half-angle cosine is negative.
        assert!(close(
            &orient_zyx(270.0, 0.0, 0.0).unwrap(),
            &[H, 0.0, 0.0, -H]
        ));
        // A tool pointing down (x 180) then turned 90 about z: Rz(90)·Rx(180).
        assert!(close(
            &orient_zyx(90.0, 0.0, 180.0).unwrap(),
            &[0.0, H, H, 0.0]
        ));
        // The manual's tool orientation [0.8339, 0, 0.5519, 0] is a rotation of ~67 deg about y.
        let q = orient_zyx(0.0, 67.0, 0.0).unwrap();
        assert!((q[0] - 0.833_886).abs() < 1e-6 && (q[2] - 0.551_937).abs() < 1e-6);
        assert_eq!(
            orient_zyx(f64::NAN, 0.0, 0.0).unwrap_err().err_name(),
            "ERR_ARGVALERR"
        );
    }

    #[test]
    fn orient_zyx_matches_matrix_product() {
        let (z, y, x) = (30.0, -20.0, 110.0);
        let q = orient_zyx(z, y, x).unwrap();
        let m = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), deg_to_rad(z))
            * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), deg_to_rad(y))
            * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), deg_to_rad(x));
        assert!(same_rot(&q, &quat_of(&m)));
    }

    #[test]
    fn euler_zyx_round_trip_and_gimbal() {
        for &(z, y, x) in &[
            (10.0, 20.0, 30.0),
            (-170.0, 45.0, 120.0),
            (90.0, -60.0, -179.0),
            (0.0, 0.0, 0.0),
        ] {
            let q = orient_zyx(z, y, x).unwrap();
            assert!(
                close(&euler_zyx_all(&q).unwrap(), &[z, y, x]),
                "{z} {y} {x}"
            );
            assert!((euler_zyx(EulerAxis::Z, &q).unwrap() - z).abs() < EPS);
            assert!((euler_zyx(EulerAxis::Y, &q).unwrap() - y).abs() < EPS);
            assert!((euler_zyx(EulerAxis::X, &q).unwrap() - x).abs() < EPS);
        }
        // Gimbal lock: y = 90, z and x combine; reported as x = 0.
        let q = orient_zyx(30.0, 90.0, 20.0).unwrap();
        let [z, y, x] = euler_zyx_all(&q).unwrap();
        assert!(
            (y - 90.0).abs() < 1e-6 && x == 0.0 && (z - 10.0).abs() < 1e-6,
            "{z} {y} {x}"
        );
        let q = orient_zyx(30.0, -90.0, 20.0).unwrap();
        let [z, y, x] = euler_zyx_all(&q).unwrap();
        assert!(
            (y + 90.0).abs() < 1e-6 && x == 0.0 && (z - 50.0).abs() < 1e-6,
            "{z} {y} {x}"
        );
        // Unnormalised input is normalised; zero is an error.
        let q = orient_zyx(0.0, 0.0, 40.0).unwrap().map(|c| c * 3.0);
        assert!((euler_zyx(EulerAxis::X, &q).unwrap() - 40.0).abs() < EPS);
        assert_eq!(
            euler_zyx(EulerAxis::X, &[0.0; 4]).unwrap_err(),
            RtError::IllQuat { func: "EulerZYX" }
        );
    }

    #[test]
    fn quaternion_product_and_norient() {
        let a = orient_zyx(90.0, 0.0, 0.0).unwrap();
        assert!(close(&orient_mult(&a, &a), &[0.0, 0.0, 0.0, 1.0]));
        // Not normalised, no error.
        assert_eq!(orient_mult(&[2.0, 0.0, 0.0, 0.0], &[0.0; 4]), [0.0; 4]);
        assert_eq!(
            orient_mult(&[0.0, 1.0, 0.0, 0.0], &[0.0, 0.0, 1.0, 0.0]),
            [0.0, 0.0, 0.0, 1.0]
        );
        assert!(close(
            &norient(&[2.0, 0.0, 0.0, 2.0]).unwrap(),
            &[H, 0.0, 0.0, H]
        ));
        assert!(close(
            &norient(&[-2.0, 0.0, 0.0, 0.0]).unwrap(),
            &[-1.0, 0.0, 0.0, 0.0]
        ));
        assert_eq!(norient(&[0.0; 4]).unwrap_err().err_name(), "ERR_ILLQUAT");
        assert_eq!(
            norient(&[f64::NAN, 0.0, 0.0, 0.0]).unwrap_err().err_name(),
            "ERR_ILLQUAT"
        );
    }

    #[test]
    fn pose_mult_inv_vect() {
        let p1 = Pose {
            trans: [100.0, 0.0, 0.0],
            rot: orient_zyx(90.0, 0.0, 0.0).unwrap(),
        };
        let p2 = Pose {
            trans: [10.0, 0.0, 0.0],
            rot: [1.0, 0.0, 0.0, 0.0],
        };
        let m = pose_mult(&p1, &p2).unwrap();
        assert!(close(&m.trans, &[100.0, 10.0, 0.0]));
        assert!(same_rot(&m.rot, &p1.rot));
        let inv = pose_inv(&p1).unwrap();
        // Rz(-90) and -(Rz(-90)·[100,0,0]) = [0,100,0].
        assert!(close(&inv.trans, &[0.0, 100.0, 0.0]));
        assert!(same_rot(&inv.rot, &orient_zyx(-90.0, 0.0, 0.0).unwrap()));
        let id = pose_mult(&p1, &inv).unwrap();
        assert!(close(&id.trans, &[0.0; 3]) && same_rot(&id.rot, &[1.0, 0.0, 0.0, 0.0]));
        assert!(close(
            &pose_vect(&p1, &[0.0, 5.0, 1.0]).unwrap(),
            &[95.0, 0.0, 1.0]
        ));
        let bad = Pose {
            trans: [0.0; 3],
            rot: [0.0; 4],
        };
        assert_eq!(pose_inv(&bad).unwrap_err().err_name(), "ERR_ILLQUAT");
        assert_eq!(pose_mult(&p1, &bad).unwrap_err().err_name(), "ERR_ILLQUAT");
        assert_eq!(
            pose_vect(&bad, &[0.0; 3]).unwrap_err().err_name(),
            "ERR_ILLQUAT"
        );
        assert_eq!(Pose::IDENTITY.rot, [1.0, 0.0, 0.0, 0.0]);
    }

    #[test]
    fn offs_and_reltool() {
        assert_eq!(offs(&[1.0, 2.0, 3.0], 10.0, -2.0, 0.5), [11.0, 0.0, 3.5]);
        // Tool pointing down (x rotated 180): tool z is world -z.
        let down = Pose {
            trans: [500.0, 0.0, 400.0],
            rot: [0.0, 1.0, 0.0, 0.0],
        };
        let r = rel_tool(&down, &[0.0, 0.0, 100.0], 0.0, 0.0, 0.0).unwrap();
        assert!(close(&r.trans, &[500.0, 0.0, 300.0]));
        assert_eq!(r.rot, down.rot);
        // Tool y is world -y.
        let r = rel_tool(&down, &[10.0, 20.0, 0.0], 0.0, 0.0, 0.0).unwrap();
        assert!(close(&r.trans, &[510.0, -20.0, 400.0]));
        // \Rz:=90 turns the tool about its own z: result = rot · Rz(90).
        let r = rel_tool(&down, &[0.0; 3], 0.0, 0.0, 90.0).unwrap();
        let expect = orient_mult(&down.rot, &orient_zyx(90.0, 0.0, 0.0).unwrap());
        assert!(same_rot(&r.rot, &expect));
        assert!(close(&r.trans, &down.trans));
        // Order: x, then the new y, then the new z = rot · Rx · Ry · Rz.
        let start = Pose {
            trans: [0.0; 3],
            rot: orient_zyx(10.0, 20.0, 30.0).unwrap(),
        };
        let r = rel_tool(&start, &[0.0; 3], 15.0, 25.0, 35.0).unwrap();
        let rx = orient_zyx(0.0, 0.0, 15.0).unwrap();
        let ry = orient_zyx(0.0, 25.0, 0.0).unwrap();
        let rz = orient_zyx(35.0, 0.0, 0.0).unwrap();
        let expect = orient_mult(&orient_mult(&orient_mult(&start.rot, &rx), &ry), &rz);
        assert!(same_rot(&r.rot, &expect));
        // …which differs from the opposite order.
        let other = orient_mult(&orient_mult(&orient_mult(&start.rot, &rz), &ry), &rx);
        assert!(!same_rot(&r.rot, &other));
        assert_eq!(
            rel_tool(&start, &[f64::INFINITY, 0.0, 0.0], 0.0, 0.0, 0.0)
                .unwrap_err()
                .err_name(),
            "ERR_ARGVALERR"
        );
    }

    #[test]
    fn vectors() {
        assert_eq!(distance(&[0.0, 0.0, 0.0], &[3.0, 4.0, 12.0]), 13.0);
        assert_eq!(vect_magn(&[3.0, 4.0, 0.0]), 5.0);
        assert_eq!(dot_prod(&[1.0, 2.0, 3.0], &[4.0, -5.0, 6.0]), 12.0);
        assert_eq!(
            cross_prod(&[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0]),
            [0.0, 0.0, 1.0]
        );
        assert_eq!(
            cross_prod(&[0.0, 1.0, 0.0], &[1.0, 0.0, 0.0]),
            [0.0, 0.0, -1.0]
        );
        assert_eq!(
            cross_prod(&[2.0, 3.0, 4.0], &[5.0, 6.0, 7.0]),
            [-3.0, 6.0, -3.0]
        );
    }

    mod props {
        use super::super::*;
        use proptest::prelude::*;

        fn close(a: &[f64], b: &[f64], eps: f64) -> bool {
            a.iter().zip(b).all(|(x, y)| (x - y).abs() < eps)
        }

        proptest! {
            #[test]
            fn euler_round_trip(z in -179.0f64..179.0, y in -89.0f64..89.0, x in -179.0f64..179.0) {
                let q = orient_zyx(z, y, x).unwrap();
                prop_assert!(q[0] >= 0.0);
                let n = q.iter().map(|c| c * c).sum::<f64>().sqrt();
                prop_assert!((n - 1.0).abs() < 1e-12);
                prop_assert!(close(&euler_zyx_all(&q).unwrap(), &[z, y, x], 1e-7));
            }

            #[test]
            fn pose_times_inverse_is_identity(
                t in proptest::array::uniform3(-2000.0f64..2000.0),
                a in proptest::array::uniform3(-180.0f64..180.0),
            ) {
                let p = Pose { trans: t, rot: orient_zyx(a[0], a[1], a[2]).unwrap() };
                let id = pose_mult(&p, &pose_inv(&p).unwrap()).unwrap();
                prop_assert!(close(&id.trans, &[0.0; 3], 1e-9));
                prop_assert!((id.rot[0].abs() - 1.0).abs() < 1e-12);
                let v = [1.0, -2.0, 3.0];
                let back = pose_vect(&pose_inv(&p).unwrap(), &pose_vect(&p, &v).unwrap()).unwrap();
                prop_assert!(close(&back, &v, 1e-9));
            }
        }
    }
}
