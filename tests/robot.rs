//! Integration tests of the virtual robot: the acceptance facts of docs/robot.md, "Acceptance facts", FK/IK round
//! trips on every model, confdata and error cases.

// Expected values are quoted digit for digit from docs/robot.md (0.707107 is not FRAC_1_SQRT_2).
#![allow(clippy::approx_constant)]

use rapidvc::robot::command::RobTarget;
use rapidvc::robot::units::{pose_from_pos_quat, pose_to_pos_quat};
use rapidvc::robot::{
    ConfData, JointsDeg, KinError, LoadData, Pose, Robot, SingularityKind, ToolData, WobjData,
    default_model, flange_target, model_by_name, models,
};
use rapidvc_testkit::robot::{JOINT_TOL, POS_TOL, QUAT_TOL, assert_joints, t_fronius_cmt};

fn irb2600() -> Robot {
    Robot::new(default_model())
}

fn p20() -> RobTarget {
    RobTarget {
        trans: [150.0, 1320.0, 1140.0],
        rot: [0.000494947, 0.662278, -0.749217, -0.00783173],
        robconf: ConfData::new(0, 0, -1, 0),
        extax: [9e9; 6],
    }
}

fn p30() -> RobTarget {
    RobTarget {
        trans: [114.50, 1005.42, 1410.38],
        rot: [0.322151, -0.601023, 0.672381, 0.287914],
        robconf: ConfData::new(0, 0, -1, 0),
        extax: [9e9; 6],
    }
}

fn assert_pos(p: &Pose, expected: [f64; 3], tol: f64) {
    let (t, _) = pose_to_pos_quat(p);
    for i in 0..3 {
        assert!((t[i] - expected[i]).abs() <= tol, "{t:?} vs {expected:?}");
    }
}

fn assert_quat(p: &Pose, expected: [f64; 4], tol: f64) {
    let (_, q) = pose_to_pos_quat(p);
    let same = (0..4).all(|i| (q[i] - expected[i]).abs() <= tol);
    let neg = (0..4).all(|i| (q[i] + expected[i]).abs() <= tol);
    assert!(same || neg, "{q:?} vs {expected:?}");
}

fn flange_for(target: &RobTarget, tool: &ToolData) -> Pose {
    flange_target(&target.pose(), tool, &WobjData::wobj0(), &Pose::identity())
}

mod acceptance {
    //! docs/robot.md, "Acceptance facts", on the default IRB 2600-12/1.85.
    use super::*;

    #[test]
    fn all_zero_joints_tool0() {
        let p = irb2600().fk(&[0.0; 6]);
        assert_pos(&p, [1030.0, 0.0, 1460.0], 1e-6);
        assert_quat(&p, [0.707107, 0.0, 0.707107, 0.0], 1e-6);
    }

    #[test]
    fn start_pose_tool0_and_torch() {
        let r = irb2600();
        let q = [0.0, 0.0, 0.0, 0.0, 40.0, 0.0];
        let p = r.fk(&q);
        assert_pos(&p, [1010.1, 0.0, 1405.4], 0.05);
        assert_quat(&p, [0.42262, 0.0, 0.90631, 0.0], QUAT_TOL);
        let tcp = r.tcp_pose(&q, &t_fronius_cmt(), &WobjData::wobj0());
        assert_pos(&tcp, [1321.0, -0.1, 1128.4], 0.05);
        // Torch pointing straight down: the tool z axis is world −z.
        let z = tcp.rotation * nalgebra::Vector3::z();
        assert!((z.z + 1.0).abs() < 1e-3, "{z:?}");
        let p35 = r.fk(&[0.0, 0.0, 0.0, 0.0, 35.0, 0.0]);
        assert_pos(&p35, [1014.6, 0.0, 1411.2], 0.05);
    }

    const P30_JOINTS: JointsDeg = [83.498, 0.077, -0.340, 0.103, 39.066, -0.136];

