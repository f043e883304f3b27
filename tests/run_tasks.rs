//! Several RAPID tasks in `rapidvc run`: booting the backup folder `tests/tasks/cell` (three
//! tasks: the motion task T_ROB1, the STATIC logger T_LOG writing HOME:/cell.log, the
//! SEMISTATIC T_CELL counting parts over the RAPID message queue), the determinism of the
//! scheduler, and each inter-task instruction and its errors in small systems written here.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use rapidvc_testkit::procs::{Ended, Proc};
use rapidvc_testkit::rapidvc;

use std::path::{Path, PathBuf};
use std::time::Duration;

const LIMIT: Duration = Duration::from_secs(60);

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh directory for one test.
fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rapidvc-tasks-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let target = to.join(e.file_name());
        if e.file_type().unwrap().is_dir() {
            copy_dir(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), target).unwrap();
        }
    }
}

/// `rapidvc ARGS…` in `dir`, to its end.
fn run_in(dir: &Path, args: &[&str]) -> Ended {
    let ended = spawn_in(dir, args).wait(LIMIT);
    assert!(!ended.timed_out, "rapidvc {args:?} did not end");
    ended
}

/// Compare with a golden file (rewritten with `UPDATE_GOLDEN=1`).
fn golden(path: &Path, actual: &str) {
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::write(path, actual).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(path).unwrap();
    assert_eq!(actual, expected, "differs from {}", path.display());
}

/// The cell boots from its backup folder and its three tasks interplay the same way every
/// run: the TP lines (with their task names) and the logger's file are golden, and a
/// second run gives the same bytes.
#[test]
fn the_cell_backup_runs_the_same_every_time() {
    let mut outputs = Vec::new();
    for k in 0..2 {
        let dir = temp_dir(&format!("cell{k}"));
        let cell = dir.join("cell");
        copy_dir(&repo().join("tests/tasks/cell"), &cell);
        let ended = run_in(&dir, &["run", "cell"]);
        assert_eq!(ended.code, Some(0), "{}", ended.stderr);
        let log = std::fs::read_to_string(cell.join("HOME/cell.log")).unwrap();
        // The STATIC logger is still waiting when the NORMAL task ends: it is stopped.
        assert!(
            ended
                .stderr
                .contains("task T_LOG: program stopped at the end of the run"),
            "{}",
            ended.stderr
        );
        outputs.push((ended.stdout, log));
        std::fs::remove_dir_all(&dir).unwrap();
    }
    assert_eq!(outputs[0], outputs[1], "two runs differ");
    golden(&repo().join("tests/tasks/cell.stdout"), &outputs[0].0);
    golden(&repo().join("tests/tasks/cell.log"), &outputs[0].1);
}

/// A small system: SYS.cfg with the given CAB_TASKS lines, and one module per task, run
/// with task prefixes.
fn system(name: &str, tasks: &[(&str, &str, &str)]) -> (PathBuf, Vec<String>) {
    let dir = temp_dir(name);
    let mut sys = String::from("SYS:CFG_1.0:6:0::\n#\nCAB_TASKS:\n\n");
    let mut args = vec!["run".to_string()];
    for (task, attrs, module) in tasks {
        sys.push_str(&format!("      -Name \"{task}\" {attrs}\n\n"));
        let file = format!("{}.mod", task.to_ascii_lowercase());
        std::fs::write(dir.join(&file), module).unwrap();
        args.push(format!("{task}={file}"));
    }
    std::fs::write(dir.join("SYS.cfg"), sys).unwrap();
    (dir, args)
}

fn run_system(name: &str, tasks: &[(&str, &str, &str)]) -> Ended {
    let (dir, args) = system(name, tasks);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let ended = run_in(&dir, &args);
    std::fs::remove_dir_all(&dir).unwrap();
    ended
}

const MOTION: &str = "-Type \"NORMAL\" -MotionTask";

#[test]
fn a_move_outside_the_motion_task_is_refused() {
    let ended = run_system(
        "nomove",
        &[
            (
                "T_ROB1",
                MOTION,
                "MODULE a\n  PROC main()\n    WaitTime 1;\n  ENDPROC\nENDMODULE\n",
            ),
            (
                "T_AUX",
                "-Type \"NORMAL\"",
                "MODULE b\n  PROC main()\n    MoveAbsJ [[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v100, fine, tool0;\n  ENDPROC\nENDMODULE\n",
            ),
        ],
    );
    assert_eq!(ended.code, Some(1), "{}", ended.stderr);
    assert!(
        ended.stderr.contains("task T_AUX is not a motion task"),
        "{}",
        ended.stderr
    );
    assert!(
        ended.stderr.contains("error in task T_AUX"),
        "{}",
        ended.stderr
    );
}

#[test]
fn a_shared_pers_of_two_types_is_a_load_error() {
    let ended = run_system(
        "perstype",
        &[
            (
                "T_ROB1",
                MOTION,
                "MODULE a\n  PERS num shared := 1;\n  PROC main()\n  ENDPROC\nENDMODULE\n",
            ),
            (
                "T_B",
                "",
                "MODULE b\n  PERS bool shared := TRUE;\n  TASK PERS bool own := TRUE;\n  PROC main()\n  ENDPROC\nENDMODULE\n",
            ),
        ],
    );
    assert_eq!(ended.code, Some(2), "{}", ended.stderr);
    assert!(
        ended.stderr.contains("rapidvc::load::pers_type_mismatch")
            && ended.stderr.contains("`shared`"),
        "{}",
        ended.stderr
    );
}

