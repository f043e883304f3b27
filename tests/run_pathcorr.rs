//! `rapidvc run` with EGM path correction (EGMMoveL/EGMMoveC): the golden straight seam, the manual's example with its simulated LTAPP sensors, the error cases, a hostile UDP sensor, and the real clients `abb_robot_client` and `ABBRobotEGM` driving a correction session over loopback.
//!
//! The Python client tests need `RAPIDVC_PYTHON` when they are built, else they are ignored
//! (see `tests/egm_clients.rs`). Every child process is bounded by a
//! time-out and killed when its guard is dropped.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use rapidvc_testkit::csv;
use rapidvc_testkit::procs;
use rapidvc_testkit::rapidvc;

use std::path::PathBuf;
use std::time::Duration;

use csv::Csv;
use procs::{Ended, run_program};

const STRAIGHT: &str = "tests/run/pathcorr/straight.mod";
const ERRORS: &str = "tests/run/pathcorr/errors.mod";
const MANUAL: &str = "programs/manual/path_correction.mod";
const LIMIT: Duration = Duration::from_secs(120);

/// Where the straight seam ends: the programmed end (1400, 20, 500) moved by the seam offset
/// y = 3, z = −2 of the path frame (x = +X, tool z = −Z: y = +Y, z = +Z).
const CORRECTED_END: [f64; 3] = [1400.0, 23.0, 498.0];

/// The largest correction step one 4 ms cycle may make: 20 mm/s.
const MAX_STEP_MM: f64 = 0.08;

/// A trace file, read by column name.
struct Trace(Csv);

impl std::ops::Deref for Trace {
    type Target = Csv;

    fn deref(&self) -> &Csv {
        &self.0
    }
}

impl Trace {
    fn read(path: &std::path::Path) -> Trace {
        Trace(Csv::read(path))
    }

    fn num(&self, row: usize, name: &str) -> Option<f64> {
        self.rows[row][self.col(name)].parse().ok()
    }

    fn tcp(&self, row: usize) -> [f64; 3] {
        ["x", "y", "z"].map(|c| self.num(row, c).unwrap())
    }

