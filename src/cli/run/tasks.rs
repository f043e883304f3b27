//! `rapidvc run` of a system with several tasks, or booted from a backup folder: every task
//! of SYS.cfg that has modules runs on the scheduler of `controller::tasks` (its rule, and
//! what STATIC and SEMISTATIC tasks do in a run, are documented there and in
//! `docs/tasks.md`). TP lines and events carry the task's name (`[T_LOG] text`) when more
//! than one task runs.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use super::{RunArgs, egm_options, print_output, print_summary, render, socket_clock};
use crate::cli::{answers, interrupt, progress_line};
use crate::controller::ControllerHost;
use crate::controller::tasks::{DEFAULT_SLICE, Scheduler, TaskSpec, TaskedHost, run_tasks};
use crate::interp::tasks::SharedPers;
use crate::interp::{Host, Interp, Outcome, VirtualHost, pers};
use crate::mass_storage::MassStorage;
use crate::program::system::{LoadedSystem, load_system};
use crate::source::SourceMap;

/// True when the arguments ask for a system rather than one program: one backup folder,
/// a task prefix (`T_ROB1=a.mod`), or a SYS.cfg (in `--config` or beside the files) that
/// defines more than one task.
pub fn wants_system(args: &RunArgs) -> bool {
    use crate::program::system::{is_backup, split_task_prefix};
    if let [one] = args.files.as_slice()
        && is_backup(one)
    {
        return true;
    }
    if args.files.iter().any(|p| split_task_prefix(p).0.is_some()) {
        return true;
    }
    let dir = crate::program::config_dir(args.config.as_deref(), &args.files);
    let Some(sys) = dir.and_then(|d| crate::config::find_file(&d, "SYS.cfg")) else {
        return false;
    };
    let mut sources = SourceMap::new();
    let mut diags = crate::diag::Diagnostics::new();
    crate::config::load_file(&sys, "SYS", &mut sources, &mut diags)
        .map(|f| crate::config::sys::read(&f, &mut diags))
        .is_some_and(|s| s.tasks.len() > 1)
}

/// What a task's thread reports when its program has ended.
struct TaskEnd {
    code: ExitCode,
    /// The robot may finish its queued moves (the program ended normally).
    drain: bool,
    /// The motion task's EGM side, to finish after the run.
    egm: Option<crate::controller::egm_controller::EgmController>,
}

/// The motion task's controller (robot, traces, plots, EGM), when a task moves the robot;
/// and whether `--egm-log` is written.
pub(crate) fn start_motion_controller(
    args: &RunArgs,
    tasks: &[crate::program::system::TaskProgram],
    sources: &Arc<SourceMap>,
    config: &crate::config::Config,
    signals: &Arc<crate::signals::SignalTable>,
    uses_sockets: bool,
    view: Option<&super::view_options::ViewRun>,
) -> Result<(Option<super::StartedController>, bool), String> {
    let Some(prog) = tasks
        .iter()
        .find(|t| t.config.motion)
        .and_then(|t| t.program.clone())
    else {
        return Ok((None, false));
    };
    let devices = egm_options::device_use(&prog);
    egm_options::check_devices(&args.egm, &devices)?
        .iter()
        .for_each(|w| eprintln!("warning: {w}"));
    let uses_egm = egm_options::uses_egm(&prog, sources);
    let c = super::start_controller(
        args,
        sources,
        config,
        signals,
        uses_egm.then_some(&devices),
        uses_sockets,
        view,
    )?;
    let written = c.2;
    Ok((Some(c), written))
}

/// The scheduler's view of the running tasks and of the idle ones (with their numbers).
pub(crate) fn task_specs(
    tasks: &[crate::program::system::TaskProgram],
    idle: &[crate::config::sys::TaskConfig],
    config: &crate::config::Config,
) -> (Vec<TaskSpec>, Vec<TaskSpec>) {
    let specs = tasks
        .iter()
        .map(|t| TaskSpec {
            config: t.config.clone(),
            number: t.number as i32,
        })
        .collect();
    let idle_specs = idle
        .iter()
        .map(|c| TaskSpec {
            config: c.clone(),
            number: config
                .sys
                .tasks
                .iter()
                .position(|t| t.name == c.name)
                .map_or(0, |i| i as i32 + 1),
        })
        .collect();
    (specs, idle_specs)
}

