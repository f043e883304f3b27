//! Path correction end to end below the interpreter: registry, program side, hook, executor, built-in and simulated sensors, in virtual time.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use std::sync::{Arc, Mutex};
use std::time::Duration;

use nalgebra::Vector3;

use super::*;
use crate::config::devices::{DeviceOverride, DeviceTable};
use crate::config::moc::MocConfig;
use crate::controller::sample_feed::{FeedItem, FeedRx, PathCorrSample};
use crate::controller::{ControllerConfig, TickSink};
use crate::egm::DriverOptions;
use crate::egm::registry::{ActMove, SetupLtapp, SetupUc};
use crate::egm::types::EgmMode;
use crate::motion::Setpoint;
use crate::robot::command::{
    EXTAX_NONE, MoveArgs, MoveC, MoveJ, MoveL, RobTarget, SpeedData, ZoneData,
};
use crate::robot::{ConfData, Pose, Robot, ToolData};
use crate::signals::SignalTable;
use crate::time::RobotTime;

/// Level 2 profile "pathCorr" (the manual's MOC.cfg).
fn moc() -> MocConfig {
    let mut sources = crate::source::SourceMap::default();
    let mut diags = crate::diag::Diagnostics::default();
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("programs/manual");
    let c = crate::config::load_dir(&dir, &mut sources, &mut diags);
    c.moc
}

fn registry(overrides: &[&str]) -> EgmRegistry {
    let o: Vec<DeviceOverride> = overrides.iter().map(|s| s.parse().unwrap()).collect();
    EgmRegistry::new(crate::controller::egm_controller::registry_config(
        &moc(),
        &DeviceTable::new(None, &o).unwrap(),
    ))
}

#[derive(Clone, Default)]
struct Collect(Arc<Mutex<Vec<Setpoint>>>);

impl TickSink for Collect {
    fn record(&mut self, sp: &Setpoint) {
        self.0.lock().unwrap().push(*sp);
    }
}

struct Rig {
    handle: ControllerHandle,
    pc: PathCorr,
    reg: EgmRegistry,
    sps: Collect,
    feed: FeedRx,
    next_id: u64,
    last: LastMove,
}

fn target(x: f64, y: f64, z: f64) -> RobTarget {
    RobTarget {
        trans: [x, y, z],
        rot: [0.0, 0.0, 1.0, 0.0],
        robconf: ConfData::new(0, 0, -1, 1),
        extax: EXTAX_NONE,
    }
}

fn z5() -> ZoneData {
    ZoneData {
        finep: false,
        pzone_tcp: 5.0,
        pzone_ori: 7.5,
        pzone_eax: 7.5,
        zone_ori: 0.75,
        zone_leax: 7.5,
        zone_reax: 0.75,
    }
}

impl Rig {
    fn new(overrides: &[&str], options: PathCorrOptions) -> Rig {
        let robot = Robot::default();
        let ctx = DriverContext {
            robot: robot.clone(),
            signals: Arc::new(SignalTable::with_builtins()),
            options: DriverOptions::default(),
            drops: Default::default(),
        };
        let mut feed = Feed::new();
        let rx = feed.subscribe();
        let (pc, hook) = path_correction(ctx, options, Some(feed), None);
        let sps = Collect::default();
        let handle = ControllerHandle::start_with_hook(
            ControllerConfig::new(robot, [0.0; 6]),
            vec![Box::new(sps.clone())],
            Some(Box::new(hook)),
        )
        .unwrap();
        Rig {
            handle,
            pc,
            reg: registry(overrides),
            sps,
            feed: rx,
            next_id: 1,
            last: LastMove::None,
        }
    }

    fn args(&mut self, v: f64, zone: ZoneData) -> MoveArgs {
        let id = self.next_id;
        self.next_id += 1;
        MoveArgs::new(id, SpeedData::v(v), zone, ToolData::tool0())
    }

    /// MoveJ to `t`, fine.
    fn move_j(&mut self, t: RobTarget) {
        let args = self.args(1000.0, ZoneData::FINE);
        self.handle
            .submit(MotionCommand::MoveJ(MoveJ {
                args,
                target: t,
                conf_check: false,
            }))
            .unwrap();
        self.handle.wait_until(Condition::InPos).unwrap();
        self.last = LastMove::StopPoint;
    }

    fn egm_l(
        &mut self,
        id: EgmId,
        t: RobTarget,
        zone: ZoneData,
        no_corr: bool,
    ) -> Result<(), PathCorrError> {
        let args = self.args(10.0, zone);
        let cmd = MotionCommand::MoveL(MoveL {
            args,
            target: t,
            conf_check: false,
        });
        let ticket =
            self.pc
                .submit(&mut self.handle, &mut self.reg, id, cmd, no_corr, self.last)?;
        if ticket.fine {
            self.pc.wait_fine(&mut self.handle, &mut self.reg, ticket)?;
        }
        Ok(())
    }

