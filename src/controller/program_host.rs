//! `ControllerHost`: the interpreter's [`Host`] with the virtual robot behind it. Time is the
//! controller's robot time (virtual by default, so motion goes on while the program waits),
//! moves go into the controller's motion queue, motion errors become RAPID errors with the
//! ABB event number, and the kinematic functions use the controller's robot. Program output
//! and I/O signals are those of a [`VirtualHost`].
//!
//! The struct is built with `ControllerHost::new(handle)` and `with_*` methods, so other
//! capabilities (EGM) can add fields and builders without touching the callers.

mod corr_generators;
mod egm_parts;
mod motion_events;
pub mod panel_moves;
mod path_recovery;
mod position_events;

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use crate::interp::host::{
    MotionModes, MotionSetting, MotionWait, Output, PathCommand, SingAreaMode, no_robot,
};
use crate::interp::{Host, HostError, VirtualHost};
use crate::motion::{MotionEvent, MotionState, SingArea};
use crate::robot::command::{EXTAX_NONE, MotionCommand, RobTarget};
use crate::robot::trigger::PathTrigger;
use crate::robot::{
    JointsDeg, Pose, ToolData, WobjData, flange_target, pose_to_pos_quat, target_from_flange,
};
use crate::signals::SignalTable;
use crate::source::SourceMap;
use crate::time::RobotTime;

use super::ControllerError;
use super::condition::Condition;
use super::egm_controller::{EgmController, LastMove};
use super::handle::ControllerHandle;
use super::summary::RunSummary;
use crate::interp::host::EgmHost;
use motion_events::stopped_error;

pub use motion_events::{describe_event, kin_error, motion_error};

/// The interpreter's host on a running controller (see the module docs).
pub struct ControllerHost {
    ctl: Option<ControllerHandle>,
    io: VirtualHost,
    modes: MotionModes,
    /// Id of the last move handed to the controller (ids start at 1).
    last_id: u64,
    /// Id of the last move the controller accepted (refused moves never run).
    last_accepted: u64,
    /// Moves up to this id were dropped when the robot stopped on an error: waits for them
    /// are over.
    void_up_to: u64,
    /// Moves accepted by the controller.
    submitted: u64,
    /// The correction generators of `\Corr` moves (made at the first request).
    corr: Option<path_recovery::Corr>,
    /// `last_accepted` when `StorePath` put the path aside (the moves of the new path are
    /// complete when `RestoPath` brings it back).
    stored_accepted: Option<u64>,
    /// Error events not yet given to the program.
    errors: Vec<MotionEvent>,
    max_time: Option<f64>,
    lines: Option<Arc<SourceMap>>,
    /// Virtual time: where the program's clock stands (s). A `WaitTime` ends at its exact
    /// deadline while the robot's clock moves in whole motion cycles, so the program's clock
    /// may be ahead of the robot's by less than one cycle.
    program_time: RobotTime,
    /// The EGM side (`None`: EGM instructions are not supported).
    egm: Option<EgmController>,
    /// What the last move handed to the controller was (EGM movements need a stop point).
    last_move: LastMove,
    /// Set from outside (Ctrl-C): waits end at once so the program can stop.
    stop: Option<Arc<AtomicBool>>,
    /// Something outside the program takes part in a virtual run (an external sensor in
    /// lockstep), so a wait may end for reasons the program does not control.
    outside_inputs: bool,
    /// A controller that stays up: the panel's speed ratio and operating mode applied to
    /// every move, and the moves kept so a stopped program's move can continue
    /// (`panel_moves.rs`).
    panel: Option<panel_moves::PanelMoves>,
    /// Signal changes at given times (`--signal-script`).
    script: super::signal_script::SignalScript,
}

impl std::fmt::Debug for ControllerHost {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ControllerHost")
            .field("controller", &self.ctl)
            .field("last_id", &self.last_id)
            .field("submitted", &self.submitted)
            .finish_non_exhaustive()
    }
}

impl ControllerHost {
    /// A host on `ctl`, with the built-in signals, output kept in memory and no time limit.
    pub fn new(ctl: ControllerHandle) -> ControllerHost {
        ControllerHost {
            ctl: Some(ctl),
            io: VirtualHost::new(),
            modes: MotionModes::default(),
            last_id: 0,
            last_accepted: 0,
            void_up_to: 0,
            submitted: 0,
            stored_accepted: None,
            corr: None,
            errors: Vec::new(),
            max_time: None,
            lines: None,
            program_time: RobotTime::ZERO,
            egm: None,
            last_move: LastMove::None,
            stop: None,
            outside_inputs: false,
            panel: None,
            script: Default::default(),
        }
    }

