//! Real third-party EGM clients against rapidvc's controller session over loopback: abbegm (Rust, V1.1 schema) and the PyPI clients abb_robot_client and ABBRobotEGM.
//!
//! Two levels: the session alone (a controller loop in this process), and whole RAPID
//! programs run by `rapidvc run` with `--device sensor=127.0.0.1:PORT` pointing at the client
//! (module `through_rapidvc_run`), each client driving a joint-mode and a pose-mode session,
//! once in lockstep and once in real time.
//!
//! The Python tests need `RAPIDVC_PYTHON` pointing at a Python with both packages installed
//! (see `tests/clients/common.py`) when they are built; without it they are ignored
//! (`build.rs` sets the `rapidvc_python` cfg), so `cargo test` on a fresh machine lists them as
//! ignored, and CI, which exports the variable, runs them with the same command. Every test ends by itself (bounded cycles, client time-outs, read time-outs).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use rapidvc_testkit::egm_loop;
use rapidvc_testkit::procs;
use rapidvc_testkit::rapidvc;

use std::io::{BufRead, BufReader};
use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

use egm_loop::*;
use procs::{json_field, numbers as json_numbers, python};
use rapidvc::egm::EgmMode;
use rapidvc::egm::servo::ServoInput;

const JOINT_TARGET: [f64; 6] = [10.0, -5.0, 20.0, 0.0, 40.0, 30.0];
const POSE_TARGET: [f64; 6] = [40.0, -20.0, 60.0, 0.0, 30.0, 0.0];

mod abbegm_client {
    use super::*;
    use abbegm::msg::{EgmClock, EgmSensor};
    use abbegm::sync_peer::EgmPeer;

    /// abbegm decodes with the V1.1 schema and a 1024-byte buffer: every EgmRobot we send
    /// must decode there, with everything its examples read.
    #[test]
    fn abbegm_decodes_every_message_and_drives_a_joint_session() {
        let mut peer = EgmPeer::bind("127.0.0.1:0").unwrap();
        peer.socket()
            .set_read_timeout(Some(Duration::from_millis(500)))
            .unwrap();
        let addr = peer.socket().local_addr().unwrap();
        let client = std::thread::spawn(move || {
            let mut seq = 0u32;
            let mut problems = Vec::new();
            let mut last_joints = Vec::new();
            for _ in 0..600 {
                let (robot, src) = match peer.recv_from() {
                    Ok(x) => x,
                    Err(e) => {
                        problems.push(format!("recv/decode: {e}"));
                        break;
                    }
                };
                let ok = robot.sequence_number() == Some(seq)
                    && robot.timestamp_ms().is_some()
                    && robot.feedback_joints().map(Vec::len) == Some(6)
                    && robot.planned_joints().map(Vec::len) == Some(6)
                    && robot
                        .feedback_pose()
                        .is_some_and(|p| p.pos.is_some() && p.orient.is_some())
                    && robot.feedback_time().is_some()
                    && robot.planned_time().is_some()
                    && robot.motors_enabled() == Some(true)
                    && robot.rapid_running() == Some(true)
                    && robot.measured_force().is_none()
                    && !robot.has_nan();
                if !ok {
                    problems.push(format!("message {seq} incomplete: {robot:?}"));
                }
                last_joints = robot.feedback_joints().cloned().unwrap_or_default();
                let time: EgmClock = robot.feedback_time().unwrap_or_default();
                let reply = EgmSensor::joint_target(seq, JOINT_TARGET, time);
                if let Err(e) = peer.send_to(&reply, &src) {
                    problems.push(format!("send: {e}"));
                }
                seq += 1;
            }
            (seq, problems, last_joints)
        });
        let mut c = Controller::new(EgmMode::Joint, addr, Duration::from_secs(2));
        let mut reference = ServoInput::position(START);
        c.session.start(c.now());
        let mut cycles = 0;
        while !client.is_finished() && cycles < 2000 {
            c.run(1, &mut reference, joints_of);
            cycles += 1;
        }
        c.session.stop();
        let (received, problems, last_joints) = client.join().unwrap();
        assert!(problems.is_empty(), "{problems:?}");
        assert_eq!(received, 600);
        assert!(c.events.is_empty(), "{:?}", c.events);
        assert!(close(&c.last, &JOINT_TARGET, 0.05), "robot at {:?}", c.last);
        assert!(c.session.stats().accepted >= 598);
        assert_eq!(last_joints.len(), 6);
    }
}

