//! `MotionCore`: the planner and the executor in one sans-IO state machine, driven by
//! `enqueue(command)` and `tick(now)`. Tests drive it by hand; the controller's real-time
//! shell splits it into its two halves (planning on the caller's thread, cycles on the
//! motion thread).

use crate::robot::command::MotionCommand;
use crate::robot::trigger::PathTrigger;
use crate::robot::{JointsDeg, Robot, ToolData};

use super::correction::PathCorrection;
use super::event::{InstrRef, MotionError, MotionEvent, Severity};
use super::executor::{Executor, PathOp, PathOpError};
use super::external_guidance::ExternalGuidance;
use super::planner::PlanCheckpoint;
use super::planner::Planner;
use super::settings::{CoreConfig, MotionSettings};
use super::state::{MotionState, Setpoint};
use crate::time::RobotTime;

/// Why a command was not queued.
#[derive(Debug, thiserror::Error)]
pub enum EnqueueError {
    /// The queue is full: tick and try again. The command is handed back.
    #[error("the motion queue is full")]
    QueueFull(Box<MotionCommand>),
    /// The command was refused before the robot moved (also recorded as an event).
    #[error(transparent)]
    Rejected(MotionError),
}

/// The motion core (see the module docs).
#[derive(Debug)]
pub struct MotionCore {
    planner: Planner,
    exec: Executor,
    /// The planning state of the path `StorePath` put aside.
    stored_plan: Option<PlanCheckpoint>,
}

impl MotionCore {
    /// A core for `robot` standing at `start` (the configuration is clamped to its supported
    /// range, see [`CoreConfig::sanitized`]).
    pub fn new(robot: Robot, config: CoreConfig, start: JointsDeg) -> MotionCore {
        let config = config.sanitized();
        MotionCore {
            planner: Planner::new(robot.clone(), config.period, start),
            exec: Executor::new(robot, &config, start),
            stored_plan: None,
        }
    }

    /// Join a planner and an executor (see [`MotionCore::into_parts`]).
    pub fn from_parts(planner: Planner, exec: Executor) -> MotionCore {
        MotionCore {
            planner,
            exec,
            stored_plan: None,
        }
    }

    /// Split into the planning half and the cycle half.
    pub fn into_parts(self) -> (Planner, Executor) {
        (self.planner, self.exec)
    }

    /// Plan `cmd` and queue it. Errors are found here, before the robot moves, and are also
    /// recorded as events; warnings (a corner path that could not be built) only as events.
    pub fn enqueue(&mut self, cmd: MotionCommand) -> Result<(), EnqueueError> {
        while let Some(seg) = self.exec.take_done() {
            self.planner.recycle(seg);
        }
        let instr = InstrRef {
            id: cmd.id(),
            name: cmd.name(),
            source: cmd.source(),
        };
        let refuse = |exec: &mut Executor, error: MotionError| {
            exec.log(Severity::Error, Some(instr), error.clone());
            Err(EnqueueError::Rejected(error))
        };
        let state = self.exec.state();
        if state.halted {
            return refuse(&mut self.exec, MotionError::Halted);
        }
        if state.mode != super::state::CoreMode::Planned {
            return refuse(&mut self.exec, MotionError::ExternalGuidance);
        }
        if !self.exec.has_space() {
            return Err(EnqueueError::QueueFull(Box::new(cmd)));
        }
        if state.in_position() && state.setpoint.joints != self.planner.start() {
            // The robot was moved by something else (guidance, a stop): plan from where it is.
            self.planner.set_start(state.setpoint.joints);
        }
        match self.planner.plan(&cmd) {
            Ok(planned) => {
                for w in planned.warnings {
                    self.exec.log(Severity::Warning, Some(instr), w);
                }
                match self.exec.push(planned.segment) {
                    Ok(()) => Ok(()),
                    // Unreachable: space was checked above. Hand the command back anyway.
                    Err(seg) => {
                        self.planner.recycle(seg);
                        Err(EnqueueError::QueueFull(Box::new(cmd)))
                    }
                }
            }
            Err(e) => refuse(&mut self.exec, e),
        }
    }

    /// Position events (and the RAPID instruction's name) for the next move planned (see
    /// [`Planner::set_triggers`]).
    pub fn set_triggers(&mut self, triggers: &[PathTrigger], name: Option<&'static str>) {
        self.planner.set_triggers(triggers, name);
    }

