//! Holding and resuming on the path (`StopMove`/`StartMove`), the speed of the ongoing move
//! (`SpeedRefresh`), and the stored path (`StorePath`/`RestoPath`, `ClearPath`).
//!
//! **Path rate.** The planned samples are played at a *rate*: 1 plays one sample per cycle
//! (the planned speed), 0.5 half a sample (half the speed, on the same path), 0 holds the
//! robot where it is on the path. While the rate is not 1 the executor interpolates between
//! two neighbouring samples (joints linearly, the TCP by position and orientation), so the
//! robot never leaves the planned path. The rate changes by at most a bounded step per cycle:
//! the part of each axis's acceleration the change adds (`Δrate/dt · v_path`) stays within
//! [`RAMP_SHARE`] of the axis's acceleration (half of it with `StopMove \Quick`), so stopping
//! on the path and starting again both keep within the robot's limits. With the rate at 1 and
//! nothing interpolated the executor plays samples exactly as without this module.
//!
//! **Speed ratio.** The controller's speed ratio ([`PathOp::Ratio`], the panel's override of
//! a controller that stays up) is a second factor of the rate's target, on top of
//! `SpeedRefresh`: a move already planned slows down or speeds up at once, within the same
//! bounded ramp. It is kept while external guidance runs (EGM scales its own speed).
//!
//! **Program stop.** [`PathOp::Pause`] (the program is stopped: the panel's stop button,
//! RWS) decelerates on the path with the same bounded ramp as `StopMove` and holds;
//! [`PathOp::Continue`] (the program starts again) resumes the same path, fly-by corners
//! included, as a controller continues a stopped program's moves. It is a hold of its own:
//! a `StopMove` of the program is still in force after the start.
//!
//! **Stored path.** [`PathOp::Store`] puts the moves of the current path (active, queued, and
//! the place on the path the robot holds at) aside and leaves an empty path for new moves;
//! [`PathOp::Restore`] brings them back. The first cycles after a restore run from where the
//! robot is to the held place on the path (the regain), at the ramp's low rate.

use super::{Active, Executor, Out};
use crate::motion::brake::fewest_steps;
use crate::motion::event::InstrRef;
use crate::motion::segment::{Sample, Segment};
use crate::robot::JointsDeg;
use crate::time::RobotTime;
use std::collections::VecDeque;

/// Share of each axis's acceleration a change of the path rate may use (a normal `StopMove`,
/// `StartMove`, `SpeedRefresh`): the rest is left for the planned path's own accelerations.
pub const RAMP_SHARE: f64 = 0.25;
/// Share with `StopMove \Quick`.
pub const QUICK_RAMP_SHARE: f64 = 0.5;
/// Farthest the robot may be from the held place on the path (mm of TCP) for a restart after
/// `RestoPath`: ABB's regain limit.
pub const REGAIN_MAX_MM: f64 = 10.0;
/// Farthest any axis may be from the held place on the path (deg) for a restart.
pub const REGAIN_MAX_DEG: f64 = 20.0;

/// A change of the path's execution (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PathOp {
    /// Decelerate on the path and hold (`StopMove`); `quick`: with twice the ramp.
    Hold {
        /// `StopMove \Quick`.
        quick: bool,
    },
    /// Resume the held path (`StartMove`).
    Release,
    /// Play the path at this share of its planned speed (`SpeedRefresh`), 0…1.
    Speed(f64),
    /// Put the current path aside (`StorePath`); the robot must stand still.
    Store,
    /// Bring the stored path back (`RestoPath`); nothing may move on the current path.
    Restore,
    /// Drop the moves of the current path (`ClearPath`); a moving robot brakes to rest.
    Clear,
    /// The controller's speed ratio as a share, 0.01…1 (module docs).
    Ratio(f64),
    /// The program is stopped: decelerate on the path and hold (module docs).
    Pause,
    /// The program starts again: resume the path a [`PathOp::Pause`] held.
    Continue,
}