    #[test]
    fn movej_p30_with_tool0() {
        let r = irb2600();
        let target = p30();
        let flange = flange_for(&target, &ToolData::tool0());
        let q = r.ik_conf(&flange, &target.robconf).unwrap();
        assert_joints(&q, &P30_JOINTS, JOINT_TOL);
        assert_eq!(r.conf_of(&q), ConfData::new(0, 0, -1, 0));
        let back = r.fk(&q);
        assert_pos(&back, target.trans, 0.02);
        assert_quat(&back, target.rot, 1e-5);
    }

    #[test]
    fn movej_p20_with_fronius_gives_the_same_joints() {
        let r = irb2600();
        let target = p20();
        let tool = t_fronius_cmt();
        let flange = flange_for(&target, &tool);
        let q = r.ik_conf(&flange, &target.robconf).unwrap();
        assert_joints(&q, &[83.50, 0.08, -0.34, 0.10, 39.07, -0.14], JOINT_TOL);
        assert_joints(&q, &P30_JOINTS, JOINT_TOL);
        // p30 is exactly p20's flange pose.
        let p30_pose = p30().pose();
        assert_pos(&(p30_pose * tool.tframe), target.trans, 0.01);
        assert_quat(&(p30_pose * tool.tframe), target.rot, 1e-6);
        let tcp = r.tcp_pose(&q, &tool, &WobjData::wobj0());
        assert_pos(&tcp, target.trans, POS_TOL);
    }

    #[test]
    fn egm_target_with_p20_orientation() {
        let r = irb2600();
        let target = RobTarget {
            trans: [150.0, 1320.0, 900.0],
            ..p20()
        };
        let tool = t_fronius_cmt();
        let q = r
            .ik_conf(&flange_for(&target, &tool), &target.robconf)
            .unwrap();
        assert_joints(&q, &[83.50, 0.10, 16.82, 0.17, 21.88, -0.22], JOINT_TOL);
        let tcp = r.tcp_pose(&q, &tool, &WobjData::wobj0());
        assert_pos(&tcp, [150.0, 1320.0, 900.0], 0.05);
        // Continuity from the p20 joints gives the same answer.
        let from_p20 = r
            .ik_nearest(&flange_for(&target, &tool), &P30_JOINTS)
            .unwrap();
        assert_joints(&from_p20, &q, 1e-6);
    }

    #[test]
    fn stretched_elbow() {
        let r = irb2600();
        let f = r.singularity(&[0.0, 0.0, -81.77, 0.0, 30.0, 0.0]);
        assert!(f.elbow_sin.abs() < 1e-4, "{f:?}");
        assert_eq!(
            r.near_singularity(&[0.0, 0.0, -81.77, 0.0, 30.0, 0.0]),
            Some(SingularityKind::Elbow)
        );
    }

    #[test]
    fn irb120_zero_pose() {
        let r = Robot::new(model_by_name("IRB 120-3/0.58").unwrap());
        let p = r.fk(&[0.0; 6]);
        assert_pos(&p, [374.0, 0.0, 630.0], 1e-6);
        assert_quat(&p, [0.707107, 0.0, 0.707107, 0.0], 1e-6);
    }

    #[test]
    fn pitfall_p30_with_the_torch_has_no_programmed_solution() {
        let r = irb2600();
        let target = p30();
        let flange = flange_for(&target, &t_fronius_cmt());
        match r.ik_conf(&flange, &target.robconf) {
            Err(KinError::ConfigurationUnreachable { wanted, available }) => {
                assert_eq!(wanted, ConfData::new(0, 0, -1, 0));
                assert!(
                    available.contains(&ConfData::new(0, -1, -1, 1)),
                    "{available:?}"
                );
                assert!(
                    available.contains(&ConfData::new(0, 1, 1, 0)),
                    "{available:?}"
                );
            }
            other => panic!("expected ConfigurationUnreachable, got {other:?}"),
        }
        // The nearest configuration has J5 ≈ −14°.
        let q = r.ik_conf(&flange, &ConfData::new(0, -1, -1, 1)).unwrap();
        assert!((q[4] - -14.0).abs() < 1.0, "{q:?}");
    }
}

