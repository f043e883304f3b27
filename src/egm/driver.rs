//! One EGM run (EGMRunJoint / EGMRunPose) as a sans-IO per-tick state machine for the controller's loop: datagrams in, servo step, `EgmRobot` out, convergence, stops and errors.
//!
//! # Use
//!
//! ```text
//! plan   = registry.run_joint(id, &args, axes)?            // interpreter thread
//! source = EgmSource::new(&plan.source)                      // the controller binds the socket
//! driver = EgmDriver::start(now, &ctx, &plan, source, &q)?   // q: the fine point
//! every motion tick (4 ms), in the controller's loop:
//!     for (from, bytes) in socket.drain() { driver.handle_datagram(now, from, bytes) }
//!     t = driver.tick(now, &q)      // q: last commanded joints
//!     if let Some((to, bytes)) = driver.poll_transmit(now) { socket.send_to(bytes, to) }
//!     command t.joints_cmd; while let Some(e) = driver.poll_event() { log e }
//!     while let Some(row) = driver.pop_log() { egm-log }     // or later, off the RT path
//!     if lockstep && driver.awaiting_reply() { wait for the reply, handle it, then
//!                                              driver.reply_wait_over() }
//!     if let Some(result) = t.finished { registry.run_finished(id, result.is_ok()); … }
//! EGMStop  → driver.stop(mode, ramp_out)    program stop → driver.halt()
//! ```
//!
//! `now` is the controller's clock (real or virtual), a [`RobotTime`]; it becomes
//! `header.tm` and the `EgmClock`s.
//!
//! # Per tick
//!
//! 1. Receive: the datagrams handed in since the last tick are in the [`EgmSession`]
//!    (newest valid reference wins); for signal sources, read the signals when a sample is
//!    due (every `\SampleRate`).
//! 2. Reference: joint mode takes the joints (and `speedRef`) as they are; pose mode turns
//!    the sensor pose into joints with [`PoseGuidance::joint_target`] (IK nearest to
//!    `current`, supervised) and `speedRef.cartesians` into joint speeds through the
//!    Jacobian. A reference that cannot be reached (50050), needs an axis beyond its limit
//!    (50027) or lies close to a singularity (50026) ends the run with that error: the robot
//!    brakes as for a program stop (`egm::servo`), then `finished` is `Err`. A joint
//!    reference beyond an axis limit is dropped with event 90105 ("input out of bounds") and
//!    the previous one stays in force.
//! 3. Servo step ([`EgmServo`]): the control law, MaxSpeedDeviation (event 90110 when it
//!    starts limiting — at the default 1 °/s it usually does), MaxPosDeviation (90111), and
//!    the robot's axis ranges (90112): the command never crosses a joint limit.
//! 4. Encode the `EgmRobot` when due (for [`DatagramMachine::poll_transmit`]; the built-in
//!    sensor answers it in process at once): `feedBack` = the measured (servo-delayed) position,
//!    `planned` = the commanded one; the Cartesian parts are the TCP of `\Tool` relative to
//!    the correction frame in pose mode and to `\WObj` in joint mode (guidance's feedback
//!    rules); MOTORS_ON (MOTORS_OFF after [`EgmDriver::set_motors`]), RAPID_RUNNING (RAPID_STOPPED after [`EgmDriver::halt`]), MCI
//!    RUNNING (STOPPED after a halt, ERROR after an error); `mciConvergenceMet`;
//!    `utilizationRate` = requested EGM speed / MaxSpeedDeviation.
//! 5. Convergence: every selected axis (direction) inside its window, held continuously for
//!    `\CondTime` → the stop mode runs (HOLD settles, RAMP_DOWN returns to the start) →
//!    `finished` = `Ok(EgmEnd::Converged)`. Convergence only counts once a reference
//!    arrived.
//! 6. Comm time-out: no valid sensor message within `\CommTimeout` → the robot brakes as
//!    for a program stop → `Err(EgmError::CommTimeout)` (event 41822, `ERR_UDPUC_COMM`).
//!
//! `finished` is reported on exactly one tick ([`EgmDriver::outcome`] keeps it). The events
//! of [`EgmDriver::poll_event`] never repeat the error in `finished`.
//!
//! # Lockstep (virtual time driven by an external sensor)
//!
//! After a tick that sent to an external sensor, [`DatagramMachine::awaiting_reply`] is true until
//! a valid reply arrived. The controller's loop then blocks (real time, outside the tick) up
//! to a per-message time-out for it, so a virtual-time controller advances only when the
//! sensor has answered and runs as fast as the sensor allows. This relies on the sensor
//! replying once per received message, which all four tested clients do (abb_libegm,
//! abb_robot_client, ABBRobotEGM, abbegm); a sensor that sends on its own timer instead
//! makes every message wait for the time-out. Clients that check `header.tm` against real
//! time (abb_libegm's `isConnected`) see virtual milliseconds. Once the comm time-out has
//! been declared (41822) nothing is awaited any more: the ramp-out runs without waits.
//!
//! Nothing here panics, owns a socket, reads a clock, sleeps or blocks; `tick` allocates only
//! for event texts, and in pose mode inside the IK.