/// Why a [`PathOp`] was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum PathOpError {
    /// `Store` while a path is stored already.
    #[error("a path is stored already (StorePath can be used once before RestoPath)")]
    AlreadyStored,
    /// `Store` while the robot moves.
    #[error("the robot is moving: StorePath needs the robot at rest (use StopMove first)")]
    Moving,
    /// `Restore` without a stored path.
    #[error("no path is stored (RestoPath needs a StorePath before it)")]
    NothingStored,
    /// `Restore` while moves of the new path are queued or running.
    #[error("moves of the current path are still queued or running")]
    PathBusy,
    /// `Release` too far from the held place on the path.
    #[error("the robot is too far from the interrupted path to restart it")]
    TooFar,
    /// The executor runs external guidance.
    #[error("the robot is under external guidance")]
    External,
    /// The motion thread did not answer.
    #[error("the motion thread does not answer")]
    Unavailable,
}

/// The rate the path is played at (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct PathRate {
    /// The rate of this cycle.
    pub current: f64,
    /// Held (`StopMove`): the target is 0.
    pub hold: bool,
    /// Held by a program stop ([`PathOp::Pause`]): the target is 0.
    pub paused: bool,
    /// `SpeedRefresh` share (0…1).
    pub speed: f64,
    /// Share of the axis accelerations a rate change may use.
    pub share: f64,
    /// The controller's speed ratio (0.01…1).
    pub ratio: f64,
}

impl Default for PathRate {
    fn default() -> Self {
        PathRate {
            current: 1.0,
            hold: false,
            paused: false,
            speed: 1.0,
            share: RAMP_SHARE,
            ratio: 1.0,
        }
    }
}

impl PathRate {
    fn target(&self) -> f64 {
        if self.held() {
            0.0
        } else {
            self.speed * self.ratio
        }
    }

    /// Held by `StopMove` or by a program stop.
    fn held(&self) -> bool {
        self.hold || self.paused
    }

    /// True when the path plays exactly as planned.
    fn unity(&self) -> bool {
        self.current == 1.0 && self.target() == 1.0
    }
}

/// Interpolated playback between two samples.
#[derive(Clone, Copy, Debug)]
pub(super) struct Scaled {
    /// Where the interpolation starts (the last sample reached, or the robot's position).
    base: Sample,
    /// The next planned sample.
    pending: Option<Pending>,
    /// Fraction of the way from `base` to `pending` (0…1).
    phase: f64,
}

#[derive(Clone, Copy, Debug)]
struct Pending {
    sample: Sample,
    at_stop_point: bool,
    first: bool,
    /// The move completed when this sample is reached (fetching it finished its segment).
    done: Option<InstrRef>,
}

/// A path put aside by [`PathOp::Store`].
#[derive(Debug)]
pub(super) struct StoredPath {
    active: Option<Active>,
    queue: VecDeque<Segment>,
    scaled: Option<Scaled>,
    rate: PathRate,
    /// Where the robot held on the path when it was stored.
    held_at: JointsDeg,
    /// The last move completed on the stored path (the moves of the new path do not count
    /// for waits on the stored one).
    last_done: Option<InstrRef>,
}

fn lerp(a: &Sample, b: &Sample, t: f64) -> Sample {
    let mut q = a.q;
    for (x, y) in q.iter_mut().zip(&b.q) {
        *x += (y - *x) * t;
    }
    Sample {
        q,
        tcp: a.tcp.lerp_slerp(&b.tcp, t),
    }
}

