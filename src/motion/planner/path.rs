//! Geometric paths of the four move kinds as functions of `s ∈ [0, 1]`: axis lines, straight
//! TCP lines with SLERP, and circular arcs through a circle point (docs/robot.md, "Planning").

use std::f64::consts::TAU;

use nalgebra::{Point3, Unit, UnitQuaternion, Vector3};

use crate::robot::{JointsDeg, Pose};

use super::super::event::MotionError;

/// Start, circle point and target must be at least this far apart (mm). ABB's own figure is
/// not published; 0.1 mm is far below any taught point spacing.
pub const MIN_CIRCLE_POINT_DISTANCE_MM: f64 = 0.1;

/// The sine of the angle at the start between the chords to the circle point and to the
/// target must be at least this, or the three points count as collinear.
pub const MIN_CIRCLE_SINE: f64 = 1e-4;

/// A rotation from `from`, turning by `angle` (rad, may exceed π or be negative for "the long
/// way round") about `axis` expressed in the rotating frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OriPath {
    from: UnitQuaternion<f64>,
    axis: Vector3<f64>,
    angle: f64,
}

impl OriPath {
    /// The shortest rotation from `from` to `to` (SLERP).
    pub fn shortest(from: UnitQuaternion<f64>, to: UnitQuaternion<f64>) -> OriPath {
        let delta = from.inverse() * to;
        let (axis, angle) = match delta.axis_angle() {
            Some((axis, angle)) => (axis.into_inner(), angle),
            None => (Vector3::zeros(), 0.0),
        };
        OriPath { from, axis, angle }
    }

    /// The same end orientation reached by turning the other way round the same axis.
    pub fn the_long_way(&self) -> OriPath {
        if self.angle.abs() < 1e-9 {
            return *self;
        }
        OriPath {
            angle: self.angle - TAU * self.angle.signum(),
            ..*self
        }
    }

    /// The orientation at `s`.
    pub fn at(&self, s: f64) -> UnitQuaternion<f64> {
        self.from * UnitQuaternion::from_scaled_axis(self.axis * (self.angle * s))
    }

    /// Total reorientation (rad, non-negative).
    pub fn angle(&self) -> f64 {
        self.angle.abs()
    }
}

/// A circle through three points, parametrised from the first point to the third through
/// the second.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arc {
    center: Point3<f64>,
    radius: f64,
    u: Vector3<f64>,
    v: Vector3<f64>,
    sweep: f64,
    /// Share of the arc at which the circle point lies.
    cir_share: f64,
}

impl Arc {
    /// The arc from `p0` through `p1` to `p2`.
    pub fn through(
        p0: &Point3<f64>,
        p1: &Point3<f64>,
        p2: &Point3<f64>,
    ) -> Result<Arc, MotionError> {
        let a = p1 - p0;
        let b = p2 - p0;
        for (d, reason) in [
            (a.norm(), "the circle point is too close to the start point"),
            (
                (p2 - p1).norm(),
                "the circle point is too close to the target",
            ),
            (b.norm(), "the target is too close to the start point"),
        ] {
            if d.is_nan() || d < MIN_CIRCLE_POINT_DISTANCE_MM {
                return Err(MotionError::CircleUncertain { reason });
            }
        }
        let n = a.cross(&b);
        let n_norm = n.norm();
        if n_norm.is_nan() || n_norm < MIN_CIRCLE_SINE * a.norm() * b.norm() {
            return Err(MotionError::CircleUncertain {
                reason: "start point, circle point and target lie on a straight line",
            });
        }
        // Circumcentre of (0, a, b): ((|a|² b − |b|² a) × (a × b)) / (2 |a × b|²).
        let c_rel =
            (b * a.norm_squared() - a * b.norm_squared()).cross(&n) / (2.0 * n_norm * n_norm);
        let center = p0 + c_rel;
        let radius = c_rel.norm();
        let normal = Unit::new_normalize(n);
        let u = (p0 - center) / radius;
        let v = normal.cross(&u);
        let angle_of = |p: &Point3<f64>| {
            let d = p - center;
            d.dot(&v).atan2(d.dot(&u)).rem_euclid(TAU)
        };
        let sweep = angle_of(p2);
        let cir = angle_of(p1);
        if !(sweep.is_finite() && sweep > 0.0 && radius.is_finite()) {
            return Err(MotionError::CircleUncertain {
                reason: "the three points do not define a circle",
            });
        }
        Ok(Arc {
            center,
            radius,
            u,
            v,
            sweep,
            cir_share: cir / sweep,
        })
    }

    /// The point at `s`.
    pub fn at(&self, s: f64) -> Point3<f64> {
        let phi = self.sweep * s;
        self.center + (self.u * phi.cos() + self.v * phi.sin()) * self.radius
    }

    /// Arc length (mm).
    pub fn length(&self) -> f64 {
        self.radius * self.sweep
    }

    /// Radius (mm).
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Centre of the circle.
    pub fn center(&self) -> Point3<f64> {
        self.center
    }

    /// The share of the arc at which the circle point lies.
    pub fn cir_share(&self) -> f64 {
        self.cir_share
    }
}