use std::collections::VecDeque;
use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;

use crate::egm::convert::{ReferenceLimits, euler_zyx_from_quaternion};
use crate::egm::event::{EgmEvent, EventKind};
use crate::egm::geometry::{
    FeedbackMode, GuidanceError, PoseGuidance, SignalSource, feedback_in_wobj,
};
use crate::egm::message_log::{LogKind, LogRing, LogRow};
use crate::egm::registry::{EgmError, RunPlan};
use crate::egm::sensor::SensorStats;
use crate::egm::servo::{
    DEFAULT_RAMP_TIME, EgmServo, EndCause, ServoInput, ServoOutput, ServoPhase, StopMode,
    axis_limit_event, pos_clamp_event, speed_limit_event,
};
use crate::egm::session::{EgmConfig, EgmSession, EgmStats, Outcome, SourceFilter};
use crate::egm::types::{
    EgmMode, ExternalAxes, Joints, MciState, MotorState, Pose as WirePose, ROBOT_AXES, RapidData,
    RapidExecState, RobotFeedback, SensorReference, Target,
};
use crate::robot::{Pose, Robot, ToolData, WobjData};
use crate::signals::{SignalId, SignalTable};
use crate::time::RobotTime;

mod corrections;
mod delay;
mod feedback;
mod options;
mod reference;
mod source;
mod stream;

pub use corrections::{Correction, CorrectionInput, CorrectionLink, CorrectionTick};
pub(crate) use options::check_options;
pub use options::{DEFAULT_REPLY_TIMEOUT, DriverContext, DriverOptions, MAX_EVENTS};
pub use source::EgmSource;
use source::{BUILTIN_ADDR, Peer};
pub use stream::{EgmStream, StreamTick};

/// How a run ended without error.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EgmEnd {
    /// Convergence held for `\CondTime`; the stop mode ran.
    Converged,
    /// EGMStop ended it.
    Stopped,
    /// A program stop ramped it out ([`EgmDriver::halt`]); when the program starts again the
    /// controller may start a new driver from the same plan (the run resumes from where the
    /// robot stands, with a new session, seqno 0).
    Halted,
    /// No axis or direction was selected: no movement, RAPID continues.
    NoMovement,
}

/// The result of one tick.
#[derive(Clone, Debug, PartialEq)]
pub struct EgmTick {
    /// The joints to command this tick, degrees (never beyond an axis limit).
    pub joints_cmd: Joints,
    /// The measured (servo-delayed) joints sent as feedback, degrees.
    pub feedback: Joints,
    /// The convergence criteria are met right now.
    pub converged: bool,
    /// The servo phase.
    pub phase: ServoPhase,
    /// The MCI state sent.
    pub mci_state: MciState,
    /// `utilizationRate`, percent.
    pub utilization: f64,
    /// MaxSpeedDeviation limited the speed this tick.
    pub speed_limited: bool,
    /// An `EgmRobot` went out this tick (or the signals were sampled).
    pub sent: bool,
    /// Events waiting in [`EgmDriver::poll_event`].
    pub events: usize,
    /// Set on the one tick the run finished.
    pub finished: Option<Result<EgmEnd, EgmError>>,
}

