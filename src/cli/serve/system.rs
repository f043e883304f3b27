//! `rapidvc serve` of a system with several tasks (a backup folder, SYS.cfg with several
//! `CAB_TASKS`, or `T_ROB1=a.mod T_LOG=b.mod`): every task of SYS.cfg that has modules runs
//! on the scheduler of `controller::tasks` in real time, each with its own program side
//! (services answered between its statements and in its waits).
//!
//! * NORMAL tasks are started, stopped and reset over RWS together (the active ones, as the
//!   task selection panel says); their program ends when every active one has ended its
//!   cycle, or one fails.
//! * STATIC and SEMISTATIC tasks start at boot and keep running: RWS stop and start do not
//!   act on them (on a controller the stop button does not stop them either).
//! * Requests about one task's data go to that task's program side (the router below); the
//!   robot's position and mechanical units to the motion task's.
//! * `rw/dipc` messages to `RMQ_<task>` (or the task's name) go to the task's RAPID message
//!   queue, and RAPID's `RMQSendMessage` to the slot of an external queue (found with
//!   `RMQFindSlot` by its name) lands in that `rw/dipc` queue ([`DipcBridge`]).

use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender};
use std::sync::{Arc, Mutex, Weak};
use std::time::Duration;

use super::{ServeArgs, log_output, serve_info, started_line};
use crate::cli::render;
use crate::cli::run;
use crate::cli::run::tasks::{
    exit_code, load_checked, plain_host, start_motion_controller, task_specs,
};
use crate::controller::ControllerHost;
use crate::controller::MonotonicClock;
use crate::controller::service::{
    self, DipcMessage, Request, ServiceError, TaskExecState, TaskInfo, TaskType,
};
use crate::controller::system_state::SystemState;
use crate::controller::system_state::program_side::{ProgramSide, run_program};
use crate::controller::tasks::{
    DEFAULT_SLICE, EXTERNAL_SLOT_BASE, ExternalQueues, Scheduler, TaskedHost, run_tasks,
};
use crate::events::EventKind;
use crate::interp::host::RmqMessage;
use crate::interp::tasks::SharedPers;
use crate::interp::{Host, Interp};
use crate::program::system::LoadedSystem;

/// The `rw/dipc` queues as RAPID sees them: `RMQFindSlot` gives an external queue the slot
/// [`EXTERNAL_SLOT_BASE`] + n (n in the order the program first looks them up), and a
/// message sent to it is put in the queue as `type;value` text, from `RMQ_<task>`.
struct DipcBridge {
    state: Weak<SystemState>,
    names: Mutex<Vec<String>>,
}

impl DipcBridge {
    fn names(&self) -> std::sync::MutexGuard<'_, Vec<String>> {
        self.names
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

impl ExternalQueues for DipcBridge {
    fn slot(&self, name: &str) -> Option<i32> {
        let state = self.state.upgrade()?;
        if !state.dipc_exists(name) {
            return None;
        }
        let mut names = self.names();
        let i = match names.iter().position(|n| n == name) {
            Some(i) => i,
            None => {
                names.push(name.to_string());
                names.len() - 1
            }
        };
        i32::try_from(i).ok().map(|i| EXTERNAL_SLOT_BASE + i)
    }

    fn name(&self, slot: i32) -> Option<String> {
        let i = usize::try_from(slot.checked_sub(EXTERNAL_SLOT_BASE)?).ok()?;
        self.names().get(i).cloned()
    }

