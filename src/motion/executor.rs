//! The executing half of the motion core: plays planned segments one sample per cycle, hands
//! over into corner paths, supervises axis ranges and speeds, and runs external guidance.
//!
//! [`Executor::tick`] is the real-time path: no allocation, no lock, no I/O, no panic. Queues
//! and the event log are preallocated; finished segments are parked for recycling instead of
//! being dropped.
//!
//! **Stops.** A motion error during a move (supervision, path correction) and
//! [`Executor::stop`] (the program stopped) never freeze the robot in one cycle: it brakes
//! from the joint speeds of the last cycle, all axes together and linearly, as quickly as the
//! axis accelerations allow (`motion::brake`), within the axis ranges. After an error the
//! executor is halted once the robot is at rest. The brake is a joint movement, so the TCP
//! may leave the programmed path by the little it travels while braking.

mod path_hold;

use std::collections::VecDeque;
use std::time::Duration;

use nalgebra::Translation3;

use crate::robot::{JointsDeg, Pose, Robot, ToolData};

use super::brake::{Brake, fewest_steps};
use super::correction::{PathCorrection, PathPoint, Track};
use super::event::{EventLog, InstrRef, MotionError, MotionEvent, PathPlace, Severity};
use super::external_guidance::{ExternalGuidance, GuidanceStep};
use super::limits::{self, SPEED_SUPERVISION_SLACK};
use super::segment::{Sample, Segment};
use super::settings::CoreConfig;
use super::state::{CoreMode, MotionState, Setpoint};
use crate::time::RobotTime;

pub use path_hold::{PathOp, PathOpError};

/// How far from the interrupted path a restart may begin.
pub mod path_hold_limits {
    pub use super::path_hold::{QUICK_RAMP_SHARE, RAMP_SHARE, REGAIN_MAX_DEG, REGAIN_MAX_MM};
}

/// Most position events a corner path carries over from the segment it leaves (more are
/// fired when the corner starts).
const CARRY_CAPACITY: usize = 64;

/// Record that the position event `key` of `instr` fired at `now`.
fn fire(events: &mut EventLog, now: RobotTime, instr: InstrRef, key: u64) {
    events.push(MotionEvent {
        time: now,
        severity: Severity::Info,
        instr: Some(instr),
        error: MotionError::Trigger { key },
    });
}

/// The segment being played.
#[derive(Debug)]
struct Active {
    seg: Segment,
    /// Playing the corner samples (else the segment's own samples).
    in_corner: bool,
    /// Next sample index in the current list.
    idx: usize,
    /// The first of the segment's position events not yet fired.
    trig: usize,
}

/// A stop under way (module docs).
#[derive(Debug)]
struct Braking {
    brake: Brake,
    /// The active tool's TCP relative to the flange (for the TCP of the braking cycles).
    tool: Pose,
    /// The instruction that was moving the robot.
    instr: Option<InstrRef>,
    /// Halt once at rest: a motion error stopped the robot.
    halt: bool,
}

/// External guidance and what it needs each cycle.
struct External {
    guidance: Box<dyn ExternalGuidance>,
    tool: ToolData,
    instr: Option<InstrRef>,
}

/// One output of [`Executor::next_sample`].
struct Out {
    sample: Sample,
    /// The last sample of a stop point.
    at_stop_point: bool,
    /// The first sample of a segment or of its corner path (its tool may differ from the
    /// previous sample's).
    first: bool,
}

/// The executing half of the motion core (see the module docs).
pub struct Executor {
    robot: Robot,
    period: Duration,
    dt: f64,
    capacity: usize,
    queue: VecDeque<Segment>,
    active: Option<Active>,
    done: VecDeque<Segment>,
    events: EventLog,
    external: Option<External>,
    retired: Option<Box<dyn ExternalGuidance>>,
    setpoint: Setpoint,
    last_done: Option<InstrRef>,
    halted: bool,
    correction: Option<Box<dyn PathCorrection>>,
    track: Option<Track>,
    /// The planned sample of the last cycle before its path correction (the setpoint is the
    /// corrected one): where an interpolation at a path rate below 1 starts in a corrected
    /// sequence. Kept only while a correction is installed (no copy in the plain tick).
    planned: Option<Sample>,
    /// Joint speeds of the last cycle, deg/s.
    velocity: JointsDeg,
    braking: Option<Braking>,
    /// The rate the path is played at (`executor/path_hold.rs`).
    rate: path_hold::PathRate,
    /// Interpolation between samples while the rate is not 1.
    scaled: Option<path_hold::Scaled>,
    /// The path put aside by `StorePath`.
    stored: Option<path_hold::StoredPath>,
    /// An empty queue with room for every segment, for the new path of `StorePath`.
    spare_queue: VecDeque<Segment>,
    /// After `RestoPath`: the place on the path where the robot held (for the regain check).
    held_at: Option<JointsDeg>,
    /// Position events of the segment a corner path left, still to fire in the corner:
    /// (instruction, key, share of the corner path where it fires).
    carry: Vec<(InstrRef, u64, f64)>,
}

