//! `rapidvc run FILE…`: load and check the program, start the virtual controller (robot,
//! motion core, trace and plot recorders) and run the entry routine on it. TP output goes to
//! stdout (one line per `TPWrite`); diagnostics, events and the end-of-run summary to stderr.
//! Exit codes: 0 when the program ends (also by EXIT or Stop), 1 on an unhandled run-time
//! error, 2 when the program cannot be loaded or checked, or the run's files cannot be
//! written.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::str::FromStr;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use super::files::{self, Role};
use super::robots::RobotArg;
use super::{answers, interrupt, num, progress_line, render};
use crate::controller::signal_script::SignalScript;
use crate::program;

pub mod egm_options;
pub mod socket_clock;
pub mod tasks;
pub mod view_options;
use crate::controller::egm_controller::EgmController;
use crate::controller::{
    ClockMode, ControllerConfig, ControllerError, ControllerHandle, ControllerHost, CycleHook,
    RealtimeConfig, RunSummary, TickSink,
};
use crate::interp::{Interp, Outcome, Output, pers};
use crate::mass_storage::MassStorage;
use crate::motion::CoreConfig;
use crate::output::{Feed, PlotRecorder, TraceColumns, TraceWriter};
use crate::robot::{JointsDeg, Robot};
use crate::source::SourceMap;

/// Axis values of the robot when a run starts, unless `--start` says otherwise: the
/// calibration position of ABB robots, all axes at 0°.
pub const DEFAULT_START: JointsDeg = [0.0; 6];

/// Arguments of `rapidvc run`.
#[derive(Debug, clap::Args)]
pub struct RunArgs {
    /// RAPID files or directories (all modules of one task).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// The procedure to start.
    #[arg(long, default_value = "main")]
    pub entry: String,
    /// Configuration directory (EIO.cfg …); default: the directory of the first file.
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// The controller's HOME: directory (an existing directory; RAPID's file instructions
    /// cannot leave it). Default: a fresh directory under the system's temporary directory,
    /// made and printed when the program first uses the file system.
    #[arg(long, value_name = "DIR", value_parser = files::home_dir)]
    pub home: Option<PathBuf>,
    /// Persistents file: loaded at start when it exists, written at the end.
    #[arg(long)]
    pub pers: Option<PathBuf>,
    /// Fail a wait that would go beyond this robot time (seconds, more than 0 and at most
    /// 1e9; wall seconds with --realtime).
    #[arg(long, value_name = "S", default_value_t = 86_400.0, value_parser = num::max_time)]
    pub max_time: f64,
    /// Abort after this many executed statements (at least 1).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub max_steps: Option<u64>,
    /// The controller's date and time when the program starts (CDate, CTime, GetTime),
    /// `YYYY-MM-DD HH:MM:SS` (default 2025-01-01 00:00:00), or `now` for the host's local time.
    #[arg(long, value_name = "DATE", value_parser = num::start_date)]
    pub date: Option<crate::system::calendar::Calendar>,
    /// Let SaveCfgData write into the configuration directory (never over the files the run
    /// read its configuration from).
    #[arg(long)]
    pub save_cfg: bool,
    /// Answers to the operator dialogs (TPReadFK, UIMessageBox, …), one per line in order
    /// (default: the terminal when stdin is one, else nobody answers).
    #[arg(long, value_name = "FILE")]
    pub answers: Option<PathBuf>,
    /// Signal changes at given robot times, one per line: `TIME SIGNAL VALUE` (seconds, a
    /// configured signal, its new value; `#` starts a comment line).
    #[arg(long, value_name = "FILE")]
    pub signal_script: Option<PathBuf>,
    /// Run the entry routine this many times (at least 1), or `forever` (continuous mode, as
    /// a controller runs: until Ctrl-C, EXIT, an error, --max-time or --max-steps);
    /// `ExitCycle` ends a cycle early.
    #[arg(long, value_name = "N", default_value = "1", value_parser = parse_cycles)]
    pub cycles: Cycles,
    /// Robot model (see `rapidvc robots`).
    #[arg(long, value_name = "NAME", default_value = "IRB 2600-12/1.85")]
    pub robot: RobotArg,
    /// Axis values at start in degrees, `J1,J2,J3,J4,J5,J6` (default: all 0, the calibration
    /// position).
    #[arg(long, value_name = "J1,…,J6")]
    pub start: Option<StartArg>,
    /// Write one CSV row per motion cycle (time, joints, TCP, speed, instruction, line).
    #[arg(long, value_name = "FILE.csv")]
    pub trace: Option<PathBuf>,
    /// Draw joints, TCP and speed against time, with the move instructions marked.
    #[arg(long, value_name = "FILE.svg|FILE.png")]
    pub plot: Option<PathBuf>,
    /// Run in real time (a motion thread at the fixed period) instead of virtual time.
    #[arg(long)]
    pub realtime: bool,
    /// Motion cycle in milliseconds (0.1 to 100).
    #[arg(long, value_name = "MS", default_value_t = 4.0, value_parser = num::period_ms)]
    pub period: f64,
    /// EGM: devices, message log, lockstep.
    #[command(flatten)]
    pub egm: egm_options::EgmArgs,
    /// 3D view: replay page, live view.
    #[command(flatten)]
    pub view: view_options::ViewArgs,
}

