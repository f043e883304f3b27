//! Every way an EGM run ends brings the robot to rest from the speed it has: checked on the `--trace` rows of `rapidvc run` (per-cycle joint speeds and accelerations) and the `--egm-log` (the cycle the stop began, the last reference). A property over the reference, `\MaxSpeedDeviation`, `\RampInTime` and the moment of the stop for each end cause — EGMStop HOLD and RAMP_DOWN, convergence with either stop mode, a program `Stop` from a TRAP, `EGMReset`, a run-time error, `--max-time`, the end of the program after `\NoWaitCond`, and a sensor that falls silent (41822) — plus the reproductions of issue 10.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::needless_range_loop
)]

use rapidvc_testkit::csv;
use rapidvc_testkit::egm_wire;
use rapidvc_testkit::procs;
use rapidvc_testkit::rapidvc;

use std::net::UdpSocket;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use csv::Csv;
use egm_wire::joint_reply;
use proptest::prelude::*;
use prost::Message;
use rapidvc::egm::proto;
use rapidvc::robot::Robot;

const LIMIT: Duration = Duration::from_secs(120);
/// The motion cycle, s.
const DT: f64 = 0.004;
/// Where every run starts (`home` of the programs).
const HOME: [f64; 6] = [0.0, 0.0, 0.0, 0.0, 30.0, 0.0];
/// Speed tolerance, °/s: the trace prints 6 decimals (±5e-7° per value, ±2.5e-4 °/s).
const TOL_V: f64 = 1e-3;
/// Acceleration tolerance, °/s² (±0.25 °/s² from the printed digits).
const TOL_A: f64 = 1.0;

/// How the run ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum End {
    /// `EGMStop egm1, EGM_STOP_HOLD` in a TRAP.
    StopHold,
    /// `EGMStop egm1, EGM_STOP_RAMP_DOWN \RampOutTime:=0.3` in a TRAP.
    StopRampDown,
    /// Convergence held for `\CondTime`, stop mode HOLD.
    ConvergedHold,
    /// Convergence held for `\CondTime`, stop mode RAMP_DOWN.
    ConvergedRampDown,
    /// `Stop` in a TRAP.
    ProgramStop,
    /// `EGMReset egm1` in a TRAP.
    Reset,
    /// A division by zero in a TRAP (an unhandled run-time error).
    Error,
    /// `--max-time` reached while EGMRunJoint waits.
    MaxTime,
    /// `\NoWaitCond`, `WaitTime`, end of the program.
    Finish,
    /// The external sensor falls silent: `\CommTimeout` (41822), in lockstep.
    CommTimeout,
}

impl End {
    fn converges(self) -> bool {
        matches!(self, End::ConvergedHold | End::ConvergedRampDown)
    }

    fn returns_to_start(self) -> bool {
        matches!(self, End::StopRampDown | End::ConvergedRampDown)
    }

    fn exit_code(self) -> i32 {
        match self {
            End::Error | End::MaxTime => 1,
            _ => 0,
        }
    }
}

/// One generated run.
#[derive(Clone, Debug)]
struct Case {
    end: End,
    /// The sensor's joint reference.
    reference: [f64; 6],
    /// `\MaxSpeedDeviation`, °/s.
    msd: f64,
    /// `\RampInTime`, s.
    ramp_in: f64,
    /// When the stop comes, s after EGMRunJoint started (TRAP, `--max-time`, end of
    /// program, the sensor's last reply).
    halt: f64,
}

