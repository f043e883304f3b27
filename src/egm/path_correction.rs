//! Path-correction math for EGMMoveL/EGMMoveC: the path frame, checking and smoothing sensor corrections, at-point (APTR) and look-ahead (LATR) scheduling, and simulated seam sensors — pure functions and state machines, no I/O.
//!
//! Units: mm for lengths and offsets, seconds for times (the caller converts the wire's
//! `age` in ms), degrees for the sine phase. Nothing here allocates after construction or
//! panics, and non-finite input never produces a NaN output.
//!
//! # Model
//!
//! * **Path frame** ([`PathFrame::new`], the manual's definition, docs/egm.md, "Path frame"): x
//!   along the path tangent, y = x × (z axis of the active tool) normalised, z = x × y.
//!   With the tool pointing down (tool z = −Z) on a path along +X, y is +Y and z is +Z:
//!   z points roughly against the tool axis, i.e. away from the work.
//! * **Corrections** are offsets `(y, z)` in the path frame ([`PathOffset`]). The x
//!   component of a sensor's `pos` is ignored: the manual allows corrections in y and z
//!   only. Each correction is checked ([`check_correction`]): a non-finite component (x
//!   included: it marks a corrupt message), a magnitude above
//!   [`CorrectionLimits::max_offset`], a negative or non-finite age, or an age above
//!   [`CorrectionLimits::max_age`] is a [`Rejection`] the caller turns into an event; the
//!   previous correction stays in force.
//! * **Absolute or incremental** ([`CorrectionMode`]): by default each correction is the
//!   total offset from the programmed path (one public user report says so); in incremental
//!   mode it adds to the previous total.
//! * **Scheduling** ([`Tracker`]). *APTR*: the measurement describes the seam at the TCP, so
//!   it becomes the target at once (its age is not used). *LATR*: the sensor frame origin is
//!   `look_ahead` mm ahead of the TCP along the path, so a measurement taken at time
//!   `now − age` describes the seam at arc length `s(now − age) + look_ahead`, where `s(t)`
//!   is the TCP's arc length along the programmed path at time `t` (kept in a bounded
//!   history of `(t, s)` samples from [`PathCorrector::step`]; times before the history
//!   use its oldest sample, later times its newest). The measurement waits in a bounded
//!   queue until the TCP reaches that arc length. Between queued points the target is
//!   interpolated linearly in arc length, starting from the last point passed (at the start
//!   of a sequence: zero offset at the start point, which is taught on the seam). A new
//!   measurement replaces queued ones at or beyond its own arc length (it is newer); one
//!   whose arc length has already been passed applies at once. When the queue is full the
//!   nearest entry is dropped (counted in [`PathCorrector::overflows`]).
//! * **Smoothing** ([`Smoother`]): the applied offset moves towards the target with a
//!   speed limit ([`SmoothingLimits::max_speed`], mm/s) and an acceleration limit
//!   ([`SmoothingLimits::max_accel`], mm/s², infinite for a pure rate limit), braking so it
//!   arrives without overshoot. No step is ever longer than `max_speed · dt`.
//! * **Simulated seam sensors** ([`SeamProfile`]): the seam's offset from the programmed
//!   path in the path frame as a function of arc length from the start of the corrected
//!   sequence — constant, ramp or sine — parsed from `const:y=3,z=-2`,
//!   `ramp:y=5,z=0,len=400`, `sine:y=2,z=0,period=100[,phase=90]`. A simulated sensor
//!   reports [`SeamProfile::sensed_at`]: the seam under the sensor (at the TCP for APTR,
//!   `look_ahead` ahead for LATR). This is what the built-in LTAPP stand-ins report; the
//!   LTAPP protocol itself is not public and not implemented.
//!
//! These are rapidvc's choices where ABB documents nothing (docs/egm.md, "Path correction").
#![deny(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

use std::collections::VecDeque;
use std::fmt;
use std::str::FromStr;

use nalgebra::Vector3;

/// A vector in world (or any Cartesian) coordinates, mm.
pub type Vec3 = Vector3<f64>;

/// Below this length a tangent or tool axis counts as absent.
pub const MIN_AXIS_NORM: f64 = 1e-9;

/// Below this sine of the angle between tangent and tool z, y = x × tool z is undefined and
/// the fallback applies.
pub const PARALLEL_SIN: f64 = 1e-6;

/// Offsets closer than this (mm) count as equal.
const EPS_MM: f64 = 1e-9;

/// `v > 0` (false for NaN).
fn positive(v: f64) -> bool {
    v > 0.0
}

/// `v >= 0` and finite.
fn non_negative_finite(v: f64) -> bool {
    v >= 0.0 && v.is_finite()
}

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

    fn add(self, o: PathOffset) -> PathOffset {
        PathOffset::new(self.y + o.y, self.z + o.z)
    }

    fn sub(self, o: PathOffset) -> PathOffset {
        PathOffset::new(self.y - o.y, self.z - o.z)
    }

    fn scale(self, k: f64) -> PathOffset {
        PathOffset::new(self.y * k, self.z * k)
    }

    /// `a + (b − a)·t`.
    fn lerp(a: PathOffset, b: PathOffset, t: f64) -> PathOffset {
        a.add(b.sub(a).scale(t))
    }
}

/// Limits on what a sensor may send.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CorrectionLimits {
    /// Largest total correction |(y, z)|, mm. Default 100.
    pub max_offset: f64,
    /// Largest measurement age, s. Default 2.
    pub max_age: f64,
}

impl Default for CorrectionLimits {
    fn default() -> Self {
        CorrectionLimits {
            max_offset: 100.0,
            max_age: 2.0,
        }
    }
}

/// Why a correction was not used.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum Rejection {
    /// A component of `pos` is NaN or infinite.
    #[error("path correction {axis} is not a finite number ({value})")]
    NotFinite {
        /// `x`, `y` or `z`.
        axis: char,
        /// The value.
        value: f64,
    },
    /// The correction is larger than the limit.
    #[error("path correction of {magnitude:.3} mm exceeds the limit of {limit} mm")]
    TooLarge {
        /// |(y, z)| of the (total) correction, mm.
        magnitude: f64,
        /// The limit, mm.
        limit: f64,
    },
    /// The age is negative or not a number.
    #[error("path correction age {age} s is negative or not a number")]
    BadAge {
        /// The age, s.
        age: f64,
    },
    /// The measurement is older than the limit.
    #[error("path correction is {age} s old; the limit is {limit} s")]
    TooOld {
        /// The age, s.
        age: f64,
        /// The limit, s.
        limit: f64,
    },
}

/// Check one correction `pos` (x, y, z as sent; x is ignored) with its `age` (s) and
/// return its path-frame offset.
pub fn check_correction(
    pos: [f64; 3],
    age: f64,
    limits: &CorrectionLimits,
) -> Result<PathOffset, Rejection> {
    for (axis, value) in ['x', 'y', 'z'].into_iter().zip(pos) {
        if !value.is_finite() {
            return Err(Rejection::NotFinite { axis, value });
        }
    }
    if !non_negative_finite(age) {
        return Err(Rejection::BadAge { age });
    }
    if age > limits.max_age {
        return Err(Rejection::TooOld {
            age,
            limit: limits.max_age,
        });
    }
    let [_, y, z] = pos;
    let offset = PathOffset::new(y, z);
    check_magnitude(offset, limits)?;
    Ok(offset)
}

fn check_magnitude(offset: PathOffset, limits: &CorrectionLimits) -> Result<(), Rejection> {
    let magnitude = offset.norm();
    if magnitude.is_finite() && magnitude <= limits.max_offset {
        Ok(())
    } else {
        Err(Rejection::TooLarge {
            magnitude,
            limit: limits.max_offset,
        })
    }
}

/// How fast the applied correction may change.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmoothingLimits {
    /// Largest correction speed, mm/s (`f64::INFINITY`: no limit). Default 20.
    pub max_speed: f64,
    /// Largest correction acceleration, mm/s² (`f64::INFINITY`: a pure rate limit).
    /// Default 200.
    pub max_accel: f64,
}

