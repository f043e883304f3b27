//! Integration tests of EGM position guidance geometry: the manual's examples through the full
//! pipeline (signals → sensor pose → frames → TCP → IK nearest), frame types, selection,
//! `\Offset`, convergence, supervision and speed references (docs/robot.md, "Acceptance
//! facts"; docs/egm.md, "Frames in pose mode", "Signal sources").

// Expected values are quoted digit for digit from docs/robot.md and the manual.
#![allow(clippy::approx_constant)]

use rapidvc::egm::geometry as guidance;
use rapidvc_testkit::robot::{JOINT_TOL, POS_TOL, QUAT_TOL, assert_joints, t_fronius_cmt};

use guidance::{
    Convergence, EgmFrameType, FeedbackMode, GuidanceError, PoseGuidance, PoseSetup, SignalSource,
    SpeedRefLimit, tcp_jacobian,
};
use nalgebra::{UnitQuaternion, Vector3, Vector6};
use rapidvc::robot::units::{pose_from_pos_quat, pose_to_pos_quat};
use rapidvc::robot::{
    ConfData, JointsDeg, KinError, Pose, Robot, SingularityKind, ToolData, WobjData,
};
use rapidvc::signals::{SignalKind, SignalTable};

const P20_ORIENT: [f64; 4] = [0.000494947, 0.662278, -0.749217, -0.00783173];
const XYZ: [bool; 6] = [true, true, true, false, false, false];

fn robot() -> Robot {
    Robot::default()
}

fn wobj_at(uframe: Pose, oframe: Pose) -> WobjData {
    WobjData {
        uframe,
        oframe,
        ..WobjData::wobj0()
    }
}

/// The manual's start for the signal example: `MoveJ p30, v1000, fine, tool0`.
fn p30_joints(r: &Robot) -> JointsDeg {
    let p30 = pose_from_pos_quat(
        [114.50, 1005.42, 1410.38],
        [0.322151, -0.601023, 0.672381, 0.287914],
    );
    r.ik_conf(&p30, &ConfData::new(0, 0, -1, 0)).unwrap()
}

/// `MoveJ p20, v1000, fine, tFroniusCMT` reaches the same joints as p30 with tool0.
fn p20_joints(r: &Robot) -> JointsDeg {
    let p20 = pose_from_pos_quat([150.0, 1320.0, 1140.0], P20_ORIENT);
    let flange = p20 * t_fronius_cmt().tframe.inverse();
    r.ik_conf(&flange, &ConfData::new(0, 0, -1, 0)).unwrap()
}

fn assert_pos(p: &Pose, expected: [f64; 3], tol: f64) {
    let d = p.translation.vector - Vector3::from(expected);
    assert!(
        d.norm() <= tol,
        "{:?} vs {expected:?}",
        p.translation.vector
    );
}

fn assert_orient(p: &Pose, expected: [f64; 4]) {
    let (_, q) = pose_to_pos_quat(p);
    let sign = if q[0] * expected[0] + q[1] * expected[1] + q[2] * expected[2] + q[3] * expected[3]
        < 0.0
    {
        -1.0
    } else {
        1.0
    };
    for i in 0..4 {
        assert!(
            (sign * q[i] - expected[i]).abs() <= QUAT_TOL,
            "{q:?} vs {expected:?}"
        );
    }
}

/// The TCP of tFroniusCMT at `q`.
fn tcp(r: &Robot, q: &JointsDeg) -> Pose {
    r.fk(q) * t_fronius_cmt().tframe
}

/// The AO source of the manual's pose-mode setup:
/// `EGMSetupAO ROB_1, egmID1, "default" \Pose \aoR1x:=ao_MoveX \aoR2y:=ao_MoveY
/// \aoR3z:=ao_MoveZ \aoR5ry:=ao_RotY \aoR6rz:=ao_RotZ`.
fn manual_pose_source(table: &SignalTable) -> SignalSource {
    SignalSource::from_names(
        table,
        SignalKind::Ao,
        [
            Some("ao_MoveX"),
            Some("ao_MoveY"),
            Some("ao_MoveZ"),
            None,
            Some("ao_RotY"),
            Some("ao_RotZ"),
        ],
        [None; 6],
    )
    .unwrap()
}

