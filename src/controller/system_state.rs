//! The state of a controller that stays up (`rapidvc serve`), and its side of the service
//! contract (`controller::service`).
//!
//! One owner: [`SystemState`] holds the operator panel (operating mode, motors, speed ratio),
//! the RAPID execution state and cycle mode, the task list and the event log, behind one lock
//! that is held only for plain reads and writes (never across a wait, never by the motion
//! thread). Two threads answer services:
//!
//! * the **service thread** ([`spawn_service_thread`]) owns the [`ServiceEndpoint`]: it
//!   answers what needs no interpreter at once (panel, execution state, signals, event log,
//!   configuration, files, external queues), publishes signal changes whoever made them, and
//!   hands the rest to the program side;
//! * the **program side** (`system_state/program_side.rs`) runs on the interpreter's thread:
//!   it answers RAPID data, modules and the robot's position between program steps and in
//!   waits, blocks at a statement boundary while the program is stopped, and runs the entry
//!   routine once or forever as the cycle mode says.
//!
//! Decisions where ABB documents nothing for a headless controller are listed in
//! `docs/serve.md`.

pub mod program_side;
mod service_thread;

use std::collections::{HashMap, VecDeque};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};

use super::monotonic_clock::MonotonicClock;
use super::program_host::panel_moves::PanelLimits;
use super::service::{
    CtrlState, CycleMode, DipcMessage, ElogEntry, ElogSeverity, Event, EventPublisher, ExecState,
    OpMode, RobotState, TaskExecState, TaskInfo, TaskType,
};
use crate::events::{EventKind, Severity};
use crate::system::calendar::Calendar;

pub use service_thread::{ServeInfo, spawn_service_thread};

/// Most entries the event log keeps (the oldest go first), as a controller's log is bounded.
pub const ELOG_CAPACITY: usize = 1000;

/// Most external message queues (`rw/dipc`) and messages in one.
pub const MAX_QUEUES: usize = 32;
/// Most messages one external queue holds; more are refused.
pub const MAX_QUEUE_MESSAGES: usize = 256;

#[derive(Debug)]
struct Inner {
    exec: ExecState,
    cycle: CycleMode,
    ctrl: CtrlState,
    opmode: OpMode,
    speed: u8,
    /// The operator (a service) wants the program to run.
    want_run: bool,
    /// A service moved the program pointer to main; the program side acts on it.
    reset_pp: bool,
    tasks: Vec<TaskInfo>,
    elog: VecDeque<ElogEntry>,
    next_seq: u64,
    queues: HashMap<String, VecDeque<DipcMessage>>,
    robot: RobotState,
    /// Program-pointer resets so far (each task of a system takes its own).
    pp_resets: u64,
    /// Starts so far (a NORMAL task whose cycle ended waits for the next one).
    starts: u64,
}

/// Delivers a message sent over `rw/dipc` to a RAPID task's message queue: `None` when the
/// name is no task's queue, else whether it was queued (the error says why not).
pub type TaskQueues = Box<dyn Fn(&str, &DipcMessage) -> Option<Result<(), String>> + Send + Sync>;

/// The controller's state (see the module docs).
#[derive(Debug)]
pub struct SystemState {
    inner: Mutex<Inner>,
    /// What the program side applies to every move.
    pub limits: Arc<PanelLimits>,
    /// Ctrl-C: the controller shuts down.
    shutdown: Arc<AtomicBool>,
    events: EventPublisher,
    calendar: Calendar,
    clock: MonotonicClock,
    /// The RAPID tasks' message queues (a system with several tasks).
    task_queues: TaskQueuesSlot,
    /// The motion thread's position cell, once the program side has handed it over.
    position: std::sync::OnceLock<Arc<crate::controller::position_cell::PositionCell>>,
    /// The system outputs of EIO.cfg (`SYSSIG_OUT`), once attached.
    outputs: std::sync::OnceLock<Arc<crate::controller::system_outputs::SystemOutputs>>,
}

/// Where [`TaskQueues`] is kept (a closure, shown by whether it is set).
struct TaskQueuesSlot(Mutex<Option<TaskQueues>>);

impl std::fmt::Debug for TaskQueuesSlot {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let set = self.0.lock().map(|g| g.is_some()).unwrap_or(false);
        write!(f, "TaskQueues({})", if set { "set" } else { "none" })
    }
}

