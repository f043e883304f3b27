//! `rapidvc serve FILE…`: boot a controller that stays up. The program is loaded and checked
//! as for `run`, the controller runs in real time (the motion thread), and the program is
//! started, stopped, reset and inspected over Robot Web Services 1.0 (plain HTTP, as on an
//! IRC5) until Ctrl-C (or SIGTERM): then the robot brakes, every file is finished and the
//! process exits with 0.
//!
//! The first line on stdout says where RWS listens (`rapidvc serve: Robot Web Services on
//! http://127.0.0.1:8080`); TP output follows on stdout, the event log on stderr.

mod system;

use std::io::Write;
use std::net::SocketAddr;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::Ordering;

use super::run::{self, RunArgs, egm_options};
use super::{answers, interrupt, num, render};
use crate::controller::ControllerHost;
use crate::controller::service::{self, SystemInfo};
use crate::controller::system_state::program_side::{ProgramSide, run_program};
use crate::controller::system_state::{ServeInfo, SystemState, spawn_service_thread};
use crate::events::{EventKind, Severity};
use crate::interp::{Interp, Output, pers};
use crate::mass_storage::MassStorage;
use crate::program;
use crate::services::rws::{self, RwsOptions, RwsServer};

/// The motion task of a controller booted from plain files.
pub const MOTION_TASK: &str = "T_ROB1";

/// Arguments of `rapidvc serve`.
#[derive(Debug, clap::Args)]
pub struct ServeArgs {
    /// Where Robot Web Services listens (plain HTTP). Default: 127.0.0.1:80 when the
    /// process may bind it, else 127.0.0.1:8080. Give 127.0.0.1:0 for any free port (the
    /// address is printed).
    #[arg(long, value_name = "ADDR")]
    pub rws: Option<SocketAddr>,
    /// Most RWS sessions open at once (1 to 10000); one more closes the least recently used.
    #[arg(long, value_name = "N", default_value_t = 70, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub rws_sessions: u32,
    /// Most RWS subscriptions open at once, all sessions together (1 to 1000).
    #[arg(long, value_name = "N", default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub rws_subscriptions: u32,
    /// A subscription whose WebSocket is not connected this many seconds is removed (0.1 to
    /// 3600).
    #[arg(long, value_name = "S", default_value_t = 60.0, value_parser = unclaimed_secs)]
    pub rws_unclaimed: f64,
    /// The program and the controller's options, as for `rapidvc run` (`--cycles` is
    /// refused: the cycle mode comes with each start).
    #[command(flatten)]
    pub run: RunArgs,
}

