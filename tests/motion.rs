//! Clock-driven tests of the motion core on the default robot (IRB 2600-12/1.85): acceptance
//! facts of docs/robot.md, "Acceptance facts", path accuracy of MoveL/MoveC, axis-speed limits, zones, errors before
//! motion, and byte-identical virtual-time traces. No sleeping: time is advanced by hand.

mod support {
    use std::time::Duration;

    use rapidvc::motion::{CoreConfig, MotionCore, RobotTime, Setpoint};
    use rapidvc::robot::command::{
        EXTAX_NONE, JointTarget, MotionCommand, MoveAbsJ, MoveArgs, MoveC, MoveJ, MoveL, RobTarget,
        SpeedData, SpeedOverride, ZoneData,
    };
    use rapidvc::robot::{ConfData, JointsDeg, Robot, ToolData, pose_from_pos_quat};

    pub const DT: Duration = Duration::from_millis(4);

    pub fn core_at(q: JointsDeg) -> MotionCore {
        MotionCore::new(Robot::default(), CoreConfig::default(), q)
    }

    pub fn t_fronius() -> ToolData {
        ToolData {
            tframe: pose_from_pos_quat(
                [12.3313, -0.108707, 416.142],
                [0.903899, -0.00320735, 0.427666, 0.00765917],
            ),
            ..ToolData::tool0()
        }
    }

    pub fn p20() -> RobTarget {
        RobTarget {
            trans: [150.0, 1320.0, 1140.0],
            rot: [0.000494947, 0.662278, -0.749217, -0.00783173],
            robconf: ConfData::new(0, 0, -1, 0),
            extax: EXTAX_NONE,
        }
    }

    pub fn p30() -> RobTarget {
        RobTarget {
            trans: [114.50, 1005.42, 1410.38],
            rot: [0.322151, -0.601023, 0.672381, 0.287914],
            robconf: ConfData::new(0, 0, -1, 0),
            extax: EXTAX_NONE,
        }
    }

    pub fn target(trans: [f64; 3], rot: [f64; 4]) -> RobTarget {
        RobTarget {
            trans,
            rot,
            robconf: ConfData::new(0, 0, 0, 0),
            extax: EXTAX_NONE,
        }
    }

    pub fn zone(z: f64) -> ZoneData {
        if z <= 0.0 {
            ZoneData::FINE
        } else {
            ZoneData {
                finep: false,
                pzone_tcp: z,
                pzone_ori: 1.5 * z,
                pzone_eax: 1.5 * z,
                zone_ori: 0.15 * z,
                zone_leax: 1.5 * z,
                zone_reax: 0.15 * z,
            }
        }
    }

    pub fn args(id: u64, v: f64, z: f64, tool: ToolData) -> MoveArgs {
        MoveArgs::new(id, SpeedData::v(v), zone(z), tool)
    }

    pub fn abs_j(id: u64, q: JointsDeg, v: f64, z: f64) -> MotionCommand {
        MotionCommand::MoveAbsJ(MoveAbsJ {
            args: args(id, v, z, ToolData::tool0()),
            target: JointTarget {
                robax: q,
                extax: EXTAX_NONE,
            },
            no_eoffs: false,
        })
    }

    pub fn move_j(id: u64, t: RobTarget, v: f64, z: f64, tool: ToolData) -> MotionCommand {
        MotionCommand::MoveJ(MoveJ {
            args: args(id, v, z, tool),
            target: t,
            conf_check: true,
        })
    }

    pub fn move_l(id: u64, t: RobTarget, v: f64, z: f64, tool: ToolData) -> MotionCommand {
        MotionCommand::MoveL(MoveL {
            args: args(id, v, z, tool),
            target: t,
            conf_check: false,
        })
    }

    pub fn move_c(
        id: u64,
        cir: RobTarget,
        to: RobTarget,
        v: f64,
        z: f64,
        tool: ToolData,
    ) -> MotionCommand {
        MotionCommand::MoveC(MoveC {
            args: args(id, v, z, tool),
            cir_point: cir,
            to_point: to,
            conf_check: false,
        })
    }

    pub fn with_time(mut cmd: MotionCommand, t: f64) -> MotionCommand {
        match &mut cmd {
            MotionCommand::MoveAbsJ(m) => m.args.speed_override = Some(SpeedOverride::T(t)),
            MotionCommand::MoveJ(m) => m.args.speed_override = Some(SpeedOverride::T(t)),
            MotionCommand::MoveL(m) => m.args.speed_override = Some(SpeedOverride::T(t)),
            MotionCommand::MoveC(m) => m.args.speed_override = Some(SpeedOverride::T(t)),
        }
        cmd
    }

    /// Tick the core until every queued move is done; returns every setpoint (bounded).
    pub fn run(core: &mut MotionCore, start_tick: &mut u64) -> Vec<Setpoint> {
        let mut out = Vec::new();
        for _ in 0..1_000_000 {
            *start_tick += 1;
            let now = RobotTime::from_nanos(*start_tick * DT.as_nanos() as u64);
            let sp = core.tick(now);
            out.push(sp);
            if core.state().in_position() {
                return out;
            }
        }
        panic!("the motion did not end");
    }

    /// Enqueue all (ticking while the queue is full), then run to the end.
    pub fn run_all(core: &mut MotionCore, cmds: Vec<MotionCommand>) -> Vec<Setpoint> {
        let mut tick = 0;
        let mut out = Vec::new();
        for cmd in cmds {
            let mut cmd = cmd;
            loop {
                match core.enqueue(cmd) {
                    Ok(()) => break,
                    Err(rapidvc::motion::EnqueueError::QueueFull(c)) => {
                        cmd = *c;
                        tick += 1;
                        out.push(core.tick(RobotTime::from_nanos(tick * DT.as_nanos() as u64)));
                    }
                    Err(e) => panic!("rejected: {e}"),
                }
            }
        }
        out.extend(run(core, &mut tick));
        out
    }

    pub fn assert_joints(q: &JointsDeg, want: &JointsDeg, tol: f64) {
        for (i, (a, b)) in q.iter().zip(want).enumerate() {
            assert!(
                (a - b).abs() <= tol,
                "axis {}: {a} vs {b} (all {q:?})",
                i + 1
            );
        }
    }
}

use support::*;

mod acceptance {
    use super::*;
    use rapidvc::robot::ToolData;

    const EXPECTED: [f64; 6] = [83.50, 0.08, -0.34, 0.10, 39.07, -0.14];

    #[test]
    fn move_j_p20_with_fronius_from_the_second_start_pose() {
        let mut core = core_at([0.0; 6]);
        let sps = run_all(
            &mut core,
            vec![
                abs_j(1, [0.0, 0.0, 0.0, 0.0, 35.0, 0.0], 1000.0, 0.0),
                move_j(2, p20(), 1000.0, 0.0, t_fronius()),
            ],
        );
        let last = sps.last().unwrap();
        assert_joints(
            &last.joints,
            &[83.498, 0.077, -0.340, 0.103, 39.066, -0.136],
            0.01,
        );
        assert_joints(&last.joints, &EXPECTED, 0.006);
        assert!(last.standstill);
        // The TCP of tFroniusCMT is at p20.
        let t = last.tcp.translation.vector;
        assert!(
            (t - nalgebra::Vector3::new(150.0, 1320.0, 1140.0)).norm() < 0.1,
            "{t:?}"
        );
    }

