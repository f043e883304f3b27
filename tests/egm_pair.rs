//! Pair tests: an EGM joint session, a pose session and a path-correction run, end to end in
//! virtual time with no socket — the controller-side machines (`EgmDriver`,
//! `CorrectionLink`) joined in memory to rapidvc's built-in sensor or to a sensor the test
//! scripts (`rapidvc_testkit::egm_pair`). The real-socket and real-client tests
//! (`egm_driver.rs`, `run_egm.rs`, `egm_clients.rs`) prove the wire; these prove the
//! protocol and the motion it drives, deterministically.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use std::sync::Arc;
use std::time::Duration;

use rapidvc::egm::proto::egm_mci_state::MciStateType;
use rapidvc::egm::registry::{ActJoint, ActPose, RunArgs, SetupUc, TrackerKind};
use rapidvc::egm::servo::{ServoPhase, StopMode};
use rapidvc::egm::{
    CorrState, CorrectionLink, DatagramMachine, DriverContext, DriverOptions, EgmDriver, EgmEnd,
    EgmError, EgmEvent, EgmMode, EgmSource, EgmState, EgmTick, Joints,
};
use rapidvc::robot::units::pose_to_pos_quat;
use rapidvc::robot::{Robot, ToolData};
use rapidvc::signals::SignalTable;
use rapidvc::time::RobotTime;
use rapidvc_testkit::egm_pair::{
    Pair, SENSOR, Scripted, SensorEnd, act_move_48ms, builtin, corrections, registry,
};
use rapidvc_testkit::egm_wire::{joint_reply, pose_reply};
use rapidvc_testkit::robot::t_fronius_cmt;

const TICK: Duration = Duration::from_millis(4);
const START: Joints = [0.0, 0.0, 0.0, 0.0, 30.0, 0.0];
const ALL_J: [bool; 7] = [true, true, true, true, true, true, false];

fn at(k: u32) -> RobotTime {
    RobotTime::from_duration(TICK * k)
}

fn device() -> Vec<String> {
    vec![format!("sensor={SENSOR}")]
}

fn ctx() -> DriverContext {
    DriverContext {
        robot: Robot::default(),
        signals: Arc::new(SignalTable::with_builtins()),
        options: DriverOptions::default(),
        drops: Default::default(),
    }
}

fn setup(mode: EgmMode, comm_timeout: Option<f64>) -> SetupUc {
    SetupUc {
        mecunit: "ROB_1".into(),
        profile: "default".into(),
        device: "sensor".into(),
        mode,
        tracker: None,
        comm_timeout,
    }
}

fn converge_args() -> RunArgs {
    RunArgs {
        cond_time: Some(0.5),
        ..RunArgs::new(StopMode::Hold)
    }
}

/// What a run did.
struct Run {
    ticks: Vec<EgmTick>,
    events: Vec<EgmEvent>,
    result: Result<EgmEnd, EgmError>,
}

/// Cycles `driver` against the pair's sensor from time zero until it finishes (at most
/// `max` ticks): the pair delivers before each tick and carries after it, where the
/// controller's loop drains and sends the device's socket.
fn run<S: SensorEnd>(pair: &mut Pair<S>, driver: &mut EgmDriver, max: u32) -> Run {
    let start = *driver.start_joints();
    run_from(pair, driver, 0, start, max)
}

fn joint_driver(comm_timeout: Option<f64>) -> EgmDriver {
    let mut reg = registry(&device(), false);
    let id = reg.get_id("egmID1").unwrap();
    reg.setup_uc(id, &setup(EgmMode::Joint, comm_timeout))
        .unwrap();
    let mut act = ActJoint::default();
    act.common.max_speed_deviation = Some(100.0);
    reg.act_joint(id, &act).unwrap();
    let plan = reg.run_joint(id, &converge_args(), ALL_J).unwrap();
    let source = EgmSource::new(&plan.source);
    assert!(source.is_external(), "a UdpUc device, carried by the pair");
    EgmDriver::start(RobotTime::ZERO, &ctx(), &plan, source, &START).unwrap()
}

fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

