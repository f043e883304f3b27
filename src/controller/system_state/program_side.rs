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
use crate::controller::service::{
    Coordinate, CycleMode, Event, MechUnitInfo, ModuleInfo, OpMode, Request, RobotState,
    ServiceError, SymbolClass, SymbolInfo, SymbolPath,
};
use crate::events::EventKind;
use crate::interp::data_access::{DataSymbol, DataWriteError};
use crate::interp::{HookAction, Interp, Outcome, RuntimeError};
use crate::robot::{Pose, ToolData, WobjData};

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
    /// The speed ratio the robot was last given (percent).
    ratio: u8,
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
            ratio: 100,
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
                            system: m.stdlib,
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
        match self.requests.recv_timeout(timeout) {
            Ok(req) => self.answer(it, req),
            Err(RecvTimeoutError::Timeout | RecvTimeoutError::Disconnected) => {}
        }
        self.serve(it);
    }

    /// The interpreter's service hook: between statements and in waits.
    fn between(&mut self, it: &mut Interp) -> HookAction {
        self.serve(it);
        if self.state.shutting_down() || self.state.reset_pp_pending() {
            return HookAction::Stop;
        }
        if self.state.want_run() {
            return HookAction::Continue;
        }
        // Stopped: hold the robot, keep the program pointer, wait here.
        if let Some(h) = host(it) {
            h.hold_motion();
        }
        self.update_robot(it);
        loop {
            if self.state.shutting_down() || self.state.reset_pp_pending() {
                return HookAction::Stop;
            }
            if self.state.want_run() {
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

/// The robot's TCP as a robtarget (RAPID text), for `tool0`/`wobj0`.
fn robtarget(
    it: &mut Interp,
    tool: Option<&str>,
    wobj: Option<&str>,
    coordinate: Coordinate,
) -> Result<String, ServiceError> {
    for (what, name, default) in [("tool", tool, "tool0"), ("wobj", wobj, "wobj0")] {
        if let Some(n) = name
            && !n.eq_ignore_ascii_case(default)
        {
            return Err(ServiceError::NotFound(format!(
                "{what} {n}: rapidvc serves robtargets for tool0 and wobj0 only"
            )));
        }
    }
    if coordinate == Coordinate::Tool {
        return Err(ServiceError::BadValue(
            "the Tool coordinate system is not supported by rapidvc; use Base, World or Wobj"
                .into(),
        ));
    }
    let h = host(it).ok_or_else(|| ServiceError::NotAllowed("no robot".into()))?;
    let joints = h
        .controller()
        .map(|c| c.state().setpoint.joints)
        .ok_or(ServiceError::Gone)?;
    let t = crate::interp::Host::robot_target_of(
        h,
        &joints,
        &ToolData::default(),
        &WobjData::default(),
        &Pose::identity(),
    )
    .map_err(|e| ServiceError::NotAllowed(e.message))?;
    let n = |v: f64| crate::functions::format::format_num(v as f32);
    let list = |v: &[f64]| v.iter().map(|x| n(*x)).collect::<Vec<_>>().join(",");
    Ok(format!(
        "[[{}],[{}],[{}],[{}]]",
        list(&t.trans),
        list(&t.rot),
        t.robconf
            .to_array()
            .iter()
            .map(|c| c.to_string())
            .collect::<Vec<_>>()
            .join(","),
        list(&t.extax)
    ))
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
    lock(&side).prime(it);
    loop {
        // Idle: the program pointer is at main.
        while !state.shutting_down() && !state.want_run() {
            lock(&side).idle(it, Duration::from_millis(10));
            state.take_reset_pp();
        }
        if state.shutting_down() {
            break;
        }
        state.take_reset_pp();
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
        let again = matches!(outcome, Ok(Outcome::Completed | Outcome::ExitCycle))
            && state.cycle() == CycleMode::Forever
            && state.want_run()
            && !state.reset_pp_pending();
        if again {
            continue;
        }
        if let Some(h) = host(it) {
            h.forget_motion();
        }
        if state.take_reset_pp() {
            continue;
        }
        state.run_ended(&ended(&outcome));
        state.log(
            EventKind::PpReset,
            "The program pointer is at main again after the run ended.",
        );
    }
    it.set_service_hook(None);
}
