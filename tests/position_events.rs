//! Position events on the motion core, driven by hand: each event of a move fires in the
//! motion cycle where the TCP reaches its place (a distance before the ToPoint, after the
//! start, a time before the ToPoint), in the middle of the corner path for the ToPoint of a
//! fly-by point, and never for a move that was dropped.

use rapidvc::motion::{CoreConfig, MotionCore, MotionError, RobotTime, Setpoint};
use rapidvc::robot::command::{
    EXTAX_NONE, MotionCommand, MoveArgs, MoveJ, MoveL, RobTarget, SpeedData, ZoneData,
};
use rapidvc::robot::trigger::{PathTrigger, TriggPlace};
use rapidvc::robot::{ConfData, Robot, ToolData};

const DT: std::time::Duration = std::time::Duration::from_millis(4);

/// The targets of tests/run/motion/trigg.mod: p10 → p20 is 600 mm along y, p30 200 mm below p20.
fn target(y: f64, z: f64, conf: ConfData) -> RobTarget {
    RobTarget {
        trans: [1100.0, y, z],
        rot: [0.0, 0.0, 1.0, 0.0],
        robconf: conf,
        extax: EXTAX_NONE,
    }
}

fn p10() -> RobTarget {
    target(-300.0, 800.0, ConfData::new(-1, 0, -1, 0))
}
fn p20() -> RobTarget {
    target(300.0, 800.0, ConfData::new(0, 0, 0, 0))
}
fn p30() -> RobTarget {
    target(300.0, 600.0, ConfData::new(0, 0, 0, 0))
}

/// A fly-by zone of `z` mm (only the TCP zone matters for these paths), fine for 0.
fn zone(z: f64) -> ZoneData {
    ZoneData {
        finep: z <= 0.0,
        pzone_tcp: z,
        ..ZoneData::FINE
    }
}

fn move_l(id: u64, to: RobTarget, v: f64, z: f64) -> MotionCommand {
    MotionCommand::MoveL(MoveL {
        args: MoveArgs::new(id, SpeedData::v(v), zone(z), ToolData::tool0()),
        target: to,
        conf_check: false,
    })
}

/// A core standing at p10.
fn core_at_p10() -> (MotionCore, RobotTime) {
    let mut core = MotionCore::new(
        Robot::default(),
        CoreConfig::default(),
        [0.0, 10.0, 10.0, 0.0, 70.0, 0.0],
    );
    core.enqueue(MotionCommand::MoveJ(MoveJ {
        args: MoveArgs::new(1, SpeedData::v(1000.0), ZoneData::FINE, ToolData::tool0()),
        target: p10(),
        conf_check: false,
    }))
    .expect("MoveJ p10");
    let mut now = RobotTime::ZERO;
    let (sps, fired) = run(&mut core, &mut now);
    assert!(fired.is_empty() && sps.last().is_some_and(|s| s.standstill));
    (core, now)
}

/// Tick until the robot is in position: every setpoint, and (key, setpoint) of each event.
fn run(core: &mut MotionCore, now: &mut RobotTime) -> (Vec<Setpoint>, Vec<(u64, Setpoint)>) {
    let mut sps = Vec::new();
    let mut fired = Vec::new();
    for _ in 0..100_000 {
        *now = now.saturating_add(DT);
        let sp = core.tick(*now);
        while let Some(e) = core.take_event() {
            if let MotionError::Trigger { key } = e.error {
                assert_eq!(e.time, *now, "an event carries the time of its cycle");
                fired.push((key, sp));
            }
        }
        sps.push(sp);
        if core.state().in_position() {
            break;
        }
    }
    (sps, fired)
}

fn dist(sp: &Setpoint, t: &RobTarget) -> f64 {
    let p = sp.tcp.translation.vector;
    ((p.x - t.trans[0]).powi(2) + (p.y - t.trans[1]).powi(2) + (p.z - t.trans[2]).powi(2)).sqrt()
}

fn trigger(key: u64, place: TriggPlace) -> PathTrigger {
    PathTrigger {
        key,
        place,
        lead_s: 0.0,
    }
}

