//! Child processes for tests that run `rapidvc run` and sensor scripts: output collected on threads, every wait bounded, the child killed when its guard is dropped.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdout, Command, Stdio};
use std::sync::mpsc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// A running child; killed on drop.
pub struct Proc {
    child: Child,
    out: Option<JoinHandle<String>>,
    err: Option<JoinHandle<String>>,
    lines: Option<mpsc::Receiver<String>>,
}

/// How a child ended.
#[derive(Debug)]
pub struct Ended {
    /// Exit code (`None`: killed after the time-out, or by a signal).
    pub code: Option<i32>,
    /// Everything it wrote on stdout.
    pub stdout: String,
    /// Everything it wrote on stderr.
    pub stderr: String,
    /// It ran into the time-out.
    pub timed_out: bool,
}

fn collect(mut r: impl Read + Send + 'static) -> JoinHandle<String> {
    std::thread::spawn(move || {
        let mut s = String::new();
        let _ = r.read_to_string(&mut s);
        s
    })
}

fn lines_of(stdout: ChildStdout) -> (mpsc::Receiver<String>, JoinHandle<String>) {
    let (tx, rx) = mpsc::channel();
    let h = std::thread::spawn(move || {
        let mut all = String::new();
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            all.push_str(&line);
            all.push('\n');
            let _ = tx.send(line);
        }
        all
    });
    (rx, h)
}

impl Proc {
    /// Starts `cmd` with piped stdout and stderr.
    pub fn spawn(mut cmd: Command) -> Proc {
        let mut child = cmd
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start {cmd:?}: {e}"));
        let (lines, out) = lines_of(child.stdout.take().unwrap());
        let err = collect(child.stderr.take().unwrap());
        Proc {
            child,
            out: Some(out),
            err: Some(err),
            lines: Some(lines),
        }
    }

    /// The child's process id (to send it a signal).
    pub fn id(&self) -> u32 {
        self.child.id()
    }

    /// The next stdout line, waiting at most `timeout`.
    pub fn next_line(&mut self, timeout: Duration) -> Option<String> {
        self.lines.as_ref()?.recv_timeout(timeout).ok()
    }

    /// Waits for the end (at most `timeout`, then kills it).
    pub fn wait(mut self, timeout: Duration) -> Ended {
        let start = Instant::now();
        let mut timed_out = false;
        let status = loop {
            if let Some(s) = self.child.try_wait().unwrap() {
                break Some(s);
            }
            if start.elapsed() > timeout {
                timed_out = true;
                let _ = self.child.kill();
                break self.child.wait().ok();
            }
            std::thread::sleep(Duration::from_millis(10));
        };
        // Lines not read by the caller stay in the collected output.
        self.lines = None;
        let stdout = self.out.take().unwrap().join().unwrap_or_default();
        let stderr = self.err.take().unwrap().join().unwrap_or_default();
        Ended {
            code: status.and_then(|s| s.code()),
            stdout,
            stderr,
            timed_out,
        }
    }
}