fn set_xyz(table: &SignalTable, x: f64, y: f64, z: f64) {
    for (name, v) in [("ao_MoveX", x), ("ao_MoveY", y), ("ao_MoveZ", z)] {
        table.set(table.lookup(name).unwrap(), v).unwrap();
    }
}

mod manual_signal_example {
    use super::*;

    /// docs/robot.md, "Acceptance facts": EGM target (150, 1320, 900) with p20's orientation and tFroniusCMT.
    const EXPECTED: JointsDeg = [83.50, 0.10, 16.82, 0.17, 21.88, -0.22];

    #[test]
    fn world_world_signals_put_the_tcp_at_the_signal_values() {
        let r = robot();
        let start = p30_joints(&r);
        let table = SignalTable::with_builtins();
        let src = manual_pose_source(&table);
        set_xyz(&table, 150.0, 1320.0, 900.0);
        // EGMActPose egmID1 \Tool:=tFroniusCMT \WObj:=wobj0, posecor0, EGM_FRAME_WORLD,
        // posesen0, EGM_FRAME_WORLD; EGMRunPose … \x\y\z.
        let setup = PoseSetup {
            selection: XYZ,
            ..PoseSetup::world(t_fronius_cmt())
        };
        let g = PoseGuidance::new(&r, &setup, &start).unwrap();
        // At the start the TCP is p20 (p30 is p20's flange pose).
        assert_pos(g.start_tcp_world(), [150.0, 1320.0, 1140.0], POS_TOL);
        let s = src.sensor_pose(&table, g.start_sensor_pose()).unwrap();
        let ordered = g.target_tcp_world(&s).unwrap();
        assert_pos(&ordered, [150.0, 1320.0, 900.0], 1e-9);
        // ao_RotY and ao_RotZ read 0, but rx, ry, rz are not selected: p20's orientation.
        assert_orient(&ordered, P20_ORIENT);
        let q = g.joint_target(&s, &start).unwrap();
        assert_joints(&q, &EXPECTED, JOINT_TOL);
        assert_pos(&tcp(&r, &q), [150.0, 1320.0, 900.0], POS_TOL);
        // Converged at the joint target; the default windows hold.
        let e = g.convergence_errors(&ordered, &q).unwrap();
        assert!(Convergence::POSE_DEFAULT.met(&e, g.selection()), "{e:?}");
        assert!(
            !Convergence::POSE_DEFAULT.met(&g.convergence_errors(&ordered, &start).unwrap(), &XYZ)
        );
        // Feedback in the correction frame (world here) is the TCP.
        let (p, o) = g.feedback_cartesian(&q, FeedbackMode::Pose).unwrap();
        assert_pos(&pose_from_pos_quat(p, o), [150.0, 1320.0, 900.0], POS_TOL);
        assert_orient(&pose_from_pos_quat(p, o), P20_ORIENT);
    }

    #[test]
    fn the_same_target_given_as_a_full_pose() {
        let r = robot();
        let start = p30_joints(&r);
        let g = PoseGuidance::new(&r, &PoseSetup::world(t_fronius_cmt()), &start).unwrap();
        let s = pose_from_pos_quat([150.0, 1320.0, 900.0], P20_ORIENT);
        assert_joints(&g.joint_target(&s, &start).unwrap(), &EXPECTED, JOINT_TOL);
    }