impl std::fmt::Debug for Executor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Executor")
            .field("setpoint", &self.setpoint)
            .field("queued", &self.queue.len())
            .field("halted", &self.halted)
            .finish_non_exhaustive()
    }
}

impl Executor {
    /// An idle executor holding the robot at `start`.
    pub fn new(robot: Robot, config: &CoreConfig, start: JointsDeg) -> Executor {
        let config = config.sanitized();
        let capacity = config.queue_capacity.max(1);
        let tcp = robot.tcp_world(&start, &ToolData::tool0());
        Executor {
            period: config.period,
            dt: config.period.as_secs_f64(),
            capacity,
            queue: VecDeque::with_capacity(capacity),
            active: None,
            // Every segment in existence fits: queued, active, and parked.
            done: VecDeque::with_capacity(capacity + 2),
            events: EventLog::with_capacity(config.event_capacity),
            external: None,
            retired: None,
            setpoint: Setpoint {
                time: RobotTime::ZERO,
                tick: 0,
                joints: start,
                tcp,
                speed: 0.0,
                standstill: true,
                instr: None,
            },
            last_done: None,
            halted: false,
            correction: None,
            planned: None,
            track: None,
            velocity: [0.0; 6],
            braking: None,
            rate: path_hold::PathRate::default(),
            scaled: None,
            stored: None,
            spare_queue: VecDeque::with_capacity(capacity),
            held_at: None,
            carry: Vec::with_capacity(CARRY_CAPACITY),
            robot,
        }
    }

    /// The motion cycle.
    pub fn period(&self) -> Duration {
        self.period
    }

    /// True when another segment fits in the queue.
    pub fn has_space(&self) -> bool {
        self.queue.len() < self.capacity
    }

    /// Queue a planned segment; gives it back when the queue is full (unboxed: boxing would
    /// allocate).
    #[allow(clippy::result_large_err)]
    pub fn push(&mut self, seg: Segment) -> Result<(), Segment> {
        if self.has_space() {
            self.queue.push_back(seg);
            Ok(())
        } else {
            Err(seg)
        }
    }

    /// Take a finished segment for recycling (outside the cycle).
    pub fn take_done(&mut self) -> Option<Segment> {
        self.done.pop_front()
    }

    /// Take the oldest unread event.
    pub fn take_event(&mut self) -> Option<MotionEvent> {
        self.events.pop()
    }

    /// Record an event (used by the core for planning errors and warnings).
    pub fn log(&mut self, severity: Severity, instr: Option<InstrRef>, error: MotionError) {
        self.events.push(MotionEvent {
            time: self.setpoint.time,
            severity,
            instr,
            error,
        });
    }

    /// The last setpoint.
    pub fn setpoint(&self) -> &Setpoint {
        &self.setpoint
    }

    /// A snapshot of the state.
    pub fn state(&self) -> MotionState {
        MotionState {
            setpoint: self.setpoint,
            pending: self.queue.len(),
            moving: self.active.is_some() || self.braking.is_some() || self.scaled_pending(),
            last_done: self.last_done,
            halted: self.halted,
            mode: if self.external.is_some() {
                CoreMode::External
            } else {
                CoreMode::Planned
            },
            events_total: self.events.total(),
            held: self.rate.hold,
            held_at_rest: self.held_at_rest(),
        }
    }

    /// True after a motion error, until [`Executor::recover`].
    pub fn is_halted(&self) -> bool {
        self.halted
    }

    /// Leave the halted state; the robot stays where it stopped.
    pub fn recover(&mut self) {
        self.halted = false;
    }

