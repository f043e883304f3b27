//! Operator dialogs answered on a real terminal: `rapidvc run` with no answers file and a
//! pseudo-terminal as standard input (made by util-linux `script`, which forwards our
//! piped lines to it) reads each answer from the terminal and asks again after one that
//! does not fit the dialog.

use std::io::Write;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

#[test]
fn dialogs_read_answers_from_a_terminal() {
    let root = env!("CARGO_MANIFEST_DIR");
    let cmd = format!(
        "{} run tests/fixtures/dialogs/ask.mod",
        env!("CARGO_BIN_EXE_rapidvc")
    );
    let mut child = Command::new("script")
        .args(["-qec", &cmd, "/dev/null"])
        .current_dir(root)
        .env("NO_COLOR", "1")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("util-linux `script` (Debian package bsdutils) makes the pseudo-terminal");
    child
        .stdin
        .take()
        .expect("stdin")
        .write_all(b"Go\nthree\n3\n")
        .expect("write answers");
    let start = Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            panic!("rapidvc on a terminal did not end within 60 s");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let out = child.wait_with_output().expect("output");
    let stdout = String::from_utf8_lossy(&out.stdout).replace('\r', "");
    assert!(out.status.success(), "{stdout}");
    let lines: Vec<&str> = stdout.lines().collect();
    // The terminal echoes what was typed; the dialogs' lines come in order.
    let at = |s: &str| {
        lines
            .iter()
            .position(|l| *l == s)
            .unwrap_or_else(|| panic!("no line `{s}` in:\n{stdout}"))
    };
    assert!(at("Start?") < at("  [F1 Go] [F5 Stop]"));
    assert!(at("How many?") < at("  ! a number is needed; answer again"));
    assert!(at("  ! a number is needed; answer again") < at("n = 3"));
    assert!(at("key 1") < at("n = 3"));
    // On the terminal the answer is not repeated with its origin.
    assert!(!stdout.contains("> Go ("), "{stdout}");
}
