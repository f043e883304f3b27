//! `rapidvc bench virtual|realtime|egm`: measure the motion core (and EGM: see
//! `cli/bench/egm.rs`). `virtual` runs minutes of mixed
//! MoveJ/MoveL in virtual time and reports the real-time factor (simulated seconds per wall
//! second); `realtime` runs the motion thread at its fixed period while busy-loop processes
//! load every core, and prints the distribution of the cycle-period error.

use std::io::Read;
use std::path::PathBuf;
use std::process::{Child, ExitCode, Stdio};
use std::time::Duration;

use crate::controller::{
    ClockMode, Condition, ControllerConfig, ControllerError, ControllerHandle, MonotonicClock,
    RealtimeConfig, TickSink,
};
use crate::output::TraceWriter;
use crate::robot::command::{
    EXTAX_NONE, MotionCommand, MoveArgs, MoveJ, MoveL, RobTarget, SpeedData, ZoneData,
};
use crate::robot::{ConfData, Robot, ToolData};
use crate::time::RobotTime;

use super::num;
use super::robots::RobotArg;

mod egm;

/// Arguments of `rapidvc bench`.
#[derive(Debug, clap::Args)]
pub struct BenchArgs {
    /// What to measure.
    #[command(subcommand)]
    pub what: BenchKind,
}

/// The benchmarks.
#[derive(Debug, clap::Subcommand)]
pub enum BenchKind {
    /// Virtual-time speed: simulated seconds per wall second over mixed MoveJ/MoveL.
    Virtual {
        /// Simulated duration in seconds (more than 0, at most 1e6).
        #[arg(long, default_value_t = 300.0, value_parser = num::bench_virtual_seconds)]
        seconds: f64,
        /// Also write a CSV trace (measures the cost of tracing).
        #[arg(long, value_name = "FILE.csv")]
        trace: Option<PathBuf>,
        /// Robot model.
        #[arg(long, value_name = "NAME", default_value = "IRB 2600-12/1.85")]
        robot: RobotArg,
    },
    /// EGM with an external sensor over loopback: loopback round trip, cycle-period jitter
    /// of a real-time EGM run, controller turnaround, lockstep speed-up.
    Egm {
        /// Real-time run length in seconds (the lockstep run covers the same robot time;
        /// more than 0, at most 86400).
        #[arg(long, default_value_t = 20.0, value_parser = num::bench_wall_seconds)]
        seconds: f64,
        /// Do not ask for SCHED_FIFO priority.
        #[arg(long)]
        no_priority: bool,
    },
    /// One busy-loop load process of `bench realtime` (started by it): spins until its
    /// standard input closes — which happens when the bench ends or dies, however it dies —
    /// or after `--seconds`.
    #[command(hide = true)]
    LoadWorker {
        /// The longest time to spin, seconds.
        #[arg(long, value_parser = num::bench_wall_seconds)]
        seconds: f64,
    },
    /// Real-time cycle jitter under load: histogram of |period − nominal|.
    Realtime {
        /// Duration in seconds (more than 0, at most 86400).
        #[arg(long, default_value_t = 60.0, value_parser = num::bench_wall_seconds)]
        seconds: f64,
        /// Busy-loop processes to start as load (0 to 256; each ends with the run, and with
        /// rapidvc if it is killed).
        #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u16).range(num::BENCH_LOAD))]
        load: u16,
        /// Do not ask for SCHED_FIFO priority.
        #[arg(long)]
        no_priority: bool,
        /// Spin this many µs before each deadline instead of sleeping (0 to 4000).
        #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u64).range(num::BENCH_SPIN_US))]
        spin_us: u64,
    },
}

/// Run a benchmark.
pub fn run(args: BenchArgs) -> ExitCode {
    let result = match args.what {
        BenchKind::Virtual {
            seconds,
            trace,
            robot,
        } => bench_virtual(seconds, trace, robot),
        BenchKind::Realtime {
            seconds,
            load,
            no_priority,
            spin_us,
        } => bench_realtime(seconds, load, no_priority, Duration::from_micros(spin_us)),
        BenchKind::Egm {
            seconds,
            no_priority,
        } => egm::bench_egm(seconds, no_priority),
        BenchKind::LoadWorker { seconds } => load_worker(seconds),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("rapidvc bench: {e}");
            ExitCode::FAILURE
        }
    }
}

