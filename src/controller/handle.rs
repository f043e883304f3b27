//! `ControllerHandle`: what the program side (the interpreter, tests, the CLI) talks to.
//! `submit` plans and queues a move (blocking while the queue is full), `wait_until` blocks
//! until a condition holds, `now` and `state` observe. In virtual time the handle drives the
//! motion core itself, so robot time advances only while the program waits; in real time a
//! motion thread runs the cycles and the handle waits on its published state.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::TrySendError;
use std::time::Duration;

use crate::motion::{
    CoreMode, EnqueueError, ExternalGuidance, InstrRef, MotionCore, MotionError, MotionEvent,
    MotionSettings, MotionState, PathOp, PathOpError, Severity,
};
use crate::robot::command::MotionCommand;
use crate::robot::{Robot, ToolData};
use crate::time::RobotTime;

use super::condition::Condition;
use super::cycle_hook::CycleHook;
use super::monotonic_clock::MonotonicClock;
use super::motion_thread::Control;
use super::position_events::PositionEvents;
use super::realtime_driver::RealTimeDriver;
use super::summary::RunSummary;
use super::tick_sink::TickSink;
use super::virtual_driver::VirtualDriver;
use super::{ClockMode, ControllerConfig, ControllerError};
use crate::robot::trigger::PathTrigger;

enum Driver {
    Virtual(Box<VirtualDriver>),
    RealTime(Box<RealTimeDriver>),
}

/// The program side's handle on the virtual controller (see the module docs).
pub struct ControllerHandle {
    driver: Driver,
    robot: Robot,
    events: Vec<MotionEvent>,
    wall: MonotonicClock,
    max_wait: Duration,
    period: Duration,
    /// Set from outside (Ctrl-C): a submit blocked on a full queue gives up.
    interrupt: Option<Arc<AtomicBool>>,
    /// Real time: the planning state of the path `StorePath` put aside (the virtual core
    /// keeps its own).
    stored_plan: Option<crate::motion::planner::PlanCheckpoint>,
    /// What the position events of the queued moves do.
    position: PositionEvents,
}

impl std::fmt::Debug for ControllerHandle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ControllerHandle")
            .field("realtime", &matches!(self.driver, Driver::RealTime(_)))
            .finish_non_exhaustive()
    }
}

impl ControllerHandle {
    /// Start a controller. `sinks` receive every cycle's setpoint (the initial position first).
    pub fn start(
        config: ControllerConfig,
        sinks: Vec<Box<dyn TickSink>>,
    ) -> Result<ControllerHandle, ControllerError> {
        ControllerHandle::start_with_hook(config, sinks, None)
    }

    /// Start a controller whose shell runs `hook` around every motion cycle (e.g. the EGM
    /// exchange), on the motion thread in real time and inline in virtual time.
    pub fn start_with_hook(
        config: ControllerConfig,
        mut sinks: Vec<Box<dyn TickSink>>,
        hook: Option<Box<dyn CycleHook>>,
    ) -> Result<ControllerHandle, ControllerError> {
        config
            .robot
            .check_limits(&config.start)
            .map_err(ControllerError::InvalidStart)?;
        let robot = config.robot.clone();
        let core_config = config.core.sanitized();
        let core = MotionCore::new(config.robot, core_config, config.start);
        let driver = match config.clock {
            ClockMode::Virtual => {
                let initial = core.state().setpoint;
                for s in &mut sinks {
                    s.record(&initial);
                }
                Driver::Virtual(Box::new(VirtualDriver::new(
                    core,
                    core_config.period,
                    sinks,
                    hook,
                )))
            }
            ClockMode::RealTime(rt) => {
                let (planner, exec) = core.into_parts();
                Driver::RealTime(Box::new(RealTimeDriver::start(
                    planner,
                    exec,
                    core_config.queue_capacity,
                    config.spin,
                    rt,
                    sinks,
                    hook,
                )?))
            }
        };
        Ok(ControllerHandle {
            driver,
            robot,
            events: Vec::new(),
            wall: MonotonicClock::new(),
            max_wait: config.max_wait,
            period: core_config.period,
            interrupt: None,
            stored_plan: None,
            position: PositionEvents::default(),
        })
    }