    #[test]
    fn wobj_egm1_puts_the_signals_in_work_object_coordinates() {
        // MoveJ p30 … tool0; SetAO 50, −20, −20; EGMActPose \WObj:=wobj_EGM1, posecor1,
        // EGM_FRAME_WOBJ, posesen1, EGM_FRAME_WOBJ; EGMRunPose … \x\y\z.
        let r = robot();
        let start = p30_joints(&r);
        let table = SignalTable::with_builtins();
        let src = manual_pose_source(&table);
        set_xyz(&table, 50.0, -20.0, -20.0);
        let setup = PoseSetup {
            wobj: wobj_at(
                pose_from_pos_quat([150.0, 1320.0, 1140.0], [1.0, 0.0, 0.0, 0.0]),
                Pose::identity(),
            ),
            corr_type: EgmFrameType::Wobj,
            sens_type: EgmFrameType::Wobj,
            selection: XYZ,
            ..PoseSetup::world(t_fronius_cmt())
        };
        let g = PoseGuidance::new(&r, &setup, &start).unwrap();
        // The start in work-object coordinates is the work object's origin (p20).
        assert_pos(g.start_sensor_pose(), [0.0, 0.0, 0.0], POS_TOL);
        let s = src.sensor_pose(&table, g.start_sensor_pose()).unwrap();
        let q = g.joint_target(&s, &start).unwrap();
        let t = tcp(&r, &q);
        assert_pos(&t, [200.0, 1300.0, 1120.0], POS_TOL);
        assert_orient(&t, P20_ORIENT);
        let (p, _) = g.feedback_cartesian(&q, FeedbackMode::Pose).unwrap();
        assert_pos(
            &pose_from_pos_quat(p, [1.0, 0.0, 0.0, 0.0]),
            [50.0, -20.0, -20.0],
            POS_TOL,
        );
    }

    #[test]
    fn wobj_egm2_with_frame_offsets() {
        // MoveJ p20 … tFroniusCMT; SetAO 0, 0, 0; EGMActPose \WObj:=wobj_EGM2, posecor2,
        // EGM_FRAME_WOBJ, posesen2, EGM_FRAME_WOBJ: the sensor origin is at (150, 1320, 1000).
        let r = robot();
        let start = p20_joints(&r);
        let table = SignalTable::with_builtins();
        let src = manual_pose_source(&table);
        set_xyz(&table, 0.0, 0.0, 0.0);
        let posecor2 = pose_from_pos_quat([150.0, 320.0, 0.0], [1.0, 0.0, 0.0, 0.0]);
        let setup = PoseSetup {
            wobj: wobj_at(
                pose_from_pos_quat([0.0, 1000.0, 1000.0], [1.0, 0.0, 0.0, 0.0]),
                Pose::identity(),
            ),
            corr_frame: posecor2,
            corr_type: EgmFrameType::Wobj,
            sensor_frame: posecor2,
            sens_type: EgmFrameType::Wobj,
            selection: XYZ,
            ..PoseSetup::world(t_fronius_cmt())
        };
        let g = PoseGuidance::new(&r, &setup, &start).unwrap();
        assert_pos(g.sensor_frame(), [150.0, 1320.0, 1000.0], 1e-9);
        let s = src.sensor_pose(&table, g.start_sensor_pose()).unwrap();
        let q = g.joint_target(&s, &start).unwrap();
        let t = tcp(&r, &q);
        assert_pos(&t, [150.0, 1320.0, 1000.0], POS_TOL);
        assert_orient(&t, P20_ORIENT);
    }

    #[test]
    fn joint_mode_source() {
        // EGMSetupAO … \Joint with all six signals; SetAO 70, −5, 0, 0, 0, 0.
        let table = SignalTable::with_builtins();
        let src = SignalSource::from_names(
            &table,
            SignalKind::Ao,
            [
                Some("ao_MoveX"),
                Some("ao_MoveY"),
                Some("ao_MoveZ"),
                Some("ao_RotX"),
                Some("ao_RotY"),
                Some("ao_RotZ"),
            ],
            [None; 6],
        )
        .unwrap();
        set_xyz(&table, 70.0, -5.0, 0.0);
        let start = p20_joints(&robot());
        let j = src.joint_reference(&table, &start).unwrap();
        assert_eq!(j, [70.0, -5.0, 0.0, 0.0, 0.0, 0.0]);
        // A source that maps only some joints keeps the others at the start.
        let partial = SignalSource::from_names(
            &table,
            SignalKind::Ao,
            [None, Some("ao_MoveY"), None, None, None, None],
            [None; 6],
        )
        .unwrap();
        let j = partial.joint_reference(&table, &start).unwrap();
        assert_eq!(j[1], -5.0);
        assert_eq!(
            [j[0], j[2], j[3], j[4], j[5]],
            [start[0], start[2], start[3], start[4], start[5]]
        );
    }
}

mod tool_frame {
    use super::*;

