//! Frames from points and mirrored poses: the math of RAPID's `DefFrame`, `DefDFrame` and
//! `MirPos` (mm and the crate's [`Pose`]).

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

use super::Pose;

/// Two points closer than this (mm), or a third point closer than this to the line through
/// the other two, define no frame.
pub const MIN_SPREAD_MM: f64 = 0.1;

/// Where `DefFrame` puts the origin (`\Origin`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameOrigin {
    /// In the first point (`\Origin := 1`, the default).
    First,
    /// In the second point (`\Origin := 2`).
    Second,
    /// On the line through the first two points, so that the third lies on the y axis
    /// (`\Origin := 3`).
    Projection,
}

/// Why three points define no frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FrameError {
    /// The first two points coincide.
    #[error("the first two points are less than {MIN_SPREAD_MM} mm apart")]
    Coincident,
    /// The third point lies on the line through the first two.
    #[error("the third point lies on the line through the first two")]
    Collinear,
    /// A coordinate is not finite.
    #[error("a coordinate is not a finite number")]
    NotFinite,
}

/// The frame of three points: x from `p1` toward `p2`, `p3` in the xy plane on the side of
/// positive y, z = x × y; the origin where `origin` says.
pub fn frame_from_points(
    p1: &Vector3<f64>,
    p2: &Vector3<f64>,
    p3: &Vector3<f64>,
    origin: FrameOrigin,
) -> Result<Pose, FrameError> {
    if [p1, p2, p3]
        .iter()
        .any(|p| p.iter().any(|c| !c.is_finite()))
    {
        return Err(FrameError::NotFinite);
    }
    let dx = p2 - p1;
    let len = dx.norm();
    if len < MIN_SPREAD_MM {
        return Err(FrameError::Coincident);
    }
    let x = dx / len;
    let d3 = p3 - p1;
    let along = d3.dot(&x);
    let perp = d3 - x * along;
    let off = perp.norm();
    if off < MIN_SPREAD_MM {
        return Err(FrameError::Collinear);
    }
    let y = perp / off;
    let z = x.cross(&y);
    let rot = Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[x, y, z]));
    let o = match origin {
        FrameOrigin::First => *p1,
        FrameOrigin::Second => *p2,
        FrameOrigin::Projection => p1 + x * along,
    };
    Ok(Pose::from_parts(
        o.into(),
        UnitQuaternion::from_rotation_matrix(&rot),
    ))
}

/// The displacement that moves the frame of `old` onto the frame of `new` (each frame as in
/// [`frame_from_points`] with the origin in the first point): `F_new · F_old⁻¹`, which maps
/// every old point onto its new place when the points keep their shape.
pub fn displacement_frame(
    old: [&Vector3<f64>; 3],
    new: [&Vector3<f64>; 3],
) -> Result<Pose, FrameError> {
    let f_old = frame_from_points(old[0], old[1], old[2], FrameOrigin::First)?;
    let f_new = frame_from_points(new[0], new[1], new[2], FrameOrigin::First)?;
    Ok(f_new * f_old.inverse())
}

/// `pose` mirrored in the xy plane of `plane` (both in the same frame): the position's z
/// (in `plane`) changes sign; of the tool frame's axes, x and z are mirrored and y completes
/// a right-handed frame, or with `mir_y` y and z are mirrored and x completes it.
pub fn mirror_in_xy(pose: &Pose, plane: &Pose, mir_y: bool) -> Pose {
    let local = plane.inverse() * pose;
    let s = Vector3::new(1.0, 1.0, -1.0);
    let t = local.translation.vector.component_mul(&s);
    let m = local.rotation.to_rotation_matrix();
    let ex = m.matrix().column(0).component_mul(&s);
    let ey = m.matrix().column(1).component_mul(&s);
    let ez = m.matrix().column(2).component_mul(&s);
    let (x, y, z) = if mir_y {
        (ey.cross(&ez), ey, ez)
    } else {
        (ex, ez.cross(&ex), ez)
    };
    let rot = Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[x, y, z]));
    let mirrored = Pose::from_parts(t.into(), UnitQuaternion::from_rotation_matrix(&rot));
    plane * mirrored
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> Vector3<f64> {
        Vector3::new(x, y, z)
    }

    #[test]
    fn three_points_give_the_frame() {
        let f = frame_from_points(
            &v(100.0, 0.0, 0.0),
            &v(100.0, 100.0, 0.0),
            &v(0.0, 50.0, 0.0),
            FrameOrigin::First,
        )
        .unwrap();
        // x along +y of the world, y toward −x, z up.
        let x = f.rotation * Vector3::x();
        let y = f.rotation * Vector3::y();
        assert!((x - v(0.0, 1.0, 0.0)).norm() < 1e-12);
        assert!((y - v(-1.0, 0.0, 0.0)).norm() < 1e-12);
        assert!((f.translation.vector - v(100.0, 0.0, 0.0)).norm() < 1e-12);
        let f3 = frame_from_points(
            &v(100.0, 0.0, 0.0),
            &v(100.0, 100.0, 0.0),
            &v(0.0, 50.0, 0.0),
            FrameOrigin::Projection,
        )
        .unwrap();
        assert!((f3.translation.vector - v(100.0, 50.0, 0.0)).norm() < 1e-12);
        assert_eq!(
            frame_from_points(
                &v(0.0, 0.0, 0.0),
                &v(1.0, 0.0, 0.0),
                &v(2.0, 0.0, 0.0),
                FrameOrigin::First
            ),
            Err(FrameError::Collinear)
        );
    }

    #[test]
    fn a_displacement_maps_old_points_onto_new_ones() {
        let old = [v(0.0, 0.0, 0.0), v(100.0, 0.0, 0.0), v(0.0, 100.0, 0.0)];
        let new = [v(10.0, 20.0, 0.0), v(10.0, 120.0, 0.0), v(-90.0, 20.0, 0.0)];
        let d =
            displacement_frame([&old[0], &old[1], &old[2]], [&new[0], &new[1], &new[2]]).unwrap();
        for (o, n) in old.iter().zip(&new) {
            assert!((d * nalgebra::Point3::from(*o) - nalgebra::Point3::from(*n)).norm() < 1e-9);
        }
    }

    #[test]
    fn mirroring_twice_gives_the_pose_back() {
        let p = Pose::from_parts(
            v(300.0, 200.0, 100.0).into(),
            UnitQuaternion::from_euler_angles(0.3, -0.2, 1.1),
        );
        let plane = Pose::from_parts(
            v(0.0, 0.0, 50.0).into(),
            UnitQuaternion::from_euler_angles(0.1, 0.0, 0.0),
        );
        for mir_y in [false, true] {
            let m = mirror_in_xy(&p, &plane, mir_y);
            let back = mirror_in_xy(&m, &plane, mir_y);
            assert!((back.translation.vector - p.translation.vector).norm() < 1e-9);
            assert!(back.rotation.angle_to(&p.rotation) < 1e-9);
        }
    }
}
