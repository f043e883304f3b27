//! The controller-side EGM machinery end to end in virtual time stepped by hand: registry → plan → driver ticks, with the built-in sensor in process, signal sources, and real loopback sockets carried by the controller's `DeviceSocket` (a silent peer, the built-in sensor on a thread in lockstep).
//!
//! Every test ends by itself: loops are bounded in ticks and sockets have read time-outs.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use std::net::{SocketAddr, UdpSocket};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use prost::Message;
use rapidvc::controller::egm_controller::DeviceSocket;
use rapidvc::egm::message_log::{EgmLogWriter, LOG_COLUMNS, LogRow};
use rapidvc::egm::proto::EgmRobot;
use rapidvc::egm::proto::egm_mci_state::MciStateType;
use rapidvc::egm::registry::{ActJoint, ActPose, RunArgs, SetupSignals, SetupUc, StopTarget};
use rapidvc::egm::sensor::{BuiltinSensor, SensorConfig, SensorStats};
use rapidvc::egm::servo::{MinMax, ServoPhase, StopMode};
use rapidvc::egm::{
    CorrState, DatagramMachine, DriverContext, DriverOptions, EgmDriver, EgmEnd, EgmError,
    EgmEvent, EgmMode, EgmRegistry, EgmSource, EgmState, EgmStream, EgmTick, Joints,
    RapidExecState,
};
use rapidvc::robot::units::pose_from_pos_quat;
use rapidvc::robot::{ConfData, LoadData, Robot, ToolData};
use rapidvc::signals::{SignalKind, SignalTable};
use rapidvc::time::RobotTime;

const TICK: Duration = Duration::from_millis(4);
const START: Joints = [0.0, 0.0, 0.0, 0.0, 30.0, 0.0];
const ALL_J: [bool; 7] = [true, true, true, true, true, true, false];

/// Robot time `d` after the start.
fn rt(d: Duration) -> RobotTime {
    RobotTime::from_duration(d)
}

fn registry(overrides: &[String]) -> EgmRegistry {
    rapidvc_testkit::egm_pair::registry(overrides, false)
}

fn ctx(signals: Arc<SignalTable>) -> DriverContext {
    DriverContext {
        robot: Robot::default(),
        signals,
        options: DriverOptions::default(),
        drops: Default::default(),
    }
}

/// A driver for `plan` started at time zero from `START`, with the plan's own source.
fn start_at_zero(ctx: &DriverContext, plan: &rapidvc::egm::registry::RunPlan) -> EgmDriver {
    let source = EgmSource::new(&plan.source);
    EgmDriver::start(RobotTime::ZERO, ctx, plan, source, &START).unwrap()
}

fn uc(device: &str, mode: EgmMode) -> SetupUc {
    SetupUc {
        mecunit: "ROB_1".into(),
        profile: "default".into(),
        device: device.into(),
        mode,
        tracker: None,
        comm_timeout: None,
    }
}

fn act_joint(max_speed: f64) -> ActJoint {
    let mut a = ActJoint::default();
    a.common.max_speed_deviation = Some(max_speed);
    a
}

/// What a hand-stepped run produced.
struct Finished {
    result: Result<EgmEnd, EgmError>,
    ticks: Vec<EgmTick>,
    events: Vec<EgmEvent>,
    rows: Vec<LogRow>,
    end: Duration,
}

/// Ticks `driver` in virtual time from `now` until it finishes (at most `max` ticks),
/// commanding what it asks; in lockstep it waits for each reply. Asserts the command never
/// leaves the robot's axis ranges.
fn drive(driver: &mut EgmDriver, now: Duration, max: usize, lockstep: bool) -> Finished {
    drive_over(&mut DeviceSocket::default(), driver, now, max, lockstep)
}

/// [`drive`] with the device's socket carried as the controller's cycle does: drained into
/// the driver before each tick, what it produced sent after it, and in lockstep the wait for
/// the reply.
fn drive_over(
    socket: &mut DeviceSocket,
    driver: &mut EgmDriver,
    mut now: Duration,
    max: usize,
    lockstep: bool,
) -> Finished {
    let robot = Robot::default();
    let mut q = *driver.start_joints();
    let mut ticks = Vec::new();
    let mut events = Vec::new();
    let mut rows = Vec::new();
    for _ in 0..max {
        socket.receive(rt(now), driver);
        let t = driver.tick(rt(now), &q);
        socket.send(rt(now), driver);
        robot.check_limits(&t.joints_cmd).unwrap();
        q = t.joints_cmd;
        while let Some(e) = driver.poll_event() {
            events.push(e);
        }
        while let Some(r) = driver.pop_log() {
            rows.push(r);
        }
        if lockstep && driver.awaiting_reply() {
            socket.wait_reply(rt(now), Duration::from_secs(2), driver);
            assert!(!driver.awaiting_reply());
        }
        let done = t.finished.clone();
        ticks.push(t);
        if let Some(result) = done {
            return Finished {
                result,
                ticks,
                events,
                rows,
                end: now,
            };
        }
        now += TICK;
    }
    panic!(
        "the run did not finish within {max} ticks; phase {:?}",
        driver.phase()
    );
}

fn close(a: &Joints, b: &Joints, tol: f64) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

mod builtin {
    use super::*;

    const TARGET: Joints = [10.0, -5.0, 20.0, 0.0, 40.0, 30.0];