    /// The UdpUc example: `EGMActPose egmID1 \Tool:=tFroniusCMT, corr_frame_offs,
    /// EGM_FRAME_WORLD, tFroniusCMT.tframe, EGM_FRAME_TOOL` from `jpos10` = [0,0,0,0,40,0].
    fn udpuc_setup() -> PoseSetup {
        PoseSetup {
            sensor_frame: t_fronius_cmt().tframe,
            sens_type: EgmFrameType::Tool,
            ..PoseSetup::world(t_fronius_cmt())
        }
    }

    const JPOS10: JointsDeg = [0.0, 0.0, 0.0, 0.0, 40.0, 0.0];

    /// rapidvc's choice: TOOL = tool0 (flange) frozen at the start of EGMRun, so with
    /// SensorFrame = tframe the sensor frame is the TCP frame at the start, and the sensor
    /// pose is the TCP target relative to where the TCP started.
    #[test]
    fn sensor_frame_is_the_start_tcp() {
        let r = robot();
        let g = PoseGuidance::new(&r, &udpuc_setup(), &JPOS10).unwrap();
        let start_tcp = tcp(&r, &JPOS10);
        // docs/robot.md, "Acceptance facts": TCP [1321.0, −0.1, 1128.4], torch pointing straight down.
        assert_pos(&start_tcp, [1321.0, -0.1, 1128.4], POS_TOL);
        assert_pos(g.sensor_frame(), [1321.0, -0.1, 1128.4], POS_TOL);
        assert!(g.sensor_frame().rotation.angle_to(&start_tcp.rotation) < 1e-12);
        // The identity sensor pose holds the robot where it is.
        assert_pos(g.start_sensor_pose(), [0.0, 0.0, 0.0], 1e-9);
        let q = g.joint_target(&Pose::identity(), &JPOS10).unwrap();
        assert_joints(&q, &JPOS10, 1e-6);
    }

    #[test]
    fn sensor_values_move_along_the_start_tool_axes() {
        let r = robot();
        let g = PoseGuidance::new(&r, &udpuc_setup(), &JPOS10).unwrap();
        let start_tcp = tcp(&r, &JPOS10);
        // −100 mm along the torch axis (which points down) lifts the TCP by 100 mm.
        let s = pose_from_pos_quat([0.0, 0.0, -100.0], [1.0, 0.0, 0.0, 0.0]);
        let q = g.joint_target(&s, &JPOS10).unwrap();
        let t = tcp(&r, &q);
        let d = t.translation.vector - start_tcp.translation.vector;
        // Exactly along the start tool z axis, which is about 1° off vertical.
        assert!((d - start_tcp.rotation * Vector3::new(0.0, 0.0, -100.0)).norm() < 1e-6);
        assert!(d.z > 99.9, "{d}");
        assert!(t.rotation.angle_to(&start_tcp.rotation) < 1e-9);
        // The frame does not follow the robot: the same sensor pose from other current
        // joints gives the same TCP.
        let q2 = g.joint_target(&s, &q).unwrap();
        assert_joints(&q2, &q, 1e-9);
        let t2 = tcp(&r, &q2);
        assert!((t2.translation.vector - t.translation.vector).norm() < 1e-6);
    }

    #[test]
    fn tool_correction_frame_sets_the_directions() {
        // Correction frame of type TOOL (the manual's last pose example uses posecor2 with
        // EGM_FRAME_TOOL): selecting only z moves along the start flange's z axis.
        let r = robot();
        let setup = PoseSetup {
            corr_type: EgmFrameType::Tool,
            selection: [false, false, true, false, false, false],
            ..PoseSetup::world(t_fronius_cmt())
        };
        let g = PoseGuidance::new(&r, &setup, &JPOS10).unwrap();
        let start_tcp = tcp(&r, &JPOS10);
        let flange_z = r.fk(&JPOS10).rotation * Vector3::z();
        // Ask for a TCP 200 mm away in world x and y: only the flange-z component survives.
        let wanted = start_tcp.translation.vector + Vector3::new(200.0, 0.0, -50.0);
        let s = Pose::from_parts(wanted.into(), start_tcp.rotation);
        let t = g.target_tcp_world(&s).unwrap();
        let d = t.translation.vector - start_tcp.translation.vector;
        let along = (wanted - start_tcp.translation.vector).dot(&flange_z);
        assert!((d - flange_z * along).norm() < 1e-9, "{d}");
    }
}