    /// Make [`Self::submit`] give up with [`ControllerError::Interrupted`] instead of waiting
    /// for room in a full queue once `flag` turns true.
    pub fn set_interrupt(&mut self, flag: Arc<AtomicBool>) {
        self.interrupt = Some(flag);
    }

    /// The robot.
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// The motion cycle.
    pub fn period(&self) -> Duration {
        self.period
    }

    /// True in real-time mode.
    pub fn is_realtime(&self) -> bool {
        matches!(self.driver, Driver::RealTime(_))
    }

    /// The motion thread's lock-free position cell (real time only): services read the
    /// latest cycle's position from it without waiting for the program.
    pub fn position_cell(&self) -> Option<Arc<super::position_cell::PositionCell>> {
        match &self.driver {
            Driver::Virtual(_) => None,
            Driver::RealTime(r) => Some(Arc::clone(&r.shared.position)),
        }
    }

    /// The current robot time.
    pub fn now(&mut self) -> RobotTime {
        self.state().setpoint.time
    }

    /// The current robot time, readable through a shared reference (unlike [`Self::now`],
    /// it collects no events).
    pub fn time(&self) -> RobotTime {
        match &self.driver {
            Driver::Virtual(v) => v.now(),
            Driver::RealTime(r) => r.published().state.setpoint.time,
        }
    }

    /// The latest motion state.
    pub fn state(&mut self) -> MotionState {
        match &mut self.driver {
            Driver::Virtual(v) => v.core.state(),
            Driver::RealTime(r) => {
                let st = r.published().state;
                let from = self.events.len();
                Self::drain_rt_events(r, &mut self.events);
                self.position
                    .route(&mut self.events, from, st.setpoint.speed);
                st
            }
        }
    }

    /// Take every event recorded since the last call (planning errors and warnings, faults).
    pub fn take_events(&mut self) -> Vec<MotionEvent> {
        if let Driver::RealTime(r) = &mut self.driver {
            let from = self.events.len();
            Self::drain_rt_events(r, &mut self.events);
            let speed = r.published().state.setpoint.speed;
            self.position.route(&mut self.events, from, speed);
        }
        std::mem::take(&mut self.events)
    }

    fn drain_rt_events(r: &mut RealTimeDriver, into: &mut Vec<MotionEvent>) {
        while let Ok(e) = r.events.try_recv() {
            into.push(e);
        }
    }

    /// The modal motion settings.
    pub fn settings(&self) -> MotionSettings {
        match &self.driver {
            Driver::Virtual(v) => *v.core.settings(),
            Driver::RealTime(r) => *r.planner.settings(),
        }
    }

    /// Change the modal settings (`VelSet`, `AccSet`, `SingArea`) for moves submitted from now.
    pub fn set_settings(&mut self, s: MotionSettings) {
        match &mut self.driver {
            Driver::Virtual(v) => v.core.set_settings(s),
            Driver::RealTime(r) => r.planner.set_settings(s),
        }
    }

    /// Plan `cmd` and queue it; blocks while the queue is full (in virtual time: runs cycles
    /// until there is room). A move that cannot be executed is refused here, before the robot
    /// moves, with its ABB event ([`MotionError::event`]).
    pub fn submit(&mut self, cmd: MotionCommand) -> Result<(), ControllerError> {
        self.submit_triggered(cmd, &[], None)
    }

    /// What the position events of queued moves do (register an action for its key).
    pub fn position_events(&mut self) -> &mut PositionEvents {
        &mut self.position
    }

    /// What the position events of queued moves do, read-only.
    pub fn position_events_ref(&self) -> &PositionEvents {
        &self.position
    }