#[test]
fn task_pers_is_per_task_and_pers_is_shared() {
    let ended = run_system(
        "pers",
        &[
            (
                "T_ROB1",
                MOTION,
                "MODULE a\n  PERS num shared := 1;\n  TASK PERS num own := 1;\n  PROC main()\n    shared := 5;\n    own := 5;\n    WaitTime 1;\n    TPWrite \"a: \" \\Num:=shared + own;\n  ENDPROC\nENDMODULE\n",
            ),
            (
                "T_B",
                "",
                "MODULE b\n  PERS num shared := 1;\n  TASK PERS num own := 2;\n  PROC main()\n    WaitTime 0.5;\n    TPWrite \"b: \" \\Num:=shared + own;\n    shared := 7;\n  ENDPROC\nENDMODULE\n",
            ),
        ],
    );
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    assert_eq!(ended.stdout, "[T_B] b: 7\n[T_ROB1] a: 12\n");
}

#[test]
fn wait_sync_task_waits_for_every_task_and_times_out() {
    let ended = run_system(
        "sync",
        &[
            (
                "T_ROB1",
                MOTION,
                "MODULE a\n  PERS tasks both{2} := [[\"T_ROB1\"],[\"T_B\"]];\n  VAR syncident s1;\n  VAR syncident s2;\n  VAR clock c;\n  PROC main()\n    ClkStart c;\n    WaitSyncTask s1, both;\n    TPWrite \"a synced at \" + NumToStr(ClkRead(c), 2);\n    WaitSyncTask s2, both \\TimeOut:=0.5;\n  ERROR\n    IF ERRNO = ERR_WAITSYNCTASK THEN\n      TPWrite \"a: time-out at \" + NumToStr(ClkRead(c), 2);\n      RETURN;\n    ENDIF\n  ENDPROC\nENDMODULE\n",
            ),
            (
                "T_B",
                "",
                "MODULE b\n  PERS tasks both{2} := [[\"T_ROB1\"],[\"T_B\"]];\n  VAR syncident s1;\n  PROC main()\n    WaitTime 2;\n    WaitSyncTask s1, both;\n    TPWrite \"b synced\";\n  ENDPROC\nENDMODULE\n",
            ),
        ],
    );
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    assert_eq!(
        ended.stdout,
        "[T_B] b synced\n[T_ROB1] a synced at 2.00\n[T_ROB1] a: time-out at 2.50\n"
    );
}

#[test]
fn get_task_name_gives_real_numbers() {
    let ended = run_system(
        "names",
        &[
            (
                "T_ROB1",
                MOTION,
                "MODULE a\n  PROC main()\n  ENDPROC\nENDMODULE\n",
            ),
            (
                "T_B",
                "-Type \"SEMISTATIC\"",
                "MODULE b\n  VAR num n;\n  VAR num m;\n  PROC main()\n    TPWrite GetTaskName(\\TaskNo:=n) + \" \" + NumToStr(n, 0);\n    TPWrite GetTaskName(\\MecTaskNo:=m) + \" \" + NumToStr(m, 0);\n    TPWrite ValToStr(TaskRunMec()) + \" \" + ValToStr(TaskRunRob()) + \" \" + NumToStr(TasksInSync(), 0);\n  ENDPROC\nENDMODULE\n",
            ),
        ],
    );
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    assert_eq!(
        ended.stdout,
        "[T_B] T_B 2\n[T_B] T_B 1\n[T_B] FALSE FALSE 0\n"
    );
}

/// The RAPID message queue's errors, each handled in an ERROR handler.
#[test]
fn rmq_errors_are_raised() {
    let sender = "MODULE a\n  VAR rmqslot b;\n  VAR rmqslot none;\n  VAR rmqmessage m;\n  VAR num x;\n  VAR string big := \"12345678901234567890123456789012345678901234567890\";\n  PROC main()\n    RMQFindSlot b, \"T_B\";\n    try 1;\n    try 2;\n    try 3;\n    try 4;\n    try 5;\n    try 6;\n    try 7;\n  ENDPROC\n  PROC try(num k)\n    TEST k\n    CASE 1: RMQFindSlot none, \"T_NOBODY\";\n    CASE 2: RMQGetMessage m;\n    CASE 3: RMQSendMessage b, big;\n    CASE 4: RMQSendMessage b, 1; RMQSendMessage b, 2; RMQSendMessage b, 3;\n    CASE 5: RMQReadWait m \\TimeOut:=0.1;\n    CASE 6: RMQSendMessage none, 1;\n    CASE 7: RMQSendWait b, 1, m, x \\TimeOut:=0.2;\n    ENDTEST\n    TPWrite \"case \" + NumToStr(k, 0) + \": ok\";\n  ERROR\n    TPWrite \"case \" + NumToStr(k, 0) + \": \" + NumToStr(ERRNO, 0);\n    RETURN;\n  ENDPROC\nENDMODULE\n";
    let receiver = "MODULE b\n  VAR rmqmessage m;\n  VAR string s;\n  PROC main()\n    WaitTime 1;\n    RMQGetMessage m;\n    RMQGetMsgData m, s;\n  ERROR\n    TPWrite \"b: \" + NumToStr(ERRNO, 0);\n    RMQEmptyQueue;\n    RETURN;\n  ENDPROC\nENDMODULE\n";
    let ended = run_system(
        "rmqerr",
        &[
            ("T_ROB1", MOTION, sender),
            ("T_B", "-RmqMaxMsgSize 40 -RmqMaxNoOfMsg 2", receiver),
        ],
    );
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    let num = |name: &str| {
        rapidvc::ir::errnum::by_name(name)
            .map(|e| e.num.to_string())
            .unwrap()
    };
    let expected = format!(
        "[T_ROB1] case 1: {}\n[T_ROB1] case 2: {}\n[T_ROB1] case 3: {}\n[T_ROB1] case 4: {}\n[T_ROB1] case 5: {}\n[T_ROB1] case 6: {}\n[T_ROB1] case 7: {}\n[T_B] b: {}\n",
        num("ERR_RMQ_NAME"),
        num("ERR_RMQ_NOMSG"),
        num("ERR_RMQ_MSGSIZE"),
        num("ERR_RMQ_FULL"),
        num("ERR_RMQ_TIMEOUT"),
        num("ERR_RMQ_INVALID"),
        num("ERR_RMQ_FULL"),
        num("ERR_RMQ_VALUE"),
    );
    assert_eq!(ended.stdout, expected, "{}", ended.stderr);
}

