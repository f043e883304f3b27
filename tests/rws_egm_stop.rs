//! Stopping and starting a program during an EGM run, and the speed ratio on EGM and moves,
//! against a real `rapidvc serve` of `tests/serve_egm/` (mode 4: a slow EGMRunJoint) and a
//! sensor written here: a UDP socket on loopback that answers every `EgmRobot` with a joint
//! target and keeps what the controller told it (RAPID execution state, MCI state, the
//! measured joints).
//!
//! Every test ends by itself: the sensor stops after a time-out, every wait is bounded, and
//! the controller is killed when its guard is dropped.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use prost::Message;
use rapidvc::egm::proto::EgmRobot;
use rapidvc::egm::proto::egm_mci_state::MciStateType;
use rapidvc::egm::proto::egm_motor_state::MotorStateType;
use rapidvc::egm::proto::egm_rapid_ctrl_exec_state::RapidCtrlExecStateType;
use rapidvc_testkit::egm_wire::joint_reply;
use rapidvc_testkit::procs::wait_until;
use rapidvc_testkit::rws_http::Client;
use rapidvc_testkit::serve::Serve;

use std::net::UdpSocket;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// The sensor's target (degrees): J3 is 20° from `home`, 2 s at MaxSpeedDeviation 10 °/s.
const TARGET: [f64; 6] = [10.0, -5.0, 20.0, 0.0, 40.0, 30.0];

/// One `EgmRobot` as the sensor saw it.
#[derive(Clone, Copy, Debug)]
struct Seen {
    at: Instant,
    /// The controller's time of the feedback (s).
    time: f64,
    rapid_running: bool,
    motors_on: bool,
    mci: Option<i32>,
    joints: [f64; 6],
}

/// The test's sensor (module docs).
struct Sensor {
    port: u16,
    stop: Arc<AtomicBool>,
    seen: Arc<Mutex<Vec<Seen>>>,
    handle: Option<JoinHandle<()>>,
}

impl Sensor {
    fn spawn() -> Sensor {
        let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
        socket
            .set_read_timeout(Some(Duration::from_millis(20)))
            .unwrap();
        let port = socket.local_addr().unwrap().port();
        let stop = Arc::new(AtomicBool::new(false));
        let seen = Arc::new(Mutex::new(Vec::new()));
        let (stop2, seen2) = (Arc::clone(&stop), Arc::clone(&seen));
        let handle = std::thread::spawn(move || {
            let origin = Instant::now();
            let mut buf = vec![0u8; 4096];
            let mut seq = 0u32;
            while !stop2.load(Ordering::Relaxed) && origin.elapsed() < Duration::from_secs(120) {
                let Ok((len, from)) = socket.recv_from(&mut buf) else {
                    continue;
                };
                let Ok(m) = EgmRobot::decode(&buf[..len]) else {
                    continue;
                };
                let mut joints = [f64::NAN; 6];
                if let Some(j) = m.feed_back.as_ref().and_then(|f| f.joints.as_ref()) {
                    for (d, s) in joints.iter_mut().zip(&j.joints) {
                        *d = *s;
                    }
                }
                let time = m
                    .feed_back
                    .as_ref()
                    .and_then(|f| f.time)
                    .map_or(f64::NAN, |t| t.sec as f64 + t.usec as f64 * 1e-6);
                seen2.lock().unwrap().push(Seen {
                    at: Instant::now(),
                    time,
                    rapid_running: m.rapid_exec_state.map(|s| s.state)
                        == Some(RapidCtrlExecStateType::RapidRunning as i32),
                    motors_on: m.motor_state.map(|s| s.state)
                        == Some(MotorStateType::MotorsOn as i32),
                    mci: m.mci_state.map(|s| s.state),
                    joints,
                });
                seq = seq.wrapping_add(1);
                let _ = socket.send_to(&joint_reply(seq, TARGET), from);
            }
        });
        Sensor {
            port,
            stop,
            seen,
            handle: Some(handle),
        }
    }

    fn seen(&self) -> Vec<Seen> {
        self.seen.lock().unwrap().clone()
    }
}

impl Drop for Sensor {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(h) = self.handle.take() {
            let _ = h.join();
        }
    }
}

fn serve(tag: &str, device: &str) -> Serve {
    let device = format!("--device=sensor={device}");
    Serve::start(
        rapidvc_testkit::rapidvc!(),
        tag,
        "tests/serve_egm",
        &[device.as_str()],
    )
}

