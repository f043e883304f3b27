//! Unit tests of the EGM glue on a virtual-time controller with the built-in sensor and signal sources.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

use super::*;
use crate::config::devices::DeviceTable;
use crate::config::moc::MocConfig;
use crate::controller::ControllerConfig;
use crate::egm::registry::RunArgs;
use crate::egm::types::EgmMode;
use crate::motion::CoreConfig;
use crate::robot::command::{
    EXTAX_NONE, JointTarget, MotionCommand, MoveAbsJ, MoveArgs, SpeedData, ZoneData,
};
use crate::robot::{JointsDeg, ToolData, WobjData};

const START: JointsDeg = [0.0, 0.0, 0.0, 0.0, 30.0, 0.0];

fn abs_j(id: u64, q: JointsDeg) -> MotionCommand {
    MotionCommand::MoveAbsJ(MoveAbsJ {
        args: MoveArgs {
            id,
            source: None,
            speed: SpeedData::v(1000.0),
            speed_override: None,
            zone: ZoneData::FINE,
            tool: ToolData::tool0(),
            wobj: WobjData::wobj0(),
            tload: None,
            pdisp: Pose::identity(),
        },
        target: JointTarget {
            robax: q,
            extax: EXTAX_NONE,
        },
        no_eoffs: false,
    })
}

fn controller(devices: &[&str]) -> (ControllerHandle, EgmController) {
    let overrides: Vec<_> = devices.iter().map(|d| d.parse().unwrap()).collect();
    let table = DeviceTable::new(None, &overrides).unwrap();
    let setup = EgmSetup {
        registry: RegistryConfig::new(MocConfig::default(), table),
        driver: DriverOptions::default(),
        lockstep: None,
        feed: None,
        log: None,
    };
    let robot = Robot::default();
    let signals = Arc::new(SignalTable::with_builtins());
    let (egm, hook) = EgmController::new(setup, robot.clone(), signals).unwrap();
    let mut config = ControllerConfig::new(robot, [0.0; 6]);
    config.core = CoreConfig::default();
    let mut handle =
        ControllerHandle::start_with_hook(config, Vec::new(), Some(Box::new(hook))).unwrap();
    handle.submit(abs_j(1, START)).unwrap();
    handle.wait_until(Condition::InPos).unwrap();
    (handle, egm)
}

/// Waits (ticking virtual time) until the run of `name` is done.
fn wait_run(
    h: &mut ControllerHandle,
    egm: &mut EgmController,
    name: &str,
) -> Result<(), EgmFailure> {
    for _ in 0..100_000 {
        if egm.run_done(name, false)? {
            return Ok(());
        }
        let t = h.now().saturating_add(Duration::from_millis(4));
        h.wait_until(Condition::TimeReached(t)).unwrap();
    }
    panic!("the run did not end");
}

fn uc(mode: EgmMode, device: &str) -> SetupUc {
    SetupUc {
        mecunit: "ROB_1".into(),
        profile: "default".into(),
        device: device.into(),
        mode,
        tracker: None,
        comm_timeout: None,
    }
}

#[test]
fn a_joint_run_with_the_builtin_sensor_converges_and_returns_to_connected() {
    let (mut h, mut egm) = controller(&["sensor=builtin:joint:10,-5,20,0,40,30"]);
    egm.get_id(&mut h, "egmID1").unwrap();
    assert_eq!(
        egm.state("egmID1").unwrap(),
        (EgmState::Disconnected, CorrState::Stopped)
    );
    egm.setup_uc(&mut h, "egmID1", &uc(EgmMode::Joint, "sensor"))
        .unwrap();
    let mut act = ActJoint::default();
    act.common.max_speed_deviation = Some(100.0);
    egm.act_joint(&mut h, "egmID1", &act).unwrap();
    let args = RunArgs {
        cond_time: Some(0.5),
        ..RunArgs::new(StopMode::Hold)
    };
    let axes = [true, true, true, true, true, true, false];
    egm.run_joint(&mut h, "egmID1", &args, axes, LastMove::StopPoint, None)
        .unwrap();
    assert_eq!(egm.state("egmID1").unwrap().0, EgmState::Running);
    wait_run(&mut h, &mut egm, "egmID1").unwrap();
    assert_eq!(
        egm.state("egmID1").unwrap(),
        (EgmState::Connected, CorrState::Stopped)
    );
    let q = h.state().setpoint.joints;
    for (a, b) in q.iter().zip([10.0, -5.0, 20.0, 0.0, 40.0, 30.0]) {
        assert!((a - b).abs() < 0.5, "{q:?}");
    }
    // Planned motion works again afterwards.
    h.submit(abs_j(2, START)).unwrap();
    h.wait_until(Condition::InPos).unwrap();
    assert_eq!(h.state().setpoint.joints, START);
}