    /// End every wait as soon as `flag` turns true (the interpreter, given the same flag,
    /// then stops the program), and skip the final drain of queued moves.
    pub fn with_stop_request(mut self, flag: Arc<AtomicBool>) -> Self {
        if let Some(ctl) = self.ctl.as_mut() {
            ctl.set_interrupt(Arc::clone(&flag));
        }
        self.stop = Some(flag);
        self
    }

    /// Say that something outside the program takes part in the run even in virtual time
    /// (an external EGM sensor in lockstep): the time-limit error then does not claim that
    /// nothing could end the wait.
    pub fn with_outside_inputs(mut self, outside: bool) -> Self {
        self.outside_inputs = outside;
        self
    }

    fn stop_requested(&self) -> bool {
        self.stop
            .as_ref()
            .is_some_and(|f| f.load(Ordering::Relaxed))
    }

    /// Run EGM instructions with `egm` (whose cycle hook runs in this host's controller).
    pub fn with_egm(mut self, egm: EgmController) -> Self {
        self.egm = Some(egm);
        self
    }

    /// The EGM side, taken out (to finish it after [`ControllerHost::finish`]).
    pub fn take_egm(&mut self) -> Option<EgmController> {
        self.egm.take()
    }

    /// Use this signal table.
    pub fn with_signals(mut self, signals: Arc<SignalTable>) -> Self {
        self.io = self.io.with_signals(signals);
        self
    }

    /// Hand every output (TP lines, event-log entries, motion events) to `sink`.
    pub fn with_sink(mut self, sink: impl FnMut(&Output) + Send + 'static) -> Self {
        self.io = self.io.with_sink(sink);
        self
    }

    /// Use this system side (calendar, system information, configuration data).
    pub fn with_system(mut self, system: crate::system::Services) -> Self {
        self.io = self.io.with_system(system);
        self
    }

    /// Fail waits that would pass this robot time (seconds): nothing can end a wait for a
    /// signal nobody sets.
    pub fn with_max_time(mut self, seconds: f64) -> Self {
        self.max_time = Some(seconds);
        self
    }

    /// Name source lines in motion events (`MoveL at prog.mod:12`).
    pub fn with_lines(mut self, lines: Arc<SourceMap>) -> Self {
        self.lines = Some(lines);
        self
    }

    /// The controller (`None` after [`ControllerHost::finish`]).
    pub fn controller(&mut self) -> Option<&mut ControllerHandle> {
        self.ctl.as_mut()
    }

    /// The output kept so far (when no sink was given).
    pub fn outputs(&self) -> &[Output] {
        self.io.outputs()
    }

    /// The `TPWrite` lines kept so far (when no sink was given).
    pub fn tp_lines(&self) -> Vec<String> {
        self.io.tp_lines()
    }

    /// Moves the controller accepted so far.
    pub fn moves_submitted(&self) -> u64 {
        self.submitted
    }

    /// End the run: with `drain`, let the robot finish the queued moves first (the program
    /// ended normally); otherwise stop it where it is (the program stopped or failed). Then
    /// stop the controller, write the traces and plots, and return the summary. Motion events
    /// of the drain are output as events.
    pub fn finish(&mut self, drain: bool) -> Result<RunSummary, ControllerError> {
        let mut ctl = self
            .ctl
            .take()
            .ok_or_else(|| ControllerError::Thread("the controller was already finished".into()))?;
        let stop = self.stop.clone();
        let stopped = move || stop.as_ref().is_some_and(|f| f.load(Ordering::Relaxed));
        // A path held by StopMove never completes: the robot stays where it holds.
        let drain = drain && !stopped() && !ctl.state().held;
        if drain {
            let cond = if self.stop.is_some() {
                Condition::Predicate(Box::new(move |s: &MotionState| {
                    s.in_position() || stopped()
                }))
            } else {
                Condition::InPos
            };
            match ctl.wait_until(cond) {
                Ok(_) | Err(ControllerError::NeverSatisfied(_)) => {}
                Err(ControllerError::Stopped(_)) => {}
                Err(e) => return Err(e),
            }
        } else {
            ctl.stop_motion();
        }
        self.ctl = Some(ctl);
        self.pump_events();
        let pending = std::mem::take(&mut self.errors);
        for e in pending {
            let text = describe_event(&e, self.lines.as_deref());
            self.io.output(Output::Event(text));
        }
        match self.ctl.take() {
            Some(ctl) => ctl.finish(),
            None => Err(ControllerError::Thread(
                "the controller was already finished".into(),
            )),
        }
    }