impl Executor {
    /// Apply a path operation (module docs). Outside the cycle (it may allocate).
    pub fn path_op(&mut self, op: PathOp) -> Result<(), PathOpError> {
        if let PathOp::Ratio(r) = op {
            // Not a share in range (NaN, ≤ 0): ignored, the ratio stays what it was.
            if r.is_finite() && r > 0.0 {
                let r = r.min(1.0);
                self.rate.ratio = r;
                if let Some(st) = self.stored.as_mut() {
                    st.rate.ratio = r;
                }
            }
            return Ok(());
        }
        if self.external.is_some() {
            return Err(PathOpError::External);
        }
        match op {
            PathOp::Pause => {
                if !self.rate.held() {
                    self.rate.share = RAMP_SHARE;
                }
                self.rate.paused = true;
            }
            PathOp::Continue => {
                self.rate.paused = false;
                if !self.rate.hold {
                    self.rate.share = RAMP_SHARE;
                }
            }
            PathOp::Hold { quick } => {
                self.rate.hold = true;
                self.rate.share = if quick { QUICK_RAMP_SHARE } else { RAMP_SHARE };
            }
            PathOp::Release => {
                if let Some(held) = self.held_at {
                    let here = self.setpoint.joints;
                    let off = here
                        .iter()
                        .zip(&held)
                        .map(|(a, b)| (a - b).abs())
                        .fold(0.0, f64::max);
                    let tcp_off = (self.setpoint.tcp.translation.vector
                        - (self.robot.fk(&held) * self.tool_of_setpoint())
                            .translation
                            .vector)
                        .norm();
                    if !(off <= REGAIN_MAX_DEG && tcp_off <= REGAIN_MAX_MM) {
                        return Err(PathOpError::TooFar);
                    }
                }
                self.held_at = None;
                self.rate.hold = false;
                self.rate.share = RAMP_SHARE;
            }
            PathOp::Speed(f) => {
                self.rate.speed = if f.is_finite() {
                    f.clamp(0.0, 1.0)
                } else {
                    1.0
                };
                self.rate.share = RAMP_SHARE;
            }
            PathOp::Store => {
                if self.stored.is_some() {
                    return Err(PathOpError::AlreadyStored);
                }
                let idle = self.active.is_none() && self.queue.is_empty();
                if self.braking.is_some()
                    || !(self.held_at_rest() || idle || self.setpoint.standstill)
                {
                    return Err(PathOpError::Moving);
                }
                let scaled = self.scaled.take().map(|mut s| {
                    // The robot holds here: interpolation restarts from this place.
                    s.base = Sample {
                        q: self.setpoint.joints,
                        tcp: self.setpoint.tcp,
                    };
                    s.phase = 0.0;
                    s
                });
                // The spare queue was preallocated: no allocation here.
                let spare = std::mem::take(&mut self.spare_queue);
                self.stored = Some(StoredPath {
                    active: self.active.take(),
                    queue: std::mem::replace(&mut self.queue, spare),
                    scaled,
                    rate: self.rate,
                    held_at: self.setpoint.joints,
                    last_done: self.last_done,
                });
                self.rate = PathRate {
                    ratio: self.rate.ratio,
                    ..PathRate::default()
                };
            }
            PathOp::Restore => {
                if self.active.is_some() || !self.queue.is_empty() || self.braking.is_some() {
                    return Err(if self.stored.is_none() {
                        PathOpError::NothingStored
                    } else {
                        PathOpError::PathBusy
                    });
                }
                let Some(st) = self.stored.take() else {
                    return Err(PathOpError::NothingStored);
                };
                self.active = st.active;
                self.spare_queue = std::mem::replace(&mut self.queue, st.queue);
                self.rate = PathRate {
                    ratio: self.rate.ratio,
                    ..st.rate
                };
                self.last_done = st.last_done;
                // The robot is where the program moved it back to (near the held place): the
                // interpolation runs from there to the next sample of the path (the regain),
                // from rest, at the ramp's rate.
                let here = Sample {
                    q: self.setpoint.joints,
                    tcp: self.setpoint.tcp,
                };
                self.scaled = Some(Scaled {
                    base: here,
                    pending: st.scaled.and_then(|s| s.pending),
                    phase: 0.0,
                });
                self.held_at = Some(st.held_at);
                self.rate.current = 0.0;
            }
            PathOp::Ratio(_) => {}
            PathOp::Clear => {
                self.scaled = None;
                self.held_at = None;
                if self.setpoint.standstill || self.rate.current == 0.0 {
                    self.clear();
                    self.track = None;
                } else {
                    self.stop();
                }
            }
        }
        Ok(())
    }