#[test]
fn joint_session_with_the_builtin_sensor_converges_the_same_way_every_time() {
    let target = [10.0, -5.0, 20.0, 0.0, 40.0, 30.0];
    let once = || {
        let mut pair =
            Pair::with_latency(builtin("joint:10,-5,20,0,40,30"), Duration::from_millis(1));
        let mut driver = joint_driver(None);
        let run = run(&mut pair, &mut driver, 5000);
        (pair, driver, run)
    };
    let (pair, driver, run) = once();
    assert_eq!(run.result, Ok(EgmEnd::Converged));
    let last = run.ticks.last().unwrap();
    assert!(
        close(&last.joints_cmd, &target, 0.5),
        "{:?}",
        last.joints_cmd
    );
    // Every cycle sent one EgmRobot: seqno from 0, header.tm in virtual milliseconds, MCI
    // running, convergence met in the last one.
    assert_eq!(pair.received.len(), run.ticks.len());
    for (k, m) in pair.received.iter().enumerate() {
        let h = m.header.unwrap();
        assert_eq!((h.seqno, h.tm), (Some(k as u32), Some(4 * k as u32)));
        assert_eq!(m.mci_state.unwrap().state, MciStateType::MciRunning as i32);
    }
    assert_eq!(
        pair.received.last().unwrap().mci_convergence_met,
        Some(true)
    );
    // Each reply arrived 2 ms later and was used; only the last is still in flight.
    let st = driver.session_stats().unwrap();
    assert_eq!(st.sent as usize, run.ticks.len());
    assert_eq!(st.accepted + 1, st.sent);
    assert_eq!(st.dropped(), 0);
    assert!(
        run.events.iter().all(|e| e.number != 41822),
        "{:?}",
        run.events
    );
    // Virtual time without sockets is deterministic: the same run, bit for bit.
    let (_, _, again) = once();
    let path = |r: &Run| r.ticks.iter().map(|t| t.joints_cmd).collect::<Vec<_>>();
    assert_eq!(path(&run), path(&again));
}

#[test]
fn pose_session_with_a_scripted_sensor_moves_the_tcp_to_its_target() {
    let mut reg = registry(&device(), false);
    let id = reg.get_id("egmID1").unwrap();
    reg.setup_uc(id, &setup(EgmMode::Pose, None)).unwrap();
    let mut act = ActPose::world();
    act.common.max_speed_deviation = Some(100.0);
    reg.act_pose(id, &act).unwrap();
    let plan = reg.run_pose(id, &converge_args(), [true; 6], None).unwrap();
    let source = EgmSource::new(&plan.source);
    let mut driver = EgmDriver::start(RobotTime::ZERO, &ctx(), &plan, source, &START).unwrap();
    // The sensor asks for the pose it is first told, moved by (0, 20, -30) mm, orientation
    // kept: all in the correction frame (world here).
    let mut target: Option<([f64; 3], [f64; 4])> = None;
    let sensor = Scripted(move |k: u32, robot: &rapidvc::egm::proto::EgmRobot| {
        let (pos, orient) = *target.get_or_insert_with(|| {
            let c = robot.feed_back.as_ref().unwrap().cartesian.unwrap();
            let (p, o) = (c.pos.unwrap(), c.orient.unwrap());
            ([p.x, p.y + 20.0, p.z - 30.0], [o.u0, o.u1, o.u2, o.u3])
        });
        Some(pose_reply(k, pos, orient))
    });
    let mut pair = Pair::new(sensor);
    let run = run(&mut pair, &mut driver, 5000);
    assert_eq!(run.result, Ok(EgmEnd::Converged), "{:?}", run.events);
    let robot = Robot::default();
    let (start_pos, start_orient) = pose_to_pos_quat(&robot.tcp_world(&START, &ToolData::tool0()));
    let q = run.ticks.last().unwrap().joints_cmd;
    let (pos, orient) = pose_to_pos_quat(&robot.tcp_world(&q, &ToolData::tool0()));
    let want = [start_pos[0], start_pos[1] + 20.0, start_pos[2] - 30.0];
    assert!(close(&pos, &want, 0.5), "TCP {pos:?}, target {want:?}");
    let same = (0..4)
        .map(|i| orient[i] * start_orient[i])
        .sum::<f64>()
        .abs();
    assert!(
        same > 1.0 - 1e-6,
        "orientation kept: {orient:?} vs {start_orient:?}"
    );
    // The sensor was told where the robot is: the last feedback is the target.
    let fb = pair.received.last().unwrap().feed_back.as_ref().unwrap();
    let p = fb.cartesian.unwrap().pos.unwrap();
    assert!(close(&[p.x, p.y, p.z], &want, 0.5), "{p:?}");
}

