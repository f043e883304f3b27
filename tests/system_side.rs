//! The controller's system side with real files and the real clock: `SaveCfgData` writes a
//! CFG file that rapidvc reads back, only where `--save-cfg` allows and never over the files
//! the run read; `--date now` starts the calendar at the host's local time.

use rapidvc_testkit::rapidvc;
use std::path::{Path, PathBuf};

const EIO: &str = "EIO:CFG_1.0:6:1::\n#\nEIO_SIGNAL:\n\n      -Name \"doGripper\" -SignalType \"DO\" -Device \"USERIO\" -DeviceMap \"0\"\n\n      -Name \"diPart\" -SignalType \"DI\" -Device \"USERIO\" -DeviceMap \"1\" -Invert\n";

/// A fresh directory of its own for one test.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rapidvc-system-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn run(dir: &Path, args: &[&str]) -> (i32, String, String) {
    let args: Vec<&str> = std::iter::once("run").chain(args.iter().copied()).collect();
    rapidvc_testkit::procs::output_in(rapidvc!(), dir, &args, 80)
}

/// A program that changes the configuration database and saves it (SaveCfgData examples of
/// ABB's manual: into a directory, with the default and with a file name of its own), then
/// tries to save where it must not.
const SAVE: &str = r#"MODULE save
  PROC main()
    WriteCfgData "/EIO/EIO_SIGNAL/doGripper", "Device", "d651";
    SaveCfgData "SYSPAR", EIO_DOMAIN;
    SaveCfgData "HOME:/SYSPAR" \File:="MYEIO.cfg", EIO_DOMAIN;
    TPWrite "saved";
    try_save "";
    try_save "..";
    try_save "/tmp";
    try_save "missing";
  ENDPROC

  PROC try_save(string dir)
    SaveCfgData dir, EIO_DOMAIN;
    TPWrite "saved into " + dir;
  ERROR
    TPWrite "refused: " + dir + " " \Bool:=ERRNO = ERR_CFG_WRITEFILE;
    RETURN;
  ENDPROC
ENDMODULE
"#;

