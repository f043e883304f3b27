//! `rapidvc run FILE…`: load and check the program, start the virtual controller (robot,
//! motion core, trace and plot recorders) and run the entry routine on it. TP output goes to
//! stdout (one line per `TPWrite`); diagnostics, events and the end-of-run summary to stderr.
//! Exit codes: 0 when the program ends (also by EXIT or Stop), 1 on an unhandled run-time
//! error, 2 when the program cannot be loaded or checked, or the run's files cannot be
//! written.

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::str::FromStr;
use std::sync::Arc;
use std::time::Duration;

use super::robots::RobotArg;
use super::{program, progress_line, render};

pub mod egm;
use crate::controller::egm::EgmController;
use crate::controller::{
    ClockMode, ControllerConfig, ControllerError, ControllerHandle, ControllerHost, CycleHook,
    RealtimeConfig, RunSummary, TickSink,
};
use crate::interp::{Interp, Outcome, Output, pers};
use crate::motion::CoreConfig;
use crate::motion::settings::PERIOD_RANGE;
use crate::report::{Feed, PlotRecorder, TraceColumns, TraceWriter};
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
    /// Persistents file: loaded at start when it exists, written at the end.
    #[arg(long)]
    pub pers: Option<PathBuf>,
    /// Fail a wait that would go beyond this robot time (seconds).
    #[arg(long, default_value_t = 86_400.0)]
    pub max_time: f64,
    /// Abort after this many executed statements.
    #[arg(long)]
    pub max_steps: Option<u64>,
    /// Run the entry routine this many times; `ExitCycle` ends a cycle early.
    #[arg(long, default_value_t = 1)]
    pub cycles: u32,
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
    /// Motion cycle in milliseconds.
    #[arg(long, value_name = "MS", default_value_t = 4.0)]
    pub period: f64,
    /// EGM: devices, message log, lockstep.
    #[command(flatten)]
    pub egm: egm::EgmArgs,
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
    let loaded = program::load(&args.files, args.config.as_deref());
    render::diagnostics(&loaded.diags, &loaded.sources);
    let Some(prog) = loaded.program.clone() else {
        return ExitCode::from(2);
    };
    let registry = loaded.registry;
    let signals = loaded.signals;
    let sources: Arc<SourceMap> = Arc::new(loaded.sources);
    let uses_egm = egm::uses_egm(&prog, &sources);
    let (ctl, egm_controller) =
        match start_controller(&args, &sources, &loaded.config, &signals, uses_egm) {
            Ok(c) => c,
            Err(msg) => {
                eprintln!("error: {msg}");
                return ExitCode::from(2);
            }
        };
    let host = ControllerHost::new(ctl)
        .with_egm(egm_controller)
        .with_signals(signals)
        .with_max_time(args.max_time)
        .with_lines(Arc::clone(&sources))
        .with_sink(print_output);
    let mut it = Interp::new(prog, &registry, Box::new(host));
    it.set_budget(args.max_steps);
    // The main thread has 8 MiB of stack; leave 2 MiB of headroom.
    it.set_stack_budget(6 << 20);
    let mut kept = Vec::new();
    let (mut code, drain) = match it.init() {
        Err(e) => {
            render::runtime_error(&e, &sources);
            (ExitCode::from(1), false)
        }
        Ok(()) => {
            match load_pers(&args, &mut it) {
                Ok(k) => kept = k,
                Err(c) => return c,
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
    let announce = args.trace.is_some() || args.plot.is_some() || args.realtime;
    if let Some(host) = it
        .host_mut()
        .as_any_mut()
        .and_then(|a| a.downcast_mut::<ControllerHost>())
    {
        let moved = host.moves_submitted() > 0;
        let egm_controller = host.take_egm();
        match host.finish(drain) {
            Ok(summary) => {
                if moved || announce {
                    print_summary(&summary);
                }
            }
            Err(e) => {
                eprintln!("error: {e}");
                code = ExitCode::from(2);
            }
        }
        if let Some(e) = egm_controller
            && let Err(msg) = egm::finish(e, &args.egm)
        {
            eprintln!("error: {msg}");
            code = ExitCode::from(2);
        }
    }
    if let Some(path) = &args.pers {
        let text = pers::write(&it.persistents(), &kept);
        if let Err(e) = std::fs::write(path, text) {
            eprintln!("error: cannot write {}: {e}", path.display());
            return ExitCode::from(2);
        }
    }
    code
}

/// Run the entry routine `--cycles` times. Returns the exit code and whether the robot may
/// finish its queued moves (the program ended normally) or must stop where it is.
fn run_cycles(args: &RunArgs, it: &mut Interp, sources: &SourceMap) -> (ExitCode, bool) {
    for _ in 0..args.cycles.max(1) {
        match it.run(&args.entry) {
            Ok(Outcome::Completed | Outcome::ExitCycle) => {}
            Ok(Outcome::Exited) => {
                eprintln!("program ended by EXIT");
                return (ExitCode::SUCCESS, true);
            }
            Ok(Outcome::Stopped) => {
                eprintln!("program stopped (Stop)");
                return (ExitCode::SUCCESS, false);
            }
            Err(e) => {
                let _ = std::io::stdout().flush();
                render::runtime_error(&e, sources);
                return (ExitCode::from(1), false);
            }
        }
    }
    (ExitCode::SUCCESS, true)
}

/// Load `--pers` into the program's persistents; returns the entries the program does not
/// declare (kept for writing back).
fn load_pers(args: &RunArgs, it: &mut Interp) -> Result<Vec<pers::PersEntry>, ExitCode> {
    let Some(path) = &args.pers else {
        return Ok(Vec::new());
    };
    if !path.exists() {
        return Ok(Vec::new());
    }
    let text = std::fs::read_to_string(path).map_err(|e| {
        eprintln!("error: cannot read {}: {e}", path.display());
        ExitCode::from(2)
    })?;
    let entries = pers::parse(&text).map_err(|e| {
        eprintln!("error: {}: {e}", path.display());
        ExitCode::from(2)
    })?;
    let (unknown, warnings) = it.load_persistents(&entries);
    for w in warnings {
        eprintln!("warning: {}: {w}", path.display());
    }
    Ok(unknown)
}

/// The controller of this run: robot, period, start position, clock, trace and plot, and its
/// EGM side (devices, clock choice, report feed, `--egm-log`).
fn start_controller(
    args: &RunArgs,
    sources: &Arc<SourceMap>,
    cfg: &crate::config::Config,
    signals: &Arc<crate::io::SignalTable>,
    uses_egm: bool,
) -> Result<(ControllerHandle, EgmController), String> {
    let period_ms = args.period;
    let (lo, hi) = (
        PERIOD_RANGE.0.as_secs_f64() * 1e3,
        PERIOD_RANGE.1.as_secs_f64() * 1e3,
    );
    if !(lo..=hi).contains(&period_ms) {
        return Err(format!(
            "--period {period_ms}: the motion cycle must lie between {lo} and {hi} ms"
        ));
    }
    if !(args.max_time.is_finite() && args.max_time > 0.0) {
        return Err(format!(
            "--max-time {}: must be a positive number of seconds",
            args.max_time
        ));
    }
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
    if std::io::stderr().is_terminal() {
        sinks.push(Box::new(progress_line::ProgressLine::new(Arc::clone(
            sources,
        ))));
    }
    let start = args.start.map_or(DEFAULT_START, |s| s.0);
    let robot = Robot::new(args.robot.0);
    let mut config = ControllerConfig::new(robot.clone(), start);
    config.core = CoreConfig {
        period: Duration::from_secs_f64(period_ms / 1e3),
        ..CoreConfig::default()
    };
    config.max_wait = Duration::from_secs_f64(args.max_time);
    if args.egm.lockstep && args.realtime {
        return Err("--lockstep keeps virtual time; it cannot be combined with --realtime".into());
    }
    let feed = (!feed.is_unused()).then_some(feed);
    let prepared = args
        .egm
        .prepare(cfg, &robot, Arc::clone(signals), config.core.period, feed)?;
    let realtime = args.realtime || (uses_egm && prepared.needs_realtime);
    if realtime && !args.realtime {
        progress_line::clear();
        eprintln!(
            "note: EGM device {} is an external sensor: the clock runs in real time (--lockstep keeps virtual time)",
            prepared.external.join(", ")
        );
    }
    let hook: Option<Box<dyn CycleHook>> = Some(Box::new(prepared.hook));
    let egm_controller = prepared.controller;
    if !realtime {
        return ControllerHandle::start_with_hook(config, sinks, hook)
            .map(|c| (c, egm_controller))
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
        .map(|c| (c, egm_controller))
        .map_err(|e| start_error(&e))
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

fn print_summary(summary: &RunSummary) {
    progress_line::clear();
    eprintln!("{summary}");
}

/// Where program output goes: TP lines to stdout, the event log to stderr.
fn print_output(o: &Output) {
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