    #[test]
    fn move_j_p30_with_tool0_reaches_the_same_joints() {
        let mut core = core_at([0.0, 0.0, 0.0, 0.0, 35.0, 0.0]);
        let sps = run_all(
            &mut core,
            vec![move_j(1, p30(), 1000.0, 0.0, ToolData::tool0())],
        );
        assert_joints(
            &sps.last().unwrap().joints,
            &[83.498, 0.077, -0.340, 0.103, 39.066, -0.136],
            0.01,
        );
    }
}

/// Helpers for geometric checks.
mod geo {
    use nalgebra::Vector3;
    use rapidvc::motion::Setpoint;
    use rapidvc::robot::{JointsDeg, Robot};

    pub fn pos(sp: &Setpoint) -> Vector3<f64> {
        sp.tcp.translation.vector
    }

    /// Distance of `p` from the segment a–b.
    pub fn dist_to_segment(p: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
        let ab = b - a;
        let t = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
        (a + ab * t - p).norm()
    }

    /// Every step of every setpoint keeps every axis within its maximum speed.
    pub fn assert_axis_speeds(start: &JointsDeg, sps: &[Setpoint]) {
        let robot = Robot::default();
        let vmax = robot.model().max_speed;
        let dt = super::DT.as_secs_f64();
        let mut prev = *start;
        for sp in sps {
            for i in 0..6 {
                let v = (sp.joints[i] - prev[i]).abs() / dt;
                assert!(
                    v <= vmax[i] * (1.0 + 1e-9),
                    "axis {} at {:.1}°/s > {} at t={}",
                    i + 1,
                    v,
                    vmax[i],
                    sp.time
                );
            }
            prev = sp.joints;
        }
    }
}

mod paths {
    use super::geo::*;
    use super::*;
    use nalgebra::Vector3;
    use rapidvc::robot::{Robot, ToolData, pose_to_pos_quat};