    /// True while a path is stored.
    pub fn has_stored_path(&self) -> bool {
        self.stored.is_some()
    }

    /// True while a `StopMove` holds the path.
    pub fn is_held(&self) -> bool {
        self.rate.hold
    }

    /// The active tool as seen from the flange in the last setpoint.
    fn tool_of_setpoint(&self) -> crate::robot::Pose {
        self.robot.fk(&self.setpoint.joints).inverse() * self.setpoint.tcp
    }

    /// True when the next cycle must go through [`Executor::scaled_sample`].
    pub(super) fn scaling(&self) -> bool {
        self.scaled.is_some() || !self.rate.unity()
    }

    /// Forget the interpolation (the planned moves were dropped).
    pub(super) fn reset_scaling(&mut self) {
        self.scaled = None;
        self.held_at = None;
        self.rate.current = if self.rate.held() {
            0.0
        } else {
            self.rate.speed
        };
    }

    /// The next cycle's sample at the path rate (module docs); `None` when there is nothing
    /// to play. The flags are those of the sample reached in this cycle.
    pub(super) fn scaled_sample(&mut self, now: RobotTime) -> Option<Out> {
        let mut s = match self.scaled {
            Some(s) => s,
            None => Scaled {
                // In a corrected sequence the setpoint carries the correction, which the
                // executor adds to each played sample again: start from the planned sample.
                base: match self.planned {
                    Some(p) if self.track.is_some_and(|t| t.open) => p,
                    _ => Sample {
                        q: self.setpoint.joints,
                        tcp: self.setpoint.tcp,
                    },
                },
                pending: None,
                phase: 0.0,
            },
        };
        if s.pending.is_none() {
            s.pending = self.fetch(now);
        }
        let Some(p) = s.pending else {
            // Nothing to play: the robot stands at the end of the path.
            self.scaled = None;
            self.rate.current = self.rate.target();
            return None;
        };
        self.step_rate(&s.base, &p.sample);
        s.phase += self.rate.current;
        let mut out = Out {
            sample: lerp(&s.base, &p.sample, s.phase.min(1.0)),
            at_stop_point: false,
            first: false,
        };
        if s.phase >= 1.0 {
            s.phase -= 1.0;
            s.base = p.sample;
            if let Some(d) = p.done {
                self.last_done = Some(d);
            }
            s.pending = self.fetch(now);
            out.first = p.first;
            match s.pending {
                Some(n) if !p.at_stop_point => {
                    out.sample = lerp(&s.base, &n.sample, s.phase);
                }
                _ => {
                    // A stop point (or the end of the path) is reached exactly.
                    out.sample = p.sample;
                    out.at_stop_point = p.at_stop_point || s.pending.is_none();
                    s.phase = 0.0;
                }
            }
        }
        if out.at_stop_point && s.pending.is_none() && self.rate.unity() {
            self.scaled = None;
        } else {
            self.scaled = Some(s);
        }
        Some(out)
    }

    /// The next planned sample as the interpolation's target. A segment its fetch finishes
    /// counts as done only when the sample is reached.
    fn fetch(&mut self, now: RobotTime) -> Option<Pending> {
        let before = self.last_done;
        let o = self.next_sample(now)?;
        let done = (self.last_done != before)
            .then_some(self.last_done)
            .flatten();
        self.last_done = before;
        Some(Pending {
            sample: o.sample,
            at_stop_point: o.at_stop_point,
            first: o.first,
            done,
        })
    }