    #[test]
    fn joint_mode_converges_within_the_windows_and_ends_after_cond_time() {
        let mut reg = registry(&["EGMsensor=builtin:joint:10,-5,20,0,40,30".into()]);
        let id = reg.get_id("egmID1").unwrap();
        reg.setup_uc(id, &uc("EGMsensor:", EgmMode::Joint)).unwrap();
        reg.act_joint(id, &act_joint(100.0)).unwrap();
        let plan = reg
            .run_joint(id, &RunArgs::new(StopMode::Hold), ALL_J)
            .unwrap();
        assert_eq!(reg.state(id), (EgmState::Running, CorrState::Running));
        let ctx = ctx(Arc::new(SignalTable::with_builtins()));
        let source = EgmSource::new(&plan.source);
        let t0 = Duration::from_secs(3);
        let mut driver = EgmDriver::start(rt(t0), &ctx, &plan, source, &START).unwrap();
        let run = drive(&mut driver, t0, 5000, false);
        assert_eq!(run.result, Ok(EgmEnd::Converged));
        reg.run_finished(id, true);
        assert_eq!(reg.state(id), (EgmState::Connected, CorrState::Stopped));
        let last = run.ticks.last().unwrap();
        assert!(
            close(&last.joints_cmd, &TARGET, 0.5),
            "{:?}",
            last.joints_cmd
        );
        assert!(close(&last.feedback, &TARGET, 0.5));
        // Convergence held continuously for CondTime (1 s = 250 ticks) before the stop.
        let stop = run
            .ticks
            .iter()
            .position(|t| t.phase != ServoPhase::Running)
            .unwrap();
        let first = run.ticks[..=stop]
            .iter()
            .rposition(|t| !t.converged)
            .map_or(0, |i| i + 1);
        assert_eq!(stop - first + 1, 250, "CondTime 1 s at 4 ms");
        assert!(
            run.ticks[..first]
                .iter()
                .all(|t| t.phase == ServoPhase::Running)
        );
        // Same bytes path as UDP: one EgmRobot and one reply per tick.
        let st = driver.session_stats().unwrap();
        let sensor = driver.sensor_stats().unwrap();
        assert_eq!(st.sent as usize, run.ticks.len());
        assert_eq!(sensor.replied, st.sent);
        assert_eq!(st.accepted, st.sent);
        assert_eq!(
            (sensor.sessions, sensor.seqno_gaps, sensor.incomplete),
            (1, 0, 0)
        );
        // The robot moved at up to 100 deg/s only: no MaxSpeedDeviation event at 100? It
        // limits at the start (the step is 20°, k·e = 100 deg/s) — either way no clamp.
        assert!(
            run.events.iter().all(|e| e.number != 90111),
            "{:?}",
            run.events
        );
        assert!(run.end > t0 + Duration::from_secs(1));
        // Finished is reported once; later ticks stand still.
        let after = driver.tick(rt(run.end + TICK), &last.joints_cmd);
        assert!(after.finished.is_none() && !after.sent);
        assert_eq!(after.joints_cmd, last.joints_cmd);
        assert_eq!(driver.outcome(), Some(&Ok(EgmEnd::Converged)));
    }

    #[test]
    fn ramp_down_returns_to_the_start() {
        let mut reg = registry(&["s=builtin:joint:10,-5,20,0,40,30".into()]);
        let id = reg.get_id("egmID1").unwrap();
        reg.setup_uc(id, &uc("s", EgmMode::Joint)).unwrap();
        reg.act_joint(id, &act_joint(200.0)).unwrap();
        let args = RunArgs {
            cond_time: Some(0.2),
            ramp_out_time: Some(0.4),
            ..RunArgs::new(StopMode::RampDown)
        };
        let plan = reg.run_joint(id, &args, ALL_J).unwrap();
        let ctx = ctx(Arc::new(SignalTable::with_builtins()));
        let mut driver = start_at_zero(&ctx, &plan);
        let run = drive(&mut driver, Duration::ZERO, 5000, false);
        assert_eq!(run.result, Ok(EgmEnd::Converged));
        // It reached the target, then came back.
        assert!(run.ticks.iter().any(|t| close(&t.joints_cmd, &TARGET, 0.5)));
        let ramp: Vec<&EgmTick> = run
            .ticks
            .iter()
            .filter(|t| t.phase == ServoPhase::RampingDown)
            .collect();
        assert!(!ramp.is_empty());
        // 0.4 s at 4 ms, give or take the last step.
        assert!((99..=101).contains(&ramp.len()), "{}", ramp.len());
        let last = run.ticks.last().unwrap();
        assert!(
            close(&last.joints_cmd, &START, 1e-9),
            "{:?}",
            last.joints_cmd
        );
    }