    /// As [`Self::submit`], with position events on the move (keys of actions registered
    /// in [`Self::position_events`]) and the name of the RAPID instruction when it is not
    /// the command's own.
    pub fn submit_triggered(
        &mut self,
        cmd: MotionCommand,
        triggers: &[PathTrigger],
        name: Option<&'static str>,
    ) -> Result<(), ControllerError> {
        let interrupt = self.interrupt.clone();
        match &mut self.driver {
            Driver::Virtual(v) => {
                let mut cmd = cmd;
                loop {
                    if interrupt
                        .as_ref()
                        .is_some_and(|f| f.load(Ordering::Relaxed))
                    {
                        return Err(ControllerError::Interrupted);
                    }
                    v.core.set_triggers(triggers, name);
                    let queued = v.core.enqueue(cmd);
                    v.core.set_triggers(&[], None);
                    match queued {
                        Ok(()) => {
                            while let Some(e) = v.core.take_event() {
                                self.events.push(e);
                            }
                            return Ok(());
                        }
                        Err(EnqueueError::QueueFull(c)) => {
                            cmd = *c;
                            let from = self.events.len();
                            let sp = v.tick(&mut self.events);
                            self.position.route(&mut self.events, from, sp.speed);
                        }
                        Err(EnqueueError::Rejected(e)) => {
                            while let Some(ev) = v.core.take_event() {
                                self.events.push(ev);
                            }
                            return Err(ControllerError::Rejected(e));
                        }
                    }
                }
            }
            Driver::RealTime(r) => {
                r.recycle();
                let instr = InstrRef {
                    id: cmd.id(),
                    name: cmd.name(),
                    source: cmd.source(),
                };
                let published = *r.published();
                let refuse = |events: &mut Vec<MotionEvent>, error: MotionError| {
                    events.push(MotionEvent {
                        time: published.state.setpoint.time,
                        severity: Severity::Error,
                        instr: Some(instr),
                        error: error.clone(),
                    });
                    Err(ControllerError::Rejected(error))
                };
                if !published.running {
                    return Err(ControllerError::Thread(
                        "the motion thread has stopped".into(),
                    ));
                }
                if published.state.halted {
                    return refuse(&mut self.events, MotionError::Halted);
                }
                if published.state.mode != CoreMode::Planned {
                    return refuse(&mut self.events, MotionError::ExternalGuidance);
                }
                let idle = published.state.in_position() && published.accepted == r.submitted;
                if idle && published.state.setpoint.joints != r.planner.start() {
                    r.planner.set_start(published.state.setpoint.joints);
                }
                r.planner.set_triggers(triggers, name);
                let planned = match r.planner.plan(&cmd) {
                    Ok(p) => p,
                    Err(e) => return refuse(&mut self.events, e),
                };
                for w in planned.warnings {
                    self.events.push(MotionEvent {
                        time: published.state.setpoint.time,
                        severity: Severity::Warning,
                        instr: Some(instr),
                        error: w,
                    });
                }
                let Some(tx) = &r.segments else {
                    return Err(ControllerError::Thread(
                        "the motion thread has stopped".into(),
                    ));
                };
                // The queue is full while the channel holds a segment: wait for the motion
                // thread to take it, unless the run is interrupted meanwhile.
                let mut segment = planned.segment;
                loop {
                    match tx.try_send(segment) {
                        Ok(()) => break,
                        Err(TrySendError::Full(s)) => {
                            if interrupt
                                .as_ref()
                                .is_some_and(|f| f.load(Ordering::Relaxed))
                            {
                                return Err(ControllerError::Interrupted);
                            }
                            segment = s;
                            let guard = r.published();
                            let _ = r
                                .shared
                                .changed
                                .wait_timeout(guard, Duration::from_millis(20));
                        }
                        Err(TrySendError::Disconnected(_)) => {
                            return Err(ControllerError::Thread(
                                "the motion thread has stopped".into(),
                            ));
                        }
                    }
                }
                r.submitted += 1;
                Ok(())
            }
        }
    }

    /// Block until `cond` holds and return the state then. In virtual time this runs motion
    /// cycles (and only then does robot time advance) and stops on the first cycle where the
    /// condition holds.
    ///
    /// Errors: [`ControllerError::Stopped`] when the robot stops on a motion error meanwhile
    /// (or had stopped before), [`ControllerError::NeverSatisfied`] when the robot is idle and
    /// only motion could satisfy the condition, [`ControllerError::Timeout`] after the
    /// configured maximum wait in robot time.
    pub fn wait_until(&mut self, cond: Condition) -> Result<MotionState, ControllerError> {
        self.wait_until_within(cond, self.max_wait)
    }

