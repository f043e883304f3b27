//! EGM over real loopback sockets: controller session + transport + servo against the built-in sensor, fixtures, hostile senders and `rapidvc sensor`.
//!
//! Every test ends by itself: loops are bounded in cycles and sockets have read time-outs.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use rapidvc_testkit::egm_loop;
use rapidvc_testkit::rapidvc;

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::Ordering;
use std::time::Duration;

use egm_loop::*;
use prost::Message;
use rapidvc::egm::proto::{EgmJoints, EgmPlanned, EgmRobot, EgmSensor};
use rapidvc::egm::servo::ServoInput;
use rapidvc::egm::session::MAX_DATAGRAM_LEN;
use rapidvc::egm::{EgmMode, EgmSession, Pose, SourceFilter, Target};
use rapidvc::time::RobotTime;

mod loopback {
    use super::*;

    #[test]
    fn joint_mode_robot_converges_to_the_sensor_target() {
        let sensor = SensorThread::spawn("joint:10,-5,20,0,40,30");
        let mut c = Controller::new(EgmMode::Joint, sensor.addr, Duration::from_secs(1));
        c.session.start(c.now());
        let mut reference = ServoInput::position(START);
        let target = [10.0, -5.0, 20.0, 0.0, 40.0, 30.0];
        let mut converged_at = None;
        for k in 1..=1000u32 {
            c.run(1, &mut reference, joints_of);
            if close(&c.last, &target, 0.05) {
                converged_at = Some(k);
                break;
            }
        }
        let sent = c.session.stats().sent;
        c.session.stop();
        let stats = sensor.finish();
        assert!(converged_at.is_some(), "robot at {:?}", c.last);
        assert!(c.events.is_empty(), "{:?}", c.events);
        let st = c.session.stats();
        assert!(st.accepted > 0 && st.dropped() == 0, "{st:?}");
        assert_eq!(stats.sessions, 1);
        assert_eq!(stats.seqno_gaps, 0, "seqno +1 per datagram");
        assert_eq!(stats.incomplete, 0);
        assert!(stats.received + 2 >= sent, "{} of {sent}", stats.received);
        // tm is real milliseconds: consecutive arrivals about one period apart.
        let p50 = stats.interval.percentile(50.0).unwrap();
        assert!(
            p50 > Duration::from_millis(2) && p50 < Duration::from_millis(8),
            "{p50:?}"
        );
        println!(
            "joint loopback: converged after {} cycles; turnaround {}; sensor interval {}",
            converged_at.unwrap_or(0),
            st.turnaround.summary(),
            stats.interval.summary()
        );
    }

    #[test]
    fn pose_mode_and_a_restarted_session_with_seqno_zero() {
        let sensor = SensorThread::spawn("pose:40,-20,60,0,0,0");
        let mut c = Controller::new(EgmMode::Pose, sensor.addr, Duration::from_secs(1));
        let mut reference = ServoInput::position(START);
        c.session.start(c.now());
        let target = [40.0, -20.0, 60.0, 0.0, 30.0, 0.0];
        for _ in 0..1000 {
            c.run(1, &mut reference, joints_of);
            if close(&c.last, &target, 0.05) {
                break;
            }
        }
        assert!(close(&c.last, &target, 0.05), "{:?}", c.last);
        c.session.stop();
        c.run(10, &mut reference, joints_of);
        c.session.start(c.now());
        assert_eq!(c.session.next_seqno(), 0);
        c.run(25, &mut reference, joints_of);
        let stats = sensor.finish();
        assert_eq!(stats.sessions, 2, "seqno 0 starts a new session");
        assert_eq!(stats.seqno_gaps, 0);
        assert!(c.events.is_empty(), "{:?}", c.events);
    }