    #[test]
    fn egm_stop_and_program_stop() {
        let mut reg = registry(&["s=builtin:sine:axis=1,amplitude=5,frequency=0.5".into()]);
        let id = reg.get_id("egmID1").unwrap();
        reg.setup_uc(id, &uc("s", EgmMode::Joint)).unwrap();
        reg.act_joint(id, &act_joint(50.0)).unwrap();
        let args = RunArgs {
            cond_time: Some(9e9),
            ..RunArgs::new(StopMode::Hold)
        };
        let ctx = ctx(Arc::new(SignalTable::with_builtins()));
        // EGMStop HOLD mid-run.
        let plan = reg.run_joint(id, &args, ALL_J).unwrap();
        let mut driver = start_at_zero(&ctx, &plan);
        let mut q = START;
        for k in 0..125u32 {
            let t = driver.tick(rt(TICK * k), &q);
            assert!(t.finished.is_none());
            q = t.joints_cmd;
        }
        assert!((q[0] - START[0]).abs() > 0.5, "the sine moved J1: {q:?}");
        assert_eq!(reg.stop(id).unwrap(), StopTarget::Run);
        driver.stop(StopMode::Hold, None);
        let run = drive(&mut driver, TICK * 125, 2000, false);
        assert_eq!(run.result, Ok(EgmEnd::Stopped));
        reg.run_finished(id, true);
        // Program stop: ramps out over the profile's 0.5 s.
        let plan = reg.run_joint(id, &args, ALL_J).unwrap();
        let mut driver = start_at_zero(&ctx, &plan);
        let (mut before, mut at) = (START, START);
        for k in 0..100u32 {
            before = at;
            at = driver.tick(rt(TICK * k), &at).joints_cmd;
        }
        let reference = driver.tracking().0.unwrap();
        driver.halt();
        let run = drive(&mut driver, TICK * 100, 2000, false);
        assert_eq!(run.result, Ok(EgmEnd::Halted));
        let halting = run
            .ticks
            .iter()
            .filter(|t| t.phase == ServoPhase::Halting)
            .count();
        // At most the profile's 0.5 s; shorter here, where the moving sine reference is
        // closer than a 0.5 s ramp would carry the robot.
        assert!((2..=126).contains(&halting), "{halting}");
        // J1 slows down from the speed it had, every step, and rests short of the reference.
        let dt = TICK.as_secs_f64();
        let mut speed = (at[0] - before[0]) / dt;
        let mut q = at[0];
        assert!(speed.abs() > 1.0, "J1 was moving: {speed}");
        for t in &run.ticks {
            let v = (t.joints_cmd[0] - q) / dt;
            assert!(
                v * speed >= 0.0 && v.abs() <= speed.abs() + 1e-9,
                "{v} after {speed}"
            );
            (speed, q) = (v, t.joints_cmd[0]);
        }
        assert_eq!(speed, 0.0);
        let ahead = (reference[0] - at[0]).signum();
        assert!(
            (reference[0] - q) * ahead >= 0.0,
            "{q} passed {}",
            reference[0]
        );
        assert!(
            run.ticks
                .iter()
                .all(|t| t.mci_state == rapidvc::egm::MciState::Stopped)
        );
    }

    #[test]
    fn no_axis_selected_is_no_movement() {
        let mut reg = registry(&[]);
        let id = reg.get_id("egmID1").unwrap();
        reg.setup_uc(id, &uc("any", EgmMode::Joint)).unwrap();
        reg.act_joint(id, &ActJoint::default()).unwrap();
        let plan = reg
            .run_joint(id, &RunArgs::new(StopMode::Hold), [false; 7])
            .unwrap();
        let ctx = ctx(Arc::new(SignalTable::with_builtins()));
        let mut driver = start_at_zero(&ctx, &plan);
        let t = driver.tick(rt(Duration::ZERO), &START);
        assert_eq!(t.finished, Some(Ok(EgmEnd::NoMovement)));
        assert_eq!(t.joints_cmd, START);
        assert_eq!(driver.session_stats().unwrap().sent, 0);
    }

    #[test]
    fn unreachable_pose_reference_ends_the_run_with_50050() {
        let mut reg = registry(&["s=builtin:pose:5000,0,0,0,0,0".into()]);
        let id = reg.get_id("egmID1").unwrap();
        reg.setup_uc(id, &uc("s", EgmMode::Pose)).unwrap();
        reg.act_pose(id, &ActPose::world()).unwrap();
        let plan = reg
            .run_pose(id, &RunArgs::new(StopMode::Hold), [true; 6], None)
            .unwrap();
        let ctx = ctx(Arc::new(SignalTable::with_builtins()));
        let mut driver = start_at_zero(&ctx, &plan);
        let run = drive(&mut driver, Duration::ZERO, 1000, false);
        let err = run.result.unwrap_err();
        assert_eq!(err.event().number, 50050, "{err}");
        assert!(err.is_fatal());
        assert!(
            run.ticks
                .iter()
                .any(|t| t.mci_state == rapidvc::egm::MciState::Error)
        );
        reg.run_finished(id, false);
        assert_eq!(reg.state(id), (EgmState::Connected, CorrState::Error));
    }

    #[test]
    fn hold_pose_keeps_the_robot_still_with_different_sensor_and_correction_frames() {
        // The UdpUc example's frames: correction frame WORLD with an offset, sensor frame
        // the tool's frame (EGM_FRAME_TOOL). The built-in hold-pose must hold in the sensor
        // frame, not send the correction-frame feedback back.
        let mut reg = registry(&[]);
        let id = reg.get_id("egmID1").unwrap();
        reg.setup_uc(id, &uc("EGMsensor:", EgmMode::Pose)).unwrap();
        let tool = t_fronius_cmt();
        let mut act = ActPose::world();
        act.common.tool = Some(tool);
        act.corr_frame = pose_from_pos_quat([1200.0, 400.0, 900.0], [1.0, 0.0, 0.0, 0.0]);
        act.sensor_frame = tool.tframe;
        act.sens_type = rapidvc::egm::geometry::EgmFrameType::Tool;
        reg.act_pose(id, &act).unwrap();
        let args = RunArgs {
            cond_time: Some(0.5),
            ..RunArgs::new(StopMode::Hold)
        };
        let plan = reg
            .run_pose(id, &args, [true, true, true, false, false, false], None)
            .unwrap();
        let ctx = ctx(Arc::new(SignalTable::with_builtins()));
        let jpos10 = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];
        let mut driver = EgmDriver::start(
            RobotTime::ZERO,
            &ctx,
            &plan,
            EgmSource::new(&plan.source),
            &jpos10,
        )
        .unwrap();
        let run = drive(&mut driver, Duration::ZERO, 1000, false);
        assert_eq!(run.result, Ok(EgmEnd::Converged));
        for t in &run.ticks {
            assert!(close(&t.joints_cmd, &jpos10, 1e-6), "{:?}", t.joints_cmd);
        }
    }
}