mod frames_and_offsets {
    use super::*;

    #[test]
    fn rotated_work_object_and_base() {
        let r = robot().with_base(pose_from_pos_quat(
            [100.0, -50.0, 20.0],
            [0.9659258, 0.0, 0.0, 0.2588190],
        ));
        let start = [10.0, 10.0, 10.0, 20.0, 40.0, -10.0];
        let wobj = wobj_at(
            pose_from_pos_quat([900.0, 200.0, 300.0], [0.9659258, 0.0, 0.0, 0.2588190]),
            pose_from_pos_quat([20.0, 30.0, 0.0], [0.9961947, 0.0, 0.0871557, 0.0]),
        );
        let setup = PoseSetup {
            wobj: wobj.clone(),
            corr_type: EgmFrameType::Wobj,
            sens_type: EgmFrameType::Wobj,
            ..PoseSetup::world(t_fronius_cmt())
        };
        let g = PoseGuidance::new(&r, &setup, &start).unwrap();
        // Near the start (so it is reachable), moved and turned in work-object coordinates.
        let s = pose_from_pos_quat([50.0, -40.0, 30.0], [0.9961947, 0.0, 0.0, 0.0871557])
            * g.start_sensor_pose();
        let q = g.joint_target(&s, &start).unwrap();
        let t = tcp(&r, &q);
        let want = wobj.uframe * wobj.oframe * s;
        assert!((t.translation.vector - want.translation.vector).norm() < 1e-6);
        assert!(t.rotation.angle_to(&want.rotation) < 1e-8);
        let (p, o) = g.feedback_cartesian(&q, FeedbackMode::Pose).unwrap();
        let fb = pose_from_pos_quat(p, o);
        assert!((fb.translation.vector - s.translation.vector).norm() < 1e-6);
        assert!(fb.rotation.angle_to(&s.rotation) < 1e-8);
        // Joint mode and streaming report relative to \WObj too (same frame here).
        let (pj, _) = g.feedback_cartesian(&q, FeedbackMode::Joint).unwrap();
        assert!((Vector3::from(pj) - s.translation.vector).norm() < 1e-6);
        // BASE frame type: the sensor pose is relative to the robot base.
        let setup = PoseSetup {
            sens_type: EgmFrameType::Base,
            corr_type: EgmFrameType::Base,
            ..PoseSetup::world(t_fronius_cmt())
        };
        let g = PoseGuidance::new(&r, &setup, &start).unwrap();
        let q = g.joint_target(&s, &start).unwrap();
        let want = r.base() * s;
        assert!((tcp(&r, &q).translation.vector - want.translation.vector).norm() < 1e-6);
    }

    #[test]
    fn offset_moves_the_target_in_the_correction_frame() {
        let r = robot();
        let start = p30_joints(&r);
        let s = pose_from_pos_quat([150.0, 1320.0, 900.0], P20_ORIENT);
        // Correction frame rotated 90° about world z: its x axis is world y.
        let base = PoseSetup {
            corr_frame: pose_from_pos_quat([0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 1.0]),
            ..PoseSetup::world(t_fronius_cmt())
        };
        let plain = PoseGuidance::new(&r, &base, &start).unwrap();
        let with = PoseGuidance::new(
            &r,
            &PoseSetup {
                offset: Some(pose_from_pos_quat([30.0, 0.0, 50.0], [1.0, 0.0, 0.0, 0.0])),
                ..base.clone()
            },
            &start,
        )
        .unwrap();
        let a = tcp(&r, &plain.joint_target(&s, &start).unwrap());
        let b = tcp(&r, &with.joint_target(&s, &start).unwrap());
        let d = b.translation.vector - a.translation.vector;
        assert!((d - Vector3::new(0.0, 30.0, 50.0)).norm() < 1e-6, "{d}");
        assert!(a.rotation.angle_to(&b.rotation) < 1e-8);
        // An offset in an unselected direction has no effect.
        let masked = PoseGuidance::new(
            &r,
            &PoseSetup {
                offset: Some(pose_from_pos_quat([30.0, 0.0, 50.0], [1.0, 0.0, 0.0, 0.0])),
                selection: [true, true, false, true, true, true],
                ..base
            },
            &start,
        )
        .unwrap();
        let c = masked.target_tcp_world(&s).unwrap();
        // x of F_c (world y) gets the offset; z is not selected: it keeps the start value
        // (p20's 1140), not the sensor's 900 + 50; F_c's y (world −x) carries no offset.
        assert_pos(&c, [150.0, 1350.0, 1140.0], POS_TOL);
        assert!((c.translation.vector.y - 1350.0).abs() < 1e-9);
    }