    const START: [f64; 6] = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];

    fn start_target() -> ([f64; 3], [f64; 4]) {
        pose_to_pos_quat(&Robot::default().fk(&START))
    }

    #[test]
    fn move_l_is_straight_and_reaches_its_speed() {
        let (p0, rot) = start_target();
        let p1 = [p0[0] - 300.0, p0[1] + 400.0, p0[2] - 200.0];
        let mut core = core_at(START);
        let sps = run_all(
            &mut core,
            vec![move_l(1, target(p1, rot), 500.0, 0.0, ToolData::tool0())],
        );
        let a = Vector3::from(p0);
        let b = Vector3::from(p1);
        let mut top: f64 = 0.0;
        let mut cruise = 0;
        for sp in &sps {
            let d = dist_to_segment(&pos(sp), &a, &b);
            assert!(d <= 0.1, "{d} mm off the line at {}", sp.time);
            assert!(sp.speed <= 500.0 * (1.0 + 1e-6), "{} mm/s", sp.speed);
            top = top.max(sp.speed);
            if (sp.speed - 500.0).abs() < 0.5 {
                cruise += 1;
            }
            // Orientation is kept.
            let q = Robot::default().fk(&START).rotation;
            assert!(sp.tcp.rotation.angle_to(&q) < 1e-6);
        }
        assert!((top - 500.0).abs() < 0.5, "top speed {top}");
        assert!(cruise > 100, "only {cruise} cycles at the programmed speed");
        assert!((pos(sps.last().unwrap()) - b).norm() < 1e-6);
        assert_axis_speeds(&START, &sps);
    }

    #[test]
    fn move_l_with_reorientation_interpolates_orientation() {
        let (p0, _) = start_target();
        let q0 = Robot::default().fk(&START).rotation;
        let turn = nalgebra::UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.6);
        let q1 = turn * q0;
        let p1 = [p0[0], p0[1] + 100.0, p0[2]];
        let mut core = core_at(START);
        let sps = run_all(
            &mut core,
            vec![move_l(
                1,
                target(p1, [q1.w, q1.i, q1.j, q1.k]),
                1000.0,
                0.0,
                ToolData::tool0(),
            )],
        );
        // v_ori (500°/s) allows 34° in ~0.07 s, v_tcp 100 mm in 0.1 s: the line dominates.
        let last = sps.last().unwrap();
        assert!(last.tcp.rotation.angle_to(&q1) < 1e-6);
        for sp in &sps {
            let s = (pos(sp).y - p0[1]) / 100.0;
            let expected = q0.slerp(&q1, s.clamp(0.0, 1.0));
            assert!(
                sp.tcp.rotation.angle_to(&expected) < 1e-6,
                "orientation off the SLERP at s={s}"
            );
        }
        assert_axis_speeds(&START, &sps);
    }

    #[test]
    fn move_c_stays_on_the_circle() {
        let (p0, rot) = start_target();
        let c = Vector3::new(p0[0], p0[1], p0[2] - 200.0);
        let cir = [c.x, c.y + 200.0, c.z];
        let to = [c.x, c.y, c.z - 200.0];
        let mut core = core_at(START);
        let sps = run_all(
            &mut core,
            vec![move_c(
                1,
                target(cir, rot),
                target(to, rot),
                300.0,
                0.0,
                ToolData::tool0(),
            )],
        );
        let mut passed_cir = false;
        for sp in &sps {
            let p = pos(sp);
            assert!(
                ((p - c).norm() - 200.0).abs() <= 0.1,
                "off the circle: r = {}",
                (p - c).norm()
            );
            assert!((p.x - c.x).abs() <= 0.1, "off the plane");
            assert!(sp.speed <= 300.0 * (1.0 + 1e-6));
            passed_cir |= (p - Vector3::from(cir)).norm() < 2.0;
        }
        assert!(passed_cir, "the arc does not pass the circle point");
        assert!((pos(sps.last().unwrap()) - Vector3::from(to)).norm() < 1e-6);
        // Constant speed in the middle of the arc.
        let mid = &sps[sps.len() / 2];
        assert!((mid.speed - 300.0).abs() < 0.5, "{}", mid.speed);
        assert_axis_speeds(&START, &sps);
    }

    #[test]
    fn fine_points_stop_between_moves() {
        let (p0, rot) = start_target();
        let p1 = [p0[0], p0[1] + 200.0, p0[2]];
        let p2 = [p0[0], p0[1] + 200.0, p0[2] - 200.0];
        let mut core = core_at(START);
        let sps = run_all(
            &mut core,
            vec![
                move_l(1, target(p1, rot), 1000.0, 0.0, ToolData::tool0()),
                move_l(2, target(p2, rot), 1000.0, 0.0, ToolData::tool0()),
            ],
        );
        let at_p1 = sps
            .iter()
            .position(|sp| (pos(sp) - Vector3::from(p1)).norm() < 1e-6)
            .expect("reaches p1");
        assert!(
            sps[at_p1].standstill,
            "standstill reported at the fine point"
        );
        // The path has a sharp corner at p1: every point is on one of the two lines.
        for sp in &sps {
            let d = dist_to_segment(&pos(sp), &Vector3::from(p0), &Vector3::from(p1)).min(
                dist_to_segment(&pos(sp), &Vector3::from(p1), &Vector3::from(p2)),
            );
            assert!(d <= 0.1);
        }
    }

    #[test]
    fn fly_by_corners_stay_inside_their_zones() {
        let (p0, rot) = start_target();
        let z = 50.0;
        let pts = [
            p0,
            [p0[0], p0[1] + 300.0, p0[2]],
            [p0[0] - 200.0, p0[1] + 300.0, p0[2] - 200.0],
            [p0[0] - 200.0, p0[1] + 30.0, p0[2] - 200.0],
        ];
        let mut core = core_at(START);
        let sps = run_all(
            &mut core,
            vec![
                move_l(1, target(pts[1], rot), 800.0, z, ToolData::tool0()),
                move_l(2, target(pts[2], rot), 800.0, z, ToolData::tool0()),
                move_l(3, target(pts[3], rot), 800.0, 0.0, ToolData::tool0()),
            ],
        );
        let v = |i: usize| Vector3::from(pts[i]);
        let mut in_corner = [0usize; 2];
        let mut min_speed_in_corner = [f64::INFINITY; 2];
        for sp in &sps {
            let p = pos(sp);
            let on_line = (0..3).any(|i| dist_to_segment(&p, &v(i), &v(i + 1)) <= 1e-3);
            if !on_line {
                // Off the programmed lines: inside the zone of a fly-by point.
                let k = if (p - v(1)).norm() < (p - v(2)).norm() {
                    0
                } else {
                    1
                };
                let d = (p - v(k + 1)).norm();
                assert!(d <= z + 1e-6, "corner {} leaves its zone: {d} mm", k + 1);
                in_corner[k] += 1;
                min_speed_in_corner[k] = min_speed_in_corner[k].min(sp.speed);
            }
        }
        assert!(
            in_corner[0] > 5 && in_corner[1] > 5,
            "corner paths {in_corner:?}"
        );
        // The robot flies by: it never stops in a corner.
        assert!(
            min_speed_in_corner.iter().all(|&s| s > 100.0),
            "{min_speed_in_corner:?}"
        );
        // The second zone is halved by the 270 mm third leg? No: 50 < 135, kept.
        assert!(core.take_event().is_none(), "no warnings");
        assert_axis_speeds(&START, &sps);
    }

    #[test]
    fn zones_shrink_to_half_the_distance_to_the_neighbour() {
        let (p0, rot) = start_target();
        // 40 mm second leg: the 100 mm zone shrinks to 20 mm.
        let pts = [
            p0,
            [p0[0], p0[1] + 300.0, p0[2]],
            [p0[0], p0[1] + 300.0, p0[2] - 40.0],
        ];
        let mut core = core_at(START);
        let sps = run_all(
            &mut core,
            vec![
                move_l(1, target(pts[1], rot), 500.0, 100.0, ToolData::tool0()),
                move_l(2, target(pts[2], rot), 500.0, 0.0, ToolData::tool0()),
            ],
        );
        let corner = Vector3::from(pts[1]);
        let mut deviated = 0;
        for sp in &sps {
            let p = pos(sp);
            let off = dist_to_segment(&p, &Vector3::from(pts[0]), &corner).min(dist_to_segment(
                &p,
                &corner,
                &Vector3::from(pts[2]),
            ));
            if off > 1e-3 {
                deviated += 1;
                assert!(
                    (p - corner).norm() <= 20.0 + 1e-6,
                    "{}",
                    (p - corner).norm()
                );
            }
        }
        assert!(deviated > 0);
    }

    #[test]
    fn joint_moves_blend_in_joint_space() {
        let mut core = core_at([0.0; 6]);
        let sps = run_all(
            &mut core,
            vec![
                abs_j(1, [30.0, 10.0, 0.0, 0.0, 35.0, 0.0], 1000.0, 50.0),
                abs_j(2, [30.0, 10.0, -30.0, 20.0, 60.0, 0.0], 1000.0, 0.0),
            ],
        );
        assert_axis_speeds(&[0.0; 6], &sps);
        // Axis 3 starts moving before axis 1 has stopped: a corner.
        let overlap = sps.windows(2).any(|w| {
            (w[1].joints[0] - w[0].joints[0]).abs() > 1e-9
                && (w[1].joints[2] - w[0].joints[2]).abs() > 1e-9
        });
        assert!(overlap, "no corner between the joint moves");
        assert_joints(
            &sps.last().unwrap().joints,
            &[30.0, 10.0, -30.0, 20.0, 60.0, 0.0],
            1e-9,
        );
    }

    #[test]
    fn speed_and_time_arguments() {
        let (p0, rot) = start_target();
        let p1 = [p0[0], p0[1] + 200.0, p0[2]];
        // \T 2 s: the move takes 2 s (500 cycles).
        let mut core = core_at(START);
        let sps = run_all(
            &mut core,
            vec![with_time(
                move_l(1, target(p1, rot), 1000.0, 0.0, ToolData::tool0()),
                2.0,
            )],
        );
        assert_eq!(sps.len(), 500);
        // \T replaces the speed data: v10 with \T:=1 takes 1 s, not the 20 s of 10 mm/s.
        let cycles = |from: [f64; 6], cmd: rapidvc::robot::command::MotionCommand, t: f64| {
            run_all(&mut core_at(from), vec![with_time(cmd, t)]).len()
        };
        let line = move_l(1, target(p1, rot), 10.0, 0.0, ToolData::tool0());
        assert_eq!(cycles(START, line, 1.0), 250);
        let joint = abs_j(1, [10.0, 0.0, 0.0, 0.0, 30.0, 0.0], 10.0, 0.0);
        assert_eq!(cycles([0.0; 6], joint, 1.0), 250);
        // Shorter than the axes allow: as fast as they can (axis 1 at 175°/s, 0.25 s ramp).
        let far = abs_j(1, [90.0, 0.0, 0.0, 0.0, 0.0, 0.0], 10.0, 0.0);
        let n = cycles([0.0; 6], far, 0.1);
        assert!(
            (n as f64 * 0.004 - (90.0 / 175.0 + 0.25)).abs() < 0.01,
            "{n}"
        );
        // All axes of a joint move arrive together: the limiting axis sets the duration.
        let mut core = core_at([0.0; 6]);
        let sps = run_all(
            &mut core,
            vec![abs_j(1, [90.0, 0.0, 0.0, 90.0, 0.0, 0.0], 7000.0, 0.0)],
        );
        let moving = |i: usize| sps.iter().filter(|sp| sp.joints[i] < 90.0 - 1e-9).count();
        assert_eq!(moving(0), moving(3));
        // Axis 1 (175°/s, 0.25 s ramp) limits: 90/175 + 0.25 s ≈ 0.764 s.
        assert!(
            (sps.len() as f64 * 0.004 - (90.0 / 175.0 + 0.25)).abs() < 0.01,
            "{}",
            sps.len()
        );
    }
}

mod errors {
    use super::*;
    use rapidvc::motion::{EnqueueError, MotionError, Severity};
    use rapidvc::robot::{KinError, Robot, ToolData, pose_to_pos_quat};

