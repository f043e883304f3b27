//! EGM benchmarks: encode/decode per message, session and sensor cost, servo step, a whole driver tick per source, datagram sizes, and loopback round trip with the built-in sensor.
//!
//! `cargo bench --bench egm` runs the criterion groups, then prints datagram sizes and a
//! real-socket round trip (controller `EgmRobot` → built-in sensor thread → reply read back)
//! as p50/p99/max over 5000 exchanges. Under `cargo test` it runs everything once, briefly.
#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use std::hint::black_box;
use std::net::UdpSocket;
use std::sync::Arc;
use std::time::{Duration, Instant};

use criterion::Criterion;
use prost::Message;
use rapidvc::controller::egm_controller::registry_config;
use rapidvc::egm::convert::{EncodeOptions, ReferenceLimits, decode_reference, fill_robot};
use rapidvc::egm::latency::LatencyHistogram;
use rapidvc::egm::proto::EgmRobot;
use rapidvc::egm::sensor::{BuiltinSensor, SensorConfig};
use rapidvc::egm::servo::{EgmServo, ServoInput, ServoParams};
use rapidvc::egm::{
    DriverContext, DriverOptions, EgmConfig, EgmDriver, EgmMode, EgmRegistry, EgmSession,
    EgmSource, ExternalAxes, Joints, Pose, RapidData, RobotFeedback,
};
use rapidvc::robot::Robot;
use rapidvc::signals::SignalTable;
use rapidvc::time::RobotTime;
use rapidvc::wire::udp::UdpTransport;
use rapidvc_testkit::fixed_iters::{Runner, mark};

fn feedback() -> RobotFeedback {
    let pose = Pose {
        pos: [500.0, 0.0, 600.0],
        orient: [0.0, 0.0, 1.0, 0.0],
    };
    let mut fb = RobotFeedback::standing([1.0, 2.0, 3.0, 4.0, 35.0, 6.0], pose);
    fb.time = RobotTime::from_duration(Duration::new(1_700_000_000, 123_456_000));
    fb.planned_time = fb.time + Duration::from_millis(12);
    fb.utilization = 42.0;
    fb
}

fn sensor_reply(pattern: &str, fb: &RobotFeedback) -> Vec<u8> {
    let mut robot = EgmRobot::default();
    fill_robot(&mut robot, 0, 0, fb, &EncodeOptions::default());
    let mut s = BuiltinSensor::new(SensorConfig::new(pattern.parse().unwrap())).unwrap();
    s.handle_datagram(Duration::ZERO, &robot.encode_to_vec())
        .unwrap()
}

fn codec(r: &mut Runner<Criterion>) {
    let fb = feedback();
    let mut msg = EgmRobot::default();
    let mut buf = Vec::with_capacity(1024);
    r.iter("egm/encode EgmRobot (fill + encode)", || {
        fill_robot(&mut msg, 7, 28, black_box(&fb), &EncodeOptions::default());
        buf.clear();
        msg.encode(&mut buf).unwrap();
        black_box(buf.len())
    });
    let robot_bytes = {
        fill_robot(&mut msg, 7, 28, &fb, &EncodeOptions::default());
        msg.encode_to_vec()
    };
    r.iter("egm/decode EgmRobot (sensor side)", || {
        EgmRobot::decode(black_box(robot_bytes.as_slice())).unwrap()
    });
    let limits = ReferenceLimits::default();
    for (name, pattern, mode) in [
        ("joint", "sine:axis=1", EgmMode::Joint),
        ("pose", "circle", EgmMode::Pose),
        ("pathcorr", "pathcorr:y=1,z=2", EgmMode::PathCorr),
    ] {
        let reply = sensor_reply(pattern, &fb);
        r.iter(&format!("egm/decode+validate EgmSensor {name}"), || {
            decode_reference(
                black_box(&reply),
                mode,
                &Pose::IDENTITY,
                &limits,
                RobotTime::ZERO,
            )
            .unwrap()
        });
    }
}