    /// As [`ControllerHandle::wait_until`] with its own maximum wait instead of the
    /// configured one: for waits whose length the controller itself bounds, such as a stop
    /// that must not be cut short by `--max-time`.
    pub fn wait_until_within(
        &mut self,
        mut cond: Condition,
        max_wait: Duration,
    ) -> Result<MotionState, ControllerError> {
        match &mut self.driver {
            Driver::Virtual(v) => {
                let limit = v.now().saturating_add(max_wait);
                loop {
                    let st = v.core.state();
                    if st.halted {
                        return Err(stopped(&self.events));
                    }
                    if cond.met(&st) {
                        return Ok(st);
                    }
                    if cond.depends_on_motion_only() && st.in_position() {
                        return Err(ControllerError::NeverSatisfied(format!("{cond:?}")));
                    }
                    if st.setpoint.time >= limit {
                        return Err(ControllerError::Timeout(max_wait));
                    }
                    let from = self.events.len();
                    let sp = v.tick(&mut self.events);
                    self.position.route(&mut self.events, from, sp.speed);
                }
            }
            Driver::RealTime(r) => {
                let wall_limit = self.wall.elapsed().saturating_add(max_wait);
                let mut guard = r.published();
                loop {
                    let from = self.events.len();
                    while let Ok(e) = r.events.try_recv() {
                        self.events.push(e);
                    }
                    let p = *guard;
                    self.position
                        .route(&mut self.events, from, p.state.setpoint.speed);
                    if p.state.halted {
                        return Err(stopped(&self.events));
                    }
                    if cond.met(&p.state) {
                        return Ok(p.state);
                    }
                    if !p.running {
                        return Err(ControllerError::Thread(
                            "the motion thread has stopped".into(),
                        ));
                    }
                    let idle = p.state.in_position() && p.accepted == r.submitted;
                    if cond.depends_on_motion_only() && idle {
                        return Err(ControllerError::NeverSatisfied(format!("{cond:?}")));
                    }
                    if self.wall.elapsed() >= wall_limit {
                        return Err(ControllerError::Timeout(max_wait));
                    }
                    guard = match r
                        .shared
                        .changed
                        .wait_timeout(guard, Duration::from_millis(50))
                    {
                        Ok((g, _)) => g,
                        Err(poisoned) => poisoned.into_inner().0,
                    };
                }
            }
        }
    }

    /// Stop the robot: drop queued and active moves and let it brake to rest (the
    /// executor's stops: a few cycles, as quickly as the axis accelerations allow).
    pub fn stop_motion(&mut self) {
        match &mut self.driver {
            Driver::Virtual(v) => {
                v.core.stop();
                // A brake from top speed lasts well under a second; the bound only guards
                // against a bug turning this into a hang.
                for _ in 0..100_000 {
                    if !v.core.state().moving {
                        break;
                    }
                    let from = self.events.len();
                    let sp = v.tick(&mut self.events);
                    self.position.route(&mut self.events, from, sp.speed);
                }
                v.core.plan_from_here();
                self.position.drop_pending();
            }
            Driver::RealTime(r) => {
                let _ = r.control.send(Control::Stop { sent: r.submitted });
                let _ = Self::settle(r, |p| !p.state.moving && p.state.pending == 0);
                let joints = r.published().state.setpoint.joints;
                r.planner.set_start(joints);
                let from = self.events.len();
                Self::drain_rt_events(r, &mut self.events);
                self.position.route(&mut self.events, from, 0.0);
                self.position.drop_pending();
            }
        }
    }