const START: [f64; 6] = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];

/// A deterministic stream of reachable MoveJ/MoveL commands in front of the robot, tool
/// pointing down, with fine points and fly-by zones.
struct Workload {
    state: u64,
    id: u64,
    scale: f64,
}

impl Workload {
    fn new(model_reach_mm: f64) -> Workload {
        Workload {
            state: 0x2545_F491_4F6C_DD1D,
            id: 0,
            // The box below suits the 1.85 m default; smaller robots get a scaled box.
            scale: (model_reach_mm / 1850.0).min(1.0),
        }
    }

    /// Uniform in [0, 1) from a 64-bit LCG (Knuth's MMIX constants).
    fn uniform(&mut self) -> f64 {
        self.state = self
            .state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.state >> 11) as f64 / (1u64 << 53) as f64
    }

    fn next(&mut self) -> MotionCommand {
        self.id += 1;
        let s = self.scale;
        let x = (850.0 + 500.0 * self.uniform()) * s;
        let y = (-500.0 + 1000.0 * self.uniform()) * s;
        let z = (600.0 + 700.0 * self.uniform()) * s;
        let a = (-45.0 + 90.0 * self.uniform()).to_radians() / 2.0;
        // Tool pointing down (180° about y), turned by `2a` about the vertical.
        let rot = [0.0, -a.sin(), a.cos(), 0.0];
        let zone = match self.uniform() {
            u if u < 0.25 => ZoneData::FINE,
            u if u < 0.75 => fly_by(10.0),
            _ => fly_by(50.0),
        };
        let args = MoveArgs::new(
            self.id,
            SpeedData::v(500.0 + 1500.0 * self.uniform()),
            zone,
            ToolData::tool0(),
        );
        let target = RobTarget {
            trans: [x, y, z],
            rot,
            robconf: ConfData::default(),
            extax: EXTAX_NONE,
        };
        if self.uniform() < 0.5 {
            MotionCommand::MoveJ(MoveJ {
                args,
                target,
                conf_check: false,
            })
        } else {
            MotionCommand::MoveL(MoveL {
                args,
                target,
                conf_check: false,
            })
        }
    }
}

fn fly_by(z: f64) -> ZoneData {
    ZoneData {
        finep: false,
        pzone_tcp: z,
        pzone_ori: 1.5 * z,
        pzone_eax: 1.5 * z,
        zone_ori: 0.15 * z,
        zone_leax: 1.5 * z,
        zone_reax: 0.15 * z,
    }
}

/// Submit workload moves until robot time reaches `until`; returns (moves, refused).
fn drive(
    c: &mut ControllerHandle,
    wl: &mut Workload,
    until: RobotTime,
) -> Result<(u64, u64), ControllerError> {
    let (mut moves, mut refused) = (0, 0);
    while c.now() < until {
        let cmd = wl.next();
        let fine = cmd.args().zone.finep;
        let id = cmd.id();
        match c.submit(cmd) {
            Ok(()) => {
                moves += 1;
                if fine && !c.is_realtime() {
                    // As RAPID does at a stop point: wait until the robot is there.
                    c.wait_until(Condition::Done(id))?;
                }
            }
            Err(ControllerError::Rejected(_)) => refused += 1,
            Err(e) => return Err(e),
        }
        let _ = c.take_events();
    }
    c.wait_until(Condition::InPos)?;
    Ok((moves, refused))
}

fn bench_virtual(seconds: f64, trace: Option<PathBuf>, robot: RobotArg) -> Result<(), String> {
    let mut sinks: Vec<Box<dyn TickSink>> = Vec::new();
    if let Some(path) = &trace {
        sinks.push(Box::new(TraceWriter::create(path, None)?));
    }
    let config = ControllerConfig::new(Robot::new(robot.0), START);
    let mut c = ControllerHandle::start(config, sinks).map_err(|e| e.to_string())?;
    let mut wl = Workload::new(robot.0.reach_mm());
    let wall = MonotonicClock::new();
    let (moves, refused) =
        drive(&mut c, &mut wl, RobotTime::from_secs_f64(seconds)).map_err(|e| e.to_string())?;
    let summary = c.finish().map_err(|e| e.to_string())?;
    let elapsed = wall.elapsed();
    let per_tick_us = elapsed.as_secs_f64() * 1e6 / summary.ticks.max(1) as f64;
    println!("{summary}");
    println!(
        "virtual time: {moves} moves ({refused} refused), {} cycles, {:.2} µs wall per cycle (planning included){}",
        summary.ticks,
        per_tick_us,
        if trace.is_some() {
            ", with CSV trace"
        } else {
            ""
        }
    );
    println!(
        "real-time factor: {:.0}× (goal ≥ 1000×)",
        summary.realtime_factor()
    );
    Ok(())
}