    #[test]
    fn a_sensor_that_stops_replying_raises_41822() {
        let sensor = SensorThread::spawn("hold");
        sensor.mute_after.store(20, Ordering::Relaxed);
        let mut c = Controller::new(EgmMode::Joint, sensor.addr, Duration::from_millis(200));
        let mut reference = ServoInput::position(START);
        let started = c.now();
        c.session.start(started);
        let mut cycles = 0;
        while !c.session.comm_timed_out() && cycles < 500 {
            c.run(1, &mut reference, joints_of);
            cycles += 1;
        }
        let elapsed = c.now() - started;
        sensor.finish();
        assert!(c.session.comm_timed_out());
        // 20 replies (at least 19 cycles of 4 ms) then 200 ms of silence: never earlier. (Wall
        // time, not a cycle count: a loaded machine runs fewer, longer cycles.)
        assert!(cycles > 20, "{cycles} cycles");
        assert!(
            elapsed >= Duration::from_millis(270),
            "timed out after {elapsed:?} ({cycles} cycles)"
        );
        assert_eq!(c.events.len(), 1, "{:?}", c.events);
        assert_eq!(c.events[0].number, 41822);
        assert!(close(&c.last, &START, 1e-6), "hold keeps the robot still");
    }

    /// Garbage, oversized and NaN datagrams from a second sender on another port, plus
    /// datagrams from another IP, while the built-in sensor drives the robot.
    fn hostile_run(filter: SourceFilter) -> (Controller, bool) {
        let sensor = SensorThread::spawn("joint:5,5,5,5,35,5");
        let mut c = Controller::new(EgmMode::Joint, sensor.addr, Duration::from_secs(1));
        let mut config = c.session.config().clone();
        config.source_filter = filter;
        c.session = EgmSession::new(config).unwrap();
        let local = c.transport.local_addr().unwrap();
        let second = UdpSocket::bind("127.0.0.1:0").unwrap();
        // Another IP (all of 127/8 is loopback on Linux; skipped where it is not).
        let intruder = UdpSocket::bind("127.0.0.2:0").ok();
        let nan = EgmSensor {
            planned: Some(EgmPlanned {
                joints: Some(EgmJoints {
                    joints: vec![f64::NAN; 6],
                }),
                ..Default::default()
            }),
            ..Default::default()
        }
        .encode_to_vec();
        let mut reference = ServoInput::position(START);
        c.session.start(c.now());
        // Let the sensor's first reply arrive, so the session knows its sensor.
        for _ in 0..500 {
            if c.session.stats().accepted > 0 {
                break;
            }
            c.run(1, &mut reference, joints_of);
        }
        for _ in 0..100 {
            second.send_to(&[0xff; 40], local).unwrap();
            second.send_to(&[0u8; 1500], local).unwrap();
            second.send_to(&nan, local).unwrap();
            if let Some(i) = &intruder {
                i.send_to(&[0x12, 0x00], local).unwrap();
            }
            c.run(3, &mut reference, joints_of);
        }
        sensor.finish();
        assert!(
            close(&c.last, &[5.0, 5.0, 5.0, 5.0, 35.0, 5.0], 0.05),
            "{:?}",
            c.last
        );
        assert!(!c.session.comm_timed_out());
        // Throttled: far fewer events than bad datagrams.
        assert!(c.events.len() < 20, "{:?}", c.events);
        (c, intruder.is_some())
    }

    #[test]
    fn a_second_sender_and_another_ip_are_dropped_counted_and_reported_once() {
        let (c, other_ip) = hostile_run(SourceFilter::Remote);
        let st = c.session.stats();
        let expected = if other_ip { 400 } else { 300 };
        assert!(st.wrong_source >= expected - 10, "{st:?}");
        assert_eq!(st.malformed + st.oversized + st.not_finite, 0, "{st:?}");
        let reports: Vec<_> = c.events.iter().filter(|e| e.number == 90101).collect();
        assert_eq!(reports.len(), 1, "{:?}", c.events);
    }

    #[test]
    fn garbage_oversized_and_nan_are_counted_and_the_session_survives() {
        let (c, other_ip) = hostile_run(SourceFilter::Any);
        let st = c.session.stats();
        let garbage = if other_ip { 200 } else { 100 };
        assert!(st.malformed + st.incomplete >= garbage - 10, "{st:?}");
        assert!(st.oversized >= 90, "{st:?}");
        assert!(st.not_finite >= 90, "{st:?}");
        assert_eq!(st.wrong_source, 0);
        for number in [90102, 90103, 90104] {
            assert!(
                c.events.iter().any(|e| e.number == number),
                "{:?}",
                c.events
            );
        }
    }
}

mod fixtures {
    use super::*;
    use rapidvc::egm::convert::{ReferenceLimits, decode_reference};