#[test]
fn a_scripted_sensor_that_falls_silent_ends_the_joint_run_with_err_udpuc_comm() {
    // Replies to the first 50 messages, then nothing.
    let sensor = Scripted(|k: u32, _: &rapidvc::egm::proto::EgmRobot| {
        (k < 50).then(|| joint_reply(k, [5.0, 0.0, 0.0, 0.0, 30.0, 0.0]))
    });
    let mut pair = Pair::new(sensor);
    let mut driver = joint_driver(Some(1.0));
    // The machine says when it next needs a tick: its next message, one cycle on.
    let mut q = START;
    for k in 0..=60 {
        pair.deliver(at(k), &mut driver);
        q = driver.tick(at(k), &q).joints_cmd;
        pair.carry(at(k), &mut driver);
    }
    assert_eq!(driver.poll_timeout(), Some(at(61)));
    let mut rest = run_from(&mut pair, &mut driver, 61, q, 2000);
    let err = rest.result.unwrap_err();
    assert!(matches!(err, EgmError::CommTimeout { .. }), "{err}");
    assert_eq!(err.rapid_error(), Some("ERR_UDPUC_COMM"));
    let halted = rest
        .ticks
        .iter()
        .position(|t| t.phase == ServoPhase::Halting)
        .unwrap() as u32
        + 61;
    // 1 s after the last reply (message 49's, handed in before tick 50).
    assert_eq!(at(halted), at(50) + Duration::from_secs(1));
    // From then on the sensor is told MCI_ERROR; 41822 is the run's error, not an event.
    let after = &pair.received[halted as usize..];
    assert!(!after.is_empty());
    assert!(
        after
            .iter()
            .all(|m| m.mci_state.unwrap().state == MciStateType::MciError as i32)
    );
    rest.events.retain(|e| e.number == 41822);
    assert!(rest.events.is_empty());
    assert_eq!(
        driver.poll_timeout(),
        None,
        "finished: nothing more to wait for"
    );
}

/// [`run`] from tick `from` at joints `q`.
fn run_from<S: SensorEnd>(
    pair: &mut Pair<S>,
    driver: &mut EgmDriver,
    from: u32,
    mut q: Joints,
    max: u32,
) -> Run {
    let robot = Robot::default();
    let (mut ticks, mut events) = (Vec::new(), Vec::new());
    for k in from..from + max {
        pair.deliver(at(k), driver);
        let t = driver.tick(at(k), &q);
        pair.carry(at(k), driver);
        robot.check_limits(&t.joints_cmd).unwrap();
        q = t.joints_cmd;
        events.extend(std::iter::from_fn(|| driver.poll_event()));
        let done = t.finished.clone();
        ticks.push(t);
        if let Some(result) = done {
            return Run {
                ticks,
                events,
                result,
            };
        }
    }
    panic!("the run did not finish within {max} ticks");
}

#[test]
fn path_correction_run_with_the_builtin_sensor_drives_the_corrector() {
    let mut reg = registry(&device(), true);
    let id = reg.get_id("egmId1").unwrap();
    let mut uc = setup(EgmMode::PathCorr, None);
    uc.profile = "pathCorr".into();
    uc.tracker = Some(TrackerKind::Aptr);
    reg.setup_uc(id, &uc).unwrap();
    act_move_48ms(&mut reg, id);
    let plan = reg.move_start(id, "EGMMoveL").unwrap();
    assert_eq!(reg.state(id), (EgmState::Running, CorrState::Running));
    let source = EgmSource::new(&plan.source);
    let mut link = CorrectionLink::start(RobotTime::ZERO, &ctx(), &plan, source, &START).unwrap();
    let mut pair = Pair::new(builtin("pathcorr:y=2,z=-1"));
    let (got, offset) = corrections(&mut link, Some(&mut pair), (START, &t_fronius_cmt()), 500);
    let arrivals: Vec<RobotTime> = got.iter().map(|(t, _)| *t).collect();
    assert!(got.iter().all(|(_, pos)| *pos == [0.0, 2.0, -1.0]));
    // Every 48 ms an EgmRobot went out; its reply is used on the next tick.
    assert_eq!(arrivals[0], at(1));
    assert!(
        arrivals
            .windows(2)
            .all(|w| w[1] - w[0] == Duration::from_millis(48))
    );
    assert_eq!(pair.received.len(), 42, "2 s at 48 ms");
    assert!(
        (offset.y - 2.0).abs() < 1e-9 && (offset.z + 1.0).abs() < 1e-9,
        "{offset:?}"
    );
    assert!(!link.awaiting_reply(), "every reply came");
    link.finish();
    let rows: Vec<_> = std::iter::from_fn(|| link.pop_log()).collect();
    assert_eq!(rows.len(), 42);
    assert_eq!(rows[0].reference, Some([0.0, 2.0, -1.0, 1.0, 0.0, 0.0]));
    reg.move_finished(id, true);
    assert_eq!(reg.state(id), (EgmState::Connected, CorrState::Stopped));
}
