//! RAPID programs moving the virtual robot through `rapidvc run`: golden runs of
//! `tests/run/motion/*.mod` (exit code, TP output, events, errors and the end-of-run summary
//! without its wall-clock part), issue 4's acceptance checked from the trace, straight lines,
//! deterministic traces, plots, the manual's program, real time and bad options.

use rapidvc_testkit::csv;
use rapidvc_testkit::{procs, rapidvc};

use std::path::{Path, PathBuf};

use csv::Csv;
use rapidvc_testkit::summary;
use summary::without_wall_time;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn motion_dir() -> PathBuf {
    root().join("tests/run/motion")
}

/// Run `rapidvc` in `dir`; (exit code, stdout, stderr).
fn rapidvc(dir: &Path, args: &[&str]) -> (i32, String, String) {
    procs::output_in(rapidvc!(), dir, args, 100)
}

/// A scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rapidvc-motion-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// The rows of a trace as (header, rows of fields).
fn read_trace(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let c = Csv::read(path);
    (c.header, c.rows)
}

/// Run `program` of `tests/run/motion` with `--trace` in the scratch directory `name`; it must
/// succeed. Returns the directory and the trace's header and rows.
fn traced(name: &str, program: &str) -> (PathBuf, Vec<String>, Vec<Vec<String>>) {
    let dir = scratch(name);
    let trace = dir.join(format!("{name}.csv"));
    let (code, stdout, stderr) = rapidvc(
        &motion_dir(),
        &["run", program, "--trace", trace.to_str().unwrap()],
    );
    assert_eq!(code, 0, "{stdout}{stderr}");
    let (header, rows) = read_trace(&trace);
    (dir, header, rows)
}

fn col(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"))
}

fn num(row: &[String], i: usize) -> f64 {
    row[i]
        .parse()
        .unwrap_or_else(|_| panic!("not a number: {:?}", row[i]))
}

fn joints(header: &[String], row: &[String]) -> [f64; 6] {
    let j1 = col(header, "j1");
    std::array::from_fn(|k| num(row, j1 + k))
}

fn assert_joints(got: [f64; 6], want: [f64; 6], tol: f64, what: &str) {
    for k in 0..6 {
        assert!(
            (got[k] - want[k]).abs() <= tol,
            "{what}: axis {} is {}, expected {} ± {tol}",
            k + 1,
            got[k],
            want[k]
        );
    }
}

#[test]
fn golden_motion_runs() {
    insta::glob!("run/motion/*.mod", |path| {
        let args = procs::golden_args(path);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (code, stdout, stderr) = rapidvc(path.parent().expect("dir"), &args);
        insta::assert_snapshot!(format!(
            "exit code: {code}\n--- stdout\n{stdout}--- stderr\n{}",
            without_wall_time(&stderr)
        ));
    });
}

/// docs/robot.md, "Acceptance facts": MoveJ p20 with tFroniusCMT and MoveJ p30 with tool0 end at the same joints.
const P20_JOINTS: [f64; 6] = [83.498, 0.077, -0.340, 0.103, 39.066, -0.136];

