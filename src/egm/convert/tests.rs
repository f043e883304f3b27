//! Unit tests of the proto ↔ domain conversion.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

use super::*;
use crate::egm::proto::{
    EgmCartesianSpeed, EgmEuler, EgmPathCorr, EgmSpeedRef, egm_header::MessageType,
};
use crate::egm::types::{MAX_EXTERNAL_AXES, MAX_RAPID_DNUM};

const T: RobotTime = RobotTime::from_millis(8);

fn header(mtype: MessageType) -> Option<EgmHeader> {
    Some(EgmHeader {
        seqno: Some(7),
        tm: Some(99),
        mtype: Some(mtype as i32),
    })
}

fn joint_msg(joints: Vec<f64>) -> EgmSensor {
    EgmSensor {
        header: header(MessageType::MsgtypeCorrection),
        planned: Some(EgmPlanned {
            joints: Some(EgmJoints { joints }),
            ..EgmPlanned::default()
        }),
        ..EgmSensor::default()
    }
}

fn pose_msg(pose: EgmPose) -> EgmSensor {
    EgmSensor {
        header: header(MessageType::MsgtypeCorrection),
        planned: Some(EgmPlanned {
            cartesian: Some(pose),
            ..EgmPlanned::default()
        }),
        ..EgmSensor::default()
    }
}

fn decode(msg: &impl Message, mode: EgmMode) -> Result<SensorReference, DecodeError> {
    decode_reference(
        &msg.encode_to_vec(),
        mode,
        &Pose::IDENTITY,
        &ReferenceLimits::default(),
        T,
    )
}

fn rejected(r: Result<SensorReference, DecodeError>) -> ReferenceError {
    match r {
        Err(DecodeError::Rejected(e)) => e,
        other => panic!("expected a rejection, got {other:?}"),
    }
}

fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

#[test]
fn joint_reference_takes_six_values_and_ignores_extras() {
    let r = decode(
        &joint_msg(vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]),
        EgmMode::Joint,
    )
    .unwrap();
    assert_eq!(r.received_at, T);
    assert_eq!(r.header.seqno, Some(7));
    assert_eq!(r.header.tm, Some(99));
    let Target::Joint(j) = r.target else {
        panic!("not joint")
    };
    assert_eq!(j.joints, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    assert_eq!(j.speed, [0.0; 6]);
    assert!(j.external.is_empty());
}

#[test]
fn joint_reference_reads_speed_external_axes_and_rapid_data() {
    let mut msg = joint_msg(vec![0.0; 6]);
    msg.speed_ref = Some(EgmSpeedRef {
        joints: Some(EgmJoints {
            joints: vec![1.0; 6],
        }),
        cartesians: None,
        external_joints: Some(EgmJoints {
            joints: vec![2.0; 8],
        }),
    });
    if let Some(p) = msg.planned.as_mut() {
        p.external_joints = Some(EgmJoints {
            joints: vec![3.0, 4.0],
        });
    }
    msg.set_rapid_to_robot(Some(EgmRapidData {
        dig_val: Some(true),
        dnum: (0..50).map(f64::from).collect(),
    }));
    let r = decode(&msg, EgmMode::Joint).unwrap();
    let Target::Joint(j) = r.target else {
        panic!("not joint")
    };
    assert_eq!(j.speed, [1.0; 6]);
    assert_eq!(j.external.as_slice(), &[3.0, 4.0]);
    assert_eq!(j.external_speed.as_slice(), &[2.0; MAX_EXTERNAL_AXES]);
    let rapid = r.rapid.unwrap();
    assert_eq!(rapid.dig_val, Some(true));
    assert_eq!(rapid.dnum().len(), MAX_RAPID_DNUM);
}

#[test]
fn joint_reference_rejects_short_nan_infinite_and_out_of_range() {
    assert_eq!(
        rejected(decode(&joint_msg(vec![0.0; 5]), EgmMode::Joint)),
        ReferenceError::TooFewValues {
            field: "planned.joints",
            got: 5,
            need: 6
        }
    );
    let mut nan = vec![0.0; 6];
    nan[3] = f64::NAN;
    assert!(matches!(
        rejected(decode(&joint_msg(nan), EgmMode::Joint)),
        ReferenceError::NotFinite { .. }
    ));
    let mut inf = vec![0.0; 6];
    inf[0] = f64::NEG_INFINITY;
    assert!(matches!(
        rejected(decode(&joint_msg(inf), EgmMode::Joint)),
        ReferenceError::NotFinite { .. }
    ));
    let mut big = vec![0.0; 6];
    big[5] = 1e300;
    assert!(matches!(
        rejected(decode(&joint_msg(big), EgmMode::Joint)),
        ReferenceError::OutOfRange { .. }
    ));
    let limits = ReferenceLimits {
        joint_max: [10.0; 6],
        ..ReferenceLimits::default()
    };
    let bytes = joint_msg(vec![11.0, 0.0, 0.0, 0.0, 0.0, 0.0]).encode_to_vec();
    let r = decode_reference(&bytes, EgmMode::Joint, &Pose::IDENTITY, &limits, T);
    assert!(matches!(
        rejected(r),
        ReferenceError::OutOfRange { value, .. } if value == 11.0
    ));
}