    /// Move the rate one bounded step toward its target: the change may add at most the
    /// ramp's share of each axis's acceleration, given the path's joint speed at rate 1 here
    /// (one sample step per cycle).
    fn step_rate(&mut self, from: &Sample, to: &Sample) {
        let mut unit: JointsDeg = [0.0; 6];
        for ((u, a), b) in unit.iter_mut().zip(&from.q).zip(&to.q) {
            *u = (b - a) / self.dt;
        }
        let accel = self.robot.model().max_accel.map(|a| a * self.rate.share);
        // The fewest cycles a full change (0 ↔ 1) may take here.
        let steps = fewest_steps(&unit, &accel, self.dt) as f64;
        let step = 1.0 / steps.max(1.0);
        let target = self.rate.target();
        let c = self.rate.current;
        self.rate.current = if c < target {
            (c + step).min(target)
        } else {
            (c - step).max(target)
        };
    }

    /// True while an interpolated sample is still to be reached (its segment may be finished
    /// already: the robot is still moving toward it).
    pub(super) fn scaled_pending(&self) -> bool {
        self.scaled.is_some_and(|s| s.pending.is_some())
    }

    /// The move whose last sample the interpolation is heading for, once its segment is
    /// finished (the instruction of the cycles until it is reached).
    pub(super) fn pending_done(&self) -> Option<InstrRef> {
        self.scaled.and_then(|s| s.pending).and_then(|p| p.done)
    }

    /// True while the path is held and the robot has come to rest on it.
    pub(super) fn held_at_rest(&self) -> bool {
        self.rate.held() && self.rate.current == 0.0
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]
mod tests {
    use super::*;
    use crate::motion::{CoreConfig, MotionCore, Setpoint};
    use crate::robot::command::{
        EXTAX_NONE, MotionCommand, MoveArgs, MoveJ, MoveL, RobTarget, SpeedData, ZoneData,
    };
    use crate::robot::{ConfData, Robot, ToolData};
    use std::time::Duration;

    const DT: Duration = Duration::from_millis(4);

    fn target(x: f64, y: f64, z: f64) -> RobTarget {
        RobTarget {
            trans: [x, y, z],
            rot: [0.0, 0.0, 1.0, 0.0],
            robconf: ConfData::new(0, 0, -1, 1),
            extax: EXTAX_NONE,
        }
    }

    fn move_l(id: u64, y: f64) -> MotionCommand {
        MotionCommand::MoveL(MoveL {
            args: MoveArgs::new(id, SpeedData::v(200.0), ZoneData::FINE, ToolData::tool0()),
            target: target(1000.0, y, 500.0),
            conf_check: false,
        })
    }

    struct Run {
        core: MotionCore,
        tick: u32,
    }

    impl Run {
        /// A core standing at (1000, 0, 500), tool0 pointing down.
        fn new() -> Run {
            let mut core = MotionCore::new(Robot::default(), CoreConfig::default(), [0.0; 6]);
            core.enqueue(MotionCommand::MoveJ(MoveJ {
                args: MoveArgs::new(1, SpeedData::v(1000.0), ZoneData::FINE, ToolData::tool0()),
                target: target(1000.0, 0.0, 500.0),
                conf_check: false,
            }))
            .unwrap();
            let mut r = Run { core, tick: 0 };
            r.until(|c| c.state().in_position());
            r
        }

        fn step(&mut self) -> Setpoint {
            self.tick += 1;
            self.core
                .tick(RobotTime::ZERO.saturating_add(DT * self.tick))
        }

        fn steps(&mut self, n: usize) -> Vec<Setpoint> {
            (0..n).map(|_| self.step()).collect()
        }

        fn until(&mut self, done: impl Fn(&MotionCore) -> bool) -> Vec<Setpoint> {
            let mut out = Vec::new();
            for _ in 0..100_000 {
                out.push(self.step());
                if done(&self.core) {
                    break;
                }
            }
            out
        }
    }

    fn y(sp: &Setpoint) -> f64 {
        sp.tcp.translation.vector.y
    }