/// `--signal-script FILE`, read and checked against the run's signals.
fn read_signal_script(
    path: Option<&std::path::Path>,
    signals: &crate::signals::SignalTable,
) -> Result<SignalScript, String> {
    let Some(path) = path else {
        return Ok(SignalScript::default());
    };
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read the signal script {}: {e}", path.display()))?;
    SignalScript::parse(&text, signals).map_err(|e| format!("{}: {e}", path.display()))
}

/// The durations the numeric options give a run (the value parsers bound the options, so
/// these conversions cannot overflow).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timing {
    /// The motion cycle (`--period`).
    pub period: Duration,
    /// The longest wait (`--max-time`).
    pub max_wait: Duration,
    /// Lockstep: the longest wait for one sensor reply (`--lockstep-timeout`).
    pub reply_timeout: Duration,
}

impl RunArgs {
    /// The run's durations from its options.
    pub fn timing(&self) -> Timing {
        Timing {
            period: Duration::from_secs_f64(self.period / 1e3),
            max_wait: Duration::from_secs_f64(self.max_time),
            reply_timeout: Duration::from_millis(self.egm.lockstep_timeout),
        }
    }
}

/// `--start J1,J2,J3,J4,J5,J6` (brackets allowed: `[0,0,0,0,30,0]`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StartArg(pub JointsDeg);

impl FromStr for StartArg {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let inner = s.trim().trim_start_matches('[').trim_end_matches(']');
        let parts: Vec<&str> = inner.split(',').map(str::trim).collect();
        if parts.len() != 6 {
            return Err(format!(
                "expected six axis values in degrees, `J1,J2,J3,J4,J5,J6`, not `{s}`"
            ));
        }
        let mut j = [0.0; 6];
        for (slot, p) in j.iter_mut().zip(&parts) {
            *slot = p
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("`{p}` is not an axis value in degrees"))?;
        }
        Ok(StartArg(j))
    }
}