impl Default for SmoothingLimits {
    fn default() -> Self {
        SmoothingLimits {
            max_speed: 20.0,
            max_accel: 200.0,
        }
    }
}

/// Moves the applied offset towards a target within [`SmoothingLimits`] (module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Smoother {
    limits: SmoothingLimits,
    applied: PathOffset,
    velocity: PathOffset,
}

impl Smoother {
    /// At zero offset, at rest.
    pub fn new(limits: SmoothingLimits) -> Self {
        Smoother {
            limits,
            applied: PathOffset::ZERO,
            velocity: PathOffset::ZERO,
        }
    }

    /// The applied offset, mm.
    pub fn applied(&self) -> PathOffset {
        self.applied
    }

    /// The correction velocity, mm/s.
    pub fn velocity(&self) -> PathOffset {
        self.velocity
    }

    /// Back to zero offset, at rest.
    pub fn reset(&mut self) {
        self.applied = PathOffset::ZERO;
        self.velocity = PathOffset::ZERO;
    }

    /// Advance by `dt` seconds towards `target`; returns the applied offset. A non-finite
    /// target, a `dt` that is not positive and finite, or limits that are not positive
    /// (NaN included) leave the offset where it is.
    pub fn step(&mut self, target: PathOffset, dt: f64) -> PathOffset {
        let SmoothingLimits {
            max_speed: vmax,
            max_accel: amax,
        } = self.limits;
        if !target.is_finite()
            || !positive(dt)
            || !dt.is_finite()
            || !positive(vmax)
            || !positive(amax)
        {
            return self.applied;
        }
        let error = target.sub(self.applied);
        let dist = error.norm();
        let wanted = if dist > EPS_MM {
            let brake = if amax.is_finite() {
                braking_speed(dist, amax * dt * dt) / dt
            } else {
                f64::INFINITY
            };
            let speed = vmax.min(brake).min(dist / dt);
            error.scale(speed / dist)
        } else {
            PathOffset::ZERO
        };
        let mut dv = wanted.sub(self.velocity);
        let dv_max = amax * dt;
        let dv_norm = dv.norm();
        if dv_norm > dv_max {
            dv = dv.scale(dv_max / dv_norm);
        }
        let velocity = self.velocity.add(dv);
        let applied = self.applied.add(velocity.scale(dt));
        if !velocity.is_finite() || !applied.is_finite() {
            // Only reachable with absurd magnitudes; hold rather than emit NaN.
            self.velocity = PathOffset::ZERO;
            return self.applied;
        }
        self.velocity = velocity;
        self.applied = applied;
        // Land exactly. Braking along the exact curve arrives with a speed of at most
        // `dv_max`, so the next step can bring the velocity to zero.
        if target.sub(applied).norm() <= EPS_MM && velocity.norm() <= dv_max {
            self.applied = target;
        }
        self.applied
    }
}

/// The largest step `u` (a distance per step) from which steps `u, u − q, u − 2q, …` (all
/// positive ones) cover exactly `dist`, where `q = a·dt²` is the largest change of step
/// length. With `u = q·(n + f)`, `n` whole and `0 ≤ f ≤ 1`, the steps sum to
/// `q·((n + 1)·f + n(n + 1)/2)`; after one step the same holds with `n − 1`, so following
/// this speed brakes to rest exactly at the target.
fn braking_speed(dist: f64, q: f64) -> f64 {
    if !positive(q) || !q.is_finite() {
        return f64::INFINITY;
    }
    let d = dist / q;
    if !d.is_finite() {
        return f64::INFINITY;
    }
    let n = (((1.0 + 8.0 * d).sqrt() - 1.0) / 2.0).floor().max(0.0);
    let f = ((d - n * (n + 1.0) / 2.0) / (n + 1.0)).clamp(0.0, 1.0);
    q * (n + f)
}

/// At-point or look-ahead tracking (the `\APTR` and `\LATR` switches).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tracker {
    /// The sensor measures at the TCP: corrections apply at once.
    Aptr,
    /// The sensor measures `look_ahead` mm ahead of the TCP along the path.
    Latr {
        /// Distance of the sensor frame origin ahead of the TCP, mm (≥ 0).
        look_ahead: f64,
    },
}

/// Whether each correction is the total offset or adds to the previous one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CorrectionMode {
    /// Each correction is the total offset from the programmed path (default).
    #[default]
    Absolute,
    /// Each correction adds to the previous total.
    Incremental,
}

/// Everything a [`PathCorrector`] needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathCorrConfig {
    /// APTR or LATR.
    pub tracker: Tracker,
    /// Absolute or incremental corrections.
    pub mode: CorrectionMode,
    /// Rejection limits.
    pub limits: CorrectionLimits,
    /// Smoothing limits.
    pub smoothing: SmoothingLimits,
    /// Size of the LATR queue and of the TCP arc-length history (samples). Default 512
    /// (about 2 s of history at a 4 ms step).
    pub capacity: usize,
}

impl PathCorrConfig {
    /// Defaults for an at-point tracker.
    pub fn aptr() -> Self {
        PathCorrConfig {
            tracker: Tracker::Aptr,
            mode: CorrectionMode::Absolute,
            limits: CorrectionLimits::default(),
            smoothing: SmoothingLimits::default(),
            capacity: 512,
        }
    }

    /// Defaults for a look-ahead tracker `look_ahead` mm ahead of the TCP.
    pub fn latr(look_ahead: f64) -> Self {
        PathCorrConfig {
            tracker: Tracker::Latr { look_ahead },
            ..Self::aptr()
        }
    }

    /// Check every value.
    pub fn validate(&self) -> Result<(), PathCorrConfigError> {
        let bad = |name: &'static str, value: f64, expected: &'static str| {
            Err(PathCorrConfigError {
                name,
                value,
                expected,
            })
        };
        let pos_text = "a positive number";
        let l = &self.limits;
        let s = &self.smoothing;
        if !(positive(l.max_offset) && l.max_offset.is_finite()) {
            return bad("max_offset", l.max_offset, "a positive finite number (mm)");
        }
        if !positive(l.max_age) {
            return bad("max_age", l.max_age, pos_text);
        }
        if !positive(s.max_speed) {
            return bad("max_speed", s.max_speed, pos_text);
        }
        if !positive(s.max_accel) {
            return bad("max_accel", s.max_accel, pos_text);
        }
        if let Tracker::Latr { look_ahead } = self.tracker
            && !non_negative_finite(look_ahead)
        {
            return bad(
                "look_ahead",
                look_ahead,
                "a distance ≥ 0 mm (a look-ahead sensor measures ahead of the TCP)",
            );
        }
        if !(2..=1 << 16).contains(&self.capacity) {
            return bad("capacity", self.capacity as f64, "2 to 65536 samples");
        }
        Ok(())
    }
}

/// A [`PathCorrConfig`] value that cannot be used.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("path correction {name} = {value}: expected {expected}")]
pub struct PathCorrConfigError {
    /// The field.
    pub name: &'static str,
    /// Its value.
    pub value: f64,
    /// What it must be.
    pub expected: &'static str,
}

/// A correction and the arc length at which it is (or was) the target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scheduled {
    /// Arc length of the TCP along the programmed path, mm.
    pub s: f64,
    /// The total correction there.
    pub offset: PathOffset,
}

/// The path-correction state of one corrected sequence (module doc: model).
///
/// Per motion step call [`PathCorrector::step`] with the time and the TCP's arc length
/// along the programmed path; it returns the offset to add (through
/// [`PathFrame::to_world`]). Per sensor reply call [`PathCorrector::measurement`].
#[derive(Clone, Debug)]
pub struct PathCorrector {
    config: PathCorrConfig,
    enabled: bool,
    /// `(t, s)` samples of the TCP, oldest first (LATR only).
    history: VecDeque<(f64, f64)>,
    /// Queued LATR corrections, ascending `s`.
    pending: VecDeque<Scheduled>,
    /// The last point passed.
    anchor: Scheduled,
    /// The latest total correction received (for incremental mode).
    total: PathOffset,
    target: PathOffset,
    smoother: Smoother,
    last: Option<(f64, f64)>,
    overflows: u64,
}

