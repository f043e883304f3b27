//! The program side of a controller that stays up: on the interpreter's thread, between
//! program steps and on every turn of a wait (the interpreter's service hook), it answers
//! what needs the program (RAPID data, modules, the robot's position), publishes changed
//! persistents, and while the program is stopped blocks at the statement boundary with the
//! robot held, so the program continues from its program pointer when it is started again.

use std::sync::atomic::Ordering;
use std::sync::mpsc::{Receiver, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use super::SystemState;
use crate::ast::Storage;
use crate::controller::ControllerHost;
use crate::controller::robtarget_query;
use crate::controller::service::{
    Coordinate, CtrlState, CycleMode, Event, MechUnitInfo, ModuleInfo, OpMode, Request, RobotState,
    ServiceError, SymbolClass, SymbolInfo, SymbolPath, TaskExecState,
};
use crate::events::EventKind;
use crate::interp::data_access::{DataSymbol, DataWriteError};
use crate::interp::{HookAction, Interp, Outcome, RuntimeError};

/// How often changed persistents and the robot's position are looked for.
const DATA_POLL: Duration = Duration::from_millis(20);

/// The program side's state (shared by the runner and the interpreter's service hook).
pub struct ProgramSide {
    state: Arc<SystemState>,
    requests: Receiver<Request>,
    task: String,
    /// The last published value of every persistent (by global index).
    pers: Vec<(usize, String)>,
    last_poll: Instant,
    /// One task of a system of several (see [`ProgramSide::in_system`]).
    system: Option<InSystem>,
    /// The speed ratio the robot was last given (percent).
    ratio: u8,
}

/// What a task of a system of several tasks keeps: its own view of resets and starts, and
/// whether it is a STATIC or SEMISTATIC task (it runs from boot, whatever the panel does).
#[derive(Debug, Clone, Copy)]
struct InSystem {
    background: bool,
    /// The program-pointer resets this task has acted on.
    pp_seen: u64,
    /// The start whose cycle this task has ended (it waits for the next start).
    ended_in: Option<u64>,
}

impl std::fmt::Debug for ProgramSide {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ProgramSide")
            .field("task", &self.task)
            .finish_non_exhaustive()
    }
}

fn host(it: &mut Interp) -> Option<&mut ControllerHost> {
    it.host_mut()
        .as_any_mut()
        .and_then(|a| a.downcast_mut::<ControllerHost>())
}

fn class(s: Storage) -> SymbolClass {
    match s {
        Storage::Pers => SymbolClass::Pers,
        Storage::Var => SymbolClass::Var,
        Storage::Const => SymbolClass::Const,
    }
}

impl ProgramSide {
    /// The program side of task `task`, taking the requests the service thread hands on.
    pub fn new(state: Arc<SystemState>, requests: Receiver<Request>, task: &str) -> ProgramSide {
        ProgramSide {
            state,
            requests,
            task: task.to_string(),
            pers: Vec::new(),
            last_poll: Instant::now(),
            system: None,
            ratio: 100,
        }
    }

    /// One task of a system of several: it hands the processor to the other tasks while it
    /// is stopped or idle (its host's waits do), acts on its own copy of the program-pointer
    /// resets, and, when `background` (STATIC, SEMISTATIC), runs from boot whatever the
    /// panel does (as on a controller, the stop button does not stop it).
    pub fn in_system(mut self, background: bool) -> ProgramSide {
        self.system = Some(InSystem {
            background,
            pp_seen: self.state.pp_resets(),
            ended_in: None,
        });
        self
    }

    /// True when this task is to run now.
    fn runs(&self) -> bool {
        match self.system {
            None => self.state.want_run(),
            Some(s) if s.background => true,
            Some(s) => {
                self.state.want_run()
                    && self.state.task_active(&self.task)
                    && s.ended_in != Some(self.state.starts())
            }
        }
    }

    /// True when a program-pointer reset waits for this task.
    fn reset_pending(&self) -> bool {
        match self.system {
            None => self.state.reset_pp_pending(),
            Some(s) => !s.background && s.pp_seen != self.state.pp_resets(),
        }
    }

    /// Take a waiting program-pointer reset.
    fn take_reset(&mut self) -> bool {
        let resets = self.state.pp_resets();
        match self.system.as_mut() {
            None => self.state.take_reset_pp(),
            Some(s) => {
                let was = s.pp_seen != resets;
                s.pp_seen = resets;
                if was {
                    s.ended_in = None;
                }
                was && !s.background
            }
        }
    }