/// The host of a task that does not move the robot: signals, system data, output.
pub(crate) fn plain_host(
    signals: &Arc<crate::signals::SignalTable>,
    services: crate::system::Services,
    sink: impl FnMut(&crate::interp::Output) + Send + 'static,
) -> Box<dyn Host + Send> {
    Box::new(
        VirtualHost::new()
            .with_signals(Arc::clone(signals))
            .with_system(services)
            .with_sink(sink),
    )
}

/// Load and check the system of `args` (diagnostics printed, what is not supported refused,
/// idle tasks noted), and read the operator's answers. `Err`: the exit code.
pub(crate) fn load_checked(
    args: &RunArgs,
) -> Result<(LoadedSystem, crate::interp::operator::Operator), ExitCode> {
    let loaded = load_system(&args.files, args.config.as_deref());
    render::diagnostics(&loaded.diags, &loaded.sources);
    if !loaded.ok() {
        return Err(ExitCode::from(2));
    }
    if let Some(msg) = refuse(args, &loaded) {
        eprintln!("error: {msg}");
        return Err(ExitCode::from(2));
    }
    for idle in &loaded.idle {
        eprintln!("note: task {} has no modules; it does not run", idle.name);
    }
    match answers::read(args.answers.as_deref()) {
        Ok(file) => Ok((loaded, answers::operator(file.as_ref(), None))),
        Err(msg) => {
            eprintln!("error: {msg}");
            Err(ExitCode::from(2))
        }
    }
}