mod models_table {
    //! Every model: table facts, zero pose, FK/IK round trips.
    use super::*;
    use proptest::prelude::*;
    use proptest::test_runner::{Config, TestRunner};

    #[test]
    fn required_models_are_present() {
        for name in [
            "IRB 120-3/0.58",
            "IRB 1200-5/0.9",
            "IRB 1600-10/1.45",
            "IRB 2600-12/1.65",
            "IRB 2600-12/1.85",
            "IRB 4600-60/2.05",
            "IRB 6700-200/2.60",
        ] {
            let m = model_by_name(name).unwrap_or_else(|| panic!("{name} missing"));
            assert!(m.reach_mm() > 500.0 && m.vmax_tcp > 0.0, "{name}");
        }
        assert_eq!(default_model().name, "IRB 2600-12/1.85");
        assert_eq!(models()[0].name, default_model().name);
        assert!(models().len() >= 7);
    }

    #[test]
    fn zero_pose_of_every_model() {
        // At zero the arm is an L: x = a1 + c3 + c4, z = c1 + c2 − a2, tool pointing along +x.
        for m in models() {
            let p = Robot::new(m).fk(&[0.0; 6]);
            let o = &m.opw;
            assert_pos(
                &p,
                [
                    (o.a1 + o.c3 + o.c4) * 1000.0,
                    0.0,
                    (o.c1 + o.c2 - o.a2) * 1000.0,
                ],
                1e-6,
            );
            assert_quat(&p, [0.5f64.sqrt(), 0.0, 0.5f64.sqrt(), 0.0], 1e-9);
        }
    }

    /// Joints well away from every singularity (round trips lose precision there, and the
    /// solution is no longer unique).
    fn regular(r: &Robot, q: &JointsDeg) -> bool {
        let f = r.singularity(q);
        f.shoulder_mm.abs() > 20.0 && f.elbow_sin.abs() > 0.02 && f.wrist_distance_deg() > 2.0
    }

    fn in_limit_joints(r: &Robot, u: [f64; 6]) -> JointsDeg {
        let l = &r.model().joint_limits;
        std::array::from_fn(|i| l[i].min + u[i] * (l[i].max - l[i].min))
    }

    fn close_pose(a: &Pose, b: &Pose, mm: f64, rad: f64) -> bool {
        (a.translation.vector - b.translation.vector).norm() < mm
            && a.rotation.angle_to(&b.rotation) < rad
    }