    /// Stop: drop every queued and active move (kept for recycling) and brake to rest from
    /// the current speed (module docs); [`MotionState::moving`] stays true until the robot
    /// is at rest. External guidance is left to stop itself.
    pub fn stop(&mut self) {
        self.clear();
        self.reset_scaling();
        self.track = None;
        if self.external.is_none() && !self.halted && self.braking.is_none() {
            let instr = self.setpoint.instr;
            self.begin_brake(instr, false);
        }
    }

    /// True while the robot brakes to rest after a stop or a motion error.
    pub fn is_braking(&self) -> bool {
        self.braking.is_some()
    }

    /// Drop every queued and active move (kept for recycling) at once, without braking: for
    /// a robot at rest.
    pub fn clear(&mut self) {
        self.carry.clear();
        if let Some(a) = self.active.take() {
            self.park(a.seg);
        }
        while let Some(s) = self.queue.pop_front() {
            self.park(s);
        }
    }

    fn park(&mut self, seg: Segment) {
        // `done` has room for every segment that exists; if a caller never recycles, the
        // oldest parked segment is dropped rather than growing the buffer.
        if self.done.len() == self.done.capacity() {
            self.done.pop_front();
        }
        self.done.push_back(seg);
    }

    /// Hand the robot to external guidance. Only at a stop point: nothing queued or moving.
    pub fn start_external(
        &mut self,
        guidance: Box<dyn ExternalGuidance>,
        tool: ToolData,
        instr: Option<InstrRef>,
    ) -> Result<(), MotionError> {
        if self.halted {
            return Err(MotionError::Halted);
        }
        if self.external.is_some() {
            return Err(MotionError::ExternalGuidance);
        }
        if self.active.is_some() || !self.queue.is_empty() || self.braking.is_some() {
            return Err(MotionError::NotAtStopPoint);
        }
        self.external = Some(External {
            guidance,
            tool,
            instr,
        });
        Ok(())
    }

    /// End external guidance now (the robot holds); returns the guidance object.
    pub fn stop_external(&mut self) -> Option<Box<dyn ExternalGuidance>> {
        self.external
            .take()
            .map(|e| e.guidance)
            .or_else(|| self.retired.take())
    }

    /// Take a guidance object that finished by itself (to drop it outside the cycle).
    pub fn take_retired(&mut self) -> Option<Box<dyn ExternalGuidance>> {
        self.retired.take()
    }

    /// Install (or with `None` remove) the path correction of planned moves
    /// (`motion::correction`); returns the previous one. Takes effect with the next sample.
    pub fn set_path_correction(
        &mut self,
        correction: Option<Box<dyn PathCorrection>>,
    ) -> Option<Box<dyn PathCorrection>> {
        self.track = None;
        std::mem::replace(&mut self.correction, correction)
    }

    /// True while a path correction is installed.
    pub fn has_path_correction(&self) -> bool {
        self.correction.is_some()
    }

    /// One motion cycle at robot time `now`.
    pub fn tick(&mut self, now: RobotTime) -> Setpoint {
        let prev = self.setpoint;
        let sp = if self.braking.is_some() {
            self.brake_tick(now, &prev)
        } else {
            let sp = self.play(now, &prev);
            // A motion error in this cycle began a brake: this cycle is its first step.
            if self.braking.is_some() {
                self.brake_tick(now, &prev)
            } else {
                sp
            }
        };
        // A stop point reached is rest: its last sample ends the profile at zero speed.
        for ((v, q), p) in self.velocity.iter_mut().zip(&sp.joints).zip(&prev.joints) {
            *v = if sp.standstill {
                0.0
            } else {
                (q - p) / self.dt
            };
        }
        self.setpoint = sp;
        sp
    }

