//! Peak memory of `rapidvc check` on a large module: a generated 50 MB program (the
//! generator of `benches/parse.rs`) parsed, structure-checked and semantically checked the way
//! `rapidvc check FILE` does, with the binary's allocator, in two forms:
//!
//! * `valid`: with an `EIO.cfg` for its one signal. Its only diagnostics are the task data
//!   limit (a 50 MB module of robtargets holds more than a task may: see "Data limits" in the
//!   README).
//! * `errors`: the same program with every `cycle` in `TPWrite` misspelt `cycel` (about 22,000
//!   undeclared names, each with a "did you mean" suggestion) and no `EIO.cfg` (every
//!   `SetDO doGripper` names an unknown signal).
//!
//! Each form is checked in a process of its own (peak RSS only grows). Prints the input size,
//! the peak RSS and their ratio. Run: `cargo bench --bench check_memory` (one run, not
//! samples: peak memory does not depend on the machine's load).

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use std::path::Path;
use std::process::Command;

use rapidvc::diag::Diagnostics;
use rapidvc::source::SourceMap;

use rapidvc_testkit::gen_program;

/// A field of /proc/self/status in kB (0 where there is none).
fn status_kb(field: &str) -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .unwrap_or_default()
        .lines()
        .find_map(|l| l.strip_prefix(field))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .unwrap_or(0)
}

/// VmHWM (peak RSS) in kB.
fn peak_rss_kb() -> u64 {
    status_kb("VmHWM:")
}

/// Print the resident and peak memory after a stage of the check.
fn stage(form: &str, name: &str) {
    println!(
        "check_memory {form}: after {name:<10} RSS {:>5.0} MB, peak {:>5.0} MB",
        status_kb("VmRSS:") as f64 / 1e3,
        peak_rss_kb() as f64 / 1e3
    );
}

/// The diagnostic codes and how often each was reported.
fn codes(diags: &Diagnostics) -> Vec<(String, usize)> {
    let mut out: Vec<(String, usize)> = Vec::new();
    for d in diags.iter() {
        let code = d.code().map(|c| c.to_string()).unwrap_or_default();
        match out.iter_mut().find(|(c, _)| *c == code) {
            Some((_, n)) => *n += 1,
            None => out.push((code, 1)),
        }
    }
    out
}

/// Check `path` as `rapidvc check` does and print the figures (in the child process).
fn measure(form: &str, path: &Path) {
    let len = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
    let before = peak_rss_kb();
    let mut map = SourceMap::new();
    let mut diags = Diagnostics::new();
    let id = rapidvc::program::rapid_files::load_file(&mut map, path).expect("read the program");
    stage(form, "reading");
    let file = rapidvc::parse::parse_file(id, &map.get(id).text, &mut diags);
    stage(form, "parsing");
    rapidvc::parse::check_structure(&file, &mut diags);
    stage(form, "structure");
    let registry = rapidvc::interp::Registry::standard();
    let files = [file];
    rapidvc::program::check_files(
        &files,
        &[path.to_path_buf()],
        &mut map,
        &registry,
        &mut diags,
    );
    stage(form, "sema");
    let peak = peak_rss_kb();
    let codes = codes(&diags);
    let expected: &[&str] = match form {
        "valid" => &["rapidvc::sema::data_limit"],
        _ => &[
            "rapidvc::sema::data_limit",
            "rapidvc::sema::undeclared",
            "rapidvc::sema::unknown_signal",
        ],
    };
    assert!(
        codes.iter().all(|(c, _)| expected.contains(&c.as_str())),
        "unexpected diagnostics for the {form} program: {codes:?}"
    );
    println!(
        "check_memory {form}: {:.1} MB module, {} diagnostics, peak RSS {:.0} MB ({:.1} x the input; {:.0} MB before the check)",
        len as f64 / 1e6,
        diags.len(),
        peak as f64 / 1e3,
        peak as f64 * 1e3 / len as f64,
        before as f64 / 1e3
    );
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--measure") {
        let (form, path) = (&args[i + 1], &args[i + 2]);
        measure(form, Path::new(path));
        return;
    }
    let dir = std::env::temp_dir().join(format!("rapidvc-check-memory-{}", std::process::id()));
    let text = gen_program::program(50 << 20);
    let errors = text.replace("\\Num:=cycle;", "\\Num:=cycel;");
    assert_ne!(errors, text, "the generator writes `\\Num:=cycle;`");
    for (form, text) in [("valid", text), ("errors", errors)] {
        let sub = dir.join(form);
        std::fs::create_dir_all(&sub).expect("scratch directory");
        let path = sub.join("big.mod");
        std::fs::write(&path, text).expect("write the program");
        if form == "valid" {
            std::fs::write(
                sub.join("EIO.cfg"),
                "EIO:CFG_1.0:6:1::\n#\nEIO_SIGNAL:\n\n      -Name \"doGripper\" -SignalType \"DO\" -Device \"d651\"\n",
            )
            .expect("write EIO.cfg");
        }
        let status = Command::new(std::env::current_exe().expect("this benchmark"))
            .arg("--measure")
            .arg(form)
            .arg(&path)
            .status()
            .expect("run the measurement");
        assert!(status.success(), "the {form} measurement failed");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