/// Boot the controller and serve until Ctrl-C.
pub fn run(mut args: ServeArgs) -> ExitCode {
    let shutdown = match interrupt::install() {
        Ok(flag) => flag,
        Err(e) => {
            eprintln!("error: cannot install the Ctrl-C handler: {e}");
            return ExitCode::from(2);
        }
    };
    let _ = signal_hook::flag::register(signal_hook::consts::SIGTERM, Arc::clone(&shutdown));
    let a = &mut args.run;
    if a.cycles != run::Cycles::ONCE {
        eprintln!("error: --cycles: `serve` runs the program once or forever as each start says");
        return ExitCode::from(2);
    }
    if a.egm.lockstep {
        eprintln!("error: --lockstep keeps virtual time; `serve` runs in real time");
        return ExitCode::from(2);
    }
    a.realtime = true;
    if a.date.is_none() {
        a.date = num::start_date("now").ok();
    }
    let args = args;
    let a = &args.run;
    if run::tasks::wants_system(a) {
        return system::serve_system(&args, &shutdown);
    }
    let loaded = program::load(&a.files, a.config.as_deref());
    render::diagnostics(&loaded.diags, &loaded.sources);
    let Some(prog) = loaded.program.clone() else {
        return ExitCode::from(2);
    };
    let prepared = match run::before_the_run(a, &prog) {
        Ok(p) => p,
        Err(msg) => {
            eprintln!("error: {msg}");
            return ExitCode::from(2);
        }
    };
    let operator = match answers::read(a.answers.as_deref()) {
        Ok(file) => answers::operator(file.as_ref(), None),
        Err(msg) => {
            eprintln!("error: {msg}");
            return ExitCode::from(2);
        }
    };
    let system = run::system_services(a, &loaded.config, &loaded.sources);
    let (storage, roots, listener) = match boot(&args, a.home.clone()) {
        Ok(b) => b,
        Err(msg) => {
            eprintln!("error: {msg}");
            return ExitCode::from(2);
        }
    };
    let info = serve_info(&system, roots, &loaded.signals);
    let calendar = system.calendar;
    let sources = Arc::new(loaded.sources);
    let uses_egm = egm_options::uses_egm(&prog, &sources);
    let uses_sockets = run::socket_clock::uses_sockets(&prog);
    let started = run::start_controller(
        a,
        &sources,
        &loaded.config,
        &loaded.signals,
        uses_egm.then_some(&prepared.devices),
        uses_sockets,
        None,
    );
    let (ctl, egm_controller, egm_log_written, _) = match started {
        Ok(c) => c,
        Err(msg) => {
            eprintln!("error: {msg}");
            return ExitCode::from(2);
        }
    };
    let (handle, endpoint) = service::channel();
    let state = Arc::new(SystemState::new(
        MOTION_TASK,
        endpoint.publisher(),
        Arc::clone(&shutdown),
        calendar,
    ));
    if let Some(o) = run::system_outputs(&loaded.config, &loaded.signals) {
        state.attach_outputs(Arc::new(o));
    }
    let (services, forwarded) = match start_services(endpoint, &state, info) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let server = match start_rws(&args, listener, handle) {
        Ok(s) => s,
        Err(msg) => {
            eprintln!("error: {msg}");
            shutdown.store(true, Ordering::Relaxed);
            let _ = services.join();
            return ExitCode::from(2);
        }
    };
    started_line(&server);
    // One task booted from files: no RAPID message queue to send to.
    state.set_task_queues(Box::new(|target, _| {
        let task = target
            .get(..4)
            .filter(|p| p.eq_ignore_ascii_case("RMQ_"))
            .and_then(|_| target.get(4..))
            .unwrap_or(target);
        task.eq_ignore_ascii_case(MOTION_TASK).then(|| {
            Err(format!(
                "task {MOTION_TASK} booted from plain files has no RAPID message queue: boot a \
                 system (a backup folder, SYS.cfg, or `{MOTION_TASK}=file.mod`) to use RMQ"
            ))
        })
    }));
    let log_state = Arc::clone(&state);
    let host = ControllerHost::new(ctl)
        .with_egm(egm_controller)
        .with_signals(Arc::clone(&loaded.signals))
        .with_system(system)
        .with_max_time(a.max_time)
        .with_lines(Arc::clone(&sources))
        .with_panel(Arc::clone(&state.limits))
        .with_sink(move |o| {
            run::print_output(o);
            log_output(&log_state, o);
        });
    let mut it = Interp::new(prog, &loaded.registry, Box::new(host));
    it.set_mass_storage(storage);
    it.set_budget(a.max_steps);
    it.set_operator(operator);
    it.set_stack_budget(6 << 20);
    let mut code = ExitCode::SUCCESS;
    match it.init() {
        Err(e) => {
            render::runtime_error(&e, &sources);
            state.log(EventKind::ProgramError, e.message.clone());
            code = ExitCode::from(1);
        }
        Ok(()) => {
            if let Some(stored) = &prepared.pers {
                let (_, warnings) = it.load_persistents(&stored.entries);
                for w in warnings {
                    eprintln!("warning: {}: {w}", stored.path.display());
                }
            }
            let side = ProgramSide::new(Arc::clone(&state), forwarded, MOTION_TASK);
            run_program(&mut it, &a.entry, side);
        }
    }
    // Shut down: no more requests, the robot brakes, files are finished.
    shutdown.store(true, Ordering::Relaxed);
    server.stop();
    let _ = services.join();
    if let Some((egm_controller, finished)) = finish_motion(&mut it) {
        if !finished {
            code = ExitCode::from(2);
        }
        if let Some(e) = egm_controller
            && let Err(msg) = egm_options::finish(e, &a.egm, egm_log_written)
        {
            eprintln!("error: {msg}");
            code = ExitCode::from(2);
        }
    }
    if let Some(path) = &a.pers {
        let original = prepared.pers.as_ref().map(|p| p.text.as_str());
        let text = pers::write(original, &it.persistents());
        if let Err(e) = super::files::replace(path, &text) {
            eprintln!(
                "error: cannot write {}: {e} (the file was left as it was)",
                path.display()
            );
            code = ExitCode::from(2);
        }
    }
    eprintln!("rapidvc serve: stopped");
    code
}

/// The mass storage, its roots (`HOME`, `TEMP`, `RAMDISK` on the host) and the RWS listener.
type Booted = (
    Arc<MassStorage>,
    Vec<(String, std::path::PathBuf)>,
    std::net::TcpListener,
);

/// The mass storage (HOME at `home`) with its roots, and the RWS listener.
fn boot(args: &ServeArgs, home: Option<std::path::PathBuf>) -> Result<Booted, String> {
    let listener = rws::bind(args.rws).map_err(|e| format!("--rws: cannot listen: {e}"))?;
    let storage = Arc::new(MassStorage::new(home));
    let (roots, note) = storage
        .roots()
        .map_err(|e| format!("cannot make the mass storage: {e}"))?;
    if let Some(n) = note {
        eprintln!("{n}");
    }
    Ok((storage, roots, listener))
}