/// Run the program.
pub fn run(args: RunArgs) -> ExitCode {
    // Installed first: a Ctrl-C while loading ends nothing half-written, and one during the
    // run stops the program as a controller would.
    let interrupted = match interrupt::install() {
        Ok(flag) => flag,
        Err(e) => {
            eprintln!("warning: Ctrl-C will end the run without finishing its files: {e}");
            Arc::new(AtomicBool::new(false))
        }
    };
    if tasks::wants_system(&args) {
        return tasks::run(args, interrupted);
    }
    let loaded = program::load(&args.files, args.config.as_deref());
    render::diagnostics(&loaded.diags, &loaded.sources);
    let Some(prog) = loaded.program.clone() else {
        return ExitCode::from(2);
    };
    let prepared = match before_the_run(&args, &prog) {
        Ok(p) => p,
        Err(msg) => {
            eprintln!("error: {msg}");
            return ExitCode::from(2);
        }
    };
    let operator = match answers::read(args.answers.as_deref()) {
        Ok(file) => answers::operator(file.as_ref(), None),
        Err(msg) => {
            eprintln!("error: {msg}");
            return ExitCode::from(2);
        }
    };
    if interrupted.load(Ordering::Relaxed) {
        eprintln!("interrupted before the program started");
        return ExitCode::from(interrupt::EXIT_INTERRUPTED);
    }
    let system = system_services(&args, &loaded.config, &loaded.sources);
    let registry = loaded.registry;
    let signals = loaded.signals;
    let script = match read_signal_script(args.signal_script.as_deref(), &signals) {
        Ok(s) => s,
        Err(msg) => {
            eprintln!("error: {msg}");
            return ExitCode::from(2);
        }
    };
    let sources: Arc<SourceMap> = Arc::new(loaded.sources);
    let uses_egm = egm_options::uses_egm(&prog, &sources);
    let uses_sockets = socket_clock::uses_sockets(&prog);
    let view = match start_view(&args, [&*prog], &sources) {
        Ok(v) => v,
        Err(msg) => {
            eprintln!("error: {msg}");
            return ExitCode::from(2);
        }
    };
    let started = start_controller(
        &args,
        &sources,
        &loaded.config,
        &signals,
        uses_egm.then_some(&prepared.devices),
        uses_sockets,
        view.as_ref(),
    );
    let (ctl, egm_controller, egm_log_written, outside_inputs) = match started {
        Ok(c) => c,
        Err(msg) => {
            eprintln!("error: {msg}");
            return ExitCode::from(2);
        }
    };
    let tee = view.as_ref().map(view_options::ViewRun::session);
    let outputs = system_outputs(&loaded.config, &signals);
    let loader = crate::program::runtime_loader::RuntimeLoader::new(&prog, &sources, &signals);
    let host = ControllerHost::new(ctl)
        .with_egm(egm_controller)
        .with_signals(signals)
        .with_system(system)
        .with_max_time(args.max_time)
        .with_outside_inputs(outside_inputs)
        .with_signal_script(script)
        .with_stop_request(Arc::clone(&interrupted))
        .with_lines(Arc::clone(&sources))
        .with_sink(move |o| {
            if let Some(v) = &tee {
                v.output(o);
            }
            print_output(o);
        });
    let mut it = Interp::new(prog, &registry, Box::new(host));
    it.set_module_loader(Box::new(loader));
    it.set_mass_storage(Arc::new(MassStorage::new(args.home.clone())));
    it.set_budget(args.max_steps);
    it.set_stop_request(Arc::clone(&interrupted));
    it.set_operator(operator);
    // The main thread has 8 MiB of stack; leave 2 MiB of headroom.
    it.set_stack_budget(6 << 20);
    if let Some(o) = &outputs {
        o.show(&run_output_state(
            vec![crate::config::sys::DEFAULT_TASK.to_string()],
            false,
        ));
    }
    let (mut code, drain) = match it.init() {
        Err(e) => {
            render::runtime_error(&e, &sources);
            (ExitCode::from(1), false)
        }
        Ok(()) => {
            if let Some(stored) = &prepared.pers {
                let (_, warnings) = it.load_persistents(&stored.entries);
                for w in warnings {
                    eprintln!("warning: {}: {w}", stored.path.display());
                }
            }
            if let Some(v) = &view {
                v.after_init(&it);
            }
            run_cycles(&args, &mut it, &sources)
        }
    };
    // An EGM run still active ramps out, streams end; a `\NoWaitCond` run's error nobody
    // waited for is reported now.
    if let Some(egm_host) = it.host_mut().egm()
        && let Err(e) = egm_host.egm_program_stopped()
    {
        progress_line::clear();
        eprintln!("error: {e}");
        code = ExitCode::from(1);
    }
    if let Some(o) = &outputs {
        o.show(&run_output_state(Vec::new(), code != ExitCode::SUCCESS));
    }
    if code == ExitCode::SUCCESS
        && let Some(w) = answers::unused_warning(it.operator())
    {
        progress_line::clear();
        eprintln!("warning: {w}");
    }
    let was_interrupted = interrupted.load(Ordering::Relaxed);
    let announce =
        args.trace.is_some() || args.plot.is_some() || args.realtime || args.view.wanted();
    if let Some(host) = it
        .host_mut()
        .as_any_mut()
        .and_then(|a| a.downcast_mut::<ControllerHost>())
    {
        let moved = host.moves_submitted() > 0;
        let egm_controller = host.take_egm();
        match host.finish(drain) {
            Ok(summary) => {
                if moved || announce || was_interrupted {
                    print_summary(&summary);
                }
            }
            Err(e) => {
                eprintln!("error: {e}");
                code = ExitCode::from(2);
            }
        }
        if let Some(e) = egm_controller
            && let Err(msg) = egm_options::finish(e, &args.egm, egm_log_written)
        {
            eprintln!("error: {msg}");
            code = ExitCode::from(2);
        }
    }
    let ended = if was_interrupted {
        "program stopped by Ctrl-C"
    } else {
        view_options::ended_text(&code, drain)
    };
    if let Some(v) = view
        && let Err(msg) = v.finish(ended)
    {
        eprintln!("error: {msg}");
        code = ExitCode::from(2);
    }
    if let Some(path) = &args.pers {
        let original = prepared.pers.as_ref().map(|p| p.text.as_str());
        let text = pers::write(original, &it.persistents());
        if let Err(e) = files::replace(path, &text) {
            eprintln!(
                "error: cannot write {}: {e} (the file was left as it was)",
                path.display()
            );
            return ExitCode::from(2);
        }
    }
    if interrupted.load(Ordering::Relaxed) {
        return ExitCode::from(interrupt::EXIT_INTERRUPTED);
    }
    code
}

