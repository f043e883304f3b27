//! Interpreter speed and memory, in two parts.
//!
//! * `loop`: `benches/interp.mod` (10 million iterations of arithmetic, array indexing and a
//!   function call) run in this process against the same algorithm in CPython
//!   (`benches/interp.py`, `python3` on PATH), timed in the same run; peak RSS after 1 million
//!   and after 10 million iterations shows whether memory grows with the iteration count.
//! * `lang`: the language suite of `benches/lang/` (records, strings, TEST, WHILE, recursion,
//!   late binding, pose math; see its README) plus the loop above, each program written
//!   three times with the same algorithm: RAPID (`rapidvc run`), Python (`python3`) and
//!   Lua 5.4 (`lua5.4`). Every side is a whole process; its CPU time (user + sys, from
//!   `getrusage` of the waited-for child) is the minimum of several runs, and the three must
//!   print the same result line.
//!
//! Run: `cargo bench --bench interp` (both parts, a release build), or
//! `cargo bench --bench interp -- lang [NAME…] [--runs N] [--scale F] [--rapidvc PATH]`
//! for the suite alone (`--scale 0.1` for a quick look, `--rapidvc` to time another build
//! of rapidvc, such as a copy of an earlier one), `-- loop` for the loop alone.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Arc, Mutex};
use std::time::Instant;

use rapidvc::interp::{Interp, Output, VirtualHost};
use rapidvc::program;
use rapidvc_testkit::fixed_iters::Fixed;

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
    if let Some(fixed) = Fixed::from_env() {
        lang::fixed(&fixed);
        return;
    }
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| a != "--bench")
        .collect();
    match args.first().map(String::as_str) {
        Some("loop") => loop_bench(),
        Some("lang") => lang::run(&args[1..]),
        _ => {
            loop_bench();
            println!();
            lang::run(&[]);
        }
    }
}

