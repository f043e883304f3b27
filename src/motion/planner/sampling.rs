//! Sampling a planned move at the motion cycle: axis interpolation, or inverse kinematics of
//! every cycle with continuity for linear and circular moves, slowed down until every axis
//! keeps within its speed limit.

use crate::robot::command::MoveArgs;
use crate::robot::{KinError, SingularityKind, flange_target};

use super::super::event::{MotionError, PathPlace};
use super::super::limits::{self, MAX_SLOWDOWN};
use super::super::profile::{Profile, ProfileLimits};
use super::super::segment::Sample;
use super::super::settings::SingArea;
use super::Planner;
use super::path::Geometry;
use super::track::Tracker;
use crate::robot::JointsDeg;

/// The longest move the planner accepts (s): every cycle of a move is kept in memory.
pub const MAX_MOVE_SECONDS: f64 = 900.0;

/// At most this many re-samplings to bring the axis speeds under their limits.
const MAX_RESAMPLINGS: usize = 24;

/// Number of cycles a profile of `duration` seconds takes (at least one).
pub fn sample_count(duration: f64, dt: f64) -> usize {
    if duration > 0.0 && dt > 0.0 {
        // Exact multiples of the cycle must not gain a cycle from float noise.
        let n = (duration / dt - 1e-9).ceil();
        if n >= 1.0 { n as usize } else { 1 }
    } else {
        1
    }
}

/// Time of sample `k` (the last one is the end of the profile).
pub fn sample_time(k: usize, dt: f64, duration: f64) -> f64 {
    ((k as f64 + 1.0) * dt).min(duration)
}

/// How many samples lie within the ramp-up (`up`) or ramp-down of a profile.
pub fn samples_within(p: &Profile, dt: f64, up: bool) -> usize {
    let d = p.duration();
    let n = sample_count(d, dt);
    (0..n)
        .filter(|&k| {
            let t = sample_time(k, dt, d);
            if up {
                t <= p.ramp_up_time() + 1e-12
            } else {
                t + 1e-12 >= d - p.ramp_down_time()
            }
        })
        .count()
}

impl Planner {
    /// Sample `g` under `profile` into `out`; while some axis would exceed its speed limit,
    /// stretch the profile and sample again. Returns the profile used.
    pub(super) fn sample_with_speed_limits(
        &self,
        g: &Geometry,
        args: &MoveArgs,
        mut profile: Profile,
        plimits: &ProfileLimits,
        out: &mut Vec<Sample>,
    ) -> Result<Profile, MotionError> {
        let vmax = limits::axis_speeds(self.robot.model(), &self.settings);
        let mut slowdown = 1.0;
        for _ in 0..MAX_RESAMPLINGS {
            if profile.duration().is_nan() || profile.duration() > MAX_MOVE_SECONDS {
                return Err(MotionError::NotSupported {
                    what: "a move lasting longer than 15 minutes",
                });
            }
            self.sample(g, args, &profile, out)?;
            let (ratio, k, axis) = limits::worst_speed_ratio(&self.start, out, self.dt, &vmax);
            if ratio <= 1.0 {
                return Ok(profile);
            }
            slowdown *= ratio;
            if slowdown.is_nan() || slowdown > MAX_SLOWDOWN {
                return Err(self.too_fast(out, k, axis, ratio, &vmax, profile.duration()));
            }
            let stretched = profile.duration() * ratio * (1.0 + 1e-6);
            profile = Profile::with_duration(stretched, plimits);
        }
        let (ratio, k, axis) = limits::worst_speed_ratio(&self.start, out, self.dt, &vmax);
        Err(self.too_fast(out, k, axis, ratio, &vmax, profile.duration()))
    }

    /// The error for a move whose axes cannot keep up: a singularity when the offending
    /// sample is close to one, otherwise the axis speed.
    fn too_fast(
        &self,
        samples: &[Sample],
        k: usize,
        axis: usize,
        ratio: f64,
        vmax: &crate::robot::JointsDeg,
        duration: f64,
    ) -> MotionError {
        let place =
            PathPlace::Along(sample_time(k, self.dt, duration) / duration.max(f64::MIN_POSITIVE));
        if let Some(kind) = samples.get(k).and_then(|s| {
            self.robot
                .near_singularity_with(&s.q, &wide_thresholds())
                .map(|kind| (kind, s.q))
        }) {
            return MotionError::Kinematics {
                error: KinError::Singularity {
                    kind: kind.0,
                    joints: kind.1,
                },
                place,
            };
        }
        let max = vmax.get(axis).copied().unwrap_or(f64::NAN);
        MotionError::JointSpeed {
            joint: axis + 1,
            speed: ratio * max,
            max,
        }
    }

    /// Fill `out` with one sample per cycle of `g` under `profile`.
    fn sample(
        &self,
        g: &Geometry,
        args: &MoveArgs,
        profile: &Profile,
        out: &mut Vec<Sample>,
    ) -> Result<(), MotionError> {
        out.clear();
        let duration = profile.duration();
        let n = sample_count(duration, self.dt);
        out.reserve(n);
        match g {
            Geometry::Joint { from, to } => {
                for k in 0..n {
                    let s = profile.position(sample_time(k, self.dt, duration));
                    let q = if k + 1 == n {
                        *to
                    } else {
                        Geometry::joints_at(from, to, s)
                    };
                    out.push(Sample {
                        q,
                        tcp: self.robot.tcp_world(&q, &args.tool),
                    });
                }
            }
            Geometry::Line { .. } | Geometry::Circle { .. } => {
                self.sample_cartesian(g, args, profile, n, out)?;
            }
        }
        Ok(())
    }

