//! `rapidvc` as a hostile or unlucky user meets it: absurd numeric options, output paths
//! that are inputs, a `--pers` file on a full disk or in a missing directory, Ctrl-C in the
//! middle of a run, a misspelled `--device`, an empty `--entry`, load processes of `bench
//! realtime` whose parent is killed. Every case runs the real binary; each child is bounded
//! by a time-out and killed when its guard is dropped.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use rapidvc_testkit::procs;
use rapidvc_testkit::rapidvc;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use procs::{Ended, Proc};

const LIMIT: Duration = Duration::from_secs(60);

/// A fresh directory for one test.
fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rapidvc-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `rapidvc ARGS…` in `dir`.
fn rapidvc(dir: &Path, args: &[&str]) -> Command {
    let mut cmd = rapidvc!();
    cmd.args(args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .env("COLUMNS", "1000");
    cmd
}

/// Runs `rapidvc ARGS…` in `dir` to its end.
fn run_in(dir: &Path, args: &[&str]) -> Ended {
    let ended = Proc::spawn(rapidvc(dir, args)).wait(LIMIT);
    assert!(!ended.timed_out, "rapidvc {args:?} did not end");
    ended
}

const COUNTER: &str = "MODULE counter\n  PERS num runs := 0;\n  PROC main()\n    Incr runs;\n    TPWrite \"runs: \" \\Num:=runs;\n  ENDPROC\nENDMODULE\n";

// ---------------------------------------------------------------------------------------
// Item 5: numeric options.

/// Every numeric option refuses absurd values with a clap usage error (exit 2) naming the
/// option, before anything runs; none panics.
#[test]
fn absurd_numeric_options_are_usage_errors() {
    let dir = temp_dir("numbers");
    std::fs::write(dir.join("counter.mod"), COUNTER).unwrap();
    let run = |opts: &[&str]| -> Vec<String> {
        let mut v: Vec<String> = vec!["run".into(), "counter.mod".into()];
        v.extend(opts.iter().map(|s| s.to_string()));
        v
    };
    let cases: Vec<(Vec<String>, &str)> = vec![
        (run(&["--max-time", "1e20"]), "--max-time"),
        (run(&["--realtime", "--max-time", "1e30"]), "--max-time"),
        (run(&["--max-time", "0"]), "--max-time"),
        (run(&["--max-time", "nan"]), "--max-time"),
        (run(&["--max-time=-5"]), "--max-time"),
        (run(&["--period", "0"]), "--period"),
        (run(&["--period", "1e300"]), "--period"),
        (run(&["--period", "inf"]), "--period"),
        (run(&["--lockstep-timeout", "0"]), "--lockstep-timeout"),
        (
            run(&["--lockstep-timeout", "18446744073709551615"]),
            "--lockstep-timeout",
        ),
        (run(&["--cycles", "0"]), "--cycles"),
        (run(&["--max-steps", "0"]), "--max-steps"),
        (run(&["--max-steps=-1"]), "--max-steps"),
        (run(&["--start", "0,0,0,0,nan,0"]), "--start"),
        (run(&["--start", "0,0,0,0,1e400,0"]), "--start"),
        (
            ["bench", "realtime", "--seconds", "1e30"]
                .map(String::from)
                .to_vec(),
            "--seconds",
        ),
        (
            ["bench", "realtime", "--load", "100000"]
                .map(String::from)
                .to_vec(),
            "--load",
        ),
        (
            ["bench", "realtime", "--spin-us", "1000000000"]
                .map(String::from)
                .to_vec(),
            "--spin-us",
        ),
        (
            ["bench", "virtual", "--seconds", "1e30"]
                .map(String::from)
                .to_vec(),
            "--seconds",
        ),
        (
            ["bench", "egm", "--seconds=-1"].map(String::from).to_vec(),
            "--seconds",
        ),
        (
            ["sensor", "--duration", "1e30"].map(String::from).to_vec(),
            "--duration",
        ),
        (
            ["sensor", "--pattern", "sine", "--amplitude", "nan"]
                .map(String::from)
                .to_vec(),
            "--amplitude",
        ),
        (
            ["sensor", "--pattern", "sine", "--frequency=-1"]
                .map(String::from)
                .to_vec(),
            "--frequency",
        ),
        (
            ["sensor", "--pattern", "circle", "--radius", "inf"]
                .map(String::from)
                .to_vec(),
            "--radius",
        ),
        (
            ["sensor", "--pathcorr", "ramp", "--ramp-time", "0"]
                .map(String::from)
                .to_vec(),
            "--ramp-time",
        ),
        (
            ["sensor", "--count", "0"].map(String::from).to_vec(),
            "--count",
        ),
        (
            ["sensor", "--port", "70000"].map(String::from).to_vec(),
            "--port",
        ),
        (
            ["test", "counter.mod", "--max-steps", "0"]
                .map(String::from)
                .to_vec(),
            "--max-steps",
        ),
    ];
    for (args, option) in cases {
        let argv: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = run_in(&dir, &argv);
        assert_eq!(out.code, Some(2), "{argv:?}: {}", out.stderr);
        assert!(
            out.stderr.contains("invalid value") && out.stderr.contains(option),
            "{argv:?}: {}",
            out.stderr
        );
        assert!(!out.stderr.contains("panicked"), "{argv:?}: {}", out.stderr);
        assert_eq!(out.stdout, "", "{argv:?}: nothing may run");
    }
    // The bounds themselves are accepted.
    let out = run_in(
        &dir,
        &[
            "run",
            "counter.mod",
            "--max-time",
            "1e9",
            "--period",
            "100",
            "--lockstep-timeout",
            "600000",
        ],
    );
    assert_eq!(out.code, Some(0), "{}", out.stderr);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The processes of one parent (from `/proc`).
fn children_of(pid: u32) -> Vec<u32> {
    let mut out = Vec::new();
    for e in std::fs::read_dir("/proc").unwrap().flatten() {
        let Ok(child) = e.file_name().to_string_lossy().parse::<u32>() else {
            continue;
        };
        let Ok(stat) = std::fs::read_to_string(format!("/proc/{child}/stat")) else {
            continue;
        };
        // `pid (comm) state ppid …`; comm may hold spaces and parentheses.
        let after = &stat[stat.rfind(')').unwrap() + 2..];
        let ppid: u32 = after.split(' ').nth(1).unwrap().parse().unwrap();
        if ppid == pid {
            out.push(child);
        }
    }
    out
}

/// A process that still runs (not gone, not a zombie).
fn alive(pid: u32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/stat"))
        .map(|stat| {
            let after = &stat[stat.rfind(')').unwrap() + 2..];
            !after.starts_with('Z') && !after.starts_with('X')
        })
        .unwrap_or(false)
}

/// `bench realtime`'s busy-loop load processes end when rapidvc is killed (SIGKILL leaves
/// no time for clean-up): they watch a pipe whose write end only the bench holds. (Before,
/// `timeout … sh -c 'while :; do :; done'` children spun on until their time-out.)
#[test]
fn bench_load_processes_die_with_their_parent() {
    let dir = temp_dir("bench-load");
    // No pipes: an orphan holding them would make reading the output wait for the orphan.
    let mut bench = rapidvc(
        &dir,
        &[
            "bench",
            "realtime",
            "--seconds",
            "120",
            "--load",
            "1",
            "--no-priority",
        ],
    )
    .stdin(Stdio::null())
    .stdout(Stdio::null())
    .stderr(Stdio::null())
    .spawn()
    .unwrap();
    let start = Instant::now();
    let workers = loop {
        let w = children_of(bench.id());
        if !w.is_empty() || start.elapsed() > Duration::from_secs(20) {
            break w;
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    bench.kill().unwrap();
    let status = bench.wait().unwrap();
    assert_eq!(status.code(), None, "killed by the signal");
    assert_eq!(workers.len(), 1, "one load process expected: {workers:?}");
    let start = Instant::now();
    while workers.iter().any(|&w| alive(w)) && start.elapsed() < Duration::from_secs(10) {
        std::thread::sleep(Duration::from_millis(50));
    }
    let orphans: Vec<u32> = workers.iter().copied().filter(|&w| alive(w)).collect();
    let grandchildren: Vec<u32> = orphans.iter().flat_map(|&o| children_of(o)).collect();
    for &o in orphans.iter().chain(&grandchildren) {
        let _ = Command::new("kill")
            .args(["-KILL", &o.to_string()])
            .status();
    }
    assert!(
        orphans.is_empty(),
        "load processes outlived the killed bench: {orphans:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

// ---------------------------------------------------------------------------------------
// Item 10: `--pers`.

/// A full disk while the persistents are written: the run reports it (exit 2) and the old
/// file is whole, with nothing left beside it. A tiny tmpfs in a private mount namespace
/// (`unshare`, as root or with user namespaces) is the full disk.
#[test]
fn a_full_disk_never_truncates_the_pers_file() {
    let dir = temp_dir("full-disk");
    // A program whose persistents need more room than the disk has left.
    std::fs::write(
        dir.join("big.mod"),
        "MODULE big\n  PERS num runs := 0;\n  PERS string s1 := \"\";\n  PERS string s2 := \"\";\n  PERS string s3 := \"\";\n  PROC main()\n    Incr runs;\n    s1 := \"AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA\";\n    s2 := s1;\n    s3 := s1;\n    TPWrite \"ran\";\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    let disk = dir.join("disk");
    std::fs::create_dir_all(&disk).unwrap();
    let original = "! my counter\nPERS num runs := 41;\n";
    let script = format!(
        "set -e\n\
         mount -t tmpfs -o size=8k tmpfs disk\n\
         printf '%s' '{original}' > disk/state.pers\n\
         dd if=/dev/zero of=disk/fill bs=1k count=64 2>/dev/null || true\n\
         set +e\n\
         '{exe}' run big.mod --pers disk/state.pers\n\
         echo \"exit=$?\"\n\
         echo '--- file'\n\
         cat disk/state.pers\n\
         echo '--- dir'\n\
         ls -A disk\n",
        exe = env!("CARGO_BIN_EXE_rapidvc"),
    );
    let mut cmd = Command::new("unshare");
    cmd.args(["-rm", "sh", "-c", &script]).current_dir(&dir);
    let out = Proc::spawn(cmd).wait(LIMIT);
    assert_eq!(
        out.code,
        Some(0),
        "unshare -rm must be able to mount a tmpfs here: {}",
        out.stderr
    );
    let (head, rest) = out.stdout.split_once("--- file\n").expect(&out.stdout);
    let (file, listing) = rest.split_once("--- dir\n").unwrap();
    assert!(head.contains("ran\n"), "{}", out.stdout);
    assert!(head.contains("exit=2"), "{}\n{}", out.stdout, out.stderr);
    assert!(
        out.stderr.contains("cannot write disk/state.pers")
            && out.stderr.contains("left as it was"),
        "{}",
        out.stderr
    );
    assert_eq!(file, original, "the file must be untouched");
    assert_eq!(
        listing, "fill\nstate.pers\n",
        "no temporary file may remain"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A `--pers` file in a directory that does not exist is refused before the program runs.
#[test]
fn a_pers_file_in_a_missing_directory_is_refused_before_the_run() {
    let dir = temp_dir("pers-dir");
    std::fs::write(dir.join("counter.mod"), COUNTER).unwrap();
    let out = run_in(
        &dir,
        &["run", "counter.mod", "--pers", "nowhere/state.pers"],
    );
    assert_eq!(out.code, Some(2), "{}", out.stderr);
    assert_eq!(out.stdout, "", "nothing may run");
    assert!(
        out.stderr
            .contains("--pers nowhere/state.pers: the directory nowhere does not exist"),
        "{}",
        out.stderr
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Arrays in RAPID syntax are read and written back in place; comments, blank lines and
/// other entries stay where they were; a line that is not a declaration is refused before
/// the run and the file stays as it is.
#[test]
fn pers_files_keep_arrays_comments_and_unknown_entries() {
    let dir = temp_dir("pers-arrays");
    std::fs::write(
        dir.join("arr.mod"),
        "MODULE arr\n  PERS num speeds{3} := [1,2,3];\n  PERS num grid{2,2} := [[0,0],[0,0]];\n  PERS num runs := 0;\n  PROC main()\n    Incr runs;\n    speeds{2} := speeds{2} + 10;\n    grid{2,1} := grid{2,1} + 1;\n    TPWrite \"speeds: \" + ValToStr(speeds{1}) + \",\" + ValToStr(speeds{2}) + \",\" + ValToStr(speeds{3});\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    let pers = dir.join("state.pers");
    let stored = "! cell 4 calibration, do not edit by hand\n\nPERS num speeds{3} := [100,200,300]; ! mm/s\n  PERS string other := \"kept\";\nPERS num grid{2,2} := [[1,2],[3,4]];\n";
    std::fs::write(&pers, stored).unwrap();
    let out = run_in(&dir, &["run", "arr.mod", "--pers", "state.pers"]);
    assert_eq!(out.code, Some(0), "{}", out.stderr);
    assert_eq!(out.stdout, "speeds: 100,210,300\n", "{}", out.stderr);
    assert_eq!(
        std::fs::read_to_string(&pers).unwrap(),
        "! cell 4 calibration, do not edit by hand\n\nPERS num speeds{3} := [100,210,300]; ! mm/s\n  PERS string other := \"kept\";\nPERS num grid{2,2} := [[1,2],[4,4]];\nPERS num runs := 1;\n"
    );
    // A second run reads what the first wrote.
    let out = run_in(&dir, &["run", "arr.mod", "--pers", "state.pers"]);
    assert_eq!(out.stdout, "speeds: 100,220,300\n", "{}", out.stderr);
    // Sizes that differ from the declaration: a warning, the declared value is used.
    std::fs::write(&pers, "PERS num speeds{4} := [1,2,3,4];\n").unwrap();
    let out = run_in(&dir, &["run", "arr.mod", "--pers", "state.pers"]);
    assert_eq!(out.code, Some(0));
    assert_eq!(out.stdout, "speeds: 1,12,3\n");
    assert!(
        out.stderr
            .contains("stored as `num{4}` but declared as `num{3}`"),
        "{}",
        out.stderr
    );
    // Not a regular file (a FIFO): refused before the run, never replaced.
    let fifo = dir.join("fifo");
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let out = run_in(&dir, &["run", "arr.mod", "--pers", "fifo"]);
    assert_eq!(out.code, Some(2), "{}", out.stderr);
    assert_eq!(out.stdout, "");
    assert!(out.stderr.contains("not a regular file"), "{}", out.stderr);
    assert!(!std::fs::metadata(&fifo).unwrap().is_file());
    // A broken line: refused before the run, the file is not touched.
    let broken = "PERS num runs := 1;\nrm -rf /\n";
    std::fs::write(&pers, broken).unwrap();
    let out = run_in(&dir, &["run", "arr.mod", "--pers", "state.pers"]);
    assert_eq!(out.code, Some(2));
    assert_eq!(out.stdout, "");
    assert!(out.stderr.contains("line 2"), "{}", out.stderr);
    assert_eq!(std::fs::read_to_string(&pers).unwrap(), broken);
    let _ = std::fs::remove_dir_all(&dir);
}

// ---------------------------------------------------------------------------------------
// Item 11: outputs that are inputs.

#[test]
fn outputs_that_are_inputs_or_each_other_are_refused() {
    let dir = temp_dir("outputs");
    std::fs::write(dir.join("counter.mod"), COUNTER).unwrap();
    let eio = "EIO:CFG_1.0:6:1::\n#\nEIO_SIGNAL:\n\n      -Name \"di1\" -SignalType \"DI\" -Device \"d651\"\n";
    std::fs::write(dir.join("EIO.cfg"), eio).unwrap();
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    let cases: &[(&[&str], &str)] = &[
        (
            &["--trace", "counter.mod"],
            "--trace counter.mod is an input",
        ),
        (
            &["--egm-log", "./sub/../counter.mod"],
            "--egm-log ./sub/../counter.mod is an input",
        ),
        (&["--plot", "EIO.cfg"], "--plot EIO.cfg is an input"),
        (&["--pers", "counter.mod"], "--pers counter.mod is an input"),
        (
            &["--trace", "out.csv", "--egm-log", "sub/../out.csv"],
            "are the same file",
        ),
        (
            &["--trace", "run.csv", "--pers", "run.csv"],
            "are the same file",
        ),
        (
            &["--plot", "missing/plot.svg"],
            "--plot missing/plot.svg: the directory missing does not exist",
        ),
        (&["--plot", "sub"], "--plot sub: is a directory"),
    ];
    for (opts, expected) in cases {
        let mut args = vec!["run", "counter.mod"];
        args.extend_from_slice(opts);
        let out = run_in(&dir, &args);
        assert_eq!(out.code, Some(2), "{args:?}: {}", out.stderr);
        assert_eq!(out.stdout, "", "{args:?}: nothing may run");
        assert!(out.stderr.contains(expected), "{args:?}: {}", out.stderr);
    }
    assert_eq!(
        std::fs::read_to_string(dir.join("counter.mod")).unwrap(),
        COUNTER
    );
    assert_eq!(std::fs::read_to_string(dir.join("EIO.cfg")).unwrap(), eio);
    assert!(!dir.join("out.csv").exists());
    // A symbolic link to the program is the program.
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("counter.mod", dir.join("link.csv")).unwrap();
        let out = run_in(&dir, &["run", "counter.mod", "--trace", "link.csv"]);
        assert_eq!(out.code, Some(2), "{}", out.stderr);
        assert_eq!(
            std::fs::read_to_string(dir.join("counter.mod")).unwrap(),
            COUNTER
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--egm-log` writes nothing (and creates no file) for a program without EGM.
#[test]
fn egm_log_is_not_created_without_egm() {
    let dir = temp_dir("egm-log");
    std::fs::write(dir.join("counter.mod"), COUNTER).unwrap();
    let out = run_in(&dir, &["run", "counter.mod", "--egm-log", "egm.csv"]);
    assert_eq!(out.code, Some(0), "{}", out.stderr);
    assert!(!dir.join("egm.csv").exists(), "{}", out.stderr);
    assert!(
        out.stderr
            .contains("the program uses no EGM; no log is written"),
        "{}",
        out.stderr
    );
    let _ = std::fs::remove_dir_all(&dir);
}

// ---------------------------------------------------------------------------------------
// Item 12: Ctrl-C.

/// Sends SIGINT to a process.
fn interrupt(pid: u32) {
    let status = Command::new("kill")
        .args(["-INT", &pid.to_string()])
        .status()
        .unwrap();
    assert!(status.success());
}

const MOVING: &str = "MODULE moving\n  CONST jointtarget a := [[30,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n  CONST jointtarget b := [[-30,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n  PROC main()\n    TPWrite \"moving\";\n    WHILE TRUE DO\n      MoveAbsJ a, v200, z10, tool0;\n      MoveAbsJ b, v200, z10, tool0;\n    ENDWHILE\n  ENDPROC\nENDMODULE\n";

/// Ctrl-C in a real-time run whose program is blocked on a full motion queue: the program
/// stops as a controller stops it, the trace ends with a complete row, the plot is written,
/// the summary printed, and the exit code is 130.
#[test]
fn ctrl_c_stops_the_program_and_finishes_every_output() {
    let dir = temp_dir("sigint");
    std::fs::write(dir.join("moving.mod"), MOVING).unwrap();
    let mut p = Proc::spawn(rapidvc(
        &dir,
        &[
            "run",
            "moving.mod",
            "--realtime",
            "--trace",
            "run.csv",
            "--plot",
            "run.svg",
        ],
    ));
    assert_eq!(
        p.next_line(Duration::from_secs(30)).as_deref(),
        Some("moving")
    );
    std::thread::sleep(Duration::from_millis(1500));
    interrupt(p.id());
    let out = p.wait(Duration::from_secs(30));
    assert!(!out.timed_out, "the run did not end after SIGINT");
    assert_eq!(out.code, Some(130), "{}", out.stderr);
    assert!(
        out.stderr
            .contains("program stopped (interrupted by Ctrl-C)"),
        "{}",
        out.stderr
    );
    assert!(out.stderr.contains("simulated "), "summary: {}", out.stderr);
    let trace = std::fs::read_to_string(dir.join("run.csv")).unwrap();
    assert!(trace.ends_with('\n'), "the last row is cut off");
    let mut rows = trace.lines();
    let columns = rows.next().unwrap().split(',').count();
    let rows: Vec<&str> = rows.collect();
    assert!(rows.len() > 100, "{} rows", rows.len());
    for r in &rows {
        assert_eq!(r.split(',').count(), columns, "row {r}");
    }
    let plot = std::fs::read_to_string(dir.join("run.svg")).unwrap();
    assert!(
        plot.trim_end().ends_with("</svg>"),
        "the plot is incomplete"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Ctrl-C in virtual time: during an EGM run (the session ramps out and the EGM log is
/// finished) and during a wait for a signal nobody sets.
#[test]
fn ctrl_c_stops_virtual_time_waits_and_egm_runs() {
    let dir = temp_dir("sigint-virtual");
    let session = std::fs::read_to_string(procs::root().join("tests/run_egm/joint_session.mod"))
        .unwrap()
        .replace("\\CondTime:=0.5", "\\CondTime:=1E6");
    std::fs::write(dir.join("egm.mod"), session).unwrap();
    std::fs::write(
        dir.join("wait.mod"),
        "MODULE wait\n  VAR num x := 0;\n  PROC main()\n    TPWrite \"waiting\";\n    WaitUntil x > 1;\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    let cases: [(&[&str], &str); 2] = [
        (
            &[
                "run",
                "egm.mod",
                "--max-time",
                "1e9",
                "--device",
                "sensor=builtin:sine:axis=1,amplitude=20,frequency=0.5",
                "--egm-log",
                "egm.csv",
            ],
            "state after EGMSetupUC",
        ),
        (&["run", "wait.mod", "--max-time", "1e9"], "waiting"),
    ];
    for (args, first) in cases {
        let mut p = Proc::spawn(rapidvc(&dir, args));
        let start = Instant::now();
        while !p
            .next_line(Duration::from_secs(30))
            .is_some_and(|l| l.starts_with(first))
        {
            assert!(start.elapsed() < Duration::from_secs(30), "{args:?}");
        }
        std::thread::sleep(Duration::from_millis(500));
        interrupt(p.id());
        let out = p.wait(Duration::from_secs(30));
        assert!(!out.timed_out, "{args:?}: no end after SIGINT");
        assert_eq!(out.code, Some(130), "{args:?}: {}", out.stderr);
        assert!(
            out.stderr
                .contains("program stopped (interrupted by Ctrl-C)"),
            "{args:?}: {}",
            out.stderr
        );
    }
    let log = std::fs::read_to_string(dir.join("egm.csv")).unwrap();
    let last = log.lines().last().unwrap();
    assert!(last.contains(",done,"), "the EGM run ramped out: {last}");
    let _ = std::fs::remove_dir_all(&dir);
}

// ---------------------------------------------------------------------------------------
// Item 13: `--device` names.

const SENSOR_SETUP: &str = "MODULE dev\n  VAR egmident e1;\n  PROC main()\n    EGMGetId e1;\n    EGMSetupUC ROB_1, e1, \"default\", \"sensor\" \\Joint;\n    TPWrite \"set up\";\n    EGMReset e1;\n  ENDPROC\nENDMODULE\n";

/// A `--device` name no EGMSetupUC of the program uses is refused before the run; when a
/// setup computes its device name, it is a warning.
#[test]
fn a_device_the_program_never_sets_up_is_reported() {
    let dir = temp_dir("device");
    std::fs::write(dir.join("dev.mod"), SENSOR_SETUP).unwrap();
    let out = run_in(
        &dir,
        &["run", "dev.mod", "--device", "sensr=127.0.0.1:6510"],
    );
    assert_eq!(out.code, Some(2), "{}", out.stderr);
    assert_eq!(out.stdout, "", "nothing may run");
    assert!(
        out.stderr.contains(
            "--device sensr: no EGMSetupUC/EGMSetupLTAPP of the program uses this device (it sets up `sensor`)"
        ),
        "{}",
        out.stderr
    );
    assert!(!out.stderr.contains("external sensor"), "{}", out.stderr);
    // The right name, in another case and with ABB's trailing colon: accepted.
    let out = run_in(&dir, &["run", "dev.mod", "--device", "SENSOR:=builtin"]);
    assert_eq!(out.code, Some(0), "{}", out.stderr);
    // A device name computed at run time: only a warning.
    std::fs::write(
        dir.join("dev.mod"),
        SENSOR_SETUP
            .replace(
                "VAR egmident e1;",
                "VAR egmident e1;\n  VAR string dev := \"sensor\";",
            )
            .replace("\"sensor\" \\Joint", "dev \\Joint"),
    )
    .unwrap();
    let out = run_in(&dir, &["run", "dev.mod", "--device", "sensr=builtin"]);
    assert_eq!(out.code, Some(0), "{}", out.stderr);
    assert_eq!(out.stdout, "set up\n");
    assert!(
        out.stderr.contains(
            "warning: --device sensr: no EGMSetupUC/EGMSetupLTAPP of the program names this device"
        ),
        "{}",
        out.stderr
    );
    let _ = std::fs::remove_dir_all(&dir);
}

// ---------------------------------------------------------------------------------------
// Item 16 (parts): `--entry`, the time-limit note.

#[test]
fn an_empty_or_unknown_entry_is_refused_at_load() {
    let dir = temp_dir("entry");
    std::fs::write(dir.join("counter.mod"), COUNTER).unwrap();
    for (entry, expected) in [
        (
            "",
            "--entry \"\": the name of the procedure to start is empty",
        ),
        (
            "mian",
            "--entry \"mian\": there is no procedure `mian` to start",
        ),
    ] {
        let out = run_in(&dir, &["run", "counter.mod", "--entry", entry]);
        assert_eq!(out.code, Some(2), "{}", out.stderr);
        assert_eq!(out.stdout, "");
        assert!(out.stderr.contains(expected), "{}", out.stderr);
        assert!(
            out.stderr.contains("(procedures to start: main)"),
            "{}",
            out.stderr
        );
        assert!(!out.stderr.contains("ERROR handler"), "{}", out.stderr);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// In lockstep with a live external sensor, the time limit does not claim that nothing in
/// the run could end the wait; in a closed virtual run it still does.
#[test]
fn the_time_limit_note_knows_about_a_live_sensor() {
    let dir = temp_dir("note");
    std::fs::write(
        dir.join("dev.mod"),
        SENSOR_SETUP.replace(
            "TPWrite \"set up\";",
            "TPWrite \"set up\";\n    WaitTime 100;",
        ),
    )
    .unwrap();
    let mut sensor = Proc::spawn(rapidvc(&dir, &["sensor", "--port", "0"]));
    let first = sensor.next_line(Duration::from_secs(20)).unwrap();
    let port = first
        .split_once("127.0.0.1:")
        .and_then(|(_, rest)| rest.split(':').next())
        .unwrap()
        .to_string();
    let device = format!("sensor=127.0.0.1:{port}");
    let out = run_in(
        &dir,
        &[
            "run",
            "dev.mod",
            "--device",
            &device,
            "--lockstep",
            "--max-time",
            "2",
        ],
    );
    assert_eq!(out.code, Some(1), "{}", out.stderr);
    assert!(
        out.stderr
            .contains("the program waits beyond the time limit of 2 s"),
        "{}",
        out.stderr
    );
    assert!(
        !out.stderr.contains("nothing in a virtual run"),
        "{}",
        out.stderr
    );
    drop(sensor);
    let out = run_in(&dir, &["run", "dev.mod", "--max-time", "2"]);
    assert!(
        out.stderr.contains("nothing in a virtual run can end"),
        "{}",
        out.stderr
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--cycles forever` runs as a controller in continuous mode: the entry routine again after
/// each cycle (ExitCycle included), until EXIT, an error or a limit ends it.
#[test]
fn cycles_forever_runs_until_the_program_ends_it() {
    let dir = temp_dir("forever");
    std::fs::write(
        dir.join("loop.mod"),
        "MODULE loop\n  PERS num n := 0;\n  PROC main()\n    Incr n;\n    TPWrite \"cycle \" \\Num:=n;\n    IF n = 3 ExitCycle;\n    IF n = 5 EXIT;\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    let ended = run_in(&dir, &["run", "loop.mod", "--cycles", "forever"]);
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    assert_eq!(
        ended.stdout.lines().collect::<Vec<_>>(),
        ["cycle 1", "cycle 2", "cycle 3", "cycle 4", "cycle 5"]
    );
    assert!(
        ended.stderr.contains("program ended by EXIT"),
        "{}",
        ended.stderr
    );
    // Without an end of its own, a limit ends it.
    std::fs::write(dir.join("counter.mod"), COUNTER).unwrap();
    let ended = run_in(
        &dir,
        &[
            "run",
            "counter.mod",
            "--cycles",
            "forever",
            "--max-steps",
            "50",
        ],
    );
    assert_ne!(ended.code, Some(0));
    assert!(ended.stdout.lines().count() > 5, "{}", ended.stdout);
    let ended = run_in(&dir, &["run", "counter.mod", "--cycles", "often"]);
    assert_eq!(ended.code, Some(2));
    assert!(
        ended.stderr.contains("`often` is not a number of cycles"),
        "{}",
        ended.stderr
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A program with its own module USER (a backup's user.sys) uses that one, not rapidvc's
/// default: what its user.sys leaves out does not exist, and what it declares is writable.
#[test]
fn a_programs_own_user_module_replaces_the_default_one() {
    let dir = temp_dir("usermod");
    std::fs::write(
        dir.join("user.sys"),
        "MODULE user (SYSMODULE)\n  VAR num reg1 := 5;\nENDMODULE\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("main.mod"),
        "MODULE MainModule\n  PROC main()\n    Incr reg1;\n    TPWrite \"reg1 \" \\Num:=reg1;\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    let ended = run_in(&dir, &["run", "."]);
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    assert_eq!(ended.stdout, "reg1 6\n");
    std::fs::write(
        dir.join("main.mod"),
        "MODULE MainModule\n  PROC main()\n    reg2 := 1;\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    let ended = run_in(&dir, &["check", "."]);
    assert_ne!(ended.code, Some(0));
    assert!(
        ended.stderr.contains("`reg2` is not declared"),
        "{}",
        ended.stderr
    );
    let _ = std::fs::remove_dir_all(&dir);
}
