//! ControllerHost on a virtual-time controller: waits, the program clock, motion errors and
//! recovery, kinematics.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use super::*;
use crate::controller::ControllerConfig;
use crate::interp::errnum;
use crate::motion::{ExternalGuidance, GuidanceStep};
use crate::robot::command::{JointTarget, MoveAbsJ, MoveArgs, SpeedData, ZoneData};
use crate::robot::{ConfData, Robot};

fn host() -> ControllerHost {
    let config = ControllerConfig::new(Robot::default(), [0.0, 0.0, 0.0, 0.0, 30.0, 0.0]);
    ControllerHost::new(ControllerHandle::start(config, Vec::new()).unwrap())
}

fn abs_j(robax: JointsDeg, zone: ZoneData) -> MotionCommand {
    MotionCommand::MoveAbsJ(MoveAbsJ {
        args: MoveArgs::new(0, SpeedData::v(1000.0), zone, ToolData::tool0()),
        target: JointTarget {
            robax,
            extax: EXTAX_NONE,
        },
        no_eoffs: false,
    })
}

fn z50() -> ZoneData {
    ZoneData {
        finep: false,
        pzone_tcp: 50.0,
        ..ZoneData::FINE
    }
}

/// `Host::wait_until` with the deadline and the answer in seconds.
fn wait_secs(h: &mut ControllerHost, deadline: f64) -> Result<f64, HostError> {
    h.wait_until(RobotTime::from_secs_f64(deadline))
        .map(RobotTime::as_secs_f64)
}

#[test]
fn ids_waits_and_the_program_clock() {
    let mut h = host();
    let a = h
        .motion_submit(abs_j([20.0, 0.0, 0.0, 0.0, 30.0, 0.0], z50()))
        .unwrap();
    let b = h
        .motion_submit(abs_j([20.0, 10.0, 0.0, 0.0, 30.0, 0.0], ZoneData::FINE))
        .unwrap();
    assert_eq!((a, b), (1, 2));
    assert_eq!(h.moves_submitted(), 2);
    assert!(!h.motion_reached(MotionWait::Done(a)).unwrap());
    // A long wait ends early, when the motion state changes.
    let t = wait_secs(&mut h, 100.0).unwrap();
    assert!(t > 0.0 && t < 100.0, "{t}");
    while !h.motion_reached(MotionWait::Done(b)).unwrap() {
        wait_secs(&mut h, 100.0).unwrap();
    }
    assert!(h.motion_reached(MotionWait::InPos).unwrap());
    assert!(h.motion_reached(MotionWait::ZeroSpeed).unwrap());
    assert_eq!(
        h.motion_joints().unwrap(),
        [20.0, 10.0, 0.0, 0.0, 30.0, 0.0]
    );
    // The program's clock ends waits at their exact deadline; the robot's moves in cycles.
    let deadline = h.now().after_secs(1.25);
    while h.now() < deadline {
        h.wait_until(deadline).unwrap();
    }
    assert_eq!(h.now(), deadline);
    let deadline = deadline.as_secs_f64();
    let robot = h.controller().unwrap().time().as_secs_f64();
    assert!(robot <= deadline && deadline - robot < 0.004, "{robot}");
    let summary = h.finish(true).unwrap();
    assert_eq!(summary.final_joints, [20.0, 10.0, 0.0, 0.0, 30.0, 0.0]);
    assert!(h.motion_joints().is_err());
}

/// Guidance that jumps axis 1 by 40° in one cycle: the core's speed supervision stops the
/// robot.
struct Jump;

impl ExternalGuidance for Jump {
    fn step(&mut self, _now: RobotTime, current: &JointsDeg) -> GuidanceStep {
        let mut q = *current;
        q[0] += 40.0;
        GuidanceStep::MoveTo(q)
    }
}

#[test]
fn a_fault_while_waiting_is_a_rapid_error_and_the_robot_recovers() {
    let mut h = host();
    h.controller()
        .unwrap()
        .start_external(Box::new(Jump), ToolData::tool0(), None)
        .unwrap();
    let e = wait_secs(&mut h, 1.0).unwrap_err();
    assert_eq!(e.errno, Some(errnum::ERR_ROBLIMIT), "{e}");
    assert!(
        e.message.starts_with("Joint speed error: joint 1 speed"),
        "{e}"
    );
    // Recovered: the next move is accepted and executed.
    let id = h
        .motion_submit(abs_j([0.0, 0.0, 0.0, 0.0, 45.0, 0.0], ZoneData::FINE))
        .unwrap();
    while !h.motion_reached(MotionWait::Done(id)).unwrap() {
        wait_secs(&mut h, 100.0).unwrap();
    }
    assert_eq!(h.motion_joints().unwrap()[4], 45.0);
}

#[test]
fn refused_moves_and_limits() {
    let mut h = host().with_max_time(2.0);
    let e = h
        .motion_submit(abs_j([0.0, 0.0, 90.0, 0.0, 30.0, 0.0], ZoneData::FINE))
        .unwrap_err();
    assert_eq!(e.errno, Some(errnum::ERR_ROBLIMIT));
    assert!(
        e.message.starts_with("50027 Joint out of range: joint 3"),
        "{e}"
    );
    // A refused move never runs: the robot is in position.
    assert!(h.motion_reached(MotionWait::InPos).unwrap());
    // Waiting past --max-time.
    assert_eq!(wait_secs(&mut h, 5.0).unwrap(), 2.0);
    let e = wait_secs(&mut h, 5.0).unwrap_err();
    assert!(e.message.contains("virtual time limit of 2 s"), "{e}");
}

#[test]
fn kinematics_of_crobt_and_calcjointt() {
    let mut h = host();
    h.motion_set(MotionSetting::ConfJ(false)).unwrap();
    h.motion_set(MotionSetting::VelSet {
        override_pct: 50.0,
        max_tcp: 800.0,
    })
    .unwrap();
    assert!(!h.motion_modes().conf_j && h.motion_modes().conf_l);
    let s = h.controller().unwrap().settings();
    assert_eq!((s.velset.override_pct, s.velset.max_tcp), (50.0, 800.0));
    let q = [10.0, 20.0, -10.0, 30.0, 40.0, -50.0];
    let (tool, wobj, pdisp) = (ToolData::tool0(), WobjData::wobj0(), Pose::identity());
    let t = h.robot_target_of(&q, &tool, &wobj, &pdisp).unwrap();
    assert_eq!(t.robconf, ConfData::new(0, 0, -1, 0));
    let back = h.robot_joints_of(&t, &tool, &wobj, &pdisp).unwrap();
    for (a, b) in back.iter().zip(q) {
        assert!((a - b).abs() < 1e-6, "{back:?}");
    }
    let far = RobTarget {
        trans: [4000.0, 0.0, 0.0],
        ..t
    };
    let e = h.robot_joints_of(&far, &tool, &wobj, &pdisp).unwrap_err();
    assert_eq!(e.errno, Some(errnum::ERR_OUTSIDE_REACH));
    assert!(e.message.starts_with("50050 Position outside reach"), "{e}");
}
