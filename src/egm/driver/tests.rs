//! Unit tests of the EGM driver: start checks, signal sources in joint mode, event bounds and helpers.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

use super::*;
use crate::egm::registry::{ActJoint, ActPose, RunArgs, SetupSignals, SetupUc};
use crate::egm::test_support::{ctx, registry};
use crate::signals::SignalKind;
use crate::time::RobotTime;

const START: Joints = [0.0, 0.0, 0.0, 0.0, 30.0, 0.0];

#[test]
fn joint_signals_beyond_an_axis_limit_are_refused_and_the_previous_stays() {
    let table = Arc::new(SignalTable::with_builtins());
    let mut reg = registry();
    let id = reg.get_id("egmID2").unwrap();
    let j1 = table.lookup("ao_MoveX").unwrap();
    let j2 = table.lookup("ao_MoveY").unwrap();
    let setup = SetupSignals {
        mecunit: "ROB_1".into(),
        profile: "default".into(),
        kind: SignalKind::Ao,
        mode: EgmMode::Joint,
        tracker: None,
        mapping: [Some(j1), Some(j2), None, None, None, None],
        ext: [None; 6],
    };
    reg.setup_signals(id, &setup, &table).unwrap();
    let mut act = ActJoint::default();
    act.common.max_speed_deviation = Some(100.0);
    reg.act_joint(id, &act).unwrap();
    let args = RunArgs {
        cond_time: Some(9e9),
        ..RunArgs::new(StopMode::Hold)
    };
    let plan = reg
        .run_joint(id, &args, [true, true, false, false, false, false, false])
        .unwrap();
    table.set(j1, 10.0).unwrap();
    table.set(j2, 5.0).unwrap();
    let ctx = ctx(Arc::clone(&table));
    let source = EgmSource::new(&plan.source);
    let mut d = EgmDriver::start(RobotTime::ZERO, &ctx, &plan, source, &START).unwrap();
    let mut q = START;
    let tick = Duration::from_millis(4);
    for k in 0..600u32 {
        q = d.tick(RobotTime::from_duration(tick * k), &q).joints_cmd;
    }
    assert!(
        (q[0] - 10.0).abs() < 0.05 && (q[1] - 5.0).abs() < 0.05,
        "{q:?}"
    );
    // J2 = 1000° is beyond its limit: refused once with 90105, the robot stays.
    table.set(j2, 1000.0).unwrap();
    for k in 600..700u32 {
        let t = d.tick(RobotTime::from_duration(tick * k), &q);
        q = t.joints_cmd;
        assert!(t.sent, "signals are sampled every tick at 4 ms");
    }
    assert!((q[1] - 5.0).abs() < 0.05, "{q:?}");
    let events: Vec<EgmEvent> = std::iter::from_fn(|| d.poll_event()).collect();
    let refused: Vec<&EgmEvent> = events.iter().filter(|e| e.number == 90105).collect();
    assert_eq!(refused.len(), 1, "{events:?}");
    assert!(refused[0].detail.contains("joint 2"), "{}", refused[0]);
    assert!(d.session_stats().is_none() && d.sensor_stats().is_none());
    assert!(!d.awaiting_reply() && d.poll_transmit(RobotTime::ZERO).is_none());
    // The log has one row per sample with the (refused) value as read.
    let rows: Vec<LogRow> = std::iter::from_fn(|| d.pop_log()).collect();
    assert_eq!(rows.len(), 700);
    assert_eq!(rows[699].reference.unwrap()[1], 1000.0);
    assert_eq!(rows[699].recv_time, Some(rows[699].send_time));
}

#[test]
fn start_checks() {
    let table = Arc::new(SignalTable::with_builtins());
    let ctx = ctx(Arc::clone(&table));
    let mut reg = registry();
    let id = reg.get_id("egmID1").unwrap();
    let uc = SetupUc {
        mecunit: "ROB_1".into(),
        profile: "default".into(),
        device: "builtin".into(),
        mode: EgmMode::Pose,
        tracker: None,
        comm_timeout: None,
    };
    reg.setup_uc(id, &uc).unwrap();
    // A stationary tool is not modelled for pose guidance.
    let mut act = ActPose::world();
    act.common.tool = Some(ToolData {
        robhold: false,
        ..ToolData::tool0()
    });
    reg.act_pose(id, &act).unwrap();
    let plan = reg
        .run_pose(id, &RunArgs::new(StopMode::Hold), [true; 6], None)
        .unwrap();
    let source = || EgmSource::new(&plan.source);
    let err = EgmDriver::start(RobotTime::ZERO, &ctx, &plan, source(), &START).unwrap_err();
    assert!(err.to_string().contains("stationary tool"), "{err}");
    // Start beyond an axis limit, or not finite.
    let mut beyond = START;
    beyond[2] = 500.0;
    let err = EgmDriver::start(RobotTime::ZERO, &ctx, &plan, source(), &beyond).unwrap_err();
    assert_eq!(err.event().number, 50027, "{err}");
    let err = EgmDriver::start(RobotTime::ZERO, &ctx, &plan, source(), &[f64::NAN; 6]).unwrap_err();
    assert!(matches!(err, EgmError::Supervision(_)));
    // A built-in pattern of the other mode.
    let joint_source = EgmSource::Builtin {
        device: "x".into(),
        pattern: "joint:0,0,0,0,30,0".parse().unwrap(),
    };
    reg.act_pose(id, &ActPose::world()).unwrap_err(); // still running: busy
    reg.run_finished(id, false);
    reg.act_pose(id, &ActPose::world()).unwrap();
    let plan = reg
        .run_pose(id, &RunArgs::new(StopMode::Hold), [true; 6], None)
        .unwrap();
    let err = EgmDriver::start(RobotTime::ZERO, &ctx, &plan, joint_source, &START).unwrap_err();
    assert!(matches!(err, EgmError::BadDevice { .. }), "{err}");
    // A zero tick.
    let mut bad = ctx.clone();
    bad.options.tick = Duration::ZERO;
    assert!(EgmDriver::start(RobotTime::ZERO, &bad, &plan, source(), &START).is_err());
}

#[test]
fn helpers() {
    let limits = robot_limits(&Robot::default());
    let model = Robot::default().model().joint_limits;
    for (i, l) in model.iter().enumerate() {
        assert_eq!((limits.joint_min[i], limits.joint_max[i]), (l.min, l.max));
    }
    assert_eq!(phase_name(ServoPhase::RampingDown), "ramping_down");
    let mut q = EventQueue::with_capacity();
    for i in 0..(MAX_EVENTS + 5) {
        q.push(EgmEvent::new(EventKind::Malformed, format!("{i}")));
    }
    assert_eq!((q.len(), q.dropped), (MAX_EVENTS, 5));
    assert_eq!(q.pop().unwrap().detail, "0");
    let p = pose6(&WirePose {
        pos: [1.0, 2.0, 3.0],
        orient: [1.0, 0.0, 0.0, 0.0],
    });
    assert_eq!(p, [1.0, 2.0, 3.0, 0.0, 0.0, 0.0]);
}
