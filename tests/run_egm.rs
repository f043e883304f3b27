//! EGM through `rapidvc run`: the manual's examples with one command, the failure modes as RAPID sees them, `\NoWaitCond`/EGMWaitCond/EGMStop, position streams to a UDP receiver, trace and `--egm-log` output, and a hostile sensor (garbage datagrams, NaN and out-of-range references, a second sender, silence) against which the session survives or ends with ERR_UDPUC_COMM and the robot never leaves its limits. Every test ends by itself (bounded waits, children killed on drop).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use rapidvc_testkit::egm_wire;
use rapidvc_testkit::procs;
use rapidvc_testkit::rapidvc;

use std::net::{SocketAddr, UdpSocket};
use std::time::{Duration, Instant};

use egm_wire::joint_reply;
use procs::{Ended, near, printed, run_program};
use prost::Message;
use rapidvc::egm::proto;

const LIMIT: Duration = Duration::from_secs(120);

fn args(a: &[&str]) -> Vec<String> {
    a.iter().map(|s| s.to_string()).collect()
}

/// stderr with the diagnostic's line wrapping and frame removed (for matching messages).
fn flat(s: &str) -> String {
    s.lines()
        .map(|l| l.trim().trim_start_matches(['│', '×', '·']).trim())
        .collect::<Vec<_>>()
        .join(" ")
}

fn tp_lines(e: &Ended) -> Vec<&str> {
    e.stdout.lines().collect()
}

/// The final joints of the summary line (`final joints [a, b, …]`).
fn final_joints(e: &Ended) -> Vec<f64> {
    let line = e
        .stderr
        .lines()
        .find(|l| l.contains("final joints"))
        .unwrap_or_else(|| panic!("no summary in\n{}", e.stderr));
    let list = &line[line.find("final joints").unwrap() + "final joints".len()..];
    procs::numbers(list.trim().split(';').next().unwrap())
}

/// Simulated seconds of the summary line.
fn simulated(e: &Ended) -> f64 {
    let line = e
        .stderr
        .lines()
        .find(|l| l.starts_with("simulated"))
        .unwrap();
    line.split_whitespace().nth(1).unwrap().parse().unwrap()
}

/// The cycles of the summary line (`…, 1373 cycles; final joints …`).
fn summary_cycles(e: &Ended) -> u64 {
    let line = e
        .stderr
        .lines()
        .find(|l| l.starts_with("simulated"))
        .unwrap();
    let words: Vec<&str> = line.split_whitespace().collect();
    let at = words.iter().position(|w| w.starts_with("cycles")).unwrap();
    words[at - 1].parse().unwrap()
}

mod manual {
    use super::*;

    #[test]
    fn udpuc_example_runs_with_one_command_on_the_builtin_sensor() {
        let e = run_program(
            rapidvc!(),
            "programs/manual/position_guidance_udpuc.mod",
            &[],
            LIMIT,
        );
        assert_eq!(e.code, Some(0), "{}\n{}", e.stdout, e.stderr);
        assert_eq!(
            tp_lines(&e),
            ["EGM state: 1", "Reset EGM instance egmID1"],
            "{}",
            e.stderr
        );
        // The built-in sensor holds the start pose: EGMRunPose converges and holds 2 s.
        assert!(near(
            &final_joints(&e),
            &[0.0, 0.0, 0.0, 0.0, 40.0, 0.0],
            0.01
        ));
        assert!(simulated(&e) > 2.0);
    }

    /// MaxSpeedDeviation defaults to 1 °/s, so the example is slow in simulated time (about
    /// 143 s) — faithful; it must still finish, with every run converged.
    #[test]
    fn signals_example_runs_end_to_end() {
        let e = run_program(
            rapidvc!(),
            "programs/manual/position_guidance_signals.mod",
            &[],
            LIMIT,
        );
        assert_eq!(e.code, Some(0), "{}\n{}", e.stdout, e.stderr);
        assert!(
            e.stderr
                .contains("90110 EGM speed limited by MaxSpeedDeviation")
        );
        assert!(!e.stderr.contains("error"), "{}", e.stderr);
        // The last EGMRunJoint moves joints 2-6 to the signals (-5, 0, 0, 0, 0); joint 1 keeps
        // its start.
        let q = final_joints(&e);
        assert!(near(&q[1..], &[-5.0, 0.0, 0.0, 0.0, 0.0], 0.11), "{q:?}");
        let t = simulated(&e);
        assert!((100.0..200.0).contains(&t), "simulated {t} s");
    }