#[test]
fn joint_mode_without_joints_is_rejected() {
    let msg = pose_msg(EgmPose::default());
    assert!(matches!(
        rejected(decode(&msg, EgmMode::Joint)),
        ReferenceError::MissingTarget {
            field: "planned.joints",
            ..
        }
    ));
    assert!(matches!(
        rejected(decode(&EgmSensor::default(), EgmMode::Joint)),
        ReferenceError::MissingTarget { .. }
    ));
}

#[test]
fn pose_mode_ignores_joints_and_normalises_the_quaternion() {
    let mut msg = pose_msg(EgmPose {
        pos: Some(EgmCartesian {
            x: 100.0,
            y: -20.0,
            z: 300.0,
        }),
        orient: Some(EgmQuaternion {
            u0: 2.0,
            u1: 0.0,
            u2: 0.0,
            u3: 0.0,
        }),
        euler: None,
    });
    // libegm sends joints too; pose mode must ignore them, even a short list.
    if let Some(p) = msg.planned.as_mut() {
        p.joints = Some(EgmJoints { joints: vec![1.0] });
    }
    let r = decode(&msg, EgmMode::Pose).unwrap();
    let Target::Pose(p) = r.target else {
        panic!("not pose")
    };
    assert_eq!(p.pose.pos, [100.0, -20.0, 300.0]);
    assert_eq!(p.pose.orient, [1.0, 0.0, 0.0, 0.0]);
}

#[test]
fn euler_wins_over_quaternion() {
    let msg = pose_msg(EgmPose {
        pos: None,
        orient: Some(EgmQuaternion {
            u0: 1.0,
            u1: 0.0,
            u2: 0.0,
            u3: 0.0,
        }),
        euler: Some(EgmEuler {
            x: 0.0,
            y: 0.0,
            z: 90.0,
        }),
    });
    let Target::Pose(p) = decode(&msg, EgmMode::Pose).unwrap().target else {
        panic!("not pose")
    };
    let h = std::f64::consts::FRAC_1_SQRT_2;
    assert!(close(&p.pose.orient, &[h, 0.0, 0.0, h], 1e-12), "{p:?}");
}

#[test]
fn missing_pose_parts_keep_the_previous_reference() {
    let previous = Pose {
        pos: [1.0, 2.0, 3.0],
        orient: [0.0, 1.0, 0.0, 0.0],
    };
    let only_pos = pose_msg(EgmPose {
        pos: Some(EgmCartesian {
            x: 9.0,
            y: 8.0,
            z: 7.0,
        }),
        orient: None,
        euler: None,
    });
    let r = decode_reference(
        &only_pos.encode_to_vec(),
        EgmMode::Pose,
        &previous,
        &ReferenceLimits::default(),
        T,
    )
    .unwrap();
    let Target::Pose(p) = r.target else {
        panic!("not pose")
    };
    assert_eq!(p.pose.pos, [9.0, 8.0, 7.0]);
    assert_eq!(p.pose.orient, previous.orient);

    let only_orient = pose_msg(EgmPose {
        pos: None,
        orient: Some(EgmQuaternion {
            u0: 0.0,
            u1: 0.0,
            u2: 0.0,
            u3: 1.0,
        }),
        euler: None,
    });
    let r = decode_reference(
        &only_orient.encode_to_vec(),
        EgmMode::Pose,
        &previous,
        &ReferenceLimits::default(),
        T,
    )
    .unwrap();
    let Target::Pose(p) = r.target else {
        panic!("not pose")
    };
    assert_eq!(p.pose.pos, previous.pos);
    assert_eq!(p.pose.orient, [0.0, 0.0, 0.0, 1.0]);

    assert!(matches!(
        rejected(decode(&pose_msg(EgmPose::default()), EgmMode::Pose)),
        ReferenceError::MissingTarget { .. }
    ));
}