    fn fixture(name: &str) -> Vec<u8> {
        let path = format!("{}/tests/fixtures/egm/{name}", env!("CARGO_MANIFEST_DIR"));
        std::fs::read(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
    }

    fn decode(name: &str, mode: EgmMode) -> Target {
        decode_reference(
            &fixture(name),
            mode,
            &Pose::IDENTITY,
            &ReferenceLimits::default(),
            RobotTime::ZERO,
        )
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .target
    }

    #[test]
    fn replies_encoded_by_the_python_clients_decode() {
        for name in ["abb_robot_client_joint.bin", "abbrobotegm_joint.bin"] {
            let Target::Joint(j) = decode(name, EgmMode::Joint) else {
                panic!("{name}")
            };
            assert_eq!(j.joints, [10.0, -5.0, 20.0, 0.0, 40.0, 30.0], "{name}");
        }
        for name in ["abb_robot_client_pose.bin", "abbrobotegm_pose.bin"] {
            let Target::Pose(p) = decode(name, EgmMode::Pose) else {
                panic!("{name}")
            };
            assert_eq!(p.pose.pos, [400.0, 100.0, 500.0], "{name}");
            assert!(
                (p.pose.orient[2] - 1.0).abs() < 1e-12,
                "{name}: {:?}",
                p.pose.orient
            );
        }
        for name in ["abb_robot_client_pathcorr.bin", "abbrobotegm_pathcorr.bin"] {
            let Target::PathCorr(c) = decode(name, EgmMode::PathCorr) else {
                panic!("{name}")
            };
            assert_eq!(c.pos, [0.0, 1.5, -2.5], "{name}");
            assert_eq!(c.age_ms, 1, "{name}");
        }
    }

    #[test]
    fn rw7_robot_message_with_renumbered_force_is_not_what_we_send() {
        // An RW7.16-schema EgmRobot written by ABBRobotEGM's protobuf with every field set,
        // including the renumbered measuredForce (fcActive = varint at field 1): a V1.1
        // decoder (ours, abbegm's) rejects the whole datagram, which is why rapidvc never
        // sends field 9. Without it, every RW7 extra is read or skipped.
        let bytes = fixture("rw7_robot_full.bin");
        assert!(bytes.len() <= MAX_DATAGRAM_LEN);
        assert!(EgmRobot::decode(bytes.as_slice()).is_err());
        let v11 = fixture("rw7_robot_no_force.bin");
        let robot = EgmRobot::decode(v11.as_slice()).unwrap();
        assert_eq!(robot.move_index, Some(7));
        assert_eq!(robot.rapid_from_robot().unwrap().dnum.len(), 40);
        assert!(rapidvc::egm::sensor::missing_mandatory(&robot).is_empty());
    }
}

mod cli {
    use super::*;
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;

    #[test]
    fn rapidvc_sensor_answers_and_prints_statistics() {
        let mut child = rapidvc!()
            .args([
                "sensor",
                "--port",
                "0",
                "--pattern",
                "sine:axis=1,amplitude=2,frequency=1",
                "--count",
                "100",
                "--duration",
                "20",
                "--print-every",
                "50",
            ])
            .stdout(Stdio::piped())
            .spawn()
            .unwrap();
        let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
        let first = lines.next().unwrap().unwrap();
        let addr: SocketAddr = first
            .split_whitespace()
            .nth(3)
            .and_then(|a| a.trim_end_matches(':').parse().ok())
            .unwrap_or_else(|| panic!("no address in {first:?}"));
        let mut c = Controller::new(EgmMode::Joint, addr, Duration::from_secs(5));
        let mut reference = ServoInput::position(START);
        c.session.start(c.now());
        c.run(130, &mut reference, joints_of);
        let out: Vec<String> = lines.map_while(Result::ok).collect();
        let status = child.wait().unwrap();
        assert!(status.success());
        let text = out.join("\n");
        assert!(text.contains("stopped: count reached"), "{text}");
        assert!(
            text.contains("messages: received 100 replied 100"),
            "{text}"
        );
        assert!(text.contains("#50 seqno=49"), "{text}");
        assert!(text.contains("interval   n=99 p50="), "{text}");
        assert!(c.session.stats().accepted >= 90);
        assert!(c.last[0].abs() > 0.1, "the sine moved J1: {:?}", c.last);
    }
}