/// A bounded event queue.
#[derive(Clone, Debug, Default)]
pub(crate) struct EventQueue {
    q: VecDeque<EgmEvent>,
    dropped: u64,
}

impl EventQueue {
    fn with_capacity() -> EventQueue {
        EventQueue {
            q: VecDeque::with_capacity(MAX_EVENTS),
            dropped: 0,
        }
    }

    pub(crate) fn push(&mut self, e: EgmEvent) {
        if self.q.len() >= MAX_EVENTS {
            self.dropped += 1;
        } else {
            self.q.push_back(e);
        }
    }

    fn pop(&mut self) -> Option<EgmEvent> {
        self.q.pop_front()
    }

    fn len(&self) -> usize {
        self.q.len()
    }
}

/// How references arrive.
#[derive(Debug)]
enum Link {
    /// UdpUc or built-in: an EGM session.
    Session {
        session: Box<EgmSession>,
        peer: Peer,
        buf: Vec<u8>,
        device: String,
    },
    /// Signals, sampled every `period`.
    Signals {
        source: SignalSource,
        next_sample: RobotTime,
        samples: u32,
    },
}

/// What arrived this tick (a short-lived stack value: boxing it would allocate per tick).
#[allow(clippy::large_enum_variant)]
enum Incoming {
    Sensor(SensorReference),
    Signals(SignalSource, u32),
}

/// One EGM run (see the module docs).
#[derive(Debug)]
pub struct EgmDriver {
    name: String,
    instruction: &'static str,
    mode: EgmMode,
    robot: Robot,
    signals: Arc<SignalTable>,
    tick_period: Duration,
    servo_delay: Duration,
    sample_period: Duration,
    halt_ramp: Duration,
    ramp_out: Duration,
    comm_timeout: Duration,
    guidance: Option<Box<PoseGuidance>>,
    tool: ToolData,
    wobj: WobjData,
    servo: EgmServo,
    link: Link,
    start: Joints,
    input: ServoInput,
    have_reference: bool,
    ordered: Option<Pose>,
    cmd: Joints,
    fb: Joints,
    fb_pose: WirePose,
    planned_pose: WirePose,
    motors: MotorState,
    exec: RapidExecState,
    mci: MciState,
    error: Option<EgmError>,
    outcome: Option<Result<EgmEnd, EgmError>>,
    no_movement: bool,
    events: EventQueue,
    log: LogRing,
    pending: Option<LogRow>,
    awaiting: bool,
    do_to_sensor: Option<SignalId>,
    di_from_sensor: Option<SignalId>,
    out_of_bounds: bool,
    speed_ref_reported: bool,
}