    #[test]
    fn fk_ik_round_trips_on_every_model() {
        let mut runner = TestRunner::new(Config {
            cases: 300,
            ..Config::default()
        });
        for m in models() {
            let r = Robot::new(m);
            let strategy = prop::array::uniform6(0.0..1.0f64);
            runner
                .run(&strategy, |u| {
                    let q = in_limit_joints(&r, u);
                    prop_assume!(regular(&r, &q));
                    let p = r.fk(&q);
                    // Every solution is in limits and reproduces the pose.
                    let all = r.ik_all(&p);
                    prop_assert!(!all.is_empty());
                    for s in &all {
                        prop_assert!(r.check_limits(s).is_ok(), "{s:?}");
                        prop_assert!(close_pose(&r.fk(s), &p, 1e-6, 1e-9), "{s:?}");
                    }
                    // q itself is among them.
                    let found = all
                        .iter()
                        .any(|s| s.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-6));
                    prop_assert!(found, "{} {q:?} not in {all:?}", m.name);
                    // ConfJ\On with q's confdata gives q back.
                    let conf = r.conf_of(&q);
                    let back = r.ik_conf(&p, &conf);
                    prop_assert!(back.is_ok(), "{} {q:?} {conf}: {back:?}", m.name);
                    let back = back.unwrap_or_default();
                    for i in 0..6 {
                        prop_assert!((back[i] - q[i]).abs() < 1e-6, "{} {q:?} {back:?}", m.name);
                    }
                    // The nearest solution to q is q.
                    let near = r.ik_nearest(&p, &q).unwrap_or_default();
                    for i in 0..6 {
                        prop_assert!((near[i] - q[i]).abs() < 1e-6, "{} {q:?} {near:?}", m.name);
                    }
                    Ok(())
                })
                .unwrap_or_else(|e| panic!("{}: {e}", m.name));
        }
    }

    #[test]
    fn continuity_from_a_nearby_pose() {
        // A small Cartesian step from q lands on joints close to q (MoveL cycle to cycle).
        let r = irb2600();
        let q = [30.0, 20.0, -10.0, 150.0, 40.0, -200.0];
        let p = r.fk(&q);
        let step = Pose::translation(1.0, -0.5, 0.25) * p;
        let next = r.ik_nearest(&step, &q).unwrap();
        for i in 0..6 {
            assert!((next[i] - q[i]).abs() < 1.0, "{next:?}");
        }
        assert_eq!(r.conf_of(&next), r.conf_of(&q));
    }

    #[test]
    fn base_frame_moves_the_robot() {
        let base = pose_from_pos_quat([1000.0, -500.0, 200.0], [0.0, 0.0, 0.0, 1.0]);
        let r = irb2600().with_base(base);
        assert_eq!(r.base(), &base);
        let q = [10.0, 5.0, 5.0, 0.0, 30.0, 0.0];
        let p = r.fk(&q);
        assert!(close_pose(&p, &(base * irb2600().fk(&q)), 1e-9, 1e-12));
        let back = r.ik_conf(&p, &r.conf_of(&q)).unwrap();
        assert_joints(&back, &q, 1e-6);
        // The zero pose of a robot turned by 180° about z and shifted.
        assert_pos(
            &r.fk(&[0.0; 6]),
            [1000.0 - 1030.0, -500.0, 200.0 + 1460.0],
            1e-6,
        );
    }
}

mod confdata {
    //! docs/robot.md, "Configuration", through the robot: quarter revolutions and the cfx table.
    use super::*;

    #[test]
    fn quarter_revolutions_of_axes_1_4_6() {
        let r = irb2600();
        let conf = |j1, j4, j6| r.conf_of(&[j1, 10.0, 10.0, j4, 30.0, j6]);
        assert_eq!(conf(83.5, 0.103, -0.136), ConfData::new(0, 0, -1, 0));
        assert_eq!(conf(-90.0, -180.0, 180.0), ConfData::new(-2, -3, 2, 0));
        assert_eq!(conf(90.0, 360.0, -360.0), ConfData::new(1, 4, -5, 0));
        assert_eq!(conf(-0.5, -270.0, 399.0), ConfData::new(-1, -4, 4, 0));
    }

    /// One joint vector per cfx on the IRB 2600-12/1.85: axis 2/3 put the wrist centre in
    /// front of / behind axis 1 and the lower arm, axis 5 picks the wrist.
    const CFX_CASES: [(JointsDeg, i32); 8] = [
        ([20.0, 10.0, 10.0, 30.0, 40.0, 50.0], 0),
        ([20.0, 10.0, 10.0, 30.0, -40.0, 50.0], 1),
        ([20.0, 30.0, -120.0, 30.0, 40.0, 50.0], 2),
        ([20.0, 30.0, -120.0, 30.0, -40.0, 50.0], 3),
        ([20.0, -90.0, 0.0, 30.0, 40.0, 50.0], 4),
        ([20.0, -90.0, 0.0, 30.0, -40.0, 50.0], 5),
        ([20.0, -90.0, -120.0, 30.0, 40.0, 50.0], 6),
        ([20.0, -90.0, -120.0, 30.0, -40.0, 50.0], 7),
    ];