    /// The program stops: decelerate on the path (the bounded ramp of `StopMove`) and hold
    /// there, the moves kept, until [`Self::continue_motion`]. Returns when the robot is at
    /// rest. Refused while external guidance moves the robot (an EGM run pauses itself).
    pub fn pause_motion(&mut self) -> Result<(), PathOpError> {
        self.path_op(PathOp::Pause)?;
        let at_rest = |s: &MotionState| !s.moving || s.held_at_rest;
        match &mut self.driver {
            Driver::Virtual(v) => {
                // A ramp down from top speed lasts a few seconds at most; the bound only
                // guards against a bug turning this into a hang.
                for _ in 0..1_000_000 {
                    if at_rest(&v.core.state()) {
                        break;
                    }
                    let from = self.events.len();
                    let sp = v.tick(&mut self.events);
                    self.position.route(&mut self.events, from, sp.speed);
                }
            }
            Driver::RealTime(r) => {
                let _ = Self::settle_within(r, Duration::from_secs(30), |p| at_rest(&p.state));
                let from = self.events.len();
                Self::drain_rt_events(r, &mut self.events);
                self.position.route(&mut self.events, from, 0.0);
            }
        }
        Ok(())
    }

    /// The program starts again: the path [`Self::pause_motion`] held goes on.
    pub fn continue_motion(&mut self) -> Result<(), PathOpError> {
        self.path_op(PathOp::Continue)
    }

    /// Hold, resume, store, restore or clear the path (`motion::PathOp`). A cleared path
    /// that was moving brakes to rest first; planning then goes on from where the robot is.
    pub fn path_op(&mut self, op: PathOp) -> Result<(), PathOpError> {
        match &mut self.driver {
            Driver::Virtual(v) => {
                v.core.path_op(op)?;
                if op == PathOp::Clear {
                    for _ in 0..100_000 {
                        if !v.core.state().moving {
                            break;
                        }
                        v.tick(&mut self.events);
                    }
                    v.core.plan_from_here();
                }
                Ok(())
            }
            Driver::RealTime(r) => {
                let (tx, rx) = std::sync::mpsc::sync_channel(1);
                let gone = PathOpError::Unavailable;
                r.control
                    .send(Control::Path { op, reply: tx })
                    .map_err(|_| gone)?;
                rx.recv_timeout(Duration::from_secs(1))
                    .map_err(|_| gone)??;
                if op == PathOp::Clear {
                    let _ = Self::settle(r, |p| !p.state.moving);
                }
                let here = r.published().state.setpoint.joints;
                crate::motion::core::path_op_plan(&mut r.planner, &mut self.stored_plan, op, here);
                Ok(())
            }
        }
    }

    /// Install a path correction of planned moves from the program side (the `\Corr`
    /// generators); `false` when one is installed already. Virtual time only: in real time
    /// the executor belongs to the motion thread.
    pub fn install_path_correction(
        &mut self,
        correction: Box<dyn crate::motion::PathCorrection>,
    ) -> Result<bool, ControllerError> {
        match &mut self.driver {
            Driver::Virtual(v) => {
                let exec = v.core.executor_mut();
                if exec.has_path_correction() {
                    return Ok(false);
                }
                drop(exec.set_path_correction(Some(correction)));
                Ok(true)
            }
            Driver::RealTime(_) => Err(ControllerError::Thread(
                "correction generators (CorrCon) are not supported in real time yet".into(),
            )),
        }
    }

    /// Leave the halted state after a motion error; planning restarts where the robot is.
    pub fn recover(&mut self) {
        match &mut self.driver {
            Driver::Virtual(v) => v.core.recover(),
            Driver::RealTime(r) => {
                let _ = r.control.send(Control::Recover);
                let _ = Self::settle(r, |p| !p.state.halted);
                let joints = r.published().state.setpoint.joints;
                r.planner.set_start(joints);
            }
        }
    }

    /// Wait (at most 1 s of wall time) until the motion thread publishes a state for which
    /// `ok` holds.
    fn settle(
        r: &mut RealTimeDriver,
        ok: impl Fn(&super::motion_thread::Published) -> bool,
    ) -> Result<(), ControllerError> {
        Self::settle_within(r, Duration::from_secs(1), ok)
    }