/// The controller's system side of this run: the calendar (`--date`), the robot (`--robot`),
/// the configuration database of the configuration directory (which SaveCfgData may write
/// into with `--save-cfg`).
pub(super) fn system_services(
    args: &RunArgs,
    config: &crate::config::Config,
    sources: &SourceMap,
) -> crate::system::Services {
    let mut cfg = crate::system::cfg_data::CfgData::from_files(&config.files, sources);
    if args.save_cfg
        && let Some(dir) = program::config_dir(args.config.as_deref(), &args.files)
    {
        cfg.allow_saving_in(dir);
    }
    crate::system::Services {
        calendar: args.date.unwrap_or_default(),
        info: crate::system::info::SystemInfo::default().with_robot(args.robot.0),
        cfg,
        texts: Default::default(),
        sockets: Default::default(),
    }
}

/// What is checked and read before anything runs.
pub(super) struct Prepared {
    /// The `--pers` file as it was, when it exists.
    pub(super) pers: Option<StoredPers>,
    /// The EGM devices the program sets up.
    pub(super) devices: egm_options::DeviceUse,
}

/// A `--pers` file read at the start.
pub(super) struct StoredPers {
    pub(super) path: PathBuf,
    /// The whole text (rewritten in place at the end).
    pub(super) text: String,
    pub(super) entries: Vec<pers::PersEntry>,
}

/// Everything a run can refuse before it starts (exit 2, nothing ran): the entry procedure,
/// the output paths, the `--pers` file, the `--device` names.
pub(super) fn before_the_run(
    args: &RunArgs,
    prog: &crate::ir::Program,
) -> Result<Prepared, String> {
    if let Err(e) = Interp::entry_point(prog, &args.entry) {
        return Err(format!(
            "--entry {:?}: {}{}",
            args.entry,
            e.message,
            entry_candidates(prog)
        ));
    }
    check_paths(args)?;
    let pers = match &args.pers {
        Some(path) => read_pers(path)?,
        None => None,
    };
    let devices = egm_options::device_use(prog);
    for w in egm_options::check_devices(&args.egm, &devices)? {
        eprintln!("warning: {w}");
    }
    Ok(Prepared { pers, devices })
}

/// " (procedures to start: main, calibrate)": the program's own procedures without required
/// parameters.
fn entry_candidates(prog: &crate::ir::Program) -> String {
    let names: Vec<&str> = prog
        .routines
        .iter()
        .filter(|r| {
            r.kind == crate::ir::RoutineKind::Proc
                && !r.local
                && r.params.iter().all(|p| p.optional)
                && prog
                    .modules
                    .get(r.module.0 as usize)
                    .is_some_and(|m| !m.stdlib)
        })
        .map(|r| r.name.as_str())
        .collect();
    if names.is_empty() {
        " (the program has no procedure without parameters)".to_string()
    } else {
        format!(" (procedures to start: {})", names.join(", "))
    }
}