impl EgmDriver {
    /// Starts `plan` at `now` from `current` (the fine point the robot stands in) with an
    /// opened `source`.
    ///
    /// Errors: `current` not finite or beyond an axis limit ([`EgmError::Supervision`]);
    /// frames, tool or work object pose guidance cannot use ([`EgmError::Guidance`]); servo
    /// parameters out of range ([`EgmError::Servo`]); a built-in pattern of another mode
    /// ([`EgmError::BadDevice`]). On error the registry must hear
    /// [`crate::egm::EgmRegistry::run_finished`] with `ok = false`.
    pub fn start(
        now: RobotTime,
        ctx: &DriverContext,
        plan: &RunPlan,
        source: EgmSource,
        current: &Joints,
    ) -> Result<EgmDriver, EgmError> {
        let instruction = plan.instruction;
        let opts = &ctx.options;
        check_options(instruction, opts)?;
        if !current.iter().all(|v| v.is_finite()) {
            return Err(EgmError::Supervision(GuidanceError::NotFinite {
                what: "start position",
            }));
        }
        ctx.robot
            .check_limits(current)
            .map_err(|e| EgmError::Supervision(e.into()))?;
        let guidance = match (&plan.pose, plan.mode) {
            (Some(setup), EgmMode::Pose) => Some(Box::new(
                PoseGuidance::new(&ctx.robot, setup, current).map_err(|source| {
                    EgmError::Guidance {
                        instruction,
                        source,
                    }
                })?,
            )),
            (None, EgmMode::Pose) => {
                return Err(EgmError::BadSetup {
                    instruction,
                    detail: "a pose-mode run needs its frames (EGMActPose)".to_string(),
                });
            }
            _ => None,
        };
        let params = plan.servo_params(opts.tick, opts.servo_delay, &ctx.robot);
        let servo = EgmServo::new(params, *current).map_err(|source| EgmError::Servo {
            instruction,
            source,
        })?;
        let moves = plan.moves();
        let link = match source {
            EgmSource::Udp { device, remote } => {
                let mut session = new_session(plan, ctx, remote, opts.source_filter)?;
                if moves {
                    session.start(now);
                }
                Link::Session {
                    session: Box::new(session),
                    peer: Peer::external(remote),
                    buf: Vec::with_capacity(512),
                    device,
                }
            }
            EgmSource::Builtin { device, pattern } => {
                if pattern.mode() != plan.mode {
                    return Err(EgmError::BadDevice {
                        instruction,
                        device,
                        detail: format!(
                            "the built-in sensor talks {} mode, the run is in {} mode",
                            pattern.mode(),
                            plan.mode
                        ),
                    });
                }
                let origin = guidance
                    .as_ref()
                    .map(|g| WirePose::from(g.start_sensor_pose()));
                let peer = Peer::builtin(&device, pattern, origin)?;
                let mut session = new_session(plan, ctx, BUILTIN_ADDR, SourceFilter::Any)?;
                if moves {
                    session.start(now);
                }
                Link::Session {
                    session: Box::new(session),
                    peer,
                    buf: Vec::with_capacity(512),
                    device,
                }
            }
            EgmSource::Signals { source, .. } => Link::Signals {
                source,
                next_sample: now,
                samples: 0,
            },
            EgmSource::Seam { .. } => {
                return Err(EgmError::Unsupported {
                    instruction,
                    what: "position guidance from a simulated LTAPP device (it only corrects paths)",
                });
            }
        };
        let halt_ramp =
            Duration::try_from_secs_f64(plan.profile.ramp_time).unwrap_or(DEFAULT_RAMP_TIME);
        let mut driver = EgmDriver {
            name: plan.name.clone(),
            instruction,
            mode: plan.mode,
            robot: ctx.robot.clone(),
            signals: Arc::clone(&ctx.signals),
            tick_period: opts.tick,
            servo_delay: opts.servo_delay,
            sample_period: plan.sample_period,
            halt_ramp,
            ramp_out: plan.ramp_out_time,
            comm_timeout: plan.comm_timeout,
            guidance,
            tool: plan.tool,
            wobj: plan.wobj.clone(),
            servo,
            link,
            start: *current,
            input: ServoInput::position(*current),
            have_reference: false,
            ordered: None,
            cmd: *current,
            fb: *current,
            fb_pose: WirePose::IDENTITY,
            planned_pose: WirePose::IDENTITY,
            motors: MotorState::On,
            exec: RapidExecState::Running,
            mci: MciState::Running,
            error: None,
            outcome: None,
            no_movement: !moves,
            events: EventQueue::with_capacity(),
            log: LogRing::new(&plan.name, opts.log_capacity),
            pending: None,
            awaiting: false,
            do_to_sensor: plan.do_to_sensor,
            di_from_sensor: plan.di_from_sensor,
            out_of_bounds: false,
            speed_ref_reported: false,
        };
        let start_pose = driver.cartesian(current).unwrap_or(WirePose::IDENTITY);
        driver.fb_pose = start_pose;
        driver.planned_pose = start_pose;
        Ok(driver)
    }

