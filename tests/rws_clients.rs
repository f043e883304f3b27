//! Robot Web Services of a real `rapidvc serve` driven by abb_robot_client's `RWS` class
//! (PyPI, unchanged): every call it makes, a subscription receiving signal, execution,
//! persistent and event-log events over the WebSocket, and the XHTML resources abb_librws
//! reads, parsed with a DOM parser (`tests/clients/rws_client.py`).
//!
//! Needs `RAPIDVC_PYTHON` when the tests are built (see `build.rs`); ends by itself (the
//! script's own waits are bounded, and the children are killed after a time-out).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use rapidvc_testkit::procs;
use rapidvc_testkit::serve::Serve;

use std::process::Command;
use std::time::Duration;

use procs::{Proc, python, root};

#[test]
#[cfg_attr(
    not(rapidvc_python),
    ignore = "needs RAPIDVC_PYTHON (a Python with abb_robot_client) when the tests are built"
)]
fn abb_robot_client_drives_every_resource_it_uses() {
    let srv = Serve::start(rapidvc_testkit::rapidvc!(), "pyclient", "tests/serve", &[]);
    let mut cmd = Command::new(python());
    cmd.arg(root().join("tests/clients/rws_client.py"))
        .arg(srv.url());
    let ended = Proc::spawn(cmd).wait(Duration::from_secs(90));
    assert!(
        ended.code == Some(0) && ended.stdout.contains("ALL OK"),
        "stdout:\n{}\nstderr:\n{}",
        ended.stdout,
        ended.stderr
    );
}

#[test]
#[cfg_attr(
    not(rapidvc_python),
    ignore = "needs RAPIDVC_PYTHON (a Python with abb_robot_client) when the tests are built"
)]
fn abb_robot_client_rws_and_egm_run_joint_pose_and_path_correction_sessions() {
    rws_and_egm_script("pyegm", "tests/clients/rws_egm.py");
}

#[test]
#[cfg_attr(
    not(rapidvc_python),
    ignore = "needs RAPIDVC_PYTHON (a Python with abb_robot_client) when the tests are built"
)]
fn abb_robot_client_stops_and_restarts_an_egm_session_and_sets_the_speed_ratio() {
    rws_and_egm_script("pyegmstop", "tests/clients/rws_egm_stop.py");
}

/// Runs `script` (RWS URL and EGM port as arguments) against `rapidvc serve` of
/// `tests/serve_egm/` whose device "sensor" is the client's EGM socket; it must print ALL OK.
fn rws_and_egm_script(tag: &str, script: &str) {
    // A free UDP port for the client's EGM socket (taken again by the client at once).
    let port = std::net::UdpSocket::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let device = format!("--device=sensor=127.0.0.1:{port}");
    let srv = Serve::start(
        rapidvc_testkit::rapidvc!(),
        tag,
        "tests/serve_egm",
        &[device.as_str()],
    );
    let mut cmd = Command::new(python());
    cmd.arg(root().join(script))
        .arg(srv.url())
        .arg(port.to_string());
    let ended = Proc::spawn(cmd).wait(Duration::from_secs(150));
    assert!(
        ended.code == Some(0) && ended.stdout.contains("ALL OK"),
        "stdout:\n{}\nstderr:\n{}",
        ended.stdout,
        ended.stderr
    );
}