#[test]
fn a_prefix_naming_no_task_is_refused() {
    let ended = run_system(
        "unknown",
        &[(
            "T_ROB1",
            MOTION,
            "MODULE a\n  PROC main()\n  ENDPROC\nENDMODULE\n",
        )],
    );
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    let dir = temp_dir("unknown2");
    std::fs::write(
        dir.join("a.mod"),
        "MODULE a\n  PROC main()\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    let ended = run_in(&dir, &["run", "T_NOPE=a.mod"]);
    assert_eq!(ended.code, Some(2), "{}", ended.stderr);
    assert!(
        ended
            .stderr
            .contains("names task `T_NOPE`, which SYS.cfg does not define (tasks: T_ROB1)"),
        "{}",
        ended.stderr
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_backup_without_task_folders_names_the_path() {
    let dir = temp_dir("badbackup");
    std::fs::create_dir_all(dir.join("sys/RAPID")).unwrap();
    let ended = run_in(&dir, &["run", "sys"]);
    assert_eq!(ended.code, Some(2), "{}", ended.stderr);
    assert!(
        ended
            .stderr
            .contains("RAPID: a backup's RAPID folder holds one TASK<n> folder"),
        "{}",
        ended.stderr
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every module of the cell checks with `rapidvc check` (every inter-task name is known),
/// task by task and as the backup folder; a PERS of two types is found by the check too.
#[test]
fn the_cell_modules_check() {
    let ended = run_in(&repo(), &["check", "tests/tasks/cell"]);
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    assert!(
        ended.stderr.contains("checked 4 files: 0 errors"),
        "{}",
        ended.stderr
    );
    let (dir, _) = system(
        "checkpers",
        &[
            (
                "T_ROB1",
                MOTION,
                "MODULE a\n  PERS num p := 1;\n  PROC main()\n  ENDPROC\nENDMODULE\n",
            ),
            (
                "T_B",
                "",
                "MODULE b\n  PERS string p := \"x\";\n  PROC main()\n  ENDPROC\nENDMODULE\n",
            ),
        ],
    );
    let ended = run_in(&dir, &["check", "T_ROB1=t_rob1.mod", "T_B=t_b.mod"]);
    assert_eq!(ended.code, Some(1), "{}", ended.stderr);
    assert!(
        ended.stderr.contains("pers_type_mismatch"),
        "{}",
        ended.stderr
    );
    std::fs::remove_dir_all(&dir).unwrap();
    for task in ["TASK1", "TASK2", "TASK3"] {
        let dir = repo().join("tests/tasks/cell/RAPID").join(task);
        let ended = run_in(&repo(), &["check", dir.to_str().unwrap()]);
        assert_eq!(
            ended.code,
            Some(0),
            "{task}: {}{}",
            ended.stdout,
            ended.stderr
        );
    }
}

/// A task that never waits hands the processor over every 1000 statements: the other task
/// sees the shared count it has reached by then, and the busy task's loop is not finished.
#[test]
fn a_busy_task_shares_the_processor_every_1000_statements() {
    let ended = run_system(
        "slice",
        &[
            (
                "T_ROB1",
                MOTION,
                "MODULE a\n  PERS num count := 0;\n  PROC main()\n    FOR i FROM 1 TO 5000 DO\n      count := count + 1;\n    ENDFOR\n    TPWrite \"a: \" \\Num:=count;\n  ENDPROC\nENDMODULE\n",
            ),
            (
                "T_B",
                "",
                "MODULE b\n  PERS num count := 0;\n  PROC main()\n    TPWrite \"b first sees \" \\Num:=count;\n    WHILE count < 5000 DO\n      WaitTime 0.001;\n    ENDWHILE\n    TPWrite \"b: \" \\Num:=count;\n  ENDPROC\nENDMODULE\n",
            ),
        ],
    );
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    let lines: Vec<&str> = ended.stdout.lines().collect();
    assert_eq!(lines.len(), 3, "{}", ended.stdout);
    // The slice ends at the 1000th step (the FOR statement and its body's statements count),
    // which is the same point of the loop on every run.
    assert_eq!(lines[0], "[T_B] b first sees 998");
    assert_eq!(lines[1], "[T_ROB1] a: 5000");
    assert_eq!(lines[2], "[T_B] b: 5000");
}

/// An unhandled error in one task stops the others; `EXIT` in a NORMAL task too.
#[test]
fn an_error_or_exit_in_one_task_stops_the_others() {
    let waiting = "MODULE a\n  PROC main()\n    TPWrite \"a waits\";\n    WaitTime 100;\n    TPWrite \"a never gets here\";\n  ENDPROC\nENDMODULE\n";
    let failing = "MODULE b\n  VAR num zero := 0;\n  PROC main()\n    WaitTime 1;\n    TPWrite \"b: \" \\Num:=1 / zero;\n  ENDPROC\nENDMODULE\n";
    let ended = run_system("fail", &[("T_ROB1", MOTION, waiting), ("T_B", "", failing)]);
    assert_eq!(ended.code, Some(1), "{}", ended.stderr);
    assert_eq!(ended.stdout, "[T_ROB1] a waits\n");
    assert!(
        ended.stderr.contains("error in task T_B"),
        "{}",
        ended.stderr
    );
    assert!(ended.stderr.contains("ERR_DIVZERO"), "{}", ended.stderr);
    assert!(
        ended
            .stderr
            .contains("task T_ROB1: program stopped with the other tasks"),
        "{}",
        ended.stderr
    );
    let exiting = "MODULE b\n  PROC main()\n    WaitTime 1;\n    EXIT;\n  ENDPROC\nENDMODULE\n";
    let ended = run_system("exit", &[("T_ROB1", MOTION, waiting), ("T_B", "", exiting)]);
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    assert_eq!(ended.stdout, "[T_ROB1] a waits\n");
    assert!(
        ended.stderr.contains("task T_B: program ended by EXIT"),
        "{}",
        ended.stderr
    );
}

/// Arrays travel with their sizes (`rmqheader`), a receiver of other sizes gets
/// `ERR_RMQ_DIM`, and `WaitSyncTask \\InPos` also waits for the robot to stand in position.
#[test]
fn rmq_arrays_and_wait_sync_in_position() {
    let a = "MODULE a\n  VAR rmqslot b;\n  VAR num arr{3} := [1, 2, 3];\n  PERS tasks both{2} := [[\"T_ROB1\"],[\"T_B\"]];\n  VAR syncident s;\n  PROC main()\n    RMQFindSlot b, \"T_B\";\n    RMQSendMessage b, arr;\n    RMQSendMessage b, arr;\n    MoveAbsJ [[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v100, z10, tool0;\n    WaitSyncTask \\InPos, s, both;\n    TPWrite \"a in pos\";\n  ENDPROC\nENDMODULE\n";
    let b = "MODULE b\n  VAR rmqmessage m;\n  VAR num got{3};\n  VAR num two{2};\n  VAR rmqheader h;\n  PERS tasks both{2} := [[\"T_ROB1\"],[\"T_B\"]];\n  VAR syncident s;\n  PROC main()\n    RMQReadWait m;\n    RMQGetMsgHeader m \\Header:=h;\n    RMQGetMsgData m, got;\n    TPWrite \"b got \" + ValToStr(got{3}) + \" \" + h.datatype + \" ndim \" + ValToStr(h.ndim) + \" dim1 \" + ValToStr(h.dim1);\n    RMQReadWait m;\n    RMQGetMsgData m, two;\n  ERROR\n    TPWrite \"b: \" \\Num:=ERRNO;\n    WaitSyncTask s, both;\n    TPWrite \"b synced\";\n  ENDPROC\nENDMODULE\n";
    let ended = run_system("arrays", &[("T_ROB1", MOTION, a), ("T_B", "", b)]);
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    let dim = rapidvc::ir::errnum::ERR_RMQ_DIM;
    assert_eq!(
        ended.stdout,
        format!(
            "[T_B] b got 3 num ndim 1 dim1 3\n[T_B] b: {dim}\n[T_B] b synced\n[T_ROB1] a in pos\n"
        )
    );
}

#[test]
fn a_pers_of_a_module_loaded_at_run_time_is_shared_by_name() {
    let (dir, mut args) = system(
        "loadpers",
        &[
            (
                "T_ROB1",
                MOTION,
                "MODULE a\n  PERS num late := 1;\n  PERS num odd := 0;\n  PROC main()\n    late := 7;\n    WaitTime 1;\n    TPWrite \"a: \" \\Num:=late;\n  ENDPROC\nENDMODULE\n",
            ),
            (
                "T_B",
                "",
                "MODULE b\n  PROC main()\n    WaitTime 0.5;\n    Load \\Dynamic, \"HOME:\" \\File:=\"late.mod\";\n    %\"show\"%;\n    Load \\Dynamic, \"HOME:\" \\File:=\"other.mod\";\n  ERROR\n    TPWrite \"b: load error \" \\Num:=ERRNO;\n  ENDPROC\nENDMODULE\n",
            ),
        ],
    );
    // `late` is T_ROB1's (its value, 7, wins over the module's 3); the loaded routine writes
    // it and T_ROB1 sees the write. `odd`, a num in T_ROB1, is refused as a bool.
    std::fs::write(
        dir.join("late.mod"),
        "MODULE late\n  PERS num late := 3;\n  PROC show()\n    TPWrite \"b: \" \\Num:=late;\n    late := late + 1;\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("other.mod"),
        "MODULE other\n  PERS num fresh := 0;\n  PERS bool odd := TRUE;\nENDMODULE\n",
    )
    .unwrap();
    args.extend(["--home".to_string(), ".".to_string()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let ended = run_in(&dir, &args);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    assert_eq!(
        ended.stdout, "[T_B] b: 7\n[T_B] b: load error 1152\n[T_ROB1] a: 8\n",
        "{}",
        ended.stderr
    );
}

#[test]
fn the_other_tasks_run_while_the_motion_task_is_in_an_egm_run_or_a_triggered_move() {
    // The motion task waits inside EGMRunJoint (built-in sensor) and inside a TriggL: the
    // counter task's 0.1 s ticks go on meanwhile, at their times, the same every run.
    const ROBOT: &str = r#"MODULE Robot
VAR egmident egm1;
VAR triggdata t1;
VAR clock clk;
CONST jointtarget home := [[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
CONST egm_minmax win := [-0.2,0.2];
PROC main()
  VAR robtarget p;
  ConfL \Off;
  MoveAbsJ home, v1000, fine, tool0;
  ClkStart clk;
  EGMGetId egm1;
  EGMSetupUC ROB_1, egm1, "default", "sensor" \Joint \CommTimeout:=5;
  EGMActJoint egm1 \J1:=win \J2:=win \J3:=win \J4:=win \J5:=win \J6:=win \MaxSpeedDeviation:=40;
  TPWrite "EGM run from " \Num:=ClkRead(clk);
  EGMRunJoint egm1, EGM_STOP_HOLD \J1 \J2 \J3 \J4 \J5 \J6 \CondTime:=0.5 \RampInTime:=0.1;
  TPWrite "EGM run ended at " \Num:=ClkRead(clk);
  EGMReset egm1;
  p := CRobT();
  TriggIO t1, 10 \DOp:=DO1, 1;
  TPWrite "TriggL from " \Num:=ClkRead(clk);
  TriggL Offs(p, 0, 0, 100), v100, t1, fine, tool0;
  TPWrite "TriggL ended at " \Num:=ClkRead(clk);
ENDPROC
ENDMODULE
"#;
    const COUNTER: &str = r#"MODULE Counter
PROC main()
  VAR clock c;
  ClkStart c;
  FOR i FROM 1 TO 40 DO
    WaitTime 0.1;
    TPWrite "tick " \Num:=ClkRead(c);
  ENDFOR
ENDPROC
ENDMODULE
"#;
    let (dir, mut args) = system(
        "baton",
        &[
            ("T_ROB1", MOTION, ROBOT),
            ("T_CNT", "-Type \"NORMAL\"", COUNTER),
        ],
    );
    std::fs::write(
        dir.join("EIO.cfg"),
        "EIO:CFG_1.0:6:0::\n#\nEIO_SIGNAL:\n      -Name \"DO1\" -SignalType \"DO\"\n",
    )
    .unwrap();
    args.extend([
        "--device".into(),
        "sensor=builtin:joint:10,-5,20,0,40,30".into(),
    ]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let first = run_in(&dir, &args);
    let again = run_in(&dir, &args);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(first.code, Some(0), "{}\n{}", first.stdout, first.stderr);
    assert_eq!(first.stdout, again.stdout, "deterministic");
    let lines: Vec<&str> = first.stdout.lines().collect();
    let at = |what: &str| {
        lines
            .iter()
            .position(|l| l.contains(what))
            .unwrap_or_else(|| panic!("no `{what}` in\n{}", first.stdout))
    };
    let ticks_between = |from: &str, to: &str| {
        lines[at(from)..at(to)]
            .iter()
            .filter(|l| l.contains("[T_CNT] tick"))
            .count()
    };
    // The EGM run lasts about 2 s and the TriggL 1 s of robot time.
    let egm = ticks_between("EGM run from", "EGM run ended");
    let trigg = ticks_between("TriggL from", "TriggL ended");
    assert!(
        egm >= 15,
        "{egm} ticks during the EGM run:\n{}",
        first.stdout
    );
    assert!(
        trigg >= 8,
        "{trigg} ticks during the TriggL:\n{}",
        first.stdout
    );
}

/// A free TCP port of 127.0.0.1 (free when asked: the test's program binds it soon after).
fn free_port() -> u16 {
    let l = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    l.local_addr().unwrap().port()
}

/// A client of the program's server on `port`, connected as soon as it listens (within
/// 20 s).
fn connect(port: u16) -> std::net::TcpStream {
    let deadline = std::time::Instant::now() + Duration::from_secs(20);
    loop {
        match std::net::TcpStream::connect(("127.0.0.1", port)) {
            Ok(s) => return s,
            Err(e) if std::time::Instant::now() > deadline => panic!("connect: {e}"),
            Err(_) => std::thread::sleep(Duration::from_millis(20)),
        }
    }
}

/// `rapidvc ARGS…` started in `dir` (ended by the caller).
fn spawn_in<S: AsRef<std::ffi::OsStr>>(dir: &Path, args: &[S]) -> Proc {
    let mut cmd = rapidvc!();
    cmd.args(args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .env("COLUMNS", "1000");
    Proc::spawn(cmd)
}

/// A communication task listening on a free port of 127.0.0.1 for `secs` seconds, then
/// (nobody came) failing with ERR_SOCK_TIMEOUT.
fn listener_task(secs: u32) -> String {
    let port = free_port();
    format!(
        "MODULE comm
  VAR socketdev server;
  VAR socketdev client;
  PROC main()
    SocketCreate server;
    SocketBind server, \"127.0.0.1\", {port};
    SocketListen server;
    TPWrite \"listening\";
    SocketAccept server, client \\Time:={secs};
  ENDPROC
ENDMODULE
"
    )
}

/// A motion task printing its clock every 0.5 s, five times.
const TICKS: &str = "MODULE main
  PROC main()
    VAR clock c;
    ClkStart c;
    FOR i FROM 1 TO 5 DO
      WaitTime 0.5;
      TPWrite \"tick \" + NumToStr(ClkRead(c), 1);
    ENDFOR
  ENDPROC
ENDMODULE
";

/// A task waiting in a socket instruction blocks only itself: the motion task goes on.
#[test]
fn a_task_waiting_on_a_socket_lets_the_others_run() {
    let comm = listener_task(4);
    let ended = run_system(
        "sockwait",
        &[
            ("T_ROB1", MOTION, TICKS),
            ("T_COMM", "-Type \"NORMAL\"", &comm),
        ],
    );
    // The ticks come while T_COMM waits in SocketAccept (4 s), then its time-out stops
    // the run.
    for t in ["0.5", "1.0", "1.5", "2.0", "2.5"] {
        assert!(
            ended.stdout.contains(&format!("[T_ROB1] tick {t}")),
            "{}",
            ended.stdout
        );
    }
    assert!(
        ended.stderr.contains("ERR_SOCK_TIMEOUT"),
        "{}",
        ended.stderr
    );
    assert_eq!(ended.code, Some(1));
}

/// Ctrl-C during a socket wait of one task stops every task at once (exit 130).
#[test]
fn ctrl_c_during_a_socket_wait_of_one_task_stops_the_run_at_once() {
    let comm = listener_task(30);
    let (dir, args) = system(
        "sockint",
        &[
            ("T_ROB1", MOTION, TICKS),
            ("T_COMM", "-Type \"NORMAL\"", &comm),
        ],
    );
    let mut proc = spawn_in(&dir, &args);
    assert_eq!(
        proc.next_line(Duration::from_secs(20)).as_deref(),
        Some("[T_COMM] listening")
    );
    std::thread::sleep(Duration::from_millis(300));
    let status = std::process::Command::new("kill")
        .args(["-INT", &proc.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    // Well before the 30 s of the SocketAccept.
    let ended = proc.wait(Duration::from_secs(10));
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(!ended.timed_out, "the run did not end after SIGINT");
    assert_eq!(ended.code, Some(130), "{}", ended.stderr);
    assert!(
        ended.stderr.contains("interrupted by Ctrl-C"),
        "{}",
        ended.stderr
    );
}

/// A socket server task beside the motion task: `run` goes in real time (the client is a
/// real process), the server's command reaches the motion task through a shared PERS, and
/// the run ends by itself when the NORMAL tasks have.
#[test]
fn a_socket_server_task_beside_the_motion_task_runs_in_real_time() {
    let port = free_port();
    let comm = format!(
        "MODULE comm
  PERS num target_x := 0;
  VAR socketdev server;
  VAR socketdev client;
  PROC main()
    VAR string cmd;
    VAR num x;
    SocketCreate server;
    SocketBind server, \"127.0.0.1\", {port};
    SocketListen server;
    TPWrite \"listening\";
    SocketAccept server, client \\Time:=20;
    SocketReceive client \\Str:=cmd \\Time:=20;
    IF StrToVal(cmd, x) THEN
      target_x := x;
      SocketSend client \\Str:=\"ok\";
    ELSE
      SocketSend client \\Str:=\"error\";
    ENDIF
    SocketClose client;
    SocketClose server;
  ENDPROC
ENDMODULE
"
    );
    let motion = "MODULE main
  PERS num target_x := 0;
  PROC main()
    VAR robtarget p := [[1000, 0, 800], [0, 0, 1, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
    VAR clock c;
    MoveJ p, v1000, fine, tool0;
    ClkStart c;
    WaitUntil target_x <> 0 \\MaxTime:=20;
    p.trans.x := target_x;
    MoveL p, v500, fine, tool0;
    TPWrite \"at x \" + NumToStr(CRobT(\\Tool:=tool0).trans.x, 0);
    TPWrite \"waited for the command: \" + ValToStr(ClkRead(c) >= 0.2);
  ENDPROC
ENDMODULE
";
    let (dir, args) = system(
        "socket",
        &[
            ("T_ROB1", MOTION, motion),
            ("T_COMM", "-Type \"NORMAL\"", &comm),
        ],
    );
    let proc = spawn_in(&dir, &args);
    // The client: a real process's socket, 0.3 s after the server listens (real time: the
    // motion task's WaitUntil waits for it on the same clock).
    let client = std::thread::spawn(move || {
        use std::io::{Read, Write};
        let mut s = connect(port);
        std::thread::sleep(Duration::from_millis(300));
        s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
        s.write_all(b"1250").unwrap();
        let mut reply = [0u8; 16];
        let n = s.read(&mut reply).unwrap();
        String::from_utf8_lossy(&reply[..n]).to_string()
    });
    let ended = proc.wait(LIMIT);
    let reply = client.join().unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(!ended.timed_out);
    assert_eq!(ended.code, Some(0), "{}\n{}", ended.stdout, ended.stderr);
    assert_eq!(reply, "ok");
    assert!(
        ended.stdout.contains("[T_COMM] listening"),
        "{}",
        ended.stdout
    );
    assert!(
        ended.stdout.contains("[T_ROB1] at x 1250"),
        "{}",
        ended.stdout
    );
    assert!(
        ended
            .stdout
            .contains("[T_ROB1] waited for the command: TRUE"),
        "{}",
        ended.stdout
    );
    assert!(
        ended.stderr.contains("sockets") && ended.stderr.contains("real time"),
        "{}",
        ended.stderr
    );
}

/// A state server task beside a moving motion task, as a PC interface has one: it reads the
/// robot's axes with CJointT (its task shares the robot's mechanical unit group) and sends
/// them every 0.1 s; the client sees them at that rate, changing as the robot moves.
#[test]
fn a_state_server_task_streams_the_moving_robots_axes_at_its_rate() {
    let port = free_port();
    let server = format!(
        "MODULE state
  VAR socketdev server;
  VAR socketdev client;
  PROC main()
    VAR jointtarget j;
    SocketCreate server;
    SocketBind server, \"127.0.0.1\", {port};
    SocketListen server;
    SocketAccept server, client \\Time:=20;
    FOR i FROM 1 TO 25 DO
      j := CJointT();
      SocketSend client \\Str:=NumToStr(j.robax.rax_1, 2) + \";\";
      WaitTime 0.1;
    ENDFOR
    SocketClose client;
    SocketClose server;
  ENDPROC
ENDMODULE
"
    );
    let motion = "MODULE main
  PROC main()
    FOR i FROM 1 TO 3 DO
      MoveAbsJ [[60, 0, 0, 0, 30, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v100 \\T:=1, fine, tool0;
      MoveAbsJ [[0, 0, 0, 0, 30, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v100 \\T:=1, fine, tool0;
    ENDFOR
  ENDPROC
ENDMODULE
";
    let (dir, args) = system(
        "stateserver",
        &[
            ("T_ROB1", MOTION, motion),
            (
                "T_STATE",
                "-Type \"NORMAL\" -UseMechanicalUnitGroup \"rob1\"",
                &server,
            ),
        ],
    );
    let proc = spawn_in(&dir, &args);
    let client = std::thread::spawn(move || {
        use std::io::Read;
        let mut s = connect(port);
        s.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
        let mut got = Vec::new();
        let mut text = String::new();
        let mut buf = [0u8; 256];
        while let Ok(n) = s.read(&mut buf) {
            if n == 0 {
                break;
            }
            text.push_str(&String::from_utf8_lossy(&buf[..n]));
            while let Some(end) = text.find(';') {
                let value: f64 = text[..end].parse().unwrap();
                got.push((std::time::Instant::now(), value));
                text.drain(..=end);
            }
        }
        got
    });
    let ended = proc.wait(LIMIT);
    let got = client.join().unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(ended.code, Some(0), "{}\n{}", ended.stdout, ended.stderr);
    assert_eq!(got.len(), 25, "{got:?}");
    // The rate of the server's WaitTime (0.1 s), not that of hand-overs.
    let span = got[24].0 - got[0].0;
    assert!(
        span < Duration::from_millis(24 * 100 + 600),
        "25 messages over {span:?}"
    );
    // The axes change as the robot moves (J1 between 0 and 60).
    let distinct: std::collections::BTreeSet<i64> =
        got.iter().map(|(_, v)| (*v * 10.0) as i64).collect();
    assert!(distinct.len() > 10, "{got:?}");
    assert!(
        got.iter().all(|(_, v)| (-0.01..=60.01).contains(v)),
        "{got:?}"
    );
}

/// In virtual time a task sharing the robot's mechanical unit group reads where the robot is
/// at its own time (the motion task hands over at every deadline); a task without a group
/// cannot read it. (The motion task's path instructions work as with one task.)
#[test]
fn cjointt_in_a_task_of_the_robots_group_reads_the_robot_at_that_time() {
    let motion = "MODULE main
  PROC main()
    StopMove;
    ClearPath;
    StartMove;
    MoveAbsJ [[60, 0, 0, 0, 30, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v100 \\T:=1, fine, tool0;
  ENDPROC
ENDMODULE
";
    let watch = "MODULE watch
  PROC main()
    WaitTime 0.5;
    TPWrite \"J1 at 0.5 s: \" + NumToStr(CJointT().robax.rax_1, 3);
    WaitTime 0.7;
    TPWrite \"J1 at 1.2 s: \" + NumToStr(CJointT().robax.rax_1, 3);
  ENDPROC
ENDMODULE
";
    let ended = run_system(
        "cjointt",
        &[
            ("T_ROB1", MOTION, motion),
            (
                "T_WATCH",
                "-Type \"NORMAL\" -UseMechanicalUnitGroup \"rob1\"",
                watch,
            ),
        ],
    );
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    // Half way through a symmetric profile; then at the target.
    assert!(
        ended.stdout.contains("[T_WATCH] J1 at 0.5 s: 30.000"),
        "{}",
        ended.stdout
    );
    assert!(
        ended.stdout.contains("[T_WATCH] J1 at 1.2 s: 60.000"),
        "{}",
        ended.stdout
    );
    let ended = run_system(
        "cjointt_nogroup",
        &[
            ("T_ROB1", MOTION, motion),
            ("T_WATCH", "-Type \"NORMAL\"", watch),
        ],
    );
    assert_eq!(ended.code, Some(1), "{}", ended.stdout);
    assert!(
        ended
            .stderr
            .contains("task T_WATCH is not a motion task and has no mechanical unit group"),
        "{}",
        ended.stderr
    );
}

/// EIO.cfg's system outputs follow the controller: motors on, the cycle and each task
/// running, the robot standing still or moving; a status rapidvc does not drive is a
/// warning naming it, one on a signal that is no DO an error.
#[test]
fn system_outputs_follow_the_tasks_and_the_robot() {
    const EIO: &str = "EIO:CFG_1.0:6:1::
#
EIO_SIGNAL:
      -Name \"doMotOn\" -SignalType \"DO\"
      -Name \"doCycle\" -SignalType \"DO\"
      -Name \"doRob\" -SignalType \"DO\"
      -Name \"doLog\" -SignalType \"DO\"
      -Name \"doStill\" -SignalType \"DO\"
      -Name \"doEStop\" -SignalType \"DO\" -Default 1
      -Name \"doRunch\" -SignalType \"DO\"
#
SYSSIG_OUT:
      -Status \"MotOnState\" -Signal \"doMotOn\"
      -Status \"CycleOn\" -Signal \"doCycle\"
      -Status \"TaskExecuting\" -Signal \"doRob\" -Arg2 \"T_ROB1\"
      -Status \"TaskExecuting\" -Signal \"doLog\" -Arg2 \"T_LOG\"
      -Status \"MechUnitNotMoving\" -Signal \"doStill\" -Arg1 \"ROB_1\"
      -Status \"EmStop\" -Signal \"doEStop\"
      -Status \"RunchOk\" -Signal \"doRunch\"
";
    let motion = "MODULE main
  FUNC string outs()
    RETURN NumToStr(DOutput(doMotOn), 0) + NumToStr(DOutput(doCycle), 0)
      + NumToStr(DOutput(doRob), 0) + NumToStr(DOutput(doLog), 0)
      + NumToStr(DOutput(doEStop), 0) + NumToStr(DOutput(doRunch), 0);
  ENDFUNC
  PROC main()
    TPWrite \"outputs \" + outs();
    TPWrite \"standing: \" + NumToStr(DOutput(doStill), 0);
    MoveAbsJ [[60, 0, 0, 0, 30, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v1000, z50, tool0;
    WaitTime 0.2;
    TPWrite \"moving: \" + NumToStr(DOutput(doStill), 0) + \", T_LOG ended: \" + NumToStr(DOutput(doLog), 0);
    MoveAbsJ [[0, 0, 0, 0, 30, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], v1000, fine, tool0;
    WaitTime 0.1;
    TPWrite \"standing again: \" + NumToStr(DOutput(doStill), 0);
  ENDPROC
ENDMODULE
";
    let log = "MODULE log
  PROC main()
    WaitTime 0.1;
  ENDPROC
ENDMODULE
";
    let (dir, args) = system(
        "sysout",
        &[
            ("T_ROB1", MOTION, motion),
            ("T_LOG", "-Type \"NORMAL\"", log),
        ],
    );
    std::fs::write(dir.join("EIO.cfg"), EIO).unwrap();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let ended = run_in(&dir, &args);
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    for line in [
        "[T_ROB1] outputs 111101",
        "[T_ROB1] standing: 1",
        "[T_ROB1] moving: 0, T_LOG ended: 0",
        "[T_ROB1] standing again: 1",
    ] {
        assert!(ended.stdout.contains(line), "{line}:\n{}", ended.stdout);
    }
    // Not driven: a warning naming it; on no DO: an error before the run.
    let eio = EIO.replace("\"RunchOk\"", "\"SimMode\"");
    std::fs::write(dir.join("EIO.cfg"), eio).unwrap();
    let ended = run_in(&dir, &args);
    assert!(
        ended
            .stderr
            .contains("the system output `SimMode` is not simulated by rapidvc"),
        "{}",
        ended.stderr
    );
    let eio = EIO.replace("-Signal \"doRunch\"", "-Signal \"doNothing\"");
    std::fs::write(dir.join("EIO.cfg"), eio).unwrap();
    let ended = run_in(&dir, &args);
    assert_eq!(ended.code, Some(2), "{}", ended.stdout);
    assert!(
        ended
            .stderr
            .contains("drives `doNothing`, which is not a digital output"),
        "{}",
        ended.stderr
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--pers` with several tasks keeps the persistents the tasks share: both tasks start from
/// the stored value, the file gets the value the last writer left (T_B writes after T_ROB1),
/// and the next run starts from it. A TASK PERS (one value per task) is refused before the
/// run, by name.
#[test]
fn pers_file_of_a_system_keeps_the_shared_persistents() {
    let (dir, mut args) = system(
        "persfile",
        &[
            (
                "T_ROB1",
                MOTION,
                "MODULE a\n  PERS num runs := 0;\n  PERS string last := \"\";\n  PROC main()\n    TPWrite \"a: \" \\Num:=runs;\n    runs := runs + 1;\n    last := \"a\";\n  ENDPROC\nENDMODULE\n",
            ),
            (
                "T_B",
                "",
                "MODULE b\n  PERS num runs := 0;\n  PERS string last := \"\";\n  PERS num only_b := 1;\n  PROC main()\n    WaitTime 0.5;\n    TPWrite \"b: \" \\Num:=runs;\n    runs := runs + 10;\n    last := \"b\";\n    only_b := only_b * 2;\n  ENDPROC\nENDMODULE\n",
            ),
        ],
    );
    args.splice(1..1, ["--pers".to_string(), "cell.pers".to_string()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let first = run_in(&dir, &args);
    assert_eq!(first.code, Some(0), "{}", first.stderr);
    assert_eq!(first.stdout, "[T_ROB1] a: 0\n[T_B] b: 1\n");
    let stored = std::fs::read_to_string(dir.join("cell.pers")).unwrap();
    for line in [
        "PERS num runs := 11;",
        "PERS string last := \"b\";",
        "PERS num only_b := 2;",
    ] {
        assert!(stored.contains(line), "{line} in\n{stored}");
    }
    let second = run_in(&dir, &args);
    assert_eq!(second.code, Some(0), "{}", second.stderr);
    assert_eq!(second.stdout, "[T_ROB1] a: 11\n[T_B] b: 12\n");
    let stored = std::fs::read_to_string(dir.join("cell.pers")).unwrap();
    assert!(stored.contains("PERS num runs := 22;"), "{stored}");
    assert!(stored.contains("PERS num only_b := 4;"), "{stored}");
    std::fs::write(
        dir.join("t_b.mod"),
        "MODULE b\n  TASK PERS num mine := 0;\n  PROC main()\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    let refused = run_in(&dir, &args);
    assert_eq!(refused.code, Some(2), "{}", refused.stderr);
    assert!(
        refused.stderr.contains("`mine` of task T_B is a TASK PERS"),
        "{}",
        refused.stderr
    );
    assert!(refused.stdout.is_empty(), "{}", refused.stdout);
    std::fs::remove_dir_all(&dir).unwrap();
}