    const START: [f64; 6] = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];

    fn rejected(
        core: &mut rapidvc::motion::MotionCore,
        cmd: rapidvc::robot::command::MotionCommand,
    ) -> MotionError {
        let before = core.state();
        match core.enqueue(cmd) {
            Err(EnqueueError::Rejected(e)) => {
                // Nothing was queued and the robot has not moved.
                let after = core.state();
                assert_eq!(after.pending, before.pending);
                assert_eq!(after.setpoint.joints, before.setpoint.joints);
                let ev = core.take_event().expect("an event");
                assert_eq!(ev.severity, Severity::Error);
                assert_eq!(ev.error, e);
                e
            }
            other => panic!("expected a rejection, got {other:?}"),
        }
    }

    #[test]
    fn unreachable_target_is_refused_before_motion() {
        let (_, rot) = pose_to_pos_quat(&Robot::default().fk(&START));
        let mut core = core_at(START);
        let e = rejected(
            &mut core,
            move_l(
                1,
                target([3000.0, 0.0, 1000.0], rot),
                500.0,
                0.0,
                ToolData::tool0(),
            ),
        );
        assert_eq!(e.event(), Some((50050, "Position outside reach")));
        assert_eq!(e.rapid_error_name(), Some("ERR_OUTSIDE_REACH"));
        let e = rejected(
            &mut core,
            move_j(
                2,
                target([3000.0, 0.0, 1000.0], rot),
                500.0,
                0.0,
                ToolData::tool0(),
            ),
        );
        assert_eq!(e.event().map(|e| e.0), Some(50050));
        // The core still works afterwards.
        let sps = run_all(
            &mut core,
            vec![abs_j(3, [10.0, 0.0, 0.0, 0.0, 35.0, 0.0], 500.0, 0.0)],
        );
        assert!((sps.last().unwrap().joints[0] - 10.0).abs() < 1e-9);
    }

    #[test]
    fn axis_limits_and_wrong_configuration() {
        let mut core = core_at(START);
        let e = rejected(
            &mut core,
            abs_j(1, [0.0, 0.0, 80.0, 0.0, 35.0, 0.0], 500.0, 0.0),
        );
        assert!(matches!(
            e,
            MotionError::Kinematics {
                error: KinError::JointOutOfRange { joint: 3, .. },
                ..
            }
        ));
        assert_eq!(e.event().map(|e| e.0), Some(50027));
        // p30 evaluated with the torch has no solution in conf [0,0,-1,0] (docs/robot.md, "Acceptance facts": the pitfall).
        let e = rejected(&mut core, move_j(2, p30(), 1000.0, 0.0, t_fronius()));
        assert_eq!(e.rapid_error_name(), Some("ERR_ROBLIMIT"));
    }

    #[test]
    fn linear_path_through_the_wrist_singularity_is_refused() {
        let robot = Robot::default();
        let from = [0.0, 0.0, 0.0, 0.0, 10.0, 0.0];
        let (p, rot) = pose_to_pos_quat(&robot.fk(&[0.0, 0.0, 0.0, 0.0, -10.0, 0.0]));
        let mut core = core_at(from);
        let e = rejected(
            &mut core,
            move_l(1, target(p, rot), 200.0, 0.0, ToolData::tool0()),
        );
        assert_eq!(e.event(), Some((50026, "Close to singularity")));
    }

    #[test]
    fn impossible_circle_is_refused() {
        let (p0, rot) = pose_to_pos_quat(&Robot::default().fk(&START));
        let mut core = core_at(START);
        let cir = [p0[0], p0[1] + 100.0, p0[2]];
        let to = [p0[0], p0[1] + 200.0, p0[2]];
        let e = rejected(
            &mut core,
            move_c(
                1,
                target(cir, rot),
                target(to, rot),
                200.0,
                0.0,
                ToolData::tool0(),
            ),
        );
        assert!(matches!(e, MotionError::CircleUncertain { .. }));
    }

    #[test]
    fn bad_data_is_refused() {
        let mut core = core_at(START);
        let e = rejected(&mut core, abs_j(1, [0.0; 6], -5.0, 0.0));
        assert!(matches!(e, MotionError::InvalidData { .. }));
        let e = rejected(&mut core, abs_j(1, [f64::NAN; 6], 100.0, 0.0));
        assert_eq!(e.event().map(|e| e.0), Some(50050));
    }

    #[test]
    fn late_fly_by_becomes_a_stop_point() {
        let (p0, rot) = pose_to_pos_quat(&Robot::default().fk(&START));
        let p1 = [p0[0], p0[1] + 200.0, p0[2]];
        let p2 = [p0[0], p0[1] + 200.0, p0[2] - 200.0];
        let mut core = core_at(START);
        let mut tick = 0;
        core.enqueue(move_l(1, target(p1, rot), 500.0, 50.0, ToolData::tool0()))
            .unwrap();
        let first = run(&mut core, &mut tick);
        assert!(first.last().unwrap().speed < 50.0);
        let ev = core.take_event().expect("corner path failure");
        assert_eq!(ev.error.event(), Some((50024, "Corner path failure")));
        assert_eq!(ev.severity, Severity::Warning);
        core.enqueue(move_l(2, target(p2, rot), 500.0, 0.0, ToolData::tool0()))
            .unwrap();
        run(&mut core, &mut tick);
        assert!(core.take_event().is_none());
    }

    #[test]
    fn queue_is_bounded() {
        let mut core = core_at(START);
        let mut full = false;
        for i in 0..20 {
            let q = [f64::from(i), 0.0, 0.0, 0.0, 35.0, 0.0];
            match core.enqueue(abs_j(i as u64, q, 100.0, 10.0)) {
                Ok(()) => {}
                Err(EnqueueError::QueueFull(cmd)) => {
                    assert_eq!(cmd.id(), i as u64);
                    full = true;
                    break;
                }
                Err(e) => panic!("{e}"),
            }
        }
        assert!(full);
        assert_eq!(
            core.state().pending,
            rapidvc::motion::CoreConfig::default().queue_capacity
        );
    }
}

mod configuration {
    use super::*;
    use rapidvc::motion::{EnqueueError, MotionError};
    use rapidvc::robot::command::MotionCommand;
    use rapidvc::robot::{ConfData, Robot, ToolData, pose_to_pos_quat};

    const START: [f64; 6] = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];

    fn conf_l(robconf: ConfData, check: bool) -> MotionCommand {
        let (p, rot) = pose_to_pos_quat(&Robot::default().fk(&[5.0, 5.0, -5.0, 10.0, 35.0, 10.0]));
        let mut t = target(p, rot);
        t.robconf = robconf;
        let mut cmd = move_l(1, t, 500.0, 0.0, ToolData::tool0());
        if let MotionCommand::MoveL(m) = &mut cmd {
            m.conf_check = check;
        }
        cmd
    }

    #[test]
    fn conf_l_on_checks_the_end_configuration() {
        let mut core = core_at(START);
        let r = core.enqueue(conf_l(ConfData::new(0, 0, 0, 0), true));
        assert!(r.is_ok(), "{r:?}");
        let mut core = core_at(START);
        match core.enqueue(conf_l(ConfData::new(0, 0, 1, 0), true)) {
            Err(EnqueueError::Rejected(MotionError::ConfigurationChanged { wanted, reached })) => {
                assert_eq!(wanted, ConfData::new(0, 0, 1, 0));
                assert_eq!(reached, ConfData::new(0, 0, 0, 0));
            }
            other => panic!("{other:?}"),
        }
        // ConfL\Off ignores the programmed configuration.
        let mut core = core_at(START);
        assert!(
            core.enqueue(conf_l(ConfData::new(0, 0, 1, 1), false))
                .is_ok()
        );
    }
}

mod controller {
    use std::sync::{Arc, Mutex};

    use super::*;
    use rapidvc::controller::{
        ClockMode, Condition, ControllerConfig, ControllerError, ControllerHandle, RealtimeConfig,
        TickSink,
    };
    use rapidvc::motion::{RobotTime, Setpoint};
    use rapidvc::output::{TRACE_HEADER, TraceWriter};
    use rapidvc::robot::command::MotionCommand;
    use rapidvc::robot::{Robot, ToolData, pose_to_pos_quat};