    fn send(&self, slot: i32, from: &str, msg: &RmqMessage) -> Result<(), String> {
        let name = self
            .name(slot)
            .ok_or_else(|| format!("slot {slot} is no external queue"))?;
        let state = self
            .state
            .upgrade()
            .ok_or_else(|| "the controller shuts down".to_string())?;
        state.dipc_push(
            &name,
            DipcMessage {
                source: from.to_string(),
                cmd: 111,
                userdef: i64::from(msg.userdef),
                msgtype: 1,
                data: format!("{};{}", msg.datatype, msg.data),
            },
        )
    }
}

/// The task a request is about (`None`: the motion task's: position, mechanical units).
fn task_of(req: &Request) -> Option<&str> {
    match req {
        Request::Symbol { path, .. } | Request::SetSymbol { path, .. } => Some(&path.task),
        Request::Symbols { task, .. } | Request::Modules { task, .. } => Some(task),
        _ => None,
    }
}

/// Hand each request the service thread passes on to the program side of its task, until
/// the controller shuts down.
fn route(
    forwarded: &Receiver<Request>,
    tasks: &[(String, Sender<Request>)],
    motion: usize,
    shutdown: &AtomicBool,
) {
    loop {
        let req = match forwarded.recv_timeout(Duration::from_millis(50)) {
            Ok(r) => r,
            Err(RecvTimeoutError::Timeout) if !shutdown.load(Ordering::Relaxed) => continue,
            Err(_) => return,
        };
        let to = match task_of(&req) {
            Some(name) => tasks.iter().find(|t| t.0.eq_ignore_ascii_case(name.trim())),
            None => tasks.get(motion),
        };
        match to {
            Some((_, tx)) => {
                if let Err(e) = tx.send(req) {
                    e.0.refuse(ServiceError::Gone);
                }
            }
            None => {
                let name = task_of(&req).unwrap_or_default().to_string();
                req.refuse(ServiceError::NotFound(format!("task {name}")));
            }
        }
    }
}

/// What a task's thread hands back when the controller shuts down.
struct TaskEnd {
    code: ExitCode,
    egm: Option<crate::controller::egm_controller::EgmController>,
}

/// Boot the system and serve until Ctrl-C (see the module docs).
pub(super) fn serve_system(args: &ServeArgs, shutdown: &Arc<AtomicBool>) -> ExitCode {
    let a = &args.run;
    let (loaded, operator) = match load_checked(a) {
        Ok(l) => l,
        Err(code) => return code,
    };
    let LoadedSystem {
        sources,
        tasks,
        idle,
        registry,
        signals,
        config,
        home,
        ..
    } = loaded;
    let sources = Arc::new(sources);
    let (storage, roots, listener) = match super::boot(args, a.home.clone().or(home)) {
        Ok(b) => b,
        Err(msg) => {
            eprintln!("error: {msg}");
            return ExitCode::from(2);
        }
    };
    let system = run::system_services(a, &config, &sources);
    let info = serve_info(&system, roots, &signals);
    let calendar = system.calendar;
    let uses_sockets = tasks
        .iter()
        .filter_map(|t| t.program.as_deref())
        .any(run::socket_clock::uses_sockets);
    let (mut controller, egm_log_written) =
        match start_motion_controller(a, &tasks, &sources, &config, &signals, uses_sockets, None) {
            Ok(c) => c,
            Err(msg) => {
                eprintln!("error: {msg}");
                return ExitCode::from(2);
            }
        };
    // The scheduler's clock starts with the motion thread's (within a few milliseconds).
    let clock = Arc::new(MonotonicClock::new());
    let motion = tasks.iter().position(|t| t.config.motion);
    let first = motion.unwrap_or(0);
    let motion_name = tasks
        .get(first)
        .map_or_else(|| super::MOTION_TASK.to_string(), |t| t.config.name.clone());
    let (handle, endpoint) = service::channel();
    let state = Arc::new(SystemState::new(
        &motion_name,
        endpoint.publisher(),
        Arc::clone(shutdown),
        calendar,
    ));
    if let Some(o) = run::system_outputs(&config, &signals) {
        state.attach_outputs(Arc::new(o));
    }
    let kind = |k: crate::config::sys::TaskType| match k {
        crate::config::sys::TaskType::Normal => TaskType::Normal,
        crate::config::sys::TaskType::Static => TaskType::Static,
        crate::config::sys::TaskType::SemiStatic => TaskType::SemiStatic,
    };
    let mut infos: Vec<(usize, TaskInfo)> = tasks
        .iter()
        .map(|t| {
            (
                t.number,
                TaskInfo {
                    name: t.config.name.clone(),
                    task_type: kind(t.config.kind),
                    // STATIC and SEMISTATIC tasks start at boot.
                    exec_state: if t.config.kind == crate::config::sys::TaskType::Normal {
                        TaskExecState::Ready
                    } else {
                        TaskExecState::Started
                    },
                    active: true,
                    motion_task: t.config.motion,
                },
            )
        })
        .collect();
    let (specs, idle_specs) = task_specs(&tasks, &idle, &config);
    for s in &idle_specs {
        infos.push((
            usize::try_from(s.number).unwrap_or(0),
            TaskInfo {
                name: s.config.name.clone(),
                task_type: kind(s.config.kind),
                exec_state: TaskExecState::Uninitialized,
                active: false,
                motion_task: s.config.motion,
            },
        ));
    }
    infos.sort_by_key(|t| t.0);
    state.set_tasks(infos.into_iter().map(|t| t.1).collect());

    let halt = Arc::new(AtomicBool::new(false));
    let sched = Scheduler::new(
        specs,
        idle_specs,
        Arc::clone(&halt),
        Some(Arc::clone(shutdown)),
    );
    sched.use_real_time(clock);
    if let Some((ctl, ..)) = controller.as_mut() {
        sched.use_robot(ctl.state().setpoint.joints, ctl.position_cell());
    }
    sched.use_external_queues(Arc::new(DipcBridge {
        state: Arc::downgrade(&state),
        names: Mutex::new(Vec::new()),
    }));
    {
        let sched = Arc::downgrade(&sched);
        state.set_task_queues(Box::new(move |target, m| {
            sched
                .upgrade()?
                .deliver(target, &m.source, &m.data, m.userdef)
        }));
    }

    let (services, forwarded) = match super::start_services(endpoint, &state, info) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let mut routes = Vec::new();
    let mut receivers = Vec::new();
    for t in &tasks {
        let (tx, rx) = std::sync::mpsc::channel();
        routes.push((t.config.name.clone(), tx));
        receivers.push(Some(rx));
    }
    let router = {
        let shutdown = Arc::clone(shutdown);
        std::thread::Builder::new()
            .name("rapidvc-task-router".into())
            .spawn(move || route(&forwarded, &routes, first, &shutdown))
    };
    let router = match router {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: cannot start the request router: {e}");
            shutdown.store(true, Ordering::Relaxed);
            let _ = services.join();
            return ExitCode::from(2);
        }
    };
    let server = match super::start_rws(args, listener, handle) {
        Ok(s) => s,
        Err(msg) => {
            eprintln!("error: {msg}");
            shutdown.store(true, Ordering::Relaxed);
            let _ = services.join();
            let _ = router.join();
            return ExitCode::from(2);
        }
    };
    started_line(&server);