fn session_and_sensor(r: &mut Runner<Criterion>) {
    let fb = feedback();
    let remote = "127.0.0.1:6510".parse().unwrap();
    let mut session = EgmSession::new(EgmConfig::new(EgmMode::Joint, remote)).unwrap();
    session.start(RobotTime::ZERO);
    let mut now = RobotTime::ZERO;
    let mut buf = Vec::with_capacity(1024);
    r.iter("egm/session poll_transmit_into (one cycle)", || {
        now += Duration::from_millis(4);
        black_box(session.poll_transmit_into(now, &fb, &mut buf))
    });
    let reply = sensor_reply("joint:1,2,3,4,5,6", &fb);
    r.iter("egm/session handle_datagram + poll_reference", || {
        session.handle_datagram(now, remote, black_box(&reply));
        black_box(session.poll_reference())
    });
    let mut robot = EgmRobot::default();
    fill_robot(&mut robot, 1, 4, &fb, &EncodeOptions::default());
    let robot_bytes = robot.encode_to_vec();
    let mut sensor = BuiltinSensor::new(SensorConfig::new("circle".parse().unwrap())).unwrap();
    r.iter(
        "egm/builtin sensor handle_datagram (decode + reply)",
        || {
            sensor
                .handle_datagram(now.since_start(), black_box(&robot_bytes))
                .unwrap()
        },
    );
    let params = ServoParams {
        cond_time: Duration::from_secs(1_000_000),
        ..ServoParams::default()
    };
    let mut servo = EgmServo::new(params, [0.0; 6]).unwrap();
    let input = ServoInput::position([10.0, -5.0, 20.0, 0.0, 40.0, 30.0]);
    r.iter("egm/servo step", || servo.step(black_box(&input)));
}

/// Encoded sizes of representative messages.
fn sizes() {
    let fb = feedback();
    let mut msg = EgmRobot::default();
    fill_robot(&mut msg, 1, 4, &fb, &EncodeOptions::default());
    println!(
        "EgmRobot V1.1 mandatory fields: {} bytes",
        msg.encoded_len()
    );
    fill_robot(&mut msg, 1, 4, &fb, &EncodeOptions { send_euler: true });
    println!(
        "  + euler in feedback and planned: {} bytes",
        msg.encoded_len()
    );
    let mut big = fb;
    big.external = ExternalAxes::from_slice(&[1.0; 6]);
    big.planned_external = big.external;
    big.move_index = Some(12);
    big.rapid_to_sensor = Some(RapidData::new(Some(true), &[1.0; 40]));
    fill_robot(&mut msg, 1, 4, &big, &EncodeOptions { send_euler: true });
    println!(
        "  + 6 external axes, moveIndex, RAPIDfromRobot with 40 dnum: {} bytes (limit 1024)",
        msg.encoded_len()
    );
    for (name, pattern) in [
        ("joint", "joint:1,2,3,4,5,6"),
        ("joint + speedRef", "sine:axis=1"),
        ("pose", "pose:1,2,3,0,0,0"),
        ("pose + speedRef", "circle"),
        ("path correction", "pathcorr:y=1,z=2"),
    ] {
        println!(
            "EgmSensor {name}: {} bytes",
            sensor_reply(pattern, &fb).len()
        );
    }
}

/// Real-socket round trip: send an EgmRobot, the built-in sensor thread replies, read it.
fn loopback(exchanges: u64) {
    let sensor_socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    sensor_socket
        .set_read_timeout(Some(Duration::from_secs(2)))
        .unwrap();
    let sensor_addr = sensor_socket.local_addr().unwrap();
    let thread = std::thread::spawn(move || {
        let mut sensor =
            BuiltinSensor::new(SensorConfig::new("sine:axis=1".parse().unwrap())).unwrap();
        let origin = Instant::now();
        let mut buf = vec![0u8; 2048];
        while let Ok((len, src)) = sensor_socket.recv_from(&mut buf) {
            if len == 0 {
                break;
            }
            let reply = sensor
                .handle_datagram(origin.elapsed(), &buf[..len])
                .unwrap();
            sensor_socket.send_to(&reply, src).unwrap();
        }
    });
    let mut transport = UdpTransport::for_device(0, sensor_addr).unwrap();
    let mut session = EgmSession::new(EgmConfig::new(EgmMode::Joint, sensor_addr)).unwrap();
    let origin = Instant::now();
    session.start(RobotTime::ZERO);
    let mut fb = feedback();
    let mut buf = Vec::with_capacity(1024);
    let mut rtt = LatencyHistogram::new();
    let mut lost = 0u32;
    mark();
    for k in 0..exchanges {
        let now = RobotTime::from_duration(Duration::from_millis(4 * k));
        fb.time = RobotTime::from_duration(origin.elapsed());
        assert!(session.poll_transmit_into(now, &fb, &mut buf));
        let sent = Instant::now();
        transport.send(&buf).unwrap();
        match transport.recv_timeout(Duration::from_secs(1)).unwrap() {
            Some((src, bytes)) => {
                rtt.record(sent.elapsed());
                session.handle_datagram(now, src, bytes);
                session.poll_reference();
            }
            None => lost += 1,
        }
    }
    mark();
    transport.send(&[]).unwrap();
    thread.join().unwrap();
    println!(
        "loopback round trip EgmRobot -> built-in sensor -> EgmSensor ({exchanges} exchanges, {lost} lost): {}",
        rtt.summary()
    );
    println!(
        "session: sent {} accepted {} dropped {}",
        session.stats().sent,
        session.stats().accepted,
        session.stats().dropped()
    );
}

