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

mod correction_check;
mod path_frame;
mod scheduler;
mod seam_profile;
mod smoother;

pub use correction_check::{CorrectionLimits, Rejection, check_correction};
pub use path_frame::{
    FrameBasis, MIN_AXIS_NORM, PARALLEL_SIN, PathFrame, PathOffset, Vec3, look_ahead_distance,
};
pub use scheduler::{
    CorrectionMode, PathCorrConfig, PathCorrConfigError, PathCorrector, Scheduled, Tracker,
};
pub use seam_profile::{SeamError, SeamParseError, SeamProfile};
pub use smoother::{Smoother, SmoothingLimits};

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

#[cfg(test)]
#[allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]
mod tests;