#[test]
fn events_fire_in_the_cycle_the_tcp_reaches_them() {
    let (mut core, mut now) = core_at_p10();
    // RAPID reference, TriggIO: "TriggIO gunon, 10 \DOp:=gun, 1;" 10 mm before the point;
    // here 100 mm, 20 mm after the start, 0.2 s before the point, and at the point.
    core.set_triggers(
        &[
            trigger(1, TriggPlace::BeforeEnd(100.0)),
            trigger(2, TriggPlace::AfterStart(20.0)),
            trigger(3, TriggPlace::BeforeEndTime(0.2)),
            trigger(4, TriggPlace::BeforeEnd(0.0)),
        ],
        Some("TriggL"),
    );
    core.enqueue(move_l(2, p20(), 200.0, 0.0))
        .expect("TriggL p20");
    let (sps, fired) = run(&mut core, &mut now);
    let keys: Vec<u64> = fired.iter().map(|f| f.0).collect();
    assert_eq!(keys, [2, 1, 3, 4], "in path order");
    // 200 mm/s at 4 ms: 0.8 mm per cycle; the first cycle at or past the place.
    let step = 0.8 + 1e-6;
    let before = dist(&fired[1].1, &p20());
    assert!(before <= 100.0 && before > 100.0 - step, "{before}");
    let after = dist(&fired[0].1, &p10());
    assert!(after >= 20.0 && after < 20.0 + step, "{after}");
    let end = sps.last().expect("setpoints");
    let t_before = end.time.as_secs_f64() - fired[2].1.time.as_secs_f64();
    assert!((t_before - 0.2).abs() < 0.0041, "{t_before}");
    assert!(dist(&fired[3].1, &p20()) < 1e-6);
    assert_eq!(fired[3].1.time, end.time);
    // The trace names the RAPID instruction.
    assert_eq!(fired[0].1.instr.map(|i| i.name), Some("TriggL"));
}

#[test]
fn the_to_point_of_a_fly_by_point_is_the_middle_of_the_corner_path() {
    let (mut core, mut now) = core_at_p10();
    core.set_triggers(&[trigger(7, TriggPlace::BeforeEnd(0.0))], Some("MoveLDO"));
    core.enqueue(move_l(2, p20(), 200.0, 50.0))
        .expect("MoveLDO p20 z50");
    core.enqueue(move_l(3, p30(), 200.0, 0.0))
        .expect("MoveL p30");
    let (sps, fired) = run(&mut core, &mut now);
    let [(7, at)] = fired.as_slice() else {
        panic!("{fired:?}")
    };
    let closest = sps
        .iter()
        .map(|s| dist(s, &p20()))
        .fold(f64::INFINITY, f64::min);
    let here = dist(at, &p20());
    // The robot never reaches p20; the event is where the corner path passes it closest.
    assert!(closest > 5.0, "{closest}");
    assert!(
        here - closest < 1.0,
        "fired {here} mm from p20, closest {closest} mm"
    );
}

#[test]
fn events_of_dropped_moves_never_fire() {
    let (mut core, mut now) = core_at_p10();
    core.set_triggers(&[trigger(9, TriggPlace::BeforeEnd(10.0))], None);
    core.enqueue(move_l(2, p20(), 200.0, 0.0))
        .expect("MoveL p20");
    for _ in 0..100 {
        now = now.saturating_add(DT);
        core.tick(now);
    }
    core.stop();
    let (_, fired) = run(&mut core, &mut now);
    assert!(fired.is_empty(), "{fired:?}");
    // The next move has no events of its own.
    core.plan_from_here();
    core.enqueue(move_l(3, p20(), 200.0, 0.0))
        .expect("MoveL p20");
    let (_, fired) = run(&mut core, &mut now);
    assert!(fired.is_empty(), "{fired:?}");
}

#[test]
fn lead_fires_earlier_by_whole_cycles() {
    let (mut core, mut now) = core_at_p10();
    // TriggEquip: EquipLag 0.1 s earlier than 50 mm before the point = 70 mm at 200 mm/s.
    core.set_triggers(
        &[PathTrigger {
            key: 5,
            place: TriggPlace::BeforeEnd(50.0),
            lead_s: 0.1,
        }],
        None,
    );
    core.enqueue(move_l(2, p20(), 200.0, 0.0))
        .expect("MoveL p20");
    let (_, fired) = run(&mut core, &mut now);
    let d = dist(&fired.first().expect("fired").1, &p20());
    assert!((d - 70.0).abs() < 1.0, "{d}");
}
