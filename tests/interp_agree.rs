//! The interpreter's two engines agree (issue 11): the compiled closures with their fast
//! paths (`src/interp/compile/`) and the tree-walking reference (`src/interp/expr.rs`,
//! `src/interp/stmt.rs`) must give the same TP output, the same final data, the same errors
//! (number, text, line, call stack) and the same step count.
//!
//! * Every RAPID file of the repository is run by the command-line tool once per engine
//!   (`RAPIDVC_ENGINE`); exit code, stdout and stderr must be identical.
//! * Generated programs (proptest) over num/dnum/bool/string arithmetic, records, arrays,
//!   IF/WHILE/FOR/TEST/GOTO, calls with every parameter mode, ERROR handlers with
//!   RETRY/TRYNEXT/RAISE/RETURN and simple (inlined) functions run in this process on both
//!   engines and are compared in full.

use std::path::{Path, PathBuf};
use std::process::Command;

#[path = "support/summary.rs"]
mod summary;
use summary::without_wall_time;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Run the command-line tool in `dir` on `engine`: (exit code, stdout, stderr without the
/// wall-clock part of the motion summary).
fn run_tool(dir: &Path, args: &[String], engine: &str) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_rapidvc"))
        .args(args)
        .current_dir(dir)
        .env("COLUMNS", "80")
        .env("NO_COLOR", "1")
        .env("RAPIDVC_ENGINE", engine)
        .output()
        .expect("run rapidvc");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        without_wall_time(&String::from_utf8_lossy(&out.stderr)),
    )
}

/// Every `.mod` file under `dir`, sorted.
fn rapid_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut paths: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    paths.sort();
    for p in paths {
        if p.is_dir() {
            rapid_files(&p, out);
        } else if p.extension().is_some_and(|e| e.eq_ignore_ascii_case("mod")) {
            out.push(p);
        }
    }
}

/// How the repository runs a file: `test` for RAPID test modules, else `run` with the
/// options of its `! args:` line; every run bounded by a step budget.
fn invocation(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    let name = path.to_string_lossy().into_owned();
    if text.to_ascii_lowercase().contains("proc test_") {
        return vec!["test".into(), "--max-steps".into(), "3000000".into(), name];
    }
    let mut args = vec!["run".to_string()];
    if let Some(extra) = text.lines().find_map(|l| l.strip_prefix("! args:")) {
        args.extend(extra.split_whitespace().map(String::from));
    }
    if !args.iter().any(|a| a == "--max-steps") {
        args.extend(["--max-steps".into(), "3000000".into()]);
    }
    args.push(name);
    args
}

#[test]
fn every_rapid_file_runs_the_same_on_both_engines() {
    let root = root();
    let mut files = Vec::new();
    for dir in ["tests", "programs", "benches"] {
        rapid_files(&root.join(dir), &mut files);
    }
    assert!(files.len() > 60, "only {} RAPID files found", files.len());
    let mut programs: Vec<(PathBuf, Vec<String>)> = files
        .iter()
        .map(|f| (f.parent().unwrap_or(&root).to_path_buf(), invocation(f)))
        .collect();
    // Multi-module programs: a directory of modules is one program.
    programs.push((
        root.join("tests/run"),
        vec!["run".into(), "multi_module".into()],
    ));
    let mut differ = Vec::new();
    for (dir, args) in &programs {
        let compiled = run_tool(dir, args, "compiled");
        let reference = run_tool(dir, args, "tree-walk");
        if compiled != reference {
            differ.push(format!(
                "{}: {args:?}\n--- compiled (exit {})\n{}{}--- tree-walk (exit {})\n{}{}",
                dir.display(),
                compiled.0,
                compiled.1,
                compiled.2,
                reference.0,
                reference.1,
                reference.2
            ));
        }
    }
    assert!(
        differ.is_empty(),
        "{} of {} programs differ:\n{}",
        differ.len(),
        programs.len(),
        differ.join("\n")
    );
}