#[test]
fn save_cfg_writes_a_file_rapidvc_reads_back() {
    let dir = temp_dir("save");
    std::fs::write(dir.join("EIO.cfg"), EIO).expect("EIO.cfg");
    std::fs::create_dir(dir.join("SYSPAR")).expect("SYSPAR");
    std::fs::write(dir.join("save.mod"), SAVE).expect("program");
    let (code, stdout, stderr) = run(&dir, &["--save-cfg", "save.mod"]);
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    assert_eq!(
        stdout,
        "saved\nrefused:  TRUE\nrefused: .. TRUE\nrefused: /tmp TRUE\nrefused: missing TRUE\n",
        "{stderr}"
    );
    // The input is untouched; the saved files hold the change.
    assert_eq!(std::fs::read_to_string(dir.join("EIO.cfg")).unwrap(), EIO);
    let saved = std::fs::read_to_string(dir.join("SYSPAR/EIO.cfg")).expect("SYSPAR/EIO.cfg");
    assert_eq!(
        std::fs::read_to_string(dir.join("SYSPAR/MYEIO.cfg")).expect("MYEIO.cfg"),
        saved
    );
    assert!(saved.starts_with("EIO:CFG_1.0:6:1::\n"), "{saved}");
    assert!(
        saved.contains("-Name \"doGripper\" -SignalType \"DO\" -Device \"d651\""),
        "{saved}"
    );
    // rapidvc reads the saved file as a configuration: the signals and the new value.
    let read = "MODULE read\n  PROC main()\n    VAR string dev;\n    VAR bool inv;\n    ReadCfgData \"/EIO/EIO_SIGNAL/doGripper\", \"Device\", dev;\n    ReadCfgData \"/EIO/EIO_SIGNAL/diPart\", \"Invert\", inv;\n    TPWrite dev \\Bool:=inv;\n    SetDO doGripper, 1;\n  ENDPROC\nENDMODULE\n";
    std::fs::write(dir.join("read.mod"), read).expect("program");
    let (code, stdout, stderr) = run(&dir, &["--config", "SYSPAR", "read.mod"]);
    assert_eq!((code, stdout.as_str()), (0, "d651TRUE\n"), "{stderr}");
    let leftovers: Vec<_> = std::fs::read_dir(dir.join("SYSPAR"))
        .unwrap()
        .flatten()
        .map(|e| e.file_name())
        .filter(|n| n.to_string_lossy().contains(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn without_save_cfg_nothing_is_written() {
    let dir = temp_dir("nosave");
    std::fs::write(dir.join("EIO.cfg"), EIO).expect("EIO.cfg");
    std::fs::create_dir(dir.join("SYSPAR")).expect("SYSPAR");
    let prog = "MODULE nosave\n  PROC main()\n    SaveCfgData \"SYSPAR\", EIO_DOMAIN;\n  ERROR\n    TPWrite \"refused \" \\Bool:=ERRNO = ERR_CFG_WRITEFILE;\n  ENDPROC\nENDMODULE\n";
    std::fs::write(dir.join("nosave.mod"), prog).expect("program");
    let (code, stdout, stderr) = run(&dir, &["nosave.mod"]);
    assert_eq!((code, stdout.as_str()), (0, "refused TRUE\n"), "{stderr}");
    assert_eq!(std::fs::read_dir(dir.join("SYSPAR")).unwrap().count(), 0);
    // Unhandled, the error says how to allow saving.
    let prog = "MODULE nosave2\n  PROC main()\n    SaveCfgData \"SYSPAR\", EIO_DOMAIN;\n  ENDPROC\nENDMODULE\n";
    std::fs::write(dir.join("nosave2.mod"), prog).expect("program");
    let (code, _, stderr) = run(&dir, &["nosave2.mod"]);
    assert_eq!(code, 1);
    assert!(
        stderr.contains("ERR_CFG_WRITEFILE") && stderr.contains("--save-cfg"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn date_now_is_the_hosts_local_date() {
    let dir = temp_dir("now");
    std::fs::write(
        dir.join("now.mod"),
        "MODULE now\n  PROC main()\n    TPWrite CDate();\n  ENDPROC\nENDMODULE\n",
    )
    .expect("program");
    let before = chrono::Local::now().date_naive().to_string();
    let (code, stdout, stderr) = run(&dir, &["--date", "now", "now.mod"]);
    let after = chrono::Local::now().date_naive().to_string();
    assert_eq!(code, 0, "{stderr}");
    let date = stdout.trim();
    assert!(date == before || date == after, "{date} is not {before}");
    // Without --date: the documented start date, every time.
    let (_, stdout, _) = run(&dir, &["now.mod"]);
    assert_eq!(stdout, "2025-01-01\n");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A backup's task holds the LINKEDM system module, whose service routine calls
/// `Linked_m_exe` from an encrypted RobotWare module: the task checks and its program runs;
/// calling the service routine stops the program with the reason (no linked motors).
#[test]
fn a_backup_with_the_linked_motors_service_module_checks_and_runs() {
    let dir = temp_dir("linkedm");
    let task = dir.join("RAPID").join("TASK1");
    std::fs::create_dir_all(task.join("SYSMOD")).unwrap();
    std::fs::create_dir_all(task.join("PROGMOD")).unwrap();
    std::fs::write(
        task.join("SYSMOD").join("LINKEDM.sys"),
        "MODULE LINKEDM (SYSMODULE)\n  PERS num follower_axis{2} := [0, 0];\n  PROC Linked_m()\n    Linked_m_exe;\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    let main = |body: &str| {
        std::fs::write(
            task.join("PROGMOD").join("main.mod"),
            format!("MODULE MainModule\n  PROC main()\n    {body}\n  ENDPROC\nENDMODULE\n"),
        )
        .unwrap();
    };
    main("TPWrite \"cell ready\";");
    let (code, out, err) = rapidvc_testkit::procs::output_in(rapidvc!(), &dir, &["check", "."], 80);
    assert_eq!(code, 0, "check: {out}{err}");
    let (code, out, err) = run(&dir, &["."]);
    assert_eq!(code, 0, "run: {out}{err}");
    assert!(out.contains("cell ready"), "{out}");

    main("Linked_m;");
    let (code, out, err) = run(&dir, &["."]);
    assert_ne!(
        code, 0,
        "calling the service routine must stop the program: {out}"
    );
    assert!(
        err.contains("`Linked_m_exe` is not supported by rapidvc") && err.contains("linked motors"),
        "{err}"
    );
}