impl PathCorrector {
    /// A corrector at zero offset, arc length 0 (see [`PathCorrector::start`]). Allocates
    /// its buffers here, once.
    pub fn new(config: PathCorrConfig) -> Result<Self, PathCorrConfigError> {
        config.validate()?;
        Ok(PathCorrector {
            config,
            enabled: true,
            history: VecDeque::with_capacity(config.capacity),
            pending: VecDeque::with_capacity(config.capacity),
            anchor: Scheduled {
                s: 0.0,
                offset: PathOffset::ZERO,
            },
            total: PathOffset::ZERO,
            target: PathOffset::ZERO,
            smoother: Smoother::new(config.smoothing),
            last: None,
            overflows: 0,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &PathCorrConfig {
        &self.config
    }

    /// Begin a corrected sequence at time `now` (s) and arc length `s` (mm): zero offset,
    /// nothing queued.
    pub fn start(&mut self, now: f64, s: f64) {
        self.history.clear();
        self.pending.clear();
        let s = if s.is_finite() { s } else { 0.0 };
        self.anchor = Scheduled {
            s,
            offset: PathOffset::ZERO,
        };
        self.total = PathOffset::ZERO;
        self.target = PathOffset::ZERO;
        self.smoother.reset();
        self.last = None;
        if now.is_finite() {
            self.record(now, s);
        }
    }

    /// Change the look-ahead distance (mm) of a LATR tracker, e.g. when the path direction
    /// relative to the sensor changes; ignored for APTR and for a negative or non-finite
    /// distance.
    pub fn set_look_ahead(&mut self, look_ahead: f64) {
        if let Tracker::Latr { look_ahead: d } = &mut self.config.tracker
            && non_negative_finite(look_ahead)
        {
            *d = look_ahead;
        }
    }

    /// Switch correction on or off (`\NoCorr`): while off, the target is zero (the applied
    /// offset ramps out) and measurements are checked but not used.
    pub fn set_enabled(&mut self, enabled: bool) {
        self.enabled = enabled;
    }

    /// The offset applied at the last step.
    pub fn applied(&self) -> PathOffset {
        self.smoother.applied()
    }

    /// The target at the last step (before smoothing).
    pub fn target(&self) -> PathOffset {
        self.target
    }

    /// Corrections queued for a later arc length (LATR).
    pub fn pending(&self) -> usize {
        self.pending.len()
    }

    /// How many queued corrections were dropped because the queue was full.
    pub fn overflows(&self) -> u64 {
        self.overflows
    }

    fn record(&mut self, now: f64, s: f64) {
        if !matches!(self.config.tracker, Tracker::Latr { .. }) {
            return;
        }
        if self.history.back().is_some_and(|&(t, _)| now <= t) {
            return;
        }
        if self.history.len() >= self.config.capacity {
            self.history.pop_front();
        }
        self.history.push_back((now, s));
    }

    /// The TCP's arc length at time `t` from the history (clamped to its ends).
    fn s_at(&self, t: f64) -> f64 {
        let fallback = self.last.map(|(_, s)| s).unwrap_or(self.anchor.s);
        let mut later: Option<(f64, f64)> = None;
        for &(ti, si) in self.history.iter().rev() {
            if ti <= t {
                return match later {
                    Some((tl, sl)) if tl > ti => si + (sl - si) * (t - ti) / (tl - ti),
                    _ => si,
                };
            }
            later = Some((ti, si));
        }
        later.map(|(_, s)| s).unwrap_or(fallback)
    }

    /// A sensor correction `pos` (x, y, z in the path frame, mm; x ignored) received at
    /// `now` (s), measured `age` seconds earlier. Returns where it is scheduled, or why it
    /// was rejected (the previous corrections stay in force).
    pub fn measurement(
        &mut self,
        now: f64,
        pos: [f64; 3],
        age: f64,
    ) -> Result<Scheduled, Rejection> {
        let offset = check_correction(pos, age, &self.config.limits)?;
        let total = match self.config.mode {
            CorrectionMode::Absolute => offset,
            CorrectionMode::Incremental => {
                let t = self.total.add(offset);
                check_magnitude(t, &self.config.limits)?;
                t
            }
        };
        let s_now = self.last.map(|(_, s)| s).unwrap_or(self.anchor.s);
        let s_apply = match self.config.tracker {
            Tracker::Aptr => s_now,
            Tracker::Latr { look_ahead } => {
                let t = if now.is_finite() { now - age } else { f64::NAN };
                let s = if t.is_finite() { self.s_at(t) } else { s_now };
                s + look_ahead
            }
        };
        self.total = total;
        let entry = Scheduled {
            s: s_apply,
            offset: total,
        };
        if !self.enabled {
            return Ok(entry);
        }
        while self.pending.back().is_some_and(|p| p.s >= s_apply) {
            self.pending.pop_back();
        }
        if s_apply <= s_now {
            self.anchor = Scheduled {
                s: s_now,
                offset: total,
            };
            self.target = total;
        } else {
            if self.pending.len() >= self.config.capacity
                && let Some(front) = self.pending.pop_front()
            {
                self.anchor = front;
                self.overflows = self.overflows.saturating_add(1);
            }
            self.pending.push_back(entry);
        }
        Ok(entry)
    }

    /// One motion step at time `now` (s) with the TCP at arc length `s` (mm) along the
    /// programmed path: returns the path-frame offset to apply. The first step after
    /// [`PathCorrector::start`] (or a step with a non-increasing or non-finite time) does
    /// not move the offset.
    pub fn step(&mut self, now: f64, s: f64) -> PathOffset {
        let s = if s.is_finite() {
            s
        } else {
            self.last.map(|(_, s)| s).unwrap_or(self.anchor.s)
        };
        let dt = match self.last {
            Some((t0, _)) if now.is_finite() => now - t0,
            _ => 0.0,
        };
        if now.is_finite() && dt >= 0.0 {
            self.record(now, s);
            self.last = Some((now, s));
        }
        while let Some(front) = self.pending.front().copied() {
            if front.s > s {
                break;
            }
            self.anchor = front;
            self.pending.pop_front();
        }
        self.target = if !self.enabled {
            PathOffset::ZERO
        } else {
            match self.pending.front() {
                None => self.anchor.offset,
                Some(next) => {
                    let span = next.s - self.anchor.s;
                    if span > EPS_MM {
                        let t = ((s - self.anchor.s) / span).clamp(0.0, 1.0);
                        PathOffset::lerp(self.anchor.offset, next.offset, t)
                    } else {
                        self.anchor.offset
                    }
                }
            }
        };
        self.smoother.step(self.target, dt)
    }
}

/// A seam's offset from the programmed path in the path frame as a function of arc length
/// from the start of the corrected sequence (mm); the module doc gives the text form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SeamProfile {
    /// `const:y=…,z=…`: the same offset everywhere.
    Const {
        /// y offset, mm.
        y: f64,
        /// z offset, mm.
        z: f64,
    },
    /// `ramp:y=…,z=…,len=…`: zero at the start, growing linearly to `(y, z)` at `len`, then
    /// constant.
    Ramp {
        /// y offset at the end of the ramp, mm.
        y: f64,
        /// z offset at the end of the ramp, mm.
        z: f64,
        /// Ramp length, mm (> 0).
        len: f64,
    },
    /// `sine:y=…,z=…,period=…[,phase=…]`: `(y, z) · sin(360° · s / period + phase)`.
    Sine {
        /// y amplitude, mm.
        y: f64,
        /// z amplitude, mm.
        z: f64,
        /// Period along the path, mm (> 0).
        period: f64,
        /// Phase, degrees.
        phase: f64,
    },
}

impl SeamProfile {
    /// The seam offset at arc length `s` (mm); zero for a non-finite `s`.
    pub fn offset_at(&self, s: f64) -> PathOffset {
        if !s.is_finite() {
            return PathOffset::ZERO;
        }
        match *self {
            SeamProfile::Const { y, z } => PathOffset::new(y, z),
            SeamProfile::Ramp { y, z, len } => {
                let k = (s / len).clamp(0.0, 1.0);
                PathOffset::new(y * k, z * k)
            }
            SeamProfile::Sine {
                y,
                z,
                period,
                phase,
            } => {
                // Cycles along the path plus the phase as a fraction of a cycle.
                let cycles = s / period + phase / 360.0;
                let k = (std::f64::consts::TAU * cycles.fract()).sin();
                PathOffset::new(y * k, z * k)
            }
        }
    }

    /// What a simulated sensor of kind `tracker` reports with the TCP at arc length
    /// `tcp_s`: the seam under the sensor (at the TCP for APTR, `look_ahead` ahead for
    /// LATR).
    pub fn sensed_at(&self, tracker: Tracker, tcp_s: f64) -> PathOffset {
        match tracker {
            Tracker::Aptr => self.offset_at(tcp_s),
            Tracker::Latr { look_ahead } => self.offset_at(tcp_s + look_ahead),
        }
    }
}

/// Why a seam pattern text cannot be read.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SeamError {
    /// Nothing given.
    #[error("the pattern is empty")]
    Empty,
    /// Not const, ramp or sine.
    #[error("`{0}` is not a seam pattern; use const, ramp or sine")]
    UnknownKind(String),
    /// A key the kind does not take.
    #[error("{kind} takes {allowed}, not `{key}`")]
    UnknownKey {
        /// The kind.
        kind: &'static str,
        /// The key as written.
        key: String,
        /// The keys it takes.
        allowed: &'static str,
    },
    /// Two commas with nothing between them.
    #[error("an empty item between commas")]
    EmptyItem,
    /// `key` without `=value`.
    #[error("`{0}` needs a value: `{0}=NUMBER`")]
    MissingValue(String),
    /// A value that is not a finite number.
    #[error("`{key}={value}`: not a number")]
    BadNumber {
        /// The key.
        key: String,
        /// The value as written.
        value: String,
    },
    /// The same key twice.
    #[error("`{0}` is given twice")]
    Duplicate(String),
    /// A required key is missing.
    #[error("{kind} needs `{key}=`")]
    Missing {
        /// The kind.
        kind: &'static str,
        /// The key.
        key: &'static str,
    },
    /// A length that must be positive.
    #[error("`{key}` must be greater than 0 mm, not {value}")]
    NotPositive {
        /// The key.
        key: &'static str,
        /// The value.
        value: String,
    },
}

/// A seam pattern text that cannot be read, with the text.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "bad seam pattern `{input}`: {error} (examples: `const:y=3,z=-2`, `ramp:y=5,z=0,len=400`, `sine:y=2,z=0,period=100`)"
)]
pub struct SeamParseError {
    /// The text.
    pub input: String,
    /// What is wrong.
    pub error: SeamError,
}

