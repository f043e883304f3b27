//! Integration tests of the virtual robot: the acceptance facts of robot.md §11, FK/IK round
//! trips on every model, confdata and error cases.

// Expected values are quoted digit for digit from robot.md (0.707107 is not FRAC_1_SQRT_2).
#![allow(clippy::approx_constant)]

use rapidvc::robot::command::RobTarget;
use rapidvc::robot::units::{pose_from_pos_quat, pose_to_pos_quat};
use rapidvc::robot::{
    ConfData, JointsDeg, KinError, LoadData, Pose, Robot, SingularityKind, ToolData, WobjData,
    default_model, flange_target, model_by_name,
};

/// Joint tolerance of robot.md §11 (the expected values are rounded to 0.001°).
const JOINT_TOL: f64 = 0.01;
/// Position tolerance (mm).
const POS_TOL: f64 = 0.1;
/// Quaternion tolerance per component, up to sign.
const QUAT_TOL: f64 = 1e-4;

fn irb2600() -> Robot {
    Robot::new(default_model())
}

fn t_fronius_cmt() -> ToolData {
    ToolData {
        robhold: true,
        tframe: pose_from_pos_quat(
            [12.3313, -0.108707, 416.142],
            [0.903899, -0.00320735, 0.427666, 0.00765917],
        ),
        load: LoadData::LOAD0,
    }
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

fn assert_joints(actual: &JointsDeg, expected: &JointsDeg, tol: f64) {
    for i in 0..6 {
        assert!(
            (actual[i] - expected[i]).abs() <= tol,
            "axis {}: {actual:?} vs {expected:?}",
            i + 1
        );
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
    //! robot.md §11 on the default IRB 2600-12/1.85.
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