/// The run's outputs can be written, and none is an input of the run or another output.
pub(super) fn check_paths(args: &RunArgs) -> Result<(), String> {
    let programs = program::rapid_files::find_rapid_files(&args.files).unwrap_or_default();
    let config_files: Vec<PathBuf> = program::config_dir(args.config.as_deref(), &args.files)
        .map(|dir| {
            ["EIO.cfg", "SIO.cfg", "MOC.cfg"]
                .iter()
                .filter_map(|f| crate::config::find_file(&dir, f))
                .collect()
        })
        .unwrap_or_default();
    let mut inputs: Vec<Role<'_>> = programs
        .iter()
        .map(|p| Role::new("the program file", p))
        .chain(
            config_files
                .iter()
                .map(|p| Role::new("the configuration file", p)),
        )
        .collect();
    let mut outputs = Vec::new();
    for (what, path) in [
        ("--trace", &args.trace),
        ("--plot", &args.plot),
        ("--egm-log", &args.egm.egm_log),
        ("--pers", &args.pers),
        ("--view", &args.view.view),
    ] {
        if let Some(p) = path {
            outputs.push(Role::new(what, p));
        }
    }
    if let Some(p) = &args.pers {
        inputs.push(Role::new("--pers", p));
    }
    files::check_outputs(&inputs, &outputs)
}

/// Read and parse `--pers` (nothing when the file does not exist yet).
pub(super) fn read_pers(path: &Path) -> Result<Option<StoredPers>, String> {
    if !path.exists() {
        return Ok(None);
    }
    if !path.is_file() {
        return Err(format!(
            "--pers {}: not a regular file (the persistents file is replaced when the run ends)",
            path.display()
        ));
    }
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let entries = pers::parse(&text).map_err(|e| {
        format!(
            "{}: {e} (the file is not used and stays as it is)",
            path.display()
        )
    })?;
    Ok(Some(StoredPers {
        path: path.to_path_buf(),
        text,
        entries,
    }))
}

/// How many times the entry routine runs (`--cycles`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cycles(Option<u32>);

impl Cycles {
    /// Once.
    pub const ONCE: Cycles = Cycles(Some(1));

    /// True while cycle `done` + 1 is to run.
    pub fn more(self, done: u32) -> bool {
        self.0.is_none_or(|n| done < n)
    }
}

/// `--cycles`: a count of at least 1, or `forever`.
fn parse_cycles(s: &str) -> Result<Cycles, String> {
    if s.trim().eq_ignore_ascii_case("forever") {
        return Ok(Cycles(None));
    }
    match s.trim().parse::<u32>() {
        Ok(n) if n >= 1 => Ok(Cycles(Some(n))),
        _ => Err(format!(
            "`{s}` is not a number of cycles: 1 to {} or `forever`",
            u32::MAX
        )),
    }
}

/// Run the entry routine `--cycles` times. Returns the exit code and whether the robot may
/// finish its queued moves (the program ended normally) or must stop where it is.
fn run_cycles(args: &RunArgs, it: &mut Interp, sources: &SourceMap) -> (ExitCode, bool) {
    let mut done = 0u32;
    while args.cycles.more(done) {
        done = done.saturating_add(1);
        match it.run(&args.entry) {
            Ok(Outcome::Completed | Outcome::ExitCycle) => {}
            Ok(Outcome::Exited) => {
                eprintln!("program ended by EXIT");
                return (ExitCode::SUCCESS, true);
            }
            Ok(Outcome::Stopped) => {
                progress_line::clear();
                if it.stop_requested() {
                    eprintln!("program stopped (interrupted by Ctrl-C)");
                } else {
                    eprintln!("program stopped (Stop)");
                }
                return (ExitCode::SUCCESS, false);
            }
            Err(e) => {
                let _ = std::io::stdout().flush();
                // An error in a module loaded while the program ran points into it.
                render::runtime_error(&e, it.loaded_sources().unwrap_or(sources));
                return (ExitCode::from(1), false);
            }
        }
    }
    (ExitCode::SUCCESS, true)
}