#[test]
fn zero_and_nan_quaternions_are_rejected() {
    let zero = pose_msg(EgmPose {
        pos: None,
        orient: Some(EgmQuaternion {
            u0: 0.0,
            u1: 0.0,
            u2: 0.0,
            u3: 0.0,
        }),
        euler: None,
    });
    assert_eq!(
        rejected(decode(&zero, EgmMode::Pose)),
        ReferenceError::ZeroQuaternion
    );
    let nan = pose_msg(EgmPose {
        pos: None,
        orient: None,
        euler: Some(EgmEuler {
            x: f64::NAN,
            y: 0.0,
            z: 0.0,
        }),
    });
    assert!(matches!(
        rejected(decode(&nan, EgmMode::Pose)),
        ReferenceError::NotFinite { .. }
    ));
}

#[test]
fn missing_required_leaf_is_rejected() {
    // planned { cartesian { pos { x: 1, y: 2 } } } with z left out, written by hand.
    let mut pos = vec![0x09];
    pos.extend_from_slice(&1.0f64.to_le_bytes());
    pos.push(0x11);
    pos.extend_from_slice(&2.0f64.to_le_bytes());
    let wrap = |tag: u8, inner: &[u8]| {
        let mut v = vec![tag, u8::try_from(inner.len()).unwrap()];
        v.extend_from_slice(inner);
        v
    };
    let bytes = wrap(0x12, &wrap(0x12, &wrap(0x0a, &pos)));
    let r = decode_reference(
        &bytes,
        EgmMode::Pose,
        &Pose::IDENTITY,
        &ReferenceLimits::default(),
        T,
    );
    assert_eq!(
        rejected(r),
        ReferenceError::MissingRequired {
            field: "planned.cartesian.pos"
        }
    );
}

#[test]
fn cartesian_speed_accepts_three_or_six_values() {
    let mut msg = pose_msg(EgmPose {
        pos: Some(EgmCartesian {
            x: 0.0,
            y: 0.0,
            z: 0.0,
        }),
        orient: None,
        euler: None,
    });
    msg.speed_ref = Some(EgmSpeedRef {
        joints: None,
        cartesians: Some(EgmCartesianSpeed {
            value: vec![1.0, 2.0, 3.0],
        }),
        external_joints: None,
    });
    let Target::Pose(p) = decode(&msg, EgmMode::Pose).unwrap().target else {
        panic!("not pose")
    };
    assert_eq!(p.speed, [1.0, 2.0, 3.0, 0.0, 0.0, 0.0]);
    if let Some(s) = msg.speed_ref.as_mut() {
        s.cartesians = Some(EgmCartesianSpeed {
            value: vec![1.0; 4],
        });
    }
    assert!(matches!(
        rejected(decode(&msg, EgmMode::Pose)),
        ReferenceError::TooFewValues { .. }
    ));
}

#[test]
fn path_correction_decodes_and_needs_its_required_fields() {
    let msg = EgmSensorPathCorr {
        header: header(MessageType::MsgtypePathCorrection),
        path_corr: Some(EgmPathCorr {
            pos: EgmCartesian {
                x: 0.0,
                y: 1.5,
                z: -2.0,
            },
            age: 1,
        }),
    };
    let r = decode(&msg, EgmMode::PathCorr).unwrap();
    assert_eq!(
        r.target,
        Target::PathCorr(PathCorrection {
            pos: [0.0, 1.5, -2.0],
            age_ms: 1
        })
    );
    // pathCorr with only `age`: prost accepts, rapidvc rejects.
    let bytes = [0x12, 0x02, 0x10, 0x01];
    let r = decode_reference(
        &bytes,
        EgmMode::PathCorr,
        &Pose::IDENTITY,
        &ReferenceLimits::default(),
        T,
    );
    assert!(matches!(
        rejected(r),
        ReferenceError::MissingRequired { .. }
    ));
}

