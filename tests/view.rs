//! `rapidvc run --view FILE.html`: the replay page is self-contained, its embedded rows are
//! within the drawing tolerance of every motion cycle of the trace, the path-correction
//! example's programmed path lies on the programmed seam, TP output and events carry their
//! robot time, a ten-minute run stays small, and bad options fail before the run. The page
//! in a real browser: tests/view_browser.rs; the live view: tests/view_live.rs.

use rapidvc_testkit::rapidvc;
use rapidvc_testkit::view_page;

use std::path::{Path, PathBuf};

use rapidvc::output::view::record::{JOINT_TOL_DEG, TCP_TOL_MM};
use serde_json::Value;
use view_page::{Rows, decode, decode_time, page_data, read_trace};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rapidvc-view-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// `rapidvc run ARGS…`: (exit code, stdout, stderr).
fn rapidvc(args: &[&str]) -> (i32, String, String) {
    let out = rapidvc!()
        .args(args)
        .current_dir(root())
        .output()
        .expect("run rapidvc");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Run `program` with `--view` and `--trace`; (page text, page data, trace path, stdout).
fn run_with_view(program: &str, name: &str) -> (String, Value, PathBuf, String) {
    let dir = scratch(name);
    let page = dir.join("view.html");
    let trace = dir.join("trace.csv");
    let (code, stdout, stderr) = rapidvc(&[
        "run",
        program,
        "--view",
        page.to_str().unwrap(),
        "--trace",
        trace.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stderr.contains("view: "), "the page is announced: {stderr}");
    let html = std::fs::read_to_string(&page).expect("page written");
    let data = page_data(&html);
    (html, data, trace, stdout)
}

/// Every motion cycle of the trace, drawn from the kept rows, is within the tolerance.
fn check_rows_against_trace(data: &Value, trace: &Path) -> usize {
    let (kept, cycles) = rows_within_tolerance(data, trace);
    assert!(kept * 10 < cycles, "{kept} rows kept of {cycles} cycles");
    cycles
}

/// Every motion cycle of the trace, drawn from the kept rows, is within the tolerance:
/// (rows kept, cycles traced).
fn rows_within_tolerance(data: &Value, trace: &Path) -> (usize, usize) {
    let rows = Rows::of(data);
    let traced = read_trace(trace);
    assert_eq!(rows.t.first(), traced.first().map(|r| &r.t));
    assert_eq!(rows.t.last(), traced.last().map(|r| &r.t));
    for r in &traced {
        let (j, p) = rows.at(r.t);
        for (a, (d, e)) in j.iter().zip(r.joints).enumerate() {
            assert!(
                (d - e).abs() <= JOINT_TOL_DEG + 6e-4,
                "J{} at {} µs: {d} drawn, {e} traced",
                a + 1,
                r.t
            );
        }
        for (d, e) in p.iter().zip(r.tcp) {
            assert!(
                (d - e).abs() <= TCP_TOL_MM + 6e-3,
                "TCP at {} µs: {p:?} drawn, {:?} traced",
                r.t,
                r.tcp
            );
        }
    }
    (rows.t.len(), traced.len())
}

#[test]
fn replay_page_is_self_contained_and_draws_every_cycle_within_tolerance() {
    let (html, data, trace, _) =
        run_with_view("programs/manual/position_guidance_signals.mod", "signals");
    // Nothing is loaded from elsewhere: no external scripts, styles, images or fonts.
    let lower = html.to_ascii_lowercase();
    for needle in [
        "<script src",
        "<link",
        "@import",
        "url(",
        "http://",
        "https://",
        "<img",
        "<iframe",
    ] {
        assert!(!lower.contains(needle), "the page contains `{needle}`");
    }
    assert_eq!(data["version"], 1);
    assert_eq!(data["live"], false);
    assert_eq!(data["finished"], true);
    let scene = &data["scene"];
    assert_eq!(scene["robot"]["name"], "IRB 2600-12/1.85");
    assert_eq!(scene["periodUs"], 4000);
    assert_eq!(
        scene["files"][0]["name"],
        "programs/manual/position_guidance_signals.mod"
    );
    let frames: Vec<&str> = scene["frames"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["name"].as_str().unwrap())
        .collect();
    assert_eq!(frames, ["wobj_EGM1", "wobj_EGM2"]);
    assert_eq!(
        scene["frames"][0]["pose"],
        serde_json::json!([150.0, 1320.0, 1140.0, 1.0, 0.0, 0.0, 0.0])
    );
    check_rows_against_trace(&data, &trace);
    // Instructions point at their source lines.
    let instrs = data["instrs"].as_array().unwrap();
    assert_eq!(instrs[0], serde_json::json!([1, "MoveAbsJ", 0, 44]));
    assert!(instrs.iter().any(|i| i[1] == "EGMRunJoint"));
    // EGM: samples in joint and pose mode, the states, the limiting events with their time.
    let egm = &data["egm"];
    let axes = decode(&egm["axes"], 1.0);
    assert!(axes.contains(&0.0) && axes.contains(&1.0));
    let states: Vec<i64> = data["egmStates"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s[1].as_i64().unwrap())
        .collect();
    assert!(states.contains(&1), "CONNECTED after the setup: {states:?}");
    assert!(states.contains(&2), "RUNNING: {states:?}");
    assert_eq!(states.last(), Some(&0), "EGMReset ends DISCONNECTED");
    let log = data["log"].as_array().unwrap();
    let limited: Vec<&Value> = log
        .iter()
        .filter(|e| e[1] == "event" && e[2].as_str().unwrap().contains("90110"))
        .collect();
    assert!(!limited.is_empty());
    assert!(limited.iter().all(|e| e[0].as_i64().unwrap() > 0));
    let times: Vec<i64> = log.iter().map(|e| e[0].as_i64().unwrap()).collect();
    assert!(times.windows(2).all(|w| w[0] <= w[1]), "log in time order");
    assert_eq!(log.last().unwrap()[1], "end");
}

#[test]
fn path_correction_draws_the_programmed_seam_and_the_corrected_path() {
    let (_, data, trace, _) = run_with_view("programs/manual/path_correction.mod", "pathcorr");
    check_rows_against_trace(&data, &trace);
    let p = &data["path"];
    let t = decode_time(&p["t"]);
    assert!(t.len() > 100, "{} path rows", t.len());
    let prog: Vec<Vec<f64>> = (0..3).map(|a| decode(&p["prog"][a], 1e2)).collect();
    let cor: Vec<Vec<f64>> = (0..3).map(|a| decode(&p["cor"][a], 1e2)).collect();
    let corr: Vec<Vec<f64>> = (0..2).map(|a| decode(&p["corr"][a], 1e3)).collect();
    let starts = decode(&p["start"], 1.0);
    assert_eq!(
        starts.iter().filter(|s| **s == 1.0).count(),
        3,
        "three sequences"
    );
    // The manual's seam lies in the plane z = 500 mm of wobj0, displaced by the program
    // displacement `PP` (+2 mm in z) in all three parts: the programmed path stays in that
    // plane however the sensor corrects it.
    let mut largest = 0.0f64;
    for k in 0..t.len() {
        assert!(
            (prog[2][k] - 502.0).abs() < 0.2,
            "programmed z {} at {} µs",
            prog[2][k],
            t[k]
        );
        let d = ((0..3)
            .map(|a| (cor[a][k] - prog[a][k]).powi(2))
            .sum::<f64>())
        .sqrt();
        let c = corr[0][k].hypot(corr[1][k]);
        assert!(
            (d - c).abs() < 0.25,
            "corrected − programmed = {d} mm, correction {c} mm"
        );
        largest = largest.max(d);
    }
    assert!(largest > 1.0, "the sensors moved the path by {largest} mm");
}

#[test]
fn tp_output_and_events_carry_robot_time() {
    let (_, data, _, stdout) = run_with_view("programs/manual/position_guidance_udpuc.mod", "tp");
    let log = data["log"].as_array().unwrap();
    let tp: Vec<(i64, &str)> = log
        .iter()
        .filter(|e| e[1] == "tp")
        .map(|e| (e[0].as_i64().unwrap(), e[2].as_str().unwrap()))
        .collect();
    let printed: Vec<&str> = stdout.lines().collect();
    assert_eq!(tp.iter().map(|(_, s)| *s).collect::<Vec<_>>(), printed);
    // "EGM state" is written after the MoveAbsJ fine point (0.4 s), the reset at the end.
    assert!(tp[0].0 >= 300_000, "{tp:?}");
    assert_eq!(tp[1].0, data["endUs"].as_i64().unwrap());
}

#[test]
fn ten_minute_run_is_small() {
    let (html, data, trace, _) = run_with_view("tests/view/long_run.mod", "long");
    let cycles = check_rows_against_trace(&data, &trace);
    assert!(cycles > 150_000, "{cycles} cycles");
    assert!(
        html.len() < 1_000_000,
        "a ten-minute run's page is {} bytes",
        html.len()
    );
}

#[test]
fn bad_view_options_fail_before_the_run() {
    let (code, stdout, stderr) = rapidvc(&[
        "run",
        "programs/manual/position_guidance_udpuc.mod",
        "--view",
        "/nonexistent-dir/x.html",
    ]);
    assert_eq!(code, 2);
    assert!(stdout.is_empty(), "nothing ran: {stdout}");
    assert!(
        stderr.contains(
            "--view /nonexistent-dir/x.html: the directory /nonexistent-dir does not exist"
        ),
        "{stderr}"
    );
    let (code, _, stderr) = rapidvc(&[
        "run",
        "programs/manual/position_guidance_udpuc.mod",
        "--view-live",
        "nowhere",
    ]);
    assert_eq!(code, 2);
    assert!(stderr.contains("HOST:PORT"), "{stderr}");
    let (code, _, stderr) = rapidvc(&[
        "run",
        "programs/manual/position_guidance_udpuc.mod",
        "--view-live",
        "--lockstep",
    ]);
    assert_eq!(code, 2);
    assert!(stderr.contains("--lockstep keeps virtual time"), "{stderr}");
}

#[test]
fn a_system_of_several_tasks_is_viewed_with_every_tasks_output() {
    // A copy: the cell's logger task writes into its HOME folder.
    let dir = scratch("cell");
    let cell = dir.join("cell");
    let _ = std::fs::remove_dir_all(&cell);
    let status = std::process::Command::new("cp")
        .args(["-r", "tests/tasks/cell"])
        .arg(&cell)
        .current_dir(root())
        .status()
        .expect("cp");
    assert!(status.success());
    let (_, data, trace, stdout) = run_with_view(cell.to_str().unwrap(), "cellview");
    assert_eq!(data["finished"], true);
    // The page shows the files of every task, draws the motion task's moves within the
    // tolerance and logs every task's TP lines (with their task's name) as printed.
    let files: Vec<String> = data["scene"]["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["name"].as_str().unwrap().to_string())
        .collect();
    for module in ["main.mod", "logger.mod", "cell.mod"] {
        assert!(
            files.iter().any(|f| f.ends_with(module)),
            "{module} in {files:?}"
        );
    }
    // (A short program of many small moves: a row for every few cycles.)
    let (kept, cycles) = rows_within_tolerance(&data, &trace);
    assert!(
        cycles > 1000 && kept < cycles / 2,
        "{kept} rows of {cycles} cycles"
    );
    let tp = view_page::tp_lines(&data["log"]);
    assert_eq!(tp, stdout.lines().collect::<Vec<_>>());
    assert!(tp.iter().any(|l| l.starts_with("[T_LOG] ")), "{tp:?}");
    assert!(tp.iter().any(|l| l.starts_with("[T_CELL] ")), "{tp:?}");
    let _ = std::fs::remove_dir_all(&dir);
}
