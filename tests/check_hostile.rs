//! `rapidvc check` on hostile programs: a file with 100,000 undeclared names among 20,000
//! declarations (the "did you mean" suggestion compared every undeclared name with every
//! known one: it did not end in hours). Runs the real binary; a generous time-out is the
//! only bound (speed is measured by benchmarks, not asserted here).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::Duration;

use rapidvc_testkit::{procs, rapidvc};

/// A module with `declared` globals `value<i>` and one routine assigning to `undeclared`
/// misspelt names `valeu<i>` (each two edits from a declared name of the same length).
fn broken_module(declared: usize, undeclared: usize) -> String {
    let mut s = String::from("MODULE Broken\n");
    for i in 0..declared {
        s.push_str(&format!("  VAR num value{i} := {i};\n"));
    }
    s.push_str("  PROC main()\n");
    for i in 0..undeclared {
        s.push_str(&format!("    valeu{i} := {i};\n"));
    }
    s.push_str("  ENDPROC\nENDMODULE\n");
    s
}

#[test]
fn a_hundred_thousand_undeclared_names_check_in_bounded_time() {
    let dir = std::env::temp_dir().join(format!("rapidvc-check-hostile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch directory");
    let path = dir.join("broken.mod");
    std::fs::write(&path, broken_module(20_000, 100_000)).expect("write the program");
    let mut cmd = rapidvc!();
    cmd.args(["check", "--format", "json"]).arg(&path);
    let ended = procs::Proc::spawn(cmd).wait(Duration::from_secs(300));
    let _ = std::fs::remove_dir_all(&dir);
    assert!(!ended.timed_out, "check did not end: {}", ended.stderr);
    assert_eq!(ended.code, Some(1), "{}", ended.stderr);
    let undeclared = ended.stdout.matches("rapidvc::sema::undeclared").count();
    assert_eq!(undeclared, 100_000);
    // The first ones still get their suggestion (the work is bounded, not skipped).
    assert!(
        ended.stdout.contains("did you mean `value0`?"),
        "{}",
        &ended.stdout[..ended.stdout.len().min(2000)]
    );
}
