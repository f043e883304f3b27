//! Peak memory of `rapidvc check` on a large module: a generated 50 MB program (the
//! generator of `benches/parse.rs`, with `EIO.cfg` for its one signal) parsed, structure-checked
//! and semantically checked the way `rapidvc check FILE` does, with the binary's allocator.
//! Prints the input size, the peak RSS and their ratio. Run: `cargo bench --bench check_memory`
//! (one run, not samples: peak memory does not depend on the machine's load).

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use rapidvc::diag::Diagnostics;
use rapidvc::source::SourceMap;

use rapidvc_testkit::gen_program;

/// VmHWM (peak RSS) in kB from /proc/self/status (0 where there is none).
fn peak_rss_kb() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .unwrap_or_default()
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .unwrap_or(0)
}

fn main() {
    let dir = std::env::temp_dir().join(format!("rapidvc-check-memory-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch directory");
    let path = dir.join("big.mod");
    let len = {
        let text = gen_program::program(50 << 20);
        std::fs::write(&path, &text).expect("write the program");
        text.len()
    };
    std::fs::write(
        dir.join("EIO.cfg"),
        "EIO:CFG_1.0:6:1::\n#\nEIO_SIGNAL:\n\n      -Name \"doGripper\" -SignalType \"DO\" -Device \"d651\"\n",
    )
    .expect("write EIO.cfg");
    let before = peak_rss_kb();
    let mut map = SourceMap::new();
    let mut diags = Diagnostics::new();
    let id = rapidvc::program::rapid_files::load_file(&mut map, &path).expect("read the program");
    let text = map.get(id).text.clone();
    let file = rapidvc::parse::parse_file(id, &text, &mut diags);
    rapidvc::parse::check_structure(&file, &mut diags);
    let registry = rapidvc::interp::Registry::standard();
    let files = [file];
    rapidvc::program::check_files(&files, &[path], &mut map, &registry, &mut diags);
    let peak = peak_rss_kb();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(diags.is_empty(), "the generated program must check clean");
    let mb = len as f64 / 1e6;
    println!(
        "check_memory: {mb:.1} MB module, peak RSS {:.0} MB ({:.1} x the input; {:.0} MB before the check)",
        peak as f64 / 1e3,
        peak as f64 * 1e3 / len as f64,
        before as f64 / 1e3
    );
}