impl SystemState {
    /// A controller with one motion task `task`, motors on, AUTO, 100 %, stopped; `shutdown`
    /// turns true on Ctrl-C; `calendar` dates the event log.
    pub fn new(
        task: &str,
        events: EventPublisher,
        shutdown: Arc<AtomicBool>,
        calendar: Calendar,
    ) -> SystemState {
        SystemState {
            inner: Mutex::new(Inner {
                exec: ExecState::Stopped,
                cycle: CycleMode::Once,
                ctrl: CtrlState::MotorsOn,
                opmode: OpMode::Auto,
                speed: 100,
                want_run: false,
                reset_pp: false,
                tasks: vec![TaskInfo {
                    name: task.to_string(),
                    task_type: TaskType::Normal,
                    exec_state: TaskExecState::Ready,
                    active: true,
                    motion_task: true,
                }],
                elog: VecDeque::new(),
                next_seq: 1,
                queues: HashMap::new(),
                robot: RobotState {
                    time: 0.0,
                    joints: [0.0; 6],
                },
                pp_resets: 0,
                starts: 0,
            }),
            limits: Arc::new(PanelLimits::default()),
            shutdown,
            events,
            calendar,
            clock: MonotonicClock::new(),
            task_queues: TaskQueuesSlot(Mutex::new(None)),
            position: std::sync::OnceLock::new(),
            outputs: std::sync::OnceLock::new(),
        }
    }

    /// A system of several tasks: replace the task list (in task-number order).
    pub fn set_tasks(&self, tasks: Vec<TaskInfo>) {
        self.lock().tasks = tasks;
    }

    /// Set one task's execution state (a STATIC task running or ended, a NORMAL task whose
    /// cycle ended); publishes it.
    pub fn set_task_state(&self, task: &str, exec: TaskExecState) {
        let info = {
            let mut g = self.lock();
            let Some(t) = g
                .tasks
                .iter_mut()
                .find(|t| t.name.eq_ignore_ascii_case(task))
            else {
                return;
            };
            if t.exec_state == exec {
                return;
            }
            t.exec_state = exec;
            t.clone()
        };
        self.publish(Event::Task(info));
    }

    /// True when no active NORMAL task is running (their cycles have all ended).
    pub fn normal_tasks_idle(&self) -> bool {
        !self.lock().tasks.iter().any(|t| {
            t.active && t.task_type == TaskType::Normal && t.exec_state == TaskExecState::Started
        })
    }

    /// True when task `task` is active (takes part when the NORMAL tasks start).
    pub fn task_active(&self, task: &str) -> bool {
        self.lock()
            .tasks
            .iter()
            .any(|t| t.active && t.name.eq_ignore_ascii_case(task))
    }

    /// Program-pointer resets so far.
    pub fn pp_resets(&self) -> u64 {
        self.lock().pp_resets
    }

    /// Starts so far.
    pub fn starts(&self) -> u64 {
        self.lock().starts
    }