fn bench_realtime(
    seconds: f64,
    load: u16,
    no_priority: bool,
    spin: Duration,
) -> Result<(), String> {
    let mut workers: Vec<Child> = Vec::new();
    let exe = std::env::current_exe()
        .map_err(|e| format!("cannot find this program to start the load processes: {e}"))?;
    // A time bound as well, in case a worker outlives its pipe somehow.
    let bound = (seconds + 15.0).ceil().to_string();
    for _ in 0..load {
        // The worker spins until its stdin closes: this process holds the only write end, so
        // the kernel closes it when this process ends, even on SIGKILL.
        match std::process::Command::new(&exe)
            .args(["bench", "load-worker", "--seconds", bound.as_str()])
            .stdin(Stdio::piped())
            .stdout(Stdio::null())
            .spawn()
        {
            Ok(ch) => workers.push(ch),
            Err(e) => {
                stop_workers(&mut workers);
                return Err(format!("cannot start the load processes: {e}"));
            }
        }
    }
    let result = realtime_run(seconds, no_priority, spin, load);
    stop_workers(&mut workers);
    result
}

/// The load process: spin on this core until stdin reaches its end (the bench that started
/// it ended or died) or `seconds` passed.
fn load_worker(seconds: f64) -> Result<(), String> {
    std::thread::spawn(|| {
        let mut stdin = std::io::stdin();
        let mut buf = [0u8; 64];
        while matches!(stdin.read(&mut buf), Ok(n) if n > 0) {}
        std::process::exit(0);
    });
    let start = MonotonicClock::new();
    let limit = Duration::from_secs_f64(seconds);
    let mut x = 0u64;
    while start.elapsed() < limit {
        for _ in 0..1_000_000 {
            x = std::hint::black_box(x.wrapping_add(1));
        }
    }
    Ok(())
}

fn realtime_run(seconds: f64, no_priority: bool, spin: Duration, load: u16) -> Result<(), String> {
    let mut config = ControllerConfig::new(Robot::default(), START);
    config.clock = ClockMode::RealTime(if no_priority {
        RealtimeConfig::Ignore
    } else {
        RealtimeConfig::Enforce
    });
    config.spin = spin;
    let mut c = ControllerHandle::start(config, Vec::new()).map_err(|e| match e {
        ControllerError::Priority(m) => format!("{m} (or use --no-priority)"),
        other => other.to_string(),
    })?;
    let mut wl = Workload::new(Robot::default().model().reach_mm());
    let (moves, refused) =
        drive(&mut c, &mut wl, RobotTime::from_secs_f64(seconds)).map_err(|e| e.to_string())?;
    let summary = c.finish().map_err(|e| e.to_string())?;
    println!("{summary}");
    println!(
        "real time: {moves} moves ({refused} refused), load {load} busy processes, {}, spin {} µs",
        if no_priority {
            "normal priority"
        } else {
            "SCHED_FIFO"
        },
        spin.as_micros()
    );
    if let Some(stats) = &summary.period_stats {
        println!(
            "cycle-period error |actual − 4 ms|: {}",
            stats.summary_line()
        );
        print!("{}", stats.histogram(50));
        println!(
            "goal p99 ≤ 200 µs: {}; goal max ≤ 1 ms: {}",
            verdict(stats.percentile(0.99) <= Duration::from_micros(200)),
            verdict(stats.max() <= Duration::from_millis(1))
        );
    }
    Ok(())
}

fn verdict(ok: bool) -> &'static str {
    if ok { "met" } else { "NOT met" }
}

/// End the load processes: closing a worker's stdin ends it; wait for each.
fn stop_workers(workers: &mut Vec<Child>) {
    for w in workers.iter_mut() {
        drop(w.stdin.take());
    }
    for w in workers.iter_mut() {
        let _ = w.wait();
    }
    workers.clear();
}