    fn setup_uc(&mut self, device: &str) -> EgmId {
        let id = self.reg.get_id("egmId1").unwrap();
        self.reg
            .setup_uc(
                id,
                &SetupUc {
                    mecunit: "ROB_1".into(),
                    profile: "pathCorr".into(),
                    device: device.into(),
                    mode: EgmMode::PathCorr,
                    tracker: Some(TrackerKind::Aptr),
                    comm_timeout: None,
                },
            )
            .unwrap();
        self.act(id);
        id
    }

    fn act(&mut self, id: EgmId) {
        self.reg
            .act_move(
                id,
                &ActMove {
                    sensor_frame: Pose::identity(),
                    sample_rate: Some(48.0),
                },
            )
            .unwrap();
    }

    fn samples(&mut self) -> Vec<PathCorrSample> {
        let mut out = Vec::new();
        self.feed.drain_all(|i| {
            if let FeedItem::PathCorr(s) = i {
                out.push(s)
            }
        });
        out
    }

    fn setpoints(&self) -> Vec<Setpoint> {
        self.sps.0.lock().unwrap().clone()
    }
}

fn pos(sp: &Setpoint) -> Vector3<f64> {
    sp.tcp.translation.vector
}

/// The acceptance case: 400 mm at v10 over a seam offset y = 3, z = −2 (built-in sensor).
#[test]
fn a_constant_seam_offset_is_followed_within_0_2_mm() {
    let mut rig = Rig::new(
        &["UCdevice=builtin:pathcorr:y=3,z=-2"],
        PathCorrOptions::default(),
    );
    let id = rig.setup_uc("UCdevice");
    rig.move_j(target(1000.0, 20.0, 500.0));
    rig.egm_l(id, target(1400.0, 20.0, 500.0), ZoneData::FINE, false)
        .unwrap();
    assert!(!rig.pc.is_active());
    assert_eq!(
        rig.reg.state(id),
        (
            crate::egm::EgmState::Connected,
            crate::egm::CorrState::Stopped
        )
    );
    let sps = rig.setpoints();
    let end = pos(sps.last().unwrap());
    // Path frame: x = +X, tool z = −Z → y = +Y, z = +Z.
    let want = Vector3::new(1400.0, 23.0, 498.0);
    assert!((end - want).norm() < 0.2, "{end:?}");
    let samples = rig.samples();
    assert!(samples.len() > 9000, "{}", samples.len());
    let last = samples.last().unwrap();
    assert!((last.s_mm - 400.0).abs() < 1e-6);
    assert!((last.correction()[0] - 3.0).abs() < 1e-9);
    assert!((last.correction()[1] + 2.0).abs() < 1e-9);
    // Smooth: no step longer than 20 mm/s · 4 ms.
    let mut worst: f64 = 0.0;
    for w in samples.windows(2) {
        let [a, b] = [w[0].correction(), w[1].correction()];
        worst = worst.max((a[0] - b[0]).hypot(a[1] - b[1]));
    }
    assert!(worst <= 0.08 + 1e-9, "{worst}");
    assert!(
        worst > 0.05,
        "the correction ramps at its speed limit: {worst}"
    );
    // The trace names the move EGMMoveL.
    assert!(
        sps.iter()
            .any(|s| s.instr.is_some_and(|i| i.name == "EGMMoveL"))
    );
    // Messages went out at 48 ms; the link comes back with the next cycle.
    let now = rig.handle.now();
    rig.handle
        .wait_until(Condition::TimeReached(
            now.saturating_add(Duration::from_millis(4)),
        ))
        .unwrap();
    rig.pc.take_events();
    let stats = rig.pc.last_link().unwrap().session_stats().unwrap().clone();
    assert!(stats.sent > 800 && stats.sent < 860, "{stats:?}");
}