    #[test]
    fn selection_switches() {
        let r = robot();
        let start = p30_joints(&r);
        let s = pose_from_pos_quat([150.0, 1320.0, 900.0], [1.0, 0.0, 0.0, 0.0]);
        let only_z = PoseGuidance::new(
            &r,
            &PoseSetup {
                selection: [false, false, true, false, false, false],
                ..PoseSetup::world(t_fronius_cmt())
            },
            &start,
        )
        .unwrap();
        let t = only_z.target_tcp_world(&s).unwrap();
        assert_pos(&t, [150.0, 1320.0, 900.0], POS_TOL);
        assert_orient(&t, P20_ORIENT);
        // Nothing selected: the target is the start.
        let none = PoseGuidance::new(
            &r,
            &PoseSetup {
                selection: [false; 6],
                ..PoseSetup::world(t_fronius_cmt())
            },
            &start,
        )
        .unwrap();
        let q = none.joint_target(&s, &start).unwrap();
        assert_joints(&q, &start, 1e-6);
        assert!(Convergence::POSE_DEFAULT.met(&[99.0; 6], none.selection()));
    }
}

mod convergence {
    use super::*;

    #[test]
    fn asymmetric_windows_follow_ordered_minus_actual() {
        let r = robot();
        let start = p30_joints(&r);
        let g = PoseGuidance::new(&r, &PoseSetup::world(t_fronius_cmt()), &start).unwrap();
        let ordered = g
            .target_tcp_world(&pose_from_pos_quat([150.0, 1320.0, 900.0], P20_ORIENT))
            .unwrap();
        let window =
            Convergence::with_overrides([Some((-0.1, 0.2)), None, None, None, None, None]).unwrap();
        // The actual TCP 0.15 mm short of the target in x: ordered − actual = +0.15.
        let short = Pose::from_parts(
            (ordered.translation.vector - Vector3::new(0.15, 0.0, 0.0)).into(),
            ordered.rotation,
        );
        let q_short = g.joints_for_tcp(&short, &start).unwrap();
        let e = g.convergence_errors(&ordered, &q_short).unwrap();
        assert!((e[0] - 0.15).abs() < 1e-6, "{e:?}");
        assert!(window.met(&e, &[true; 6]));
        // 0.15 mm beyond: −0.15 lies outside [−0.1, 0.2].
        let beyond = Pose::from_parts(
            (ordered.translation.vector + Vector3::new(0.15, 0.0, 0.0)).into(),
            ordered.rotation,
        );
        let q_beyond = g.joints_for_tcp(&beyond, &start).unwrap();
        let e = g.convergence_errors(&ordered, &q_beyond).unwrap();
        assert!((e[0] + 0.15).abs() < 1e-6, "{e:?}");
        assert!(!window.met(&e, &[true; 6]));
        // The manual's rotation window ±2° against a 1° error about world z.
        let rot = Convergence::with_overrides([
            None,
            None,
            None,
            Some((-2.0, 2.0)),
            Some((-2.0, 2.0)),
            Some((-2.0, 2.0)),
        ])
        .unwrap();
        let turned = Pose::from_parts(
            ordered.translation,
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), (-1.0f64).to_radians())
                * ordered.rotation,
        );
        let q_turned = g.joints_for_tcp(&turned, &start).unwrap();
        let e = g.convergence_errors(&ordered, &q_turned).unwrap();
        assert!((e[5] - 1.0).abs() < 1e-6 && e[3].abs() < 1e-6, "{e:?}");
        assert!(rot.met(&e, &[true; 6]));
        assert!(!Convergence::POSE_DEFAULT.met(&e, &[true; 6]));
    }
}

mod supervision {
    use super::*;