/// The view of a run of `progs` (one per task; the page shows their files).
pub(super) fn start_view<'a>(
    args: &RunArgs,
    progs: impl IntoIterator<Item = &'a crate::ir::Program>,
    sources: &Arc<SourceMap>,
) -> Result<Option<view_options::ViewRun>, String> {
    let mut files = Vec::new();
    for prog in progs {
        // The program's own files (not the embedded default USER module either).
        let own = |m: &&crate::ir::ModuleInfo| {
            !m.stdlib && sources.get(m.source).name != crate::interp::stdlib::DEFAULT_USER.0
        };
        for m in prog.modules.iter().filter(own) {
            if !files.contains(&m.source) {
                files.push(m.source);
            }
        }
    }
    let robot = Robot::new(args.robot.0);
    args.view
        .start(plot_title(args), &robot, args.period, sources, files)
}

/// A started controller: its handle, its EGM side, whether `--egm-log` is written, and
/// whether an external sensor takes part in a virtual run.
pub(crate) type StartedController = (ControllerHandle, EgmController, bool, bool);

/// The controller of this run: robot, period, start position, clock, trace, plot and view,
/// and its EGM side (devices, clock choice, output feed, `--egm-log`).
/// Returns the controller, its EGM side, whether `--egm-log` is written, and whether an
/// external sensor takes part in a virtual (lockstep) run. `egm_devices`: the devices the
/// program sets up, `None` when it uses no EGM; `uses_sockets`: the program has sockets, so
/// real processes take part (real time unless `--lockstep`).
#[allow(clippy::too_many_arguments)]
pub(super) fn start_controller(
    args: &RunArgs,
    sources: &Arc<SourceMap>,
    cfg: &crate::config::Config,
    signals: &Arc<crate::signals::SignalTable>,
    egm_devices: Option<&egm_options::DeviceUse>,
    uses_sockets: bool,
    view: Option<&view_options::ViewRun>,
) -> Result<StartedController, String> {
    let uses_egm = egm_devices.is_some();
    if args.egm.egm_log.is_some() && !uses_egm {
        eprintln!("note: --egm-log: the program uses no EGM; no log is written");
    }
    let timing = args.timing();
    let mut sinks: Vec<Box<dyn TickSink>> = Vec::new();
    let mut feed = Feed::new();
    if let Some(path) = &args.trace {
        let lines = Some(Arc::clone(sources));
        sinks.push(Box::new(if uses_egm {
            TraceWriter::create_with_feed(
                path,
                lines,
                TraceColumns::EGM_AND_PATHCORR,
                feed.subscribe(),
            )?
        } else {
            TraceWriter::create(path, lines)?
        }));
    }
    if let Some(path) = &args.plot {
        let title = plot_title(args);
        let plot = PlotRecorder::new(path, &title, Some(Arc::clone(sources)))?;
        sinks.push(Box::new(if uses_egm {
            plot.with_feed(feed.subscribe())
        } else {
            plot
        }));
    }
    if let Some(v) = view {
        sinks.push(v.sink(uses_egm.then(|| feed.subscribe())));
    }
    if let Some(sink) = system_outputs(cfg, signals).and_then(|o| o.motion_sink()) {
        sinks.push(sink);
    }
    if std::io::stderr().is_terminal() {
        sinks.push(Box::new(progress_line::ProgressLine::new(Arc::clone(
            sources,
        ))));
    }
    let start = args.start.map_or(DEFAULT_START, |s| s.0);
    let robot = Robot::new(args.robot.0);
    let mut config = ControllerConfig::new(robot.clone(), start);
    config.core = CoreConfig {
        period: timing.period,
        ..CoreConfig::default()
    };
    config.max_wait = timing.max_wait;
    if args.egm.lockstep && args.realtime {
        return Err("--lockstep keeps virtual time; it cannot be combined with --realtime".into());
    }
    if args.egm.lockstep && args.view.needs_realtime() {
        return Err(
            "--lockstep keeps virtual time; it cannot be combined with --view-live (which runs in real time)"
                .into(),
        );
    }
    let feed = (!feed.is_unused()).then_some(feed);
    let prepared = args.egm.prepare(
        cfg,
        &robot,
        Arc::clone(signals),
        config.core.period,
        feed,
        egm_devices,
    )?;
    let log_written = prepared.log_written;
    let outside_inputs = args.egm.lockstep && !prepared.external.is_empty();
    let egm_realtime = uses_egm && prepared.needs_realtime;
    let realtime = args.realtime
        || args.view.needs_realtime()
        || egm_realtime
        || (uses_sockets && !args.egm.lockstep);
    if egm_realtime && !args.realtime && !args.view.needs_realtime() {
        progress_line::clear();
        eprintln!(
            "note: EGM device {} is an external sensor: the clock runs in real time (--lockstep keeps virtual time)",
            prepared.external.join(", ")
        );
    }
    if uses_sockets
        && let Some(note) = socket_clock::note(
            args.realtime || args.view.needs_realtime() || egm_realtime,
            args.egm.lockstep,
        )
    {
        progress_line::clear();
        eprintln!("{note}");
    }
    let hook: Option<Box<dyn CycleHook>> = Some(Box::new(prepared.hook));
    let egm_controller = prepared.controller;
    if !realtime {
        return ControllerHandle::start_with_hook(config, sinks, hook)
            .map(|c| (c, egm_controller, log_written, outside_inputs))
            .map_err(|e| start_error(&e));
    }
    // Real time: SCHED_FIFO when the system grants it, else normal priority.
    config.clock = ClockMode::RealTime(RealtimeConfig::Enforce);
    match ControllerHandle::start(config.clone(), Vec::new()) {
        Ok(probe) => {
            let _ = probe.finish();
        }
        Err(ControllerError::Priority(msg)) => {
            eprintln!("note: running without real-time priority: {msg}");
            config.clock = ClockMode::RealTime(RealtimeConfig::Ignore);
        }
        Err(e) => return Err(start_error(&e)),
    }
    ControllerHandle::start_with_hook(config, sinks, hook)
        .map(|c| (c, egm_controller, log_written, false))
        .map_err(|e| start_error(&e))
}