fn login(srv: &Serve) -> Client {
    Client::login(srv.addr)
}

fn stopped(c: &mut Client) -> bool {
    c.state("/rw/rapid/execution")["ctrlexecstate"] == "stopped"
}

/// A number field of a resource's state.
fn number(c: &mut Client, path: &str, field: &str) -> f64 {
    c.state(path)[field].as_str().unwrap().parse().unwrap()
}

fn num(c: &mut Client, name: &str) -> f64 {
    number(
        c,
        &format!("/rw/rapid/symbol/data/RAPID/T_ROB1/{name}"),
        "value",
    )
}

/// Joint `axis` (1-based) as served.
fn joint(c: &mut Client, axis: usize) -> f64 {
    number(
        c,
        "/rw/motionsystem/mechunits/ROB_1/jointtarget",
        &format!("rax_{axis}"),
    )
}

fn post(c: &mut Client, path: &str, body: &str) {
    let r = c.post(path, body);
    assert_eq!(r.status, 204, "{path} {body}: {}", r.text());
}

fn start(c: &mut Client, cycle: &str) {
    post(
        c,
        "/rw/rapid/execution?action=start",
        &format!("cycle={cycle}"),
    );
}

fn stop(c: &mut Client) {
    post(c, "/rw/rapid/execution?action=stop", "");
}

/// Mode 4, started once; returns once J3 has passed `past` degrees.
fn start_slow_run(c: &mut Client, past: f64) {
    post(
        c,
        "/rw/iosystem/signals/Local/DRV_1/egm_mode?action=set",
        "lvalue=4",
    );
    start(c, "once");
    if past > 0.0 {
        wait_until(
            Duration::from_secs(15),
            Duration::from_millis(20),
            "the EGM run moves J3",
            || joint(c, 3) > past,
        );
    }
}

/// The test's sensor, a controller whose device "sensor" it is, and a client that started
/// mode 4 and saw J3 pass `past` degrees.
fn run_with_sensor(tag: &str, past: f64) -> (Sensor, Serve, Client) {
    let sensor = Sensor::spawn();
    let srv = serve(tag, &format!("127.0.0.1:{}", sensor.port));
    let mut c = login(&srv);
    start_slow_run(&mut c, past);
    (sensor, srv, c)
}

/// The run of one start ends: execution stopped, and `egm_time` set (it is 0 before).
fn wait_run_end(c: &mut Client, limit: Duration) -> f64 {
    wait_until(limit, Duration::from_millis(50), "the program ends", || {
        stopped(c) && num(c, "last_mode") == 4.0 && num(c, "egm_time") > 0.0
    });
    num(c, "egm_time")
}

/// The event log holds the stops and no EGM or program error.
fn no_errors(c: &mut Client) {
    let codes = c.elog_codes();
    assert!(
        codes.iter().any(|c| c == "10151"),
        "the stop is logged: {codes:?}"
    );
    for bad in ["41822", "90201", "50052"] {
        assert!(!codes.iter().any(|c| c == bad), "{bad} in {codes:?}");
    }
}

/// Highest joint speed (°/s, any axis) between consecutive messages in `seen`, by the
/// controller's feedback times.
fn peak_speed(seen: &[Seen]) -> f64 {
    seen.windows(2)
        .filter_map(|w| {
            let dt = w[1].time - w[0].time;
            (dt > 0.002).then(|| {
                w[1].joints
                    .iter()
                    .zip(&w[0].joints)
                    .map(|(a, b)| (a - b).abs() / dt)
                    .fold(0.0, f64::max)
            })
        })
        .fold(0.0, f64::max)
}