#[test]
fn run_checks_fine_point_and_previous_move() {
    let (mut h, mut egm) = controller(&[]);
    egm.get_id(&mut h, "id").unwrap();
    egm.setup_uc(&mut h, "id", &uc(EgmMode::Joint, "x"))
        .unwrap();
    egm.act_joint(&mut h, "id", &ActJoint::default()).unwrap();
    let args = RunArgs::new(StopMode::Hold);
    let axes = [true, true, true, true, true, true, false];
    let e = egm
        .run_joint(&mut h, "id", &args, axes, LastMove::None, None)
        .unwrap_err();
    assert!(
        matches!(e, EgmFailure::Egm(EgmError::NoPreviousMove { .. })),
        "{e}"
    );
    let e = egm
        .run_joint(&mut h, "id", &args, axes, LastMove::FlyBy, None)
        .unwrap_err();
    assert!(
        matches!(e, EgmFailure::Egm(EgmError::NotInFinePoint { .. })),
        "{e}"
    );
    assert_eq!(egm.state("id").unwrap().0, EgmState::Connected);
    // Mode mismatch: a pose run on a joint setup is 41826.
    let e = egm
        .run_pose(
            &mut h,
            "id",
            &args,
            [true; 6],
            None,
            LastMove::StopPoint,
            None,
        )
        .unwrap_err();
    let EgmFailure::Egm(e) = e else { panic!() };
    assert_eq!(e.event().number, 41826);
}

#[test]
fn egmstop_ends_a_no_wait_run_and_program_stop_ramps_out() {
    let (mut h, mut egm) = controller(&["s=builtin:joint:30,0,0,0,30,0"]);
    egm.get_id(&mut h, "a").unwrap();
    egm.setup_uc(&mut h, "a", &uc(EgmMode::Joint, "s")).unwrap();
    let mut act = ActJoint::default();
    act.common.max_speed_deviation = Some(10.0);
    egm.act_joint(&mut h, "a", &act).unwrap();
    let args = RunArgs {
        no_wait_cond: true,
        cond_time: Some(9e9),
        ..RunArgs::new(StopMode::Hold)
    };
    let axes = [true, false, false, false, false, false, false];
    egm.run_joint(&mut h, "a", &args, axes, LastMove::StopPoint, None)
        .unwrap();
    let t = h.now().saturating_add(Duration::from_secs(1));
    h.wait_until(Condition::TimeReached(t)).unwrap();
    let q1 = h.state().setpoint.joints[0];
    assert!(q1 > 5.0 && q1 < 15.0, "moving at ≤ 10 °/s: {q1}");
    assert!(egm.run_active("a").unwrap());
    egm.stop(&mut h, "a", StopMode::Hold, None).unwrap();
    while egm.run_active("a").unwrap() {
        let t = h.now().saturating_add(Duration::from_millis(4));
        h.wait_until(Condition::TimeReached(t)).unwrap();
    }
    egm.stop_done("a").unwrap();
    assert_eq!(egm.state("a").unwrap().0, EgmState::Connected);
    assert!(egm.run_done("a", true).unwrap());
    // Again, then the program stops: the run ramps out and ends.
    egm.run_joint(&mut h, "a", &args, axes, LastMove::StopPoint, None)
        .unwrap();
    let t = h.now().saturating_add(Duration::from_millis(500));
    h.wait_until(Condition::TimeReached(t)).unwrap();
    egm.program_stopped(&mut h).unwrap();
    assert_eq!(h.state().mode, CoreMode::Planned);
    assert!(!egm.run_active("a").unwrap());
    let events = egm.take_events();
    assert!(
        events.iter().any(|(n, e)| n == "a" && e.number == 90110),
        "the speed limit is reported: {events:?}"
    );
}

#[test]
fn streams_send_during_ordinary_motion() {
    let (mut h, mut egm) = controller(&[]);
    egm.get_id(&mut h, "s").unwrap();
    egm.setup_uc(&mut h, "s", &uc(EgmMode::Joint, "dev"))
        .unwrap();
    egm.stream_start(&mut h, "s", Some(8.0)).unwrap();
    assert_eq!(
        egm.state("s").unwrap(),
        (EgmState::Running, CorrState::Stopped)
    );
    h.submit(abs_j(2, [20.0, 0.0, 0.0, 0.0, 30.0, 0.0]))
        .unwrap();
    h.wait_until(Condition::InPos).unwrap();
    let sent = egm.streams()[0].stream.sent();
    assert!(sent > 10, "{sent}");
    egm.stream_stop(&mut h, "s").unwrap();
    assert!(egm.streams().is_empty());
    assert_eq!(egm.state("s").unwrap().0, EgmState::Connected);
    egm.reset(&mut h, "s").unwrap();
    assert_eq!(
        egm.state("s").unwrap(),
        (EgmState::Disconnected, CorrState::Undefined)
    );
}
