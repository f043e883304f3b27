//! RAPID sockets against real processes: a RAPID TCP command server (`tests/sockets/
//! server.mod`) served to a client written with Python's plain `socket` module, and a RAPID
//! client (`tests/sockets/client.mod`) of a Python server that checks the bytes
//! `PackRawBytes` made with `struct`. Both run `rapidvc run` in real time (a program with
//! sockets switches the clock) on 127.0.0.1; every process is bounded by a time-out. Plus
//! what a socket wait must allow: a timer trap runs during it, and Ctrl-C ends it.
//!
//! The Python is `python3` from `PATH` (the standard library only), or `RAPIDVC_SYSTEM_PYTHON`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use rapidvc_testkit::{procs, rapidvc};

use std::path::PathBuf;
use std::process::Command;
use std::time::Duration;

use procs::{Proc, json_field, rapidvc_run, root};

const LIMIT: Duration = Duration::from_secs(90);

fn python() -> Command {
    let exe = std::env::var_os("RAPIDVC_SYSTEM_PYTHON").unwrap_or_else(|| "python3".into());
    Command::new(exe)
}

/// A fresh directory for one test's `--pers` file.
fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rapidvc-sockets-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A port nobody listens on right now (the system's choice for port 0).
fn free_port() -> u16 {
    let l = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    l.local_addr().unwrap().port()
}

#[test]
fn a_rapid_command_server_serves_a_python_client() {
    let dir = temp_dir("server");
    let port = free_port();
    let pers = dir.join("server.pers");
    std::fs::write(&pers, format!("PERS num server_port := {port};\n")).unwrap();
    let mut server = Proc::spawn(rapidvc_run(
        rapidvc!(),
        "tests/sockets/server.mod",
        &["--pers".into(), pers.display().to_string()],
    ));
    let first = server.next_line(LIMIT);
    assert_eq!(first.as_deref(), Some("listening"));
    let mut client = python();
    client
        .arg(root().join("tests/sockets/cmd_client.py"))
        .arg(port.to_string());
    let client = Proc::spawn(client).wait(LIMIT);
    let server = server.wait(LIMIT);
    assert!(
        !client.timed_out && !server.timed_out,
        "{client:?}\n{server:?}"
    );
    assert_eq!(
        client.code,
        Some(0),
        "client:\n{}{}\nserver:\n{}{}",
        client.stdout,
        client.stderr,
        server.stdout,
        server.stderr
    );
    // Every command got its reply: the client checks each, these are the ones that matter.
    for line in [
        "move 1000,200,700 -> ok",
        "pos -> pos 1000.0 200.0 700.0",
        "set do1 1 -> ok",
        "get do1 -> do1 1",
        // Out of reach: the move fails with ERR_OUTSIDE_REACH, the server keeps serving.
        "move 9000,0,0 -> error 1402",
        // A digital output takes 0 or 1: ERR_ARGVALERR.
        "set do1 7 -> error 1004",
        "all replies right",
    ] {
        assert!(client.stdout.contains(line), "{line}\n{}", client.stdout);
    }
    assert_eq!(server.code, Some(0), "{}\n{}", server.stdout, server.stderr);
    assert!(server.stdout.contains("client from 127.0.0.1\n> pos\n"));
    assert!(
        server.stderr.contains("uses sockets") && server.stderr.contains("real time"),
        "{}",
        server.stderr
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_rapid_client_talks_to_a_python_server() {
    let dir = temp_dir("client");
    let mut server = python();
    server.arg(root().join("tests/sockets/data_server.py"));
    let mut server = Proc::spawn(server);
    let first = server
        .next_line(LIMIT)
        .expect("the Python server printed no port");
    let port: u16 = json_field(&first, "port").parse().unwrap();
    let pers = dir.join("client.pers");
    std::fs::write(&pers, format!("PERS num server_port := {port};\n")).unwrap();
    let client = Proc::spawn(rapidvc_run(
        rapidvc!(),
        "tests/sockets/client.mod",
        &["--pers".into(), pers.display().to_string()],
    ))
    .wait(LIMIT);
    let server = server.wait(LIMIT);
    assert!(
        !client.timed_out && !server.timed_out,
        "{client:?}\n{server:?}"
    );
    assert_eq!(
        server.code,
        Some(0),
        "server:\n{}{}\nclient:\n{}{}",
        server.stdout,
        server.stderr,
        client.stdout,
        client.stderr
    );
    // What Python's struct read from PackRawBytes' bytes.
    assert!(
        server
            .stdout
            .contains("numbers (1234567, 13.5, 65534, 'abc', -3)"),
        "{}",
        server.stdout
    );
    assert_eq!(client.code, Some(0), "{}\n{}", client.stdout, client.stderr);
    assert_eq!(
        client.stdout,
        "status 2\nserver says: hello robot\nreceived 8\nnetwork DINT -42\n\
         little-endian float 0.25\nthe server closed the connection\n"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A RAPID client whose server is not there: `SocketConnect` raises `ERR_SOCK_CLOSED`
/// (connection refused), and unhandled it stops the program with the event at its line.
#[test]
fn a_refused_connect_is_an_error_at_the_instruction() {
    let dir = temp_dir("refused");
    let pers = dir.join("client.pers");
    std::fs::write(&pers, format!("PERS num server_port := {};\n", free_port())).unwrap();
    let client = Proc::spawn(rapidvc_run(
        rapidvc!(),
        "tests/sockets/client.mod",
        &["--pers".into(), pers.display().to_string()],
    ))
    .wait(LIMIT);
    assert!(!client.timed_out);
    assert_ne!(client.code, Some(0), "{}", client.stdout);
    assert!(
        client.stderr.contains("ERR_SOCK_CLOSED") || client.stderr.contains("refused"),
        "{}",
        client.stderr
    );
    assert!(client.stderr.contains("client.mod:"), "{}", client.stderr);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Traps run while a socket instruction waits, and `\Time` ends the wait on the wall clock.
#[test]
fn a_timer_trap_runs_while_a_socket_waits() {
    let ended = procs::run_program(rapidvc!(), "tests/sockets/trap_wait.mod", &[], LIMIT);
    assert_eq!(ended.code, Some(0), "{}\n{}", ended.stdout, ended.stderr);
    assert_eq!(
        ended.stdout,
        "time-out after about 1 s: TRUE\nthe timer fired during the wait: TRUE\n"
    );
}

/// Ctrl-C stops a program that waits in `SocketAccept` (the server waits up to 30 s for a
/// client that never comes): it ends at once with the usual exit code 130.
#[test]
fn ctrl_c_ends_a_socket_wait() {
    let dir = temp_dir("ctrlc");
    let pers = dir.join("server.pers");
    std::fs::write(&pers, format!("PERS num server_port := {};\n", free_port())).unwrap();
    let mut server = Proc::spawn(rapidvc_run(
        rapidvc!(),
        "tests/sockets/server.mod",
        &["--pers".into(), pers.display().to_string()],
    ));
    assert_eq!(server.next_line(LIMIT).as_deref(), Some("listening"));
    let start = std::time::Instant::now();
    let status = Command::new("kill")
        .args(["-INT", &server.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let ended = server.wait(LIMIT);
    assert_eq!(ended.code, Some(130), "{}\n{}", ended.stdout, ended.stderr);
    assert!(
        start.elapsed() < Duration::from_secs(10),
        "Ctrl-C took {:?}",
        start.elapsed()
    );
    assert!(
        ended.stderr.contains("interrupted by Ctrl-C"),
        "{}",
        ended.stderr
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--max-time` ends a socket wait as it ends any other wait: the server waits up to 30 s
/// in `SocketAccept` for a client that never comes, and a run limited to 2 s ends there
/// with the time-limit error at that line.
#[test]
fn max_time_ends_a_socket_wait() {
    let dir = temp_dir("maxtime");
    let pers = dir.join("server.pers");
    std::fs::write(&pers, format!("PERS num server_port := {};\n", free_port())).unwrap();
    let start = std::time::Instant::now();
    let ended = Proc::spawn(rapidvc_run(
        rapidvc!(),
        "tests/sockets/server.mod",
        &[
            "--pers".into(),
            pers.display().to_string(),
            "--max-time".into(),
            "2".into(),
        ],
    ))
    .wait(LIMIT);
    assert!(!ended.timed_out, "{}", ended.stderr);
    assert_eq!(ended.code, Some(1), "{}\n{}", ended.stdout, ended.stderr);
    assert!(
        ended
            .stderr
            .contains("waits beyond the time limit of 2 s (use --max-time to raise it)"),
        "{}",
        ended.stderr
    );
    assert!(ended.stderr.contains("SocketAccept"), "{}", ended.stderr);
    assert!(
        start.elapsed() < Duration::from_secs(20),
        "the limit took {:?}",
        start.elapsed()
    );
    let _ = std::fs::remove_dir_all(&dir);
}
