//! Golden tests: every `tests/run/*.mod` is run with `rapidvc run` (extra arguments from a
//! leading `! args: …` line); exit code, TP output (stdout) and diagnostics (stderr) are
//! compared with insta snapshots. Plus persistents across runs.

use std::path::Path;
use std::process::Command;

fn run_in(dir: &Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_rapidvc"))
        .args(args)
        .current_dir(dir)
        .env("COLUMNS", "80")
        .env("NO_COLOR", "1")
        .output()
        .expect("run rapidvc");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn golden_runs() {
    insta::glob!("run/*.mod", |path| {
        let text = std::fs::read_to_string(path).expect("read program");
        let extra: Vec<&str> = text
            .lines()
            .find_map(|l| l.strip_prefix("! args:"))
            .map(|a| a.split_whitespace().collect())
            .unwrap_or_default();
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .expect("file name");
        let mut args = vec!["run"];
        args.extend(extra);
        args.push(name);
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