    fn symbol_info(&self, d: DataSymbol) -> SymbolInfo {
        SymbolInfo {
            path: SymbolPath {
                task: self.task.clone(),
                module: Some(d.module),
                name: d.name,
            },
            class: class(d.storage),
            data_type: d.data_type,
            dims: d.dims,
            value: d.value,
        }
    }

    fn task_ok(&self, task: &str) -> Result<(), ServiceError> {
        if task.eq_ignore_ascii_case(&self.task) {
            Ok(())
        } else {
            Err(ServiceError::NotFound(format!("task {task}")))
        }
    }

    fn find(&self, it: &Interp, path: &SymbolPath) -> Result<DataSymbol, ServiceError> {
        self.task_ok(&path.task)?;
        it.data_symbols(path.module.as_deref(), Some(&path.name))
            .into_iter()
            .next()
            .ok_or_else(|| {
                ServiceError::NotFound(format!(
                    "no data {} in task {}{}",
                    path.name,
                    path.task,
                    path.module
                        .as_ref()
                        .map(|m| format!(", module {m}"))
                        .unwrap_or_default()
                ))
            })
    }

    /// Answer one request the service thread handed on.
    fn answer(&mut self, it: &mut Interp, req: Request) {
        match req {
            Request::Symbol { path, reply } => {
                let r = self.find(it, &path).map(|d| self.symbol_info(d));
                let _ = reply.send(r);
            }
            Request::SetSymbol { path, value, reply } => {
                let r = self.find(it, &path).and_then(|d| {
                    it.set_data_text(d.index, &value).map_err(|e| match e {
                        DataWriteError::Unknown => ServiceError::NotFound(path.name.clone()),
                        DataWriteError::Constant(n) => {
                            ServiceError::NotAllowed(format!("{n} is a constant"))
                        }
                        DataWriteError::BadValue(m) => ServiceError::BadValue(m),
                    })?;
                    Ok(d.storage)
                });
                if r == Ok(Storage::Pers) {
                    self.publish_pers(it, true);
                }
                let _ = reply.send(r.map(|_| ()));
            }
            Request::Symbols {
                task,
                class: c,
                reply,
            } => {
                let r = self.task_ok(&task).map(|()| {
                    it.data_symbols(None, None)
                        .into_iter()
                        .filter(|d| c.is_none_or(|c| class(d.storage) == c))
                        .map(|d| self.symbol_info(d))
                        .collect()
                });
                let _ = reply.send(r);
            }
            Request::Modules { task, reply } => {
                let r = self.task_ok(&task).map(|()| {
                    it.program()
                        .modules
                        .iter()
                        .map(|m| ModuleInfo {
                            name: m.name.clone(),
                            system: m.system,
                        })
                        .collect()
                });
                let _ = reply.send(r);
            }
            Request::RobTarget {
                tool,
                wobj,
                coordinate,
                reply,
            } => {
                let _ = reply.send(robtarget(it, tool.as_deref(), wobj.as_deref(), coordinate));
            }
            Request::MechUnits(reply) => {
                let r = match it.host_mut().system() {
                    Some(sys) => Ok(sys
                        .info
                        .mech_units()
                        .into_iter()
                        .map(|u| MechUnitInfo {
                            name: u.unit().to_string(),
                            task: self.task.clone(),
                            axes: u.axes(),
                            tool: sys.info.active.tool.clone(),
                            wobj: sys.info.active.wobj.clone(),
                            payload: sys.info.active.load.clone(),
                        })
                        .collect()),
                    None => Ok(Vec::new()),
                };
                let _ = reply.send(r);
            }
            other => other.refuse(ServiceError::NotAllowed(
                "this request is answered by the service thread".into(),
            )),
        }
    }

    /// Remember the persistents' values (before the first look for changes).
    fn prime(&mut self, it: &Interp) {
        self.pers = it
            .data_symbols(None, None)
            .into_iter()
            .filter(|d| d.storage == Storage::Pers)
            .map(|d| (d.index, d.value))
            .collect();
    }

