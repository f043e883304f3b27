//! Unit tests of the built-in sensor and its patterns.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

use super::*;
use crate::egm::convert::{
    EncodeOptions, ReferenceLimits, decode_reference, fill_robot, quaternion_from_euler_zyx,
};
use crate::egm::types::{RobotFeedback, SensorReference, Target};
use crate::time::RobotTime;

const MS: Duration = Duration::from_millis(1);

fn robot_bytes(seqno: u32, joints: Joints, pose: Pose) -> Vec<u8> {
    let mut fb = RobotFeedback::standing(joints, pose);
    fb.time = RobotTime::from_duration(MS * 4 * seqno);
    fb.planned_time = fb.time;
    let mut msg = EgmRobot::default();
    fill_robot(&mut msg, seqno, 4 * seqno, &fb, &EncodeOptions::default());
    msg.encode_to_vec()
}

fn start_pose() -> Pose {
    Pose {
        pos: [500.0, 0.0, 600.0],
        orient: [0.0, 0.0, 1.0, 0.0],
    }
}

fn decode(bytes: &[u8], mode: EgmMode) -> SensorReference {
    decode_reference(
        bytes,
        mode,
        &Pose::IDENTITY,
        &ReferenceLimits::default(),
        RobotTime::ZERO,
    )
    .unwrap()
}

fn sensor(text: &str) -> BuiltinSensor {
    BuiltinSensor::new(SensorConfig::new(text.parse().unwrap())).unwrap()
}