    #[test]
    fn trace_plot_and_egm_log() {
        let dir = std::env::temp_dir().join(format!("rapidvc-egm-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let trace = dir.join("t.csv");
        let log = dir.join("e.csv");
        let plot = dir.join("p.svg");
        let e = run_program(
            rapidvc!(),
            "programs/manual/position_guidance_udpuc.mod",
            &[
                format!("--trace={}", trace.display()),
                format!("--egm-log={}", log.display()),
                format!("--plot={}", plot.display()),
            ],
            LIMIT,
        );
        assert_eq!(e.code, Some(0), "{}", e.stderr);
        let t = std::fs::read_to_string(&trace).unwrap();
        let header: Vec<&str> = t.lines().next().unwrap().split(',').collect();
        let col = header.iter().position(|h| *h == "egm_state").unwrap();
        let states: Vec<&str> = t
            .lines()
            .skip(1)
            .map(|l| l.split(',').nth(col).unwrap())
            .collect();
        assert!(states.contains(&"RUNNING") && states.last() == Some(&"CONNECTED"));
        let running = states.iter().filter(|s| **s == "RUNNING").count();
        assert!(running > 400, "{running} cycles RUNNING");
        let l = std::fs::read_to_string(&log).unwrap();
        assert!(l.starts_with("identity,kind,send_time_s,recv_time_s,seqno,"));
        assert!(l.lines().skip(1).all(|r| r.starts_with("egmID1,pose,")));
        assert!(l.lines().count() > 400);
        assert!(e.stderr.contains("EGM log: "));
        let svg = std::fs::read_to_string(&plot).unwrap();
        assert!(svg.contains("EGM position guidance, pose mode"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}

mod failures {
    use super::*;

    const PROGRAM: &str = "tests/run_egm/failures.mod";

    fn entry(name: &str, extra: &[&str]) -> Ended {
        let mut a = args(&["--entry", name]);
        a.extend(args(extra));
        run_program(rapidvc!(), PROGRAM, &a, LIMIT)
    }

    fn fails_with(name: &str, text: &str) {
        let e = entry(name, &[]);
        assert_eq!(e.code, Some(1), "{}\n{}", e.stdout, e.stderr);
        assert!(flat(&e.stderr).contains(text), "{name}: {}", e.stderr);
        assert!(!e.stdout.contains("caught"), "{}", e.stdout);
    }

    #[test]
    fn egm_movement_rules_and_fatal_errors() {
        fails_with(
            "no_move",
            "the first movement after a controller start cannot be an EGM movement",
        );
        fails_with("fly_by", "an EGM movement must start in a fine point");
        fails_with("mismatch", "41826 EGM mode mismatch");
        fails_with("not_reserved", "the EGM identity is not reserved");
        fails_with("no_profile", "\"fast\" is not defined");
    }

    #[test]
    fn no_wait_cond_wait_cond_stop_and_program_end_while_running() {
        let e = entry("no_wait", &["--device=sensor=builtin:joint:10,0,0,0,30,0"]);
        assert_eq!(e.code, Some(0), "{}", e.stderr);
        assert_eq!(
            tp_lines(&e),
            [
                "running: 3",
                "after EGMWaitCond: 2",
                "after EGMStop: 2",
                "ends while running: 3"
            ]
        );
        // The last run (RAMP_DOWN) is ramped out when the program ends: the robot stops
        // between the start and the target, within the axis ranges.
        let q = final_joints(&e);
        assert!(q[0] > 0.0 && q[0] <= 10.0, "{q:?}");
    }

    #[test]
    fn egmstop_in_a_trap_ends_the_run_it_interrupted() {
        let e = entry(
            "trap_stop",
            &["--device=sensor=builtin:joint:10,0,0,0,30,0"],
        );
        assert_eq!(e.code, Some(0), "{}", e.stderr);
        assert_eq!(tp_lines(&e), ["stopping: 3", "after the TRAP: 2"]);
        // Stopped after 0.5 s at ≤ 20 °/s: on its way to J1 = 10.
        let q = final_joints(&e);
        assert!(q[0] > 1.0 && q[0] < 10.0, "{q:?}");
    }

    /// A receiver for the stream: counts the EgmRobot messages and checks what they say.
    #[test]
    fn position_stream_during_ordinary_motion() {
        let rx = UdpSocket::bind("127.0.0.1:0").unwrap();
        rx.set_read_timeout(Some(Duration::from_millis(200)))
            .unwrap();
        let port = rx.local_addr().unwrap().port();
        let receiver = std::thread::spawn(move || {
            let mut buf = [0u8; 2048];
            let mut msgs: Vec<proto::EgmRobot> = Vec::new();
            let start = Instant::now();
            let mut last: Option<Instant> = None;
            while start.elapsed() < Duration::from_secs(60) {
                match rx.recv_from(&mut buf) {
                    Ok((n, _)) => {
                        last = Some(Instant::now());
                        msgs.push(proto::EgmRobot::decode(&buf[..n]).unwrap());
                    }
                    Err(_) if last.is_some_and(|t| t.elapsed() > Duration::from_secs(1)) => {
                        break;
                    }
                    Err(_) => {}
                }
            }
            msgs
        });
        let e = entry("stream", &[&format!("--device=sensor=127.0.0.1:{port}")]);
        let msgs = receiver.join().unwrap();
        assert_eq!(e.code, Some(0), "{}", e.stderr);
        assert_eq!(
            tp_lines(&e),
            [
                "streaming: 3",
                "stopped: 2",
                "streaming again: 3",
                "reset: 1"
            ]
        );
        assert!(msgs.len() > 20, "{}", msgs.len());
        let j1: Vec<f64> = msgs
            .iter()
            .map(|m| m.feedback().unwrap().joints.as_ref().unwrap().joints[0])
            .collect();
        // Out to J1 = 5 and back home.
        let top = j1.iter().copied().fold(f64::MIN, f64::max);
        assert!((top - 5.0).abs() < 0.01, "{top}");
        for m in &msgs {
            assert_eq!(m.mci_state.unwrap().state, 2, "MCI_STOPPED while streaming");
            assert_eq!(m.rapid_exec_state.unwrap().state, 2, "RAPID_RUNNING");
        }
        // Two streams, each numbering from 0.
        let seq: Vec<u32> = msgs
            .iter()
            .map(|m| m.header.unwrap().seqno.unwrap())
            .collect();
        assert_eq!(seq.iter().filter(|s| **s == 0).count(), 2, "{seq:?}");
    }
}

/// A sensor that sends garbage around its real replies, lets a second sender interfere, then
/// falls silent and comes back.
mod hostile {
    use super::*;

    const TARGET_1: [f64; 6] = [10.0, -5.0, 20.0, 0.0, 40.0, 30.0];
    const TARGET_2: [f64; 6] = [-10.0, 5.0, 10.0, 0.0, 35.0, -20.0];
    const INTRUDER: [f64; 6] = [-40.0, 30.0, -30.0, 60.0, -60.0, 90.0];

    struct Report {
        sessions: u32,
        received: u32,
        garbage_sent: u32,
    }

    /// Session 1: target 1 amid garbage and an intruder. Session 2: target 2 for 40 messages,
    /// then silence. Session 3 (after the RETRY): target 2.
    fn sensor(sock: UdpSocket, intruder: UdpSocket) -> Report {
        sock.set_read_timeout(Some(Duration::from_millis(200)))
            .unwrap();
        let mut buf = [0u8; 2048];
        let mut r = Report {
            sessions: 0,
            received: 0,
            garbage_sent: 0,
        };
        let mut in_session = 0u32;
        let mut rng = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            rng
        };
        let start = Instant::now();
        let mut last: Option<Instant> = None;
        while start.elapsed() < Duration::from_secs(90) {
            let (n, src): (usize, SocketAddr) = match sock.recv_from(&mut buf) {
                Ok(x) => x,
                Err(_) if last.is_some_and(|t| t.elapsed() > Duration::from_secs(2)) => break,
                Err(_) => continue,
            };
            last = Some(Instant::now());
            let Ok(m) = proto::EgmRobot::decode(&buf[..n]) else {
                continue;
            };
            r.received += 1;
            let seq = m.header.and_then(|h| h.seqno).unwrap_or(0);
            if seq == 0 {
                r.sessions += 1;
                in_session = 0;
            }
            in_session += 1;
            match r.sessions {
                1 => {
                    let k = in_session;
                    let mut junk = |bytes: Vec<u8>| {
                        sock.send_to(&bytes, src).unwrap();
                        r.garbage_sent += 1;
                    };
                    if k.is_multiple_of(7) {
                        junk((0..(next() % 200)).map(|_| next() as u8).collect());
                    }
                    if k.is_multiple_of(11) {
                        let mut t = joint_reply(seq, TARGET_1);
                        t.truncate(t.len() / 2);
                        junk(t);
                    }
                    if k.is_multiple_of(13) {
                        junk(vec![0x0a; 4000]);
                    }
                    if k.is_multiple_of(17) {
                        junk(joint_reply(
                            seq,
                            [f64::NAN, 0.0, 0.0, 0.0, f64::INFINITY, 0.0],
                        ));
                    }
                    if k.is_multiple_of(19) {
                        junk(joint_reply(seq, [1000.0, 0.0, 0.0, 0.0, 30.0, 0.0]));
                    }
                    intruder.send_to(&joint_reply(seq, INTRUDER), src).unwrap();
                    if k % 5 != 3 {
                        // Mostly the real reply last, sometimes before the garbage.
                        sock.send_to(&joint_reply(seq, TARGET_1), src).unwrap();
                    } else {
                        sock.send_to(&joint_reply(seq, TARGET_1), src).unwrap();
                        junk(vec![0xff; 3]);
                    }
                }
                2 if in_session > 40 => {}
                _ => {
                    sock.send_to(&joint_reply(seq, TARGET_2), src).unwrap();
                }
            }
        }
        r
    }

    #[test]
    fn session_survives_garbage_and_silence_ends_with_err_udpuc_comm() {
        let sock = UdpSocket::bind("127.0.0.1:0").unwrap();
        let intruder = UdpSocket::bind("127.0.0.1:0").unwrap();
        let port = sock.local_addr().unwrap().port();
        let h = std::thread::spawn(move || sensor(sock, intruder));
        let dir = std::env::temp_dir().join(format!("rapidvc-hostile-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let trace = dir.join("t.csv");
        let e = run_program(
            rapidvc!(),
            "tests/run_egm/hostile.mod",
            &[
                format!("--device=sensor=127.0.0.1:{port}"),
                format!("--trace={}", trace.display()),
            ],
            LIMIT,
        );
        let report = h.join().unwrap();
        assert_eq!(e.code, Some(0), "{}\n{}", e.stdout, e.stderr);
        assert!(report.garbage_sent > 20, "{}", report.garbage_sent);
        assert_eq!(
            report.sessions, 3,
            "received {}\n{}\n{}",
            report.received, e.stdout, e.stderr
        );
        let q1 = printed(&e.stdout, "phase 1: ");
        assert!(near(&q1, &TARGET_1, 0.6), "{q1:?}");
        let q2 = printed(&e.stdout, "phase 2: ");
        assert!(near(&q2, &TARGET_2, 0.6), "{q2:?}");
        let lines = tp_lines(&e);
        // The handler ran once, while the run had ended (CONNECTED) with an error (corr 1).
        assert_eq!(
            lines
                .iter()
                .filter(|l| l.starts_with("ERR_UDPUC_COMM"))
                .collect::<Vec<_>>(),
            [&"ERR_UDPUC_COMM, state 2"]
        );
        assert!(lines.contains(&"state: 2") && lines.contains(&"corr: 2"));
        // What the controller reported about the garbage, the intruder and the silence.
        for number in ["90101", "90102", "90103", "90104", "90105"] {
            assert!(
                e.stderr.contains(&format!("event: EGM egm1: {number} ")),
                "event {number} missing:\n{}",
                e.stderr
            );
        }
        assert!(
            e.stderr.contains("41822") || e.stderr.contains("No data from the UdpUc device"),
            "{}",
            e.stderr
        );
        // Every datagram the session did not use is counted by cause; the totals close the run.
        let totals = dropped_totals(&e.stderr);
        for cause in [
            "from another sender than the device's address and port",
            "truncated",
            "oversized",
            "with NaN or infinite values",
            "out of range",
        ] {
            assert!(totals.contains(cause), "{cause} missing: {totals}");
        }
        assert!(
            totals.contains("malformed") || totals.contains("truncated"),
            "{totals}"
        );
        // The robot never left its axis ranges and never followed the intruder.
        let t = std::fs::read_to_string(&trace).unwrap();
        let robot = rapidvc::robot::Robot::default();
        for row in t.lines().skip(1) {
            let q: Vec<f64> = row
                .split(',')
                .skip(1)
                .take(6)
                .map(|v| v.parse().unwrap())
                .collect();
            let q: [f64; 6] = q.try_into().unwrap();
            assert!(robot.check_limits(&q).is_ok(), "{q:?}");
            assert!(
                q[0] > -20.0 && q[3].abs() < 1.0,
                "followed the intruder: {q:?}"
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// The `EGM: N datagrams dropped: …` line at the end of a run (its text after `EGM: `).
    fn dropped_totals(stderr: &str) -> &str {
        stderr
            .lines()
            .find_map(|l| l.strip_prefix("EGM: "))
            .filter(|l| l.contains("datagrams dropped"))
            .unwrap_or_else(|| panic!("no totals of dropped datagrams in\n{stderr}"))
    }

    /// The first number of the totals line (all datagrams dropped).
    fn dropped_count(totals: &str) -> u64 {
        totals.split_whitespace().next().unwrap().parse().unwrap()
    }

    /// The configured sensor never answers; a process on its host at another port answers
    /// every message (and floods four more datagrams each time). It used to become the
    /// sensor and steer the robot without an event.
    #[test]
    fn a_sender_on_the_sensor_host_at_another_port_never_steers() {
        let sensor = UdpSocket::bind("127.0.0.1:0").unwrap();
        let intruder = UdpSocket::bind("127.0.0.1:0").unwrap();
        let port = sensor.local_addr().unwrap().port();
        sensor
            .set_read_timeout(Some(Duration::from_millis(200)))
            .unwrap();
        let h = std::thread::spawn(move || {
            let mut buf = [0u8; 2048];
            let (mut messages, mut sent) = (0u64, 0u64);
            let start = Instant::now();
            let mut last = Instant::now();
            while start.elapsed() < Duration::from_secs(60)
                && last.elapsed() < Duration::from_secs(2)
            {
                let Ok((n, controller)) = sensor.recv_from(&mut buf) else {
                    continue;
                };
                last = Instant::now();
                let Ok(m) = proto::EgmRobot::decode(&buf[..n]) else {
                    continue;
                };
                messages += 1;
                let seq = m.header.and_then(|h| h.seqno).unwrap_or(0);
                for _ in 0..5 {
                    intruder
                        .send_to(&joint_reply(seq, INTRUDER), controller)
                        .unwrap();
                    sent += 1;
                }
            }
            (messages, sent)
        });
        let e = run_program(
            rapidvc!(),
            "tests/run_egm/silent_sensor.mod",
            &[format!("--device=sensor=127.0.0.1:{port}")],
            LIMIT,
        );
        let (messages, sent) = h.join().unwrap();
        assert_eq!(e.code, Some(0), "{}\n{}", e.stdout, e.stderr);
        assert!(messages > 10, "{messages}");
        // Not steered: the run timed out where it started.
        let q = printed(&e.stdout, "ERR_UDPUC_COMM at ");
        assert!(near(&q, &[0.0, 0.0, 0.0, 0.0, 30.0, 0.0], 1e-6), "{q:?}");
        assert!(
            e.stderr.contains("event: EGM egm1: 90101 "),
            "no 90101:\n{}",
            e.stderr
        );
        assert!(e.stderr.contains("41822"), "{}", e.stderr);
        // All counted: whatever reached the socket before the run ended (a few may still
        // be in flight then), and nothing for another cause.
        let totals = dropped_totals(&e.stderr);
        let dropped = dropped_count(totals);
        assert!(
            dropped <= sent && dropped >= sent / 2,
            "{dropped} of {sent}: {totals}"
        );
        assert_eq!(
            totals,
            format!(
                "{dropped} datagrams dropped: {dropped} from another sender than the device's address and port"
            )
        );
    }

    /// Lockstep with a sensor that never answers: each cycle waits `--lockstep-timeout` for a
    /// reply until the comm time-out is declared (0.3 s of robot time, 75 cycles), and none
    /// after it: the ramp-out (0.5 s, 125 cycles) used to wait on every cycle too. Counted in
    /// waits, not wall seconds.
    #[test]
    fn lockstep_stops_waiting_once_the_comm_timeout_is_declared() {
        let dead = UdpSocket::bind("127.0.0.1:0").unwrap();
        let port = dead.local_addr().unwrap().port();
        let e = run_program(
            rapidvc!(),
            "tests/run_egm/silent_sensor.mod",
            &[
                format!("--device=sensor=127.0.0.1:{port}"),
                "--lockstep".into(),
                "--lockstep-timeout=20".into(),
            ],
            LIMIT,
        );
        drop(dead);
        assert_eq!(e.code, Some(0), "{}\n{}", e.stdout, e.stderr);
        assert!(e.stdout.contains("ERR_UDPUC_COMM at "), "{}", e.stdout);
        let line = e
            .stderr
            .lines()
            .find(|l| l.starts_with("lockstep: "))
            .unwrap_or_else(|| panic!("no lockstep line in\n{}", e.stderr));
        let n: Vec<u64> = line
            .split_whitespace()
            .filter_map(|w| w.parse().ok())
            .collect();
        let (waits, timeouts) = (n[0], n[1]);
        assert_eq!(waits, timeouts, "{line}");
        // One wait per EGM message until 0.3 s without a reply: 75 (give or take one).
        assert!((74..=77).contains(&waits), "{line}");
        // The run went on for the 0.5 s ramp-out without waiting.
        let cycles = summary_cycles(&e);
        assert!(cycles >= waits + 125, "{cycles} cycles, {line}");
    }
}