    fn world_guidance(r: &Robot) -> (PoseGuidance, JointsDeg) {
        let start = p30_joints(r);
        (
            PoseGuidance::new(r, &PoseSetup::world(t_fronius_cmt()), &start).unwrap(),
            start,
        )
    }

    #[test]
    fn beyond_reach_is_50050() {
        let r = robot();
        let (g, start) = world_guidance(&r);
        let s = pose_from_pos_quat([3000.0, 0.0, 1000.0], P20_ORIENT);
        let e = g.joint_target(&s, &start).unwrap_err();
        assert!(
            matches!(e.kin_error(), Some(KinError::OutsideReach { .. })),
            "{e:?}"
        );
        assert_eq!(e.event(), Some((50050, "Position outside reach")));
    }

    #[test]
    fn axis_limit_is_50027_and_no_command_goes_through_it() {
        let r = robot();
        let (g, start) = world_guidance(&r);
        // A TCP that only axis 5 = ±130° reaches (limit ±120°).
        let beyond = tcp(&r, &[80.0, 0.0, 0.0, 0.0, 130.0, 0.0]);
        let e = g.joints_for_tcp(&beyond, &start).unwrap_err();
        match e.kin_error() {
            Some(KinError::JointOutOfRange {
                joint: 5,
                value,
                min: -120.0,
                max: 120.0,
            }) => assert!((value.abs() - 130.0).abs() < 1e-6, "{value}"),
            other => panic!("{other:?}"),
        }
        assert_eq!(e.event(), Some((50027, "Joint out of range")));
        // Every target the pipeline returns lies inside the limits.
        for z in [200.0, 500.0, 900.0, 1400.0, 1800.0] {
            let s = pose_from_pos_quat([150.0, 1320.0, z], P20_ORIENT);
            if let Ok(q) = g.joint_target(&s, &start) {
                r.check_limits(&q).unwrap();
            }
        }
    }

    #[test]
    fn singularity_is_50026() {
        let r = robot();
        let g =
            PoseGuidance::new(&r, &PoseSetup::world(ToolData::tool0()), &p30_joints(&r)).unwrap();
        // A flange pose with axis 5 at 1°: inside the 3° wrist zone.
        let s = r.fk(&[83.5, 0.1, -0.3, 0.1, 1.0, -0.1]);
        let e = g.joint_target(&s, &p30_joints(&r)).unwrap_err();
        assert!(matches!(
            e.kin_error(),
            Some(KinError::Singularity {
                kind: SingularityKind::Wrist,
                ..
            })
        ));
        assert_eq!(e.event(), Some((50026, "Close to singularity")));
    }

    #[test]
    fn nan_inputs_are_errors() {
        let r = robot();
        let (g, start) = world_guidance(&r);
        let nan = pose_from_pos_quat([f64::NAN, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]);
        let e = g.joint_target(&nan, &start).unwrap_err();
        assert!(matches!(e, GuidanceError::NotFinite { .. }));
        assert_eq!(e.event(), Some((50050, "Position outside reach")));
        let bad_q = pose_from_pos_quat([1.0, 0.0, 0.0], [f64::NAN, 0.0, 0.0, 0.0]);
        assert!(g.joint_target(&bad_q, &start).is_err());
        let zero_q = pose_from_pos_quat([1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]);
        assert!(g.joint_target(&zero_q, &start).is_err());
        let s = pose_from_pos_quat([150.0, 1320.0, 900.0], P20_ORIENT);
        let mut cur = start;
        cur[3] = f64::NAN;
        assert!(g.joint_target(&s, &cur).is_err());
        assert!(g.convergence_errors(&s, &cur).is_err());
        assert!(g.convergence_errors(&nan, &start).is_err());
        assert!(g.feedback_cartesian(&cur, FeedbackMode::Pose).is_err());
        assert!(g.joint_speed_ref(&cur, &[1.0; 6]).is_err());
        assert!(g.joint_speed_ref(&start, &[f64::INFINITY; 6]).is_err());
        assert!(g.sensor_target_world(&nan).is_err());
    }
}

mod speed_reference {
    use super::*;