    #[test]
    fn a_program_stop_holds_on_the_path_apart_from_a_stop_move() {
        let mut r = Run::new();
        r.core.enqueue(move_l(2, 200.0)).unwrap();
        r.steps(100);
        r.core.path_op(PathOp::Pause).unwrap();
        let ramp = r.until(|c| c.state().held_at_rest);
        assert!(ramp.len() > 3, "a ramp, not a jump: {} cycles", ramp.len());
        for w in ramp.windows(2) {
            assert!(w[1].speed <= w[0].speed + 1e-9, "slows down steadily");
            let p = w[1].tcp.translation.vector;
            assert!((p.x - 1000.0).abs() < 1e-6 && (p.z - 500.0).abs() < 1e-6);
        }
        // A StopMove while stopped (a TRAP of another task, say) outlives the start.
        r.core.path_op(PathOp::Hold { quick: false }).unwrap();
        r.core.path_op(PathOp::Continue).unwrap();
        let at = y(ramp.last().unwrap());
        assert!(r.steps(100).iter().all(|s| y(s) == at && s.speed == 0.0));
        r.core.path_op(PathOp::Release).unwrap();
        let rest = r.until(|c| c.state().in_position());
        assert!((y(rest.last().unwrap()) - 200.0).abs() < 1e-6);
        // And a StopMove's hold is not ended by a program start either way round.
        r.core.enqueue(move_l(3, 0.0)).unwrap();
        r.steps(50);
        r.core.path_op(PathOp::Hold { quick: false }).unwrap();
        r.core.path_op(PathOp::Pause).unwrap();
        r.until(|c| c.state().held_at_rest);
        r.core.path_op(PathOp::Continue).unwrap();
        let here = y(&r.step());
        assert!(r.steps(100).iter().all(|s| y(s) == here));
        r.core.path_op(PathOp::Release).unwrap();
        let rest = r.until(|c| c.state().in_position());
        assert!(y(rest.last().unwrap()).abs() < 1e-6);
    }

    #[test]
    fn a_hold_decelerates_on_the_path_and_a_release_finishes_the_move() {
        let mut r = Run::new();
        r.core.enqueue(move_l(2, 200.0)).unwrap();
        r.steps(100);
        r.core.path_op(PathOp::Hold { quick: false }).unwrap();
        let ramp = r.until(|c| c.state().setpoint.standstill);
        assert!(ramp.len() > 3, "a ramp, not a jump: {} cycles", ramp.len());
        for w in ramp.windows(2) {
            assert!(w[1].speed <= w[0].speed + 1e-9, "slows down steadily");
            let p = w[1].tcp.translation.vector;
            assert!((p.x - 1000.0).abs() < 1e-6 && (p.z - 500.0).abs() < 1e-6);
        }
        let at = y(ramp.last().unwrap());
        let held = r.steps(250);
        assert!(
            held.iter()
                .all(|s| y(s) == at && s.standstill && s.speed == 0.0)
        );
        assert!(r.core.state().held && !r.core.state().in_position());
        r.core.path_op(PathOp::Release).unwrap();
        let rest = r.until(|c| c.state().in_position());
        assert!((y(rest.last().unwrap()) - 200.0).abs() < 1e-6);
        assert!(!r.core.state().held);
    }

    #[test]
    fn store_and_restore_keep_the_interrupted_move() {
        let mut r = Run::new();
        r.core.enqueue(move_l(2, 200.0)).unwrap();
        r.steps(100);
        assert_eq!(r.core.path_op(PathOp::Store), Err(PathOpError::Moving));
        assert_eq!(
            r.core.path_op(PathOp::Restore),
            Err(PathOpError::NothingStored)
        );
        r.core.path_op(PathOp::Hold { quick: true }).unwrap();
        r.until(|c| c.state().setpoint.standstill);
        let at = r.core.state().setpoint.tcp.translation.vector.y;
        r.core.path_op(PathOp::Store).unwrap();
        assert_eq!(
            r.core.path_op(PathOp::Store),
            Err(PathOpError::AlreadyStored)
        );
        // A detour on the new path, and back.
        r.core.enqueue(move_l(3, at - 50.0)).unwrap();
        r.core.enqueue(move_l(4, at)).unwrap();
        r.until(|c| c.state().in_position());
        r.core.path_op(PathOp::Restore).unwrap();
        assert_eq!(
            r.core.path_op(PathOp::Restore),
            Err(PathOpError::NothingStored)
        );
        r.core.path_op(PathOp::Release).unwrap();
        let rest = r.until(|c| c.state().in_position());
        assert!(rest.iter().all(|s| y(s) >= at - 1e-6), "continues forward");
        assert!(
            (y(rest.last().unwrap()) - 200.0).abs() < 1e-6,
            "ends at {} after {} cycles, {:?}",
            y(rest.last().unwrap()),
            rest.len(),
            r.core.state()
        );
        assert_eq!(r.core.state().last_done.map(|d| d.id), Some(2));
    }