    /// Publish persistents whose value changed since the last look (`force`: look now).
    fn publish_pers(&mut self, it: &Interp, force: bool) {
        if !force && !self.state.publisher().has_subscribers() {
            return;
        }
        let now: Vec<DataSymbol> = it
            .data_symbols(None, None)
            .into_iter()
            .filter(|d| d.storage == Storage::Pers)
            .collect();
        for d in now {
            let old = self.pers.iter_mut().find(|(i, _)| *i == d.index);
            let changed = match old {
                Some((_, v)) if *v == d.value => false,
                Some((_, v)) => {
                    v.clone_from(&d.value);
                    true
                }
                None => {
                    self.pers.push((d.index, d.value.clone()));
                    false
                }
            };
            if changed {
                self.state.publish(Event::Pers {
                    path: SymbolPath {
                        task: self.task.clone(),
                        module: Some(d.module),
                        name: d.name,
                    },
                    value: d.value,
                });
            }
        }
    }

    /// Answer what waits, and every [`DATA_POLL`] publish persistents and the robot's
    /// position.
    fn serve(&mut self, it: &mut Interp) {
        while let Ok(req) = self.requests.try_recv() {
            self.answer(it, req);
        }
        // The speed ratio scales the robot at once (moves already planned, EGM).
        let ratio = self.state.limits.speed_ratio.load(Ordering::Relaxed);
        if ratio != self.ratio
            && let Some(h) = host(it)
        {
            self.ratio = ratio;
            h.set_speed_ratio(ratio);
        }
        if self.last_poll.elapsed() >= DATA_POLL {
            self.last_poll = Instant::now();
            self.publish_pers(it, false);
            self.update_robot(it);
            self.state.show_outputs();
            // EGM tells its sensors whether the program runs and the motors are on.
            let (running, motors) = (self.runs(), self.state.ctrl_state() == CtrlState::MotorsOn);
            if let Some(h) = host(it) {
                h.set_controller_state(running, motors);
            }
            // RAPID's OpMode() reads the panel's mode.
            let mode = match self.state.opmode() {
                OpMode::Auto => crate::system::info::OpMode::Auto,
                OpMode::ManualReduced => crate::system::info::OpMode::ManualReduced,
                OpMode::ManualFull => crate::system::info::OpMode::ManualFull,
            };
            if let Some(sys) = it.host_mut().system() {
                sys.info.op_mode = mode;
            }
        }
    }

    fn update_robot(&self, it: &mut Interp) {
        if let Some(ctl) = host(it).and_then(ControllerHost::controller) {
            let st = ctl.state();
            let r = RobotState {
                time: st.setpoint.time.as_secs_f64(),
                joints: st.setpoint.joints,
            };
            self.state.set_robot(r);
        }
    }

    /// Block until a request arrives or `timeout` passes, then answer what waits.
    fn idle(&mut self, it: &mut Interp, timeout: Duration) {
        if self.system.is_some() {
            // The other tasks run meanwhile: wait through the host (it hands the processor
            // over), answering what came first.
            self.serve(it);
            let until = it.host_mut().now().after_secs(timeout.as_secs_f64());
            if it.host_wait_until(until).is_err() {
                std::thread::sleep(timeout);
            }
            return;
        }
        match self.requests.recv_timeout(timeout) {
            Ok(req) => self.answer(it, req),
            Err(RecvTimeoutError::Timeout | RecvTimeoutError::Disconnected) => {}
        }
        self.serve(it);
    }

    /// The interpreter's service hook: between statements and in waits.
    fn between(&mut self, it: &mut Interp) -> HookAction {
        self.serve(it);
        if self.state.shutting_down() || self.reset_pending() {
            return HookAction::Stop;
        }
        if self.runs() {
            return HookAction::Continue;
        }
        // Stopped: hold the robot, keep the program pointer, wait here.
        if let Some(h) = host(it) {
            h.hold_motion();
        }
        self.update_robot(it);
        loop {
            if self.state.shutting_down() || self.reset_pending() {
                return HookAction::Stop;
            }
            if self.runs() {
                if let Some(h) = host(it)
                    && let Err(e) = h.resume_motion()
                {
                    self.state.log(EventKind::ProgramError, e.message);
                    self.state.run_ended("The stopped move could not continue.");
                    continue;
                }
                return HookAction::Continue;
            }
            self.idle(it, Duration::from_millis(10));
        }
    }
}

