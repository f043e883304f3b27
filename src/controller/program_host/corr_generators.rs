//! Correction generators (`CorrCon`, `CorrWrite`, `CorrRead`, `CorrDiscon`, `CorrClear`) and
//! the path offset they add to `MoveL`/`MoveC` with `\Corr`, through the motion core's path
//! correction seam (`motion::correction`, the seam EGM path correction uses too).
//!
//! Each connected generator holds an offset; their sum is the correction, written in the
//! **path frame**: x along the path (the direction the TCP moves), z the tool's z axis made
//! perpendicular to x, y = z × x. The offset actually applied follows the written one at
//! most [`CORR_MAX_SPEED`] mm/s, and every corrected sequence starts from no offset, so the
//! TCP never jumps. A sequence of `\Corr` moves ends in a stop point (a fly-by point into an
//! uncorrected move stops the robot with an error), as EGM path correction does.
//!
//! The program side writes the sum and marks the `\Corr` moves through atomics; the cycle
//! reads them without locks.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

use nalgebra::{Matrix3, Vector3};

use crate::motion::{InstrRef, MotionError, PathCorrection, PathPoint};
use crate::time::RobotTime;

/// Fastest change of the applied offset (mm/s).
pub const CORR_MAX_SPEED: f64 = 100.0;
/// `\Corr` moves remembered at once (older ones are forgotten; the queue is far shorter).
const MARKS: usize = 64;

/// What the program side and the cycle share.
#[derive(Debug)]
pub struct CorrShared {
    /// The written correction (path frame, mm), as f64 bits.
    offset: [AtomicU64; 3],
    /// Ids of `\Corr` moves (0: free).
    marks: [AtomicU64; MARKS],
    next: AtomicUsize,
}

impl Default for CorrShared {
    fn default() -> Self {
        CorrShared {
            offset: std::array::from_fn(|_| AtomicU64::new(0f64.to_bits())),
            marks: std::array::from_fn(|_| AtomicU64::new(0)),
            next: AtomicUsize::new(0),
        }
    }
}

impl CorrShared {
    /// Write the correction (path frame, mm).
    pub fn set_offset(&self, o: [f64; 3]) {
        for (a, x) in self.offset.iter().zip(o) {
            a.store(x.to_bits(), Ordering::Relaxed);
        }
    }

    fn offset(&self) -> Vector3<f64> {
        let [x, y, z] = &self.offset;
        Vector3::new(
            f64::from_bits(x.load(Ordering::Relaxed)),
            f64::from_bits(y.load(Ordering::Relaxed)),
            f64::from_bits(z.load(Ordering::Relaxed)),
        )
    }

    /// The move `id` is a `\Corr` move.
    pub fn mark(&self, id: u64) {
        let k = self.next.fetch_add(1, Ordering::Relaxed) % MARKS;
        if let Some(m) = self.marks.get(k) {
            m.store(id, Ordering::Relaxed);
        }
    }

    fn marked(&self, id: u64) -> bool {
        id != 0 && self.marks.iter().any(|m| m.load(Ordering::Relaxed) == id)
    }
}

/// The path correction of the `\Corr` moves (module docs).
#[derive(Debug)]
pub struct CorrPath {
    shared: Arc<CorrShared>,
    applied: Vector3<f64>,
    last: Option<RobotTime>,
    /// The last path direction (kept while the TCP stands still).
    along: Vector3<f64>,
}

impl CorrPath {
    /// A correction reading `shared`.
    pub fn new(shared: Arc<CorrShared>) -> CorrPath {
        CorrPath {
            shared,
            applied: Vector3::zeros(),
            last: None,
            along: Vector3::x(),
        }
    }
}

impl PathCorrection for CorrPath {
    fn corrects(&self, instr: &InstrRef) -> bool {
        self.shared.marked(instr.id)
    }

    fn offset(&mut self, now: RobotTime, point: &PathPoint) -> Result<Vector3<f64>, MotionError> {
        if point.first {
            self.applied = Vector3::zeros();
            self.last = None;
        }
        let dt = self
            .last
            .map_or(0.0, |l| now.saturating_since(l).as_secs_f64());
        self.last = Some(now);
        let wanted = self.shared.offset();
        if wanted.iter().all(|c| c.is_finite()) {
            let d = wanted - self.applied;
            let max = CORR_MAX_SPEED * dt;
            let n = d.norm();
            self.applied += if n > max && n > 0.0 { d * (max / n) } else { d };
        }
        let step = point.step;
        if step.norm() > 1e-9 {
            self.along = step.normalize();
        }
        let x = self.along;
        let tool_z = point.tcp.rotation * Vector3::z();
        let z_raw = tool_z - x * tool_z.dot(&x);
        let z = if z_raw.norm() > 1e-9 {
            z_raw.normalize()
        } else {
            // The tool points along the path: any perpendicular will do.
            let other = if x.x.abs() < 0.9 {
                Vector3::x()
            } else {
                Vector3::y()
            };
            x.cross(&other).normalize()
        };
        let y = z.cross(&x);
        Ok(Matrix3::from_columns(&[x, y, z]) * self.applied)
    }

    fn leave(&mut self, _now: RobotTime, _instr: &InstrRef) -> Result<(), MotionError> {
        Err(MotionError::NotSupported {
            what: "a sequence of \\Corr moves that does not end in a stop point",
        })
    }
}