    /// One cycle of planned moves or external guidance after `prev`.
    fn play(&mut self, now: RobotTime, prev: &Setpoint) -> Setpoint {
        let prev = *prev;
        // Whether this cycle's TCP may belong to another tool than the previous one's.
        let mut fresh = false;
        let (target, at_stop_point, instr, tool_tcp) = if self.halted {
            (None, true, None, None)
        } else if let Some(ext) = self.external.as_mut() {
            match ext.guidance.step(now, &prev.joints) {
                GuidanceStep::MoveTo(q) => {
                    let tcp = self.robot.tcp_world(&q, &ext.tool);
                    (Some(q), false, ext.instr, Some(tcp))
                }
                GuidanceStep::Hold => (None, false, ext.instr, None),
                GuidanceStep::Finished => {
                    if let Some(e) = self.external.take() {
                        self.retired = Some(e.guidance);
                    }
                    (None, true, None, None)
                }
            }
        } else {
            let next = if self.scaling() {
                self.scaled_sample(now)
            } else {
                self.next_sample(now)
            };
            match next {
                Some(mut out) => {
                    // A path correction sequence ends at a planned stop point only.
                    let planned_stop = out.at_stop_point;
                    // Held on the path at rest: the robot stands still.
                    out.at_stop_point |= self.held_at_rest();
                    fresh = out.first;
                    let mut instr = self
                        .active_instr()
                        .or(self.pending_done())
                        .or(self.last_done);
                    if self.correction.is_some() {
                        self.planned = Some(out.sample);
                    }
                    match self.correct(now, &mut instr, out.sample, planned_stop, &prev) {
                        Ok(sample) => (Some(sample.q), out.at_stop_point, instr, Some(sample.tcp)),
                        Err(error) => {
                            self.fault(instr, error);
                            (None, true, instr, None)
                        }
                    }
                }
                None => (None, true, None, None),
            }
        };
        let mut sp = prev.held(now, at_stop_point, instr);
        if let (Some(q), Some(tcp)) = (target, tool_tcp) {
            match self.supervise(&prev.joints, &q) {
                Ok(()) => {
                    sp.joints = q;
                    sp.tcp = tcp;
                    sp.speed = self.tcp_speed(&prev, &q, &tcp, fresh || instr != prev.instr);
                }
                Err(error) => self.fault(instr, error),
            }
        }
        if self.halted {
            sp.standstill = true;
            sp.speed = 0.0;
        }
        sp
    }

    /// Begins a brake from the last cycle's speed (module docs); `halt`: halt at rest. A
    /// robot already at rest stops (and halts) at once.
    fn begin_brake(&mut self, instr: Option<InstrRef>, halt: bool) {
        let speed = self.velocity;
        if speed.iter().all(|v| *v == 0.0 || !v.is_finite()) {
            self.halted |= halt;
            return;
        }
        let steps = fewest_steps(&speed, &self.robot.model().max_accel, self.dt);
        let sp = &self.setpoint;
        let tool = self.robot.fk(&sp.joints).inverse() * sp.tcp;
        self.braking = Some(Braking {
            brake: Brake::new(speed, steps),
            tool,
            instr,
            halt,
        });
    }

    /// One cycle of the brake after `prev`.
    fn brake_tick(&mut self, now: RobotTime, prev: &Setpoint) -> Setpoint {
        let mut sp = prev.held(now, true, None);
        let Some(b) = self.braking.as_mut() else {
            return sp;
        };
        let (v, done) = b.brake.step();
        let limits = &self.robot.model().joint_limits;
        for ((q, v), l) in sp.joints.iter_mut().zip(&v).zip(limits) {
            // The planner never plans beyond an axis range; the brake never leaves one.
            *q = (*q + v * self.dt).clamp(l.min, l.max);
        }
        let tcp = self.robot.fk(&sp.joints) * b.tool;
        if tcp.translation.vector.iter().all(|c| c.is_finite()) {
            sp.speed = (tcp.translation.vector - prev.tcp.translation.vector).norm() / self.dt;
            sp.tcp = tcp;
        }
        sp.standstill = done;
        sp.instr = if done { None } else { b.instr };
        if done {
            self.halted |= b.halt;
            self.braking = None;
        }
        sp
    }

    /// TCP speed (mm/s) from the previous setpoint to the TCP `tcp` at axes `q`. When `fresh`
    /// (a new segment, corner or instruction starts) and the tool is not the previous cycle's,
    /// the previous position is taken with this cycle's tool: a tool change moves the TCP
    /// without moving the robot.
    fn tcp_speed(&self, prev: &Setpoint, q: &JointsDeg, tcp: &Pose, fresh: bool) -> f64 {
        let mut from = prev.tcp.translation.vector;
        if fresh {
            let tool = self.robot.fk(q).inverse() * tcp;
            let prev_flange = self.robot.fk(&prev.joints);
            let prev_tool = prev_flange.inverse() * prev.tcp;
            let moved = (tool.translation.vector - prev_tool.translation.vector).norm();
            let same_tool_from = (prev_flange * tool).translation.vector;
            // (1 µm: the same tool, up to rounding; keep the previous TCP exactly then.)
            if moved > 1e-3 && same_tool_from.iter().all(|c| c.is_finite()) {
                from = same_tool_from;
            }
        }
        (tcp.translation.vector - from).norm() / self.dt
    }