/// The manual's tool with the payload of its path-correction example.
fn t_fronius_cmt() -> ToolData {
    ToolData {
        load: LoadData {
            mass: 2.6,
            cog: [-111.1, 24.6, 386.6],
            aom: [1.0, 0.0, 0.0, 0.0],
            ix: 0.0,
            iy: 0.0,
            iz: 0.072,
        },
        ..rapidvc_testkit::robot::t_fronius_cmt()
    }
}

mod signals {
    use super::*;

    /// docs/robot.md, "Acceptance facts": target (150, 1320, 900) with p20's orientation and tFroniusCMT.
    const EXPECTED: Joints = [83.50, 0.10, 16.82, 0.17, 21.88, -0.22];

    /// `MoveJ p30, v1000, fine, tool0`.
    fn p30_joints(r: &Robot) -> Joints {
        let p30 = pose_from_pos_quat(
            [114.50, 1005.42, 1410.38],
            [0.322151, -0.601023, 0.672381, 0.287914],
        );
        r.ik_conf(&p30, &ConfData::new(0, 0, -1, 0)).unwrap()
    }

    /// The manual's pose-mode signal setup and activation; `max_speed` overrides the
    /// default MaxSpeedDeviation when given.
    fn manual_run(max_speed: Option<f64>) -> (Finished, Joints) {
        let table = Arc::new(SignalTable::with_builtins());
        let sig = |n: &str| Some(table.lookup(n).unwrap());
        let mut reg = registry(&[]);
        let id1 = reg.get_id("egmID1").unwrap();
        let id2 = reg.get_id("egmID2").unwrap();
        // EGMSetupAO ROB_1,egmID1,"default" \Pose \aoR1x:=ao_MoveX \aoR2y:=ao_MoveY
        //   \aoR3z:=ao_MoveZ \aoR5ry:=ao_RotY \aoR6rz:=ao_RotZ;
        let setup = SetupSignals {
            mecunit: "ROB_1".into(),
            profile: "default".into(),
            kind: SignalKind::Ao,
            mode: EgmMode::Pose,
            tracker: None,
            mapping: [
                sig("ao_MoveX"),
                sig("ao_MoveY"),
                sig("ao_MoveZ"),
                None,
                sig("ao_RotY"),
                sig("ao_RotZ"),
            ],
            ext: [None; 6],
        };
        reg.setup_signals(id1, &setup, &table).unwrap();
        let joint_setup = SetupSignals {
            mode: EgmMode::Joint,
            mapping: [
                sig("ao_MoveX"),
                sig("ao_MoveY"),
                sig("ao_MoveZ"),
                sig("ao_RotX"),
                sig("ao_RotY"),
                sig("ao_RotZ"),
            ],
            ..setup.clone()
        };
        reg.setup_signals(id2, &joint_setup, &table).unwrap();
        let robot = Robot::default();
        let start = p30_joints(&robot);
        // SetAO ao_MoveX, 150; SetAO ao_MoveY, 1320; SetAO ao_MoveZ, 900;
        for (n, v) in [
            ("ao_MoveX", 150.0),
            ("ao_MoveY", 1320.0),
            ("ao_MoveZ", 900.0),
        ] {
            table.set(table.lookup(n).unwrap(), v).unwrap();
        }
        // EGMActPose egmID1 \Tool:=tFroniusCMT \WObj:=wobj0 \TLoad:=load1, posecor0,
        //   EGM_FRAME_WORLD, posesen0, EGM_FRAME_WORLD \x:=egm_minmax_lin1 … \rz:=…rot1
        //   \LpFilter:=20 \SampleRate:=16 \MaxPosDeviation:=1000;
        let mut act = ActPose::world();
        act.common.tool = Some(t_fronius_cmt());
        act.common.tload = Some(LoadData {
            mass: 5.0,
            cog: [0.0, 1.0, 0.0],
            ..LoadData::LOAD0
        });
        act.common.lp_filter = Some(20.0);
        act.common.sample_rate = Some(16.0);
        act.common.max_pos_deviation = Some(1000.0);
        act.common.max_speed_deviation = max_speed;
        let lin = Some(MinMax {
            min: -1.0,
            max: 1.0,
        });
        let rot = Some(MinMax {
            min: -2.0,
            max: 2.0,
        });
        act.windows = [lin, lin, lin, rot, rot, rot];
        reg.act_pose(id1, &act).unwrap();
        // EGMRunPose egmID1, EGM_STOP_HOLD\x\y\z\RampInTime:=0.05\PosCorrGain:=1;
        let args = RunArgs {
            ramp_in_time: Some(0.05),
            pos_corr_gain: Some(1.0),
            ..RunArgs::new(StopMode::Hold)
        };
        let plan = reg
            .run_pose(id1, &args, [true, true, true, false, false, false], None)
            .unwrap();
        assert_eq!(plan.sample_period, Duration::from_millis(16));
        let ctx = ctx(Arc::clone(&table));
        let source = EgmSource::new(&plan.source);
        let mut driver = EgmDriver::start(RobotTime::ZERO, &ctx, &plan, source, &start).unwrap();
        let run = drive(&mut driver, Duration::ZERO, 20_000, false);
        // Samples every 16 ms: one logged row per sample.
        let rows = &run.rows;
        assert_eq!(
            rows.len(),
            run.ticks.len().div_ceil(4),
            "{} rows",
            rows.len()
        );
        assert!(rows.iter().all(|r| r.reference.unwrap()[2] == 900.0));
        assert!(
            rows.windows(2)
                .all(|w| w[1].send_time - w[0].send_time == 4 * TICK)
        );
        reg.run_finished(id1, run.result.is_ok());
        (run, start)
    }