    fn ctl(&mut self) -> Result<&mut ControllerHandle, HostError> {
        self.ctl
            .as_mut()
            .ok_or_else(|| HostError::fatal("the controller has already finished"))
    }

    /// Collect the controller's events: warnings and notes go out as events at once, errors
    /// wait to be given to the program.
    fn pump_events(&mut self) {
        let Some(ctl) = self.ctl.as_mut() else {
            return;
        };
        for e in ctl.take_events() {
            if e.severity == crate::motion::Severity::Error {
                self.errors.push(e);
            } else {
                let text = describe_event(&e, self.lines.as_deref());
                self.io.output(Output::Event(text));
            }
        }
    }

    /// The robot stopped on a motion error: the error for the program. The robot is
    /// recovered (queued moves are dropped) so the program's ERROR handler can move it again.
    fn take_halt(&mut self, fallback: Option<ControllerError>) -> HostError {
        self.pump_events();
        let events = std::mem::take(&mut self.errors);
        let cause = events
            .iter()
            .find(|e| e.error != crate::motion::MotionError::Halted)
            .cloned();
        if let Some(ctl) = self.ctl.as_mut() {
            ctl.stop_motion();
            ctl.recover();
        }
        self.void_up_to = self.last_id;
        match cause {
            Some(e) => motion_error(&e.error, Some(&e), self.lines.as_deref()),
            None => match fallback.map(stopped_error) {
                Some(e) => e,
                None => HostError::fatal("the robot stopped after a motion error"),
            },
        }
    }

    /// The motion state, with halts turned into the program's error.
    fn state_checked(&mut self) -> Result<MotionState, HostError> {
        let st = self.ctl()?.state();
        self.pump_events();
        if st.halted {
            return Err(self.take_halt(None));
        }
        Ok(st)
    }

    /// Queue a move with position events (keys registered with the controller) as the
    /// RAPID instruction `name`; see [`Host::motion_submit`].
    fn submit_with(
        &mut self,
        mut cmd: MotionCommand,
        triggers: &[PathTrigger],
        name: Option<&'static str>,
    ) -> Result<u64, HostError> {
        self.state_checked()?;
        self.last_id += 1;
        let id = self.last_id;
        set_id(&mut cmd, id);
        let stop_point = zone_of(&cmd).finep;
        let kept = self.panel.as_ref().map(|_| cmd.clone());
        let limits = self.panel.as_ref().map(|p| p.limits.clone());
        let ctl = self.ctl()?;
        let result = panel_moves::with_limits(ctl, limits.as_deref(), |c| {
            c.submit_triggered(cmd, triggers, name)
        });
        if result.is_ok()
            && let (Some(p), Some(c)) = (self.panel.as_mut(), kept)
        {
            p.unfinished.push_back((id, c));
        }
        self.pump_events();
        if result.is_ok() {
            self.last_accepted = id;
        }
        match result {
            Ok(()) => {
                self.submitted += 1;
                self.last_move = if stop_point {
                    LastMove::StopPoint
                } else {
                    LastMove::FlyBy
                };
                Ok(id)
            }
            Err(ControllerError::Rejected(crate::motion::MotionError::Halted)) => {
                Err(self.take_halt(None))
            }
            Err(ControllerError::Rejected(e)) => {
                // The refusal is this instruction's error; its event is not printed.
                self.errors.retain(|ev| ev.error != e);
                Err(motion_error(&e, None, self.lines.as_deref()))
            }
            Err(e @ ControllerError::Stopped(_)) => Err(self.take_halt(Some(e))),
            Err(e) => Err(HostError::fatal(e.to_string())),
        }
    }

    /// True when every move handed to the controller is complete (or was dropped).
    fn all_done(&self, st: &MotionState) -> bool {
        self.last_accepted <= self.void_up_to || st.done(self.last_accepted)
    }
}

/// True when something a waiting program may care about changed between `a` and `b`.
fn motion_changed(a: &MotionState, b: &MotionState) -> bool {
    a.last_done != b.last_done
        || a.moving != b.moving
        || a.pending != b.pending
        || a.halted != b.halted
        || a.mode != b.mode
        || a.setpoint.standstill != b.setpoint.standstill
        || a.events_total != b.events_total
}

impl ControllerHost {
    /// A wait that reaches past the time limit `max` (s).
    fn beyond_limit(&self, max: f64) -> HostError {
        let realtime = self.ctl.as_ref().is_some_and(ControllerHandle::is_realtime);
        HostError::fatal(if realtime || self.outside_inputs {
            format!(
                "the program waits beyond the time limit of {max} s \
                 (use --max-time to raise it)"
            )
        } else {
            format!(
                "the program waits beyond the virtual time limit of {max} s \
                 (nothing in a virtual run can end this wait; use --max-time to raise it)"
            )
        })
    }
}