    /// The identity's variable name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// `EGMRunJoint` or `EGMRunPose`.
    pub fn instruction(&self) -> &'static str {
        self.instruction
    }

    /// Joint or pose.
    pub fn mode(&self) -> EgmMode {
        self.mode
    }

    /// The servo phase.
    pub fn phase(&self) -> ServoPhase {
        self.servo.phase()
    }

    /// The joints the run started at.
    pub fn start_joints(&self) -> &Joints {
        &self.start
    }

    /// The last commanded joints.
    pub fn commanded(&self) -> &Joints {
        &self.cmd
    }

    /// The reference in use and the measured position in the same axes, for reports: joints
    /// in degrees in joint mode; in pose mode the ordered and the measured TCP in the
    /// correction frame (x, y, z mm; rx, ry, rz degrees, Euler ZYX). The reference is `None`
    /// before the first one arrived.
    pub fn tracking(&self) -> (Option<[f64; 6]>, [f64; 6]) {
        match (&self.guidance, self.mode) {
            (Some(g), EgmMode::Pose) => {
                let reference = self
                    .ordered
                    .map(|o| pose6(&WirePose::from(&(g.correction_frame().inverse() * o))));
                (reference, pose6(&self.fb_pose))
            }
            _ => {
                // Axes the run does not move keep their start value as reference.
                let selected = self.servo.params().selected;
                let mut reference = self.input.position;
                for ((r, s), on) in reference.iter_mut().zip(&self.start).zip(&selected) {
                    if !on {
                        *r = *s;
                    }
                }
                (self.have_reference.then_some(reference), self.fb)
            }
        }
    }

    /// The result, once finished.
    pub fn outcome(&self) -> Option<&Result<EgmEnd, EgmError>> {
        self.outcome.as_ref()
    }

    /// True once finished.
    pub fn is_finished(&self) -> bool {
        self.outcome.is_some()
    }

    /// The session's counters (UdpUc and built-in sources).
    pub fn session_stats(&self) -> Option<&EgmStats> {
        match &self.link {
            Link::Session { session, .. } => Some(session.stats()),
            Link::Signals { .. } => None,
        }
    }

    /// The in-process built-in sensor's counters.
    pub fn sensor_stats(&self) -> Option<&SensorStats> {
        match &self.link {
            Link::Session {
                peer: Peer::Builtin(Some(sensor)),
                ..
            } => Some(sensor.stats()),
            _ => None,
        }
    }

    /// The next event (speed limit, clamps, dropped datagrams, …).
    pub fn poll_event(&mut self) -> Option<EgmEvent> {
        self.events.pop()
    }

    /// The oldest log row.
    pub fn pop_log(&mut self) -> Option<LogRow> {
        self.log.pop()
    }

    /// The log ring (for [`crate::egm::message_log::EgmLogWriter::drain`]).
    pub fn log_mut(&mut self) -> &mut LogRing {
        &mut self.log
    }

    /// `EGMStop Mode \RampOutTime`: ends the run (`ramp_out` for RAMP_DOWN; the run's
    /// `\RampOutTime` when `None`). Ignored once the run is ending.
    pub fn stop(&mut self, mode: StopMode, ramp_out: Option<Duration>) {
        if self.outcome.is_none() {
            self.servo.stop(mode, ramp_out.unwrap_or(self.ramp_out));
        }
    }

    /// Program stop: the robot brakes from its speed (over the profile's Default Ramp Time
    /// at most, sooner near the reference: `egm::servo`) while the driver keeps sending with
    /// RAPID_STOPPED and MCI_STOPPED; then `finished` is `Ok(EgmEnd::Halted)`.
    pub fn halt(&mut self) {
        if self.outcome.is_none() {
            self.exec = RapidExecState::Stopped;
            if self.error.is_none() {
                self.mci = MciState::Stopped;
            }
            self.servo.halt(self.halt_ramp);
        }
    }

    /// The program stopped with the run going on (a controller that stays up): the EGM speed
    /// ramps to zero over the profile's Default Ramp Time while the session goes on, telling
    /// the sensor RAPID_STOPPED and MCI_STOPPED; [`EgmDriver::resume`] continues the run.
    pub fn pause(&mut self) {
        if self.outcome.is_none() && self.error.is_none() {
            self.exec = RapidExecState::Stopped;
            self.mci = MciState::Stopped;
            self.servo.pause(self.halt_ramp);
        }
    }

    /// The program started again: the paused run goes on (RAPID_RUNNING, MCI_RUNNING), its
    /// EGM speed ramping back in.
    pub fn resume(&mut self) {
        if self.outcome.is_none() && self.servo.is_paused() {
            self.exec = RapidExecState::Running;
            if self.error.is_none() {
                self.mci = MciState::Running;
            }
            self.servo.resume(self.halt_ramp);
        }
    }

    /// True while paused by [`EgmDriver::pause`].
    pub fn is_paused(&self) -> bool {
        self.outcome.is_none() && self.servo.is_paused()
    }

    /// The controller's motors were switched on or off: the feedback reports it from the
    /// next message on (a controller switches them off only with the program stopped, so
    /// the run is paused or halted then).
    pub fn set_motors(&mut self, on: bool) {
        self.motors = if on { MotorState::On } else { MotorState::Off };
    }

    /// The controller's speed ratio (0…1): scales the EGM speed (`egm::servo`, "Speed
    /// scale"), reached over the profile's Default Ramp Time.
    pub fn set_speed_ratio(&mut self, ratio: f64) {
        self.servo.set_ratio(ratio, self.halt_ramp);
    }

    /// True once the session's comm time-out expired (event 41822).
    fn comm_timed_out(&self) -> bool {
        match &self.link {
            Link::Session { session, .. } => session.comm_timed_out(),
            Link::Signals { .. } => false,
        }
    }

    /// One motion tick at `now`; `current` are the joints commanded last (normally the
    /// previous tick's `joints_cmd`), used as the IK seed.
    pub fn tick(&mut self, now: RobotTime, current: &Joints) -> EgmTick {
        if self.outcome.is_some() {
            return self.idle_tick(None);
        }
        if self.no_movement {
            self.finish(Ok(EgmEnd::NoMovement));
            return self.idle_tick(self.outcome.clone());
        }
        let (incoming, timed_out) = self.receive(now);
        let running = self.servo.phase() == ServoPhase::Running;
        let mut sample: Option<(u32, [f64; 6])> = None;
        match incoming {
            Some(Incoming::Sensor(r)) if running => self.apply_sensor(&r, current),
            Some(Incoming::Sensor(r)) => self.log_reply(&r),
            Some(Incoming::Signals(src, n)) => {
                sample = self.read_signals(&src, current, running).map(|r| (n, r));
            }
            None => {}
        }
        if timed_out && self.error.is_none() && self.servo.phase() == ServoPhase::Running {
            let device = match &self.link {
                Link::Session { device, .. } => device.clone(),
                Link::Signals { .. } => String::new(),
            };
            self.fail(EgmError::CommTimeout {
                device,
                timeout: self.comm_timeout,
            });
        }
        self.input.convergence_error = self.convergence_error();
        let out = self.servo.step(&self.input);
        self.report_servo(&out);
        self.cmd = out.commanded;
        self.fb = out.feedback;
        if let Some(p) = self.cartesian(&out.feedback) {
            self.fb_pose = p;
        }
        if let Some(p) = self.cartesian(&out.commanded) {
            self.planned_pose = p;
        }
        let sent = self.transmit(now, &out);
        if let Some((n, reference)) = sample {
            let row = self.row(now, n, &out);
            self.log.push(LogRow {
                recv_time: Some(now),
                reference: Some(reference),
                ..row
            });
        }
        let mut finished = None;
        if let Some(cause) = out.finished {
            let result = match (self.error.take(), cause) {
                (Some(e), _) => Err(e),
                (None, EndCause::Converged) => Ok(EgmEnd::Converged),
                (None, EndCause::Stopped) => Ok(EgmEnd::Stopped),
                (None, EndCause::Halted) => Ok(EgmEnd::Halted),
            };
            self.finish(result);
            finished = self.outcome.clone();
        }
        EgmTick {
            joints_cmd: out.commanded,
            feedback: out.feedback,
            converged: out.convergence_met,
            phase: out.phase,
            mci_state: self.mci,
            utilization: out.utilization,
            speed_limited: out.speed_limited,
            sent: sent || sample.is_some(),
            events: self.events.len(),
            finished,
        }
    }

    /// Step 1: what arrived, and whether the comm time-out expired.
    fn receive(&mut self, now: RobotTime) -> (Option<Incoming>, bool) {
        let half = self.tick_period / 2;
        match &mut self.link {
            Link::Session { session, .. } => {
                session.handle_timeout(now);
                forward_events(session, &mut self.events);
                let timed_out = session.comm_timed_out();
                (session.poll_reference().map(Incoming::Sensor), timed_out)
            }
            Link::Signals {
                source,
                next_sample,
                samples,
            } => {
                if now.saturating_add(half) < *next_sample {
                    return (None, false);
                }
                *next_sample = next_sample.saturating_add(self.sample_period);
                if *next_sample <= now {
                    *next_sample = now.saturating_add(self.sample_period);
                }
                let n = *samples;
                *samples = samples.wrapping_add(1);
                (Some(Incoming::Signals(*source, n)), false)
            }
        }
    }

    /// Ends the run with `err` after braking to rest (first error wins).
    fn fail(&mut self, err: EgmError) {
        if self.error.is_some()
            || !matches!(
                self.servo.phase(),
                ServoPhase::Running | ServoPhase::Holding
            )
        {
            return;
        }
        self.error = Some(err);
        self.mci = MciState::Error;
        self.servo.halt(self.halt_ramp);
    }

    fn finish(&mut self, result: Result<EgmEnd, EgmError>) {
        if let Link::Session { session, .. } = &mut self.link {
            session.stop();
        }
        if let Some(done) = self.pending.take() {
            self.log.push(done);
        }
        self.awaiting = false;
        self.outcome = Some(result);
    }

    fn idle_tick(&self, finished: Option<Result<EgmEnd, EgmError>>) -> EgmTick {
        EgmTick {
            joints_cmd: self.cmd,
            feedback: self.cmd,
            converged: false,
            phase: ServoPhase::Done,
            mci_state: self.mci,
            utilization: 0.0,
            speed_limited: false,
            sent: false,
            events: self.events.len(),
            finished,
        }
    }
}