#[test]
fn a_stop_during_an_egm_run_pauses_it_and_a_start_resumes_it_to_convergence() {
    let (sensor, _srv, mut c) = run_with_sensor("egmstop", 5.0);
    stop(&mut c);
    let stopped_at = Instant::now();
    assert!(stopped(&mut c));
    // The EGM speed ramps to zero over the default profile's ramp time (0.5 s); the robot
    // then stands, short of the target.
    std::thread::sleep(Duration::from_millis(1200));
    let held = joint(&mut c, 3);
    std::thread::sleep(Duration::from_millis(500));
    assert_eq!(joint(&mut c, 3), held, "the robot stands while stopped");
    assert!(held > 5.0 && held < 19.0, "stopped on the way: {held}");
    // The sensor session stayed up and was told the truth.
    let seen = sensor.seen();
    let during: Vec<Seen> = seen
        .iter()
        .filter(|s| s.at > stopped_at + Duration::from_millis(100))
        .copied()
        .collect();
    assert!(
        during.len() > 100,
        "messages while stopped: {}",
        during.len()
    );
    assert!(
        during
            .iter()
            .all(|s| !s.rapid_running && s.mci == Some(MciStateType::MciStopped as i32)),
        "RAPID_STOPPED and MCI_STOPPED while stopped"
    );
    let before: Vec<Seen> = seen.iter().filter(|s| s.at < stopped_at).copied().collect();
    assert!(
        before
            .iter()
            .rev()
            .take(50)
            .all(|s| s.rapid_running && s.mci == Some(MciStateType::MciRunning as i32))
    );
    // Decelerated: never faster than MaxSpeedDeviation (10 °/s between messages, by the
    // controller's clock), and the ramp took time.
    let ramp: Vec<Seen> = seen
        .iter()
        .filter(|s| s.at >= stopped_at - Duration::from_millis(50))
        .copied()
        .collect();
    assert!(peak_speed(&ramp) < 10.5, "{}", peak_speed(&ramp));
    let moving_after = ramp
        .windows(2)
        .filter(|w| (w[1].joints[2] - w[0].joints[2]).abs() > 1e-6)
        .count();
    assert!(
        moving_after > 20,
        "a ramp, not a jump: {moving_after} messages"
    );
    // Start: the same EGMRunJoint goes on and converges on the target.
    start(&mut c, "asis");
    let t = wait_run_end(&mut c, Duration::from_secs(20));
    assert!(t > 1.0, "egm_time {t}");
    for (axis, want) in TARGET.iter().enumerate() {
        let got = joint(&mut c, axis + 1);
        assert!((got - want).abs() < 0.3, "J{}: {got} vs {want}", axis + 1);
    }
    let after = sensor.seen();
    assert!(
        after
            .iter()
            .filter(|s| s.at > stopped_at + Duration::from_millis(2000))
            .any(|s| s.rapid_running && s.mci == Some(MciStateType::MciRunning as i32)),
        "running again after the start"
    );
    assert!(peak_speed(&after) < 10.5, "{}", peak_speed(&after));
    no_errors(&mut c);
}

/// The motors switched off and on over RWS while an EGM run is stopped.
fn set_motors(c: &mut Client, on: bool) {
    post(
        c,
        "/rw/panel/ctrlstate?action=setctrlstate",
        if on {
            "ctrl-state=motoron"
        } else {
            "ctrl-state=motoroff"
        },
    );
}

#[test]
fn the_sensor_hears_the_motors_switched_off_and_on_while_the_run_is_stopped() {
    let (sensor, _srv, mut c) = run_with_sensor("egmmotors", 3.0);
    stop(&mut c);
    std::thread::sleep(Duration::from_millis(700));
    set_motors(&mut c, false);
    let off_at = Instant::now();
    std::thread::sleep(Duration::from_millis(600));
    set_motors(&mut c, true);
    let on_at = Instant::now();
    std::thread::sleep(Duration::from_millis(400));
    start(&mut c, "asis");
    let started_at = Instant::now();
    wait_run_end(&mut c, Duration::from_secs(20));
    let got = joint(&mut c, 3);
    assert!((got - TARGET[2]).abs() < 0.3, "J3 {got}");
    let seen = sensor.seen();
    let between = |from: Instant, to: Instant| -> Vec<Seen> {
        seen.iter()
            .filter(|s| s.at > from && s.at < to)
            .copied()
            .collect()
    };
    // Motors off: every message says so (a 20 ms poll and a cycle after the request), with
    // RAPID stopped; before it and after switching them on, MOTORS_ON.
    let off = between(off_at + Duration::from_millis(100), on_at);
    assert!(off.len() > 100, "messages while off: {}", off.len());
    assert!(
        off.iter().all(|s| !s.motors_on && !s.rapid_running),
        "MOTORS_OFF and RAPID_STOPPED while the motors are off"
    );
    let before = between(off_at - Duration::from_millis(600), off_at);
    assert!(!before.is_empty() && before.iter().all(|s| s.motors_on && !s.rapid_running));
    let on = between(on_at + Duration::from_millis(100), started_at);
    assert!(!on.is_empty() && on.iter().all(|s| s.motors_on && !s.rapid_running));
    let running = between(started_at + Duration::from_millis(100), Instant::now());
    assert!(
        running.iter().any(|s| s.motors_on && s.rapid_running),
        "MOTORS_ON and RAPID_RUNNING after the start"
    );
    assert!(peak_speed(&seen) < 10.5, "{}", peak_speed(&seen));
    no_errors(&mut c);
}