    #[test]
    fn cfx_table_on_the_real_arm() {
        let r = irb2600();
        for (q, cfx) in CFX_CASES {
            let f = r.singularity(&q);
            assert_eq!(r.conf_of(&q).cfx, cfx, "{q:?} {f:?}");
            // Bits are the signs of the three det-J factors.
            assert_eq!(f.shoulder_mm < 0.0, cfx & 4 != 0);
            assert_eq!(f.elbow_sin < 0.0, cfx & 2 != 0);
            assert_eq!(f.wrist_deg < 0.0, cfx & 1 != 0);
        }
    }

    #[test]
    fn every_cfx_solves_back_in_its_configuration() {
        let r = irb2600();
        for (q, cfx) in CFX_CASES {
            let p = r.fk(&q);
            let conf = r.conf_of(&q);
            let back = r.ik_conf(&p, &conf).unwrap();
            assert_joints(&back, &q, 1e-6);
            assert_eq!(r.conf_of(&back).cfx, cfx);
            // The same pose in another arm configuration is a different joint vector.
            for other in r.ik_all(&p) {
                let c = r.conf_of(&other);
                if c.cfx != cfx {
                    let diff = (0..6).map(|i| (other[i] - q[i]).abs()).fold(0.0, f64::max);
                    assert!(diff > 1.0, "{other:?}");
                }
            }
        }
    }

    #[test]
    fn conf_matches_follows_ik_conf() {
        let r = irb2600();
        let q = [83.498, 0.077, -0.340, 0.103, 39.066, -0.136];
        assert!(r.conf_matches(&q, &ConfData::new(0, 0, -1, 0)));
        // Within the slack of a quadrant boundary.
        assert!(r.conf_matches(&q, &ConfData::new(0, 0, 0, 0)));
        assert!(!r.conf_matches(&q, &ConfData::new(0, 0, 1, 0)));
        assert!(!r.conf_matches(&q, &ConfData::new(0, 0, -1, 1)));
        assert!(!r.conf_matches(&[f64::NAN; 6], &ConfData::default()));
        // Wrist centre between axis 1 and axis 2 (a1 = 150 mm): convention-dependent cfx.
        assert!(!r.cfx_convention_dependent(&q));
        let opw = &r.model().opw;
        let j2 = -20.0f64;
        let target_r = 0.075; // m, half of a1
        let s = ((target_r - opw.a1 - opw.c2 * j2.to_radians().sin()) / opw.k()).asin();
        let j3 = s.to_degrees() - j2 - 90.0 - opw.psi3().to_degrees();
        assert!(r.cfx_convention_dependent(&[0.0, j2, j3, 0.0, 40.0, 0.0]));
    }

    #[test]
    fn turn_expansion_of_axes_4_and_6() {
        let r = irb2600();
        let q = [10.0, 10.0, 10.0, 10.0, 30.0, 20.0];
        let p = r.fk(&q);
        let all = r.ik_all(&p);
        let same_arm: Vec<_> = all
            .iter()
            .filter(|s| (s[0] - 10.0).abs() < 1e-6 && (s[4] - 30.0).abs() < 1e-6)
            .collect();
        // axis 4 ∈ {−350, 10, 370}, axis 6 ∈ {−340, 20, 380} (±400° both).
        assert_eq!(same_arm.len(), 9, "{same_arm:?}");
        let q_turned = r.ik_conf(&p, &ConfData::new(0, 4, -4, 0)).unwrap();
        assert_joints(&q_turned, &[10.0, 10.0, 10.0, 370.0, 30.0, -340.0], 1e-6);
        // With axis 6 at 100°, cf6 = 5 means 460°, beyond ±400°.
        let q = [10.0, 10.0, 10.0, 10.0, 30.0, 100.0];
        let e = r
            .ik_conf(&r.fk(&q), &ConfData::new(0, 0, 5, 0))
            .unwrap_err();
        assert!(
            matches!(e, KinError::JointOutOfRange { joint: 6, .. }),
            "{e:?}"
        );
    }