impl Host for ControllerHost {
    fn now(&self) -> RobotTime {
        let robot = self.ctl.as_ref().map_or(RobotTime::ZERO, |c| c.time());
        robot.max(self.program_time)
    }

    fn check_time_limit(&mut self) -> Result<(), HostError> {
        match self.max_time {
            Some(max) if self.now() >= RobotTime::from_secs_f64(max) => Err(self.beyond_limit(max)),
            _ => Ok(()),
        }
    }

    /// Runs the robot until `deadline`, or until the motion state changes (a move ends or
    /// starts, the robot stops), whichever comes first.
    fn wait_until(&mut self, deadline: RobotTime) -> Result<RobotTime, HostError> {
        // A scripted signal change ends the wait at its time.
        self.apply_script()?;
        let deadline = self
            .script
            .next_time()
            .map_or(deadline, |t| t.min(deadline));
        let (target, limit) = match self.max_time {
            Some(max) if deadline > RobotTime::from_secs_f64(max) => {
                (RobotTime::from_secs_f64(max), Some(max))
            }
            _ => (deadline, None),
        };
        let start = self.state_checked()?;
        let now = self.now();
        if self.stop_requested() {
            return Ok(now);
        }
        if let Some(max) = limit
            && now >= target
        {
            return Err(self.beyond_limit(max));
        }
        if target <= now {
            return Ok(now);
        }
        let stop = self.stop.clone();
        let ctl = self.ctl()?;
        let until = target;
        // Virtual time stops on the last cycle at or before the deadline (the program's clock
        // then jumps to it); real time on the first cycle at or after it.
        let lead = if ctl.is_realtime() {
            Duration::ZERO
        } else {
            ctl.period().saturating_sub(Duration::from_nanos(1))
        };
        let reached = move |s: &MotionState| s.setpoint.time.saturating_add(lead) >= until;
        let cond = Condition::Predicate(Box::new(move |s: &MotionState| {
            reached(s)
                || motion_changed(&start, s)
                || stop.as_ref().is_some_and(|f| f.load(Ordering::Relaxed))
        }));
        let result = ctl.wait_until(cond);
        self.pump_events();
        match result {
            Ok(st) => {
                if reached(&st) && !lead.is_zero() {
                    self.program_time = self.program_time.max(target);
                }
                self.apply_script()?;
                Ok(self.now())
            }
            // The robot stopped on a motion error; its event may have been taken already
            // (the robot brakes over several cycles after the error is logged).
            Err(
                e @ (ControllerError::Stopped(_)
                | ControllerError::Rejected(crate::motion::MotionError::Halted)),
            ) => Err(self.take_halt(Some(e))),
            Err(e) => Err(HostError::fatal(e.to_string())),
        }
    }

    fn output(&mut self, out: Output) {
        self.io.output(out);
    }

    fn read_signal(&mut self, name: &str) -> Result<f64, HostError> {
        self.apply_script()?;
        self.io.read_signal(name)
    }

    fn write_signal(&mut self, name: &str, value: f64) -> Result<(), HostError> {
        self.io.write_signal(name, value)
    }

    fn signal_kind(&self, name: &str) -> Option<crate::signals::SignalKind> {
        self.io.signal_kind(name)
    }

    fn motion_submit(&mut self, cmd: MotionCommand) -> Result<u64, HostError> {
        self.submit_with(cmd, &[], None)
    }

    fn motion_reached(&mut self, wait: MotionWait) -> Result<bool, HostError> {
        let st = self.state_checked()?;
        Ok(match wait {
            MotionWait::Done(id) => id <= self.void_up_to || st.done(id),
            MotionWait::InPos => st.in_position() && self.all_done(&st),
            MotionWait::ZeroSpeed => st.setpoint.standstill,
        })
    }

    fn motion_joints(&mut self) -> Result<JointsDeg, HostError> {
        Ok(self.ctl()?.state().setpoint.joints)
    }

    fn motion_modes(&self) -> MotionModes {
        self.modes
    }