/// The in-process loop benchmark (`benches/interp.mod` against CPython) and memory.
fn loop_bench() {
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

/// The language suite: every program as RAPID, Python and Lua, whole processes side by side.
mod lang {
    use std::path::{Path, PathBuf};
    use std::process::{Command, Stdio};

    use nix::sys::resource::{UsageWho, getrusage};

    /// A program of the suite: its name, its files without extension (under `benches/`) and
    /// the RAPID constant holding its size (the Python and Lua versions take the size as
    /// their argument).
    struct Program {
        name: &'static str,
        stem: &'static str,
        constant: &'static str,
    }

    const SUITE: &[Program] = &[
        Program {
            name: "numeric",
            stem: "interp",
            constant: "ITERATIONS",
        },
        Program {
            name: "records",
            stem: "lang/records",
            constant: "N",
        },
        Program {
            name: "strings",
            stem: "lang/strings",
            constant: "N",
        },
        Program {
            name: "testcase",
            stem: "lang/testcase",
            constant: "N",
        },
        Program {
            name: "loops",
            stem: "lang/loops",
            constant: "N",
        },
        Program {
            name: "recursion",
            stem: "lang/recursion",
            constant: "N",
        },
        Program {
            name: "latebind",
            stem: "lang/latebind",
            constant: "N",
        },
        Program {
            name: "pose",
            stem: "lang/pose",
            constant: "N",
        },
    ];

    /// CPU time (user + sys, seconds) of every terminated and waited-for child so far.
    fn children_cpu() -> f64 {
        match getrusage(UsageWho::RUSAGE_CHILDREN) {
            Ok(u) => {
                let t =
                    |tv: nix::sys::time::TimeVal| tv.tv_sec() as f64 + tv.tv_usec() as f64 * 1e-6;
                t(u.user_time()) + t(u.system_time())
            }
            Err(_) => f64::NAN,
        }
    }

    /// Run a command to its end: (CPU seconds of the process, first line of its output), or
    /// why it failed.
    fn measure(cmd: &mut Command) -> Result<(f64, String), String> {
        let before = children_cpu();
        let out = cmd
            .stdin(Stdio::null())
            .output()
            .map_err(|e| format!("cannot start {cmd:?}: {e}"))?;
        let cpu = children_cpu() - before;
        let text = String::from_utf8_lossy(&out.stdout);
        if !out.status.success() {
            return Err(format!(
                "{cmd:?} failed ({}): {text}{}",
                out.status,
                String::from_utf8_lossy(&out.stderr)
            ));
        }
        Ok((cpu, text.lines().next().unwrap_or("").trim().to_string()))
    }

    /// The first of `names` that runs (`NAME -v`), if any.
    fn find_tool(names: &[&'static str]) -> Option<&'static str> {
        names.iter().copied().find(|n| {
            Command::new(n)
                .arg("-v")
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .status()
                .is_ok()
        })
    }

    fn version(tool: &str, arg: &str) -> String {
        Command::new(tool)
            .arg(arg)
            .output()
            .map(|o| {
                let s = if o.stdout.is_empty() {
                    o.stderr
                } else {
                    o.stdout
                };
                String::from_utf8_lossy(&s).trim().to_string()
            })
            .unwrap_or_default()
    }

    /// The RAPID program with its size constant scaled by `scale`, written to `dir`, and
    /// that size.
    fn rapid_source(p: &Program, src: &Path, scale: f64, dir: &Path) -> (PathBuf, u64) {
        let text = std::fs::read_to_string(src).expect("read the RAPID program");
        let prefix = format!("CONST num {} := ", p.constant);
        let mut size = None;
        let text: String = text
            .lines()
            .map(|l| {
                let n = l
                    .trim_start()
                    .strip_prefix(&prefix)
                    .and_then(|v| v.trim_end().strip_suffix(';'))
                    .and_then(|v| v.trim().parse::<f64>().ok());
                match n {
                    Some(n) if size.is_none() => {
                        let n = ((n * scale).round() as u64).max(1);
                        size = Some(n);
                        format!("  {prefix}{n};\n")
                    }
                    _ => format!("{l}\n"),
                }
            })
            .collect();
        let Some(n) = size else {
            panic!("{} declares no `{prefix}<number>;`", src.display());
        };
        let file = dir.join(format!("{}.mod", p.name));
        std::fs::write(&file, text).expect("write the RAPID program");
        (file, n)
    }

    /// Size of the programs in the fixed-iteration mode (a fraction of the suite's).
    const FIXED_SCALE: f64 = 0.02;

    /// The fixed-iteration mode (`rapidvc_testkit::fixed_iters`, for callgrind): every
    /// program of the suite in this process at `FIXED_SCALE` of its size, named
    /// `lang/NAME`. One iteration is one run: the interpreter made for the loaded program
    /// (its routines compiled), `init` and `main`, on a `VirtualHost`; loading and checking
    /// the program come before, outside the count.
    pub fn fixed(fixed: &super::Fixed) {
        let dir = std::env::temp_dir().join(format!("rapidvc-fixed-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let benches = super::bench_dir();
        for p in SUITE {
            let mut loaded = None;
            fixed.iter(&format!("lang/{}", p.name), || {
                let loaded = loaded.get_or_insert_with(|| {
                    let src = benches.join(format!("{}.mod", p.stem));
                    let (file, _) = rapid_source(p, &src, FIXED_SCALE, &dir);
                    super::program::load(&[file], Some(&dir))
                });
                let prog = loaded.program.clone().expect("the program checks");
                let mut it =
                    super::Interp::new(prog, &loaded.registry, Box::new(super::VirtualHost::new()));
                it.init().expect("init");
                it.run("main").expect("the program runs");
            });
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// `cargo bench --bench interp -- lang [NAME…] [--runs N] [--scale F] [--rapidvc PATH]`.
    pub fn run(args: &[String]) {
        let mut runs = 3usize;
        let mut scale = 1.0f64;
        let mut only: Vec<&str> = Vec::new();
        // Another build of rapidvc (a copy of an earlier one, to compare in one run).
        let mut rapidvc = env!("CARGO_BIN_EXE_rapidvc");
        let mut it = args.iter();
        while let Some(a) = it.next() {
            match a.as_str() {
                "--runs" => {
                    runs = it
                        .next()
                        .and_then(|v| v.parse().ok())
                        .unwrap_or(runs)
                        .max(1)
                }
                "--scale" => scale = it.next().and_then(|v| v.parse().ok()).unwrap_or(scale),
                "--rapidvc" => rapidvc = it.next().map(String::as_str).unwrap_or(rapidvc),
                name => only.push(name),
            }
        }
        let python = find_tool(&["python3"]);
        let lua = find_tool(&["lua5.4", "lua"]);
        let dir = std::env::temp_dir().join(format!("rapidvc-lang-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        println!(
            "language suite: CPU time (user+sys) of the whole process, min of {runs} runs{}",
            if scale != 1.0 {
                format!(", sizes x{scale}")
            } else {
                String::new()
            }
        );
        println!(
            "  python: {}   lua: {}",
            python
                .map(|p| version(p, "--version"))
                .unwrap_or_else(|| "not found".into()),
            lua.map(|l| version(l, "-v"))
                .unwrap_or_else(|| "not found".into())
        );
        println!(
            "{:<10} {:>10} {:>10} {:>10} {:>12} {:>12}",
            "program", "rapidvc s", "CPython s", "Lua s", "vs CPython", "vs Lua"
        );
        let bench = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches");
        let mut failed = false;
        for p in SUITE {
            if !only.is_empty() && !only.contains(&p.name) {
                continue;
            }
            let (mod_file, n) =
                rapid_source(p, &bench.join(format!("{}.mod", p.stem)), scale, &dir);
            let py_file = bench.join(format!("{}.py", p.stem));
            let lua_file = bench.join(format!("{}.lua", p.stem));
            let mut best = [f64::INFINITY; 3];
            let mut lines: [Option<String>; 3] = [None, None, None];
            for _ in 0..runs {
                let mut cmds: Vec<(usize, Command)> = Vec::new();
                let mut c = Command::new(rapidvc);
                c.arg("run").arg(&mod_file);
                cmds.push((0, c));
                if let Some(py) = python {
                    let mut c = Command::new(py);
                    c.arg(&py_file).arg(n.to_string());
                    cmds.push((1, c));
                }
                if let Some(l) = lua {
                    let mut c = Command::new(l);
                    c.arg(&lua_file).arg(n.to_string());
                    cmds.push((2, c));
                }
                for (k, mut c) in cmds {
                    match measure(&mut c) {
                        Ok((cpu, line)) => {
                            best[k] = best[k].min(cpu);
                            lines[k] = Some(line);
                        }
                        Err(e) => {
                            println!("{}: {e}", p.name);
                            failed = true;
                        }
                    }
                }
            }
            let cell = |k: usize| match &lines[k] {
                Some(_) => format!("{:.3}", best[k]),
                None => "-".to_string(),
            };
            let ratio = |k: usize| match &lines[k] {
                Some(_) => format!("{:.2}x", best[k] / best[0]),
                None => "-".to_string(),
            };
            println!(
                "{:<10} {:>10} {:>10} {:>10} {:>12} {:>12}",
                p.name,
                cell(0),
                cell(1),
                cell(2),
                ratio(1),
                ratio(2)
            );
            for k in 1..3 {
                if let (Some(a), Some(b)) = (&lines[0], &lines[k])
                    && a != b
                {
                    println!(
                        "  MISMATCH: rapidvc printed `{a}`, {} `{b}`",
                        ["", "CPython", "Lua"][k]
                    );
                    failed = true;
                }
            }
        }
        println!("(vs X: X's CPU time / rapidvc's; above 1 means rapidvc is faster)");
        let _ = std::fs::remove_dir_all(&dir);
        if failed {
            std::process::exit(1);
        }
    }
}
