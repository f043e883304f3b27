//! Golden tests: every `tests/run/*.mod` is run with `rapidvc run` (extra arguments from a
//! leading `! args: …` line); exit code, TP output (stdout) and diagnostics (stderr) are
//! compared with insta snapshots. Plus persistents across runs.

use rapidvc_testkit::{procs, rapidvc};
use std::path::Path;

fn run_in(dir: &Path, args: &[&str]) -> (i32, String, String) {
    procs::output_in(rapidvc!(), dir, args, 80)
}

#[test]
fn golden_runs() {
    insta::glob!("run/*.mod", |path| {
        let args = procs::golden_args(path);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (code, stdout, stderr) = run_in(path.parent().expect("dir"), &args);
        insta::assert_snapshot!(format!(
            "exit code: {code}\n--- stdout\n{stdout}--- stderr\n{stderr}"
        ));
    });
}

/// Multi-module programs: each directory under `tests/run` is one program.
#[test]
fn golden_multi_module_runs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/run");
    let mut dirs: Vec<_> = std::fs::read_dir(&root)
        .expect("tests/run")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_dir())
        // `tests/run/motion` holds single-module motion programs (tests/run_motion.rs),
        // `tests/run/pathcorr` the path-correction programs (tests/run_pathcorr.rs).
        .filter(|p| !p.ends_with("motion") && !p.ends_with("pathcorr"))
        .collect();
    dirs.sort();
    assert!(!dirs.is_empty());
    for dir in dirs {
        let name = dir
            .file_name()
            .and_then(|n| n.to_str())
            .expect("name")
            .to_string();
        let (code, stdout, stderr) = run_in(&root, &["run", &name]);
        insta::assert_snapshot!(
            format!("dir_{name}"),
            format!("exit code: {code}\n--- stdout\n{stdout}--- stderr\n{stderr}")
        );
    }
}

/// The EGM manual's programs pass the semantic pass (`check` without `--syntax`), as a
/// folder of independent programs and one by one.
#[test]
fn manual_programs_check_clean() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let (code, stdout, stderr) = run_in(root, &["check", "programs/manual"]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(stderr.contains(" 0 errors"), "{stderr}");
    for f in [
        "position_guidance_udpuc.mod",
        "position_guidance_signals.mod",
        "path_correction.mod",
    ] {
        let path = format!("programs/manual/{f}");
        let (code, stdout, stderr) = run_in(root, &["check", &path]);
        assert_eq!(code, 0, "{path}: {stdout}{stderr}");
    }
}

#[test]
fn persistents_survive_between_runs() {
    let dir = std::env::temp_dir().join(format!("rapidvc-pers-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("count.mod"),
        "MODULE count\n  PERS num runs := 0;\n  TASK PERS pos last := [0, 0, 0];\n  PERS string note := \"x\";\n  PROC main()\n    Incr runs;\n    last.x := last.x + 1.5;\n    note := note + \"\"\"\";\n    TPWrite \"runs: \" \\Num:=runs;\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    let pers = dir.join("state.pers");
    let _ = std::fs::remove_file(&pers);
    for expected in ["runs: 1\n", "runs: 2\n", "runs: 3\n"] {
        let (code, out, err) = run_in(&dir, &["run", "count.mod", "--pers", "state.pers"]);
        assert_eq!(code, 0, "{err}");
        assert_eq!(out, expected);
    }
    let saved = std::fs::read_to_string(&pers).unwrap();
    assert!(saved.contains("PERS num runs := 3;"), "{saved}");
    assert!(
        saved.contains("TASK PERS pos last := [4.5,0,0];"),
        "{saved}"
    );
    assert!(
        saved.contains("PERS string note := \"x\"\"\"\"\"\"\";"),
        "{saved}"
    );
    // Entries the program does not declare are kept; a bad file is a clear error.
    std::fs::write(&pers, format!("{saved}PERS num other := 7;\n")).unwrap();
    let (code, _, _) = run_in(&dir, &["run", "count.mod", "--pers", "state.pers"]);
    assert_eq!(code, 0);
    let saved = std::fs::read_to_string(&pers).unwrap();
    assert!(saved.contains("PERS num other := 7;"), "{saved}");
    std::fs::write(&pers, "PERS num runs := [1,;\n").unwrap();
    let (code, _, err) = run_in(&dir, &["run", "count.mod", "--pers", "state.pers"]);
    assert_eq!(code, 2);
    assert!(err.contains("line 1"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `rapidvc ARGS…` in the crate root that must end by itself within `secs` seconds (a
/// guard against hangs, not a speed check: it is killed and the test fails if it does not).
fn run_guarded(args: &[&str], secs: u64) -> (i32, String, String) {
    use std::io::Read;
    let mut child = rapidvc!()
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("COLUMNS", "80")
        .env("NO_COLOR", "1")
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("start rapidvc");
    let mut out_pipe = child.stdout.take().expect("stdout");
    let mut err_pipe = child.stderr.take().expect("stderr");
    let out_reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = out_pipe.read_to_string(&mut s);
        s
    });
    let err_reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = err_pipe.read_to_string(&mut s);
        s
    });
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(secs);
    let status = loop {
        if let Some(st) = child.try_wait().expect("wait for rapidvc") {
            break Some(st);
        }
        if std::time::Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    let stdout = out_reader.join().unwrap_or_default();
    let stderr = err_reader.join().unwrap_or_default();
    let Some(status) = status else {
        panic!("rapidvc {args:?} did not end within {secs} s (killed)\n{stdout}{stderr}");
    };
    (status.code().unwrap_or(-1), stdout, stderr)
}

/// Issue 10, item 7: a loop with an empty body counts against the statement budget, in
/// compiled bodies and on the tree-walking path (ERROR handlers), for WHILE, FOR and GOTO.
#[test]
fn empty_loops_end_at_the_budget() {
    let (code, out, err) = run_guarded(
        &[
            "test",
            "--max-steps",
            "1000",
            "tests/fixtures/loops/empty_loops.mod",
        ],
        120,
    );
    assert_eq!(code, 1, "{out}{err}");
    assert!(out.ends_with("0 passed, 6 failed\n"), "{out}");
    let exhausted = out
        .matches("the operation budget of 1000 steps is exhausted")
        .count();
    assert_eq!(exhausted, 6, "{out}");

    // `rapidvc test`'s default budget ends it too.
    let (code, out, err) = run_guarded(
        &[
            "test",
            "--filter",
            "test_empty_while_in_handler",
            "tests/fixtures/loops/empty_loops.mod",
        ],
        300,
    );
    assert_eq!(code, 1, "{out}{err}");
    assert!(
        out.contains("the operation budget of 50000000 steps"),
        "{out}"
    );

    // `run --max-steps` stops the program at the loop.
    let (code, out, err) = run_guarded(
        &[
            "run",
            "--max-steps",
            "1000",
            "tests/fixtures/loops/empty_while.mod",
        ],
        120,
    );
    assert_eq!(code, 1, "{out}{err}");
    assert!(err.contains("rapidvc::run::aborted"), "{err}");
    assert!(err.contains("empty_while.mod:4:5"), "{err}");
}
