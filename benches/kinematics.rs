//! FK and IK time per call on the default robot (IRB 2600-12/1.85):
//! `cargo bench --bench kinematics`.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use rapidvc::robot::{ConfData, Robot, default_model};

fn kinematics(c: &mut Criterion) {
    let robot = Robot::new(default_model());
    // The manual's p30 joints: a regular pose with 8 arm solutions in reach.
    let q = [83.498, 0.077, -0.340, 0.103, 39.066, -0.136];
    let pose = robot.fk(&q);
    let conf = ConfData::new(0, 0, -1, 0);
    let near = [83.0, 0.0, 0.0, 0.0, 39.0, 0.0];

    c.bench_function("fk", |b| b.iter(|| robot.fk(black_box(&q))));
    c.bench_function("ik_all", |b| b.iter(|| robot.ik_all(black_box(&pose))));
    c.bench_function("ik_conf", |b| {
        b.iter(|| robot.ik_conf(black_box(&pose), black_box(&conf)))
    });
    c.bench_function("ik_nearest", |b| {
        b.iter(|| robot.ik_nearest(black_box(&pose), black_box(&near)))
    });
    c.bench_function("conf_of", |b| b.iter(|| robot.conf_of(black_box(&q))));
    c.bench_function("near_singularity", |b| {
        b.iter(|| robot.near_singularity(black_box(&q)))
    });
}

criterion_group!(benches, kinematics);
criterion_main!(benches);