fn program(case: &Case) -> String {
    let (mode, cond) = match case.end {
        End::ConvergedHold => ("EGM_STOP_HOLD", "0.1"),
        End::ConvergedRampDown => ("EGM_STOP_RAMP_DOWN \\RampOutTime:=0.2", "0.1"),
        _ => ("EGM_STOP_HOLD", "9E9"),
    };
    let trap = match case.end {
        End::StopHold => "EGMStop egm1, EGM_STOP_HOLD;",
        End::StopRampDown => "EGMStop egm1, EGM_STOP_RAMP_DOWN \\RampOutTime:=0.3;",
        End::ProgramStop => "Stop;",
        End::Reset => "EGMReset egm1;",
        End::Error => "x := 1 / zero;",
        _ => "",
    };
    let timer = if trap.is_empty() {
        String::new()
    } else {
        format!(
            "CONNECT tmr WITH ender;\n  ITimer \\Single, {:.3}, tmr;",
            case.halt
        )
    };
    let (no_wait, after) = match case.end {
        End::Finish => (" \\NoWaitCond", format!("WaitTime {:.3};", case.halt)),
        _ => ("", String::new()),
    };
    format!(
        "MODULE HaltCase
VAR egmident egm1;
VAR intnum tmr;
VAR num x;
VAR num zero := 0;
CONST jointtarget home := [[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
CONST egm_minmax win := [-0.1,0.1];
PROC main()
  MoveAbsJ home, v1000, fine, tool0;
  EGMGetId egm1;
  EGMSetupUC ROB_1, egm1, \"default\", \"sensor\" \\Joint \\CommTimeout:=0.1;
  EGMActJoint egm1 \\J1:=win \\J2:=win \\J3:=win \\J4:=win \\J5:=win \\J6:=win \\MaxSpeedDeviation:={msd};
  {timer}
  EGMRunJoint egm1, {mode}{no_wait} \\J1 \\J2 \\J3 \\J4 \\J5 \\J6 \\CondTime:={cond} \\RampInTime:={ramp};
  {after}
  TPWrite \"after the run\";
ERROR
  IF ERRNO = ERR_UDPUC_COMM THEN
    TPWrite \"ERR_UDPUC_COMM\";
    TRYNEXT;
  ENDIF
ENDPROC
TRAP ender
  {trap}
ENDTRAP
ENDMODULE
",
        msd = case.msd,
        ramp = case.ramp_in,
    )
}

/// A sensor on 127.0.0.1 that answers the first `answers` messages with `reference`, then
/// stays silent; it ends when told or after 2 s without messages.
struct SilentSensor {
    port: u16,
    stop: Arc<AtomicBool>,
    received: Arc<AtomicU64>,
    thread: Option<JoinHandle<()>>,
}

impl SilentSensor {
    fn start(answers: u64, reference: [f64; 6]) -> SilentSensor {
        let sock = UdpSocket::bind("127.0.0.1:0").unwrap();
        sock.set_read_timeout(Some(Duration::from_millis(50)))
            .unwrap();
        let port = sock.local_addr().unwrap().port();
        let stop = Arc::new(AtomicBool::new(false));
        let received = Arc::new(AtomicU64::new(0));
        let (stop2, received2) = (Arc::clone(&stop), Arc::clone(&received));
        let thread = std::thread::spawn(move || {
            let mut buf = [0u8; 2048];
            let mut last = Instant::now();
            while !stop2.load(Ordering::Relaxed) && last.elapsed() < Duration::from_secs(30) {
                let Ok((n, src)) = sock.recv_from(&mut buf) else {
                    continue;
                };
                last = Instant::now();
                let Ok(m) = proto::EgmRobot::decode(&buf[..n]) else {
                    continue;
                };
                let k = received2.fetch_add(1, Ordering::Relaxed) + 1;
                if k <= answers {
                    let seq = m.header.and_then(|h| h.seqno).unwrap_or(0);
                    sock.send_to(&joint_reply(seq, reference), src).unwrap();
                }
            }
        });
        SilentSensor {
            port,
            stop,
            received,
            thread: Some(thread),
        }
    }
}

impl Drop for SilentSensor {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// A scratch directory, removed on drop.
struct Scratch(PathBuf);

impl Scratch {
    fn new() -> Scratch {
        static N: AtomicU64 = AtomicU64::new(0);
        let dir = std::env::temp_dir().join(format!(
            "rapidvc-egm-halt-{}-{}",
            std::process::id(),
            N.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// What a run left behind.
struct Outcome {
    ended: procs::Ended,
    trace: Vec<Row>,
    log: Vec<LogRow>,
}

/// One trace row.
struct Row {
    t: f64,
    q: [f64; 6],
    egm: String,
    instr: String,
}

/// One `--egm-log` row.
struct LogRow {
    t: f64,
    reference: Option<[f64; 6]>,
    state: String,
}

fn six(row: &[String], first: usize) -> Option<[f64; 6]> {
    let v: Vec<f64> = row[first..first + 6]
        .iter()
        .map(|s| s.parse::<f64>())
        .collect::<Result<_, _>>()
        .ok()?;
    v.try_into().ok()
}

fn read_trace(path: &Path) -> Vec<Row> {
    let c = Csv::read(path);
    let (t, j1, egm, instr) = (
        c.col("time_s"),
        c.col("j1"),
        c.col("egm_state"),
        c.col("instr"),
    );
    c.rows
        .iter()
        .map(|r| Row {
            t: r[t].parse().unwrap(),
            q: six(r, j1).unwrap(),
            egm: r[egm].clone(),
            instr: r[instr].clone(),
        })
        .collect()
}

fn read_log(path: &Path) -> Vec<LogRow> {
    let c = Csv::read(path);
    let (t, r1, state) = (c.col("send_time_s"), c.col("ref_1"), c.col("state"));
    c.rows
        .iter()
        .map(|r| LogRow {
            t: r[t].parse().unwrap(),
            reference: six(r, r1),
            state: r[state].clone(),
        })
        .collect()
}

/// Runs `program` with `args`, the trace and the EGM log.
fn run(program: &str, args: &[String]) -> Outcome {
    let dir = Scratch::new();
    let file = dir.0.join("halt.mod");
    std::fs::write(&file, program).unwrap();
    let (trace, log) = (dir.0.join("t.csv"), dir.0.join("l.csv"));
    let mut all = vec![
        format!("--trace={}", trace.display()),
        format!("--egm-log={}", log.display()),
    ];
    all.extend_from_slice(args);
    let ended = procs::run_program(rapidvc!(), file.to_str().unwrap(), &all, LIMIT);
    Outcome {
        trace: read_trace(&trace),
        log: read_log(&log),
        ended,
    }
}

fn run_case(case: &Case) -> Outcome {
    let text = program(case);
    let pattern = case.reference.map(|v| format!("{v}")).join(",");
    match case.end {
        End::CommTimeout => {
            let answers = (case.halt / DT).round().max(1.0) as u64;
            let sensor = SilentSensor::start(answers, case.reference);
            let out = run(
                &text,
                &[
                    format!("--device=sensor=127.0.0.1:{}", sensor.port),
                    "--lockstep".into(),
                    "--lockstep-timeout=20".into(),
                ],
            );
            assert!(sensor.received.load(Ordering::Relaxed) > 0);
            out
        }
        End::MaxTime => run(
            &text,
            &[
                format!("--device=sensor=builtin:joint:{pattern}"),
                format!("--max-time={:.3}", 0.3 + case.halt),
            ],
        ),
        _ => run(&text, &[format!("--device=sensor=builtin:joint:{pattern}")]),
    }
}

fn speed(a: &Row, b: &Row) -> [f64; 6] {
    let mut v = [0.0; 6];
    for (i, v) in v.iter_mut().enumerate() {
        *v = (b.q[i] - a.q[i]) / DT;
    }
    v
}

/// The checks of every end (see the module docs); `Err` says what went wrong where. The
/// log's references are joints unless `pose` (then the reference check is left out).
fn check(out: &Outcome, msd: f64, returns_to_start: bool, pose: bool) -> Result<(), String> {
    let robot = Robot::default();
    let accel = robot.model().max_accel;
    let slowest = robot
        .model()
        .max_speed
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    let msd = msd.min(slowest);
    let rows = &out.trace;
    let first = rows
        .iter()
        .position(|r| r.egm == "RUNNING")
        .ok_or("the run never started")?;
    let last = rows
        .iter()
        .rposition(|r| r.egm == "RUNNING")
        .unwrap_or(first);
    let end = (last + 1).min(rows.len() - 1);
    // 1. No cycle of the run, its stop included, is faster than MaxSpeedDeviation.
    for i in first.max(1)..=end {
        let v = speed(&rows[i - 1], &rows[i]);
        if let Some(j) = (0..6).find(|&j| v[j].abs() > msd + TOL_V) {
            return Err(format!(
                "J{} at {:.3} °/s at t={:.3} exceeds MaxSpeedDeviation {msd}",
                j + 1,
                v[j],
                rows[i].t
            ));
        }
    }
    // 2. The stop: the first message whose state is not `running`.
    let stop = out
        .log
        .iter()
        .find(|r| r.state != "running")
        .ok_or("no stop in the EGM log")?;
    let reference = out
        .log
        .iter()
        .filter(|r| r.t < stop.t - 1e-9)
        .filter_map(|r| r.reference)
        .next_back()
        .filter(|_| !pose);
    let s = rows
        .iter()
        .position(|r| (r.t - stop.t).abs() < 1e-7)
        .ok_or(format!("no trace row at the stop t={}", stop.t))?;
    if s < 2 {
        return Err("the stop came before the run moved".into());
    }
    // 3. From the stop on, no axis accelerates beyond its limit.
    for i in s..=end {
        let (v0, v1) = (
            speed(&rows[i - 2], &rows[i - 1]),
            speed(&rows[i - 1], &rows[i]),
        );
        for j in 0..6 {
            let a = (v1[j] - v0[j]) / DT;
            if a.abs() > accel[j] * (1.0 + 1e-6) + TOL_A {
                return Err(format!(
                    "J{} accelerates at {a:.1} °/s² at t={:.3} (limit {}): {:.4} → {:.4} °/s",
                    j + 1,
                    rows[i].t,
                    accel[j],
                    v0[j],
                    v1[j]
                ));
            }
        }
    }
    // 4. It decelerates from the speed it had, never speeding up or reversing, to rest,
    //    and rests at or before the last reference.
    let at = rows[s - 1].q;
    let mut previous = speed(&rows[s - 2], &rows[s - 1]);
    let dir = previous.map(f64::signum);
    let mut rest = None;
    for i in s..=end {
        let v = speed(&rows[i - 1], &rows[i]);
        for j in 0..6 {
            if v[j] * previous[j] < -TOL_V * TOL_V || v[j].abs() > previous[j].abs() + TOL_V {
                return Err(format!(
                    "J{} speeds up or reverses while stopping at t={:.3}: {:.4} → {:.4} °/s",
                    j + 1,
                    rows[i].t,
                    previous[j],
                    v[j]
                ));
            }
            if let Some(r) = reference {
                let ahead = (r[j] - at[j]) * dir[j];
                let gone = (rows[i].q[j] - at[j]) * dir[j];
                if ahead > 0.0 && gone > ahead + 1e-5 {
                    return Err(format!(
                        "J{} passed the last reference {} while stopping: {} at t={:.3}",
                        j + 1,
                        r[j],
                        rows[i].q[j],
                        rows[i].t
                    ));
                }
            }
        }
        previous = v;
        if v.iter().all(|x| *x == 0.0) {
            rest = Some(i);
            break;
        }
    }
    let rest = rest.ok_or("the robot never came to rest")?;
    // 5. RAMP_DOWN then returns to the start; everything else stays where it stopped.
    let last_q = rows[rows.len() - 1].q;
    let expected = if returns_to_start { HOME } else { rows[rest].q };
    if last_q
        .iter()
        .zip(&expected)
        .any(|(a, b)| (a - b).abs() > 1e-5)
    {
        return Err(format!(
            "the run ended at {last_q:?}, not at {expected:?} (returns to start: {returns_to_start})"
        ));
    }
    Ok(())
}

fn check_case(case: &Case) -> Result<(), String> {
    let out = run_case(case);
    let code = out.ended.code;
    if code != Some(case.end.exit_code()) {
        return Err(format!(
            "exit {code:?}, expected {}\n{}\n{}",
            case.end.exit_code(),
            out.ended.stdout,
            out.ended.stderr
        ));
    }
    if out.ended.stderr.contains("exceeds its maximum") {
        return Err(format!("a motion supervision error:\n{}", out.ended.stderr));
    }
    check(&out, case.msd, case.end.returns_to_start(), false)
        .map_err(|e| format!("{e}\n{}\n{}", out.ended.stdout, out.ended.stderr))
}

fn case(end: End) -> impl Strategy<Value = Case> {
    // Converging runs get nearer targets and faster limits so they end in a few seconds.
    let (reach, msd_min) = if end.converges() {
        (20.0f64, 5.0f64)
    } else {
        (50.0, 1.0)
    };
    (
        proptest::array::uniform6(-reach..reach),
        msd_min..175.0f64,
        prop_oneof![Just(0.0), 0.0..2.0f64],
        0.02..1.5f64,
    )
        .prop_map(
            move |(offset, msd, ramp_in, halt): ([f64; 6], f64, f64, f64)| {
                let mut reference = HOME;
                for (r, o) in reference.iter_mut().zip(offset) {
                    *r += (o * 1000.0_f64).round() / 1000.0;
                }
                Case {
                    end,
                    reference,
                    msd: (msd * 10.0).round() / 10.0,
                    ramp_in: (ramp_in * 100.0).round() / 100.0,
                    halt: (halt * 1000.0).round() / 1000.0,
                }
            },
        )
}

macro_rules! every_end {
    ($($name:ident: $end:expr, $cases:expr;)*) => {
        $(
            proptest! {
                #![proptest_config(ProptestConfig {
                    cases: $cases,
                    failure_persistence: None,
                    ..ProptestConfig::default()
                })]
                #[test]
                fn $name(c in case($end)) {
                    if let Err(e) = check_case(&c) {
                        prop_assert!(false, "{:?}: {}", c, e);
                    }
                }
            }
        )*
    };
}

every_end! {
    egm_stop_hold_brakes_within_the_limits: End::StopHold, 8;
    egm_stop_ramp_down_brakes_then_returns_within_the_limits: End::StopRampDown, 8;
    convergence_with_hold_brakes_within_the_limits: End::ConvergedHold, 6;
    convergence_with_ramp_down_returns_within_the_limits: End::ConvergedRampDown, 6;
    program_stop_from_a_trap_brakes_within_the_limits: End::ProgramStop, 8;
    egm_reset_brakes_within_the_limits: End::Reset, 6;
    a_run_time_error_brakes_within_the_limits: End::Error, 6;
    max_time_brakes_within_the_limits: End::MaxTime, 6;
    the_end_of_the_program_brakes_within_the_limits: End::Finish, 6;
    a_comm_timeout_brakes_within_the_limits: End::CommTimeout, 6;
}

/// The reproductions of issue 10.
mod issue {
    use super::*;

    fn trap_stop(reference: [f64; 6]) -> Case {
        Case {
            end: End::ProgramStop,
            reference,
            msd: 10.0,
            ramp_in: 2.0,
            halt: 0.3,
        }
    }

    /// `\MaxSpeedDeviation:=10`, `\RampInTime:=2`, target `10,-5,20,0,40,30`, a TRAP `Stop`
    /// after 0.3 s: j6 moved at most 10 °/s before the stop and jumped to 136 °/s after it,
    /// ending past the reference.
    #[test]
    fn a_program_stop_from_a_trap_never_speeds_the_robot_up() {
        let case = trap_stop([10.0, -5.0, 20.0, 0.0, 40.0, 30.0]);
        check_case(&case).unwrap();
    }

    /// The same with J1 = 60: the halt tripped "joint 1 speed … exceeds its maximum" and the
    /// run exited 1 although the program ended by `Stop`.
    #[test]
    fn a_program_stop_with_a_far_target_ends_by_stop_with_exit_0() {
        let case = trap_stop([60.0, -5.0, 20.0, 0.0, 40.0, 30.0]);
        let out = run_case(&case);
        assert_eq!(out.ended.code, Some(0), "{}", out.ended.stderr);
        assert!(out.ended.stderr.contains("program stopped (Stop)"));
        assert!(!out.ended.stderr.contains("exceeds its maximum"));
        check(&out, case.msd, false, false).unwrap();
    }

    /// An external sensor that falls silent: at the time-out j6 jumped from 10 to 97.6 °/s.
    #[test]
    fn a_sensor_that_falls_silent_stops_the_robot_from_its_speed() {
        let case = Case {
            end: End::CommTimeout,
            reference: [10.0, -5.0, 20.0, 0.0, 40.0, 30.0],
            msd: 10.0,
            ramp_in: 2.0,
            halt: 1.0,
        };
        let out = run_case(&case);
        assert_eq!(out.ended.code, Some(0), "{}", out.ended.stderr);
        assert!(out.ended.stdout.contains("ERR_UDPUC_COMM"));
        check(&out, case.msd, false, false).unwrap();
    }

    /// EGMRunPose halts the same way: a circling pose target, a TRAP `Stop` during the
    /// ramp-in (J2 jumped from 12 to 35 °/s, beyond MaxSpeedDeviation 20).
    #[test]
    fn a_pose_run_stopped_from_a_trap_brakes_within_the_limits() {
        let text = "MODULE PoseHalt
VAR egmident egm1;
VAR intnum tmr;
CONST jointtarget home := [[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
CONST pose world := [[0,0,0],[1,0,0,0]];
PROC main()
  MoveAbsJ home, v1000, fine, tool0;
  EGMGetId egm1;
  EGMSetupUC ROB_1, egm1, \"default\", \"sensor\" \\Pose;
  EGMActPose egm1 \\Tool:=tool0 \\WObj:=wobj0, world, EGM_FRAME_WORLD, world, EGM_FRAME_WORLD
    \\MaxSpeedDeviation:=20;
  CONNECT tmr WITH ender;
  ITimer \\Single, 0.7, tmr;
  EGMRunPose egm1, EGM_STOP_HOLD \\x \\y \\z \\rx \\ry \\rz \\CondTime:=9E9 \\RampInTime:=2;
ENDPROC
TRAP ender
  Stop;
ENDTRAP
ENDMODULE
";
        let out = run(
            text,
            &["--device=sensor=builtin:circle:radius=80,frequency=0.5".to_string()],
        );
        assert_eq!(out.ended.code, Some(0), "{}", out.ended.stderr);
        assert!(out.ended.stderr.contains("program stopped (Stop)"));
        check(&out, 20.0, false, true).unwrap();
    }
}

/// Path correction (EGMMoveL): a sensor that falls silent and a program stop both used to
/// freeze the robot from path speed in one cycle; it brakes within the axis accelerations.
mod path_correction {
    use super::*;

    const PROGRAM: &str = "MODULE PathStop
  PERS tooldata tTorch := [TRUE,[[0,0,200],[1,0,0,0]],[1,[0,0,100],[1,0,0,0],0,0,0]];
  VAR egmident egmId1;
  VAR intnum tmr;
  CONST robtarget pStart := [[1000,20,500],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  CONST robtarget pEnd := [[1400,20,500],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
  PROC main()
    EGMGetId egmId1;
    EGMSetupUC ROB_1, egmId1, \"pathCorr\", \"UCdevice\" \\PathCorr \\APTR \\CommTimeout:=0.5;
    EGMActMove egmId1, tTorch.tframe;
    MoveJ pStart, v1000, fine, tTorch;
    STOP_TIMER
    EGMMoveL egmId1, pEnd, v200, fine, tTorch;
    TPWrite \"not reached\";
  ERROR
    IF ERRNO = ERR_UDPUC_COMM THEN
      TPWrite \"ERR_UDPUC_COMM handled\";
      RETURN;
    ENDIF
  ENDPROC
  TRAP stopper
    Stop;
  ENDTRAP
ENDMODULE
";

    /// From the last cycle of the EGMMoveL at its path speed on: every axis slows down
    /// within its acceleration to rest, never speeding up.
    fn check_brake(out: &Outcome) {
        let accel = Robot::default().model().max_accel;
        let rows = &out.trace;
        let speed = |i: usize| speed(&rows[i - 1], &rows[i]);
        let norm = |v: [f64; 6]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let corrected: Vec<usize> = (1..rows.len())
            .filter(|i| rows[*i].instr == "EGMMoveL")
            .collect();
        let cruise = corrected
            .iter()
            .map(|i| norm(speed(*i)))
            .fold(0.0, f64::max);
        let s = *corrected
            .iter()
            .rfind(|i| norm(speed(**i)) >= 0.98 * cruise)
            .unwrap();
        assert!(
            s + 1 < rows.len(),
            "the trace ends at path speed: the robot was frozen in one cycle"
        );
        let mut previous = speed(s);
        for i in s + 1..rows.len() {
            let v = speed(i);
            for j in 0..6 {
                let a = (v[j] - previous[j]) / DT;
                assert!(
                    a.abs() <= accel[j] * (1.0 + 1e-6) + TOL_A,
                    "J{} at {a:.0} °/s² at t={:.3}: {:.3} → {:.3} °/s",
                    j + 1,
                    rows[i].t,
                    previous[j],
                    v[j]
                );
                assert!(
                    v[j].abs() <= previous[j].abs() + TOL_V,
                    "J{} speeds up",
                    j + 1
                );
            }
            previous = v;
        }
        assert_eq!(previous, [0.0; 6], "at rest at the end");
    }

    /// Runs the program with `timer` (the TRAP's ITimer, or nothing) and `args`.
    fn run_path(timer: &str, args: &[String]) -> Outcome {
        let text = PROGRAM.replace("STOP_TIMER", timer);
        let config = procs::root().join("tests/run/pathcorr");
        let mut all = vec![format!("--config={}", config.display())];
        all.extend_from_slice(args);
        run(&text, &all)
    }

    #[test]
    fn a_sensor_that_falls_silent_brakes_the_corrected_move() {
        let dead = UdpSocket::bind("127.0.0.1:0").unwrap();
        let port = dead.local_addr().unwrap().port();
        let out = run_path(
            "",
            &[
                format!("--device=UCdevice=127.0.0.1:{port}"),
                "--lockstep".into(),
                "--lockstep-timeout=5".into(),
            ],
        );
        drop(dead);
        assert_eq!(out.ended.code, Some(0), "{}", out.ended.stderr);
        assert!(out.ended.stdout.contains("ERR_UDPUC_COMM handled"));
        check_brake(&out);
    }

    #[test]
    fn a_program_stop_brakes_the_corrected_move() {
        let out = run_path(
            "CONNECT tmr WITH stopper;\n    ITimer \\Single, 1, tmr;",
            &["--device=UCdevice=builtin:pathcorr:y=3,z=-2".into()],
        );
        assert_eq!(out.ended.code, Some(0), "{}", out.ended.stderr);
        assert!(out.ended.stderr.contains("program stopped (Stop)"));
        check_brake(&out);
    }
}