impl DatagramMachine for EgmDriver {
    /// Hands the datagram to the session while the run receives (not before it moves, not
    /// once it finished: those stay unread, as a finished run's socket closes).
    fn handle_datagram(&mut self, now: RobotTime, from: SocketAddr, bytes: &[u8]) -> bool {
        if self.outcome.is_some() || self.no_movement {
            return false;
        }
        let Link::Session { session, .. } = &mut self.link else {
            return false;
        };
        let accepted = session.handle_datagram(now, from, bytes) == Outcome::Accepted;
        if accepted {
            self.awaiting = false;
        }
        accepted
    }

    fn poll_transmit(&mut self, _now: RobotTime) -> Option<(SocketAddr, &[u8])> {
        match &mut self.link {
            Link::Session { peer, buf, .. } => peer.take_transmit(buf),
            Link::Signals { .. } => None,
        }
    }

    fn poll_timeout(&self) -> Option<RobotTime> {
        if self.outcome.is_some() {
            return None;
        }
        match &self.link {
            Link::Session { session, .. } => session.poll_timeout(),
            Link::Signals { next_sample, .. } => Some(*next_sample),
        }
    }

    /// Never once the comm time-out was declared (41822): the sensor is taken for dead, and
    /// the ramp-out after it runs at the pace of virtual time, not of a wait per cycle.
    fn awaiting_reply(&self) -> bool {
        self.awaiting && self.outcome.is_none() && !self.comm_timed_out()
    }

