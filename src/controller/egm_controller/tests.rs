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
use crate::robot::{JointsDeg, ToolData};
use crate::time::RobotTime;

const START: JointsDeg = [0.0, 0.0, 0.0, 0.0, 30.0, 0.0];

fn abs_j(id: u64, q: JointsDeg) -> MotionCommand {
    MotionCommand::MoveAbsJ(MoveAbsJ {
        args: MoveArgs::new(id, SpeedData::v(1000.0), ZoneData::FINE, ToolData::tool0()),
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
        registry: super::registry_config(&MocConfig::default(), &table),
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

/// RAPID programs end to end on a host of this test (the robot starts at a fine point).
mod rapid {
    use super::*;
    use crate::diag::Diagnostics;
    use crate::interp::{Host, HostError, Interp, Output, Registry};
    use crate::source::{SourceMap, Span};

    struct TestHost {
        handle: ControllerHandle,
        egm: EgmController,
        signals: Arc<SignalTable>,
        now: RobotTime,
        lines: Arc<std::sync::Mutex<Vec<String>>>,
        joints: Arc<std::sync::Mutex<JointsDeg>>,
        next_id: u64,
    }

    impl Host for TestHost {
        fn now(&self) -> RobotTime {
            self.now
        }
        fn wait_until(&mut self, deadline: RobotTime) -> Result<RobotTime, HostError> {
            self.handle
                .wait_until(Condition::TimeReached(deadline))
                .map_err(|e| HostError::fatal(e.to_string()))?;
            self.now = self.handle.now();
            *self.joints.lock().unwrap() = self.handle.state().setpoint.joints;
            Ok(self.now)
        }
        fn output(&mut self, out: Output) {
            let line = match out {
                Output::TpWrite(s) => s,
                Output::Event(e) => format!("event: {e}"),
                other => format!("{other:?}"),
            };
            self.lines.lock().unwrap().push(line);
        }
        fn read_signal(&mut self, name: &str) -> Result<f64, HostError> {
            let id = self.signals.lookup(name).unwrap();
            Ok(self.signals.value(id).unwrap())
        }
        fn write_signal(&mut self, name: &str, value: f64) -> Result<(), HostError> {
            let id = self.signals.lookup(name).unwrap();
            self.signals.set(id, value).unwrap();
            Ok(())
        }
        fn egm(&mut self) -> Option<&mut dyn EgmHost> {
            Some(self)
        }
    }

    impl EgmParts for TestHost {
        fn egm_parts(&mut self) -> Option<(&mut EgmController, &mut ControllerHandle)> {
            Some((&mut self.egm, &mut self.handle))
        }
        fn last_move(&self) -> LastMove {
            LastMove::StopPoint
        }
        fn egm_instr(&mut self, name: &'static str, span: Span) -> Option<InstrRef> {
            self.next_id += 1;
            Some(InstrRef {
                id: self.next_id,
                name,
                source: Some(span),
            })
        }
        fn egm_event(&mut self, text: String) {
            self.lines.lock().unwrap().push(format!("event: {text}"));
        }
    }

    use crate::interp::host::EgmHost;

    /// Runs `main` of `text`; the TP lines and events, the final joints, the result.
    fn run(text: &str, devices: &[&str]) -> (Vec<String>, JointsDeg, Result<(), String>) {
        let (handle, egm) = controller(devices);
        let signals = Arc::clone(egm.signals());
        let lines = Arc::new(std::sync::Mutex::new(Vec::new()));
        let joints = Arc::new(std::sync::Mutex::new([0.0; 6]));
        let mut host = TestHost {
            handle,
            egm,
            signals: Arc::clone(&signals),
            now: RobotTime::ZERO,
            lines: Arc::clone(&lines),
            joints: Arc::clone(&joints),
            next_id: 100,
        };
        host.now = host.handle.now();
        let mut sources = SourceMap::new();
        let mut diags = Diagnostics::new();
        let id = sources.add("t.mod", text);
        let file = crate::parse::parse_file(id, text, &mut diags);
        let registry = Registry::standard();
        let prog = crate::program::check(&[file], &mut sources, &signals, &registry, &mut diags);
        assert!(!diags.has_errors(), "{diags:?}");
        let mut it = Interp::new(Arc::new(prog.unwrap()), &registry, Box::new(host));
        let r = it.run("main").map(drop).map_err(|e| e.message.clone());
        let stopped = it.host_mut().egm().unwrap().egm_program_stopped();
        assert!(stopped.is_ok() || r.is_err(), "{stopped:?}");
        let t = it.host().now().after_secs(0.004);
        it.host_mut().wait_until(t).unwrap();
        let lines = lines.lock().unwrap().clone();
        let q = *joints.lock().unwrap();
        (lines, q, r)
    }

    fn close(q: &JointsDeg, want: [f64; 6], tol: f64) -> bool {
        q.iter().zip(want).all(|(a, b)| (a - b).abs() <= tol)
    }

    #[test]
    fn joint_guidance_prints_the_states_and_arrives() {
        let prog = r#"
MODULE T
VAR egmident egmID1;
VAR egmstate st;
PROC main()
  EGMReset egmID1;
  EGMGetId egmID1;
  st := EGMGetState(egmID1);
  TPWrite "after GetId: "\Num:=st;
  EGMSetupUC ROB_1, egmID1, "default", "sensor:" \Joint \CommTimeout:=2;
  TPWrite "after setup: "\Num:=EGMGetState(egmID1);
  EGMActJoint egmID1 \J1:=[-0.1,0.1] \MaxSpeedDeviation:=100;
  EGMRunJoint egmID1, EGM_STOP_HOLD \J1 \J2 \J3 \J4 \J5 \J6 \CondTime:=0.5 \RampInTime:=0.05;
  TPWrite "after run: "\Num:=EGMGetState(egmID1);
  EGMReset egmID1;
  TPWrite "after reset: "\Num:=EGMGetState(egmID1);
ENDPROC
ENDMODULE
"#;
        let (lines, q, r) = run(prog, &["sensor=builtin:joint:10,-5,20,0,40,30"]);
        r.unwrap();
        let tp: Vec<&str> = lines
            .iter()
            .filter(|l| !l.starts_with("event:"))
            .map(String::as_str)
            .collect();
        assert_eq!(
            tp,
            [
                "after GetId: 1",
                "after setup: 2",
                "after run: 2",
                "after reset: 1"
            ]
        );
        assert!(close(&q, [10.0, -5.0, 20.0, 0.0, 40.0, 30.0], 0.2), "{q:?}");
    }

    #[test]
    fn comm_timeout_is_err_udpuc_comm_catchable_with_trynext() {
        // A sensor that never answers.
        let quiet = std::net::UdpSocket::bind("127.0.0.1:0").unwrap();
        let dev = format!("sensor={}", quiet.local_addr().unwrap());
        let prog = r#"
MODULE T
VAR egmident id;
VAR num corr;
PROC main()
  EGMGetId id;
  EGMSetupUC ROB_1, id, "default", "sensor" \Joint \CommTimeout:=0.2;
  EGMActJoint id;
  EGMRunJoint id, EGM_STOP_HOLD \J1;
  TPWrite "not reached";
  TPWrite "after: "\Num:=EGMGetState(id \CorrectionState:=corr);
  TPWrite "corr: "\Num:=corr;
ERROR
  IF ERRNO = ERR_UDPUC_COMM THEN
    TPWrite "comm error";
    TRYNEXT;
  ENDIF
ENDPROC
ENDMODULE
"#;
        let (lines, _, r) = run(prog, &[&dev]);
        r.unwrap();
        let tp: Vec<&str> = lines
            .iter()
            .filter(|l| !l.starts_with("event:"))
            .map(String::as_str)
            .collect();
        assert_eq!(tp, ["comm error", "not reached", "after: 2", "corr: 1"]);
    }

    #[test]
    fn mode_mismatch_is_fatal_41826() {
        let prog = r#"
MODULE T
VAR egmident id;
PROC main()
  EGMGetId id;
  EGMSetupUC ROB_1, id, "default", "sensor" \Pose;
  EGMActPose id, [[0,0,0],[1,0,0,0]], EGM_FRAME_WORLD, [[0,0,0],[1,0,0,0]], EGM_FRAME_WORLD;
  EGMRunJoint id, EGM_STOP_HOLD \J1;
ERROR
  TPWrite "handled";
ENDPROC
ENDMODULE
"#;
        let (lines, _, r) = run(prog, &[]);
        let e = r.unwrap_err();
        assert!(e.contains("41826 EGM mode mismatch"), "{e}");
        assert!(!lines.iter().any(|l| l == "handled"));
    }

    #[test]
    fn identities_are_named_by_variable() {
        let prog = r#"
MODULE T
VAR egmident a;
VAR egmident b;
VAR egmident c;
VAR egmident d;
VAR egmident e;
PROC get(VAR egmident x)
  EGMGetId x;
ENDPROC
PROC main()
  get a; get a; EGMGetId a;
  get b; get c; get d;
  EGMGetId e;
ENDPROC
ENDMODULE
"#;
        let (_, _, r) = run(prog, &[]);
        let e = r.unwrap_err();
        assert!(
            e.contains("at most 4 EGM identities") && e.contains("a, b, c, d"),
            "{e}"
        );
    }
}

/// Ticks virtual time by `cycles` motion cycles.
fn tick(h: &mut ControllerHandle, cycles: u32) {
    let t = h.now().saturating_add(Duration::from_millis(4) * cycles);
    h.wait_until(Condition::TimeReached(t)).unwrap();
}

#[test]
fn a_paused_run_stands_and_resumes_to_convergence_and_the_ratio_slows_it() {
    let target = [10.0, -5.0, 20.0, 0.0, 40.0, 30.0];
    let (mut h, mut egm) = controller(&["sensor=builtin:joint:10,-5,20,0,40,30"]);
    egm.get_id(&mut h, "e").unwrap();
    egm.setup_uc(&mut h, "e", &uc(EgmMode::Joint, "sensor"))
        .unwrap();
    let mut act = ActJoint::default();
    act.common.max_speed_deviation = Some(10.0);
    egm.act_joint(&mut h, "e", &act).unwrap();
    let args = RunArgs {
        cond_time: Some(0.2),
        ..RunArgs::new(StopMode::Hold)
    };
    let axes = [true, true, true, true, true, true, false];
    egm.run_joint(&mut h, "e", &args, axes, LastMove::StopPoint, None)
        .unwrap();
    // Half speed: J6 (the farthest, 30°, at MaxSpeedDeviation) moves at 5 °/s.
    egm.set_speed_ratio(50);
    tick(&mut h, 250);
    let a = h.state().setpoint.joints[5];
    tick(&mut h, 25);
    let speed = (h.state().setpoint.joints[5] - a) / 0.1;
    assert!((speed - 5.0).abs() < 0.2, "{speed} °/s at 50 %");
    egm.set_speed_ratio(100);
    tick(&mut h, 100);
    // Paused: the speed ramps out over the default profile's 0.5 s, then the robot stands
    // and the run does not end.
    assert!(egm.pause_run());
    tick(&mut h, 150);
    let held = h.state().setpoint.joints;
    tick(&mut h, 500);
    assert_eq!(h.state().setpoint.joints, held, "stands while paused");
    assert!(held[5] < 29.0, "short of the target: {held:?}");
    assert!(!egm.run_done("e", false).unwrap());
    egm.resume_run();
    wait_run(&mut h, &mut egm, "e").unwrap();
    let q = h.state().setpoint.joints;
    for (a, b) in q.iter().zip(target) {
        assert!((a - b).abs() < 0.5, "{q:?}");
    }
    assert!(!egm.pause_run(), "nothing to pause after the run");
}