#[test]
fn simulated_ltapp_seams_and_a_circle() {
    let mut rig = Rig::new(&[], PathCorrOptions::default());
    let id = rig.reg.get_id("egmId1").unwrap();
    rig.reg
        .setup_ltapp(
            id,
            &SetupLtapp {
                mecunit: "ROB_1".into(),
                profile: "pathCorr".into(),
                device: "wg1sim".into(),
                joint_type: 1.0,
                tracker: TrackerKind::Aptr,
            },
        )
        .unwrap();
    rig.act(id);
    rig.move_j(target(1000.0, 20.0, 500.0));
    rig.egm_l(id, target(1200.0, 20.0, 500.0), z5(), false)
        .unwrap();
    let args = rig.args(10.0, z5());
    let c = MotionCommand::MoveC(MoveC {
        args,
        cir_point: target(1250.0, 70.0, 500.0),
        to_point: target(1300.0, 20.0, 500.0),
        conf_check: false,
    });
    let t = rig
        .pc
        .submit(&mut rig.handle, &mut rig.reg, id, c, false, LastMove::FlyBy)
        .unwrap();
    assert!(!t.fine);
    rig.egm_l(id, target(1400.0, 20.0, 500.0), ZoneData::FINE, false)
        .unwrap();
    // wg1sim: ramp:y=3,z=-1,len=150 — at the end of the straight line the seam is 3 mm
    // to the left (+Y) and 1 mm down.
    let sps = rig.setpoints();
    let end = pos(sps.last().unwrap());
    assert!(
        (end - Vector3::new(1400.0, 23.0, 499.0)).norm() < 0.2,
        "{end:?}"
    );
    let samples = rig.samples();
    let s_end = samples.last().unwrap().s_mm;
    let arc = std::f64::consts::PI * 50.0;
    // Two 90° corners, each cut by its z5 zone.
    assert!(s_end < 300.0 + arc && s_end > 300.0 + arc - 5.0, "{s_end}");
    assert!(samples.iter().any(|s| s.measured_yz.is_some()));
    assert!(
        sps.iter()
            .any(|s| s.instr.is_some_and(|i| i.name == "EGMMoveC"))
    );
}

#[test]
fn no_corr_ramps_the_correction_out() {
    let mut rig = Rig::new(
        &["UCdevice=builtin:pathcorr:y=2,z=0"],
        PathCorrOptions::default(),
    );
    let id = rig.setup_uc("UCdevice");
    rig.move_j(target(1000.0, 20.0, 500.0));
    rig.egm_l(id, target(1100.0, 20.0, 500.0), z5(), false)
        .unwrap();
    rig.egm_l(id, target(1200.0, 20.0, 500.0), ZoneData::FINE, true)
        .unwrap();
    let sps = rig.setpoints();
    let end = pos(sps.last().unwrap());
    assert!(
        (end - Vector3::new(1200.0, 20.0, 500.0)).norm() < 1e-6,
        "{end:?}"
    );
    let samples = rig.samples();
    let at_100 = samples.iter().find(|s| s.s_mm >= 95.0).unwrap();
    assert!((at_100.correction()[0] - 2.0).abs() < 1e-9);
}

#[test]
fn the_sequence_must_start_and_end_in_a_fine_point() {
    let mut rig = Rig::new(
        &["UCdevice=builtin:pathcorr:y=1"],
        PathCorrOptions::default(),
    );
    let id = rig.setup_uc("UCdevice");
    // Before any move since the start.
    let e = rig
        .egm_l(id, target(1100.0, 20.0, 500.0), ZoneData::FINE, false)
        .unwrap_err();
    assert!(e.to_string().contains("cannot be an EGM movement"), "{e}");
    rig.move_j(target(1000.0, 20.0, 500.0));
    // From a fly-by point.
    rig.last = LastMove::FlyBy;
    let args = rig.args(100.0, z5());
    rig.handle
        .submit(MotionCommand::MoveL(MoveL {
            args,
            target: target(1050.0, 20.0, 500.0),
            conf_check: false,
        }))
        .unwrap();
    let e = rig
        .egm_l(id, target(1100.0, 20.0, 500.0), ZoneData::FINE, false)
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "EGMMoveL egmId1: EGM Path correction has to start and end in a fine point; the movement before the first EGMMoveL/EGMMoveC must end with `fine`"
    );
    assert_eq!(e.rapid_error(), None);
    assert!(e.event_text().starts_with("90128 "), "{}", e.event_text());
    assert_eq!(
        rig.reg.state(id).0,
        crate::egm::EgmState::Connected,
        "a refused start leaves the identity connected"
    );
    rig.handle.wait_until(Condition::InPos).unwrap();
    rig.last = LastMove::StopPoint;
    // Ending with a fly-by point, then a plain MoveL: the robot stops.
    rig.egm_l(id, target(1100.0, 20.0, 500.0), z5(), false)
        .unwrap();
    assert!(rig.pc.check_other_move("MoveL").is_err());
    let args = rig.args(100.0, ZoneData::FINE);
    rig.handle
        .submit(MotionCommand::MoveL(MoveL {
            args,
            target: target(1150.0, 20.0, 500.0),
            conf_check: false,
        }))
        .unwrap();
    let e = rig.handle.wait_until(Condition::InPos).unwrap_err();
    let text = e.to_string();
    assert!(
        text.contains("90131 EGM path correction not ended in a fine point: MoveL egmId1: EGM Path correction has to start and end in a fine point"),
        "{text}"
    );
    rig.pc.abandon(&mut rig.handle, &mut rig.reg);
    assert!(!rig.handle.state().halted);
    assert_eq!(rig.reg.state(id).1, crate::egm::CorrState::Error);
}