impl Drop for Proc {
    fn drop(&mut self) {
        if let Ok(None) = self.child.try_wait() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}

/// The repository root (this crate lives in `tests/support`).
pub fn root() -> PathBuf {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    here.ancestors().nth(2).unwrap_or(here).to_path_buf()
}

/// `rapidvc run` on `program` (relative to the repository root) with `args`; `rapidvc` is
/// the binary's command ([`crate::rapidvc!`]).
pub fn rapidvc_run(mut cmd: Command, program: &str, args: &[String]) -> Command {
    cmd.arg("run").arg(root().join(program)).args(args);
    cmd.env("NO_COLOR", "1").current_dir(root());
    cmd
}

/// Runs `rapidvc run` to its end (at most `timeout`).
pub fn run_program(rapidvc: Command, program: &str, args: &[String], timeout: Duration) -> Ended {
    let ended = Proc::spawn(rapidvc_run(rapidvc, program, args)).wait(timeout);
    assert!(
        !ended.timed_out,
        "rapidvc run {program} did not end within {timeout:?}\n{}\n{}",
        ended.stdout, ended.stderr
    );
    ended
}

/// The Python to run the client scripts with (`RAPIDVC_PYTHON`). The tests that call this
/// are ignored unless the variable was set when they were built (`build.rs` sets the
/// `rapidvc_python` cfg), so `cargo test` on a fresh machine reports them as ignored and CI,
/// which exports it, runs them; run with `--include-ignored` but without the variable, they
/// fail rather than pass having done nothing.
pub fn python() -> PathBuf {
    match std::env::var_os("RAPIDVC_PYTHON") {
        Some(p) => PathBuf::from(p),
        None => panic!(
            "RAPIDVC_PYTHON is not set: this test drives the PyPI EGM clients. Create the \
             environment with `python3 -m venv .venv-egm && .venv-egm/bin/pip install \
             abb_robot_client ABBRobotEGM` and run \
             `RAPIDVC_PYTHON=$PWD/.venv-egm/bin/python cargo test`"
        ),
    }
}

/// A client script of `tests/clients` running as a sensor; its port once bound.
pub fn start_script(python: &Path, script: &str, args: &[&str]) -> (Proc, u16) {
    let mut cmd = Command::new(python);
    cmd.arg(root().join("tests/clients").join(script))
        .args(args);
    let mut p = Proc::spawn(cmd);
    let first = p
        .next_line(Duration::from_secs(20))
        .unwrap_or_else(|| panic!("{script} printed no port"));
    let port: u16 = json_field(&first, "port").parse().unwrap();
    (p, port)
}

/// The value of `"key": …` in a flat one-line JSON object (numbers, booleans, arrays).
pub fn json_field<'a>(json: &'a str, key: &str) -> &'a str {
    let pat = format!("\"{key}\": ");
    let start = json
        .find(&pat)
        .map(|i| i + pat.len())
        .unwrap_or_else(|| panic!("no {key} in {json}"));
    let rest = &json[start..];
    let end = if rest.starts_with('[') {
        rest.find(']').map(|i| i + 1)
    } else {
        rest.find([',', '}'])
    };
    &rest[..end.unwrap_or(rest.len())]
}

/// The numbers of a JSON array or a RAPID value (`[1,2,3]`).
pub fn numbers(value: &str) -> Vec<f64> {
    value
        .trim_matches(['[', ']'])
        .split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|s| s.trim().parse().unwrap())
        .collect()
}

/// The numbers after `prefix` on a stdout line (`joints: [1,2,…]`).
pub fn printed(stdout: &str, prefix: &str) -> Vec<f64> {
    let line = stdout
        .lines()
        .find_map(|l| l.strip_prefix(prefix))
        .unwrap_or_else(|| panic!("no `{prefix}` line in\n{stdout}"));
    numbers(line.trim())
}

/// True when every value is within `tol` of the wanted one.
pub fn near(got: &[f64], want: &[f64], tol: f64) -> bool {
    got.len() == want.len() && got.iter().zip(want).all(|(a, b)| (a - b).abs() <= tol)
}

/// `rapidvc ARGS` (`cmd`, from [`crate::rapidvc!`]) run to its end in `dir`, with `COLUMNS`
/// = `columns` and no colour: (exit code, stdout, stderr) as text.
pub fn output_in(
    mut cmd: Command,
    dir: &Path,
    args: &[&str],
    columns: u16,
) -> (i32, String, String) {
    let out = cmd
        .args(args)
        .current_dir(dir)
        .env("COLUMNS", columns.to_string())
        .env("NO_COLOR", "1")
        .output()
        .expect("run rapidvc");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The arguments of a golden run of the program `path`: `run`, the extra arguments of its
/// `! args: …` line if it has one, and its file name (the run happens in its directory).
pub fn golden_args(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).expect("read program");
    let mut args = vec!["run".to_string()];
    if let Some(extra) = text.lines().find_map(|l| l.strip_prefix("! args:")) {
        args.extend(extra.split_whitespace().map(str::to_string));
    }
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .expect("file name");
    args.push(name.to_string());
    args
}

/// Poll `done` every `every` until it holds; panics naming `what` once `limit` has passed
/// (tests that wait for a live controller always end by themselves).
pub fn wait_until(limit: Duration, every: Duration, what: &str, mut done: impl FnMut() -> bool) {
    let t0 = Instant::now();
    while !done() {
        assert!(t0.elapsed() < limit, "timed out after {limit:?}: {what}");
        std::thread::sleep(every);
    }
}