/// A driver that never finishes (CondTime 9e9 s) for `device` = `pattern` or signals.
fn endless_driver(mode: EgmMode, pattern: Option<&str>, sample_ms: f64) -> (EgmDriver, Joints) {
    use rapidvc::config::devices::DeviceTable;
    use rapidvc::egm::registry::{ActJoint, ActPose, RunArgs, SetupSignals, SetupUc};
    use rapidvc::egm::servo::StopMode;
    let table = Arc::new(SignalTable::with_builtins());
    let overrides: Vec<_> = pattern
        .map(|p| format!("s=builtin:{p}").parse().unwrap())
        .into_iter()
        .collect();
    let devices = DeviceTable::new(None, &overrides).unwrap();
    let mut reg = EgmRegistry::new(registry_config(&Default::default(), &devices));
    let id = reg.get_id("egmID1").unwrap();
    if pattern.is_some() {
        let setup = SetupUc {
            mecunit: "ROB_1".into(),
            profile: "default".into(),
            device: "s".into(),
            mode,
            tracker: None,
            comm_timeout: None,
        };
        reg.setup_uc(id, &setup).unwrap();
    } else {
        let sig = |n: &str| Some(table.lookup(n).unwrap());
        let setup = SetupSignals {
            mecunit: "ROB_1".into(),
            profile: "default".into(),
            kind: rapidvc::signals::SignalKind::Ao,
            mode,
            tracker: None,
            mapping: [
                sig("ao_MoveX"),
                sig("ao_MoveY"),
                sig("ao_MoveZ"),
                None,
                None,
                None,
            ],
            ext: [None; 6],
        };
        reg.setup_signals(id, &setup, &table).unwrap();
        for (n, v) in [
            ("ao_MoveX", 900.0),
            ("ao_MoveY", 100.0),
            ("ao_MoveZ", 1200.0),
        ] {
            table.set(table.lookup(n).unwrap(), v).unwrap();
        }
    }
    let args = RunArgs {
        cond_time: Some(9e9),
        ..RunArgs::new(StopMode::Hold)
    };
    let plan = if mode == EgmMode::Joint {
        let mut a = ActJoint::default();
        a.common.max_speed_deviation = Some(100.0);
        a.common.sample_rate = Some(sample_ms);
        reg.act_joint(id, &a).unwrap();
        reg.run_joint(id, &args, [true, true, true, true, true, true, false])
            .unwrap()
    } else {
        let mut a = ActPose::world();
        a.common.max_speed_deviation = Some(100.0);
        a.common.sample_rate = Some(sample_ms);
        reg.act_pose(id, &a).unwrap();
        reg.run_pose(id, &args, [true, true, true, false, false, false], None)
            .unwrap()
    };
    let ctx = DriverContext {
        robot: Robot::default(),
        signals: table,
        options: DriverOptions::default(),
        drops: Default::default(),
    };
    let start = [0.0, 10.0, 10.0, 0.0, 40.0, 0.0];
    let source = EgmSource::new(&plan.source);
    let driver = EgmDriver::start(RobotTime::ZERO, &ctx, &plan, source, &start).unwrap();
    (driver, start)
}

fn driver(r: &mut Runner<Criterion>) {
    let cases = [
        (
            "egm/driver tick: joint, built-in sine (servo + EgmRobot + in-process reply)",
            EgmMode::Joint,
            Some("sine:axis=1,amplitude=5,frequency=0.5"),
            4.0,
        ),
        (
            "egm/driver tick: pose, built-in circle (IK + Jacobian every tick)",
            EgmMode::Pose,
            Some("circle:radius=50,frequency=0.5"),
            4.0,
        ),
        (
            "egm/driver tick: pose, AO signals every 4 ms (IK every tick)",
            EgmMode::Pose,
            None,
            4.0,
        ),
    ];
    for (name, mode, pattern, rate) in cases {
        let (mut d, mut q) = endless_driver(mode, pattern, rate);
        let mut now = RobotTime::ZERO;
        r.iter(name, || {
            now += Duration::from_millis(4);
            let t = d.tick(black_box(now), &q);
            q = t.joints_cmd;
            while d.poll_event().is_some() {}
            while d.pop_log().is_some() {}
            black_box(t.joints_cmd)
        });
        assert!(!d.is_finished(), "{name}: {:?}", d.outcome());
    }
}

fn main() {
    let bench_mode = std::env::args().any(|a| a == "--bench");
    let mut c = Criterion::default().configure_from_args();
    let mut r = Runner::new(&mut c);
    codec(&mut r);
    session_and_sensor(&mut r);
    driver(&mut r);
    if let Some(fixed) = r.fixed() {
        // Both threads: the controller side and the built-in sensor thread that replies.
        fixed.run("egm/loopback round trip (both sides)", loopback);
        return;
    }
    c.final_summary();
    sizes();
    loopback(if bench_mode { 5000 } else { 50 });
}