/// Runs one client script as the sensor of a joint or pose session; returns its summary.
fn run_client(python: &PathBuf, script: &str, mode: EgmMode, target: &str, count: u32) -> String {
    let path = format!("{}/tests/clients/{script}", env!("CARGO_MANIFEST_DIR"));
    let mode_arg = if mode == EgmMode::Joint {
        "joint"
    } else {
        "pose"
    };
    let mut child = Command::new(python)
        .args([
            path.as_str(),
            "--mode",
            mode_arg,
            "--target",
            target,
            "--count",
            &count.to_string(),
            "--timeout",
            "20",
        ])
        .stdout(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot run {python:?}: {e}"));
    let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
    let first = lines.next().expect("client printed nothing").unwrap();
    let port: u16 = json_field(&first, "port").parse().unwrap();
    let addr: SocketAddr = ([127, 0, 0, 1], port).into();
    let mut c = Controller::new(mode, addr, Duration::from_secs(5));
    let mut reference = ServoInput::position(START);
    c.session.start(c.now());
    let mut cycles = 0;
    while cycles < 3000 {
        if child.try_wait().unwrap().is_some() {
            break;
        }
        c.run(1, &mut reference, joints_of);
        cycles += 1;
    }
    c.session.stop();
    if child.try_wait().unwrap().is_none() {
        child.kill().unwrap();
    }
    let status = child.wait().unwrap();
    let summary = lines.map_while(Result::ok).last().unwrap_or_default();
    assert!(status.success(), "{script} {mode_arg}: {summary}");
    assert_eq!(json_field(&summary, "well_formed"), "true", "{summary}");
    assert_eq!(
        json_field(&summary, "received"),
        count.to_string(),
        "{summary}"
    );
    assert_eq!(
        json_field(&summary, "replied"),
        count.to_string(),
        "{summary}"
    );
    assert_eq!(json_field(&summary, "first_seqno"), "0", "{summary}");
    assert_eq!(json_field(&summary, "seqno_gaps"), "0", "{summary}");
    assert_eq!(json_field(&summary, "tm_backwards"), "0", "{summary}");
    assert!(c.events.is_empty(), "{:?}", c.events);
    let st = c.session.stats();
    assert!(u64::from(count) <= st.accepted + 2, "{st:?}");
    assert_eq!(st.dropped(), 0, "{st:?}");
    let expected = if mode == EgmMode::Joint {
        JOINT_TARGET
    } else {
        POSE_TARGET
    };
    assert!(close(&c.last, &expected, 0.05), "robot at {:?}", c.last);
    let seen = json_numbers(json_field(&summary, "last_feedback_joints"));
    assert!(
        seen.iter().zip(&expected).all(|(a, b)| (a - b).abs() < 0.1),
        "the client saw the robot arrive: {seen:?}"
    );
    summary
}

mod python_clients {
    use super::*;

    const JOINT: &str = "10,-5,20,0,40,30";
    const POSE: &str = "40,-20,60,1,0,0,0";

    #[test]
    #[cfg_attr(
        not(rapidvc_python),
        ignore = "needs RAPIDVC_PYTHON (a Python with abb_robot_client and ABBRobotEGM) when the tests are built"
    )]
    fn abb_robot_client_joint_and_pose() {
        let py = python();
        run_client(&py, "arc_sensor.py", EgmMode::Joint, JOINT, 500);
        run_client(&py, "arc_sensor.py", EgmMode::Pose, POSE, 500);
    }

    #[test]
    #[cfg_attr(
        not(rapidvc_python),
        ignore = "needs RAPIDVC_PYTHON (a Python with abb_robot_client and ABBRobotEGM) when the tests are built"
    )]
    fn abbrobotegm_joint_and_pose() {
        let py = python();
        run_client(&py, "abbrobotegm_sensor.py", EgmMode::Joint, JOINT, 500);
        run_client(&py, "abbrobotegm_sensor.py", EgmMode::Pose, POSE, 500);
    }
}

/// Whole RAPID programs (`tests/run_egm/*_session.mod`) run by `rapidvc run` against each
/// client: the EGM states the program prints, where the robot ends (CJointT/CRobT), and what
/// the client received.
mod through_rapidvc_run {
    use super::*;
    use procs::{Ended, near, printed, run_program, start_script};

    const JOINT_PROGRAM: &str = "tests/run_egm/joint_session.mod";
    const POSE_PROGRAM: &str = "tests/run_egm/pose_session.mod";
    const JOINT_TARGET: [f64; 6] = [10.0, -5.0, 20.0, 0.0, 40.0, 30.0];
    const JOINT_ARG: &str = "10,-5,20,0,40,30";
    const POSE_POS: [f64; 3] = [1068.61, -30.0, 1457.5];
    const POSE_ORIENT: [f64; 4] = [0.5, 0.0, 0.866_025, 0.0];
    const POSE_ARG: &str = "1068.61,-30,1457.5,0.5,0,0.866025,0";
    const LIMIT: Duration = Duration::from_secs(90);