    /// [`Self::settle`] with a bound of `limit` wall time.
    fn settle_within(
        r: &mut RealTimeDriver,
        limit: Duration,
        ok: impl Fn(&super::motion_thread::Published) -> bool,
    ) -> Result<(), ControllerError> {
        let clock = MonotonicClock::new();
        let mut guard = r.published();
        while !ok(&guard) {
            if !guard.running || clock.elapsed() > limit {
                return Err(ControllerError::Thread(
                    "the motion thread does not answer".into(),
                ));
            }
            guard = match r
                .shared
                .changed
                .wait_timeout(guard, Duration::from_millis(20))
            {
                Ok((g, _)) => g,
                Err(poisoned) => poisoned.into_inner().0,
            };
        }
        Ok(())
    }

    /// Hand the robot to external guidance (EGM). Only at a stop point.
    pub fn start_external(
        &mut self,
        guidance: Box<dyn ExternalGuidance>,
        tool: ToolData,
        instr: Option<InstrRef>,
    ) -> Result<(), ControllerError> {
        match &mut self.driver {
            Driver::Virtual(v) => v
                .core
                .start_external(guidance, tool, instr)
                .map_err(ControllerError::Rejected),
            Driver::RealTime(r) => {
                let (tx, rx) = std::sync::mpsc::sync_channel(1);
                r.control
                    .send(Control::StartExternal {
                        guidance,
                        tool,
                        instr,
                        reply: tx,
                    })
                    .map_err(|_| ControllerError::Thread("the motion thread has stopped".into()))?;
                rx.recv_timeout(Duration::from_secs(1))
                    .map_err(|_| {
                        ControllerError::Thread("the motion thread does not answer".into())
                    })?
                    .map_err(ControllerError::Rejected)
            }
        }
    }

    /// End external guidance; planning restarts where the robot is. Returns the guidance.
    pub fn stop_external(&mut self) -> Option<Box<dyn ExternalGuidance>> {
        match &mut self.driver {
            Driver::Virtual(v) => v.core.stop_external(),
            Driver::RealTime(r) => {
                let (tx, rx) = std::sync::mpsc::sync_channel(1);
                r.control.send(Control::StopExternal { reply: tx }).ok()?;
                let g = rx.recv_timeout(Duration::from_secs(1)).ok().flatten();
                let joints = r.published().state.setpoint.joints;
                r.planner.set_start(joints);
                g
            }
        }
    }

    /// End the run: stop the motion thread (real time), finish the sinks (write files) and
    /// return the summary. Sink errors are reported after all sinks were finished.
    pub fn finish(self) -> Result<RunSummary, ControllerError> {
        let wall = self.wall.elapsed();
        let (summary, mut sinks) = match self.driver {
            Driver::Virtual(v) => {
                let sp = v.core.state().setpoint;
                (
                    RunSummary {
                        simulated: sp.time.since_start(),
                        wall,
                        ticks: v.ticks,
                        final_joints: sp.joints,
                        realtime: false,
                        period_stats: None,
                        dropped_records: 0,
                    },
                    v.sinks,
                )
            }
            Driver::RealTime(mut r) => {
                let end = r.stop()?;
                (
                    RunSummary {
                        simulated: end.exit.last.time.since_start(),
                        wall,
                        ticks: end.exit.ticks,
                        final_joints: end.exit.last.joints,
                        realtime: true,
                        period_stats: Some(end.exit.stats),
                        dropped_records: end.exit.dropped_records,
                    },
                    end.sinks,
                )
            }
        };
        let mut first_error = None;
        for s in &mut sinks {
            if let Err(e) = s.finish() {
                first_error.get_or_insert(e);
            }
        }
        match first_error {
            Some(e) => Err(ControllerError::Sink(e)),
            None => Ok(summary),
        }
    }
}

/// The error for a wait that ended because the robot stopped: the last error event.
fn stopped(events: &[MotionEvent]) -> ControllerError {
    match events.iter().rev().find(|e| e.severity == Severity::Error) {
        Some(e) => ControllerError::Stopped(Box::new(e.clone())),
        None => ControllerError::Rejected(MotionError::Halted),
    }
}