    fn motion_set(&mut self, setting: MotionSetting) -> Result<(), HostError> {
        let ctl = self.ctl()?;
        let mut s = ctl.settings();
        match setting {
            MotionSetting::ConfJ(on) => self.modes.conf_j = on,
            MotionSetting::ConfL(on) => self.modes.conf_l = on,
            MotionSetting::PDisp(p) => self.modes.pdisp = p,
            MotionSetting::SingArea(m) => {
                s.singarea = match m {
                    SingAreaMode::Off => SingArea::Off,
                    SingAreaMode::Wrist => SingArea::Wrist,
                    SingAreaMode::LockAxis4 => SingArea::LockAxis4,
                };
                ctl.set_settings(s);
            }
            MotionSetting::VelSet {
                override_pct,
                max_tcp,
            } => {
                s.velset.override_pct = override_pct;
                s.velset.max_tcp = max_tcp;
                ctl.set_settings(s);
            }
            MotionSetting::AccSet { acc_pct, ramp_pct } => {
                s.accset.acc_pct = acc_pct;
                s.accset.ramp_pct = ramp_pct;
                ctl.set_settings(s);
            }
            MotionSetting::PathAccLim { acc, decel } => {
                let lim = match (acc, decel) {
                    (Some(a), Some(d)) => Some(a.min(d)),
                    (a, d) => a.or(d),
                };
                s.path_acc_lim = lim;
                ctl.set_settings(s);
            }
            MotionSetting::WorldAccLim(lim) => {
                s.world_acc_lim = lim;
                ctl.set_settings(s);
            }
            MotionSetting::EOffs(e) => self.modes.eoffs = e,
        }
        Ok(())
    }

    fn motion_path(&mut self, cmd: PathCommand) -> Result<(), HostError> {
        path_recovery::run(self, cmd)
    }

    fn motion_corr(
        &mut self,
        req: crate::interp::host::CorrRequest,
    ) -> Result<crate::interp::host::CorrAnswer, HostError> {
        path_recovery::corr(self, req)
    }

    fn robot_target_of(
        &self,
        joints: &JointsDeg,
        tool: &ToolData,
        wobj: &WobjData,
        pdisp: &Pose,
    ) -> Result<RobTarget, HostError> {
        let ctl = self.ctl.as_ref().ok_or_else(no_robot)?;
        let robot = ctl.robot();
        let flange = robot.try_fk(joints).map_err(|e| kin_error(&e))?;
        let pose = target_from_flange(&flange, tool, wobj, pdisp);
        let (trans, rot) = pose_to_pos_quat(&pose);
        // One sign for equal rotations: the first non-zero component positive.
        let rot = match rot.iter().find(|c| **c != 0.0) {
            Some(c) if *c < 0.0 => rot.map(|c| -c),
            _ => rot,
        };
        Ok(RobTarget {
            trans,
            rot,
            robconf: robot.conf_of(joints),
            extax: EXTAX_NONE,
        })
    }

    fn robot_joints_of(
        &self,
        target: &RobTarget,
        tool: &ToolData,
        wobj: &WobjData,
        pdisp: &Pose,
    ) -> Result<JointsDeg, HostError> {
        let ctl = self.ctl.as_ref().ok_or_else(no_robot)?;
        let flange = flange_target(&target.pose(), tool, wobj, pdisp);
        ctl.robot()
            .ik_conf(&flange, &target.robconf)
            .map_err(|e| kin_error(&e))
    }

    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        Some(self)
    }

    fn egm(&mut self) -> Option<&mut dyn EgmHost> {
        if self.egm.is_some() { Some(self) } else { None }
    }

    fn system(&mut self) -> Option<&mut crate::system::Services> {
        self.io.system()
    }

    fn egm_path(&mut self) -> Option<&mut dyn crate::interp::host::EgmPathHost> {
        if self.egm.is_some() { Some(self) } else { None }
    }

    fn position_events(&mut self) -> Option<&mut dyn crate::interp::host::PositionEventHost> {
        if self.ctl.is_some() { Some(self) } else { None }
    }
}

/// The zone of a command.
fn zone_of(cmd: &MotionCommand) -> &crate::robot::command::ZoneData {
    match cmd {
        MotionCommand::MoveAbsJ(m) => &m.args.zone,
        MotionCommand::MoveJ(m) => &m.args.zone,
        MotionCommand::MoveL(m) => &m.args.zone,
        MotionCommand::MoveC(m) => &m.args.zone,
    }
}

/// Give a command its id.
fn set_id(cmd: &mut MotionCommand, id: u64) {
    match cmd {
        MotionCommand::MoveAbsJ(m) => m.args.id = id,
        MotionCommand::MoveJ(m) => m.args.id = id,
        MotionCommand::MoveL(m) => m.args.id = id,
        MotionCommand::MoveC(m) => m.args.id = id,
    }
}

#[cfg(test)]
mod tests;