/// The robot's TCP as a robtarget (RAPID text) of a tool and work object of the task's data
/// in a coordinate system, at the motion thread's latest cycle
/// (`controller/robtarget_query.rs`).
fn robtarget(
    it: &mut Interp,
    tool: Option<&str>,
    wobj: Option<&str>,
    coordinate: Coordinate,
) -> Result<String, ServiceError> {
    let tool = robtarget_query::tool(it, tool)?;
    let wobj = robtarget_query::wobj(it, wobj)?;
    let pdisp = it.host_mut().motion_modes().pdisp;
    let h = host(it).ok_or_else(|| ServiceError::NotAllowed("no robot".into()))?;
    let ctl = h.controller().ok_or(ServiceError::Gone)?;
    let joints = match ctl.position_cell() {
        Some(cell) => cell.load().joints,
        None => ctl.state().setpoint.joints,
    };
    let h: &ControllerHost = h;
    let t =
        robtarget_query::in_coordinate(&joints, &tool, &wobj, &pdisp, coordinate, |j, t, w, p| {
            crate::interp::Host::robot_target_of(h, j, t, w, p).map_err(|e| e.message)
        })?;
    Ok(robtarget_query::text(&t))
}

/// How a program run ended, for the event log.
fn ended(outcome: &Result<Outcome, Box<RuntimeError>>) -> String {
    match outcome {
        Ok(Outcome::Completed | Outcome::ExitCycle) => "The program's cycle ended.".into(),
        Ok(Outcome::Exited) => "The program ended by EXIT.".into(),
        Ok(Outcome::Stopped) => "The program stopped.".into(),
        Err(e) => format!("The program stopped on an error: {}", e.message),
    }
}

/// Run the controller's program until shutdown: idle while stopped (answering services),
/// run `entry` from main when started, once or forever as the cycle mode says, continue from
/// the program pointer after a stop (inside the service hook). Returns when the controller
/// shuts down.
pub fn run_program(it: &mut Interp, entry: &str, side: ProgramSide) {
    let side = Arc::new(Mutex::new(side));
    fn lock(s: &Mutex<ProgramSide>) -> std::sync::MutexGuard<'_, ProgramSide> {
        s.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }
    {
        let s = Arc::clone(&side);
        it.set_service_hook(Some(Box::new(move |it: &mut Interp| {
            let mut g = s.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
            g.between(it)
        })));
    }
    let state = Arc::clone(&lock(&side).state);
    let task = lock(&side).task.clone();
    let background = lock(&side).system.is_some_and(|s| s.background);
    lock(&side).prime(it);
    if let Some(cell) = host(it)
        .and_then(ControllerHost::controller)
        .and_then(|c| c.position_cell())
    {
        state.attach_position(cell);
    }
    loop {
        // Idle: the program pointer is at main.
        while !state.shutting_down() && !lock(&side).runs() {
            lock(&side).idle(it, Duration::from_millis(10));
            lock(&side).take_reset();
        }
        if state.shutting_down() {
            break;
        }
        lock(&side).take_reset();
        if background {
            state.set_task_state(&task, TaskExecState::Started);
        }
        let outcome = it.run(entry);
        if state.shutting_down() {
            break;
        }
        if let Err(e) = &outcome {
            state.log(
                EventKind::ProgramError,
                format!("{} ({:?})", e.message, e.kind),
            );
        }
        if background {
            // A STATIC or SEMISTATIC task whose entry routine returns has ended: it stays
            // (answering services) until the controller shuts down.
            let exec = if outcome.is_ok() {
                TaskExecState::Ready
            } else {
                TaskExecState::Stopped
            };
            state.set_task_state(&task, exec);
            state.log(
                EventKind::ProgramStopped,
                format!("task {task}: {}", ended(&outcome)),
            );
            while !state.shutting_down() {
                lock(&side).idle(it, Duration::from_millis(10));
            }
            break;
        }
        let again = matches!(outcome, Ok(Outcome::Completed | Outcome::ExitCycle))
            && state.cycle() == CycleMode::Forever
            && lock(&side).runs()
            && !lock(&side).reset_pending();
        if again {
            continue;
        }
        if let Some(h) = host(it) {
            h.forget_motion();
        }
        if lock(&side).take_reset() {
            continue;
        }
        let in_system = lock(&side).system.is_some();
        if in_system {
            // This task's cycle has ended; the program has ended when every active NORMAL
            // task's has (an error stops them all).
            if let Some(s) = lock(&side).system.as_mut() {
                s.ended_in = Some(state.starts());
            }
            state.set_task_state(&task, TaskExecState::Ready);
            if outcome.is_ok() && !state.normal_tasks_idle() {
                continue;
            }
        }
        state.run_ended(&ended(&outcome));
        state.log(
            EventKind::PpReset,
            "The program pointer is at main again after the run ended.",
        );
    }
    it.set_service_hook(None);
}