    #[test]
    fn a_restart_far_from_the_path_is_refused() {
        let mut r = Run::new();
        r.core.enqueue(move_l(2, 200.0)).unwrap();
        r.steps(100);
        r.core.path_op(PathOp::Hold { quick: false }).unwrap();
        r.until(|c| c.state().setpoint.standstill);
        r.core.path_op(PathOp::Store).unwrap();
        let at = r.core.state().setpoint.tcp.translation.vector.y;
        r.core.enqueue(move_l(3, at - 50.0)).unwrap();
        r.until(|c| c.state().in_position());
        r.core.path_op(PathOp::Restore).unwrap();
        assert_eq!(r.core.path_op(PathOp::Release), Err(PathOpError::TooFar));
        assert_eq!(
            r.core.path_op(PathOp::Restore),
            Err(PathOpError::NothingStored)
        );
    }

    #[test]
    fn the_speed_ratio_slows_a_planned_move_at_once_and_speeds_it_up_again() {
        let mut r = Run::new();
        r.core.enqueue(move_l(2, 400.0)).unwrap();
        r.steps(150);
        assert!((r.core.state().setpoint.speed - 200.0).abs() < 1e-6);
        r.core.path_op(PathOp::Ratio(0.5)).unwrap();
        let slow = r.steps(100);
        for w in slow.windows(2) {
            assert!(
                w[1].speed <= w[0].speed + 1e-3,
                "slows down steadily: {:?}",
                slow.iter().map(|s| s.speed).collect::<Vec<_>>()
            );
        }
        let s = slow.last().unwrap().speed;
        assert!((s - 100.0).abs() < 1e-3, "{s}");
        // Nonsense is ignored.
        r.core.path_op(PathOp::Ratio(f64::NAN)).unwrap();
        r.core.path_op(PathOp::Ratio(0.0)).unwrap();
        let s = r.steps(10).last().unwrap().speed;
        assert!((s - 100.0).abs() < 1e-3, "{s}");
        r.core.path_op(PathOp::Ratio(1.0)).unwrap();
        let s = r.steps(100).last().unwrap().speed;
        assert!((s - 200.0).abs() < 1e-3, "{s}");
        let rest = r.until(|c| c.state().in_position());
        assert!((y(rest.last().unwrap()) - 400.0).abs() < 1e-6);
    }

    #[test]
    fn a_speed_share_slows_the_move_and_clear_drops_it() {
        let mut r = Run::new();
        r.core.enqueue(move_l(2, 200.0)).unwrap();
        r.steps(150);
        r.core.path_op(PathOp::Speed(0.5)).unwrap();
        let s = r.steps(100);
        assert!(
            (s.last().unwrap().speed - 100.0).abs() < 1e-6,
            "{}",
            s.last().unwrap().speed
        );
        r.core.path_op(PathOp::Clear).unwrap();
        let rest = r.until(|c| !c.state().moving);
        assert!(rest.len() > 1, "a moving robot brakes to rest");
        let stop = y(rest.last().unwrap());
        assert!(stop < 199.0, "the move was dropped at y {stop}");
    }
}