    #[test]
    fn the_manual_example_reaches_its_joints_at_the_default_1_deg_per_s() {
        let (run, start) = manual_run(None);
        assert_eq!(run.result, Ok(EgmEnd::Converged));
        let last = run.ticks.last().unwrap();
        assert!(
            close(&last.joints_cmd, &EXPECTED, 0.01),
            "{:?}",
            last.joints_cmd
        );
        // The default MaxSpeedDeviation limited the run, and the event said so once.
        let limited: Vec<&EgmEvent> = run.events.iter().filter(|e| e.number == 90110).collect();
        assert_eq!(limited.len(), 1, "{:?}", run.events);
        assert!(
            limited[0].detail.contains("MaxSpeedDeviation is 1 deg/s"),
            "{}",
            limited[0]
        );
        // The largest joint travel at 1 deg/s bounds the duration from below.
        let travel = start
            .iter()
            .zip(&EXPECTED)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let secs = run.end.as_secs_f64();
        assert!(secs >= travel / 1.0, "{secs} s for {travel} deg");
        // No joint ever moved faster than 1 deg/s (plus float noise).
        for w in run.ticks.windows(2) {
            for i in 0..6 {
                let v = (w[1].joints_cmd[i] - w[0].joints_cmd[i]).abs() / TICK.as_secs_f64();
                assert!(v <= 1.0 + 1e-6, "J{} at {v} deg/s", i + 1);
            }
        }
        assert!(run.ticks.iter().filter(|t| t.speed_limited).count() > run.ticks.len() / 2);
    }

    #[test]
    fn the_manual_example_with_max_speed_deviation_raised() {
        let (run, _) = manual_run(Some(100.0));
        assert_eq!(run.result, Ok(EgmEnd::Converged));
        let last = run.ticks.last().unwrap();
        assert!(
            close(&last.joints_cmd, &EXPECTED, 0.01),
            "{:?}",
            last.joints_cmd
        );
        assert!(run.end < Duration::from_secs(4), "{:?}", run.end);
    }
}

mod udp {
    use super::*;

    /// The built-in sensor on its own thread and socket, until stopped or 30 s pass.
    struct SensorThread {
        addr: SocketAddr,
        stop: Arc<AtomicBool>,
        handle: JoinHandle<(SensorStats, Vec<EgmRobot>)>,
    }

    impl SensorThread {
        fn spawn(pattern: &str) -> Self {
            let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
            socket
                .set_read_timeout(Some(Duration::from_millis(20)))
                .unwrap();
            let addr = socket.local_addr().unwrap();
            let mut sensor =
                BuiltinSensor::new(SensorConfig::new(pattern.parse().unwrap())).unwrap();
            let stop = Arc::new(AtomicBool::new(false));
            let stop2 = stop.clone();
            let handle = std::thread::spawn(move || {
                let origin = Instant::now();
                let mut buf = vec![0u8; 2048];
                let mut seen = Vec::new();
                // Until stopped and nothing more arrives for one read time-out (so the
                // last message is always seen), or 30 s.
                while origin.elapsed() < Duration::from_secs(30) {
                    let Ok((len, src)) = socket.recv_from(&mut buf) else {
                        if stop2.load(Ordering::Relaxed) {
                            break;
                        }
                        continue;
                    };
                    seen.push(EgmRobot::decode(&buf[..len]).unwrap());
                    if let Ok(reply) = sensor.handle_datagram(origin.elapsed(), &buf[..len]) {
                        let _ = socket.send_to(&reply, src);
                    }
                }
                (sensor.stats().clone(), seen)
            });
            SensorThread { addr, stop, handle }
        }

        fn finish(self) -> (SensorStats, Vec<EgmRobot>) {
            self.stop.store(true, Ordering::Relaxed);
            self.handle.join().unwrap()
        }
    }