    const START: [f64; 6] = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];

    /// A trace sink writing into shared memory.
    struct SharedTrace(
        Arc<Mutex<Option<TraceWriter<Vec<u8>>>>>,
        Arc<Mutex<Vec<u8>>>,
    );

    impl TickSink for SharedTrace {
        fn record(&mut self, sp: &Setpoint) {
            if let Some(w) = self.0.lock().unwrap().as_mut() {
                w.record(sp);
            }
        }
        fn finish(&mut self) -> Result<(), String> {
            let w = self.0.lock().unwrap().take().ok_or("finished twice")?;
            *self.1.lock().unwrap() = w.into_inner()?;
            Ok(())
        }
    }

    fn program() -> Vec<MotionCommand> {
        let (p0, rot) = pose_to_pos_quat(&Robot::default().fk(&START));
        let p = |dx: f64, dy: f64, dz: f64| target([p0[0] + dx, p0[1] + dy, p0[2] + dz], rot);
        vec![
            move_j(1, p30(), 1000.0, 0.0, ToolData::tool0()),
            move_l(2, p(0.0, 200.0, 0.0), 500.0, 20.0, ToolData::tool0()),
            move_l(3, p(-100.0, 200.0, -150.0), 500.0, 20.0, ToolData::tool0()),
            move_c(
                4,
                p(-150.0, 100.0, -200.0),
                p(-100.0, 0.0, -250.0),
                300.0,
                10.0,
                ToolData::tool0(),
            ),
            abs_j(5, START, 1000.0, 0.0),
        ]
    }

    /// Run `program()` like an interpreter would: submit everything, wait at the end.
    fn run_virtual() -> (Vec<u8>, rapidvc::controller::RunSummary) {
        let out = Arc::new(Mutex::new(Vec::new()));
        let writer = Arc::new(Mutex::new(Some(TraceWriter::new(Vec::new(), None))));
        let sink = SharedTrace(writer, Arc::clone(&out));
        let mut c = ControllerHandle::start(
            ControllerConfig::new(Robot::default(), START),
            vec![Box::new(sink)],
        )
        .unwrap();
        for cmd in program() {
            let fine = matches!(&cmd, MotionCommand::MoveJ(_) | MotionCommand::MoveAbsJ(_));
            let id = cmd.id();
            c.submit(cmd).unwrap();
            if fine {
                c.wait_until(Condition::Done(id)).unwrap();
            }
        }
        c.wait_until(Condition::InPos).unwrap();
        let summary = c.finish().unwrap();
        let bytes = out.lock().unwrap().clone();
        (bytes, summary)
    }

    #[test]
    fn virtual_time_traces_are_byte_identical() {
        let (a, sa) = run_virtual();
        let (b, sb) = run_virtual();
        assert!(a.len() > 10_000);
        assert_eq!(a, b, "two virtual-time runs differ");
        assert_eq!(sa.ticks, sb.ticks);
        let text = String::from_utf8(a).unwrap();
        let header = text.lines().next().unwrap();
        assert_eq!(header, TRACE_HEADER.join(","));
        assert!(header.starts_with("time_s,j1,j2,j3,j4,j5,j6,x,y,z,q1,q2,q3,q4"));
        // One row per cycle plus the initial position.
        assert_eq!(text.lines().count() as u64, sa.ticks + 2);
        let first = text.lines().nth(1).unwrap();
        assert!(
            first.starts_with("0.000000,0.000000,0.000000,0.000000,0.000000,35.000000,0.000000,"),
            "{first}"
        );
        assert!(text.lines().nth(2).unwrap().starts_with("0.004000,"));
        assert!(text.contains(",MoveC,4,"));
        // The summary line.
        let line = sa.to_string();
        assert!(line.starts_with("simulated "), "{line}");
        assert!(
            line.contains("final joints [0.00, 0.00, 0.00, 0.00, 35.00, 0.00]"),
            "{line}"
        );
    }

    #[test]
    fn virtual_time_advances_only_while_waiting() {
        let mut c = ControllerHandle::start(ControllerConfig::new(Robot::default(), START), vec![])
            .unwrap();
        assert_eq!(c.now(), RobotTime::ZERO);
        c.submit(abs_j(1, [20.0, 0.0, 0.0, 0.0, 35.0, 0.0], 1000.0, 0.0))
            .unwrap();
        // Submitting does not move time.
        assert_eq!(c.now(), RobotTime::ZERO);
        let st = c.wait_until(Condition::Done(1)).unwrap();
        assert!((st.setpoint.joints[0] - 20.0).abs() < 1e-9);
        let t_done = c.now();
        assert!(t_done > RobotTime::ZERO);
        // Already true: no time passes.
        c.wait_until(Condition::InPos).unwrap();
        assert_eq!(c.now(), t_done);
        // WaitTime 0.1 s: 25 cycles, then stop.
        let until = t_done.saturating_add(std::time::Duration::from_millis(100));
        c.wait_until(Condition::TimeReached(until)).unwrap();
        assert_eq!(c.now(), until);
        // Waiting for a move that was never submitted would never end.
        assert!(matches!(
            c.wait_until(Condition::Done(99)),
            Err(ControllerError::NeverSatisfied(_))
        ));
        // A predicate: wait until axis 1 passes 10° on the way back.
        c.submit(abs_j(2, START, 1000.0, 0.0)).unwrap();
        let st = c
            .wait_until(Condition::Predicate(Box::new(|s| {
                s.setpoint.joints[0] < 10.0
            })))
            .unwrap();
        assert!(st.setpoint.joints[0] < 10.0 && st.setpoint.joints[0] > 5.0);
        c.wait_until(Condition::InPos).unwrap();
        c.finish().unwrap();
    }

    #[test]
    fn a_full_queue_blocks_submit_and_runs_cycles() {
        let mut c = ControllerHandle::start(ControllerConfig::new(Robot::default(), START), vec![])
            .unwrap();
        for i in 0..30u32 {
            let q = [f64::from(i % 5) * 2.0, 0.0, 0.0, 0.0, 35.0, 0.0];
            c.submit(abs_j(u64::from(i) + 1, q, 1000.0, 5.0)).unwrap();
        }
        // RAPID ran ahead of the robot by at most the queue length.
        let st = c.state();
        assert!(st.pending <= rapidvc::motion::CoreConfig::default().queue_capacity);
        assert!(c.now() > RobotTime::ZERO);
        c.wait_until(Condition::InPos).unwrap();
        assert!(c.state().done(30));
    }

    #[test]
    fn refused_moves_report_abb_events() {
        let mut c = ControllerHandle::start(ControllerConfig::new(Robot::default(), START), vec![])
            .unwrap();
        let (_, rot) = pose_to_pos_quat(&Robot::default().fk(&START));
        let err = c.submit(move_l(
            1,
            target([3000.0, 0.0, 0.0], rot),
            100.0,
            0.0,
            ToolData::tool0(),
        ));
        match err {
            Err(ControllerError::Rejected(e)) => assert_eq!(e.event().map(|e| e.0), Some(50050)),
            other => panic!("{other:?}"),
        }
        let events = c.take_events();
        assert_eq!(events.len(), 1);
        assert!(
            events[0]
                .to_string()
                .starts_with("50050 Position outside reach"),
            "{}",
            events[0]
        );
        assert_eq!(c.now(), RobotTime::ZERO);
    }

    #[test]
    fn real_time_mode_runs_the_same_moves() {
        let mut cfg = ControllerConfig::new(Robot::default(), START);
        cfg.clock = ClockMode::RealTime(RealtimeConfig::Ignore);
        let mut c = ControllerHandle::start(cfg, vec![]).unwrap();
        c.submit(abs_j(1, [5.0, 0.0, 0.0, 0.0, 35.0, 0.0], 1000.0, 0.0))
            .unwrap();
        let st = c.wait_until(Condition::Done(1)).unwrap();
        assert!((st.setpoint.joints[0] - 5.0).abs() < 1e-9);
        let (_, rot) = pose_to_pos_quat(&Robot::default().fk(&START));
        assert!(matches!(
            c.submit(move_l(
                2,
                target([3000.0, 0.0, 0.0], rot),
                100.0,
                0.0,
                ToolData::tool0()
            )),
            Err(ControllerError::Rejected(_))
        ));
        let summary = c.finish().unwrap();
        assert!(summary.realtime);
        assert!(summary.ticks > 10);
        assert!((summary.final_joints[0] - 5.0).abs() < 1e-9);
        assert!(summary.period_stats.is_some());
    }
}

