//! Motion core costs on the default robot: one motion cycle (`MotionCore::tick`), and planning
//! a linear and a joint move (IK of every cycle included): `cargo bench --bench motion`.
//! The virtual-time factor and real-time jitter are measured by `rapidvc bench`.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use rapidvc::motion::{CoreConfig, MotionCore, Planner, RobotTime};
use rapidvc::robot::command::{
    EXTAX_NONE, JointTarget, MotionCommand, MoveAbsJ, MoveArgs, MoveJ, MoveL, RobTarget, SpeedData,
    SpeedOverride, ZoneData,
};
use rapidvc::robot::{ConfData, Pose, Robot, ToolData, WobjData, pose_to_pos_quat};
use rapidvc_testkit::fixed_iters::{Runner, mark};

const START: [f64; 6] = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];
const DT: Duration = Duration::from_millis(4);

fn args(speed: f64) -> MoveArgs {
    MoveArgs {
        id: 1,
        source: None,
        speed: SpeedData::v(speed),
        speed_override: None,
        zone: ZoneData::FINE,
        tool: ToolData::tool0(),
        wobj: WobjData::wobj0(),
        tload: None,
        pdisp: Pose::identity(),
    }
}

fn target(dy: f64, dz: f64) -> RobTarget {
    let (p, rot) = pose_to_pos_quat(&Robot::default().fk(&START));
    RobTarget {
        trans: [p[0] - 200.0, p[1] + dy, p[2] + dz],
        rot,
        robconf: ConfData::default(),
        extax: EXTAX_NONE,
    }
}

fn motion(c: &mut Criterion) {
    let mut r = Runner::new(c);
    // One cycle while a long joint move plays (planning excluded from the timing).
    r.iter_custom("tick", |iters| {
        let mut total = Duration::ZERO;
        let mut left = iters;
        while left > 0 {
            let n = left.min(200_000);
            let mut core = MotionCore::new(Robot::default(), CoreConfig::default(), START);
            let mut cmd = MoveAbsJ {
                args: args(100.0),
                target: JointTarget {
                    robax: [90.0, 20.0, -20.0, 90.0, 60.0, 90.0],
                    extax: EXTAX_NONE,
                },
                no_eoffs: false,
            };
            cmd.args.speed_override = Some(SpeedOverride::T((n + 10) as f64 * DT.as_secs_f64()));
            core.enqueue(MotionCommand::MoveAbsJ(cmd)).ok();
            let start = Instant::now();
            mark();
            for k in 1..=n {
                black_box(core.tick(RobotTime::from_nanos(k * 4_000_000)));
            }
            mark();
            total += start.elapsed();
            left -= n;
        }
        total
    });

    let movel = MotionCommand::MoveL(MoveL {
        args: args(1000.0),
        target: target(500.0, -100.0),
        conf_check: false,
    });
    r.iter_batched(
        "plan_movel_510mm_v1000",
        || Planner::new(Robot::default(), DT, START),
        |mut p| black_box(p.plan(&movel).is_ok()),
        BatchSize::SmallInput,
    );

    let movej = MotionCommand::MoveJ(MoveJ {
        args: args(1000.0),
        target: target(500.0, -100.0),
        conf_check: false,
    });
    r.iter_batched(
        "plan_movej_v1000",
        || Planner::new(Robot::default(), DT, START),
        |mut p| black_box(p.plan(&movej).is_ok()),
        BatchSize::SmallInput,
    );
}

criterion_group!(benches, motion);
criterion_main!(benches);