    #[test]
    fn axis_1_turns_on_robots_with_a_range_beyond_180() {
        // The IRB 2600's axis 1 is ±180°: at exactly 180° both ends are valid.
        let r = irb2600();
        let q = [180.0, 10.0, 10.0, 0.0, 30.0, 0.0];
        let all = r.ik_all(&r.fk(&q));
        assert!(all.iter().any(|s| (s[0] - 180.0).abs() < 1e-6));
        assert!(all.iter().any(|s| (s[0] + 180.0).abs() < 1e-6));
        let back = r.ik_conf(&r.fk(&q), &ConfData::new(-3, 0, 0, 0)).unwrap();
        assert!((back[0] + 180.0).abs() < 1e-6, "{back:?}");
    }

    #[test]
    fn rounded_targets_at_a_quadrant_boundary_still_match() {
        // Taught at axis 6 = −0.001° (cf6 = −1), solved at +0.0004° after rounding: the slack
        // of CONF_QUADRANT_SLACK_DEG accepts it.
        let r = irb2600();
        let q = [10.0, 10.0, 10.0, 20.0, 30.0, 0.0004];
        let back = r.ik_conf(&r.fk(&q), &ConfData::new(0, 0, -1, 0)).unwrap();
        assert_joints(&back, &q, 1e-6);
        // A whole quadrant off is not accepted.
        assert!(r.ik_conf(&r.fk(&q), &ConfData::new(0, 0, 1, 0)).is_err());
    }
}

mod errors {
    //! Limits, unreachable poses, singularities and non-finite input: errors, never panics.
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn joint_limits() {
        let r = irb2600();
        assert!(r.check_limits(&[0.0, 0.0, 0.0, 0.0, 40.0, 0.0]).is_ok());
        assert!(
            r.check_limits(&[180.0, 155.0, -180.0, -400.0, 120.0, 400.0])
                .is_ok()
        );
        let e = r
            .check_limits(&[0.0, 0.0, 80.0, 0.0, 0.0, 0.0])
            .unwrap_err();
        assert_eq!(
            e,
            KinError::JointOutOfRange {
                joint: 3,
                value: 80.0,
                min: -180.0,
                max: 75.0
            }
        );
        assert_eq!(e.event(), (50027, "Joint out of range"));
        assert_eq!(e.rapid_error_name(), "ERR_ROBLIMIT");
    }

    #[test]
    fn pose_reachable_only_beyond_the_limits() {
        // IRB 120: axis 1 is ±165°; every solution for a pose at axis 1 = 175° needs an axis
        // beyond its range (the shoulder-flipped ones fold axis 3 past its limit).
        let r = Robot::new(model_by_name("IRB 120-3/0.58").unwrap());
        let q = [175.0, 10.0, 10.0, 0.0, 30.0, 0.0];
        let p = r.fk(&q);
        assert!(r.ik_all(&p).is_empty());
        for e in [
            r.ik_nearest(&p, &[165.0, 0.0, 0.0, 0.0, 30.0, 0.0])
                .unwrap_err(),
            r.ik_conf(&p, &ConfData::new(1, 0, 0, 0)).unwrap_err(),
        ] {
            assert!(matches!(e, KinError::JointOutOfRange { .. }), "{e:?}");
            assert_eq!(e.event().0, 50027);
        }
    }

    #[test]
    fn outside_reach() {
        let r = irb2600();
        let far = pose_from_pos_quat([3000.0, 0.0, 1000.0], [1.0, 0.0, 0.0, 0.0]);
        assert!(r.ik_all(&far).is_empty());
        let e = r.ik_conf(&far, &ConfData::default()).unwrap_err();
        assert_eq!(
            e,
            KinError::OutsideReach {
                position: [3000.0, 0.0, 1000.0]
            }
        );
        assert_eq!(e.event(), (50050, "Position outside reach"));
        assert_eq!(e.rapid_error_name(), "ERR_OUTSIDE_REACH");
        assert!(matches!(
            r.ik_nearest(&far, &[0.0; 6]),
            Err(KinError::OutsideReach { .. })
        ));
    }