    #[test]
    fn lockstep_joint_run_against_the_builtin_sensor_over_loopback() {
        let sensor = SensorThread::spawn("joint:10,-5,20,0,40,30");
        let mut reg = registry(&[format!("EGMsensor={}", sensor.addr)]);
        let id = reg.get_id("egmID1").unwrap();
        reg.setup_uc(id, &uc("EGMsensor", EgmMode::Joint)).unwrap();
        reg.act_joint(id, &act_joint(100.0)).unwrap();
        let args = RunArgs {
            cond_time: Some(0.5),
            ..RunArgs::new(StopMode::Hold)
        };
        let plan = reg.run_joint(id, &args, ALL_J).unwrap();
        assert!(plan.source.is_external());
        let ctx = ctx(Arc::new(SignalTable::with_builtins()));
        let source = EgmSource::new(&plan.source);
        assert!(source.is_external());
        let mut socket = DeviceSocket::open(&plan.source).unwrap();
        let mut driver = EgmDriver::start(RobotTime::ZERO, &ctx, &plan, source, &START).unwrap();
        // Lockstep: the first tick sends and then waits for the reply.
        let t = driver.tick(rt(Duration::ZERO), &START);
        socket.send(rt(Duration::ZERO), &mut driver);
        assert!(t.sent && driver.awaiting_reply());
        assert_eq!(
            socket.wait_reply(rt(Duration::ZERO), Duration::from_secs(2), &mut driver),
            Some(true)
        );
        let run = drive_over(&mut socket, &mut driver, TICK, 3000, true);
        let (stats, seen) = sensor.finish();
        assert_eq!(run.result, Ok(EgmEnd::Converged));
        let last = run.ticks.last().unwrap();
        assert!(close(
            &last.joints_cmd,
            &[10.0, -5.0, 20.0, 0.0, 40.0, 30.0],
            0.5
        ));
        let st = driver.session_stats().unwrap().clone();
        // One reply per message, every one used (lockstep never loses one) except the
        // reply to the last message, which arrives after the run ended.
        assert_eq!(st.sent, stats.received);
        assert_eq!(st.sent as usize, run.ticks.len() + 1);
        assert_eq!(st.accepted + 1, st.sent);
        assert_eq!(st.dropped(), 0);
        assert_eq!(
            (stats.sessions, stats.seqno_gaps, stats.incomplete),
            (1, 0, 0)
        );
        // seqno from 0, tm in virtual milliseconds, MCI running, DATA messages.
        assert_eq!(seen[0].header.unwrap().seqno, Some(0));
        for (k, m) in seen.iter().enumerate() {
            let h = m.header.unwrap();
            assert_eq!(h.seqno, Some(k as u32));
            assert_eq!(h.tm, Some(4 * k as u32));
            assert_eq!(m.mci_state.unwrap().state, MciStateType::MciRunning as i32);
        }
        assert_eq!(seen.last().unwrap().mci_convergence_met, Some(true));
        // The log has one row per message, each with its reply but the last. (The first
        // tick's row went into the ring before `drive` drained it.)
        let rows = &run.rows;
        assert_eq!(rows.len() as u64, st.sent);
        let (last_row, replied) = rows.split_last().unwrap();
        assert!(
            replied
                .iter()
                .all(|r| r.recv_time.is_some() && r.reference.is_some())
        );
        assert!(last_row.recv_time.is_none());
        let mut w = EgmLogWriter::new(Vec::new()).unwrap();
        for r in rows {
            w.write_row(driver.name(), r).unwrap();
        }
        let text = String::from_utf8(w.into_inner().unwrap()).unwrap();
        assert_eq!(text.lines().count(), rows.len() + 1);
        assert_eq!(text.lines().next().unwrap(), LOG_COLUMNS.join(","));
        assert!(
            text.lines()
                .nth(1)
                .unwrap()
                .starts_with("egmID1,joint,0.000000,")
        );
    }

    #[test]
    fn a_silent_peer_ends_the_run_with_err_udpuc_comm_after_comm_timeout() {
        let silent = UdpSocket::bind("127.0.0.1:0").unwrap();
        silent
            .set_read_timeout(Some(Duration::from_secs(2)))
            .unwrap();
        let mut reg = registry(&[format!("UCdevice={}", silent.local_addr().unwrap())]);
        let id = reg.get_id("egmID1").unwrap();
        let mut setup = uc("UCdevice", EgmMode::Joint);
        setup.comm_timeout = Some(1.0);
        reg.setup_uc(id, &setup).unwrap();
        reg.act_joint(id, &ActJoint::default()).unwrap();
        let plan = reg
            .run_joint(id, &RunArgs::new(StopMode::Hold), ALL_J)
            .unwrap();
        let ctx = ctx(Arc::new(SignalTable::with_builtins()));
        let mut driver = start_at_zero(&ctx, &plan);
        let mut socket = DeviceSocket::open(&plan.source).unwrap();
        let run = drive_over(&mut socket, &mut driver, Duration::ZERO, 1000, false);
        let err = run.result.unwrap_err();
        assert!(matches!(err, EgmError::CommTimeout { .. }), "{err}");
        assert_eq!(err.rapid_error(), Some("ERR_UDPUC_COMM"));
        assert_eq!(err.event().number, 41822);
        assert_eq!(err.event().title, "No data from the UdpUc device");
        assert!(
            err.to_string()
                .contains("\"UCdevice\" within \\CommTimeout 1.000s"),
            "{err}"
        );
        // The time-out came after 1 s; then the EGM speed ramped out over 0.5 s.
        let halted_at = run
            .ticks
            .iter()
            .position(|t| t.phase == ServoPhase::Halting)
            .unwrap();
        assert_eq!(halted_at, 250, "1 s of 4 ms ticks");
        assert!(
            run.end >= Duration::from_millis(1490) && run.end <= Duration::from_millis(1510),
            "{:?}",
            run.end
        );
        // The 41822 event is the error's, not repeated among the events.
        assert!(
            run.events.iter().all(|e| e.number != 41822),
            "{:?}",
            run.events
        );
        // The peer got the messages (one per tick while running).
        let mut buf = [0u8; 2048];
        let (len, _) = silent.recv_from(&mut buf).unwrap();
        let first = EgmRobot::decode(&buf[..len]).unwrap();
        assert_eq!(first.header.unwrap().seqno, Some(0));
        reg.run_finished(id, false);
        assert_eq!(reg.state(id), (EgmState::Connected, CorrState::Error));
    }