    /// One motion cycle at robot time `now`: no allocation, no lock, no I/O, no panic.
    pub fn tick(&mut self, now: RobotTime) -> Setpoint {
        self.exec.tick(now)
    }

    /// The executing half (for the shell's per-cycle hook).
    pub fn executor_mut(&mut self) -> &mut Executor {
        &mut self.exec
    }

    /// A snapshot of the state.
    pub fn state(&self) -> MotionState {
        self.exec.state()
    }

    /// True when another command fits in the queue.
    pub fn has_space(&self) -> bool {
        self.exec.has_space()
    }

    /// Take the oldest unread event.
    pub fn take_event(&mut self) -> Option<MotionEvent> {
        self.exec.take_event()
    }

    /// The modal settings for moves planned from now on.
    pub fn settings(&self) -> &MotionSettings {
        self.planner.settings()
    }

    /// Change the modal settings (`VelSet`, `AccSet`, `SingArea`) for moves queued from now on.
    pub fn set_settings(&mut self, s: MotionSettings) {
        self.planner.set_settings(s);
    }

    /// Stop: drop queued and active moves and brake to rest (the executor's stops); tick
    /// until [`MotionState::moving`] is false, then [`MotionCore::plan_from_here`].
    pub fn stop(&mut self) {
        self.exec.stop();
        self.planner.set_start(self.exec.setpoint().joints);
    }

    /// Plan the next move from where the robot is (after a stop has come to rest).
    pub fn plan_from_here(&mut self) {
        self.planner.set_start(self.exec.setpoint().joints);
    }

    /// Hold, resume, store, restore or clear the path (see `motion::executor::PathOp`); the
    /// planner follows: after a store it plans from where the robot is, after a restore from
    /// the stored path's end.
    pub fn path_op(&mut self, op: PathOp) -> Result<(), PathOpError> {
        self.exec.path_op(op)?;
        let here = self.exec.setpoint().joints;
        path_op_plan(&mut self.planner, &mut self.stored_plan, op, here);
        Ok(())
    }

    /// Leave the halted state after a motion error; planning restarts where the robot is.
    pub fn recover(&mut self) {
        self.exec.recover();
        self.planner.set_start(self.exec.setpoint().joints);
    }

    /// The robot.
    pub fn robot(&self) -> &Robot {
        self.planner.robot()
    }

    /// Hand the robot to external guidance (EGM); only at a stop point.
    pub fn start_external(
        &mut self,
        guidance: Box<dyn ExternalGuidance>,
        tool: ToolData,
        instr: Option<InstrRef>,
    ) -> Result<(), MotionError> {
        self.exec.start_external(guidance, tool, instr)
    }

    /// Take a guidance object that finished by itself.
    pub fn take_retired_guidance(&mut self) -> Option<Box<dyn ExternalGuidance>> {
        self.exec.take_retired()
    }

    /// End external guidance; planning restarts where the robot is.
    pub fn stop_external(&mut self) -> Option<Box<dyn ExternalGuidance>> {
        let g = self.exec.stop_external();
        self.planner.set_start(self.exec.setpoint().joints);
        g
    }

    /// Install (or remove) the path correction of planned moves (see
    /// [`Executor::set_path_correction`]).
    pub fn set_path_correction(
        &mut self,
        correction: Option<Box<dyn PathCorrection>>,
    ) -> Option<Box<dyn PathCorrection>> {
        self.exec.set_path_correction(correction)
    }
}

/// The planner's side of a path operation the executor accepted, `here` being where the
/// robot is (shared by the virtual core and the real-time shell, whose planner lives apart
/// from its executor).
pub fn path_op_plan(
    planner: &mut Planner,
    stored: &mut Option<PlanCheckpoint>,
    op: PathOp,
    here: crate::robot::JointsDeg,
) {
    match op {
        PathOp::Store => *stored = Some(planner.store(here)),
        PathOp::Restore => {
            if let Some(cp) = stored.take() {
                planner.restore(cp);
            }
        }
        PathOp::Clear => planner.set_start(here),
        PathOp::Hold { .. }
        | PathOp::Release
        | PathOp::Speed(_)
        | PathOp::Ratio(_)
        | PathOp::Pause
        | PathOp::Continue => {}
    }
}
