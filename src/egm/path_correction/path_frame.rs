//! The path frame (x along the path tangent, y = x × tool z, z = x × y) with its fallbacks at
//! degenerate points, and offsets in it.

use nalgebra::Vector3;

/// A vector in world (or any Cartesian) coordinates, mm.
pub type Vec3 = Vector3<f64>;

/// Below this length a tangent or tool axis counts as absent.
pub const MIN_AXIS_NORM: f64 = 1e-9;

/// Below this sine of the angle between tangent and tool z, y = x × tool z is undefined and
/// the fallback applies.
pub const PARALLEL_SIN: f64 = 1e-6;

/// A unit vector along `v`, if `v` is finite and long enough.
fn unit(v: &Vec3) -> Option<Vec3> {
    let n = v.norm();
    (n.is_finite() && n > MIN_AXIS_NORM).then(|| v / n)
}

/// A unit vector perpendicular to the unit vector `v`: `v × e`, with `e` the world axis
/// least aligned with `v` (X, then Y, then Z on ties).
fn perpendicular(v: &Vec3) -> Vec3 {
    let axes = [Vec3::x(), Vec3::y(), Vec3::z()];
    let mut best = Vec3::x();
    let mut best_dot = f64::INFINITY;
    for e in axes {
        let d = v.dot(&e).abs();
        if d < best_dot {
            best_dot = d;
            best = e;
        }
    }
    unit(&v.cross(&best)).unwrap_or_else(Vec3::y)
}

/// How a [`PathFrame`] was obtained.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FrameBasis {
    /// By the manual's definition.
    Regular,
    /// The tangent is (nearly) parallel to the tool z axis: y is the previous frame's y
    /// made perpendicular to x, or without a previous frame x × (the world axis least
    /// aligned with x).
    TangentAlongToolZ,
    /// The tool z axis is zero or not finite: y as for [`FrameBasis::TangentAlongToolZ`].
    NoToolZ,
    /// The tangent is zero or not finite (the path is not moving): x is the previous
    /// frame's x, or without one the world X axis made perpendicular to the tool z axis
    /// (world Y if X is along it); then y and z as usual.
    NoTangent,
    /// Neither a tangent, a previous frame nor a tool axis: the world frame.
    World,
}

/// The path frame: orthonormal, right-handed (`z = x × y`), axes in world coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathFrame {
    /// Along the path tangent.
    pub x: Vec3,
    /// x × tool z, normalised.
    pub y: Vec3,
    /// x × y.
    pub z: Vec3,
    /// Whether a fallback was needed.
    pub basis: FrameBasis,
}

impl PathFrame {
    /// The world frame (used when nothing defines a path frame).
    pub fn world() -> PathFrame {
        PathFrame {
            x: Vec3::x(),
            y: Vec3::y(),
            z: Vec3::z(),
            basis: FrameBasis::World,
        }
    }

    /// The path frame at a path point with direction `tangent` (any length) and active tool
    /// z axis `tool_z` (any length), both in world coordinates. `previous` (the frame of the
    /// previous path point) keeps degenerate points continuous; see [`FrameBasis`].
    pub fn new(tangent: Vec3, tool_z: Vec3, previous: Option<&PathFrame>) -> PathFrame {
        let tz = unit(&tool_z);
        let x = unit(&tangent)
            .map(|x| (x, false))
            .or_else(|| previous.and_then(|p| unit(&p.x)).map(|x| (x, true)))
            .or_else(|| {
                let tz = tz?;
                let from_x = Vec3::x() - tz * tz.dot(&Vec3::x());
                let from_y = Vec3::y() - tz * tz.dot(&Vec3::y());
                unit(&from_x).or_else(|| unit(&from_y)).map(|x| (x, true))
            });
        let Some((x, no_tangent)) = x else {
            return PathFrame::world();
        };
        let regular_y = tz.and_then(|tz| {
            let c = x.cross(&tz);
            let n = c.norm();
            (n.is_finite() && n > PARALLEL_SIN).then(|| c / n)
        });
        let (y, basis) = match regular_y {
            Some(y) if no_tangent => (y, FrameBasis::NoTangent),
            Some(y) => (y, FrameBasis::Regular),
            None => {
                let y = previous
                    .and_then(|p| unit(&(p.y - x * x.dot(&p.y))))
                    .filter(|y| y.dot(&x).abs() < PARALLEL_SIN)
                    .unwrap_or_else(|| perpendicular(&x));
                let basis = match (no_tangent, tz) {
                    (true, _) => FrameBasis::NoTangent,
                    (false, Some(_)) => FrameBasis::TangentAlongToolZ,
                    (false, None) => FrameBasis::NoToolZ,
                };
                (y, basis)
            }
        };
        let z = x.cross(&y);
        let frame = PathFrame { x, y, z, basis };
        if [frame.x, frame.y, frame.z]
            .iter()
            .all(|v| v.iter().all(|c| c.is_finite()))
        {
            frame
        } else {
            PathFrame::world()
        }
    }

    /// The world vector of an offset in this frame (`y·Y + z·Z`; there is no x part).
    pub fn to_world(&self, offset: PathOffset) -> Vec3 {
        self.y * offset.y + self.z * offset.z
    }

    /// The y and z components of a world vector in this frame (e.g. corrected minus
    /// programmed TCP position, for plots).
    pub fn offset_of(&self, v: &Vec3) -> PathOffset {
        PathOffset {
            y: self.y.dot(v),
            z: self.z.dot(v),
        }
    }

    /// The x component of a world vector in this frame.
    pub fn along(&self, v: &Vec3) -> f64 {
        self.x.dot(v)
    }
}

/// How far the sensor frame origin is ahead of the TCP along the path (`frame.x`), mm; 0
/// for non-finite input. Negative means behind.
pub fn look_ahead_distance(frame: &PathFrame, tcp: &Vec3, sensor_origin: &Vec3) -> f64 {
    let d = frame.along(&(sensor_origin - tcp));
    if d.is_finite() { d } else { 0.0 }
}

/// An offset in the path frame, mm (y and z only).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PathOffset {
    /// Along the path frame's y axis.
    pub y: f64,
    /// Along the path frame's z axis.
    pub z: f64,
}

impl PathOffset {
    /// No offset.
    pub const ZERO: PathOffset = PathOffset { y: 0.0, z: 0.0 };

    /// An offset.
    pub fn new(y: f64, z: f64) -> Self {
        PathOffset { y, z }
    }

    /// Its length, mm.
    pub fn norm(&self) -> f64 {
        self.y.hypot(self.z)
    }

    /// Whether both components are finite.
    pub fn is_finite(&self) -> bool {
        self.y.is_finite() && self.z.is_finite()
    }

    pub(super) fn add(self, o: PathOffset) -> PathOffset {
        PathOffset::new(self.y + o.y, self.z + o.z)
    }

    pub(super) fn sub(self, o: PathOffset) -> PathOffset {
        PathOffset::new(self.y - o.y, self.z - o.z)
    }

    pub(super) fn scale(self, k: f64) -> PathOffset {
        PathOffset::new(self.y * k, self.z * k)
    }

    /// `a + (b − a)·t`.
    pub(super) fn lerp(a: PathOffset, b: PathOffset, t: f64) -> PathOffset {
        a.add(b.sub(a).scale(t))
    }
}