    let labels = tasks.len() > 1;
    let store = SharedPers::new();
    let mut operator = Some(operator);
    let mut bodies: Vec<Box<dyn FnOnce() -> TaskEnd + Send + '_>> = Vec::new();
    for (i, task) in tasks.iter().enumerate() {
        let Some(prog) = task.program.clone() else {
            continue;
        };
        let Some(requests) = receivers.get_mut(i).and_then(Option::take) else {
            continue;
        };
        let mut services = system.clone();
        services.info.task = task.config.name.clone();
        let log_state = Arc::clone(&state);
        let sink = move |o: &crate::interp::Output| {
            run::print_output(o);
            log_output(&log_state, o);
        };
        let inner: Box<dyn Host + Send> = match (Some(i) == motion, controller.take()) {
            (true, Some((ctl, egm, _, _))) => Box::new(
                ControllerHost::new(ctl)
                    .with_egm(egm)
                    .with_signals(Arc::clone(&signals))
                    .with_system(services)
                    .with_max_time(a.max_time)
                    .with_lines(Arc::clone(&sources))
                    .with_panel(Arc::clone(&state.limits))
                    .with_sink(sink),
            ),
            (_, ctl) => {
                controller = ctl;
                plain_host(&signals, services, sink)
            }
        };
        let host = TaskedHost::new(Arc::clone(&sched), bodies.len(), inner, labels, None);
        let loader = crate::program::runtime_loader::RuntimeLoader::new(&prog, &sources, &signals);
        let registry = registry.clone();
        let storage = Arc::clone(&storage);
        let store = Arc::clone(&store);
        let halt = Arc::clone(&halt);
        let sources = Arc::clone(&sources);
        let state = Arc::clone(&state);
        let entry = task.config.entry.clone();
        let name = task.config.name.clone();
        let background = task.config.kind != crate::config::sys::TaskType::Normal;
        let operator = if i == first { operator.take() } else { None };
        let max_steps = a.max_steps;
        bodies.push(Box::new(move || {
            let mut it = Interp::new(prog, &registry, Box::new(host));
            it.set_module_loader(Box::new(loader));
            it.set_mass_storage(storage);
            it.set_budget(max_steps);
            it.set_stop_request(halt);
            if let Some(op) = operator {
                it.set_operator(op);
            }
            it.set_stack_budget(6 << 20);
            let mut code = ExitCode::SUCCESS;
            match it.init() {
                Err(e) => {
                    eprintln!("error in task {name}:");
                    render::runtime_error(&e, &sources);
                    state.log(
                        EventKind::ProgramError,
                        format!("task {name}: {}", e.message),
                    );
                    state.set_task_state(&name, TaskExecState::Uninitialized);
                    code = ExitCode::from(1);
                }
                Ok(()) => {
                    it.set_task_link(store, DEFAULT_SLICE);
                    let side =
                        ProgramSide::new(Arc::clone(&state), requests, &name).in_system(background);
                    run_program(&mut it, &entry, side);
                }
            }
            let mut egm = None;
            if let Some((e, finished)) = super::finish_motion(&mut it) {
                egm = e;
                if !finished {
                    code = ExitCode::from(2);
                }
            }
            TaskEnd { code, egm }
        }));
    }
    let ends = run_tasks(&sched, bodies);
    shutdown.store(true, Ordering::Relaxed);
    server.stop();
    let _ = services.join();
    let _ = router.join();
    let code = exit_code(
        ends.into_iter().map(|e| e.map(|e| (e.code, e.egm))),
        a,
        egm_log_written,
    );
    eprintln!("rapidvc serve: stopped");
    code
}