    fn reply_wait_over(&mut self) {
        self.awaiting = false;
    }

    fn transport_error(&mut self, event: EgmEvent) {
        self.events.push(event);
    }
}

/// The datagram side of a sans-IO EGM machine (a run's [`EgmDriver`], an [`EgmStream`], a
/// [`CorrectionLink`]): what the controller's cycle calls to carry its datagrams. The
/// machines own no socket, read no clock and never block; the loop drains the device's
/// socket into [`DatagramMachine::handle_datagram`] before the machine's tick and sends what
/// [`DatagramMachine::poll_transmit`] returns after it (see `docs/architecture.md`, "One
/// motion cycle").
pub trait DatagramMachine {
    /// A datagram from `from` arrived (handled at `now`, the cycle's time). Returns whether
    /// the session accepted it as a valid sensor message.
    fn handle_datagram(&mut self, now: RobotTime, from: SocketAddr, bytes: &[u8]) -> bool;

    /// The datagram the last tick produced for an external sensor, once: the address to
    /// send it to and its bytes.
    fn poll_transmit(&mut self, now: RobotTime) -> Option<(SocketAddr, &[u8])>;

    /// When the machine next has something to do by time alone (its comm time-out, its next
    /// sample), if ever.
    fn poll_timeout(&self) -> Option<RobotTime>;

