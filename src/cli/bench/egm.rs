//! `rapidvc bench egm`: EGM figures with an external sensor over loopback — the loopback round trip, the cycle-period jitter of a real-time EGM run, the controller's turnaround (reply arrival → reference applied), and the lockstep speed-up over real time.
//!
//! The sensor is a thread of this process on its own UDP socket that answers every
//! `EgmRobot` at once with a slowly moving joint target (the run never converges). The
//! controller is the one `rapidvc run` uses: motion thread, EGM driver as external guidance,
//! cycle hook.
//!
//! Turnaround: a reply is read and applied by the first motion cycle that starts after it
//! arrived (receive → servo → send in one cycle). The bench notes the start of every cycle
//! (a wrapper around the EGM cycle hook) and the moment the sensor sent each reply, both on
//! this process's monotonic clock: turnaround = start of the applying cycle − reply sent
//! (the loopback trip, a few µs, included). The sensor also measures reply sent → next
//! message received, which adds the cycle's work and the trip back.

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use prost::Message;

use crate::config::devices::DeviceTable;
use crate::config::moc::MocConfig;
use crate::controller::egm_controller::registry_config;
use crate::controller::egm_controller::{EgmController, EgmHook, EgmSetup, LastMove};
use crate::controller::{
    ClockMode, Condition, ControllerConfig, ControllerError, ControllerHandle, CycleHook,
    RealtimeConfig,
};
use crate::egm::latency::{LatencyHistogram, fmt_duration};
use crate::egm::registry::{ActJoint, RunArgs, SetupUc};
use crate::egm::servo::StopMode;
use crate::egm::{DriverOptions, EgmMode, proto};
use crate::motion::{Executor, Setpoint};
use crate::robot::command::{
    EXTAX_NONE, JointTarget, MotionCommand, MoveAbsJ, MoveArgs, SpeedData, ZoneData,
};
use crate::robot::{Robot, ToolData};
use crate::signals::SignalTable;
use crate::time::RobotTime;

const START: [f64; 6] = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];

/// Runs the benchmark: `seconds` of real time, then the same in lockstep.
pub fn bench_egm(seconds: f64, no_priority: bool) -> Result<(), String> {
    if !(seconds.is_finite() && seconds > 0.0 && seconds <= 3600.0) {
        return Err(format!("--seconds {seconds}: must be in (0, 3600]"));
    }
    let rtt = loopback_round_trip(5000)?;
    println!(
        "loopback round trip (UDP, 300-byte datagrams): {}",
        rtt.summary()
    );
    let rtt_p50 = rtt.percentile(50.0).unwrap_or_default();

    let rt = session(seconds, Mode::RealTime { no_priority })?;
    println!(
        "real time, {} s with an external sensor: {} EGM messages, {} replies",
        seconds, rt.received, rt.replied
    );
    if let Some(stats) = &rt.period {
        println!(
            "  cycle-period error: p50={} p99={} max={} (n={}, overruns {})",
            fmt_duration(stats.percentile(0.5)),
            fmt_duration(stats.percentile(0.99)),
            fmt_duration(stats.max()),
            stats.count(),
            stats.overruns()
        );
    }
    println!(
        "  reply sent → next message received: {}",
        rt.turnaround.summary()
    );
    println!(
        "  controller turnaround (reply sent → start of the cycle that applies it): {}",
        rt.applied.summary()
    );
    println!(
        "  EGM work per cycle (receive, servo, send, hook): {}",
        rt.work.summary()
    );
    println!(
        "  loopback one-way ≈ round trip / 2 = {}",
        fmt_duration(rtt_p50 / 2)
    );
    let ls = session(seconds, Mode::Lockstep)?;
    println!(
        "lockstep, {} s of robot time: {} EGM messages in {:.3} s wall: {:.1}× real time",
        ls.simulated.as_secs_f64(),
        ls.received,
        ls.wall.as_secs_f64(),
        ls.simulated.as_secs_f64() / ls.wall.as_secs_f64().max(1e-9)
    );
    Ok(())
}

/// Ping-pong between two loopback sockets.
fn loopback_round_trip(n: u32) -> Result<LatencyHistogram, String> {
    let io = |e: std::io::Error| format!("loopback: {e}");
    let a = UdpSocket::bind("127.0.0.1:0").map_err(io)?;
    let b = UdpSocket::bind("127.0.0.1:0").map_err(io)?;
    a.set_read_timeout(Some(Duration::from_secs(1)))
        .map_err(io)?;
    b.set_read_timeout(Some(Duration::from_secs(1)))
        .map_err(io)?;
    let b_addr = b.local_addr().map_err(io)?;
    let echo = std::thread::spawn(move || {
        let mut buf = [0u8; 2048];
        for _ in 0..n {
            match b.recv_from(&mut buf) {
                Ok((len, src)) => {
                    let _ = b.send_to(buf.get(..len).unwrap_or(&[]), src);
                }
                Err(_) => return,
            }
        }
    });
    let msg = [0x5au8; 300];
    let mut buf = [0u8; 2048];
    let mut h = LatencyHistogram::new();
    for _ in 0..n {
        let t = Instant::now();
        a.send_to(&msg, b_addr).map_err(io)?;
        a.recv_from(&mut buf).map_err(io)?;
        h.record(t.elapsed());
    }
    let _ = echo.join();
    Ok(h)
}