    #[test]
    fn configuration_not_in_the_table() {
        let r = irb2600();
        let p = r.fk(&[0.0, 0.0, 0.0, 0.0, 40.0, 0.0]);
        let e = r.ik_conf(&p, &ConfData::new(0, 0, 0, 9)).unwrap_err();
        assert!(
            matches!(e, KinError::ConfigurationUnreachable { .. }),
            "{e:?}"
        );
        assert_eq!(e.rapid_error_name(), "ERR_ROBLIMIT");
    }

    #[test]
    fn singularities() {
        let r = irb2600();
        assert_eq!(
            r.near_singularity(&[0.0, 0.0, 0.0, 0.0, 1.0, 0.0]),
            Some(SingularityKind::Wrist)
        );
        assert_eq!(r.near_singularity(&[0.0, 0.0, 0.0, 0.0, 40.0, 0.0]), None);
        // Wrist centre on axis 1: r = a1 + c2·sin J2 + k·sin(J2 + J3 + 90° + ψ3) = 0.
        let opw = &r.model().opw;
        let j2 = -20.0f64;
        let s = (-(opw.a1 + opw.c2 * j2.to_radians().sin()) / opw.k()).asin();
        let j3 = s.to_degrees() - j2 - 90.0 - opw.psi3().to_degrees();
        let q = [0.0, j2, j3, 0.0, 40.0, 0.0];
        assert!(r.singularity(&q).shoulder_mm.abs() < 1e-9, "{q:?}");
        assert_eq!(r.near_singularity(&q), Some(SingularityKind::Shoulder));
        let e = r.check_singularity(&q).unwrap_err();
        assert_eq!(e.event(), (50026, "Close to singularity"));
        assert!(
            r.check_singularity(&[0.0, 0.0, 0.0, 0.0, 40.0, 0.0])
                .is_ok()
        );
    }

    #[test]
    fn non_finite_input() {
        let r = irb2600();
        let nan_q = [f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0];
        assert!(r.fk(&nan_q).translation.vector.x.is_nan());
        assert_eq!(r.try_fk(&nan_q), Err(KinError::NotFinite));
        assert_eq!(r.check_limits(&nan_q), Err(KinError::NotFinite));
        let _ = r.conf_of(&nan_q);
        assert_eq!(r.near_singularity(&[f64::NAN; 6]), None);
        let good = r.fk(&[0.0, 0.0, 0.0, 0.0, 40.0, 0.0]);
        for bad in [
            pose_from_pos_quat([f64::NAN, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]),
            pose_from_pos_quat([f64::INFINITY, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]),
            pose_from_pos_quat([1000.0, 0.0, 1000.0], [0.0, 0.0, 0.0, 0.0]),
            pose_from_pos_quat([1000.0, 0.0, 1000.0], [f64::NAN, 0.0, 0.0, 0.0]),
        ] {
            assert!(r.ik_all(&bad).is_empty());
            assert_eq!(
                r.ik_conf(&bad, &ConfData::default()),
                Err(KinError::NotFinite)
            );
            assert_eq!(r.ik_nearest(&bad, &[0.0; 6]), Err(KinError::NotFinite));
        }
        assert_eq!(r.ik_nearest(&good, &nan_q), Err(KinError::NotFinite));
        let nan_base = irb2600().with_base(pose_from_pos_quat([f64::NAN; 3], [1.0, 0.0, 0.0, 0.0]));
        assert_eq!(
            nan_base.ik_conf(&good, &ConfData::default()),
            Err(KinError::NotFinite)
        );
        // Absurd but finite references do not break continuity either.
        let far_ref = [1e300, 0.0, 0.0, 0.0, 40.0, 0.0];
        assert!(r.ik_nearest(&good, &far_ref).is_ok());
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]
        #[test]
        fn never_panics_on_any_pose(
            pos in prop::array::uniform3(prop_oneof![any::<f64>(), -3000.0..3000.0f64]),
            rot in prop::array::uniform4(prop_oneof![any::<f64>(), -1.0..1.0f64]),
            cur in prop::array::uniform6(prop_oneof![any::<f64>(), -400.0..400.0f64]),
            conf in prop::array::uniform4(-10i32..10),
        ) {
            let r = irb2600();
            let p = pose_from_pos_quat(pos, rot);
            let all = r.ik_all(&p);
            for s in &all {
                prop_assert!(r.check_limits(s).is_ok());
            }
            let _ = r.ik_conf(&p, &ConfData::from_array(conf));
            let _ = r.ik_nearest(&p, &cur);
            let _ = r.fk(&cur);
            let _ = r.conf_of(&cur);
            let _ = r.near_singularity(&cur);
            let _ = r.check_limits(&cur);
        }
    }
}

