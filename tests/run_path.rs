//! Path recovery and acceleration limits checked on the trace of `tests/run/motion`
//! programs (their TP output is golden in tests/run_motion.rs): StopMove holds the robot on
//! its path within the accelerations a planned move uses, StartMove resumes it, StorePath /
//! RestoPath continue the interrupted move, SpeedRefresh halves the speed, PathAccLim and
//! WorldAccLim bound the TCP acceleration.

use rapidvc_testkit::csv::Csv;
use rapidvc_testkit::{procs, rapidvc};

use std::path::PathBuf;

/// Run `program` of `tests/run/motion` with a trace in a scratch directory named after
/// `test`; the trace.
fn trace_of(program: &str, test: &str) -> Csv {
    let dir = std::env::temp_dir().join(format!("rapidvc-path-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let trace = dir.join("trace.csv");
    let motion = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/run/motion");
    let (code, stdout, stderr) = procs::output_in(
        rapidvc!(),
        &motion,
        &[
            "run",
            program,
            "--trace",
            trace.to_str().expect("utf-8 path"),
        ],
        100,
    );
    assert_eq!(code, 0, "{stdout}{stderr}");
    let c = Csv::read(&trace);
    let _ = std::fs::remove_dir_all(&dir);
    c
}

/// One row's numbers.
struct Row {
    t: f64,
    q: [f64; 6],
    p: [f64; 3],
    speed: f64,
    line: String,
    id: String,
}

fn rows(c: &Csv) -> Vec<Row> {
    let (t, j1, x, speed, line, id) = (
        c.col("time_s"),
        c.col("j1"),
        c.col("x"),
        c.col("speed_mm_s"),
        c.col("line"),
        c.col("id"),
    );
    let n = |r: &Vec<String>, i: usize| -> f64 { r[i].parse().expect("number") };
    c.rows
        .iter()
        .map(|r| Row {
            t: n(r, t),
            q: std::array::from_fn(|k| n(r, j1 + k)),
            p: std::array::from_fn(|k| n(r, x + k)),
            speed: n(r, speed),
            line: r[line].clone(),
            id: r[id].clone(),
        })
        .collect()
}

/// The largest axis acceleration (deg/s²) over `rows`, from second differences.
fn max_axis_accel(rows: &[Row]) -> f64 {
    rows.windows(3)
        .map(|w| {
            let dt = w[1].t - w[0].t;
            (0..6)
                .map(|k| ((w[2].q[k] - 2.0 * w[1].q[k] + w[0].q[k]) / (dt * dt)).abs())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

/// The largest TCP acceleration (mm/s²) over `rows`, from second differences.
fn max_tcp_accel(rows: &[Row]) -> f64 {
    rows.windows(3)
        .map(|w| {
            let dt = w[1].t - w[0].t;
            let a: f64 = (0..3)
                .map(|k| ((w[2].p[k] - 2.0 * w[1].p[k] + w[0].p[k]) / (dt * dt)).powi(2))
                .sum();
            a.sqrt()
        })
        .fold(0.0, f64::max)
}

#[test]
fn stopmove_holds_on_the_path_and_startmove_resumes() {
    let c = trace_of("stopmove.mod", "hold");
    let all = rows(&c);
    // `MoveL p20, v200, fine, tool0` (line 34): from p10 to p20 along y at x 1100, z 800.
    let mv: Vec<&Row> = all.iter().filter(|r| r.line == "34").collect();
    assert!(mv.len() > 100, "rows of the MoveL");
    for r in &mv {
        assert!(
            (r.p[0] - 1100.0).abs() < 1e-3 && (r.p[2] - 800.0).abs() < 1e-3,
            "off the line at {}: {:?}",
            r.t,
            r.p
        );
    }
    // y never goes back, and the robot stands still for the second of the TRAP's WaitTime.
    for w in mv.windows(2) {
        assert!(w[1].p[1] >= w[0].p[1] - 1e-9, "y goes back at {}", w[1].t);
    }
    let held: Vec<&&Row> = mv.iter().filter(|r| r.speed == 0.0).collect();
    let (held_from, held_to) = (held[0].t, held.last().expect("held rows").t);
    let span = held_to - held_from;
    assert!(span >= 1.0, "held for {span} s");
    // Decelerating and starting again takes several cycles, never one: the speed steps of
    // 200 mm/s go through intermediate values.
    let ramps = mv
        .iter()
        .filter(|r| r.speed > 1.0 && r.speed < 199.0 && r.t > held_from - 0.5)
        .count();
    assert!(ramps >= 10, "{ramps} cycles between full speed and rest");
    // The hold and the restart are no harsher on any axis than the planned move itself
    // (whose start and end use the robot's accelerations).
    drop(mv);
    let seg: Vec<Row> = all.into_iter().filter(|r| r.line == "34").collect();
    let start = seg
        .iter()
        .position(|r| r.t >= held_from - 0.3)
        .expect("hold");
    let end = seg
        .iter()
        .position(|r| r.t >= held_to + 0.3)
        .expect("resume");
    let around = max_axis_accel(&seg[start..end]);
    let planned = max_axis_accel(&seg[..start]);
    assert!(
        around <= planned * 1.0001,
        "hold/resume {around} deg/s² vs planned start {planned} deg/s²"
    );
}

#[test]
fn speedrefresh_halves_the_ongoing_move() {
    let c = trace_of("stopmove.mod", "refresh");
    let all = rows(&c);
    // `MoveL p10, v200, fine, tool0` (line 41) after `SpeedRefresh 50` in a TRAP at 1 s.
    let mv: Vec<&Row> = all.iter().filter(|r| r.line == "41").collect();
    let full = mv.iter().filter(|r| (r.speed - 200.0).abs() < 0.01).count();
    let half = mv.iter().filter(|r| (r.speed - 100.0).abs() < 0.01).count();
    assert!(
        full > 100 && half > 100,
        "{full} cycles at 200, {half} at 100 mm/s"
    );
    let last_full = mv
        .iter()
        .rposition(|r| (r.speed - 200.0).abs() < 0.01)
        .expect("full");
    let first_half = mv
        .iter()
        .position(|r| (r.speed - 100.0).abs() < 0.01)
        .expect("half");
    assert!(last_full < first_half, "full speed before, half after");
}

#[test]
fn storepath_and_restopath_continue_the_interrupted_move() {
    let c = trace_of("storepath.mod", "store");
    let all = rows(&c);
    // `MoveL p20, v200, z10, tool0` (line 15) interrupted by ERR_DIVZERO; the handler moves
    // the robot 100 mm back in x (lines 27, 29) and the MoveL goes on.
    let first = all.iter().position(|r| r.line == "27").expect("the detour");
    let back = all
        .iter()
        .rposition(|r| r.line == "29")
        .expect("the return");
    let stored_y = all[first].p[1];
    assert!(
        all[first..back]
            .iter()
            .any(|r| (r.p[0] - 1000.0).abs() < 0.01),
        "the detour reaches x 1000"
    );
    let after: Vec<&Row> = all[back + 1..].iter().filter(|r| r.line == "15").collect();
    assert!(after.len() > 50, "the MoveL continues after RestoPath");
    assert!(
        (after[0].p[1] - stored_y).abs() < 0.5,
        "from where it stopped"
    );
    for w in after.windows(2) {
        assert!((w[1].p[0] - 1100.0).abs() < 1e-3 && (w[1].p[2] - 800.0).abs() < 1e-3);
        assert!(w[1].p[1] >= w[0].p[1] - 1e-9);
    }
    // The fly-by point p20 then turns into MoveL p30 (line 19) on its corner path.
    let p30 = all.iter().rposition(|r| r.line == "19").expect("MoveL p30");
    let end = &all[p30];
    assert!((end.p[1] - 300.0).abs() < 1e-3 && (end.p[2] - 600.0).abs() < 1e-3);
}

#[test]
fn path_and_world_acceleration_limits_bound_the_tcp() {
    let c = trace_of("acclim.mod", "acclim");
    let all = rows(&c);
    // Every timed move is `MoveL target, v1000, fine, tool0` (line 11), one move id each.
    let mut moves: Vec<Vec<Row>> = Vec::new();
    for r in all.into_iter().filter(|r| r.line == "11") {
        match moves.last_mut() {
            Some(m) if m.last().is_some_and(|l| l.id == r.id) => m.push(r),
            _ => moves.push(vec![r]),
        }
    }
    assert_eq!(moves.len(), 4, "four timed moves");
    let a: Vec<f64> = moves.iter().map(|m| max_tcp_accel(m)).collect();
    // mm/s²; a little slack for the last, shorter step of a profile.
    assert!(a[0] > 4500.0, "unlimited {}", a[0]);
    assert!(a[1] <= 1000.0 * 1.01, "PathAccLim 2, 1: {}", a[1]);
    assert!(a[1] > 900.0, "PathAccLim 2, 1 uses its limit: {}", a[1]);
    assert!(
        a[2] <= 4000.0 * 1.01 && a[2] > 3600.0,
        "WorldAccLim 4: {}",
        a[2]
    );
    assert!((a[3] - a[0]).abs() < 1.0, "off again: {} vs {}", a[3], a[0]);
}

#[test]
fn corrwrite_offsets_the_corr_move_in_the_path_frame() {
    let c = trace_of("corr.mod", "corr");
    let all = rows(&c);
    // `MoveL p20, v200, fine, tool0 \Corr` (line 28) along world +y with the tool pointing
    // down: path y is world +x (5 mm from `lateral`), path z is world −z (10 mm from
    // `height`, written by a TRAP half-way).
    let mv: Vec<&Row> = all.iter().filter(|r| r.line == "28").collect();
    assert!(mv.len() > 100, "rows of the MoveL");
    let end = mv.last().expect("rows");
    assert!((end.p[0] - 1105.0).abs() < 1e-3, "x {}", end.p[0]);
    assert!((end.p[1] - 300.0).abs() < 1e-3, "y {}", end.p[1]);
    assert!((end.p[2] - 790.0).abs() < 1e-3, "z {}", end.p[2]);
    // The offset grows at most 100 mm/s (0.4 mm a cycle): no jump.
    for w in mv.windows(2) {
        let dx = (w[1].p[0] - w[0].p[0]).abs();
        let dz = (w[1].p[2] - w[0].p[2]).abs();
        assert!(dx <= 0.4 + 1e-6 && dz <= 0.4 + 1e-6, "jump at {}", w[1].t);
    }
    let lowered = mv.iter().position(|r| r.p[2] < 799.99).expect("lowered");
    assert!(
        mv[lowered].t - mv[0].t > 1.0,
        "the height comes with the TRAP"
    );
}