    /// Where `rw/dipc` messages to a RAPID task's queue go.
    pub fn set_task_queues(&self, queues: TaskQueues) {
        *self
            .task_queues
            .0
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner) = Some(queues);
    }

    /// Deliver `message` to the RAPID task queue `target`; `None` when it names none.
    pub fn deliver_to_task(
        &self,
        target: &str,
        message: &DipcMessage,
    ) -> Option<Result<(), String>> {
        let g = self
            .task_queues
            .0
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        g.as_ref().and_then(|f| f(target, message))
    }

    /// True when the external queue `queue` exists.
    pub fn dipc_exists(&self, queue: &str) -> bool {
        self.lock().queues.contains_key(queue)
    }

    /// Put `message` in the external queue `queue` (a RAPID task sends to it) and publish it.
    pub fn dipc_push(&self, queue: &str, message: DipcMessage) -> Result<(), String> {
        {
            let mut g = self.lock();
            match g.queues.get_mut(queue) {
                None => return Err(format!("there is no external queue {queue}")),
                Some(q) if q.len() >= MAX_QUEUE_MESSAGES => {
                    return Err(format!("queue {queue} is full"));
                }
                Some(q) => q.push_back(message.clone()),
            }
        }
        self.publish(Event::Dipc {
            queue: queue.to_string(),
            message,
        });
        Ok(())
    }

    fn lock(&self) -> MutexGuard<'_, Inner> {
        // Every change is a plain assignment: a panic elsewhere leaves consistent state.
        self.inner
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// True once the controller shuts down.
    pub fn shutting_down(&self) -> bool {
        self.shutdown.load(Ordering::Relaxed)
    }

    /// Publish an event to the services.
    pub fn publish(&self, event: Event) {
        self.events.publish(event);
    }

    /// The publisher (for the program side's data events).
    pub fn publisher(&self) -> &EventPublisher {
        &self.events
    }

    /// Log an event: every event rapidvc prints during `serve` is one.
    pub fn log(&self, kind: EventKind, description: impl Into<String>) {
        self.log_entry(
            kind.number(),
            kind.severity(),
            kind.title(),
            description.into(),
        );
    }

    /// Log an entry with a number and title of its own (events whose text carries them).
    pub fn log_entry(&self, code: u32, severity: Severity, title: &str, description: String) {
        let timestamp = self
            .calendar
            .unix_seconds(self.clock.elapsed().as_secs_f64());
        let entry = {
            let mut g = self.lock();
            let e = ElogEntry {
                seq: g.next_seq,
                severity: match severity {
                    Severity::Info => ElogSeverity::Info,
                    Severity::Warning => ElogSeverity::Warning,
                    Severity::Error => ElogSeverity::Error,
                },
                code,
                title: title.to_string(),
                description,
                timestamp,
            };
            g.next_seq += 1;
            if g.elog.len() >= ELOG_CAPACITY {
                g.elog.pop_front();
            }
            g.elog.push_back(e.clone());
            e
        };
        self.publish(Event::Elog(0, entry));
    }

    /// The event log, oldest first.
    pub fn elog(&self) -> Vec<ElogEntry> {
        self.lock().elog.iter().cloned().collect()
    }

    /// Execution state and cycle mode.
    pub fn execution(&self) -> (ExecState, CycleMode) {
        let g = self.lock();
        (g.exec, g.cycle)
    }

    /// Controller state.
    pub fn ctrl_state(&self) -> CtrlState {
        self.lock().ctrl
    }

    /// Operating mode.
    pub fn opmode(&self) -> OpMode {
        self.lock().opmode
    }

    /// Speed ratio (percent).
    pub fn speed_ratio(&self) -> u8 {
        self.lock().speed
    }

    /// Every task.
    pub fn tasks(&self) -> Vec<TaskInfo> {
        self.lock().tasks.clone()
    }

    /// True when the operator wants the program to run.
    pub fn want_run(&self) -> bool {
        self.lock().want_run
    }

    /// Take a pending program-pointer reset.
    pub fn take_reset_pp(&self) -> bool {
        std::mem::take(&mut self.lock().reset_pp)
    }

    /// True when a program-pointer reset waits.
    pub fn reset_pp_pending(&self) -> bool {
        self.lock().reset_pp
    }

    /// The cycle mode.
    pub fn cycle(&self) -> CycleMode {
        self.lock().cycle
    }

    /// The robot's position: the motion thread's latest cycle (at most one cycle old) once
    /// its position cell is attached, else the program side's last copy.
    pub fn robot(&self) -> RobotState {
        match self.position.get() {
            Some(cell) => {
                let s = cell.load();
                RobotState {
                    time: s.time,
                    joints: s.joints,
                }
            }
            None => self.lock().robot,
        }
    }

    /// Read the robot's position from the motion thread's cell from now on (the first cell
    /// given stays).
    pub fn attach_position(&self, cell: Arc<crate::controller::position_cell::PositionCell>) {
        let _ = self.position.set(cell);
    }

    /// Drive the system outputs of EIO.cfg from this state from now on (the first given
    /// stays).
    pub fn attach_outputs(&self, outputs: Arc<crate::controller::system_outputs::SystemOutputs>) {
        let _ = self.outputs.set(outputs);
    }

    /// Set the system outputs to the panel's and the tasks' state (called by the program
    /// sides at their panel poll): motors, operating mode, and the tasks that run — the
    /// STATIC and SEMISTATIC ones always, the active NORMAL ones while the program runs.
    /// (`Error` stays 0 here: the event log has the error.)
    pub fn show_outputs(&self) {
        let Some(outputs) = self.outputs.get() else {
            return;
        };
        let g = self.lock();
        let mut running: Vec<String> = g
            .tasks
            .iter()
            .filter(|t| t.active && (t.task_type != TaskType::Normal || g.want_run))
            .map(|t| t.name.clone())
            .collect();
        if g.tasks.is_empty() && g.want_run {
            running.push(crate::config::sys::DEFAULT_TASK.to_string());
        }
        let st = crate::controller::system_outputs::OutputState {
            motors_on: g.ctrl == CtrlState::MotorsOn,
            auto: g.opmode == OpMode::Auto,
            running,
            error: false,
        };
        drop(g);
        outputs.show(&st);
    }

    /// The program side tells where the robot is.
    pub fn set_robot(&self, r: RobotState) {
        self.lock().robot = r;
    }

    /// Change the execution state and say so (execution, task, and the event log).
    fn set_exec(&self, exec: ExecState, task_state: TaskExecState) {
        let (changed, cycle, tasks) = {
            let mut g = self.lock();
            let changed = g.exec != exec;
            g.exec = exec;
            // STATIC and SEMISTATIC tasks are not started or stopped with the program.
            for t in g
                .tasks
                .iter_mut()
                .filter(|t| t.active && t.task_type == TaskType::Normal)
            {
                t.exec_state = task_state;
            }
            (changed, g.cycle, g.tasks.clone())
        };
        if changed {
            self.publish(Event::Execution { state: exec, cycle });
            for t in tasks {
                self.publish(Event::Task(t));
            }
        }
    }

    /// Start: from the program pointer, with `cycle` (AsIs keeps the mode). Refused with the
    /// motors off.
    pub fn start(&self, cycle: CycleMode) -> Result<(), String> {
        {
            let mut g = self.lock();
            if g.ctrl != CtrlState::MotorsOn {
                return Err("the motors are off: switch them on before starting".into());
            }
            if !g
                .tasks
                .iter()
                .any(|t| t.active && t.task_type == TaskType::Normal)
            {
                return Err("no normal task is active".into());
            }
            if cycle != CycleMode::AsIs {
                g.cycle = cycle;
            }
            g.want_run = true;
            g.starts += 1;
        }
        self.set_exec(ExecState::Running, TaskExecState::Started);
        self.log(
            EventKind::ProgramStarted,
            format!(
                "Execution of the program has been started ({:?}).",
                self.cycle()
            ),
        );
        Ok(())
    }

    /// Stop: the program stops at the next statement boundary, the robot brakes, the
    /// program pointer is kept. `why` goes into the event log.
    pub fn stop(&self, why: &str) {
        let was = {
            let mut g = self.lock();
            std::mem::replace(&mut g.want_run, false)
        };
        self.set_exec(ExecState::Stopped, TaskExecState::Stopped);
        if was {
            self.log(EventKind::ProgramStopped, why.to_string());
        }
    }

    /// The program side: a run ended by itself (a single cycle, EXIT, Stop, an error).
    pub fn run_ended(&self, why: &str) {
        self.stop(why);
    }

    /// Program pointer to main; refused while the program runs.
    pub fn reset_pp(&self) -> Result<(), String> {
        {
            let mut g = self.lock();
            if g.want_run {
                return Err("the program is running: stop it first".into());
            }
            g.reset_pp = true;
            g.pp_resets += 1;
        }
        self.set_exec(ExecState::Stopped, TaskExecState::Ready);
        self.log(
            EventKind::PpReset,
            "The program pointer has been reset to main.",
        );
        Ok(())
    }

    /// Motors on or off; off stops a running program.
    pub fn set_motors(&self, on: bool) {
        let state = if on {
            CtrlState::MotorsOn
        } else {
            CtrlState::MotorsOff
        };
        let changed = {
            let mut g = self.lock();
            std::mem::replace(&mut g.ctrl, state) != state
        };
        if !on {
            self.stop("The motors were switched off.");
        }
        if changed {
            self.publish(Event::CtrlState(state));
            self.log(
                if on {
                    EventKind::MotorsOn
                } else {
                    EventKind::MotorsOff
                },
                "Requested over Robot Web Services.",
            );
        }
    }

    /// Change the operating mode; a running program stops (as turning the key does).
    pub fn set_opmode(&self, mode: OpMode) {
        let changed = {
            let mut g = self.lock();
            std::mem::replace(&mut g.opmode, mode) != mode
        };
        self.limits
            .manual_reduced
            .store(mode == OpMode::ManualReduced, Ordering::Relaxed);
        if changed {
            self.stop("The operating mode was changed.");
            self.publish(Event::OpMode(mode));
        }
    }

    /// Change the speed ratio (1–100 %).
    pub fn set_speed_ratio(&self, percent: u8) -> Result<(), String> {
        if !(1..=100).contains(&percent) {
            return Err(format!(
                "the speed ratio {percent} is outside 1..100 percent"
            ));
        }
        self.lock().speed = percent;
        self.limits.speed_ratio.store(percent, Ordering::Relaxed);
        self.publish(Event::SpeedRatio(percent));
        Ok(())
    }

    /// Activate or deactivate a task (only while stopped).
    pub fn set_task_active(&self, task: &str, active: bool) -> Result<(), TaskError> {
        let info = {
            let mut g = self.lock();
            if g.want_run {
                return Err(TaskError::Running);
            }
            let Some(t) = g
                .tasks
                .iter_mut()
                .find(|t| t.name.eq_ignore_ascii_case(task))
            else {
                return Err(TaskError::Unknown);
            };
            t.active = active;
            t.clone()
        };
        self.publish(Event::Task(info));
        Ok(())
    }
}

/// Why a task could not be (de)activated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TaskError {
    /// No such task.
    Unknown,
    /// Not while the program runs.
    Running,
}
