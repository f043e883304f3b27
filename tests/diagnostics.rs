//! Hostile source text in rendered diagnostics: a label far right on a 100,000-column line
//! (parse, sema, configuration and run-time errors), control characters and escape sequences
//! in the source, old Mac line ends (a lone CR), and the call stack of a runaway recursion.
//! Each runs the real binary on files written into a scratch directory.

use rapidvc_testkit::rapidvc;
use std::path::{Path, PathBuf};

/// A fresh scratch directory for one test, removed when dropped.
struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn scratch(test: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("rapidvc-diag-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch directory");
    Scratch(dir)
}

/// Run rapidvc in `dir` (80 columns, no colour): exit code, stdout, stderr as bytes.
fn rapidvc(dir: &Path, args: &[&str]) -> (i32, Vec<u8>, Vec<u8>) {
    let out = rapidvc!()
        .args(args)
        .current_dir(dir)
        .env("COLUMNS", "80")
        .env("NO_COLOR", "1")
        .output()
        .expect("run rapidvc");
    (out.status.code().unwrap_or(-1), out.stdout, out.stderr)
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// 100,000 spaces: a label after them is past miette's column limit (65,535).
fn wide() -> String {
    " ".repeat(100_000)
}

/// Write `files` into a scratch directory, run rapidvc there with `args`, check it exits 1
/// and prints no line wider than a clipped one; its stderr.
fn rendered_wide(test: &str, files: &[(&str, String)], args: &[&str]) -> String {
    let dir = scratch(test);
    for (name, content) in files {
        std::fs::write(dir.join(name), content).expect("write");
    }
    let (code, _, stderr) = rapidvc(&dir, args);
    let stderr = text(&stderr);
    assert_eq!(code, 1, "{stderr}");
    for line in stderr.lines() {
        assert!(
            line.chars().count() < 200,
            "a rendered line is {} characters wide",
            line.chars().count()
        );
    }
    stderr
}

/// A module whose line 3 is `text` after 100,000 spaces (past miette's column limit, 65,535).
fn wide_statement(text: &str) -> String {
    format!(
        "MODULE M\n  PROC main()\n{}{text}\n  ENDPROC\nENDMODULE\n",
        wide()
    )
}

#[test]
fn check_renders_a_syntax_error_past_column_65535_clipped() {
    let files = [("wide.mod", wide_statement("x := ;"))];
    let args = ["check", "--syntax", "wide.mod"];
    insta::assert_snapshot!(rendered_wide("wide-syntax", &files, &args));
}

#[test]
fn check_json_reports_the_full_column_of_a_wide_line() {
    let dir = scratch("wide-json");
    std::fs::write(dir.join("wide.mod"), wide_statement("x := ;")).expect("write");
    let (code, stdout, _) = rapidvc(&dir, &["check", "--format", "json", "wide.mod"]);
    let stdout = text(&stdout);
    assert_eq!(code, 1, "{stdout}");
    assert!(
        stdout.contains(r#""line":3,"column":100006,"end_line":3,"end_column":100007"#),
        "{stdout}"
    );
}

#[test]
fn check_renders_sema_and_config_errors_past_column_65535_clipped() {
    let eio = format!(
        "EIO:CFG_1.0:6:1::\n#\nEIO_SIGNAL:\n\n{}-Name \"x\" -SignalType \"XX\" -Device \"d\"\n",
        wide()
    );
    let files = [("p.mod", wide_statement("y := 1;")), ("EIO.cfg", eio)];
    let args = ["check", "p.mod"];
    insta::assert_snapshot!(rendered_wide("wide-sema-config", &files, &args));
}

#[test]
fn run_time_error_past_column_65535_is_rendered_clipped() {
    let files = [(
        "wide_rt.mod",
        wide_statement("x := 1 / 0;").replace("PROC main", "VAR num x;\n  PROC main"),
    )];
    let args = ["run", "wide_rt.mod"];
    insta::assert_snapshot!(rendered_wide("wide-run", &files, &args));
}

#[test]
fn labels_on_both_ends_of_a_wide_line_keep_their_places() {
    // A label at column 11 and one past column 100,000 on the same line: two windows.
    let program = format!("MODULE M\n  VAR num a;{}VAR num A;\nENDMODULE\n", wide());
    let args = ["check", "--syntax", "two.mod"];
    insta::assert_snapshot!(rendered_wide(
        "wide-two-labels",
        &[("two.mod", program)],
        &args
    ));
}

#[test]
fn escape_sequences_in_the_source_never_reach_the_terminal() {
    let dir = scratch("escapes");
    // An OSC title sequence in a string, a CSI in a comment, and a C1 control (U+009B, the
    // one-byte CSI) from a Latin-1 file, each on a line a diagnostic shows.
    let utf8 = "MODULE M\n  PROC main()\n    TPWrite \"\u{1b}]0;pwned\u{7}\" x; ! \u{1b}[2J\n  ENDPROC\nENDMODULE\n";
    std::fs::write(dir.join("esc.mod"), utf8).expect("write");
    let mut latin1 =
        b"MODULE L\n  PROC main()\n    TPWrite \"\x9b2J\" x;\n  ENDPROC\nENDMODULE\n".to_vec();
    latin1.extend_from_slice(b"! \xe9\n");
    std::fs::write(dir.join("latin.mod"), latin1).expect("write");
    let (code, _, stderr) = rapidvc(&dir, &["check", "--syntax", "esc.mod", "latin.mod"]);
    assert_eq!(code, 1, "{}", text(&stderr));
    let shown = text(&stderr);
    for bad in ['\u{1b}', '\u{7}', '\u{9b}'] {
        assert!(!shown.contains(bad), "{bad:?} reached the output:\n{shown}");
    }
    // The replacements keep the label under the token it points at.
    insta::assert_snapshot!(shown);
    let (_, json, _) = rapidvc(&dir, &["check", "--format", "json", "esc.mod", "latin.mod"]);
    assert!(
        !json.iter().any(|&b| b == 0x1b || b == 0x07),
        "raw control in JSON"
    );
}

#[test]
fn a_lone_cr_ends_a_line_for_the_header_and_the_snippet() {
    let dir = scratch("lone-cr");
    // Old Mac line ends, a comment among them (it ends at its CR).
    let program = "MODULE M\r  ! a comment\r  PROC main()\r    x := ;\r  ENDPROC\rENDMODULE\r";
    std::fs::write(dir.join("mac.mod"), program).expect("write");
    let (code, stdout, stderr) = rapidvc(&dir, &["check", "--syntax", "mac.mod"]);
    let stderr = text(&stderr);
    assert_eq!(code, 1, "{stderr}");
    insta::assert_snapshot!(stderr);
    let (_, json, _) = rapidvc(&dir, &["check", "--format", "json", "mac.mod"]);
    assert!(
        text(&json).contains(r#""line":4,"column":10"#),
        "{}",
        text(&stdout)
    );
}

#[test]
fn a_runaway_recursion_shows_the_ends_of_the_call_stack_and_counts_the_rest() {
    let dir = scratch("recursion");
    let program = "MODULE M\n  PROC down(num n)\n    down n + 1;\n  ENDPROC\n  PROC main()\n    down 1;\n  ENDPROC\nENDMODULE\n";
    std::fs::write(dir.join("deep.mod"), program).expect("write");
    let (code, _, stderr) = rapidvc(&dir, &["run", "deep.mod"]);
    let stderr = text(&stderr);
    assert_eq!(code, 1, "{stderr}");
    // The depth depends on the interpreter's stack (debug or release build).
    let depth: usize = stderr
        .split("calls nested ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|n| n.parse().ok())
        .expect("the depth in the message");
    let stack: Vec<&str> = stderr
        .lines()
        .skip_while(|l| !l.contains("RAPID call stack"))
        .skip(1)
        .collect();
    let frames = stack.iter().filter(|l| l.starts_with("  in ")).count();
    assert_eq!(frames, 20, "{stderr}");
    assert_eq!(stack.first(), Some(&"  in down at deep.mod:3:5"));
    assert_eq!(stack.last(), Some(&"  in main at deep.mod:6:5"));
    let omitted = format!("  … {} more frames …", depth - 20);
    assert_eq!(stack.get(10), Some(&omitted.as_str()), "{stderr}");
}