    /// Per-cycle supervision: finite values inside the axis ranges, axis speeds within limits.
    fn supervise(&self, from: &JointsDeg, to: &JointsDeg) -> Result<(), MotionError> {
        self.robot
            .check_limits(to)
            .map_err(|error| MotionError::Kinematics {
                error,
                place: PathPlace::Cycle,
            })?;
        let model = self.robot.model();
        let (ratio, axis) = limits::step_speed_ratio(from, to, self.dt, &model.max_speed);
        if ratio > 1.0 + SPEED_SUPERVISION_SLACK {
            let max = model.max_speed.get(axis).copied().unwrap_or(f64::NAN);
            return Err(MotionError::JointSpeed {
                joint: axis + 1,
                speed: ratio * max,
                max,
            });
        }
        Ok(())
    }

    /// Apply the path correction to a planned sample (`motion::correction`): the sample
    /// itself when it is not corrected.
    fn correct(
        &mut self,
        now: RobotTime,
        instr: &mut Option<InstrRef>,
        sample: Sample,
        at_stop_point: bool,
        prev: &Setpoint,
    ) -> Result<Sample, MotionError> {
        let (Some(corr), Some(instr)) = (self.correction.as_mut(), instr.as_mut()) else {
            self.track = None;
            return Ok(sample);
        };
        if !corr.corrects(instr) {
            let open = self.track.is_some_and(|t| t.open);
            self.track = None;
            if open {
                corr.leave(now, instr)?;
            }
            return Ok(sample);
        }
        instr.name = corr.rename(instr);
        let flange = self.robot.fk(&sample.q);
        let here = sample.tcp.translation.vector;
        let (track, first) = match self.track {
            Some(t) if t.open => (t, false),
            _ => {
                // The sequence starts at the fine point the robot stands in: the previous
                // setpoint, with this move's tool (flange⁻¹ · TCP of the sample).
                let tool = flange.inverse() * sample.tcp;
                let start = self.robot.fk(&prev.joints) * tool;
                let last = start.translation.vector;
                let last = if last.iter().all(|c| c.is_finite()) {
                    last
                } else {
                    here
                };
                (
                    Track {
                        s: 0.0,
                        last,
                        open: true,
                    },
                    true,
                )
            }
        };
        let step = here - track.last;
        let len = step.norm();
        let s = if len.is_finite() {
            track.s + len
        } else {
            track.s
        };
        self.track = Some(Track {
            s,
            last: here,
            open: !at_stop_point,
        });
        let point = PathPoint {
            instr: *instr,
            s,
            tcp: sample.tcp,
            flange,
            step,
            first,
            stop_point: at_stop_point,
        };
        let offset = corr.offset(now, &point)?;
        if offset.iter().all(|c| *c == 0.0) {
            return Ok(sample);
        }
        if !offset.iter().all(|c| c.is_finite()) {
            return Err(MotionError::InvalidData {
                what: "path correction offset (mm)",
                value: offset.norm(),
            });
        }
        let shift = Translation3::from(offset);
        let q = self
            .robot
            .ik_nearest(&(shift * flange), &prev.joints)
            .map_err(|error| MotionError::Kinematics {
                error,
                place: PathPlace::Cycle,
            })?;
        Ok(Sample {
            q,
            tcp: shift * sample.tcp,
        })
    }

    /// Stop everything after a supervision error: the robot brakes to rest, then the
    /// executor is halted.
    fn fault(&mut self, instr: Option<InstrRef>, error: MotionError) {
        self.track = None;
        self.clear();
        self.reset_scaling();
        if let Some(e) = self.external.take() {
            self.retired = Some(e.guidance);
        }
        self.log(Severity::Error, instr, error);
        self.begin_brake(instr, true);
    }

    fn active_instr(&self) -> Option<InstrRef> {
        self.active.as_ref().map(|a| a.seg.instr)
    }