#[test]
fn stop_and_start_spam_during_an_egm_run_stays_within_its_speed_and_completes() {
    let (sensor, _srv, mut c) = run_with_sensor("egmspam", 2.0);
    for k in 0..20 {
        stop(&mut c);
        std::thread::sleep(Duration::from_millis(20 + 7 * (k % 5)));
        start(&mut c, "asis");
        std::thread::sleep(Duration::from_millis(15 + 11 * (k % 3)));
    }
    wait_run_end(&mut c, Duration::from_secs(30));
    let got = joint(&mut c, 3);
    assert!((got - TARGET[2]).abs() < 0.3, "J3 {got}");
    assert!(
        peak_speed(&sensor.seen()) < 10.5,
        "{}",
        peak_speed(&sensor.seen())
    );
    no_errors(&mut c);
}

#[test]
fn the_speed_ratio_slows_an_egm_run_at_once() {
    let srv = serve(
        "egmratio",
        &format!("builtin:joint:{}", {
            TARGET.map(|v| v.to_string()).join(",")
        }),
    );
    let mut c = login(&srv);
    start_slow_run(&mut c, 0.0);
    let full = wait_run_end(&mut c, Duration::from_secs(20));
    post(
        &mut c,
        "/rw/rapid/symbol/data/RAPID/T_ROB1/egm_time?action=set",
        "value=0",
    );
    // Set while the run goes on: it slows down at once.
    start_slow_run(&mut c, 0.5);
    post(
        &mut c,
        "/rw/panel/speedratio?action=setspeedratio",
        "speed-ratio=50",
    );
    let half = wait_run_end(&mut c, Duration::from_secs(30));
    // Robot time measured by the program: the ratio, not wall-clock figures.
    let ratio = half / full;
    assert!((1.4..2.4).contains(&ratio), "{half} s / {full} s = {ratio}");
    no_errors(&mut c);
}

/// The TCP's x (mm) in Base, as served.
fn tcp_x(c: &mut Client) -> f64 {
    number(c, ROBTARGET, "x")
}

/// tool0's robtarget in Base.
const ROBTARGET: &str =
    "/rw/motionsystem/mechunits/ROB_1/robtarget?tool=tool0&wobj=wobj0&coordinate=Base";

#[test]
fn a_stop_during_egm_move_l_brakes_and_a_start_continues_the_corrected_move() {
    // The built-in sensor corrects the path by (0, 3, -2) mm.
    let srv = serve("egmmovestop", "builtin:pathcorr:y=3,z=-2");
    let mut c = login(&srv);
    post(
        &mut c,
        "/rw/iosystem/signals/Local/DRV_1/egm_mode?action=set",
        "lvalue=3",
    );
    start(&mut c, "once");
    wait_until(
        Duration::from_secs(20),
        Duration::from_millis(20),
        "EGMMoveL moves along x",
        || num(&mut c, "last_mode") == 3.0 && tcp_x(&mut c) > 1100.0,
    );
    stop(&mut c);
    std::thread::sleep(Duration::from_millis(800));
    let held = tcp_x(&mut c);
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(tcp_x(&mut c), held, "the robot stands while stopped");
    assert!(held > 1100.0 && held < 1390.0, "stopped on the way: {held}");
    start(&mut c, "asis");
    wait_until(
        Duration::from_secs(20),
        Duration::from_millis(50),
        "the program ends",
        || stopped(&mut c),
    );
    // At the end of the path, still corrected after the start (tool0's TCP: the program's
    // tool is 200 mm long along z).
    let at = |c: &mut Client, f: &str| number(c, ROBTARGET, f);
    let (x, y, z) = (at(&mut c, "x"), at(&mut c, "y"), at(&mut c, "z"));
    assert!((x - 1400.0).abs() < 0.5, "at the end of the path: {x}");
    assert!(
        ((y - 20.0).abs() - 3.0).abs() < 0.5 && ((z - 700.0).abs() - 2.0).abs() < 0.5,
        "corrected: {y} {z}"
    );
    no_errors(&mut c);
}