#[test]
fn parses_every_pattern_form() {
    assert_eq!(
        "hold".parse::<SensorPattern>().unwrap(),
        SensorPattern::Hold(EgmMode::Joint)
    );
    assert_eq!(
        "HOLD-POSE".parse::<SensorPattern>().unwrap().mode(),
        EgmMode::Pose
    );
    assert_eq!(
        "joint:1,2,3,4,5,6".parse::<SensorPattern>().unwrap(),
        SensorPattern::Joint([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
    );
    assert_eq!(
        "pose: 500, 0, 600, 0, 180, 0"
            .parse::<SensorPattern>()
            .unwrap(),
        SensorPattern::Pose {
            pos: [500.0, 0.0, 600.0],
            euler: [0.0, 180.0, 0.0]
        }
    );
    assert_eq!(
        "sine".parse::<SensorPattern>().unwrap(),
        SensorPattern::Sine {
            axis: SineAxis::Joint(0),
            amplitude: 10.0,
            frequency_hz: 0.1
        }
    );
    let s: SensorPattern = "sine:axis=z,amplitude=20,frequency=0.5".parse().unwrap();
    assert_eq!(
        s,
        SensorPattern::Sine {
            axis: SineAxis::Cartesian(2),
            amplitude: 20.0,
            frequency_hz: 0.5
        }
    );
    assert_eq!(s.mode(), EgmMode::Pose);
    assert_eq!(
        "circle:radius=30".parse::<SensorPattern>().unwrap(),
        SensorPattern::Circle {
            radius_mm: 30.0,
            frequency_hz: 0.1
        }
    );
    assert_eq!(
        "pathcorr:kind=ramp,y=2,z=-1,time=0.5"
            .parse::<SensorPattern>()
            .unwrap(),
        SensorPattern::PathCorr {
            profile: PathCorrProfile::Ramp { time_s: 0.5 },
            y_mm: 2.0,
            z_mm: -1.0
        }
    );
}

#[test]
fn rejects_bad_patterns_with_clear_messages() {
    for (text, needle) in [
        ("wiggle", "unknown sensor pattern `wiggle`"),
        ("joint:1,2,3", "joint needs 6 values"),
        ("joint:1,2,3,4,5,6,7", "joint needs 6 values"),
        ("joint:1,2,3,4,5,nan", "not a finite number"),
        ("pose:1,2,3", "pose needs 6 values"),
        ("sine:axis=7", "axis `7`"),
        ("sine:speed=3", "sine has no parameter `speed`"),
        ("sine:frequency=-1", "frequency"),
        ("circle:radius", "is not key=value"),
        ("circle:radius=-5", "radius"),
        ("pathcorr:kind=zigzag", "kind `zigzag`"),
        ("pathcorr:kind=ramp,time=0", "ramp time"),
        ("hold:1", "takes no values"),
    ] {
        let err = text.parse::<SensorPattern>().unwrap_err().to_string();
        assert!(err.contains(needle), "{text}: {err}");
    }
    assert!(BuiltinSensor::new(SensorConfig::new(SensorPattern::Hold(EgmMode::PathCorr))).is_err());
}

#[test]
fn pattern_outputs_start_at_the_origin_and_carry_their_speed() {
    let origin = Origin {
        joints: Some([10.0, 0.0, 0.0, 0.0, 30.0, 0.0]),
        pose: Some(start_pose()),
    };
    let sine: SensorPattern = "sine:axis=2,amplitude=5,frequency=0.25".parse().unwrap();
    let PatternOutput::Joint { joints, speed } = sine.output(&origin, 0.0).unwrap() else {
        panic!()
    };
    assert_eq!(joints, [10.0, 0.0, 0.0, 0.0, 30.0, 0.0]);
    let peak = 5.0 * std::f64::consts::TAU * 0.25;
    assert!((speed.unwrap()[1] - peak).abs() < 1e-12);
    let PatternOutput::Joint { joints, .. } = sine.output(&origin, 1.0).unwrap() else {
        panic!()
    };
    assert!((joints[1] - 5.0).abs() < 1e-12, "quarter period");

    let circle: SensorPattern = "circle:radius=50,frequency=0.25".parse().unwrap();
    let PatternOutput::Pose { pose, .. } = circle.output(&origin, 0.0).unwrap() else {
        panic!()
    };
    assert_eq!(pose, start_pose());
    let PatternOutput::Pose { pose, .. } = circle.output(&origin, 2.0).unwrap() else {
        panic!()
    };
    assert!((pose.pos[0] - 400.0).abs() < 1e-9 && pose.pos[1].abs() < 1e-9);

    let ramp: SensorPattern = "pathcorr:kind=ramp,y=4,z=2,time=2".parse().unwrap();
    assert_eq!(
        ramp.output(&origin, 1.0).unwrap(),
        PatternOutput::PathCorr {
            pos: [0.0, 2.0, 1.0]
        }
    );
    assert_eq!(
        ramp.output(&origin, 5.0).unwrap(),
        PatternOutput::PathCorr {
            pos: [0.0, 4.0, 2.0]
        }
    );
    let none = Origin {
        joints: None,
        pose: None,
    };
    assert!(matches!(
        sine.output(&none, 0.0),
        Err(PatternError::NoOrigin(_))
    ));
}

#[test]
fn joint_replies_decode_on_the_controller_side() {
    let mut s = sensor("joint:1,2,3,4,5,6");
    let start = [0.0, 0.0, 0.0, 0.0, 30.0, 0.0];
    let reply = s
        .handle_datagram(MS * 100, &robot_bytes(0, start, start_pose()))
        .unwrap();
    let r = decode(&reply, EgmMode::Joint);
    assert_eq!(r.header.seqno, Some(0));
    assert_eq!(r.header.tm, Some(100));
    let Target::Joint(j) = r.target else { panic!() };
    assert_eq!(j.joints, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    assert_eq!(j.speed, [0.0; 6], "constant target: no speed reference");
    let reply = s
        .handle_datagram(MS * 104, &robot_bytes(1, start, start_pose()))
        .unwrap();
    assert_eq!(decode(&reply, EgmMode::Joint).header.seqno, Some(1));
    let st = s.stats();
    assert_eq!(
        (st.received, st.replied, st.sessions, st.incomplete),
        (2, 2, 1, 0)
    );
    assert_eq!(st.interval.max(), Some(MS * 4));
    assert_eq!(s.last_robot().unwrap().seqno, Some(1));
    assert_eq!(s.last_robot().unwrap().mci_state, Some(MciState::Running));
}

#[test]
fn pose_replies_carry_the_quaternion_of_the_euler_target() {
    let mut s = sensor("pose:400,100,500,0,90,0");
    let reply = s
        .handle_datagram(Duration::ZERO, &robot_bytes(0, [0.0; 6], start_pose()))
        .unwrap();
    let Target::Pose(p) = decode(&reply, EgmMode::Pose).target else {
        panic!()
    };
    assert_eq!(p.pose.pos, [400.0, 100.0, 500.0]);
    let q = quaternion_from_euler_zyx([0.0, 90.0, 0.0]);
    assert!(
        p.pose
            .orient
            .iter()
            .zip(&q)
            .all(|(a, b)| (a - b).abs() < 1e-12)
    );
}

#[test]
fn moving_patterns_send_speed_unless_disabled() {
    let mut s = sensor("circle:radius=10,frequency=1");
    let reply = s
        .handle_datagram(Duration::ZERO, &robot_bytes(0, [0.0; 6], start_pose()))
        .unwrap();
    let Target::Pose(p) = decode(&reply, EgmMode::Pose).target else {
        panic!()
    };
    assert!((p.speed[1] - 10.0 * std::f64::consts::TAU).abs() < 1e-9);
    let mut cfg = SensorConfig::new("circle".parse().unwrap());
    cfg.speed_feedforward = false;
    let mut quiet = BuiltinSensor::new(cfg).unwrap();
    let reply = quiet
        .handle_datagram(Duration::ZERO, &robot_bytes(0, [0.0; 6], start_pose()))
        .unwrap();
    let Target::Pose(p) = decode(&reply, EgmMode::Pose).target else {
        panic!()
    };
    assert_eq!(p.speed, [0.0; 6]);
}

#[test]
fn path_correction_replies_are_egm_sensor_path_corr() {
    let mut s = sensor("pathcorr:y=1.5,z=-2");
    assert_eq!(s.mode(), EgmMode::PathCorr);
    let reply = s
        .handle_datagram(Duration::ZERO, &robot_bytes(0, [0.0; 6], start_pose()))
        .unwrap();
    let r = decode(&reply, EgmMode::PathCorr);
    assert_eq!(
        r.header.mtype,
        Some(MessageType::MsgtypePathCorrection as i32)
    );
    let Target::PathCorr(c) = r.target else {
        panic!()
    };
    assert_eq!((c.pos, c.age_ms), ([0.0, 1.5, -2.0], 1));
}

#[test]
fn a_new_controller_session_resets_origin_time_and_seqno() {
    let mut s = sensor("sine:axis=1,amplitude=10,frequency=0.25");
    let a = [0.0, 0.0, 0.0, 0.0, 30.0, 0.0];
    s.handle_datagram(Duration::ZERO, &robot_bytes(0, a, start_pose()))
        .unwrap();
    s.handle_datagram(MS * 4, &robot_bytes(1, a, start_pose()))
        .unwrap();
    s.handle_datagram(MS * 8, &robot_bytes(3, a, start_pose()))
        .unwrap();
    assert_eq!(s.stats().seqno_gaps, 1);
    let b = [20.0, 0.0, 0.0, 0.0, 30.0, 0.0];
    let reply = s
        .handle_datagram(Duration::from_secs(10), &robot_bytes(0, b, start_pose()))
        .unwrap();
    let r = decode(&reply, EgmMode::Joint);
    assert_eq!(r.header.seqno, Some(0));
    let Target::Joint(j) = r.target else { panic!() };
    assert_eq!(j.joints[0], 20.0, "new origin, t = 0");
    assert_eq!(s.stats().sessions, 2);
    assert_eq!(s.origin().unwrap().joints, Some(b));
}

#[test]
fn bad_input_is_counted_not_answered() {
    let mut s = sensor("hold");
    assert!(matches!(
        s.handle_datagram(Duration::ZERO, &[0xff, 0xff]),
        Err(SensorError::Decode(_))
    ));
    // An empty EgmRobot: incomplete and no joints to hold.
    assert!(matches!(
        s.handle_datagram(Duration::ZERO, &[]),
        Err(SensorError::Pattern(PatternError::NoOrigin(_)))
    ));
    assert_eq!(s.stats().decode_errors, 1);
    assert_eq!(s.stats().incomplete, 1);
    assert_eq!(s.stats().replied, 0);
    assert!(s.last_missing().contains(&"feedBack.time"));
}

#[test]
fn mandatory_items_are_listed() {
    let complete = EgmRobot::decode(robot_bytes(5, [0.0; 6], start_pose()).as_slice()).unwrap();
    assert!(missing_mandatory(&complete).is_empty());
    let mut partial = complete.clone();
    partial.mci_convergence_met = None;
    partial.feedback_mut().time = None;
    assert_eq!(
        missing_mandatory(&partial),
        vec!["feedBack.time", "mciConvergenceMet"]
    );
    assert_eq!(missing_mandatory(&EgmRobot::default()).len(), 14);
}