    /// The next sample of the planned moves, handing over into corner paths and finishing
    /// segments as they end. `None` when there is nothing to play.
    fn next_sample(&mut self, now: RobotTime) -> Option<Out> {
        // Each pass either returns or makes progress (a segment started, a corner ended, or a
        // segment finished), so this terminates within a few passes.
        for _ in 0..(4 + 2 * self.capacity) {
            let Some(act) = self.active.as_mut() else {
                let mut seg = self.queue.pop_front()?;
                // Starting from rest: a corner planned into this segment is void.
                seg.corner = None;
                self.active = Some(Active {
                    seg,
                    in_corner: false,
                    idx: 0,
                    trig: 0,
                });
                continue;
            };
            if act.in_corner {
                if let Some(s) = act.seg.corner_samples.get(act.idx) {
                    let first = act.idx == 0;
                    act.idx += 1;
                    // Position events in the corner path: the left segment's up to its
                    // ToPoint in the first half, this segment's up to its corner exit in
                    // the second half.
                    let share = act.idx as f64 / act.seg.corner_samples.len().max(1) as f64;
                    let events = &mut self.events;
                    self.carry.retain(|&(instr, key, at)| {
                        let due = at <= share;
                        if due {
                            fire(events, now, instr, key);
                        }
                        !due
                    });
                    let resume = act.seg.corner.map_or(0, |c| c.resume_at).max(1);
                    while let Some(t) = act.seg.triggers.get(act.trig) {
                        let at = 0.5 + 0.5 * (t.at + 1) as f64 / resume as f64;
                        if t.at >= resume || at > share {
                            break;
                        }
                        fire(&mut self.events, now, act.seg.instr, t.key);
                        act.trig += 1;
                    }
                    return Some(Out {
                        sample: *s,
                        at_stop_point: false,
                        first,
                    });
                }
                for (instr, key, _) in self.carry.drain(..) {
                    fire(&mut self.events, now, instr, key);
                }
                act.in_corner = false;
                act.idx = act.seg.corner.map_or(0, |c| c.resume_at);
                continue;
            }
            let handoff = self
                .queue
                .front()
                .and_then(|n| n.corner)
                .is_some_and(|c| c.enter_at == act.idx);
            if handoff {
                // The position events of the segment left: into the first half of the
                // corner path, by where they are in the part the corner replaces.
                let enter = act.idx;
                let len = act.seg.samples.len().saturating_sub(enter).max(1);
                for t in act.seg.triggers.get(act.trig..).unwrap_or(&[]) {
                    let at = 0.5 * (t.at + 1).saturating_sub(enter) as f64 / len as f64;
                    if self.carry.len() < CARRY_CAPACITY {
                        self.carry.push((act.seg.instr, t.key, at));
                    } else {
                        fire(&mut self.events, now, act.seg.instr, t.key);
                    }
                }
                act.trig = act.seg.triggers.len();
                if let Some(next) = self.queue.pop_front()
                    && let Some(old) = self.active.replace(Active {
                        seg: next,
                        in_corner: true,
                        idx: 0,
                        trig: 0,
                    })
                {
                    self.last_done = Some(old.seg.instr);
                    self.park(old.seg);
                }
                continue;
            }
            if let Some(s) = act.seg.samples.get(act.idx).copied() {
                let first = act.idx == 0;
                while let Some(t) = act.seg.triggers.get(act.trig) {
                    if t.at > act.idx {
                        break;
                    }
                    fire(&mut self.events, now, act.seg.instr, t.key);
                    act.trig += 1;
                }
                act.idx += 1;
                let last = act.idx >= act.seg.samples.len();
                let fine = act.seg.fine;
                if last {
                    self.finish_active();
                }
                return Some(Out {
                    sample: s,
                    at_stop_point: last && fine,
                    first,
                });
            }
            self.finish_active();
        }
        None
    }

    /// The active segment has played its last sample.
    fn finish_active(&mut self) {
        let Some(act) = self.active.take() else {
            return;
        };
        let instr = act.seg.instr;
        if act.seg.flyby {
            let reason = match self.queue.front() {
                None => Some("the next move was not planned in time"),
                Some(n) if n.corner.is_some() => Some("the next move was planned too late"),
                Some(_) => None,
            };
            if let Some(reason) = reason {
                self.log(
                    Severity::Warning,
                    Some(instr),
                    MotionError::CornerPathFailure { reason },
                );
            }
        }
        self.last_done = Some(instr);
        self.park(act.seg);
    }
}