    /// Inverse kinematics of every cycle of a linear or circular move, with continuity: a
    /// tracking solve from the extrapolated previous joints, or the analytic
    /// `Robot::ik_nearest` from the previous joints when tracking fails.
    fn sample_cartesian(
        &self,
        g: &Geometry,
        args: &MoveArgs,
        profile: &Profile,
        n: usize,
        out: &mut Vec<Sample>,
    ) -> Result<(), MotionError> {
        let duration = profile.duration();
        let mut checker = SingularityWatch::new(self, &self.start);
        let mut tracker = Tracker::default();
        let mut prev_q = self.start;
        // The last three (joints, s) for the prediction of the next cycle.
        let mut history: [Option<(JointsDeg, f64)>; 3] = [None, None, Some((self.start, 0.0))];
        for k in 0..n {
            let last = k + 1 == n;
            let s = if last {
                1.0
            } else {
                profile.position(sample_time(k, self.dt, duration))
            };
            let place = if last {
                PathPlace::Target
            } else {
                PathPlace::Along(s)
            };
            let Some(pose) = g.pose_at(s) else {
                return Ok(());
            };
            let flange = flange_target(&pose, &args.tool, &args.wobj, &args.pdisp);
            let guess = extrapolate(&history, s).unwrap_or(prev_q);
            let (q, fk) = match tracker.solve(&self.robot, &flange, &guess, &prev_q) {
                Some(found) => found,
                None => {
                    tracker.reset();
                    let q = self
                        .robot
                        .ik_nearest(&flange, &prev_q)
                        .map_err(|error| MotionError::Kinematics { error, place })?;
                    (q, self.robot.fk(&q))
                }
            };
            checker.check(&q, place)?;
            out.push(Sample {
                q,
                tcp: tcp_of(&fk, &args.tool),
            });
            history = [history[1], history[2], Some((q, s))];
            prev_q = q;
        }
        Ok(())
    }
}

/// Predict the joints at path parameter `s` from the last samples: quadratic (Lagrange in
/// `s`) through three, linear through two.
fn extrapolate(h: &[Option<(JointsDeg, f64)>; 3], s: f64) -> Option<JointsDeg> {
    match h {
        [Some((q0, s0)), Some((q1, s1)), Some((q2, s2))] if s0 < s1 && s1 < s2 => {
            let l0 = (s - s1) * (s - s2) / ((s0 - s1) * (s0 - s2));
            let l1 = (s - s0) * (s - s2) / ((s1 - s0) * (s1 - s2));
            let l2 = (s - s0) * (s - s1) / ((s2 - s0) * (s2 - s1));
            let mut q = *q2;
            for (((qi, a), b), c) in q.iter_mut().zip(q0).zip(q1).zip(q2) {
                *qi = l0 * a + l1 * b + l2 * c;
            }
            Some(q)
        }
        [_, Some((q1, s1)), Some((q2, s2))] if s1 < s2 => {
            let r = (s - s2) / (s2 - s1);
            let mut q = *q2;
            for ((qi, a), b) in q.iter_mut().zip(q1).zip(q2) {
                *qi = b + (b - a) * r;
            }
            Some(q)
        }
        _ => None,
    }
}

/// The TCP in world from the flange pose (as `Robot::tcp_world`).
fn tcp_of(flange: &crate::robot::Pose, tool: &crate::robot::ToolData) -> crate::robot::Pose {
    if tool.robhold {
        flange * tool.tframe
    } else {
        tool.tframe
    }
}

/// Refuses a linear path that runs into a singularity (SingArea\Wrist tolerates the wrist).
struct SingularityWatch<'a> {
    planner: &'a Planner,
    prev: Option<SingularityKind>,
    allow_wrist: bool,
}

impl<'a> SingularityWatch<'a> {
    fn new(planner: &'a Planner, start: &crate::robot::JointsDeg) -> Self {
        SingularityWatch {
            planner,
            prev: planner.robot.near_singularity(start),
            allow_wrist: planner.settings.singarea != SingArea::Off,
        }
    }

    fn check(&mut self, q: &crate::robot::JointsDeg, place: PathPlace) -> Result<(), MotionError> {
        let near = self.planner.robot.near_singularity(q);
        if let Some(kind) = near {
            let entering = self.prev != Some(kind);
            let tolerated = kind == SingularityKind::Wrist && self.allow_wrist;
            if entering && !tolerated {
                return Err(MotionError::Kinematics {
                    error: KinError::Singularity { kind, joints: *q },
                    place,
                });
            }
        }
        self.prev = near;
        Ok(())
    }
}

/// Thresholds three times the defaults: used only to name the cause of an axis that cannot
/// keep up (a path grazing a singularity just outside the default thresholds).
fn wide_thresholds() -> crate::robot::SingularityThresholds {
    let d = crate::robot::SingularityThresholds::default();
    crate::robot::SingularityThresholds {
        shoulder_mm: d.shoulder_mm * 3.0,
        elbow_sin: d.elbow_sin * 3.0,
        wrist_deg: d.wrist_deg * 3.0,
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]
mod tests {
    use super::*;

    #[test]
    fn counts() {
        assert_eq!(sample_count(0.0, 0.004), 1);
        assert_eq!(sample_count(0.004, 0.004), 1);
        assert_eq!(sample_count(0.0041, 0.004), 2);
        assert_eq!(sample_count(1.0, 0.004), 250);
        assert_eq!(sample_time(249, 0.004, 0.999), 0.999);
    }
}