    fn device_args(port: u16, lockstep: bool) -> Vec<String> {
        let mut args = vec![format!("--device=sensor=127.0.0.1:{port}")];
        if lockstep {
            args.push("--lockstep".into());
        }
        args
    }

    /// The program's EGM states, its exit and the clock mode it ran in.
    fn check_run(run: &Ended, instruction: &str, lockstep: bool) {
        assert_eq!(run.code, Some(0), "{}\n{}", run.stdout, run.stderr);
        let states: Vec<&str> = run
            .stdout
            .lines()
            .filter(|l| l.starts_with("state after"))
            .collect();
        assert_eq!(
            states,
            [
                "state after EGMGetId: 1".to_string(),
                "state after EGMSetupUC: 2".to_string(),
                format!("state after {instruction}: 2"),
                "state after EGMReset: 1".to_string(),
            ],
            "{}",
            run.stdout
        );
        if lockstep {
            assert!(
                run.stderr.contains("lockstep: ") && run.stderr.contains(" 0 timed out"),
                "{}",
                run.stderr
            );
        } else {
            assert!(
                run.stderr.contains("the clock runs in real time"),
                "{}",
                run.stderr
            );
        }
        assert!(!run.stderr.contains("41822"), "{}", run.stderr);
    }

    fn check_joint_result(run: &Ended) {
        let q = printed(&run.stdout, "joints: ");
        assert!(near(&q, &JOINT_TARGET, 0.25), "robot at {q:?}");
    }

    fn check_pose_result(run: &Ended) {
        let pos = printed(&run.stdout, "pos: ");
        let orient = printed(&run.stdout, "orient: ");
        assert!(near(&pos, &POSE_POS, 0.6), "TCP at {pos:?}");
        assert!(near(&orient, &POSE_ORIENT, 0.005), "orientation {orient:?}");
    }

    /// A Python client script drives one session of `program`.
    fn python_session(py: &Path, script: &str, joint: bool, lockstep: bool) {
        let (mode, target, program, instruction) = if joint {
            ("joint", JOINT_ARG, JOINT_PROGRAM, "EGMRunJoint")
        } else {
            ("pose", POSE_ARG, POSE_PROGRAM, "EGMRunPose")
        };
        let (client, port) = start_script(
            py,
            script,
            &[
                "--mode",
                mode,
                "--target",
                target,
                "--count",
                "0",
                "--until-quiet",
                "1",
                "--timeout",
                "60",
            ],
        );
        let run = run_program(rapidvc!(), program, &device_args(port, lockstep), LIMIT);
        let c = client.wait(Duration::from_secs(30));
        let summary = c.stdout.lines().last().unwrap_or_default().to_string();
        check_run(&run, instruction, lockstep);
        assert_eq!(c.code, Some(0), "{script} {mode}: {summary}\n{}", c.stderr);
        assert_eq!(json_field(&summary, "well_formed"), "true", "{summary}");
        assert_eq!(json_field(&summary, "reason"), "\"quiet\"", "{summary}");
        let received: u32 = json_field(&summary, "received").parse().unwrap();
        assert!(received > 50, "{summary}");
        assert_eq!(
            json_field(&summary, "replied"),
            received.to_string(),
            "{summary}"
        );
        assert_eq!(json_field(&summary, "first_seqno"), "0", "{summary}");
        assert_eq!(json_field(&summary, "seqno_gaps"), "0", "{summary}");
        assert_eq!(json_field(&summary, "tm_backwards"), "0", "{summary}");
        if joint {
            check_joint_result(&run);
            let seen = json_numbers(json_field(&summary, "last_feedback_joints"));
            assert!(near(&seen, &JOINT_TARGET, 0.25), "client saw {seen:?}");
        } else {
            check_pose_result(&run);
            let seen = json_numbers(json_field(&summary, "last_feedback_pos"));
            assert!(near(&seen, &POSE_POS, 0.6), "client saw {seen:?}");
        }
    }