    /// Rows with a path-correction sample: (row, path_s, corr_y, corr_z).
    fn corrections(&self) -> Vec<(usize, f64, f64, f64)> {
        (0..self.rows.len())
            .filter_map(|r| {
                Some((
                    r,
                    self.num(r, "path_s")?,
                    self.num(r, "corr_y")?,
                    self.num(r, "corr_z")?,
                ))
            })
            .collect()
    }
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rapidvc-pathcorr-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn args(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

/// The straight seam run in lockstep with the sensor on `port`, tracing to `trace`.
fn straight_in_lockstep(port: u16, trace: &std::path::Path) -> Ended {
    let device = format!("UCdevice=127.0.0.1:{port}");
    let trace = trace.to_str().unwrap();
    let args = args(&["--device", &device, "--lockstep", "--trace", trace]);
    run_program(rapidvc!(), STRAIGHT, &args, LIMIT)
}

/// `program` run to its end with the built-in sensor's seam offset y = 3, z = −2 on
/// UCdevice, traced to the temporary file `trace`.
fn with_seam_sensor(program: &str, trace: &str) -> (Ended, Trace) {
    let trace_path = temp(trace);
    let run = run_program(
        rapidvc!(),
        program,
        &args(&[
            "--device",
            "UCdevice=builtin:pathcorr:y=3,z=-2",
            "--trace",
            trace_path.to_str().unwrap(),
        ]),
        LIMIT,
    );
    ok(&run);
    (run, Trace::read(&trace_path))
}

fn ok(run: &Ended) {
    assert_eq!(run.code, Some(0), "{}\n{}", run.stdout, run.stderr);
}

/// The straight seam's end and smoothness (shared by the built-in and the client runs).
fn check_straight(trace: &Trace) {
    let last = trace.rows.len() - 1;
    let end = trace.tcp(last);
    assert!(
        dist(&end, &CORRECTED_END) < 0.2,
        "the TCP ends at {end:?}, not on the corrected path {CORRECTED_END:?}"
    );
    let corr = trace.corrections();
    let (_, s_end, y_end, z_end) = *corr.last().unwrap();
    assert!((s_end - 400.0).abs() < 1e-3, "path_s ends at {s_end}");
    assert!((y_end - 3.0).abs() < 1e-3 && (z_end + 2.0).abs() < 1e-3);
    // Ramped in, never stepping: consecutive cycles differ by at most 20 mm/s · 4 ms.
    let mut worst: f64 = 0.0;
    for w in corr.windows(2) {
        let (_, _, y0, z0) = w[0];
        let (_, _, y1, z1) = w[1];
        worst = worst.max((y1 - y0).hypot(z1 - z0));
    }
    // The trace rounds to 0.0001 mm.
    assert!(
        worst <= MAX_STEP_MM + 2e-4,
        "a correction step of {worst} mm"
    );
    assert!(
        worst > 0.5 * MAX_STEP_MM,
        "the correction ramps at its limit"
    );
    // Every corrected row is an EGMMoveL row.
    let instr = trace.col("instr");
    assert!(
        corr.iter()
            .all(|(r, ..)| trace.rows[*r][instr] == "EGMMoveL")
    );
}

/// Golden: 400 mm at v10 over a seam offset y = 3, z = −2 from the built-in sensor.
mod golden {
    use super::*;

    #[test]
    fn straight_seam_400_mm_at_v10_ends_on_the_corrected_path() {
        let (run, trace) = with_seam_sensor(STRAIGHT, "straight.csv");
        assert_eq!(run.stdout, "state after the fine point: 2\n");
        check_straight(&trace);
        // Golden rows: every 10th corrected cycle of the ramp-in, every 400th after it, the
        // last one.
        let corr = trace.corrections();
        let pick: Vec<usize> = corr
            .iter()
            .map(|(r, ..)| *r)
            .enumerate()
            .filter(|(k, _)| (*k < 100 && k % 10 == 0) || k % 400 == 0 || *k == corr.len() - 1)
            .map(|(_, r)| r)
            .collect();
        let cols = [
            "time_s",
            "x",
            "y",
            "z",
            "speed_mm_s",
            "instr",
            "egm_state",
            "path_s",
            "corr_y",
            "corr_z",
        ];
        let mut golden = cols.join(",");
        for r in pick {
            golden.push('\n');
            let row: Vec<&str> = cols
                .iter()
                .map(|c| trace.rows[r][trace.col(c)].as_str())
                .collect();
            golden.push_str(&row.join(","));
        }
        insta::assert_snapshot!("straight_seam", golden);
    }
}

/// StopMove/StartMove and SpeedRefresh during a corrected EGMMoveL hold and slow the path
/// without leaving the corrected seam. (Playing the path at a rate below 1 once started from
/// the corrected setpoint and ended the correction sequence at the hold: the robot swung
/// across the seam at 1,275 mm/s.)
#[test]
fn a_corrected_move_held_and_slowed_stays_on_the_corrected_seam() {
    let (_, trace) = with_seam_sensor("tests/run/pathcorr/held.mod", "held.csv");
    let instr = trace.col("instr");
    let rows: Vec<usize> = (0..trace.rows.len())
        .filter(|r| trace.rows[*r][instr] == "EGMMoveL")
        .collect();
    let speed = |r: usize| trace.num(r, "speed_mm_s").unwrap();
    let mut x_before = f64::NEG_INFINITY;
    for &r in &rows {
        let [x, y, z] = trace.tcp(r);
        assert!(speed(r) <= 102.0, "row {r}: {} mm/s at v100", speed(r));
        assert!(
            (20.0 - 1e-3..=23.0 + 1e-3).contains(&y) && (498.0 - 1e-3..=500.0 + 1e-3).contains(&z),
            "row {r}: off the seam at y {y}, z {z}"
        );
        assert!(
            x >= x_before - 1e-6,
            "row {r}: x went back from {x_before} to {x}"
        );
        x_before = x;
    }
    // Held at rest on the path for the TRAP's 0.5 s (4 ms cycles), later at half speed.
    let longest_rest = rows
        .iter()
        .fold((0, 0), |(run, best), &r| {
            let run = if speed(r) == 0.0 { run + 1 } else { 0 };
            (run, best.max(run))
        })
        .1;
    assert!(longest_rest >= 120, "held for {longest_rest} cycles");
    assert!(
        rows.iter().any(|&r| (speed(r) - 50.0).abs() < 0.5),
        "SpeedRefresh 50 plays the path at 50 mm/s"
    );
    let end = trace.tcp(*rows.last().unwrap());
    assert!(dist(&end, &CORRECTED_END) < 0.2, "ends at {end:?}");
}

/// The manual's example (§9.3.6.3) with one command and defaults.
mod manual {
    use super::*;

    /// The three procedures' corrected sequences: (largest |corr_y|, largest |corr_z|,
    /// final TCP) of each.
    fn sequences(trace: &Trace) -> Vec<(f64, f64, [f64; 3])> {
        let mut out: Vec<(f64, f64, [f64; 3])> = Vec::new();
        let mut last_s = f64::INFINITY;
        for (r, s, y, z) in trace.corrections() {
            if s < last_s {
                out.push((0.0, 0.0, [0.0; 3]));
            }
            last_s = s;
            let seq = out.last_mut().unwrap();
            seq.0 = seq.0.max(y.abs());
            seq.1 = seq.1.max(z.abs());
            seq.2 = trace.tcp(r);
        }
        out
    }

    #[test]
    fn the_manual_example_runs_all_three_procedures() {
        let trace_path = temp("manual.csv");
        let plot_path = temp("manual.svg");
        let run = run_program(
            rapidvc!(),
            MANUAL,
            &args(&[
                "--trace",
                trace_path.to_str().unwrap(),
                "--plot",
                plot_path.to_str().unwrap(),
            ]),
            LIMIT,
        );
        ok(&run);
        assert!(!run.stderr.contains("EGM egmId1"), "{}", run.stderr);
        let trace = Trace::read(&trace_path);
        let seqs = sequences(&trace);
        assert_eq!(seqs.len(), 3, "{seqs:?}");
        // OptSim: sine y = 2, z = 0.5 (look-ahead); wg1sim: ramp to y = 3, z = −1 (at
        // point); UCdevice: the built-in sensor, zero correction.
        let [(y1, z1, _), (y2, z2, end2), (y3, z3, end3)] = [seqs[0], seqs[1], seqs[2]];
        assert!(
            (y1 - 2.0).abs() < 0.01 && (z1 - 0.5).abs() < 0.01,
            "{seqs:?}"
        );
        assert!(
            (y2 - 3.0).abs() < 0.01 && (z2 - 1.0).abs() < 0.01,
            "{seqs:?}"
        );
        assert!(y3 == 0.0 && z3 == 0.0, "{seqs:?}");
        // The seam runs along +y; the path frame's y is then −X and z is +Z. With PDispSet
        // [0,−3,2], p170 (1000, 450, 500) is at (1000, 447, 502); wg1sim ends 3 mm along
        // −X and 1 mm down.
        assert!(dist(&end2, &[997.0, 447.0, 501.0]) < 0.2, "{end2:?}");
        assert!(dist(&end3, &[1000.0, 447.0, 502.0]) < 0.2, "{end3:?}");
        let svg = std::fs::read_to_string(&plot_path).unwrap();
        assert!(svg.contains("Path correction in the path frame"));
    }
}

/// Errors a program can meet (tests/run/pathcorr/errors.mod, one procedure each).
mod errors {
    use super::*;

    fn entry(name: &str, extra: &[&str]) -> Ended {
        let mut a = args(&["--entry", name]);
        a.extend(args(extra));
        run_program(rapidvc!(), ERRORS, &a, LIMIT)
    }

    fn fails_with(run: &Ended, text: &str) {
        assert_eq!(run.code, Some(1), "{}\n{}", run.stdout, run.stderr);
        let flat = run
            .stderr
            .lines()
            .map(|l| l.trim_start_matches([' ', '│', '×']).trim_end())
            .collect::<Vec<_>>()
            .join(" ");
        assert!(flat.contains(text), "expected `{text}` in\n{}", run.stderr);
    }

    #[test]
    fn egm_move_l_without_egm_act_move() {
        fails_with(
            &entry("no_act_move", &[]),
            "90123 EGM identity not activated: EGMMoveL egmId1: the identity is not activated; run EGMActMove first",
        );
    }

    #[test]
    fn the_sequence_must_start_in_a_fine_point() {
        fails_with(
            &entry("start_not_fine", &[]),
            "90128 EGM movement not started in a fine point: EGMMoveL egmId1: EGM Path correction has to start and end in a fine point",
        );
    }

    #[test]
    fn the_sequence_must_end_in_a_fine_point() {
        let run = entry("end_not_fine", &[]);
        fails_with(
            &run,
            "90131 EGM path correction not ended in a fine point: MoveL egmId1: EGM Path correction has to start and end in a fine point",
        );
        assert_eq!(run.stderr.matches("90131").count(), 1, "{}", run.stderr);
    }

    #[test]
    fn a_sample_rate_that_is_not_a_multiple_of_24_ms() {
        fails_with(
            &entry("bad_rate", &[]),
            "EGMActMove: \\SampleRate:=50 is not allowed; use a multiple of 24 ms",
        );
    }

    #[test]
    fn no_corr_ramps_the_correction_out() {
        let trace_path = temp("no_corr.csv");
        let run = entry(
            "no_corr",
            &[
                "--device",
                "UCdevice=builtin:pathcorr:y=2",
                "--trace",
                trace_path.to_str().unwrap(),
            ],
        );
        ok(&run);
        let trace = Trace::read(&trace_path);
        let corr = trace.corrections();
        // Before the corner into the \NoCorr move (z5 at 100 mm) the correction is in full.
        let at_mid = corr.iter().find(|(_, s, ..)| *s >= 90.0).unwrap();
        assert!((at_mid.2 - 2.0).abs() < 1e-3, "{at_mid:?}");
        let (r, _, y, z) = *corr.last().unwrap();
        assert!(y == 0.0 && z == 0.0);
        assert!(dist(&trace.tcp(r), &[1200.0, 20.0, 500.0]) < 1e-3);
    }

    #[test]
    fn absurd_corrections_are_rejected_with_an_event() {
        let run = run_program(
            rapidvc!(),
            STRAIGHT,
            &args(&["--device", "UCdevice=builtin:pathcorr:y=500,z=0"]),
            LIMIT,
        );
        ok(&run);
        assert!(
            run.stderr.contains(
                "EGM egmId1: 90132 EGM path correction rejected: path correction of 500.000 mm exceeds the limit of 100 mm; the previous correction stays in force"
            ),
            "{}",
            run.stderr
        );
        // Reported about once a second of the 40 s move, not for each of its 800 messages.
        let n = run.stderr.matches("90132").count();
        assert!((35..=45).contains(&n), "{n}: {}", run.stderr);
    }
}

/// Sensors on real UDP sockets driven by the test itself (lockstep).
mod udp {
    use super::*;
    use prost::Message;
    use rapidvc::egm::proto::{
        EgmCartesian, EgmHeader, EgmPathCorr, EgmRobot, EgmSensorPathCorr, egm_header::MessageType,
    };
    use std::net::UdpSocket;

    /// A path-correction sensor answering every message with `y(n), z(n)` for the n-th
    /// message (n from 0); it stops after `quiet` without messages. Returns the port.
    fn sensor(
        reply: impl Fn(u32) -> (f64, f64) + Send + 'static,
        quiet: Duration,
    ) -> (u16, std::thread::JoinHandle<u32>) {
        let sock = UdpSocket::bind("127.0.0.1:0").unwrap();
        sock.set_read_timeout(Some(quiet)).unwrap();
        let port = sock.local_addr().unwrap().port();
        let h = std::thread::spawn(move || {
            let mut buf = [0u8; 2048];
            let mut n = 0u32;
            let mut first = true;
            loop {
                let Ok((len, src)) = sock.recv_from(&mut buf) else {
                    if first {
                        continue;
                    }
                    return n;
                };
                first = false;
                assert!(EgmRobot::decode(&buf[..len]).is_ok());
                let (y, z) = reply(n);
                let msg = EgmSensorPathCorr {
                    header: Some(EgmHeader {
                        seqno: Some(n),
                        tm: None,
                        mtype: Some(MessageType::MsgtypePathCorrection as i32),
                    }),
                    path_corr: Some(EgmPathCorr {
                        pos: EgmCartesian { x: 0.0, y, z },
                        age: 1,
                    }),
                };
                sock.send_to(&msg.encode_to_vec(), src).unwrap();
                n += 1;
            }
        });
        (port, h)
    }

    #[test]
    fn nan_corrections_are_dropped_with_an_event() {
        // NaN for the first 20 messages (about 1 s), then the seam.
        let (port, h) = sensor(
            |n| if n < 20 { (f64::NAN, 0.0) } else { (3.0, -2.0) },
            Duration::from_secs(2),
        );
        let trace_path = temp("nan.csv");
        let run = straight_in_lockstep(port, &trace_path);
        ok(&run);
        assert!(
            run.stderr
                .contains("EGM egmId1: 90104 Invalid EGM reference"),
            "{}",
            run.stderr
        );
        assert!(h.join().unwrap() > 800);
        let trace = Trace::read(&trace_path);
        check_straight(&trace);
    }

    #[test]
    fn a_sensor_that_stops_answering_gives_err_udpuc_comm() {
        let silent = UdpSocket::bind("127.0.0.1:0").unwrap();
        let port = silent.local_addr().unwrap().port();
        let run = run_program(
            rapidvc!(),
            ERRORS,
            &args(&[
                "--entry",
                "silent_sensor",
                "--device",
                &format!("UCdevice=127.0.0.1:{port}"),
                "--lockstep",
                "--lockstep-timeout",
                "20",
            ]),
            LIMIT,
        );
        ok(&run);
        assert_eq!(run.stdout, "ERR_UDPUC_COMM handled\nmoved on\n");
        assert!(
            run.stderr.contains(
                "41822 No data from the UdpUc device: no data from UdpUc device \"UCdevice\" within \\CommTimeout 500.00ms"
            ),
            "{}",
            run.stderr
        );
        drop(silent);
    }
}

/// The PyPI clients' own path-correction call drives the correction session.
mod clients {
    use super::*;
    use procs::{json_field, python, start_script};

    fn session(client: &str) {
        let py = python();
        let (sensor, port) = start_script(
            &py,
            "pathcorr_sensor.py",
            &[
                "--client",
                client,
                "--y",
                "3",
                "--z",
                "-2",
                "--until-quiet",
                "1",
                "--timeout",
                "90",
            ],
        );
        let trace_path = temp(&format!("{client}.csv"));
        let run = straight_in_lockstep(port, &trace_path);
        let c = sensor.wait(Duration::from_secs(30));
        ok(&run);
        assert!(!run.stderr.contains("41822"), "{}", run.stderr);
        let summary = c.stdout.lines().last().unwrap_or_default().to_string();
        assert_eq!(c.code, Some(0), "{client}: {summary}\n{}", c.stderr);
        assert_eq!(json_field(&summary, "well_formed"), "true", "{summary}");
        let received: u32 = json_field(&summary, "received").parse().unwrap();
        // 400 mm at 10 mm/s, one message per 48 ms.
        assert!((820..=880).contains(&received), "{summary}");
        assert_eq!(json_field(&summary, "replied"), received.to_string());
        assert_eq!(json_field(&summary, "first_seqno"), "0", "{summary}");
        assert_eq!(json_field(&summary, "seqno_gaps"), "0", "{summary}");
        check_straight(&Trace::read(&trace_path));
    }

    #[test]
    #[cfg_attr(
        not(rapidvc_python),
        ignore = "needs RAPIDVC_PYTHON (a Python with abb_robot_client and ABBRobotEGM) when the tests are built"
    )]
    fn abb_robot_client_send_to_robot_path_corr() {
        session("abb_robot_client");
    }

    #[test]
    #[cfg_attr(
        not(rapidvc_python),
        ignore = "needs RAPIDVC_PYTHON (a Python with abb_robot_client and ABBRobotEGM) when the tests are built"
    )]
    fn abbrobotegm_send_to_robot_path_corr() {
        session("ABBRobotEGM");
    }
}