#[test]
fn message_type_is_a_cross_check_only() {
    let mut msg = joint_msg(vec![0.0; 6]);
    msg.header = None;
    assert!(decode(&msg, EgmMode::Joint).is_ok(), "header is optional");
    msg.header = header(MessageType::MsgtypeUndefined);
    assert!(decode(&msg, EgmMode::Joint).is_ok());
    msg.header = header(MessageType::MsgtypePathCorrection);
    assert!(matches!(
        rejected(decode(&msg, EgmMode::Joint)),
        ReferenceError::WrongMessageType { mtype: 4, .. }
    ));
    // A controller DATA message is never a reference.
    msg.header = header(MessageType::MsgtypeData);
    assert!(matches!(
        rejected(decode(&msg, EgmMode::Joint)),
        ReferenceError::WrongMessageType { mtype: 2, .. }
    ));
    // Our own EgmRobot echoed back (a device pointing at itself) is never accepted.
    let mut robot = EgmRobot::default();
    let fb = RobotFeedback::standing([1.0; 6], Pose::IDENTITY);
    fill_robot(&mut robot, 0, 0, &fb, &EncodeOptions::default());
    assert!(decode(&robot, EgmMode::Joint).is_err());
    assert!(decode(&robot, EgmMode::Pose).is_err());
}

#[test]
fn garbage_is_malformed() {
    let r = decode_reference(
        &[0xff, 0xff, 0xff],
        EgmMode::Joint,
        &Pose::IDENTITY,
        &ReferenceLimits::default(),
        T,
    );
    assert!(matches!(r, Err(DecodeError::Malformed { .. })));
}

fn rot_x(a: f64) -> nalgebra::Matrix3<f64> {
    let (s, c) = a.sin_cos();
    nalgebra::Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}
fn rot_y(a: f64) -> nalgebra::Matrix3<f64> {
    let (s, c) = a.sin_cos();
    nalgebra::Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)
}
fn rot_z(a: f64) -> nalgebra::Matrix3<f64> {
    let (s, c) = a.sin_cos();
    nalgebra::Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

#[test]
fn euler_is_zyx_and_round_trips() {
    for angles in [
        [10.0, 20.0, 30.0],
        [-170.0, 45.0, 90.0],
        [0.0, -89.0, 179.0],
        [0.0, 0.0, 0.0],
    ] {
        let q = quaternion_from_euler_zyx(angles);
        let [x, y, z] = angles.map(f64::to_radians);
        let expected = rot_z(z) * rot_y(y) * rot_x(x);
        let unit = UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3]));
        let got = unit.to_rotation_matrix().into_inner();
        assert!((got - expected).abs().max() < 1e-12, "{angles:?}");
        let back = euler_zyx_from_quaternion(q);
        assert!(close(&back, &angles, 1e-9), "{angles:?} -> {back:?}");
    }
}

#[test]
fn robot_message_has_every_mandatory_field_and_no_force() {
    let mut fb = RobotFeedback::standing([1.0, 2.0, 3.0, 4.0, 5.0, 6.0], Pose::IDENTITY);
    fb.time = RobotTime::from_duration(Duration::new(12, 345_678_000));
    fb.planned_time = RobotTime::from_duration(Duration::new(12, 349_678_000));
    fb.utilization = 12.5;
    let mut msg = EgmRobot::default();
    fill_robot(&mut msg, 3, 4000, &fb, &EncodeOptions::default());
    let bytes = msg.encode_to_vec();
    let back = EgmRobot::decode(bytes.as_slice()).unwrap();
    let h = back.header.unwrap();
    assert_eq!(
        (h.seqno, h.tm, h.mtype),
        (Some(3), Some(4000), Some(MessageType::MsgtypeData as i32))
    );
    let feed = back.feedback().unwrap();
    assert_eq!(feed.joints.as_ref().unwrap().joints.len(), 6);
    let cart = feed.cartesian.as_ref().unwrap();
    assert!(cart.pos.is_some() && cart.orient.is_some() && cart.euler.is_none());
    assert_eq!(
        feed.time,
        Some(EgmClock {
            sec: 12,
            usec: 345_678
        })
    );
    let planned = back.planned.as_ref().unwrap();
    assert_eq!(planned.joints.as_ref().unwrap().joints.len(), 6);
    assert!(planned.cartesian.as_ref().unwrap().orient.is_some());
    assert_eq!(planned.time.as_ref().unwrap().usec, 349_678);
    assert_eq!(
        back.motor_state.unwrap().state,
        MotorStateType::MotorsOn as i32
    );
    assert_eq!(
        back.mci_state.unwrap().state,
        MciStateType::MciRunning as i32
    );
    assert_eq!(
        back.rapid_exec_state.unwrap().state,
        RapidCtrlExecStateType::RapidRunning as i32
    );
    assert_eq!(back.mci_convergence_met, Some(false));
    assert_eq!(back.utilization_rate, Some(12.5));
    assert!(back.measured_force.is_none());
    assert!(back.rapid_from_robot().is_none());
    // A complete V1.1-layout message is under 400 bytes (docs/egm.md, "Messages sent").
    assert!(bytes.len() < 400, "{} bytes", bytes.len());
}