/// The system outputs of the configuration's EIO.cfg on `signals`, if it has any.
pub(crate) fn system_outputs(
    cfg: &crate::config::Config,
    signals: &Arc<crate::signals::SignalTable>,
) -> Option<crate::controller::system_outputs::SystemOutputs> {
    let eio = cfg.eio.as_ref()?;
    crate::controller::system_outputs::SystemOutputs::new(&eio.system_outputs, signals)
}

/// What the system outputs show while a `rapidvc run` goes on (`running`: its tasks) or
/// after it ended (`error`: on an error).
pub(crate) fn run_output_state(
    running: Vec<String>,
    error: bool,
) -> crate::controller::system_outputs::OutputState {
    crate::controller::system_outputs::OutputState {
        motors_on: true,
        auto: true,
        running,
        error,
    }
}

fn start_error(e: &ControllerError) -> String {
    match e {
        ControllerError::InvalidStart(k) => format!("--start: {k}"),
        other => other.to_string(),
    }
}

/// The plot's title: the program's files and the robot.
fn plot_title(args: &RunArgs) -> String {
    let names: Vec<String> = args
        .files
        .iter()
        .map(|p| {
            p.file_name()
                .map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into())
        })
        .collect();
    format!("{} on {}", names.join(", "), args.robot.0.name)
}

pub(super) fn print_summary(summary: &RunSummary) {
    progress_line::clear();
    eprintln!("{summary}");
}

/// Where program output goes: TP lines to stdout, the event log to stderr.
pub(super) fn print_output(o: &Output) {
    match o {
        Output::TpWrite(s) => {
            let mut out = std::io::stdout().lock();
            let _ = writeln!(out, "{s}");
        }
        Output::TpErase => {}
        Output::ErrWrite {
            warning,
            header,
            reason,
        } => {
            progress_line::clear();
            let kind = if *warning { "warning" } else { "error" };
            eprintln!("event log ({kind}): {header}: {}", reason.join(" "));
        }
        Output::Event(e) => {
            progress_line::clear();
            eprintln!("event: {e}");
        }
    }
}