enum Mode {
    RealTime { no_priority: bool },
    Lockstep,
}

struct Outcome {
    received: u64,
    replied: u64,
    turnaround: LatencyHistogram,
    applied: LatencyHistogram,
    work: LatencyHistogram,
    period: Option<crate::controller::PeriodStats>,
    simulated: Duration,
    wall: Duration,
}

struct SensorResult {
    received: u64,
    replied: u64,
    turnaround: LatencyHistogram,
    sent_at: Vec<Instant>,
}

/// The sensor thread: answers every message with a slowly moving joint target.
fn sensor(sock: UdpSocket, stop: Arc<AtomicBool>) -> JoinHandle<SensorResult> {
    std::thread::spawn(move || {
        let _ = sock.set_read_timeout(Some(Duration::from_millis(50)));
        let mut buf = [0u8; 2048];
        let mut r = SensorResult {
            received: 0,
            replied: 0,
            turnaround: LatencyHistogram::new(),
            sent_at: Vec::with_capacity(1 << 20),
        };
        let mut last_reply: Option<Instant> = None;
        let mut seq = 0u32;
        while !stop.load(Ordering::Relaxed) {
            let Ok((n, src)) = sock.recv_from(&mut buf) else {
                continue;
            };
            let got = Instant::now();
            if let Some(t) = last_reply.take() {
                r.turnaround.record(got.saturating_duration_since(t));
            }
            let Ok(m) = proto::EgmRobot::decode(buf.get(..n).unwrap_or(&[])) else {
                continue;
            };
            r.received += 1;
            let tm = m.header.and_then(|h| h.tm).unwrap_or(0);
            let phase = f64::from(tm) / 1000.0;
            let mut joints = START.to_vec();
            if let Some(j) = joints.first_mut() {
                *j = 10.0 * (0.5 * phase).sin();
            }
            let reply = proto::EgmSensor {
                header: Some(proto::EgmHeader {
                    seqno: Some(seq),
                    tm: Some(tm),
                    mtype: Some(proto::egm_header::MessageType::MsgtypeCorrection as i32),
                }),
                planned: Some(proto::EgmPlanned {
                    joints: Some(proto::EgmJoints { joints }),
                    ..Default::default()
                }),
                ..Default::default()
            }
            .encode_to_vec();
            seq = seq.wrapping_add(1);
            if sock.send_to(&reply, src).is_ok() {
                let t = Instant::now();
                last_reply = Some(t);
                r.sent_at.push(t);
                r.replied += 1;
            }
        }
        r
    })
}

/// Wraps the EGM hook and notes when each cycle starts and how long its work took (the
/// bench's own measurement; `try_lock` on a lock nobody else holds during the run).
struct Probe {
    inner: EgmHook,
    ticks: Arc<Mutex<Ticks>>,
    started: Option<Instant>,
}

#[derive(Default)]
struct Ticks {
    starts: Vec<Instant>,
    work: LatencyHistogram,
}

impl CycleHook for Probe {
    fn before_tick(&mut self, now: RobotTime, exec: &mut Executor) {
        let t = Instant::now();
        self.started = Some(t);
        if let Ok(mut ticks) = self.ticks.try_lock() {
            ticks.starts.push(t);
        }
        self.inner.before_tick(now, exec);
    }

    fn after_tick(&mut self, sp: &Setpoint, exec: &mut Executor) {
        self.inner.after_tick(sp, exec);
        if let (Some(t), Ok(mut ticks)) = (self.started.take(), self.ticks.try_lock()) {
            ticks.work.record(t.elapsed());
        }
    }
}

fn ctl_err(e: ControllerError) -> String {
    e.to_string()
}

/// One EGM run of `seconds` against the sensor thread.
fn session(seconds: f64, mode: Mode) -> Result<Outcome, String> {
    let sock = UdpSocket::bind("127.0.0.1:0").map_err(|e| e.to_string())?;
    let addr: SocketAddr = sock.local_addr().map_err(|e| e.to_string())?;
    let stop = Arc::new(AtomicBool::new(false));
    let thread = sensor(sock, Arc::clone(&stop));
    let ticks = Arc::new(Mutex::new(Ticks {
        starts: Vec::with_capacity(1 << 20),
        work: LatencyHistogram::new(),
    }));
    let result = drive(seconds, &mode, addr, &ticks);
    stop.store(true, Ordering::Relaxed);
    let s = thread
        .join()
        .map_err(|_| "the sensor thread panicked".to_string())?;
    let (period, simulated, wall) = result?;
    let ticks = std::mem::take(&mut *ticks.lock().map_err(|_| "probe lock".to_string())?);
    // Each reply is applied by the first cycle that starts after it was sent.
    let mut applied = LatencyHistogram::new();
    let mut k = 0;
    for sent in &s.sent_at {
        while ticks.starts.get(k).is_some_and(|t| t < sent) {
            k += 1;
        }
        if let Some(t) = ticks.starts.get(k) {
            applied.record(t.saturating_duration_since(*sent));
        }
    }
    Ok(Outcome {
        received: s.received,
        replied: s.replied,
        turnaround: s.turnaround,
        applied,
        work: ticks.work,
        period,
        simulated,
        wall,
    })
}