mod plots {
    use super::*;
    use rapidvc::controller::{Condition, ControllerConfig, ControllerHandle};
    use rapidvc::output::PlotRecorder;
    use rapidvc::robot::{Robot, ToolData, pose_to_pos_quat};

    const START: [f64; 6] = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];

    #[test]
    fn plots_render_to_svg_and_png() {
        let dir = std::env::temp_dir().join(format!("rapidvc-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let svg = dir.join("run.svg");
        let png = dir.join("run.png");
        let sinks: Vec<Box<dyn rapidvc::controller::TickSink>> = vec![
            Box::new(PlotRecorder::new(&svg, "motion test", None).unwrap()),
            Box::new(PlotRecorder::new(&png, "rapidvc — MoveJ/MoveL/MoveC demo", None).unwrap()),
        ];
        let mut c =
            ControllerHandle::start(ControllerConfig::new(Robot::default(), START), sinks).unwrap();
        let (p0, rot) = pose_to_pos_quat(&Robot::default().fk(&START));
        let p = |dx: f64, dy: f64, dz: f64| target([p0[0] + dx, p0[1] + dy, p0[2] + dz], rot);
        for cmd in [
            move_j(1, p30(), 1000.0, 0.0, ToolData::tool0()),
            abs_j(2, START, 1000.0, 50.0),
            move_l(3, p(0.0, 300.0, 0.0), 800.0, 30.0, ToolData::tool0()),
            move_l(4, p(-200.0, 300.0, -200.0), 800.0, 30.0, ToolData::tool0()),
            move_c(
                5,
                p(-250.0, 150.0, -250.0),
                p(-200.0, 0.0, -300.0),
                400.0,
                0.0,
                ToolData::tool0(),
            ),
            abs_j(6, START, 1000.0, 0.0),
        ] {
            c.submit(cmd).unwrap();
        }
        c.wait_until(Condition::InPos).unwrap();
        c.finish().unwrap();
        let svg_text = std::fs::read_to_string(&svg).unwrap();
        assert!(
            svg_text.contains("<svg")
                && svg_text.contains("Joint angles")
                && svg_text.contains("MoveC")
        );
        let png_bytes = std::fs::read(&png).unwrap();
        assert!(png_bytes.starts_with(b"\x89PNG"));
        assert!(PlotRecorder::new(&dir.join("run.pdf"), "x", None).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

mod settings_and_guidance {
    use super::*;
    use rapidvc::motion::{
        EnqueueError, ExternalGuidance, GuidanceStep, MotionError, MotionSettings, RobotTime,
        Setpoint, Severity, SingArea,
    };
    use rapidvc::robot::{JointsDeg, Robot, ToolData, pose_to_pos_quat};

    const START: [f64; 6] = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];

    #[test]
    fn sing_area_wrist_passes_the_wrist_singularity() {
        let robot = Robot::default();
        let from = [0.0, 0.0, 0.0, 0.0, 10.0, 0.0];
        let (p, rot) = pose_to_pos_quat(&robot.fk(&[0.0, 0.0, 0.0, 0.0, -10.0, 0.0]));
        let mut core = core_at(from);
        core.set_settings(MotionSettings {
            singarea: SingArea::Wrist,
            ..MotionSettings::default()
        });
        // The straight path bends axis 5 through 0° (axes 4 and 6 stay put): refused under
        // SingArea\Off (see errors::linear_path_through_the_wrist_singularity_is_refused),
        // executed under \Wrist.
        core.enqueue(move_l(1, target(p, rot), 200.0, 0.0, ToolData::tool0()))
            .unwrap();
        let mut tick = 0;
        let sps = run(&mut core, &mut tick);
        super::geo::assert_axis_speeds(&from, &sps);
        let end = robot.fk(&sps.last().unwrap().joints);
        assert!((end.translation.vector - nalgebra::Vector3::from(p)).norm() < 1e-6);
        assert!(
            sps.iter().any(|sp| sp.joints[4].abs() < 0.5),
            "passes J5 = 0"
        );
        assert!(core.take_event().is_none());
    }

    #[test]
    fn vel_set_and_acc_set_slow_moves_down() {
        let cmd = || abs_j(1, [60.0, 0.0, 0.0, 0.0, 35.0, 0.0], 7000.0, 0.0);
        let mut core = core_at(START);
        let normal = run_all(&mut core, vec![cmd()]).len();
        let mut core = core_at(START);
        let mut s = MotionSettings::default();
        s.velset.override_pct = 50.0;
        core.set_settings(s);
        let half = run_all(&mut core, vec![cmd()]).len();
        // Axis speeds halve, accelerations stay: 0.59 s becomes 0.81 s.
        assert!(half as f64 > 1.3 * normal as f64, "{normal} vs {half}");
        let mut core = core_at(START);
        let mut s = MotionSettings::default();
        s.accset.acc_pct = 25.0;
        core.set_settings(s);
        let soft = run_all(&mut core, vec![cmd()]).len();
        assert!(soft > normal, "{normal} vs {soft}");
    }

    #[test]
    fn stationary_tool_moves_the_work_object_in_a_straight_line() {
        use rapidvc::robot::command::MotionCommand;
        use rapidvc::robot::{WobjData, pose_from_pos_quat};
        let robot = Robot::default();
        // A fixed torch in front of the robot, pointing up; the robot holds the part.
        let tool = ToolData {
            robhold: false,
            tframe: pose_from_pos_quat([1300.0, 0.0, 900.0], [1.0, 0.0, 0.0, 0.0]),
            ..ToolData::tool0()
        };
        let wobj = WobjData {
            robhold: true,
            uframe: pose_from_pos_quat([0.0, 0.0, 100.0], [1.0, 0.0, 0.0, 0.0]),
            ..WobjData::wobj0()
        };
        // Where the torch is in the object frame now, and 100 mm further along object y.
        let here = rapidvc::robot::frames::target_from_flange(
            &robot.fk(&START),
            &tool,
            &wobj,
            &rapidvc::robot::Pose::identity(),
        );
        let (p, rot) = pose_to_pos_quat(&here);
        let to = target([p[0], p[1] + 100.0, p[2]], rot);
        let mut cmd = move_l(1, to, 200.0, 0.0, tool);
        if let MotionCommand::MoveL(m) = &mut cmd {
            m.args.wobj = wobj.clone();
        }
        let mut core = core_at(START);
        let sps = run_all(&mut core, vec![cmd]);
        // In the object frame, the torch moves along a straight line.
        for sp in &sps {
            let t = robot.tcp_pose(&sp.joints, &tool, &wobj).translation.vector;
            assert!(
                (t.x - p[0]).abs() < 0.1 && (t.z - p[2]).abs() < 0.1,
                "{t:?}"
            );
            // The trace's TCP is the fixed torch.
            assert!((sp.tcp.translation.vector - tool.tframe.translation.vector).norm() < 1e-9);
        }
        super::geo::assert_axis_speeds(&START, &sps);
    }

    /// Moves axis 1 at `step` degrees per cycle for `n` cycles.
    struct JogState {
        step: f64,
        n: usize,
    }

    /// The guidance of a [`JogState`] the test keeps a handle on (the shell's typed access).
    struct Jog(std::sync::Arc<std::sync::Mutex<JogState>>);

    /// A jog and the test's handle on its state.
    fn jog(step: f64, n: usize) -> (Box<Jog>, std::sync::Arc<std::sync::Mutex<JogState>>) {
        let state = std::sync::Arc::new(std::sync::Mutex::new(JogState { step, n }));
        (Box::new(Jog(std::sync::Arc::clone(&state))), state)
    }

    impl ExternalGuidance for Jog {
        fn step(&mut self, _now: RobotTime, current: &JointsDeg) -> GuidanceStep {
            let mut j = self.0.lock().unwrap();
            if j.n == 0 {
                return GuidanceStep::Finished;
            }
            j.n -= 1;
            let mut q = *current;
            q[0] += j.step;
            GuidanceStep::MoveTo(q)
        }
    }

    #[test]
    fn external_guidance_is_supervised() {
        let mut core = core_at(START);
        // Only at a stop point.
        core.enqueue(abs_j(1, [10.0, 0.0, 0.0, 0.0, 35.0, 0.0], 1000.0, 0.0))
            .unwrap();
        core.tick(RobotTime::from_nanos(4_000_000));
        assert_eq!(
            core.start_external(jog(0.1, 10).0, ToolData::tool0(), None),
            Err(MotionError::NotAtStopPoint)
        );
        let mut tick = 1;
        run(&mut core, &mut tick);
        let (guidance, handle) = jog(0.1, 10);
        core.start_external(guidance, ToolData::tool0(), None)
            .unwrap();
        assert!(matches!(
            core.enqueue(abs_j(2, START, 1000.0, 0.0)),
            Err(EnqueueError::Rejected(MotionError::ExternalGuidance))
        ));
        while core.take_event().is_some() {}
        // The shell reaches the running guidance between cycles.
        assert_eq!(handle.lock().unwrap().n, 10);
        for _ in 0..12 {
            tick += 1;
            core.tick(RobotTime::from_nanos(tick * 4_000_000));
        }
        let st = core.state();
        assert!(
            (st.setpoint.joints[0] - 11.0).abs() < 1e-9,
            "{:?}",
            st.setpoint.joints
        );
        assert_eq!(st.mode, rapidvc::motion::CoreMode::Planned);
        // Planned motion resumes from where guidance left the robot.
        let sps = run_all(&mut core, vec![abs_j(3, START, 1000.0, 0.0)]);
        assert!(sps.last().unwrap().joints[0].abs() < 1e-9);
        // A reference faster than axis 1 allows (175°/s = 0.7° per cycle) stops the robot.
        core.start_external(jog(2.0, 10).0, ToolData::tool0(), None)
            .unwrap();
        tick += 1000;
        let sp = core.tick(RobotTime::from_nanos(tick * 4_000_000));
        assert!(sp.standstill && sp.joints == START);
        let st = core.state();
        assert!(st.halted);
        let ev = core.take_event().unwrap();
        assert_eq!(ev.severity, Severity::Error);
        assert!(
            matches!(ev.error, MotionError::JointSpeed { joint: 1, .. }),
            "{ev}"
        );
        // Halted until recovered.
        assert!(matches!(
            core.enqueue(abs_j(4, START, 1000.0, 0.0)),
            Err(EnqueueError::Rejected(MotionError::Halted))
        ));
        core.recover();
        assert!(
            core.enqueue(abs_j(5, [1.0, 0.0, 0.0, 0.0, 35.0, 0.0], 1000.0, 0.0))
                .is_ok()
        );
    }

    /// Jogs axis 1 at `steps[k]` degrees in cycle k, then ends.
    struct Schedule {
        steps: Vec<f64>,
    }

    impl ExternalGuidance for Schedule {
        fn step(&mut self, _now: RobotTime, current: &JointsDeg) -> GuidanceStep {
            if self.steps.is_empty() {
                return GuidanceStep::Finished;
            }
            let mut q = *current;
            q[0] += self.steps.remove(0);
            GuidanceStep::MoveTo(q)
        }
    }

    /// Axis speeds (deg/s) of consecutive setpoints.
    fn speeds(sps: &[Setpoint]) -> Vec<JointsDeg> {
        sps.windows(2)
            .map(|w| std::array::from_fn(|i| (w[1].joints[i] - w[0].joints[i]) / 0.004))
            .collect()
    }

    /// A motion error while the robot moves at 125 °/s does not freeze it in one cycle: it
    /// brakes within axis 1's 700 °/s² (45 cycles), and the core halts once at rest.
    #[test]
    fn a_motion_error_brakes_to_rest_within_the_accelerations_then_halts() {
        let mut core = core_at(START);
        let mut steps = vec![0.5; 20];
        steps.push(2.0);
        core.start_external(Box::new(Schedule { steps }), ToolData::tool0(), None)
            .unwrap();
        let mut sps = vec![core.state().setpoint];
        for tick in 1..=100u64 {
            sps.push(core.tick(RobotTime::from_nanos(tick * 4_000_000)));
        }
        let ev = core.take_event().unwrap();
        assert!(
            matches!(ev.error, MotionError::JointSpeed { joint: 1, .. }),
            "{ev}"
        );
        let v = speeds(&sps);
        assert!((v[19][0] - 125.0).abs() < 1e-9, "{:?}", v[19]);
        let accel = Robot::default().model().max_accel[0];
        for w in v[19..].windows(2) {
            assert!(w[1][0] <= w[0][0] + 1e-9, "{} → {}", w[0][0], w[1][0]);
            assert!((w[0][0] - w[1][0]) / 0.004 <= accel + 1e-6);
        }
        let rest = 20 + v[20..].iter().position(|v| v[0] == 0.0).unwrap();
        assert_eq!(rest - 20, 44, "45 braking cycles, the last at rest");
        assert!(sps[rest + 1].standstill);
        assert!(core.state().halted);
    }

    /// A program stop during a planned move brakes within the accelerations; the core is
    /// not halted and plans the next move from where the robot came to rest.
    #[test]
    fn stop_brakes_a_planned_move_and_planning_resumes_there() {
        let mut core = core_at(START);
        core.enqueue(abs_j(1, [90.0, 0.0, 0.0, 0.0, 35.0, 0.0], 1000.0, 0.0))
            .unwrap();
        let mut sps = vec![core.state().setpoint];
        let mut tick = 0u64;
        for _ in 0..100 {
            tick += 1;
            sps.push(core.tick(RobotTime::from_nanos(tick * 4_000_000)));
        }
        let cruise = speeds(&sps).last().unwrap()[0];
        assert!(cruise > 50.0, "{cruise}");
        core.stop();
        while core.state().moving {
            tick += 1;
            sps.push(core.tick(RobotTime::from_nanos(tick * 4_000_000)));
            assert!(sps.len() < 400, "the brake never ended");
        }
        core.plan_from_here();
        let accel = Robot::default().model().max_accel;
        let v = speeds(&sps);
        for w in v[99..].windows(2) {
            for i in 0..6 {
                assert!(w[1][i].abs() <= w[0][i].abs() + 1e-9);
                assert!((w[0][i] - w[1][i]).abs() / 0.004 <= accel[i] + 1e-6);
            }
        }
        let st = core.state();
        assert!(!st.halted && st.setpoint.standstill);
        let here = st.setpoint.joints;
        assert!(here[0] > sps[100].joints[0] && here[0] < 90.0, "{here:?}");
        let more = run_all(&mut core, vec![abs_j(2, START, 1000.0, 0.0)]);
        let first = more.first().unwrap().joints;
        assert!((first[0] - here[0]).abs() < 1.0, "{first:?} after {here:?}");
    }

    /// Feeds the running `Jog` a new step before every cycle and counts cycles.
    struct Feeder {
        before: usize,
        jog: std::sync::Arc<std::sync::Mutex<JogState>>,
    }

    impl rapidvc::controller::CycleHook for Feeder {
        fn before_tick(&mut self, _now: RobotTime, exec: &mut rapidvc::motion::Executor) {
            self.before += 1;
            if exec.state().mode == rapidvc::motion::CoreMode::External {
                self.jog.lock().unwrap().step = 0.5;
            }
        }
    }

    #[test]
    fn the_cycle_hook_reaches_the_guidance() {
        use rapidvc::controller::{Condition, ControllerConfig, ControllerHandle};
        use rapidvc::motion::CoreMode;
        let (guidance, handle) = jog(0.0, 4);
        let mut c = ControllerHandle::start_with_hook(
            ControllerConfig::new(Robot::default(), START),
            vec![],
            Some(Box::new(Feeder {
                before: 0,
                jog: handle,
            })),
        )
        .unwrap();
        c.start_external(guidance, ToolData::tool0(), None).unwrap();
        // 4 cycles of 0.5° (the step the hook sets), then the guidance ends.
        let st = c
            .wait_until(Condition::Predicate(Box::new(|s| {
                s.mode == CoreMode::Planned
            })))
            .unwrap();
        assert!(
            (st.setpoint.joints[0] - 2.0).abs() < 1e-9,
            "{:?}",
            st.setpoint.joints
        );
        assert_eq!(c.finish().unwrap().ticks, 5);
    }
}

mod config {
    use rapidvc::controller::{ControllerConfig, ControllerError, ControllerHandle};
    use rapidvc::motion::{CoreConfig, MotionCore, RobotTime};
    use rapidvc::robot::Robot;

    #[test]
    fn unusable_configuration_is_clamped_or_refused() {
        let mut cfg = ControllerConfig::new(Robot::default(), [0.0, 0.0, 100.0, 0.0, 0.0, 0.0]);
        assert!(matches!(
            ControllerHandle::start(cfg.clone(), vec![]),
            Err(ControllerError::InvalidStart(_))
        ));
        cfg.start = [f64::NAN; 6];
        assert!(matches!(
            ControllerHandle::start(cfg, vec![]),
            Err(ControllerError::InvalidStart(_))
        ));
        // A zero period and an empty queue are clamped, not a panic or a division by zero.
        let bad = CoreConfig {
            period: std::time::Duration::ZERO,
            queue_capacity: 0,
            event_capacity: 0,
        };
        let mut core = MotionCore::new(Robot::default(), bad, [0.0, 0.0, 0.0, 0.0, 35.0, 0.0]);
        core.enqueue(super::abs_j(1, [1.0, 0.0, 0.0, 0.0, 35.0, 0.0], 100.0, 0.0))
            .unwrap();
        for k in 1..100_000u64 {
            core.tick(RobotTime::from_nanos(k * 100_000));
            if core.state().in_position() {
                break;
            }
        }
        assert!(core.state().in_position());
    }
}

mod cli {

    #[test]
    fn robots_lists_models_with_reach_and_limits() {
        let out = rapidvc_testkit::rapidvc!().arg("robots").output().unwrap();
        assert!(out.status.success());
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(
            text.starts_with("IRB 2600-12/1.85  (default)\n  reach 1853 mm"),
            "{text}"
        );
        assert!(
            text.contains("IRB 120-3/0.58") && text.contains("IRB 6700-200/2.60"),
            "{text}"
        );
        let out = rapidvc_testkit::rapidvc!()
            .args(["robots", "--robot", "irb120"])
            .output()
            .unwrap();
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(
            text.contains("min (°)            -165     -110     -110     -160     -120     -400"),
            "{text}"
        );
        let out = rapidvc_testkit::rapidvc!()
            .args(["robots", "--robot", "irb9999"])
            .output()
            .unwrap();
        assert!(!out.status.success());
        assert!(
            String::from_utf8_lossy(&out.stderr)
                .contains("unknown or ambiguous robot model 'irb9999'")
        );
    }
}

mod properties {
    use super::*;
    use proptest::prelude::*;
    use rapidvc::motion::EnqueueError;
    use rapidvc::robot::{Robot, ToolData};

    const START: [f64; 6] = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];

    fn command() -> impl Strategy<Value = (u8, [f64; 3], f64, f64, f64)> {
        (
            0u8..4,
            [500.0f64..1900.0, -1200.0f64..1200.0, 100.0f64..2000.0],
            -60.0f64..60.0,
            50.0f64..3000.0,
            prop_oneof![Just(0.0), 1.0f64..100.0],
        )
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

        /// Any mix of moves (reachable or not, fine or fly-by): no panic, every cycle inside
        /// the axis ranges and speed limits, and the robot ends at rest.
        #[test]
        fn moves_never_leave_limits(cmds in proptest::collection::vec(command(), 1..6)) {
            let robot = Robot::default();
            let model = robot.model();
            let mut core = core_at(START);
            let mut tick = 0;
            let mut all = Vec::new();
            for (i, (kind, p, turn, v, z)) in cmds.into_iter().enumerate() {
                let a = turn.to_radians() / 2.0;
                let t = target(p, [0.0, -a.sin(), a.cos(), 0.0]);
                let id = i as u64 + 1;
                let cmd = match kind {
                    0 => move_l(id, t, v, z, ToolData::tool0()),
                    1 => {
                        let mut c = move_j(id, t, v, z, ToolData::tool0());
                        if let rapidvc::robot::command::MotionCommand::MoveJ(m) = &mut c {
                            m.conf_check = false;
                        }
                        c
                    }
                    2 => abs_j(id, [p[1] / 10.0, turn / 2.0, -turn / 2.0, turn, 30.0 + turn / 3.0, -turn], v, z),
                    _ => {
                        let cir = target([p[0] - 100.0, p[1] + 100.0, p[2]], t.rot);
                        move_c(id, cir, t, v, z, ToolData::tool0())
                    }
                };
                match core.enqueue(cmd) {
                    Ok(()) | Err(EnqueueError::Rejected(_)) => {}
                    Err(EnqueueError::QueueFull(_)) => prop_assert!(false, "queue full"),
                }
            }
            // Everything queued first: fly-by points get their corner paths.
            all.extend(run(&mut core, &mut tick));
            let dt = DT.as_secs_f64();
            let mut prev = START;
            for sp in &all {
                for (((q, p), l), vmax) in sp.joints.iter().zip(&prev).zip(&model.joint_limits).zip(&model.max_speed) {
                    prop_assert!(*q >= l.min - 1e-9 && *q <= l.max + 1e-9);
                    prop_assert!((q - p).abs() / dt <= vmax * (1.0 + 1e-9));
                }
                prev = sp.joints;
            }
            prop_assert!(core.state().in_position());
            prop_assert!(!core.state().halted);
        }
    }
}