#[test]
fn without_egm_act_move_or_level_2_it_is_refused() {
    let mut rig = Rig::new(
        &["UCdevice=builtin:pathcorr:y=1"],
        PathCorrOptions::default(),
    );
    rig.move_j(target(1000.0, 20.0, 500.0));
    let id = rig.reg.get_id("egmId1").unwrap();
    let setup = |profile: &str| SetupUc {
        mecunit: "ROB_1".into(),
        profile: profile.into(),
        device: "UCdevice".into(),
        mode: EgmMode::PathCorr,
        tracker: Some(TrackerKind::Aptr),
        comm_timeout: None,
    };
    rig.reg.setup_uc(id, &setup("pathCorr")).unwrap();
    let e = rig
        .egm_l(id, target(1100.0, 20.0, 500.0), ZoneData::FINE, false)
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "EGMMoveL egmId1: the identity is not activated; run EGMActMove first"
    );
    rig.reg.setup_uc(id, &setup("default")).unwrap();
    rig.act(id);
    let e = rig
        .egm_l(id, target(1100.0, 20.0, 500.0), ZoneData::FINE, false)
        .unwrap_err();
    assert!(
        e.event_text()
            .starts_with("50452 External Interface Cyclic Error"),
        "{}",
        e.event_text()
    );
    assert!(rig.handle.state().in_position());
}

#[test]
fn absurd_corrections_are_rejected_with_an_event() {
    let mut rig = Rig::new(
        &["UCdevice=builtin:pathcorr:y=500,z=0"],
        PathCorrOptions::default(),
    );
    let id = rig.setup_uc("UCdevice");
    rig.move_j(target(1000.0, 20.0, 500.0));
    rig.egm_l(id, target(1050.0, 20.0, 500.0), ZoneData::FINE, false)
        .unwrap();
    let end = pos(rig.setpoints().last().unwrap());
    assert!((end - Vector3::new(1050.0, 20.0, 500.0)).norm() < 1e-6);
    let events = rig.pc.take_events();
    // Once a second (about 5 s of motion), not once per message (every 48 ms).
    let n = events.iter().filter(|(_, e)| e.number == 90132).count();
    assert!((4..=6).contains(&n), "{events:?}");
    assert!(
        events[1]
            .1
            .detail
            .ends_with("(20 more since the last report)"),
        "{events:?}"
    );
    assert!(
        events.iter().any(|(name, e)| name == "egmId1"
            && e.number == 90132
            && e.detail
                == "path correction of 500.000 mm exceeds the limit of 100 mm; the previous correction stays in force"),
        "{events:?}"
    );
}

/// A UdpUc sensor that never answers: 41822 and ERR_UDPUC_COMM after \CommTimeout.
#[test]
fn a_silent_sensor_gives_err_udpuc_comm() {
    let silent = std::net::UdpSocket::bind("127.0.0.1:0").unwrap();
    let addr = silent.local_addr().unwrap();
    let device = format!("UCdevice={addr}");
    let mut rig = Rig::new(&[device.as_str()], PathCorrOptions::default());
    let id = rig.reg.get_id("egmId1").unwrap();
    rig.reg
        .setup_uc(
            id,
            &SetupUc {
                mecunit: "ROB_1".into(),
                profile: "pathCorr".into(),
                device: "UCdevice".into(),
                mode: EgmMode::PathCorr,
                tracker: Some(TrackerKind::Aptr),
                comm_timeout: Some(0.5),
            },
        )
        .unwrap();
    rig.act(id);
    rig.move_j(target(1000.0, 20.0, 500.0));
    let t0 = rig.handle.now();
    let e = rig
        .egm_l(id, target(1100.0, 20.0, 500.0), ZoneData::FINE, false)
        .unwrap_err();
    assert_eq!(e.rapid_error(), Some("ERR_UDPUC_COMM"), "{e}");
    assert!(
        e.event_text()
            .starts_with("41822 No data from the UdpUc device"),
        "{}",
        e.event_text()
    );
    let stopped = rig.handle.now().saturating_since(t0);
    assert!(
        stopped >= Duration::from_millis(500) && stopped < Duration::from_millis(600),
        "{stopped:?}"
    );
    // The motion core was recovered: the program may go on.
    assert!(!rig.handle.state().halted);
    assert_eq!(rig.reg.state(id).1, crate::egm::CorrState::Error);
    assert!(rig.pc.take_events().iter().any(|(_, e)| e.number == 41822));
    rig.move_j(target(1000.0, 20.0, 600.0));
    let _ = RobotTime::ZERO;
}