type Driven = (Option<crate::controller::PeriodStats>, Duration, Duration);

fn drive(
    seconds: f64,
    mode: &Mode,
    sensor: SocketAddr,
    ticks: &Arc<Mutex<Ticks>>,
) -> Result<Driven, String> {
    let robot = Robot::default();
    let mut config = ControllerConfig::new(robot.clone(), START);
    if let Mode::RealTime { no_priority } = mode {
        // SCHED_FIFO when the system grants it, else normal priority (as `rapidvc run`).
        config.clock = ClockMode::RealTime(RealtimeConfig::Ignore);
        if !no_priority {
            let mut probe = config.clone();
            probe.clock = ClockMode::RealTime(RealtimeConfig::Enforce);
            match ControllerHandle::start(probe, Vec::new()) {
                Ok(h) => {
                    let _ = h.finish();
                    config.clock = ClockMode::RealTime(RealtimeConfig::Enforce);
                }
                Err(ControllerError::Priority(msg)) => {
                    eprintln!("note: running without real-time priority: {msg}");
                }
                Err(e) => return Err(ctl_err(e)),
            }
        }
    }
    let device = format!("sensor={sensor}")
        .parse()
        .map_err(|e: crate::config::devices::DeviceOverrideError| e.to_string())?;
    let devices = DeviceTable::new(None, &[device]).map_err(|e| e.to_string())?;
    let setup = EgmSetup {
        registry: registry_config(&MocConfig::default(), &devices),
        driver: DriverOptions::default(),
        lockstep: matches!(mode, Mode::Lockstep)
            .then_some(crate::egm::driver::DEFAULT_REPLY_TIMEOUT),
        feed: None,
        log: None,
    };
    let signals = Arc::new(SignalTable::with_builtins());
    let (mut egm, hook) = EgmController::new(setup, robot, signals)?;
    let probe = Probe {
        inner: hook,
        ticks: Arc::clone(ticks),
        started: None,
    };
    let mut handle = ControllerHandle::start_with_hook(config, Vec::new(), Some(Box::new(probe)))
        .map_err(ctl_err)?;
    let fail = |e: crate::controller::egm_controller::EgmFailure| e.to_string();
    handle
        .submit(MotionCommand::MoveAbsJ(MoveAbsJ {
            args: MoveArgs::new(1, SpeedData::v(1000.0), ZoneData::FINE, ToolData::tool0()),
            target: JointTarget {
                robax: START,
                extax: EXTAX_NONE,
            },
            no_eoffs: false,
        }))
        .map_err(ctl_err)?;
    // Done(1), not InPos: in real time the motion thread may not have taken the move yet.
    handle.wait_until(Condition::Done(1)).map_err(ctl_err)?;
    egm.get_id(&mut handle, "bench").map_err(fail)?;
    egm.setup_uc(
        &mut handle,
        "bench",
        &SetupUc {
            mecunit: "ROB_1".into(),
            profile: "default".into(),
            device: "sensor".into(),
            mode: EgmMode::Joint,
            tracker: None,
            comm_timeout: Some(5.0),
        },
    )
    .map_err(fail)?;
    let mut act = ActJoint::default();
    act.common.max_speed_deviation = Some(100.0);
    egm.act_joint(&mut handle, "bench", &act).map_err(fail)?;
    let args = RunArgs {
        no_wait_cond: true,
        cond_time: Some(9e9),
        ..RunArgs::new(StopMode::Hold)
    };
    let wall = Instant::now();
    let t0 = handle.now();
    egm.run_joint(
        &mut handle,
        "bench",
        &args,
        [true, false, false, false, false, false, false],
        LastMove::StopPoint,
        None,
    )
    .map_err(fail)?;
    let end = t0.saturating_add(Duration::from_secs_f64(seconds));
    let until = move |s: &crate::motion::MotionState| s.setpoint.time >= end;
    handle
        .wait_until(Condition::Predicate(Box::new(until)))
        .map_err(ctl_err)?;
    let wall = wall.elapsed();
    let simulated = handle.now().saturating_since(t0);
    egm.program_stopped(&mut handle).map_err(fail)?;
    let summary = handle.finish().map_err(ctl_err)?;
    egm.finish()?;
    Ok((summary.period_stats, simulated, wall))
}