/// Run the system (see the module docs).
pub fn run(args: RunArgs, interrupted: Arc<AtomicBool>) -> ExitCode {
    let (loaded, operator) = match load_checked(&args) {
        Ok(l) => l,
        Err(code) => return code,
    };
    let uses_sockets = tasks_use_sockets(&loaded);
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
    if let Err(msg) = super::check_paths(&args) {
        eprintln!("error: {msg}");
        return ExitCode::from(2);
    }
    let stored = match args.pers.as_deref().map(super::read_pers).transpose() {
        Ok(s) => s.flatten(),
        Err(msg) => {
            eprintln!("error: {msg}");
            return ExitCode::from(2);
        }
    };
    // Each task's persistents when its program has ended (task index, values).
    let pers_out: Arc<TaskPers> = Arc::default();
    let view = match super::start_view(
        &args,
        tasks.iter().filter_map(|t| t.program.as_deref()),
        &sources,
    ) {
        Ok(v) => v,
        Err(msg) => {
            eprintln!("error: {msg}");
            return ExitCode::from(2);
        }
    };
    let labels = tasks.len() > 1;
    let home = args.home.clone().or(home);
    let storage = Arc::new(MassStorage::new(home));
    let system = super::system_services(&args, &config, &sources);
    let motion = tasks.iter().position(|t| t.config.motion);
    let (mut controller, egm_log_written) = match start_motion_controller(
        &args,
        &tasks,
        &sources,
        &config,
        &signals,
        uses_sockets,
        view.as_ref(),
    ) {
        Ok(c) => c,
        Err(msg) => {
            eprintln!("error: {msg}");
            return ExitCode::from(2);
        }
    };
    // Every task keeps the motion thread's clock: real time when it runs in real time
    // (--realtime, an external EGM sensor, sockets without --lockstep), else virtual.
    let realtime = match &controller {
        Some((ctl, ..)) => ctl.is_realtime(),
        None => args.realtime || (uses_sockets && !args.egm.lockstep),
    };
    if realtime && controller.is_none() && uses_sockets {
        progress_line::clear();
        if let Some(note) = socket_clock::note(args.realtime, args.egm.lockstep) {
            eprintln!("{note}");
        }
    }
    let halt = Arc::new(AtomicBool::new(false));
    let (specs, idle_specs) = task_specs(&tasks, &idle, &config);
    let sched = Scheduler::new(
        specs,
        idle_specs,
        Arc::clone(&halt),
        Some(Arc::clone(&interrupted)),
    );
    if realtime {
        // The scheduler's clock starts with the motion thread's (within a few milliseconds).
        sched.use_real_time(Arc::new(crate::controller::MonotonicClock::new()));
    }
    if let Some((ctl, ..)) = controller.as_mut() {
        sched.use_robot(ctl.state().setpoint.joints, ctl.position_cell());
    }
    let outputs = super::system_outputs(&config, &signals);
    // The tasks still running, for the system outputs (a task leaves when its body ends).
    let running = std::sync::Mutex::new(
        tasks
            .iter()
            .filter(|t| t.program.is_some())
            .map(|t| t.config.name.clone())
            .collect::<Vec<_>>(),
    );
    let (running, outputs) = (&running, &outputs);
    let show_running = move |error: bool| {
        if let (Some(o), Ok(r)) = (outputs, running.lock()) {
            o.show(&super::run_output_state(r.clone(), error));
        }
    };
    show_running(false);
    let session = view.as_ref().map(super::view_options::ViewRun::session);
    let store = SharedPers::new();
    let mut operator = Some(operator);
    let mut bodies: Vec<Box<dyn FnOnce() -> TaskEnd + Send + '_>> = Vec::new();
    for (i, task) in tasks.iter().enumerate() {
        let Some(prog) = task.program.clone() else {
            continue;
        };
        let mut services = system.clone();
        services.info.task = task.config.name.clone();
        let inner: Box<dyn Host + Send> = match (Some(i) == motion, controller.take()) {
            (true, Some((ctl, egm, _, outside))) => Box::new(
                ControllerHost::new(ctl)
                    .with_egm(egm)
                    .with_signals(Arc::clone(&signals))
                    .with_system(services)
                    .with_max_time(args.max_time)
                    .with_outside_inputs(outside)
                    .with_stop_request(Arc::clone(&halt))
                    .with_lines(Arc::clone(&sources))
                    .with_sink(teed(session.clone())),
            ),
            (_, ctl) => {
                controller = ctl;
                plain_host(&signals, services, teed(session.clone()))
            }
        };
        // The view draws the motion task's work objects.
        let frames = session.clone().filter(|_| Some(i) == motion);
        let host = TaskedHost::new(
            Arc::clone(&sched),
            bodies.len(),
            inner,
            labels,
            Some(args.max_time),
        );
        // `Load`/`UnLoad` in this task rebuild this task's program.
        let loader = crate::program::runtime_loader::RuntimeLoader::new(&prog, &sources, &signals);
        let registry = registry.clone();
        let storage = Arc::clone(&storage);
        let store = Arc::clone(&store);
        let halt = Arc::clone(&halt);
        let interrupted = Arc::clone(&interrupted);
        let sources = Arc::clone(&sources);
        let sched = Arc::clone(&sched);
        let entry = task.config.entry.clone();
        let name = task.config.name.clone();
        let normal = task.config.kind == crate::config::sys::TaskType::Normal;
        let cycles = if normal {
            args.cycles
        } else {
            super::Cycles::ONCE
        };
        let operator = if Some(i) == motion || motion.is_none() && i == 0 {
            operator.take()
        } else {
            None
        };
        let max_steps = args.max_steps;
        let announce = args.trace.is_some() || args.plot.is_some() || args.view.wanted();
        let pers_in = stored.as_ref().map(|s| s.entries.clone());
        let pers_out = Arc::clone(&pers_out);
        let first_task = bodies.is_empty();
        bodies.push(Box::new(move || {
            let mut it = Interp::new(prog, &registry, Box::new(host));
            it.set_module_loader(Box::new(loader));
            it.set_mass_storage(storage);
            it.set_budget(max_steps);
            it.set_stop_request(Arc::clone(&halt));
            if let Some(op) = operator {
                it.set_operator(op);
            }
            it.set_stack_budget(6 << 20);
            let init = it.init();
            // The stored values of the shared persistents, before the task joins the others
            // (each task loads the same values; the warnings are printed once).
            if init.is_ok()
                && let Some(entries) = &pers_in
            {
                let (_, warnings) = it.load_persistents(entries);
                if first_task {
                    for w in warnings {
                        eprintln!("warning: {w}");
                    }
                }
            }
            if init.is_ok()
                && let Some(v) = &frames
            {
                v.set_frames_from(&it.persistents());
            }
            let end = match init {
                Err(e) => {
                    report_error(&name, &e, &sources);
                    sched.halt_all(format!("task {name} failed"));
                    TaskEnd {
                        code: ExitCode::from(1),
                        drain: false,
                        egm: None,
                    }
                }
                Ok(()) => {
                    it.set_task_link(store, DEFAULT_SLICE);
                    run_task(
                        &mut it,
                        &Which {
                            name: &name,
                            entry: &entry,
                            cycles,
                            labels,
                            normal,
                        },
                        &sources,
                        &sched,
                        &interrupted,
                    )
                }
            };
            let end = finish_task(&mut it, end, announce, &sched);
            if let Ok(mut out) = pers_out.lock() {
                out.push((i, it.persistents()));
            }
            if let Ok(mut r) = running.lock() {
                r.retain(|t| *t != name);
            }
            show_running(false);
            end
        }));
    }
    let ends = run_tasks(&sched, bodies);
    let drained = ends.iter().flatten().all(|e| e.drain);
    let mut code = exit_code(
        ends.into_iter().map(|e| e.map(|e| (e.code, e.egm))),
        &args,
        egm_log_written,
    );
    if let Some(path) = &args.pers {
        let values = shared_persistents(&pers_out, &store);
        let original = stored.as_ref().map(|p| p.text.as_str());
        let text = pers::write(original, &values);
        if let Err(e) = crate::cli::files::replace(path, &text) {
            eprintln!(
                "error: cannot write {}: {e} (the file was left as it was)",
                path.display()
            );
            return ExitCode::from(2);
        }
    }
    let was_interrupted = interrupted.load(Ordering::Relaxed);
    show_running(code != ExitCode::SUCCESS);
    if let Some(v) = view {
        let ended = if was_interrupted {
            "program stopped by Ctrl-C"
        } else {
            super::view_options::ended_text(&code, drained)
        };
        if let Err(msg) = v.finish(ended) {
            eprintln!("error: {msg}");
            code = ExitCode::from(2);
        }
    }
    if was_interrupted {
        return ExitCode::from(interrupt::EXIT_INTERRUPTED);
    }
    code
}