/// What a move interpolates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Geometry {
    /// Axis interpolation (MoveAbsJ, MoveJ).
    Joint {
        /// Start joints.
        from: JointsDeg,
        /// Goal joints.
        to: JointsDeg,
    },
    /// A straight TCP line with SLERP orientation, in the object frame (MoveL).
    Line {
        /// Start position.
        from: Point3<f64>,
        /// Target position.
        to: Point3<f64>,
        /// Orientation.
        ori: OriPath,
    },
    /// A circular arc with SLERP orientation, in the object frame (MoveC).
    Circle {
        /// The arc.
        arc: Arc,
        /// Orientation.
        ori: OriPath,
    },
}

impl Geometry {
    /// Joints at `s` (joint geometries only).
    pub fn joints_at(from: &JointsDeg, to: &JointsDeg, s: f64) -> JointsDeg {
        let mut q = *from;
        for (qi, (a, b)) in q.iter_mut().zip(from.iter().zip(to)) {
            *qi = a + (b - a) * s;
        }
        q
    }

    /// The TCP pose (object frame) at `s` (Cartesian geometries only; `None` for joints).
    pub fn pose_at(&self, s: f64) -> Option<Pose> {
        match self {
            Geometry::Joint { .. } => None,
            Geometry::Line { from, to, ori } => {
                let p = from + (to - from) * s;
                Some(Pose::from_parts(p.into(), ori.at(s)))
            }
            Geometry::Circle { arc, ori } => Some(Pose::from_parts(arc.at(s).into(), ori.at(s))),
        }
    }

    /// True for MoveL/MoveC geometries.
    pub fn is_cartesian(&self) -> bool {
        !matches!(self, Geometry::Joint { .. })
    }
}

/// Superpose two moves in Cartesian space for a corner path: `a` on the previous move, `b` on
/// the next one, both TCP poses in world; `joint` is where the two moves meet. Position and
/// orientation offsets of `b` from the corner point are added onto `a`.
pub fn superpose(a: &Pose, b: &Pose, joint: &Pose) -> Pose {
    let p = a.translation.vector + (b.translation.vector - joint.translation.vector);
    let r = b.rotation * joint.rotation.inverse() * a.rotation;
    Pose::from_parts(p.into(), r)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]
mod tests {
    use super::*;

    #[test]
    fn circle_through_three_points() {
        let p0 = Point3::new(100.0, 0.0, 50.0);
        let p1 = Point3::new(0.0, 100.0, 50.0);
        let p2 = Point3::new(-100.0, 0.0, 50.0);
        let arc = Arc::through(&p0, &p1, &p2).unwrap();
        assert!((arc.radius() - 100.0).abs() < 1e-9);
        assert!((arc.center() - Point3::new(0.0, 0.0, 50.0)).norm() < 1e-9);
        assert!((arc.length() - std::f64::consts::PI * 100.0).abs() < 1e-9);
        assert!((arc.at(0.5) - p1).norm() < 1e-9);
        assert!((arc.at(1.0) - p2).norm() < 1e-9);
        assert!((arc.cir_share() - 0.5).abs() < 1e-12);
        // Going the other way round passes the circle point too.
        let q1 = Point3::new(0.0, -100.0, 50.0);
        let arc = Arc::through(&p0, &q1, &p2).unwrap();
        assert!((arc.at(0.5) - q1).norm() < 1e-9);
        // A 270° arc.
        let r1 = Point3::new(-100.0, 0.0, 50.0);
        let r2 = Point3::new(0.0, -100.0, 50.0);
        let arc = Arc::through(&p0, &r1, &r2).unwrap();
        assert!((arc.length() - 1.5 * std::f64::consts::PI * 100.0).abs() < 1e-9);
        assert!((arc.cir_share() - 2.0 / 3.0).abs() < 1e-9);
    }

    #[test]
    fn degenerate_circles() {
        let p = Point3::new(0.0, 0.0, 0.0);
        let q = Point3::new(10.0, 0.0, 0.0);
        let r = Point3::new(20.0, 0.0, 0.0);
        assert!(matches!(
            Arc::through(&p, &q, &r),
            Err(MotionError::CircleUncertain { .. })
        ));
        assert!(Arc::through(&p, &p, &r).is_err());
        let nan = Point3::new(f64::NAN, 0.0, 0.0);
        assert!(Arc::through(&p, &nan, &r).is_err());
    }

    #[test]
    fn orientation_paths() {
        let a = UnitQuaternion::identity();
        let b = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 1.0);
        let o = OriPath::shortest(a, b);
        assert!((o.angle() - 1.0).abs() < 1e-12);
        assert!(
            o.at(0.5)
                .angle_to(&UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.5))
                < 1e-12
        );
        let l = o.the_long_way();
        assert!(l.at(1.0).angle_to(&b) < 1e-9);
        assert!((l.angle() - (TAU - 1.0)).abs() < 1e-12);
        assert!(
            l.at(0.5).angle_to(&UnitQuaternion::from_axis_angle(
                &Vector3::z_axis(),
                0.5 - std::f64::consts::PI
            )) < 1e-9
        );
        // Sign of the quaternion does not matter.
        let minus_b = UnitQuaternion::new_unchecked(-b.into_inner());
        assert!((OriPath::shortest(a, minus_b).angle() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn superposition_meets_both_moves() {
        let joint = Pose::translation(100.0, 0.0, 0.0);
        let a = Pose::translation(90.0, 0.0, 0.0);
        let b = Pose::translation(100.0, 10.0, 0.0);
        let c = superpose(&a, &b, &joint);
        assert!((c.translation.vector - Vector3::new(90.0, 10.0, 0.0)).norm() < 1e-12);
        assert_eq!(superpose(&joint, &b, &joint), b);
    }
}