#[test]
fn largest_robot_message_fits_in_1024_bytes() {
    let mut fb = RobotFeedback::standing([-123.456_789; 6], Pose::IDENTITY);
    fb.external = ExternalAxes::from_slice(&[1e5; 6]);
    fb.planned_external = fb.external;
    fb.time = RobotTime::from_duration(Duration::new(u64::from(u32::MAX), 999_999_000));
    fb.planned_time = fb.time;
    fb.move_index = Some(u32::MAX);
    fb.rapid_to_sensor = Some(RapidData::new(Some(true), &[1e300; MAX_RAPID_DNUM]));
    fb.pose.orient = normalize_quaternion([0.1, 0.2, 0.3, 0.4]).unwrap();
    let mut msg = EgmRobot::default();
    fill_robot(
        &mut msg,
        u32::MAX,
        u32::MAX,
        &fb,
        &EncodeOptions { send_euler: true },
    );
    let len = msg.encoded_len();
    assert!(len <= 1024, "{len} bytes");
    let euler = msg
        .feedback()
        .unwrap()
        .cartesian
        .as_ref()
        .unwrap()
        .euler
        .unwrap();
    let q = quaternion_from_euler_zyx([euler.x, euler.y, euler.z]);
    let same = close(&q, &fb.pose.orient, 1e-12) || close(&q.map(|v| -v), &fb.pose.orient, 1e-12);
    assert!(same, "euler consistent with orient");
}

#[test]
fn fill_robot_reuses_and_clears_optional_parts() {
    let mut fb = RobotFeedback::standing([0.0; 6], Pose::IDENTITY);
    fb.external = ExternalAxes::from_slice(&[1.0]);
    fb.rapid_to_sensor = Some(RapidData::new(None, &[1.0, 2.0]));
    let mut msg = EgmRobot::default();
    fill_robot(&mut msg, 0, 0, &fb, &EncodeOptions::default());
    assert!(msg.feedback().unwrap().external_joints.is_some());
    assert_eq!(msg.rapid_from_robot().unwrap().dnum, vec![1.0, 2.0]);
    let plain = RobotFeedback::standing([0.0; 6], Pose::IDENTITY);
    fill_robot(&mut msg, 1, 4, &plain, &EncodeOptions::default());
    assert!(msg.feedback().unwrap().external_joints.is_none());
    assert!(msg.rapid_from_robot().is_none());
}

#[test]
fn non_finite_feedback_is_named() {
    let mut fb = RobotFeedback::standing([0.0; 6], Pose::IDENTITY);
    assert_eq!(feedback_non_finite(&fb), None);
    fb.planned_pose.pos[1] = f64::INFINITY;
    assert_eq!(feedback_non_finite(&fb), Some("planned.cartesian.pos"));
    fb.planned_pose.pos[1] = 0.0;
    fb.rapid_to_sensor = Some(RapidData::new(None, &[f64::NAN]));
    assert_eq!(feedback_non_finite(&fb), Some("RAPIDfromRobot.dnum"));
}

#[test]
fn clock_and_tm_conversions() {
    let t = RobotTime::from_duration(Duration::new(5, 4_001_999));
    assert_eq!(clock(t), EgmClock { sec: 5, usec: 4001 });
    assert_eq!(clock_to_duration(&clock(t)), Duration::new(5, 4_001_000));
    assert_eq!(header_tm(RobotTime::from_millis(1234)), 1234);
    assert_eq!(
        header_tm(RobotTime::from_millis((1u64 << 32) + 5)),
        5,
        "wraps at 2^32"
    );
    assert_eq!(
        clock_to_duration(&EgmClock {
            sec: u64::MAX,
            usec: u64::MAX
        }),
        Duration::MAX
    );
}

#[test]
fn poses_convert_to_and_from_the_robot_module() {
    let p = Pose {
        pos: [500.0, -10.0, 600.0],
        orient: normalize_quaternion([0.1, 0.7, 0.2, 0.3]).unwrap(),
    };
    let back = Pose::from(&p.to_robot());
    assert!(close(&back.pos, &p.pos, 1e-12));
    let same =
        close(&back.orient, &p.orient, 1e-12) || close(&back.orient.map(|v| -v), &p.orient, 1e-12);
    assert!(same, "{back:?}");
}