    #[test]
    #[cfg_attr(
        not(rapidvc_python),
        ignore = "needs RAPIDVC_PYTHON (a Python with abb_robot_client and ABBRobotEGM) when the tests are built"
    )]
    fn abb_robot_client_joint_lockstep_and_pose_real_time() {
        let py = python();
        python_session(&py, "arc_sensor.py", true, true);
        python_session(&py, "arc_sensor.py", false, false);
    }

    #[test]
    #[cfg_attr(
        not(rapidvc_python),
        ignore = "needs RAPIDVC_PYTHON (a Python with abb_robot_client and ABBRobotEGM) when the tests are built"
    )]
    fn abbrobotegm_joint_real_time_and_pose_lockstep() {
        let py = python();
        python_session(&py, "abbrobotegm_sensor.py", true, false);
        python_session(&py, "abbrobotegm_sensor.py", false, true);
    }

    /// What the abbegm sensor saw.
    struct Seen {
        received: u32,
        problems: Vec<String>,
        last_joints: Vec<f64>,
        last_pos: [f64; 3],
    }

    /// abbegm (V1.1 schema) as the sensor: replies to every message with the target until
    /// messages stop for a second (at most 60 s).
    fn abbegm_sensor(joint: bool) -> (std::thread::JoinHandle<Seen>, u16) {
        use abbegm::msg::{EgmClock, EgmSensor};
        use abbegm::sync_peer::EgmPeer;
        use abbegm::{msg, msg::EgmPose};
        let mut peer = EgmPeer::bind("127.0.0.1:0").unwrap();
        peer.socket()
            .set_read_timeout(Some(Duration::from_millis(200)))
            .unwrap();
        let port = peer.socket().local_addr().unwrap().port();
        let h = std::thread::spawn(move || {
            let start = std::time::Instant::now();
            let mut last_rx: Option<std::time::Instant> = None;
            let mut seen = Seen {
                received: 0,
                problems: Vec::new(),
                last_joints: Vec::new(),
                last_pos: [0.0; 3],
            };
            let mut expected_seq = 0u32;
            while start.elapsed() < Duration::from_secs(60) {
                let (robot, src) = match peer.recv_from() {
                    Ok(x) => x,
                    Err(_) => {
                        if last_rx.is_some_and(|t| t.elapsed() > Duration::from_secs(1)) {
                            break;
                        }
                        continue;
                    }
                };
                last_rx = Some(std::time::Instant::now());
                let ok = robot.sequence_number() == Some(expected_seq)
                    && robot.timestamp_ms().is_some()
                    && robot.feedback_joints().map(Vec::len) == Some(6)
                    && robot.planned_joints().map(Vec::len) == Some(6)
                    && robot
                        .feedback_pose()
                        .is_some_and(|p| p.pos.is_some() && p.orient.is_some())
                    && robot.motors_enabled() == Some(true)
                    && robot.rapid_running() == Some(true)
                    && !robot.has_nan();
                if !ok && seen.problems.len() < 5 {
                    seen.problems
                        .push(format!("message {expected_seq}: {robot:?}"));
                }
                expected_seq = expected_seq.wrapping_add(1);
                seen.received += 1;
                seen.last_joints = robot.feedback_joints().cloned().unwrap_or_default();
                if let Some(p) = robot.feedback_pose().and_then(|p| p.pos.as_ref()) {
                    seen.last_pos = [p.x, p.y, p.z];
                }
                let time: EgmClock = robot.feedback_time().unwrap_or_default();
                let seq = seen.received;
                let reply = if joint {
                    EgmSensor::joint_target(seq, JOINT_TARGET, time)
                } else {
                    let pose = EgmPose::new(
                        msg::EgmCartesian::from_mm(POSE_POS[0], POSE_POS[1], POSE_POS[2]),
                        msg::EgmQuaternion::from_wxyz(
                            POSE_ORIENT[0],
                            POSE_ORIENT[1],
                            POSE_ORIENT[2],
                            POSE_ORIENT[3],
                        ),
                    );
                    EgmSensor::pose_target(seq, pose, time)
                };
                if let Err(e) = peer.send_to(&reply, &src) {
                    seen.problems.push(format!("send: {e}"));
                }
            }
            seen
        });
        (h, port)
    }

    fn abbegm_session(joint: bool, lockstep: bool) {
        let (sensor, port) = abbegm_sensor(joint);
        let (program, instruction) = if joint {
            (JOINT_PROGRAM, "EGMRunJoint")
        } else {
            (POSE_PROGRAM, "EGMRunPose")
        };
        let run = run_program(rapidvc!(), program, &device_args(port, lockstep), LIMIT);
        let seen = sensor.join().unwrap();
        check_run(&run, instruction, lockstep);
        assert!(seen.problems.is_empty(), "{:?}", seen.problems);
        assert!(seen.received > 50, "{}", seen.received);
        if joint {
            check_joint_result(&run);
            assert!(
                near(&seen.last_joints, &JOINT_TARGET, 0.25),
                "{:?}",
                seen.last_joints
            );
        } else {
            check_pose_result(&run);
            assert!(near(&seen.last_pos, &POSE_POS, 0.6), "{:?}", seen.last_pos);
        }
    }

    #[test]
    fn abbegm_joint_lockstep_and_pose_real_time() {
        abbegm_session(true, true);
        abbegm_session(false, false);
    }
}