    #[test]
    fn cartesian_speed_becomes_joint_speed_in_the_correction_frame() {
        let r = robot();
        let start = p30_joints(&r);
        let corr = pose_from_pos_quat([0.0; 3], [1.0, 0.0, 0.0, 1.0]);
        let setup = PoseSetup {
            corr_frame: corr,
            selection: [true, false, true, true, true, true],
            ..PoseSetup::world(t_fronius_cmt())
        };
        let g = PoseGuidance::new(&r, &setup, &start).unwrap();
        let v = [20.0, 40.0, -10.0, 0.0, 0.0, 1.0];
        let s = g.joint_speed_ref(&start, &v).unwrap();
        assert_eq!(s.limit, None);
        // The TCP moves at v with y (unselected) zeroed, along the axes of F_c.
        let j = tcp_jacobian(&r, &start, &t_fronius_cmt().tframe, &corr.rotation).unwrap();
        let got = j * Vector6::from_column_slice(&s.joints);
        let want = [20.0, 0.0, -10.0, 0.0, 0.0, 1.0];
        for (a, b) in got.iter().zip(&want) {
            assert!((a - b).abs() < 1e-6, "{got}");
        }
    }

    #[test]
    fn near_a_singularity_the_speed_reference_is_zero() {
        let r = robot();
        let q = [83.5, 0.1, -0.3, 0.1, 1.0, -0.1];
        let g = PoseGuidance::new(&r, &PoseSetup::world(t_fronius_cmt()), &q).unwrap();
        let s = g
            .joint_speed_ref(&q, &[10.0, 0.0, 0.0, 0.0, 0.0, 0.0])
            .unwrap();
        assert_eq!(s.joints, [0.0; 6]);
        assert_eq!(
            s.limit,
            Some(SpeedRefLimit::Singularity(SingularityKind::Wrist))
        );
    }
}

mod no_panic {
    use super::*;
    use proptest::prelude::*;

    /// Any f64, with the awkward ones (NaN, ±∞, huge, tiny) well represented.
    fn any_f64() -> impl Strategy<Value = f64> {
        prop_oneof![
            4 => -3000.0..3000.0f64,
            1 => Just(f64::NAN),
            1 => Just(f64::INFINITY),
            1 => Just(f64::NEG_INFINITY),
            1 => Just(1e300),
            1 => Just(-1e300),
            1 => Just(0.0),
            1 => any::<f64>(),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]

        #[test]
        fn every_input_gives_a_limited_target_or_an_error(
            pos in proptest::array::uniform3(any_f64()),
            quat in proptest::array::uniform4(any_f64()),
            current in proptest::array::uniform6(any_f64()),
            speed in proptest::array::uniform6(any_f64()),
        ) {
            let r = robot();
            let start = p30_joints(&r);
            let g = PoseGuidance::new(&r, &PoseSetup::world(t_fronius_cmt()), &start).unwrap();
            let s = pose_from_pos_quat(pos, quat);
            if let Ok(q) = g.joint_target(&s, &current) {
                prop_assert!(r.check_limits(&q).is_ok());
                prop_assert!(r.near_singularity(&q).is_none());
            }
            let _ = g.convergence_errors(&s, &current);
            let _ = g.feedback_cartesian(&current, FeedbackMode::Pose);
            if let Ok(v) = g.joint_speed_ref(&current, &speed) {
                prop_assert!(v.joints.iter().all(|x| x.is_finite()));
            }
        }

        #[test]
        fn reachable_targets_round_trip(
            q in (-170.0..170.0f64, -60.0..100.0f64, -60.0..60.0f64,
                  -150.0..150.0f64, 10.0..110.0f64, -150.0..150.0f64),
        ) {
            let r = robot();
            let q = [q.0, q.1, q.2, q.3, q.4, q.5];
            prop_assume!(r.near_singularity(&q).is_none());
            let start = p30_joints(&r);
            let g = PoseGuidance::new(&r, &PoseSetup::world(t_fronius_cmt()), &start).unwrap();
            let target = tcp(&r, &q);
            // From the joints themselves the nearest solution is those joints.
            let back = g.joint_target(&target, &q).unwrap();
            for (a, b) in back.iter().zip(&q) {
                prop_assert!((a - b).abs() < 1e-6, "{back:?} vs {q:?}");
            }
            let e = g.convergence_errors(&target, &back).unwrap();
            prop_assert!(e.iter().all(|v| v.abs() < 1e-6));
        }
    }
}