#[test]
fn acceptance_joints_from_the_trace() {
    let (dir, header, rows) = traced("acceptance", "acceptance.mod");
    let (instr, line) = (col(&header, "instr"), col(&header, "line"));
    // The last row of the MoveJ p20 (line 20) and the last row of the run (MoveJ p30).
    let end_p20 = rows
        .iter()
        .rev()
        .find(|r| r[instr] == "MoveJ" && r[line] == "20")
        .expect("rows of MoveJ p20");
    assert_joints(joints(&header, end_p20), P20_JOINTS, 0.01, "MoveJ p20");
    let last = rows.last().expect("rows");
    assert_eq!((last[instr].as_str(), last[line].as_str()), ("MoveJ", "26"));
    assert_joints(joints(&header, last), P20_JOINTS, 0.01, "MoveJ p30");
    // The TCP of the trace is tool0's at the end (p30).
    let x = col(&header, "x");
    let tcp = [num(last, x), num(last, x + 1), num(last, x + 2)];
    for (got, want) in tcp.iter().zip([114.50, 1005.42, 1410.38]) {
        assert!((got - want).abs() < 0.1, "TCP {tcp:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A tool change moves the TCP of the trace by the tools' difference (416 mm here) without
/// moving the robot: the speed column must not show that as one cycle at 100 m/s.
#[test]
fn tool_changes_do_not_show_as_tcp_speed() {
    let (dir, header, rows) = traced("toolchange", "acceptance.mod");
    let (x, speed, line) = (
        col(&header, "x"),
        col(&header, "speed_mm_s"),
        col(&header, "line"),
    );
    // The first cycle of `MoveAbsJ jpos10, …, tool0` (line 25), right after p20 with
    // tFroniusCMT: the TCP jumps, the robot starts from rest.
    let first = rows
        .iter()
        .position(|r| r[line] == "25")
        .expect("rows of line 25");
    let before = &rows[first - 1];
    let at = &rows[first];
    let jump: f64 = (0..3)
        .map(|k| (num(at, x + k) - num(before, x + k)).powi(2))
        .sum::<f64>()
        .sqrt();
    assert!(
        jump > 300.0,
        "the TCP moves with the tool change ({jump} mm)"
    );
    assert!(
        num(at, speed) < 50.0,
        "speed at the tool change {} mm/s",
        num(at, speed)
    );
    let top = rows.iter().map(|r| num(r, speed)).fold(0.0, f64::max);
    assert!(top < 5000.0, "top TCP speed {top} mm/s");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn movel_keeps_the_tcp_on_the_line_at_the_programmed_speed() {
    let (dir, header, rows) = traced("movel", "moves.mod");
    let (x, speed, instr, line) = (
        col(&header, "x"),
        col(&header, "speed_mm_s"),
        col(&header, "instr"),
        col(&header, "line"),
    );
    // `MoveL p20, v500` (line 15) from p10 [1100, -300, 800] to p20 [1100, 300, 800].
    let on_line: Vec<&Vec<String>> = rows
        .iter()
        .filter(|r| r[instr] == "MoveL" && r[line] == "15")
        .collect();
    assert!(on_line.len() > 250, "{} rows", on_line.len());
    let mut top: f64 = 0.0;
    for r in &on_line {
        let p = [num(r, x), num(r, x + 1), num(r, x + 2)];
        let off = ((p[0] - 1100.0).powi(2) + (p[2] - 800.0).powi(2)).sqrt();
        assert!(off < 0.1, "{off} mm off the line at {p:?}");
        assert!((-300.1..=300.1).contains(&p[1]), "{p:?}");
        top = top.max(num(r, speed));
    }
    assert!((top - 500.0).abs() < 1.0, "top speed {top} mm/s");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn two_runs_give_byte_identical_traces() {
    let dir = scratch("determinism");
    let a = dir.join("a.csv");
    let b = dir.join("b.csv");
    for t in [&a, &b] {
        let (code, _, stderr) = rapidvc(
            &motion_dir(),
            &["run", "zones.mod", "--trace", t.to_str().unwrap()],
        );
        assert_eq!(code, 0, "{stderr}");
    }
    let (ta, tb) = (std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    assert!(ta.len() > 10_000);
    assert!(ta == tb, "the traces differ");
    let head = String::from_utf8_lossy(&ta[..120]).into_owned();
    assert!(
        head.starts_with("time_s,j1,j2,j3,j4,j5,j6,x,y,z,q1,q2,q3,q4,"),
        "{head}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn plots_are_written() {
    let dir = scratch("plot");
    for name in ["zones.png", "zones.svg"] {
        let path = dir.join(name);
        let (code, _, stderr) = rapidvc(
            &motion_dir(),
            &["run", "zones.mod", "--plot", path.to_str().unwrap()],
        );
        assert_eq!(code, 0, "{stderr}");
        let bytes = std::fs::read(&path).expect("plot written");
        if name.ends_with(".png") {
            assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
        } else {
            let text = String::from_utf8_lossy(&bytes);
            assert!(text.contains("<svg") && text.contains("MoveL"), "svg");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn realtime_run_moves_the_robot() {
    let dir = scratch("realtime");
    std::fs::write(
        dir.join("rt.mod"),
        "MODULE rt\n  PROC main()\n    MoveAbsJ [[0,0,0,0,20,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v1000, fine, tool0;\n    WaitTime 0.1;\n    TPWrite \"done\";\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    let (code, stdout, stderr) = rapidvc(&dir, &["run", "rt.mod", "--realtime"]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(stdout, "done\n");
    assert!(
        stderr.contains("final joints [0.00, 0.00, 0.00, 0.00, 20.00, 0.00]")
            && stderr.contains("period error"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_options_are_clear_errors() {
    let dir = motion_dir();
    for (args, expect) in [
        (
            vec!["--period", "0"],
            "'--period <MS>': 0 is out of range: expected milliseconds from 0.1 to 100",
        ),
        (vec!["--start", "1,2,3"], "expected six axis values"),
        (
            vec!["--start", "0,0,100,0,0,0"],
            "--start: joint 3 out of range",
        ),
        (
            vec!["--plot", "out.jpg"],
            "the file name must end in .svg or .png",
        ),
        (
            vec!["--robot", "IRB 9999"],
            "unknown or ambiguous robot model",
        ),
    ] {
        let mut all = vec!["run", "moves.mod"];
        all.extend(args.iter().copied());
        let (code, stdout, stderr) = rapidvc(&dir, &all);
        assert_eq!(code, 2, "{args:?}: {stdout}{stderr}");
        assert!(stderr.contains(expect), "{args:?}: {stderr}");
        assert!(stdout.is_empty(), "{args:?}: {stdout}");
    }
}

#[test]
fn start_option_and_other_robots() {
    let dir = scratch("start");
    std::fs::write(
        dir.join("where.mod"),
        "MODULE where\n  PROC main()\n    TPWrite \"start \" \\Pos:=CPos();\n    MoveAbsJ [[10,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v1000, fine, tool0;\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    let (code, stdout, stderr) = rapidvc(&dir, &["run", "where.mod"]);
    assert_eq!(code, 0, "{stderr}");
    // All axes at 0 (the calibration position): tool0 at [1030, 0, 1460] on the default robot.
    assert_eq!(stdout, "start [1030,0,1460]\n");
    let (code, stdout, stderr) = rapidvc(
        &dir,
        &[
            "run",
            "where.mod",
            "--robot",
            "IRB 120-3/0.58",
            "--start",
            "[0,0,0,0,90,0]",
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(stdout, "start [302,0,558]\n");
    assert!(stderr.contains("final joints [10.00, 0.00, 0.00, 0.00, 30.00, 0.00]"));
    let _ = std::fs::remove_dir_all(&dir);
}
