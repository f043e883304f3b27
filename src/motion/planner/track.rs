//! Cycle-to-cycle inverse kinematics for linear and circular moves: quasi-Newton steps from a
//! predicted joint vector with a Broyden-updated Jacobian. It follows the current arm
//! branch by construction and costs a few forward kinematics per cycle instead of a full
//! analytic solve; when it does not converge (near a singularity), leaves the axis ranges or
//! jumps, the caller falls back to `Robot::ik_nearest`.

use nalgebra::{Matrix6, Vector6};

use crate::robot::{JointsDeg, Pose, Robot};

/// Converged when the flange is this close to the target (mm)…
const TOL_MM: f64 = 1e-7;
/// … and this close in orientation (rad).
const TOL_RAD: f64 = 1e-10;
/// Newton steps per cycle before giving up.
const MAX_STEPS: usize = 10;
/// Finite-difference step for the Jacobian (deg).
const JACOBIAN_STEP_DEG: f64 = 1e-5;
/// A cycle-to-cycle solution moving any axis further than this (deg) is rejected.
const MAX_JUMP_DEG: f64 = 30.0;

/// Tracking IK state: the Jacobian of a recent cycle, kept up to date between cycles by
/// Broyden's rank-one updates (no extra forward kinematics) and refreshed numerically only
/// when convergence slows down.
#[derive(Default)]
pub(super) struct Tracker {
    jac: Option<Matrix6<f64>>,
}

impl Tracker {
    /// Solve for `target` (flange in world) starting from `guess`; `prev` is the previous
    /// cycle's solution. Returns the joints and their forward kinematics, or `None` when the
    /// caller must use the analytic IK.
    pub fn solve(
        &mut self,
        robot: &Robot,
        target: &Pose,
        guess: &JointsDeg,
        prev: &JointsDeg,
    ) -> Option<(JointsDeg, Pose)> {
        let mut q = *guess;
        let mut fk = robot.fk(&q);
        let mut refreshed = false;
        for step in 0..MAX_STEPS {
            let e = error(target, &fk);
            let (pos, rot) = (e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm());
            if !(pos.is_finite() && rot.is_finite()) {
                break;
            }
            if pos <= TOL_MM && rot <= TOL_RAD {
                let jump = q
                    .iter()
                    .zip(prev)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max);
                return (jump <= MAX_JUMP_DEG && robot.check_limits(&q).is_ok()).then_some((q, fk));
            }
            // Refresh a missing or stale Jacobian (slow convergence: several steps so far).
            if self.jac.is_none() || (step >= REFRESH_AFTER && !refreshed) {
                self.jac = Some(jacobian(robot, &q, &fk));
                refreshed = true;
            }
            let j = self.jac?;
            let dq = j.lu().solve(&e)?;
            let mut q_new = q;
            for (qi, d) in q_new.iter_mut().zip(dq.iter()) {
                *qi += d;
            }
            let fk_new = robot.fk(&q_new);
            // Broyden: make the Jacobian reproduce the change this step actually made.
            let y = error(&fk_new, &fk);
            let ss = dq.norm_squared();
            if ss > 0.0 && ss.is_finite() {
                self.jac = Some(j + (y - j * dq) * dq.transpose() / ss);
            }
            q = q_new;
            fk = fk_new;
        }
        self.jac = None;
        None
    }

    /// Forget the Jacobian (after a fallback to the analytic IK).
    pub fn reset(&mut self) {
        self.jac = None;
    }
}

/// Refresh the Jacobian numerically after this many steps without convergence.
const REFRESH_AFTER: usize = 4;

/// `[Δposition (mm); Δorientation (rad, world frame)]` from `fk` to `target`.
fn error(target: &Pose, fk: &Pose) -> Vector6<f64> {
    let dp = target.translation.vector - fk.translation.vector;
    let dr = (target.rotation * fk.rotation.inverse()).scaled_axis();
    Vector6::new(dp.x, dp.y, dp.z, dr.x, dr.y, dr.z)
}

/// The numerical Jacobian at `q` (columns per degree).
fn jacobian(robot: &Robot, q: &JointsDeg, fk: &Pose) -> Matrix6<f64> {
    let mut j = Matrix6::zeros();
    for (i, mut col) in j.column_iter_mut().enumerate() {
        let mut qh = *q;
        if let Some(v) = qh.get_mut(i) {
            *v += JACOBIAN_STEP_DEG;
        }
        let d = error(&robot.fk(&qh), fk) / JACOBIAN_STEP_DEG;
        col.copy_from(&d);
    }
    j
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::*;

    #[test]
    fn tracks_a_nearby_pose() {
        let robot = Robot::default();
        let q0 = [10.0, 5.0, -10.0, 20.0, 40.0, -30.0];
        let q1 = [10.3, 5.2, -10.1, 20.4, 39.8, -29.5];
        let target = robot.fk(&q1);
        let mut t = Tracker::default();
        let (q, fk) = t.solve(&robot, &target, &q0, &q0).unwrap();
        for i in 0..6 {
            assert!((q[i] - q1[i]).abs() < 1e-6, "{q:?}");
        }
        assert!((fk.translation.vector - target.translation.vector).norm() < 1e-6);
        // Out of reach: no solution, the caller falls back.
        let far = Pose::translation(5000.0, 0.0, 0.0) * target;
        assert!(t.solve(&robot, &far, &q0, &q0).is_none());
    }
}