    #[test]
    fn a_stream_sends_feedback_during_ordinary_motion() {
        let peer = UdpSocket::bind("127.0.0.1:0").unwrap();
        peer.set_read_timeout(Some(Duration::from_secs(2))).unwrap();
        let mut reg = registry(&[format!("EGMsensor={}", peer.local_addr().unwrap())]);
        let id = reg.get_id("egmID1").unwrap();
        reg.setup_uc(id, &uc("EGMsensor", EgmMode::Joint)).unwrap();
        let plan = reg.stream_start(id, Some(8.0)).unwrap();
        assert_eq!(reg.state(id), (EgmState::Running, CorrState::Stopped));
        let ctx = ctx(Arc::new(SignalTable::with_builtins()));
        let source = EgmSource::new(&plan.source);
        let mut socket = DeviceSocket::open(&plan.source).unwrap();
        let mut stream = EgmStream::start(RobotTime::ZERO, &ctx, &plan, source, &START).unwrap();
        // A MoveAbsJ-like ramp on J1, 20 ticks.
        let mut sent = 0;
        for k in 0..20u32 {
            let mut q = START;
            q[0] = f64::from(k) * 0.5;
            socket.receive(rt(TICK * k), &mut stream);
            let t = stream.tick(rt(TICK * k), &q, RapidExecState::Running);
            socket.send(rt(TICK * k), &mut stream);
            sent += usize::from(t.sent);
        }
        assert_eq!(sent, 10, "every 8 ms");
        assert_eq!(stream.sent(), 10);
        let mut buf = [0u8; 2048];
        let mut last = None;
        for _ in 0..10 {
            let (len, _) = peer.recv_from(&mut buf).unwrap();
            last = Some(EgmRobot::decode(&buf[..len]).unwrap());
        }
        let last = last.unwrap();
        assert_eq!(last.header.unwrap().seqno, Some(9));
        assert_eq!(
            last.mci_state.unwrap().state,
            MciStateType::MciStopped as i32
        );
        let planned = last.planned.unwrap().joints.unwrap().joints;
        let feedback = last.feed_back.unwrap().joints.unwrap().joints;
        assert_eq!(planned[0], 9.0, "sent at tick 18");
        assert_eq!(feedback[0], 7.5, "measured 12 ms (3 ticks) later");
        assert_eq!(stream.pop_log().unwrap().state, "streaming");
        // A run takes over the identity's device.
        reg.act_joint(id, &ActJoint::default()).unwrap_err();
        assert!(reg.stream_stop(id).unwrap());
        let source = stream.into_source();
        assert!(source.is_external());
    }
}

#[test]
fn drivers_and_streams_can_move_to_the_real_time_thread() {
    fn send<T: Send>() {}
    send::<EgmDriver>();
    send::<EgmStream>();
    send::<EgmRegistry>();
}

#[test]
fn mode_mismatch_and_the_fifth_identity() {
    let mut reg = registry(&[]);
    let id = reg.get_id("egmID1").unwrap();
    reg.setup_uc(id, &uc("EGMsensor:", EgmMode::Pose)).unwrap();
    reg.act_pose(id, &ActPose::world()).unwrap();
    let err = reg
        .run_joint(id, &RunArgs::new(StopMode::Hold), ALL_J)
        .unwrap_err();
    assert_eq!(err.event().number, 41826);
    assert_eq!(err.event().title, "EGM mode mismatch");
    assert!(err.is_fatal());
    for n in ["b", "c", "d"] {
        reg.get_id(n).unwrap();
    }
    let err = reg.get_id("egmID5").unwrap_err();
    assert_eq!(err.event().number, 90120);
    assert!(err.to_string().contains("at most 4"), "{err}");
}

mod path_correction {
    use super::*;
    use rapidvc::egm::driver::{CorrectionInput, CorrectionLink};
    use rapidvc::egm::path_correction::{SeamProfile, Tracker};
    use rapidvc::egm::registry::{SetupLtapp, TrackerKind};
    use rapidvc::robot::WobjData;
    use rapidvc_testkit::egm_pair::corrections;

    /// A registry whose MOC.cfg defines the manual's Level 2 profile "pathCorr".
    fn registry_pathcorr(overrides: &[String]) -> EgmRegistry {
        rapidvc_testkit::egm_pair::registry(overrides, true)
    }

    use rapidvc_testkit::egm_pair::act_move_48ms as act_move;

    #[test]
    fn udpuc_builtin_corrections_every_48_ms_drive_the_path_corrector() {
        let mut reg = registry_pathcorr(&["UCdevice=builtin:pathcorr:y=2,z=-1".into()]);
        let id = reg.get_id("egmId1").unwrap();
        let mut setup = uc("UCdevice", EgmMode::PathCorr);
        setup.profile = "pathCorr".into();
        setup.tracker = Some(TrackerKind::Aptr);
        reg.setup_uc(id, &setup).unwrap();
        act_move(&mut reg, id);
        let plan = reg.move_start(id, "EGMMoveL").unwrap();
        assert_eq!(reg.state(id), (EgmState::Running, CorrState::Running));
        let ctx = ctx(Arc::new(SignalTable::with_builtins()));
        let source = EgmSource::new(&plan.source);
        let mut link = CorrectionLink::start(RobotTime::ZERO, &ctx, &plan, source, &START).unwrap();
        // In process: no pair carries anything.
        let (got, offset) =
            corrections::<BuiltinSensor>(&mut link, None, (START, &t_fronius_cmt()), 500);
        let arrivals: Vec<Duration> = got.iter().map(|(t, _)| t.since_start()).collect();
        for (_, pos) in &got {
            assert_eq!(*pos, [0.0, 2.0, -1.0]);
        }
        // The built-in sensor answers at once; the reply is used on the next tick.
        assert_eq!(arrivals[0], TICK);
        assert!(
            arrivals
                .windows(2)
                .all(|w| w[1] - w[0] == Duration::from_millis(48))
        );
        assert!(
            (offset.y - 2.0).abs() < 1e-9 && (offset.z + 1.0).abs() < 1e-9,
            "{offset:?}"
        );
        let st = link.session_stats().unwrap();
        assert_eq!(st.sent, 42, "2 s at 48 ms");
        link.finish();
        let rows: Vec<_> = std::iter::from_fn(|| link.pop_log()).collect();
        assert_eq!(rows.len(), 42);
        assert_eq!(rows[0].reference, Some([0.0, 2.0, -1.0, 1.0, 0.0, 0.0]));
        reg.move_finished(id, true);
        assert_eq!(reg.state(id), (EgmState::Connected, CorrState::Stopped));
    }

