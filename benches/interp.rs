//! Interpreter speed and memory: `benches/interp.mod` (10 million iterations of arithmetic,
//! array indexing and a function call) against the same algorithm in CPython
//! (`benches/interp.py`, `python3` on PATH), timed in the same run; peak RSS after 1 million
//! and after 10 million iterations shows whether memory grows with the iteration count.
//!
//! Run: `cargo bench --bench interp` (a release build).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Arc, Mutex};
use std::time::Instant;

use rapidvc::interp::{Interp, Output, VirtualHost};
use rapidvc::program;

fn bench_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("benches")
}

/// CPU time of this thread in seconds (from /proc/thread-self/schedstat, nanoseconds).
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<u64>().ok())
        .map(|ns| ns as f64 / 1e9)
        .unwrap_or(0.0)
}

/// A timing: wall and CPU seconds.
#[derive(Clone, Copy)]
struct Timing {
    wall: f64,
    cpu: f64,
}

/// Run the RAPID benchmark with `n` iterations: (timing, TP output).
fn run_rapid(n: u64) -> (Timing, String) {
    let src = std::fs::read_to_string(bench_dir().join("interp.mod")).expect("read interp.mod");
    let src = src.replace(
        "CONST num ITERATIONS := 10000000;",
        &format!("CONST num ITERATIONS := {n};"),
    );
    let dir = std::env::temp_dir().join(format!("rapidvc-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join("bench.mod");
    std::fs::write(&file, src).expect("write program");
    let loaded = program::load(&[file], Some(&dir));
    let prog = loaded.program.clone().expect("benchmark program checks");
    let tp = Arc::new(Mutex::new(String::new()));
    let sink = tp.clone();
    let host = VirtualHost::new().with_sink(move |o| {
        if let (Output::TpWrite(s), Ok(mut t)) = (o, sink.lock()) {
            t.push_str(s);
        }
    });
    let mut it = Interp::new(prog, &loaded.registry, Box::new(host));
    it.init().expect("init");
    let cpu = cpu_seconds();
    let start = Instant::now();
    it.run("main").expect("benchmark runs");
    let secs = Timing {
        wall: start.elapsed().as_secs_f64(),
        cpu: cpu_seconds() - cpu,
    };
    let _ = std::fs::remove_dir_all(&dir);
    let out = tp.lock().map(|t| t.clone()).unwrap_or_default();
    (secs, out)
}

/// Run the CPython version: (loop timing, "acc: …"), or None without python3.
fn run_python(n: u64) -> Option<(Timing, String)> {
    let out = Command::new("python3")
        .arg(bench_dir().join("interp.py"))
        .arg(n.to_string())
        .output()
        .ok()?;
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let acc = text.lines().find(|l| l.starts_with("acc: "))?.to_string();
    let field = |name: &str| -> Option<f64> {
        text.lines()
            .find_map(|l| l.strip_prefix(name))?
            .trim()
            .parse()
            .ok()
    };
    Some((
        Timing {
            wall: field("seconds: ")?,
            cpu: field("cpu: ")?,
        },
        acc,
    ))
}

/// (VmHWM, VmRSS) in kB from /proc/self/status.
fn memory_kb() -> (u64, u64) {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let field = |name: &str| {
        status
            .lines()
            .find_map(|l| l.strip_prefix(name))
            .and_then(|v| v.split_whitespace().next())
            .and_then(|v| v.parse().ok())
            .unwrap_or(0)
    };
    (field("VmHWM:"), field("VmRSS:"))
}

fn main() {
    // `cargo test --benches` passes `--bench`-less arguments; only run when benchmarking.
    if std::env::args().any(|a| a == "--list") {
        return;
    }
    let small = 1_000_000;
    let big = 10_000_000;
    let (t_small, out_small) = run_rapid(small);
    let (hwm_small, rss_small) = memory_kb();
    let (t_big, out_big) = run_rapid(big);
    let (hwm_big, rss_big) = memory_kb();
    println!(
        "rapidvc  {small:>9} iterations: {:7.3} s CPU, {:7.3} s wall  ({out_small})",
        t_small.cpu, t_small.wall
    );
    println!(
        "rapidvc  {big:>9} iterations: {:7.3} s CPU, {:7.3} s wall  ({out_big})",
        t_big.cpu, t_big.wall
    );
    println!(
        "rapidvc  {:.1} ns CPU per iteration",
        t_big.cpu * 1e9 / big as f64
    );
    println!(
        "memory   peak RSS after {small}: {hwm_small} kB, after {big}: {hwm_big} kB (current {rss_small} → {rss_big} kB)"
    );
    match run_python(big) {
        Some((t_py, out_py)) => {
            println!(
                "CPython  {big:>9} iterations: {:7.3} s CPU, {:7.3} s wall  ({out_py})",
                t_py.cpu, t_py.wall
            );
            if out_py != out_big {
                println!("MISMATCH: CPython computed `{out_py}`, rapidvc `{out_big}`");
                std::process::exit(1);
            }
            println!(
                "ratio    rapidvc is {:.2}x faster than CPython (CPU time; {:.2}x by wall time)",
                t_py.cpu / t_big.cpu,
                t_py.wall / t_big.wall
            );
        }
        None => println!("CPython  not available (python3 not on PATH)"),
    }
}