impl SeamProfile {
    /// Read the text form (module doc); kinds and keys are case-insensitive, spaces around
    /// them are ignored, missing `y`/`z`/`phase` are 0.
    pub fn parse(text: &str) -> Result<SeamProfile, SeamParseError> {
        Self::parse_inner(text).map_err(|error| SeamParseError {
            input: text.to_string(),
            error,
        })
    }

    fn parse_inner(text: &str) -> Result<SeamProfile, SeamError> {
        let text = text.trim();
        if text.is_empty() {
            return Err(SeamError::Empty);
        }
        let (kind, params) = match text.split_once(':') {
            Some((k, p)) => (k.trim(), p.trim()),
            None => (text, ""),
        };
        let (kind, allowed): (&'static str, &'static str) = match kind.to_ascii_lowercase().as_str()
        {
            "const" => ("const", "y and z"),
            "ramp" => ("ramp", "y, z and len"),
            "sine" => ("sine", "y, z, period and phase"),
            _ => return Err(SeamError::UnknownKind(kind.to_string())),
        };
        // Values of y, z, len, period, phase.
        let mut values: [Option<f64>; 5] = [None; 5];
        if !params.is_empty() {
            for part in params.split(',').map(str::trim) {
                if part.is_empty() {
                    return Err(SeamError::EmptyItem);
                }
                let Some((key, value)) = part.split_once('=').map(|(k, v)| (k.trim(), v.trim()))
                else {
                    return Err(SeamError::MissingValue(part.to_string()));
                };
                let slot = match (kind, key.to_ascii_lowercase().as_str()) {
                    (_, "y") => 0,
                    (_, "z") => 1,
                    ("ramp", "len") => 2,
                    ("sine", "period") => 3,
                    ("sine", "phase") => 4,
                    _ => {
                        return Err(SeamError::UnknownKey {
                            kind,
                            key: key.to_string(),
                            allowed,
                        });
                    }
                };
                let number = value
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| SeamError::BadNumber {
                        key: key.to_string(),
                        value: value.to_string(),
                    })?;
                match values.get_mut(slot) {
                    Some(Some(_)) => return Err(SeamError::Duplicate(key.to_string())),
                    Some(v) => *v = Some(number),
                    None => {}
                }
            }
        }
        let get = |i: usize| values.get(i).copied().flatten();
        let y = get(0).unwrap_or(0.0);
        let z = get(1).unwrap_or(0.0);
        let required_positive = |i: usize, key: &'static str| -> Result<f64, SeamError> {
            match get(i) {
                None => Err(SeamError::Missing { kind, key }),
                Some(v) if v > 0.0 => Ok(v),
                Some(v) => Err(SeamError::NotPositive {
                    key,
                    value: v.to_string(),
                }),
            }
        };
        Ok(match kind {
            "const" => SeamProfile::Const { y, z },
            "ramp" => SeamProfile::Ramp {
                y,
                z,
                len: required_positive(2, "len")?,
            },
            _ => SeamProfile::Sine {
                y,
                z,
                period: required_positive(3, "period")?,
                phase: get(4).unwrap_or(0.0),
            },
        })
    }
}

impl FromStr for SeamProfile {
    type Err = SeamParseError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        SeamProfile::parse(s)
    }
}

impl fmt::Display for SeamProfile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            SeamProfile::Const { y, z } => write!(f, "const:y={y},z={z}"),
            SeamProfile::Ramp { y, z, len } => write!(f, "ramp:y={y},z={z},len={len}"),
            SeamProfile::Sine {
                y,
                z,
                period,
                phase,
            } => {
                write!(f, "sine:y={y},z={z},period={period}")?;
                if phase != 0.0 {
                    write!(f, ",phase={phase}")?;
                }
                Ok(())
            }
        }
    }
}