/// Each task's persistents when its program has ended: (task index, values).
type TaskPers = std::sync::Mutex<Vec<(usize, Vec<pers::PersValue>)>>;

/// The persistents of a system's run for `--pers`: every task's, in task order, one entry
/// per name, each with the value the tasks share at the end (a task's own copy may be older
/// than the last write of another task).
fn shared_persistents(out: &TaskPers, store: &SharedPers) -> Vec<pers::PersValue> {
    let mut per_task = out.lock().map(|v| v.clone()).unwrap_or_default();
    per_task.sort_by_key(|(i, _)| *i);
    let mut values: Vec<pers::PersValue> = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for (_, list) in per_task {
        for mut v in list {
            if !seen.insert(v.name.to_ascii_uppercase()) {
                continue;
            }
            if let Some(shared) = store.get(&v.name) {
                v.value = shared;
            }
            values.push(v);
        }
    }
    values
}

/// A task's output sink: printed, and shown in the view when there is one.
fn teed(
    view: Option<crate::output::view::ViewSession>,
) -> impl FnMut(&crate::interp::Output) + Send + 'static {
    move |o| {
        if let Some(v) = &view {
            v.output(o);
        }
        print_output(o);
    }
}

/// The exit code of a system's run from its tasks' (code, EGM side) — `None` for a task
/// whose thread failed — after finishing the EGM side (`--egm-log`).
pub(crate) fn exit_code(
    ends: impl Iterator<
        Item = Option<(
            ExitCode,
            Option<crate::controller::egm_controller::EgmController>,
        )>,
    >,
    args: &RunArgs,
    egm_log_written: bool,
) -> ExitCode {
    let mut code = ExitCode::SUCCESS;
    for end in ends {
        match end {
            Some((c, egm)) => {
                if c != ExitCode::SUCCESS {
                    code = c;
                }
                if let Some(egm) = egm
                    && let Err(msg) = egm_options::finish(egm, &args.egm, egm_log_written)
                {
                    eprintln!("error: {msg}");
                    code = ExitCode::from(2);
                }
            }
            None => {
                eprintln!("error: a task's thread failed");
                code = ExitCode::from(1);
            }
        }
    }
    code
}

fn tasks_use_sockets(loaded: &LoadedSystem) -> bool {
    loaded
        .tasks
        .iter()
        .filter_map(|t| t.program.as_deref())
        .any(socket_clock::uses_sockets)
}

/// What a run of several tasks does not support yet (checked before anything runs).
fn refuse(args: &RunArgs, loaded: &LoadedSystem) -> Option<String> {
    if args.pers.is_some() {
        // The file holds one value per name: the task-global persistents, which every task
        // shares, fit; a TASK PERS has one value in each task.
        for t in &loaded.tasks {
            let Some(prog) = &t.program else { continue };
            if let Some(g) = prog.globals.iter().find(|g| {
                g.task
                    && g.storage == crate::ir::Storage::Pers
                    && matches!(g.origin, crate::ir::GlobalOrigin::Module(m)
                        if prog.modules.get(m.0 as usize).is_some_and(|m| !m.stdlib))
            }) {
                return Some(format!(
                    "--pers with several tasks keeps the persistents the tasks share; `{}` of task {} is a TASK PERS (a value per task), which a --pers file cannot hold yet",
                    g.name, t.config.name
                ));
            }
        }
    }
    if args.entry != "main" {
        return Some(
            "--entry: with several tasks each task starts at its -Entry of SYS.cfg (main by default)"
                .into(),
        );
    }
    for t in &loaded.tasks {
        let Some(prog) = &t.program else { continue };
        if let Err(e) = Interp::entry_point(prog, &t.config.entry) {
            return Some(format!(
                "task {} (files {}): {}",
                t.config.name,
                t.files
                    .iter()
                    .map(|f: &PathBuf| f.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", "),
                e.message
            ));
        }
    }
    None
}