    #[test]
    fn a_simulated_look_ahead_seam_is_sensed_ahead_of_the_tcp() {
        let mut reg = registry_pathcorr(&[]);
        let id = reg.get_id("egmId1").unwrap();
        reg.setup_ltapp(
            id,
            &SetupLtapp {
                mecunit: "ROB_1".into(),
                profile: "pathCorr".into(),
                device: "OptSim".into(),
                joint_type: 1.0,
                tracker: TrackerKind::Latr,
            },
        )
        .unwrap();
        act_move(&mut reg, id);
        let plan = reg.move_start(id, "EGMMoveL").unwrap();
        let ctx = ctx(Arc::new(SignalTable::with_builtins()));
        let source = EgmSource::new(&plan.source);
        assert!(
            EgmDriver::start(
                RobotTime::ZERO,
                &ctx,
                &{
                    let mut p = reg_plan_for_guidance();
                    p.source = plan.source.clone();
                    p
                },
                EgmSource::new(&plan.source),
                &START
            )
            .is_err(),
            "a seam cannot guide"
        );
        let mut link = CorrectionLink::start(RobotTime::ZERO, &ctx, &plan, source, &START).unwrap();
        let seam: SeamProfile = "sine:y=2,z=0.5,period=200".parse().unwrap();
        let (tool, wobj) = (t_fronius_cmt(), WobjData::wobj0());
        let mut got = 0;
        for k in 0..120u32 {
            let tcp_s = f64::from(k) * 0.5;
            let input = CorrectionInput {
                commanded: START,
                tool: &tool,
                wobj: &wobj,
                tcp_s,
                look_ahead: 30.0,
            };
            if let Some(c) = link.tick(rt(TICK * k), &input).correction {
                let want = seam.sensed_at(Tracker::Latr { look_ahead: 30.0 }, tcp_s);
                assert_eq!(c.pos, [0.0, want.y, want.z]);
                assert_eq!(c.received_at, rt(TICK * k));
                got += 1;
            }
        }
        assert_eq!(got, 10, "every 48 ms for 480 ms");
        assert!(link.session_stats().is_none());
    }

    /// Any joint-mode plan (only its source is swapped in).
    fn reg_plan_for_guidance() -> rapidvc::egm::registry::RunPlan {
        let mut reg = registry(&[]);
        let id = reg.get_id("x").unwrap();
        reg.setup_uc(id, &uc("b", EgmMode::Joint)).unwrap();
        reg.act_joint(id, &ActJoint::default()).unwrap();
        reg.run_joint(id, &RunArgs::new(StopMode::Hold), ALL_J)
            .unwrap()
    }

    #[test]
    fn a_silent_path_correction_sensor_fails_with_err_udpuc_comm() {
        let silent = UdpSocket::bind("127.0.0.1:0").unwrap();
        let mut reg = registry_pathcorr(&[format!("UCdevice={}", silent.local_addr().unwrap())]);
        let id = reg.get_id("egmId1").unwrap();
        let mut setup = uc("UCdevice", EgmMode::PathCorr);
        setup.profile = "pathCorr".into();
        setup.tracker = Some(TrackerKind::Latr);
        setup.comm_timeout = Some(0.5);
        reg.setup_uc(id, &setup).unwrap();
        act_move(&mut reg, id);
        let plan = reg.move_start(id, "EGMMoveC").unwrap();
        let ctx = ctx(Arc::new(SignalTable::with_builtins()));
        let source = EgmSource::new(&plan.source);
        let mut socket = DeviceSocket::open(&plan.source).unwrap();
        let mut link = CorrectionLink::start(RobotTime::ZERO, &ctx, &plan, source, &START).unwrap();
        let (tool, wobj) = (t_fronius_cmt(), WobjData::wobj0());
        let input = CorrectionInput {
            commanded: START,
            tool: &tool,
            wobj: &wobj,
            tcp_s: 0.0,
            look_ahead: 0.0,
        };
        let mut failed_at = None;
        for k in 0..300u32 {
            socket.receive(rt(TICK * k), &mut link);
            let t = link.tick(rt(TICK * k), &input);
            socket.send(rt(TICK * k), &mut link);
            if let Some(err) = t.failed {
                assert_eq!(err.rapid_error(), Some("ERR_UDPUC_COMM"));
                assert_eq!(err.event().number, 41822);
                assert!(failed_at.is_none(), "reported once");
                failed_at = Some(k);
            }
            if failed_at.is_some() {
                assert!(!link.awaiting_reply());
            }
        }
        assert_eq!(failed_at, Some(125), "0.5 s");
        assert_eq!(
            link.session_stats().unwrap().sent,
            11,
            "every 48 ms until then"
        );
        reg.move_finished(id, false);
        assert_eq!(reg.state(id), (EgmState::Connected, CorrState::Error));
    }
}