/// Start Robot Web Services on `listener` with the options of `args`.
fn start_rws(
    args: &ServeArgs,
    listener: std::net::TcpListener,
    handle: crate::controller::service::ServiceHandle,
) -> Result<RwsServer, String> {
    let opts = RwsOptions {
        max_sessions: args.rws_sessions as usize,
        max_subscriptions: args.rws_subscriptions as usize,
        subscription_unclaimed: std::time::Duration::from_secs_f64(args.rws_unclaimed),
        ..RwsOptions::default()
    };
    let max = opts.max_connections;
    RwsServer::start(listener, rws::router(handle, opts), max)
        .map_err(|e| format!("cannot start Robot Web Services: {e}"))
}

/// What the controller says about itself over RWS.
fn serve_info(
    system: &crate::system::Services,
    roots: Vec<(String, std::path::PathBuf)>,
    signals: &Arc<crate::signals::SignalTable>,
) -> ServeInfo {
    ServeInfo {
        system: SystemInfo {
            name: system.info.system_name.clone(),
            robotware_version: crate::system::info::ROBOTWARE_VERSION
                .split('.')
                .take(3)
                .collect::<Vec<_>>()
                .join("."),
            options: vec![
                "616-1 PC Interface".into(),
                "689-1 Externally Guided Motion (EGM)".into(),
            ],
            serial: system.info.serial.clone(),
        },
        // What the configuration files lack is served as a single-robot backup has it.
        cfg: crate::system::backup_defaults::completed(&system.cfg, &system.info, MOTION_TASK),
        roots,
        signals: Arc::clone(signals),
    }
}

/// A task's program has ended at shutdown: EGM hears that the program stopped, the robot
/// brakes and the motion controller finishes (its summary printed). `None` for a task
/// without a motion controller; else its EGM controller and whether finishing went well.
pub(super) fn finish_motion(
    it: &mut Interp,
) -> Option<(
    Option<crate::controller::egm_controller::EgmController>,
    bool,
)> {
    if let Some(egm_host) = it.host_mut().egm()
        && let Err(e) = egm_host.egm_program_stopped()
    {
        eprintln!("error: {e}");
    }
    let host = it
        .host_mut()
        .as_any_mut()
        .and_then(|x| x.downcast_mut::<ControllerHost>())?;
    let egm = host.take_egm();
    let finished = match host.finish(false) {
        Ok(summary) => {
            run::print_summary(&summary);
            true
        }
        Err(e) => {
            eprintln!("error: {e}");
            false
        }
    };
    Some((egm, finished))
}

/// The service thread answering requests from the controller's state; the requests it
/// forwards to the program side arrive on the receiver.
pub(super) fn start_services(
    endpoint: service::ServiceEndpoint,
    state: &Arc<SystemState>,
    info: ServeInfo,
) -> Result<
    (
        std::thread::JoinHandle<()>,
        std::sync::mpsc::Receiver<service::Request>,
    ),
    ExitCode,
> {
    let (forward, forwarded) = std::sync::mpsc::channel();
    match spawn_service_thread(endpoint, Arc::clone(state), info, forward) {
        Ok(t) => Ok((t, forwarded)),
        Err(e) => {
            eprintln!("error: cannot start the service thread: {e}");
            Err(ExitCode::from(2))
        }
    }
}

/// The first line on stdout: where RWS listens.
fn started_line(server: &RwsServer) {
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "rapidvc serve: Robot Web Services on {} (RWS 1.0, plain HTTP; user \"Default User\", password \"robotics\")",
        server.url()
    );
    let _ = out.flush();
}

/// `--rws-unclaimed`: seconds, 0.1 to 3600.
fn unclaimed_secs(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.1..=3600.0).contains(&v) => Ok(v),
        _ => Err(format!("`{s}` is not a number of seconds from 0.1 to 3600")),
    }
}

/// Every event the program side prints goes into the event log too.
fn log_output(state: &SystemState, o: &Output) {
    match o {
        Output::TpWrite(_) | Output::TpErase => {}
        Output::ErrWrite {
            warning,
            header,
            reason,
        } => {
            let kind = if *warning {
                EventKind::ErrWriteWarning
            } else {
                EventKind::ErrWriteError
            };
            state.log_entry(kind.number(), kind.severity(), header, reason.join(" "));
        }
        Output::Event(text) => {
            // "50024 Corner path failure: …": the event's own number and title.
            let numbered = text.split_once(' ').and_then(|(n, rest)| {
                let code = n.parse::<u32>().ok()?;
                let (title, desc) = rest.split_once(": ").unwrap_or((rest, ""));
                let kind = EventKind::ALL.iter().find(|k| k.number() == code);
                Some((
                    code,
                    kind.map_or(Severity::Warning, |k| k.severity()),
                    title.to_string(),
                    desc.to_string(),
                ))
            });
            match numbered {
                Some((code, sev, title, desc)) => state.log_entry(code, sev, &title, desc),
                None => state.log(EventKind::ProgramEvent, text.clone()),
            }
        }
    }
}