fn report_error(task: &str, e: &crate::interp::RuntimeError, sources: &SourceMap) {
    let _ = std::io::stdout().flush();
    progress_line::clear();
    eprintln!("error in task {task}:");
    render::runtime_error(e, sources);
}

/// Which task runs where.
#[derive(Clone, Copy)]
struct Which<'a> {
    name: &'a str,
    entry: &'a str,
    /// How many times the entry routine runs.
    cycles: super::Cycles,
    /// Several tasks run: messages name the task.
    labels: bool,
    /// A NORMAL task (its EXIT or Stop stops the other tasks).
    normal: bool,
}

/// Run a task's entry routine `cycles` times.
fn run_task(
    it: &mut Interp,
    task: &Which<'_>,
    sources: &SourceMap,
    sched: &Scheduler,
    interrupted: &AtomicBool,
) -> TaskEnd {
    let Which {
        name,
        entry,
        cycles,
        labels,
        normal,
    } = *task;
    let who = if labels {
        format!("task {name}: ")
    } else {
        String::new()
    };
    let mut done = 0u32;
    while cycles.more(done) {
        done = done.saturating_add(1);
        match it.run(entry) {
            Ok(Outcome::Completed | Outcome::ExitCycle) => {}
            Ok(Outcome::Exited) => {
                eprintln!("{who}program ended by EXIT");
                if normal {
                    // The NORMAL tasks start and stop together.
                    sched.halt_all(format!("EXIT in task {name}"));
                }
                return TaskEnd {
                    code: ExitCode::SUCCESS,
                    drain: true,
                    egm: None,
                };
            }
            Ok(Outcome::Stopped) => {
                progress_line::clear();
                let why = if sched.halted_because().is_some() {
                    "stopped with the other tasks"
                } else if interrupted.load(Ordering::Relaxed) {
                    "stopped (interrupted by Ctrl-C)"
                } else if sched.halt_flag().load(Ordering::Relaxed) {
                    "stopped at the end of the run"
                } else {
                    if normal {
                        sched.halt_all(format!("Stop in task {name}"));
                    }
                    "stopped (Stop)"
                };
                eprintln!("{who}program {why}");
                return TaskEnd {
                    code: ExitCode::SUCCESS,
                    drain: false,
                    egm: None,
                };
            }
            Err(e) => {
                report_error(name, &e, sources);
                sched.halt_all(format!("task {name} failed"));
                return TaskEnd {
                    code: ExitCode::from(1),
                    drain: false,
                    egm: None,
                };
            }
        }
    }
    TaskEnd {
        code: ExitCode::SUCCESS,
        drain: true,
        egm: None,
    }
}

/// After a task's program: an EGM run still active ends, the motion task's controller
/// finishes its moves (when the program ended normally) and prints its summary.
fn finish_task(it: &mut Interp, mut end: TaskEnd, announce: bool, sched: &Scheduler) -> TaskEnd {
    if let Some(egm_host) = it.host_mut().egm()
        && let Err(e) = egm_host.egm_program_stopped()
    {
        progress_line::clear();
        eprintln!("error: {e}");
        end.code = ExitCode::from(1);
    }
    if let Some(w) = answers::unused_warning(it.operator())
        && end.code == ExitCode::SUCCESS
    {
        eprintln!("warning: {w}");
    }
    if let Some(host) = it
        .host_mut()
        .as_any_mut()
        .and_then(|a| a.downcast_mut::<ControllerHost>())
    {
        let moved = host.moves_submitted() > 0;
        end.egm = host.take_egm();
        match host.finish(end.drain) {
            Ok(summary) => {
                // The tasks still running read the robot where it came to rest.
                sched.robot_rests_at(summary.final_joints);
                if moved || announce {
                    print_summary(&summary);
                }
            }
            Err(e) => {
                eprintln!("error: {e}");
                end.code = ExitCode::from(2);
            }
        }
    }
    end
}