#[cfg(test)]
#[allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const TOL: f64 = 1e-12;

    fn v(x: f64, y: f64, z: f64) -> Vec3 {
        Vec3::new(x, y, z)
    }

    fn close(a: &Vec3, b: &Vec3, tol: f64) -> bool {
        (a - b).norm() <= tol
    }

    fn assert_orthonormal_right_handed(f: &PathFrame) {
        for a in [f.x, f.y, f.z] {
            assert!(a.iter().all(|c| c.is_finite()), "{f:?}");
            assert!((a.norm() - 1.0).abs() < 1e-9, "{f:?}");
        }
        assert!(f.x.dot(&f.y).abs() < 1e-9, "{f:?}");
        assert!(f.x.dot(&f.z).abs() < 1e-9, "{f:?}");
        assert!(f.y.dot(&f.z).abs() < 1e-9, "{f:?}");
        assert!(close(&f.x.cross(&f.y), &f.z, 1e-9), "{f:?}");
        let det = nalgebra::Matrix3::from_columns(&[f.x, f.y, f.z]).determinant();
        assert!((det - 1.0).abs() < 1e-9, "{f:?}");
    }

    // ---- path frame ----

    #[test]
    fn frame_signs_are_pinned() {
        // Tool pointing down, path along +X: y = +Y, z = +Z (away from the work).
        let f = PathFrame::new(v(10.0, 0.0, 0.0), v(0.0, 0.0, -1.0), None);
        assert_eq!(f.basis, FrameBasis::Regular);
        assert!(close(&f.x, &Vec3::x(), TOL));
        assert!(close(&f.y, &Vec3::y(), TOL));
        assert!(close(&f.z, &Vec3::z(), TOL));
        // Path along +Y: y = Y × (−Z) = −X.
        let f = PathFrame::new(v(0.0, 3.0, 0.0), v(0.0, 0.0, -2.0), None);
        assert!(close(&f.y, &-Vec3::x(), TOL));
        assert!(close(&f.z, &Vec3::z(), TOL));
        // With the tool axis perpendicular to the path, z = −tool z exactly.
        let tz = v(0.0, 0.5, -1.0).normalize();
        let f = PathFrame::new(v(1.0, 0.0, 0.0), tz, None);
        assert!(close(&f.z, &-tz, 1e-12));
        assert_orthonormal_right_handed(&f);
        // A tilted tool: y is still x × tool z, normalised.
        let t = v(1.0, 1.0, 0.0);
        let tz = v(0.3, -0.2, -1.0);
        let f = PathFrame::new(t, tz, None);
        assert!(close(&f.y, &t.cross(&tz).normalize(), 1e-12));
        assert!(close(&f.x, &t.normalize(), 1e-12));
        assert_orthonormal_right_handed(&f);
    }

    #[test]
    fn correction_to_world_and_back() {
        let f = PathFrame::new(v(1.0, 0.0, 0.0), v(0.0, 0.0, -1.0), None);
        let w = f.to_world(PathOffset::new(3.0, -2.0));
        assert!(close(&w, &v(0.0, 3.0, -2.0), TOL));
        let back = f.offset_of(&(w + v(7.0, 0.0, 0.0)));
        assert_eq!(back, PathOffset::new(3.0, -2.0));
        assert_eq!(f.along(&v(7.0, 1.0, 1.0)), 7.0);
        let tcp = v(100.0, 0.0, 0.0);
        assert_eq!(look_ahead_distance(&f, &tcp, &v(150.0, 20.0, 5.0)), 50.0);
        assert_eq!(look_ahead_distance(&f, &tcp, &v(90.0, 0.0, 0.0)), -10.0);
        assert_eq!(look_ahead_distance(&f, &tcp, &v(f64::NAN, 0.0, 0.0)), 0.0);
    }

    #[test]
    fn tangent_along_tool_z() {
        let f = PathFrame::new(v(0.0, 0.0, -5.0), v(0.0, 0.0, -1.0), None);
        assert_eq!(f.basis, FrameBasis::TangentAlongToolZ);
        assert_orthonormal_right_handed(&f);
        assert!(close(&f.x, &-Vec3::z(), TOL));
        // With a previous frame, its y is kept (made perpendicular to x).
        let prev = PathFrame::new(v(1.0, 0.0, -0.2), v(0.0, 0.0, -1.0), None);
        let f = PathFrame::new(v(0.0, 0.0, -1.0), v(0.0, 0.0, -1.0), Some(&prev));
        assert_eq!(f.basis, FrameBasis::TangentAlongToolZ);
        assert_orthonormal_right_handed(&f);
        assert!(close(&f.y, &prev.y, 1e-12));
        // Nearly parallel (below PARALLEL_SIN) counts as parallel.
        let f = PathFrame::new(v(1e-8, 0.0, 1.0), v(0.0, 0.0, 1.0), None);
        assert_eq!(f.basis, FrameBasis::TangentAlongToolZ);
        assert_orthonormal_right_handed(&f);
        // A missing tool axis takes the same fallback.
        let f = PathFrame::new(v(1.0, 0.0, 0.0), v(f64::NAN, 0.0, 0.0), None);
        assert_eq!(f.basis, FrameBasis::NoToolZ);
        assert_orthonormal_right_handed(&f);
    }

    #[test]
    fn no_tangent() {
        let prev = PathFrame::new(v(0.0, 1.0, 0.0), v(0.0, 0.0, -1.0), None);
        let f = PathFrame::new(Vec3::zeros(), v(0.0, 0.0, -1.0), Some(&prev));
        assert_eq!(f.basis, FrameBasis::NoTangent);
        assert_eq!((f.x, f.y, f.z), (prev.x, prev.y, prev.z));
        // Without a previous frame: world X made perpendicular to the tool axis.
        let f = PathFrame::new(v(0.0, 0.0, 1e-12), v(0.0, 0.0, -1.0), None);
        assert_eq!(f.basis, FrameBasis::NoTangent);
        assert!(close(&f.x, &Vec3::x(), TOL) && close(&f.y, &Vec3::y(), TOL));
        // Tool along X: world Y is used.
        let f = PathFrame::new(v(f64::INFINITY, 0.0, 0.0), v(1.0, 0.0, 0.0), None);
        assert_eq!(f.basis, FrameBasis::NoTangent);
        assert!(close(&f.x, &Vec3::y(), TOL));
        assert_orthonormal_right_handed(&f);
        // Nothing at all: the world frame.
        let f = PathFrame::new(Vec3::zeros(), Vec3::zeros(), None);
        assert_eq!(f, PathFrame::world());
        let f = PathFrame::new(v(f64::NAN, 1.0, 1.0), v(0.0, f64::NAN, 0.0), None);
        assert_eq!(f.basis, FrameBasis::World);
        // A corrupt previous frame is not trusted.
        let bad = PathFrame {
            x: v(f64::NAN, 0.0, 0.0),
            ..PathFrame::world()
        };
        let f = PathFrame::new(Vec3::zeros(), v(0.0, 0.0, -1.0), Some(&bad));
        assert_orthonormal_right_handed(&f);
    }

    fn component() -> impl Strategy<Value = f64> {
        prop_oneof![
            8 => -1000.0..1000.0f64,
            1 => Just(0.0),
            1 => Just(1e-10),
            1 => Just(f64::NAN),
            1 => Just(f64::INFINITY),
        ]
    }

    fn vector() -> impl Strategy<Value = Vec3> {
        (component(), component(), component()).prop_map(|(a, b, c)| v(a, b, c))
    }

    proptest! {
        #[test]
        fn frames_are_always_orthonormal_and_right_handed(
            t in vector(), tz in vector(), pt in vector(), ptz in vector(), with_prev: bool,
        ) {
            let prev = PathFrame::new(pt, ptz, None);
            assert_orthonormal_right_handed(&prev);
            let f = PathFrame::new(t, tz, with_prev.then_some(&prev));
            assert_orthonormal_right_handed(&f);
            if f.basis == FrameBasis::Regular {
                let x = t.normalize();
                prop_assert!(close(&f.x, &x, 1e-9));
                prop_assert!(close(&f.y, &x.cross(&tz).normalize(), 1e-6));
            }
        }
    }

    // ---- checking corrections ----

    #[test]
    fn rejections() {
        let l = CorrectionLimits::default();
        // x is ignored.
        assert_eq!(
            check_correction([99.0, 3.0, -2.0], 0.05, &l),
            Ok(PathOffset::new(3.0, -2.0))
        );
        // ... but a non-finite x marks a corrupt message.
        assert!(matches!(
            check_correction([f64::NAN, 3.0, -2.0], 0.0, &l),
            Err(Rejection::NotFinite { axis: 'x', .. })
        ));
        let e = check_correction([0.0, f64::INFINITY, 0.0], 0.0, &l).unwrap_err();
        assert_eq!(
            e.to_string(),
            "path correction y is not a finite number (inf)"
        );
        assert!(matches!(
            check_correction([0.0, 0.0, f64::NEG_INFINITY], 0.0, &l),
            Err(Rejection::NotFinite { axis: 'z', .. })
        ));
        // Exactly at the limit is allowed, just above is not.
        assert!(check_correction([0.0, 60.0, 80.0], 0.0, &l).is_ok());
        let e = check_correction([0.0, 60.0, 80.01], 0.0, &l).unwrap_err();
        assert!(matches!(e, Rejection::TooLarge { limit, .. } if limit == 100.0));
        assert_eq!(
            e.to_string(),
            "path correction of 100.008 mm exceeds the limit of 100 mm"
        );
        assert!(matches!(
            check_correction([0.0; 3], -0.001, &l),
            Err(Rejection::BadAge { .. })
        ));
        assert!(matches!(
            check_correction([0.0; 3], f64::NAN, &l),
            Err(Rejection::BadAge { .. })
        ));
        assert_eq!(
            check_correction([0.0; 3], 2.5, &l),
            Err(Rejection::TooOld {
                age: 2.5,
                limit: 2.0
            })
        );
        assert_eq!(
            Rejection::TooOld {
                age: 2.5,
                limit: 2.0
            }
            .to_string(),
            "path correction is 2.5 s old; the limit is 2 s"
        );
    }

    // ---- smoothing ----

    fn dist(a: PathOffset, b: PathOffset) -> f64 {
        a.sub(b).norm()
    }

    #[test]
    fn smoother_reaches_the_target_without_overshoot() {
        let limits = SmoothingLimits::default();
        let mut sm = Smoother::new(limits);
        let target = PathOffset::new(3.0, -2.0);
        let d = target.norm();
        let dt = 0.004;
        let mut prev = sm.applied();
        let mut steps = 0;
        while sm.applied() != target {
            let a = sm.step(target, dt);
            // Monotonic approach along the straight line to the target.
            let along = (a.y * target.y + a.z * target.z) / d;
            let across = (a.y * target.z - a.z * target.y).abs() / d;
            assert!(along <= d + 1e-12 && across < 1e-9, "{a:?}");
            assert!(dist(a, target) <= dist(prev, target) + 1e-12);
            assert!(dist(a, prev) <= limits.max_speed * dt + 1e-12);
            prev = a;
            steps += 1;
            assert!(steps < 10_000);
        }
        // Time-optimal within a few steps: d/vmax + vmax/amax.
        let t = steps as f64 * dt;
        let ideal = d / limits.max_speed + limits.max_speed / limits.max_accel;
        assert!(t <= ideal + 5.0 * dt, "{t} vs {ideal}");
        assert!(t >= d / limits.max_speed);
        // Holding the target keeps it exactly, and the next step is at rest.
        assert_eq!(sm.step(target, dt), target);
        assert_eq!(sm.velocity(), PathOffset::ZERO);
        assert_eq!(sm.step(target, dt), target);
    }

    #[test]
    fn pure_rate_limit() {
        let mut sm = Smoother::new(SmoothingLimits {
            max_speed: 10.0,
            max_accel: f64::INFINITY,
        });
        let target = PathOffset::new(0.0, 1.0);
        assert!((sm.step(target, 0.01).z - 0.1).abs() < 1e-12);
        assert!((sm.step(target, 0.01).z - 0.2).abs() < 1e-12);
        for _ in 0..20 {
            sm.step(target, 0.01);
        }
        assert_eq!(sm.applied(), target);
        // No limits at all: a jump.
        let mut sm = Smoother::new(SmoothingLimits {
            max_speed: f64::INFINITY,
            max_accel: f64::INFINITY,
        });
        assert_eq!(sm.step(target, 0.004), target);
    }

    #[test]
    fn smoother_holds_on_bad_input() {
        let mut sm = Smoother::new(SmoothingLimits::default());
        let target = PathOffset::new(1.0, 0.0);
        sm.step(target, 0.004);
        let a = sm.applied();
        for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(sm.step(target, dt), a);
        }
        assert_eq!(sm.step(PathOffset::new(f64::NAN, 0.0), 0.004), a);
        for limits in [
            SmoothingLimits {
                max_speed: f64::NAN,
                max_accel: 1.0,
            },
            SmoothingLimits {
                max_speed: 1.0,
                max_accel: 0.0,
            },
        ] {
            let mut sm = Smoother::new(limits);
            assert_eq!(sm.step(target, 0.004), PathOffset::ZERO);
        }
        let mut sm = Smoother::new(SmoothingLimits::default());
        let huge = PathOffset::new(f64::MAX, f64::MAX);
        let a = sm.step(huge, 0.004);
        assert!(a.is_finite());
        sm.reset();
        assert_eq!(sm.applied(), PathOffset::ZERO);
    }

    fn offset() -> impl Strategy<Value = PathOffset> {
        (-50.0..50.0f64, -50.0..50.0f64).prop_map(|(y, z)| PathOffset::new(y, z))
    }

    proptest! {
        /// Whatever the targets and steps, no step is longer than max_speed·dt and no
        /// velocity change larger than max_accel·dt.
        #[test]
        fn smoothing_never_exceeds_its_limits(
            vmax in 0.5..100.0f64,
            amax in prop_oneof![1.0..2000.0f64, Just(f64::INFINITY)],
            moves in proptest::collection::vec((offset(), 0.0005..0.1f64, 1..40usize), 1..12),
        ) {
            let mut sm = Smoother::new(SmoothingLimits { max_speed: vmax, max_accel: amax });
            for (target, dt, n) in moves {
                for _ in 0..n {
                    let (a0, v0) = (sm.applied(), sm.velocity());
                    let a1 = sm.step(target, dt);
                    let v1 = sm.velocity();
                    prop_assert!(a1.is_finite() && v1.is_finite());
                    prop_assert!(dist(a1, a0) <= vmax * dt * (1.0 + 1e-9) + 1e-9);
                    prop_assert!(v1.norm() <= vmax * (1.0 + 1e-9));
                    if amax.is_finite() {
                        prop_assert!(dist(v1, v0) <= amax * dt * (1.0 + 1e-9) + 1e-9);
                    }
                }
            }
        }
    }

    // ---- the corrector ----

    #[test]
    fn config_validation() {
        assert!(PathCorrConfig::aptr().validate().is_ok());
        assert!(PathCorrConfig::latr(50.0).validate().is_ok());
        let mut c = PathCorrConfig::latr(-1.0);
        let e = PathCorrector::new(c).unwrap_err();
        assert_eq!(e.name, "look_ahead");
        c = PathCorrConfig::aptr();
        c.limits.max_offset = f64::INFINITY;
        assert_eq!(c.validate().unwrap_err().name, "max_offset");
        c = PathCorrConfig::aptr();
        c.limits.max_age = 0.0;
        assert_eq!(c.validate().unwrap_err().name, "max_age");
        c = PathCorrConfig::aptr();
        c.smoothing.max_speed = f64::NAN;
        assert_eq!(c.validate().unwrap_err().name, "max_speed");
        c = PathCorrConfig::aptr();
        c.smoothing.max_accel = -1.0;
        assert_eq!(
            c.validate().unwrap_err().to_string(),
            "path correction max_accel = -1: expected a positive number"
        );
        c = PathCorrConfig::aptr();
        c.capacity = 1;
        assert_eq!(c.validate().unwrap_err().name, "capacity");
    }

    /// The acceptance case of the path-correction issue: a straight 400 mm move at 10 mm/s
    /// with a constant simulated seam offset y = 3, z = −2 from an at-point sensor
    /// answering every 48 ms; the correction ramps in within the limits and holds.
    #[test]
    fn aptr_constant_seam_over_400_mm() {
        let seam = SeamProfile::parse("const:y=3,z=-2").unwrap();
        let cfg = PathCorrConfig::aptr();
        let mut pc = PathCorrector::new(cfg).unwrap();
        let dt = 0.004;
        let speed = 10.0;
        pc.start(0.0, 0.0);
        let mut prev = PathOffset::ZERO;
        let mut max_step: f64 = 0.0;
        let ticks = (400.0 / speed / dt) as usize;
        for i in 1..=ticks {
            let now = i as f64 * dt;
            let s = speed * now;
            if i % 12 == 0 {
                let m = seam.sensed_at(cfg.tracker, s);
                pc.measurement(now, [0.0, m.y, m.z], 0.0).unwrap();
            }
            let a = pc.step(now, s);
            max_step = max_step.max(dist(a, prev));
            prev = a;
        }
        assert!(max_step <= cfg.smoothing.max_speed * dt + 1e-12);
        assert!(dist(pc.applied(), PathOffset::new(3.0, -2.0)) < 1e-9);
        // The world offset at the end, with the tool pointing down on a path along +X.
        let f = PathFrame::new(v(1.0, 0.0, 0.0), v(0.0, 0.0, -1.0), None);
        assert!(close(&f.to_world(pc.applied()), &v(0.0, 3.0, -2.0), 1e-9));
    }

    #[test]
    fn aptr_applies_at_once() {
        let mut pc = PathCorrector::new(PathCorrConfig::aptr()).unwrap();
        pc.start(0.0, 0.0);
        pc.step(0.004, 0.04);
        let sch = pc.measurement(0.005, [0.0, 1.0, 0.0], 0.5).unwrap();
        assert_eq!(sch.s, 0.04);
        assert_eq!(pc.pending(), 0);
        pc.step(0.008, 0.08);
        assert_eq!(pc.target(), PathOffset::new(1.0, 0.0));
        assert!(pc.applied().y > 0.0 && pc.applied().y < 1.0);
    }

    /// A seam that steps from 0 to 3 mm at s = 100 mm, seen by a look-ahead sensor 50 mm
    /// ahead whose messages arrive 30 ms after measuring: the target steps where the seam
    /// does, not where the sensor saw it.
    #[test]
    fn latr_applies_at_the_right_arc_length() {
        let look_ahead = 50.0;
        let mut cfg = PathCorrConfig::latr(look_ahead);
        cfg.smoothing.max_speed = f64::INFINITY;
        cfg.smoothing.max_accel = f64::INFINITY;
        let mut pc = PathCorrector::new(cfg).unwrap();
        let seam = |s: f64| if s >= 100.0 { 3.0 } else { 0.0 };
        let (dt, speed, age) = (0.004, 10.0, 0.030);
        let s_of = |t: f64| speed * t;
        pc.start(0.0, 0.0);
        let sample_spacing = speed * 0.048;
        let mut checked = 0;
        for i in 1..=5000 {
            let now = i as f64 * dt;
            let s = s_of(now);
            // Every 48 ms a message arrives about what the sensor saw `age` earlier.
            if i % 12 == 0 {
                let t_meas = now - age;
                let y = seam(s_of(t_meas) + look_ahead);
                let sch = pc.measurement(now, [0.0, y, 0.0], age).unwrap();
                assert!((sch.s - (s_of(t_meas) + look_ahead)).abs() < 1e-9);
            }
            let a = pc.step(now, s);
            if s < 100.0 - sample_spacing {
                assert_eq!(a.y, 0.0, "s = {s}");
                checked += 1;
            } else if s >= 100.0 + sample_spacing {
                assert_eq!(a.y, 3.0, "s = {s}");
                checked += 1;
            }
        }
        assert!(checked > 4900);
    }

    /// A ramp seam seen through the look-ahead delay is reproduced exactly (linear
    /// interpolation between queued points), however late the messages arrive. Ignoring
    /// the age would misplace every point by 1 mm, an error of 0.5 mm on this slope.
    #[test]
    fn latr_reproduces_a_ramp_seam() {
        let look_ahead = 40.0;
        let seam = SeamProfile::parse("ramp:y=50,z=-25,len=100").unwrap();
        let mut cfg = PathCorrConfig::latr(look_ahead);
        cfg.smoothing.max_speed = f64::INFINITY;
        cfg.smoothing.max_accel = f64::INFINITY;
        let mut pc = PathCorrector::new(cfg).unwrap();
        let (dt, speed, age) = (0.004, 10.0, 0.1);
        pc.start(0.0, 0.0);
        let mut worst: f64 = 0.0;
        for i in 1..=3000 {
            let now = i as f64 * dt;
            let s = speed * now;
            if i % 12 == 0 {
                let sensed = seam.sensed_at(cfg.tracker, speed * (now - age));
                pc.measurement(now, [0.0, sensed.y, sensed.z], age).unwrap();
            }
            let a = pc.step(now, s);
            // From the first queued point on (the sensor saw s = 40 at t = 0), except
            // within one sample spacing of the ramp's end, where interpolating between
            // samples cuts the corner.
            let spacing = speed * 0.048;
            if s >= look_ahead + spacing && (s - 100.0).abs() > spacing {
                worst = worst.max(dist(a, seam.offset_at(s)));
            }
        }
        assert!(worst < 1e-9, "{worst}");
    }

    #[test]
    fn latr_queue_rules() {
        let mut pc = PathCorrector::new(PathCorrConfig::latr(10.0)).unwrap();
        pc.start(0.0, 0.0);
        pc.step(1.0, 5.0);
        // s(1.0) = 5 → applies at 15.
        let a = pc.measurement(1.0, [0.0, 1.0, 0.0], 0.0).unwrap();
        assert_eq!(a.s, 15.0);
        // Measured at t = 0.5 (s = 2.5, interpolated) → 12.5: supersedes the one at 15.
        let b = pc.measurement(1.0, [0.0, 2.0, 0.0], 0.5).unwrap();
        assert_eq!(b.s, 12.5);
        assert_eq!(pc.pending(), 1);
        // Older than the history: clamped to its oldest sample (s = 0) → 10.
        let c = pc.measurement(1.0, [0.0, 3.0, 0.0], 1.5).unwrap();
        assert_eq!(c.s, 10.0);
        assert_eq!(pc.pending(), 1);
        // Halfway from the anchor (s = 0, offset 0) to (10, 3).
        pc.step(1.5, 5.0);
        assert!((pc.target().y - 1.5).abs() < 1e-12);
        pc.step(2.0, 10.0);
        assert_eq!(pc.target().y, 3.0);
        assert_eq!(pc.pending(), 0);
        // With no look-ahead the arc length has been passed: applies at once.
        pc.set_look_ahead(0.0);
        pc.set_look_ahead(-5.0);
        pc.set_look_ahead(f64::NAN);
        assert_eq!(pc.config().tracker, Tracker::Latr { look_ahead: 0.0 });
        pc.measurement(2.0, [0.0, 4.0, 0.0], 0.2).unwrap();
        assert_eq!(pc.pending(), 0);
        pc.step(2.1, 11.0);
        assert_eq!(pc.target().y, 4.0);
    }

    #[test]
    fn latr_queue_overflow() {
        let mut cfg = PathCorrConfig::latr(100.0);
        cfg.capacity = 2;
        let mut pc = PathCorrector::new(cfg).unwrap();
        pc.start(0.0, 0.0);
        for i in 1..=5 {
            let t = i as f64;
            pc.step(t, t);
            pc.measurement(t, [0.0, t, 0.0], 0.0).unwrap();
        }
        assert_eq!(pc.pending(), 2);
        assert_eq!(pc.overflows(), 3);
        // The dropped entries became the anchor: the target stays continuous.
        pc.step(6.0, 6.0);
        assert!(pc.target().is_finite());
    }

    #[test]
    fn incremental_mode_and_limits() {
        let mut cfg = PathCorrConfig::aptr();
        cfg.mode = CorrectionMode::Incremental;
        cfg.limits.max_offset = 5.0;
        let mut pc = PathCorrector::new(cfg).unwrap();
        pc.start(0.0, 0.0);
        pc.measurement(0.0, [0.0, 2.0, 0.0], 0.0).unwrap();
        let s = pc.measurement(0.0, [0.0, 2.0, 1.0], 0.0).unwrap();
        assert_eq!(s.offset, PathOffset::new(4.0, 1.0));
        // 4 + 2 = 6 > 5: rejected, the total stays.
        assert!(matches!(
            pc.measurement(0.0, [0.0, 2.0, 0.0], 0.0),
            Err(Rejection::TooLarge { .. })
        ));
        pc.step(0.004, 0.0);
        assert_eq!(pc.target(), PathOffset::new(4.0, 1.0));
        // A rejected absolute correction leaves the previous one in force too.
        let mut pc = PathCorrector::new(PathCorrConfig::aptr()).unwrap();
        pc.measurement(0.0, [0.0, 1.0, 0.0], 0.0).unwrap();
        assert!(pc.measurement(0.0, [0.0, f64::NAN, 0.0], 0.0).is_err());
        assert!(pc.measurement(0.0, [0.0, 500.0, 0.0], 0.0).is_err());
        pc.step(0.0, 0.0);
        assert_eq!(pc.target(), PathOffset::new(1.0, 0.0));
    }

    #[test]
    fn no_corr_ramps_out() {
        let mut pc = PathCorrector::new(PathCorrConfig::aptr()).unwrap();
        pc.start(0.0, 0.0);
        pc.measurement(0.0, [0.0, 1.0, 0.0], 0.0).unwrap();
        for i in 1..200 {
            pc.step(i as f64 * 0.004, 0.0);
        }
        assert_eq!(pc.applied(), PathOffset::new(1.0, 0.0));
        pc.set_enabled(false);
        pc.measurement(0.8, [0.0, 2.0, 0.0], 0.0).unwrap();
        for i in 200..400 {
            pc.step(i as f64 * 0.004, 0.0);
        }
        assert_eq!(pc.target(), PathOffset::ZERO);
        assert_eq!(pc.applied(), PathOffset::ZERO);
        pc.set_enabled(true);
        pc.measurement(1.6, [0.0, 2.0, 0.0], 0.0).unwrap();
        pc.step(1.604, 0.0);
        assert_eq!(pc.target(), PathOffset::new(2.0, 0.0));
    }

    #[test]
    fn corrector_survives_bad_times_and_arc_lengths() {
        for cfg in [PathCorrConfig::aptr(), PathCorrConfig::latr(30.0)] {
            let mut pc = PathCorrector::new(cfg).unwrap();
            pc.start(f64::NAN, f64::INFINITY);
            pc.measurement(0.0, [0.0, 1.0, 1.0], 0.0).unwrap();
            for (t, s) in [
                (0.004, 1.0),
                (f64::NAN, 2.0),
                (0.002, 3.0),
                (0.008, f64::NAN),
                (f64::INFINITY, 4.0),
                (0.012, -10.0),
                (0.016, 5.0),
            ] {
                let a = pc.step(t, s);
                assert!(a.is_finite(), "{cfg:?} {t} {s}");
            }
            pc.measurement(f64::NAN, [0.0, 1.0, 1.0], 0.0).unwrap();
            assert!(pc.step(0.02, 6.0).is_finite());
        }
    }

    // ---- seam profiles ----

    #[test]
    fn seam_profiles() {
        let c = SeamProfile::parse("const:y=3,z=-2").unwrap();
        assert_eq!(c, SeamProfile::Const { y: 3.0, z: -2.0 });
        assert_eq!(c.offset_at(-5.0), PathOffset::new(3.0, -2.0));
        assert_eq!(c.offset_at(f64::NAN), PathOffset::ZERO);
        let r: SeamProfile = " Ramp : Y = 5 , len=400 ".parse().unwrap();
        assert_eq!(
            r,
            SeamProfile::Ramp {
                y: 5.0,
                z: 0.0,
                len: 400.0
            }
        );
        assert_eq!(r.offset_at(-1.0), PathOffset::ZERO);
        assert_eq!(r.offset_at(200.0), PathOffset::new(2.5, 0.0));
        assert_eq!(r.offset_at(400.0), PathOffset::new(5.0, 0.0));
        assert_eq!(r.offset_at(1e6), PathOffset::new(5.0, 0.0));
        let s = SeamProfile::parse("sine:y=2,z=-1,period=100").unwrap();
        assert!(s.offset_at(0.0).norm() < 1e-12);
        assert!(dist(s.offset_at(25.0), PathOffset::new(2.0, -1.0)) < 1e-12);
        assert!(s.offset_at(50.0).norm() < 1e-12);
        assert!(dist(s.offset_at(75.0), PathOffset::new(-2.0, 1.0)) < 1e-12);
        assert!(dist(s.offset_at(1e7 + 25.0), PathOffset::new(2.0, -1.0)) < 1e-6);
        let p = SeamProfile::parse("sine:y=2,period=100,phase=90").unwrap();
        assert!(dist(p.offset_at(0.0), PathOffset::new(2.0, 0.0)) < 1e-12);
        assert_eq!(
            SeamProfile::parse("const").unwrap().offset_at(1.0),
            PathOffset::ZERO
        );
        assert_eq!(
            SeamProfile::parse("CONST:").unwrap().offset_at(1.0),
            PathOffset::ZERO
        );
        // APTR senses at the TCP, LATR ahead of it.
        assert_eq!(r.sensed_at(Tracker::Aptr, 200.0), PathOffset::new(2.5, 0.0));
        assert_eq!(
            r.sensed_at(Tracker::Latr { look_ahead: 200.0 }, 0.0),
            PathOffset::new(2.5, 0.0)
        );
    }

    #[test]
    fn seam_text_round_trips() {
        for text in [
            "const:y=3,z=-2",
            "ramp:y=5,z=0,len=400",
            "sine:y=2,z=0,period=100",
            "sine:y=2,z=0.5,period=200,phase=-45",
        ] {
            let p = SeamProfile::parse(text).unwrap();
            assert_eq!(p.to_string(), text);
            assert_eq!(SeamProfile::parse(&p.to_string()).unwrap(), p);
        }
        // The simulated LTAPP devices' patterns are valid.
        for (_, pattern) in crate::config::devices::SIMULATED_LTAPP {
            assert!(SeamProfile::parse(pattern).is_ok(), "{pattern}");
        }
    }

    #[test]
    fn seam_parse_errors() {
        let err = |s: &str| SeamProfile::parse(s).unwrap_err().error;
        assert_eq!(err(" "), SeamError::Empty);
        assert_eq!(err("square:y=1"), SeamError::UnknownKind("square".into()));
        assert_eq!(
            err("const:len=3").to_string(),
            "const takes y and z, not `len`"
        );
        assert_eq!(
            err("ramp:y=1,period=3").to_string(),
            "ramp takes y, z and len, not `period`"
        );
        assert_eq!(
            err("sine:y=1,len=3").to_string(),
            "sine takes y, z, period and phase, not `len`"
        );
        assert_eq!(err("ramp:y=1").to_string(), "ramp needs `len=`");
        assert_eq!(err("sine:y=2").to_string(), "sine needs `period=`");
        assert_eq!(
            err("ramp:len=0").to_string(),
            "`len` must be greater than 0 mm, not 0"
        );
        assert_eq!(
            err("sine:period=-5").to_string(),
            "`period` must be greater than 0 mm, not -5"
        );
        assert_eq!(
            err("sine:period=abc").to_string(),
            "`period=abc`: not a number"
        );
        for bad in ["inf", "NaN", "1e999", ""] {
            assert!(matches!(
                err(&format!("const:y={bad}")),
                SeamError::BadNumber { .. }
            ));
        }
        assert_eq!(err("const:y").to_string(), "`y` needs a value: `y=NUMBER`");
        assert_eq!(err("const:y=1,Y=2"), SeamError::Duplicate("Y".into()));
        assert_eq!(err("const:y=1,,z=2"), SeamError::EmptyItem);
        assert_eq!(err("const:y=1,"), SeamError::EmptyItem);
        let full = SeamProfile::parse("ramp:y=1").unwrap_err().to_string();
        assert_eq!(
            full,
            "bad seam pattern `ramp:y=1`: ramp needs `len=` (examples: `const:y=3,z=-2`, \
             `ramp:y=5,z=0,len=400`, `sine:y=2,z=0,period=100`)"
        );
    }

    proptest! {
        #[test]
        fn seam_parser_is_total(text in "[a-zA-Z:=,.0-9 -]{0,40}") {
            if let Ok(p) = SeamProfile::parse(&text) {
                prop_assert!(p.offset_at(123.4).is_finite());
                prop_assert_eq!(SeamProfile::parse(&p.to_string()), Ok(p));
            }
        }
    }
}