    /// Lockstep: a message went to an external sensor and no valid reply came yet; never
    /// once the comm time-out was declared (41822).
    fn awaiting_reply(&self) -> bool;

    /// Lockstep: the loop stopped waiting for the reply to the last message (it came, or the
    /// wait timed out); the machine awaits nothing until it sends again.
    fn reply_wait_over(&mut self);

    /// A failure of the transport (sending or receiving), reported with the machine's
    /// events.
    fn transport_error(&mut self, event: EgmEvent);
}

/// The session's events, except 41822 (the run's `CommTimeout` error carries it).
fn forward_events(session: &mut EgmSession, events: &mut EventQueue) {
    while let Some(e) = session.poll_event() {
        if e.number != EventKind::CommTimeout.number() {
            events.push(e);
        }
    }
}

/// The session of a run, stream or path-correction link: `mode` with `remote` (accepting
/// senders per `filter`) at `sample_period`, with the context's options, the robot's
/// reference bounds, and the controller's drop tally.
pub(crate) fn open_session(
    ctx: &DriverContext,
    instruction: &'static str,
    mode: EgmMode,
    link: (std::net::SocketAddr, SourceFilter),
    sample_period: Duration,
    comm_timeout: Option<Duration>,
) -> Result<EgmSession, EgmError> {
    let opts = &ctx.options;
    let (remote, filter) = link;
    let mut config = EgmConfig::new(mode, remote);
    config.source_filter = filter;
    config.sample_period = sample_period;
    config.comm_timeout = comm_timeout;
    config.queue = opts.queue;
    config.encode = opts.encode;
    config.event_repeat = opts.event_repeat;
    config.limits = robot_limits(&ctx.robot);
    let mut session = EgmSession::new(config).map_err(|e| EgmError::BadSetup {
        instruction,
        detail: e.to_string(),
    })?;
    session.share_drops(Arc::clone(&ctx.drops));
    Ok(session)
}

fn new_session(
    plan: &RunPlan,
    ctx: &DriverContext,
    remote: std::net::SocketAddr,
    filter: SourceFilter,
) -> Result<EgmSession, EgmError> {
    open_session(
        ctx,
        plan.instruction,
        plan.mode,
        (remote, filter),
        plan.sample_period,
        Some(plan.comm_timeout),
    )
}

/// Reference bounds narrowed to the robot's axis ranges.
pub(crate) fn robot_limits(robot: &Robot) -> ReferenceLimits {
    let mut limits = ReferenceLimits::default();
    for ((lo, hi), l) in limits
        .joint_min
        .iter_mut()
        .zip(limits.joint_max.iter_mut())
        .zip(&robot.model().joint_limits)
    {
        *lo = l.min;
        *hi = l.max;
    }
    limits
}

/// A wire pose as x, y, z (mm) and rx, ry, rz (degrees, Euler ZYX).
fn pose6(p: &WirePose) -> [f64; 6] {
    let [x, y, z] = p.pos;
    let [rx, ry, rz] = euler_zyx_from_quaternion(p.orient);
    [x, y, z, rx, ry, rz]
}

/// The log's `state` text of a phase.
pub(crate) fn phase_name(p: ServoPhase) -> &'static str {
    match p {
        ServoPhase::Running => "running",
        ServoPhase::Holding => "holding",
        ServoPhase::RampingDown => "ramping_down",
        ServoPhase::Halting => "halting",
        ServoPhase::Done => "done",
    }
}

#[cfg(test)]
mod tests;