mod frames {
    //! Tools and work objects through the whole chain.
    use super::*;

    #[test]
    fn work_object_and_displacement() {
        let r = irb2600();
        let tool = t_fronius_cmt();
        let wobj = WobjData {
            uframe: pose_from_pos_quat([800.0, -200.0, 300.0], [0.9659258, 0.0, 0.0, 0.258819]),
            oframe: pose_from_pos_quat([50.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]),
            ..WobjData::wobj0()
        };
        let pdisp = pose_from_pos_quat([0.0, 20.0, 0.0], [1.0, 0.0, 0.0, 0.0]);
        // A point in the object frame, torch pointing down.
        let target = pose_from_pos_quat([100.0, 50.0, 10.0], [0.0, 0.0, 1.0, 0.0]);
        let flange = flange_target(&target, &tool, &wobj, &pdisp);
        let q = r
            .ik_nearest(&flange, &[0.0, 0.0, 0.0, 0.0, 40.0, 0.0])
            .unwrap();
        let tcp_world = r.tcp_world(&q, &tool);
        let expected = wobj.uframe * wobj.oframe * pdisp * target;
        assert_pos(&tcp_world, pose_to_pos_quat(&expected).0, 1e-6);
        // tcp_pose is in the object frame without the displacement.
        let tcp_obj = r.tcp_pose(&q, &tool, &wobj);
        assert_pos(&tcp_obj, [100.0, 70.0, 10.0], 1e-6);
        let in_disp = rapidvc::robot::target_from_flange(&r.fk(&q), &tool, &wobj, &pdisp);
        assert_pos(&in_disp, [100.0, 50.0, 10.0], 1e-6);
    }

    #[test]
    fn stationary_tool_with_robot_held_work_object() {
        let r = irb2600();
        // A fixed spindle in front of the robot, pointing up.
        let tool = ToolData {
            robhold: false,
            tframe: pose_from_pos_quat([1300.0, 0.0, 800.0], [1.0, 0.0, 0.0, 0.0]),
            load: LoadData::LOAD0,
        };
        // The part hangs 150 mm below the flange.
        let wobj = WobjData {
            robhold: true,
            uframe: pose_from_pos_quat([0.0, 0.0, 150.0], [1.0, 0.0, 0.0, 0.0]),
            ..WobjData::wobj0()
        };
        assert!(rapidvc::robot::frames::frames_consistent(&tool, &wobj));
        // Bring the point (10, 0, 0) of the part, facing down, onto the spindle tip.
        let target = pose_from_pos_quat([10.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]);
        let flange = flange_target(&target, &tool, &wobj, &Pose::identity());
        let q = r
            .ik_nearest(&flange, &[0.0, 0.0, 0.0, 0.0, 40.0, 0.0])
            .unwrap();
        // The part point in world coincides with the spindle.
        let part_point = r.fk(&q) * wobj.uframe * wobj.oframe * target;
        assert_pos(&part_point, [1300.0, 0.0, 800.0], 1e-6);
        let tcp = r.tcp_pose(&q, &tool, &wobj);
        assert_pos(&tcp, [10.0, 0.0, 0.0], 1e-6);
        assert_quat(&tcp, [0.0, 1.0, 0.0, 0.0], 1e-9);
    }
}
