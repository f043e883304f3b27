//! Robot Web Services over real loopback sockets: login and sessions, both representations,
//! ABB's status codes and error bodies, bad input of every kind, many sessions, subscriptions
//! over WebSocket and their clean-up.
//!
//! The controller is a real `rapidvc serve` of `tests/serve/` (its program counts cycles and
//! copies DI1 to DO_ECHO) on a free loopback port. Every test ends by itself (read time-outs
//! on every socket; the controller is killed when its guard is dropped).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use rapidvc_testkit::procs::wait_until;
use rapidvc_testkit::rws_http;
use rapidvc_testkit::serve::Serve;

use std::time::{Duration, Instant};

use rws_http::{Client, raw};

fn start(tag: &str) -> Serve {
    Serve::start(rapidvc_testkit::rapidvc!(), tag, "tests/serve", &[])
}

fn login(srv: &Serve) -> Client {
    Client::login(srv.addr)
}

/// The first `_state` entry of a resource in the JSON representation.
fn state(c: &mut Client, path: &str) -> serde_json::Value {
    c.state(path)
}

/// Joint 1 of the robot, in degrees, as served.
fn j1(c: &mut Client) -> f64 {
    state(c, "/rw/motionsystem/mechunits/ROB_1/jointtarget")["rax_1"]
        .as_str()
        .unwrap()
        .parse()
        .unwrap()
}

/// The `moves` program's `reached` flag.
fn reached(c: &mut Client) -> bool {
    state(c, "/rw/rapid/symbol/data/RAPID/T_ROB1/reached")["value"] == "TRUE"
}

/// True when RAPID execution is stopped.
fn stopped(c: &mut Client) -> bool {
    state(c, "/rw/rapid/execution")["ctrlexecstate"] == "stopped"
}

/// A controller serving `tests/serve/` with the `moves` routine as its entry.
fn start_moves(tag: &str) -> Serve {
    Serve::start(
        rapidvc_testkit::rapidvc!(),
        tag,
        "tests/serve",
        &["--entry", "moves"],
    )
}

/// Starts RAPID execution in a cycle mode (`once`, `forever`, `asis`); the write must answer 204.
fn start_program(c: &mut Client, cycle: &str) {
    let r = c.post(
        "/rw/rapid/execution?action=start",
        &format!("cycle={cycle}"),
    );
    assert_eq!(r.status, 204, "start {cycle}: {}", r.text());
}

/// Stops RAPID execution; the write must answer 204.
fn stop_program(c: &mut Client) {
    let r = c.post("/rw/rapid/execution?action=stop", "");
    assert_eq!(r.status, 204, "stop: {}", r.text());
}

/// Polls a live controller every 20 ms until `done`, for at most `secs` seconds.
fn within(secs: u64, what: &str, done: impl FnMut() -> bool) {
    wait_until(
        Duration::from_secs(secs),
        Duration::from_millis(20),
        what,
        done,
    );
}

#[test]
fn no_resource_answers_without_login() {
    let srv = start("nologin");
    for path in [
        "/rw/panel/ctrlstate",
        "/rw/rapid/execution?json=1",
        "/fileservice/$HOME",
        "/poll/1",
        "/no/such/thing",
        "/logout",
    ] {
        let r = raw(
            srv.addr,
            format!("GET {path} HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n").as_bytes(),
        )
        .unwrap();
        assert_eq!(r.status, 401, "{path}");
        let ch = r.header("www-authenticate").unwrap();
        assert!(
            ch.starts_with("Digest realm=\"validusers@robapi.abb\""),
            "{ch}"
        );
        assert!(
            ch.contains("qop=\"auth\"") && ch.contains("nonce=\""),
            "{ch}"
        );
    }
}

#[test]
fn wrong_credentials_get_401_even_with_a_valid_cookie() {
    let srv = start("wrongpw");
    let mut bad = Client::new(srv.addr, "Default User", "wrong");
    let r = bad.get("/rw/panel/ctrlstate?json=1");
    assert_eq!(r.status, 401);
    assert_eq!(r.header("content-type"), Some("application/json"));
    let j = r.json();
    assert!(
        j["_embedded"]["status"]["msg"]
            .as_str()
            .unwrap()
            .contains("password")
    );
    assert!(bad.cookie("ABBCX").is_none());
    let mut other = Client::new(srv.addr, "Admin", "robotics");
    assert_eq!(other.get("/rw/system").status, 401);
    // A good session's cookie does not excuse wrong credentials sent with it.
    let good = login(&srv);
    bad.cookies = good.cookies.clone();
    assert_eq!(
        bad.get("/rw/system").status,
        200,
        "the cookie alone is a session"
    );
    assert_eq!(bad.request_signed("GET", "/rw/system", b"").status, 401);
}

#[test]
fn the_session_cookie_replaces_credentials_until_logout() {
    let srv = start("cookie");
    let mut c = login(&srv);
    assert!(c.cookie("ABBCX").is_some());
    assert!(c.cookie("-http-session-").is_some());
    c.digest = false;
    assert_eq!(c.get("/rw/panel/opmode?json=1").status, 200);
    // ABBCX alone (what abb_robot_client sends for the WebSocket) is enough.
    c.cookies.retain(|(k, _)| k == "ABBCX");
    assert_eq!(c.get("/rw/panel/opmode?json=1").status, 200);
    let r = c.get("/logout");
    assert_eq!(r.status, 200);
    assert!(r.text().contains("<html"));
    assert_eq!(c.get("/rw/panel/opmode").status, 401);
    // A forged cookie is no session.
    c.cookies = vec![("ABBCX".into(), "0123456789abcdef0123456789abcdef".into())];
    assert_eq!(c.get("/rw/panel/opmode").status, 401);
}

#[test]
fn both_representations_carry_abb_classes() {
    let srv = start("repr");
    let mut c = login(&srv);
    let x = c.get("/rw/rapid/tasks");
    assert_eq!(x.status, 200);
    assert_eq!(
        x.header("content-type"),
        Some("application/xhtml+xml;v=1.0")
    );
    let t = x.text();
    assert!(
        t.contains("<li class=\"rap-task-li\" title=\"T_ROB1\">"),
        "{t}"
    );
    assert!(t.contains("<span class=\"excstate\">read</span>"));
    assert!(t.contains("<span class=\"motiontask\">TRUE</span>"));
    let j = c.get("/rw/rapid/tasks?json=1");
    assert_eq!(j.header("content-type"), Some("application/json"));
    let v = j.json();
    assert_eq!(v["_embedded"]["_state"][0]["_type"], "rap-task-li");
    assert_eq!(v["_embedded"]["_state"][0]["name"], "T_ROB1");
    let sys = c.get("/rw/system").text();
    assert!(sys.contains("<span class=\"rwversionname\">6.08.00.00</span>"));
    assert!(sys.contains("<span class=\"option\">689-1 Externally Guided Motion (EGM)</span>"));
    assert!(
        c.get("/ctrl")
            .text()
            .contains("<span class=\"ctrl-type\">Virtual Controller</span>")
    );
    let cfg = c.get("/rw/cfg/moc/mechanical_unit/instances").text();
    assert!(cfg.contains("<li class=\"cfg-dt-instance-li\" title=\"ROB_1\">"));
    assert!(cfg.contains(
        "<li class=\"cfg-ia-t-li\" title=\"use_robot\"><span class=\"value\">ROB_1</span>"
    ));
    let mu = c
        .get("/rw/motionsystem/mechunits/ROB_1?resource=static")
        .text();
    assert!(mu.contains("<span class=\"type\">TCPRobot</span>"));
    let rt = c
        .get("/rw/motionsystem/mechunits/ROB_1/robtarget?coordinate=Word&json=1")
        .json();
    assert_eq!(rt["_embedded"]["_state"][0]["_type"], "ms-robtargets");
    assert_eq!(rt["_embedded"]["_state"][0]["eaxa"], "9E+09");
    assert_eq!(rt["_embedded"]["_state"][0]["eax_a"], "9E+09");
}

#[test]
fn writes_answer_204_and_reach_the_controller() {
    let srv = start("writes");
    let mut c = login(&srv);
    let r = c.post(
        "/rw/iosystem/signals/Local/DRV_1/DO1?action=set",
        "lvalue=1",
    );
    assert_eq!(r.status, 204);
    let v = c.get("/rw/iosystem/signals/DO1?json=1").json();
    assert_eq!(v["_embedded"]["_state"][0]["lvalue"], "1");
    assert_eq!(
        c.post(
            "/rw/rapid/symbol/data/RAPID/T_ROB1/MainModule/counter?action=set",
            "value=7"
        )
        .status,
        204
    );
    let v = c
        .get("/rw/rapid/symbol/data/RAPID/T_ROB1/counter?json=1")
        .json();
    assert_eq!(v["_embedded"]["_state"][0]["value"], "7");
    assert_eq!(c.post("/rw/rapid/execution?action=start", "regain=continue&execmode=continue&cycle=once&condition=none&stopatbp=disabled&alltaskbytsp=false").status, 204);
    let v = c.get("/rw/rapid/execution?json=1").json();
    assert_eq!(v["_embedded"]["_state"][0]["ctrlexecstate"], "running");
    assert_eq!(v["_embedded"]["_state"][0]["cycle"], "once");
    // The file service: upload (201, then 200 on replace), list, read, delete.
    let mut put = |body: &str| {
        c.request("PUT", "/fileservice/$RAMDISK/a.txt", body.as_bytes())
            .status
    };
    assert_eq!(put("one"), 201);
    assert_eq!(put("two"), 200);
    assert_eq!(c.get("/fileservice/$RAMDISK/a.txt").text(), "two");
    let l = c.get("/fileservice/$RAMDISK?json=1").json();
    assert_eq!(l["_embedded"]["_state"][0]["_title"], "a.txt");
    assert_eq!(
        c.request("DELETE", "/fileservice/$RAMDISK/a.txt", b"")
            .status,
        204
    );
    assert_eq!(c.get("/fileservice/$RAMDISK/a.txt").status, 404);
}

#[test]
fn bad_input_gets_abb_errors_and_the_server_stays_up() {
    let srv = start("bad");
    let mut c = login(&srv);
    let code = |r: &rws_http::Resp| r.json()["_embedded"]["status"]["code"].as_i64().unwrap();
    // Unknown resources: 404 with ABB's body in both representations.
    let r = c.get("/rw/no/such?json=1");
    assert_eq!(r.status, 404);
    assert!(code(&r) < 0);
    let r = c.get("/rw/no/such");
    assert_eq!(r.status, 404);
    assert!(
        r.text().contains("<div class=\"status\">") && r.text().contains("<span class=\"code\">")
    );
    assert_eq!(c.get("/rw/iosystem/signals/NOPE?json=1").status, 404);
    assert_eq!(
        c.get("/rw/iosystem/signals/Other/DRV_1/DO1?json=1").status,
        404
    );
    // Writes of the wrong type: 400.
    for (path, form) in [
        ("/rw/iosystem/signals/DO1?action=set&json=1", "lvalue=2"),
        ("/rw/iosystem/signals/GO1?action=set&json=1", "lvalue=1.5"),
        (
            "/rw/panel/speedratio?action=setspeedratio&json=1",
            "speed-ratio=150",
        ),
        (
            "/rw/rapid/symbol/data/RAPID/T_ROB1/counter?action=set&json=1",
            "value=abc",
        ),
        (
            "/rw/rapid/symbol/data/RAPID/T_ROB1/arr?action=set&json=1",
            "value=[1,2]",
        ),
        ("/rw/rapid/execution?action=start&json=1", "cycle=sometimes"),
        ("/rw/rapid/execution?action=fly&json=1", ""),
        (
            "/rw/panel/ctrlstate?action=setctrlstate&json=1",
            "ctrl-state=warp",
        ),
    ] {
        let r = c.post(path, form);
        assert_eq!(r.status, 400, "{path} {form}: {}", r.text());
        assert!(code(&r) < 0);
    }
    // A constant is not writable: 403.
    assert_eq!(
        c.post(
            "/rw/rapid/symbol/data/RAPID/T_ROB1/c?action=set&json=1",
            "value=1"
        )
        .status,
        403
    );
    // The file sandbox: no escape, no host paths.
    for p in [
        "/fileservice/$HOME/../../etc/passwd",
        "/fileservice/$HOME/%2e%2e/x",
        "/fileservice/etc/passwd",
    ] {
        let r = c.get(p);
        assert!(r.status == 400 || r.status == 404, "{p}: {}", r.status);
    }
    // Huge bodies: 413 with ABB's body; the limit for uploads is larger but bounded too.
    let big = "x=".to_string() + &"a".repeat(200 * 1024);
    let r = c.post("/rw/panel/speedratio?action=setspeedratio&json=1", &big);
    assert_eq!(r.status, 413);
    assert!(code(&r) < 0);
    let huge = vec![b'a'; 17 * 1024 * 1024];
    assert_eq!(
        c.request("PUT", "/fileservice/$HOME/big.bin", &huge).status,
        413
    );
    assert!(!srv.home.join("big.bin").exists());
    // Malformed HTTP: answered (400) or closed, and the server keeps serving.
    for junk in [
        &b"GARBAGE\r\n\r\n"[..],
        b"GET / HTTP/9.9\r\n\r\n",
        b"\x00\x01\x02\x03\r\n\r\n",
        b"GET /rw/system HTTP/1.1\r\nContent-Length: nope\r\n\r\n",
    ] {
        if let Ok(r) = raw(srv.addr, junk) {
            assert!(r.status >= 400, "{junk:?}");
        }
    }
    let long_header = format!(
        "GET /rw/system HTTP/1.1\r\nHost: x\r\nX-Long: {}\r\n\r\n",
        "a".repeat(1 << 20)
    );
    if let Ok(r) = raw(srv.addr, long_header.as_bytes()) {
        assert!(r.status >= 400);
    }
    assert_eq!(c.get("/rw/panel/ctrlstate?json=1").status, 200);
}

#[test]
fn a_thousand_sessions_stay_bounded() {
    let srv = Serve::start(
        rapidvc_testkit::rapidvc!(),
        "sessions",
        "tests/serve",
        &["--rws-sessions", "50"],
    );
    let first = login(&srv);
    let addr = srv.addr;
    let threads: Vec<_> = (0..8)
        .map(|_| {
            std::thread::spawn(move || {
                let mut last = None;
                for _ in 0..125 {
                    let mut c = Client::new(addr, "Default User", "robotics");
                    assert_eq!(c.get("/rw/panel/ctrlstate?json=1").status, 200);
                    last = Some(c);
                }
                last.unwrap()
            })
        })
        .collect();
    for t in threads {
        t.join().unwrap();
    }
    // The oldest session made room; the newest ones still work without credentials.
    let mut first = first;
    first.digest = false;
    assert_eq!(first.get("/rw/panel/ctrlstate").status, 401);
    let lasts: Vec<Client> = (0..10).map(|_| login(&srv)).collect();
    for mut c in lasts {
        c.digest = false;
        assert_eq!(c.get("/rw/panel/ctrlstate").status, 200);
    }
}

#[test]
fn subscriptions_deliver_events_over_the_websocket_and_are_cleaned_up() {
    use futures_util::StreamExt;
    use tokio_tungstenite::tungstenite::client::IntoClientRequest;

    let srv = Serve::start(
        rapidvc_testkit::rapidvc!(),
        "subs",
        "tests/serve",
        &["--rws-subscriptions", "3", "--rws-unclaimed", "0.5"],
    );
    let mut c = login(&srv);
    let form = "resources=1&1=/rw/iosystem/signals/Local/DRV_1/DO_ECHO;state&1-p=1\
                &resources=2&2=/rw/rapid/execution;ctrlexecstate&2-p=1\
                &resources=3&3=/rw/rapid/symbol/data/RAPID/T_ROB1/counter;value&3-p=2";
    let r = c.post("/subscription?json=1", form);
    assert_eq!(r.status, 201, "{}", r.text());
    let loc = r.header("location").unwrap().to_string();
    assert!(loc.starts_with("ws://") && loc.contains("/poll/"), "{loc}");
    assert!(
        r.text()
            .contains(&format!("<a href=\"{loc}\" rel=\"self\">"))
    );
    // Unknown resources and a VAR are refused.
    assert_eq!(
        c.post("/subscription?json=1", "resources=1&1=/rw/nothing&1-p=1")
            .status,
        400
    );
    assert_eq!(
        c.post(
            "/subscription?json=1",
            "resources=1&1=/rw/rapid/symbol/data/RAPID/T_ROB1/v;value&1-p=1"
        )
        .status,
        400
    );
    let cookie = format!("ABBCX={}", c.cookie("ABBCX").unwrap());
    let rt = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    let frames = rt.block_on(async {
        let mut req = loc.as_str().into_client_request().unwrap();
        req.headers_mut().insert("Cookie", cookie.parse().unwrap());
        req.headers_mut().insert(
            "Sec-WebSocket-Protocol",
            "robapi2_subscription".parse().unwrap(),
        );
        let (mut ws, resp) = tokio::time::timeout(
            Duration::from_secs(5),
            tokio_tungstenite::connect_async(req),
        )
        .await
        .unwrap()
        .unwrap();
        assert_eq!(
            resp.headers()
                .get("sec-websocket-protocol")
                .map(|v| v.to_str().unwrap()),
            Some("robapi2_subscription")
        );
        let mut c2 = Client {
            digest: false,
            ..Client::new(srv.addr, "", "")
        };
        c2.cookies = c.cookies.clone();
        tokio::task::spawn_blocking(move || {
            assert_eq!(
                c2.post("/rw/rapid/execution?action=start", "cycle=forever")
                    .status,
                204
            );
            assert_eq!(
                c2.post(
                    "/rw/rapid/symbol/data/RAPID/T_ROB1/counter?action=set",
                    "value=3"
                )
                .status,
                204
            );
            // The program copies DI1 to DO_ECHO: a signal set by RAPID.
            assert_eq!(
                c2.post(
                    "/rw/iosystem/signals/Local/DRV_1/DI1?action=set",
                    "lvalue=1"
                )
                .status,
                204
            );
        })
        .await
        .unwrap();
        let mut got = Vec::new();
        let all_there = |got: &[String]| {
            let all = got.join("\n");
            all.contains("<span class=\"lvalue\">1</span>")
                && all.contains("<span class=\"ctrlexecstate\">running</span>")
                && all.contains("<span class=\"value\">3</span>")
        };
        while !all_there(&got) {
            let m = tokio::time::timeout(Duration::from_secs(5), ws.next())
                .await
                .unwrap_or_else(|_| panic!("no more events; got {got:?}"))
                .unwrap()
                .unwrap();
            got.push(m.into_text().unwrap().to_string());
        }
        got
    });
    let all = frames.join("\n");
    assert!(all.contains("li class=\"ios-signalstate-ev\""), "{all}");
    assert!(all.contains("<span class=\"lvalue\">1</span>"));
    assert!(all.contains("<span class=\"ctrlexecstate\">running</span>"));
    assert!(all.contains("<span class=\"value\">3</span>"));
    // The cap on subscriptions; one left unclaimed is removed after the unclaimed time.
    let ids: Vec<String> = (0..2)
        .map(|_| {
            let r = c.post("/subscription", "resources=1&1=/rw/panel/ctrlstate&1-p=0");
            assert_eq!(r.status, 201);
            r.header("location")
                .unwrap()
                .rsplit('/')
                .next()
                .unwrap()
                .to_string()
        })
        .collect();
    let r = c.post(
        "/subscription?json=1",
        "resources=1&1=/rw/panel/ctrlstate&1-p=0",
    );
    assert_eq!(r.status, 503, "{}", r.text());
    let t0 = Instant::now();
    while t0.elapsed() < Duration::from_secs(5) {
        std::thread::sleep(Duration::from_millis(300));
        if c.post("/subscription", "resources=1&1=/rw/panel/ctrlstate&1-p=0")
            .status
            == 201
        {
            break;
        }
    }
    assert_eq!(
        c.request("DELETE", &format!("/subscription/{}", ids[0]), b"")
            .status,
        404,
        "swept"
    );
    assert!(t0.elapsed() < Duration::from_secs(5));
}

#[test]
fn the_program_stops_keeps_its_pointer_and_shares_data_and_signals() {
    let srv = start("program");
    let mut c = login(&srv);
    let cycles = |c: &mut Client| -> f64 {
        let v = c
            .get("/rw/rapid/symbol/data/RAPID/T_ROB1/MainModule/cycles?json=1")
            .json();
        v["_embedded"]["_state"][0]["value"]
            .as_str()
            .unwrap()
            .parse()
            .unwrap()
    };
    let wait_for = |c: &mut Client, what: &str, ok: &dyn Fn(&mut Client) -> bool| {
        within(10, what, || ok(c));
    };
    assert_eq!(cycles(&mut c), 0.0, "nothing runs before a start");
    start_program(&mut c, "forever");
    wait_for(&mut c, "the program runs", &|c| cycles(c) >= 3.0);
    // PERS written over RWS is what RAPID reads next.
    assert_eq!(
        c.post(
            "/rw/rapid/symbol/data/RAPID/T_ROB1/cycles?action=set",
            "value=1000"
        )
        .status,
        204
    );
    wait_for(&mut c, "RAPID counts on from 1000", &|c| cycles(c) > 1000.0);
    // A signal set over RWS is read by RAPID, which sets another one.
    assert_eq!(
        c.post(
            "/rw/iosystem/signals/Local/DRV_1/DI1?action=set",
            "lvalue=1"
        )
        .status,
        204
    );
    wait_for(&mut c, "DO_ECHO follows DI1", &|c| {
        c.get("/rw/iosystem/signals/Local/DRV_1/DO_ECHO?json=1")
            .json()["_embedded"]["_state"][0]["lvalue"]
            == "1"
    });
    // The program pointer cannot be reset while running; stop, and nothing runs.
    assert!(
        c.post("/rw/rapid/execution?action=resetpp", "").status >= 400,
        "resetpp while running"
    );
    stop_program(&mut c);
    std::thread::sleep(Duration::from_millis(200));
    let stopped_at = cycles(&mut c);
    std::thread::sleep(Duration::from_millis(400));
    assert_eq!(cycles(&mut c), stopped_at, "a stopped program does not run");
    // Start continues from the program pointer (the cycle mode kept as it was).
    start_program(&mut c, "asis");
    let v = c.get("/rw/rapid/execution?json=1").json();
    assert_eq!(v["_embedded"]["_state"][0]["cycle"], "forever");
    wait_for(&mut c, "the program goes on", &|c| cycles(c) > stopped_at);
    // The operating mode is what RAPID's OpMode() reads; changing it stops the program.
    assert_eq!(
        c.post("/rw/panel/opmode?action=setopmode", "opmode=man")
            .status,
        204
    );
    let v = c.get("/rw/rapid/execution?json=1").json();
    assert_eq!(v["_embedded"]["_state"][0]["ctrlexecstate"], "stopped");
    start_program(&mut c, "asis");
    wait_for(&mut c, "RAPID sees OP_MAN_PROG", &|c| {
        c.get("/rw/rapid/symbol/data/RAPID/T_ROB1/opmode_seen?json=1")
            .json()["_embedded"]["_state"][0]["value"]
            == "2"
    });
    stop_program(&mut c);
    assert_eq!(c.post("/rw/rapid/execution?action=resetpp", "").status, 204);
    // Motors off: start is refused.
    assert_eq!(
        c.post(
            "/rw/panel/ctrlstate?action=setctrlstate",
            "ctrl-state=motoroff"
        )
        .status,
        204
    );
    assert!(
        c.post("/rw/rapid/execution?action=start", "cycle=once")
            .status
            >= 400
    );
    // The event log holds what happened, numbered.
    let codes = c.elog_codes();
    for want in ["10150", "10151", "10002", "10010"] {
        assert!(codes.iter().any(|c| c == want), "{want} in {codes:?}");
    }
    // Ctrl-C: a clean shutdown.
    let ended = srv.stop(Duration::from_secs(20));
    assert_eq!(ended.code, Some(0), "{ended:?}");
    assert!(ended.stderr.contains("rapidvc serve: stopped"), "{ended:?}");
}

#[test]
fn a_move_interrupted_by_stop_continues_to_its_target_on_start() {
    let srv = start_moves("moves");
    let mut c = login(&srv);
    start_program(&mut c, "once");
    within(10, "the robot moves", || j1(&mut c) >= 3.0);
    stop_program(&mut c);
    std::thread::sleep(Duration::from_millis(500));
    let held = j1(&mut c);
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(j1(&mut c), held, "the robot stands while stopped");
    assert!(held > 3.0 && held < 29.0, "stopped on the way: {held}");
    assert!(!reached(&mut c), "the program waits in its move");
    start_program(&mut c, "asis");
    within(15, "the move ends", || reached(&mut c));
    // The served position is the motion thread's latest cycle (docs/rws.md): once the
    // program knows its fine move ended, one read shows the target (a copy refreshed by the
    // program side every 20 ms could still be on the way).
    let at = j1(&mut c);
    assert!(
        (at - 30.0).abs() < 0.01,
        "at the target when `reached`: {at}"
    );
    // A single cycle ended: execution stopped.
    within(5, "stopped after once", || stopped(&mut c));
}

/// A stop in the middle of a fast straight line decelerates on the line and holds there; a
/// start goes on along the same path, through the fly-by corner, to the end. (Before, a stop
/// braked every axis on its own and left the line by more than a millimetre.)
#[test]
fn a_stop_holds_the_robot_on_its_path_and_a_start_goes_on_along_it() {
    let dir = std::env::temp_dir().join(format!("rapidvc-rws-line-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let trace = dir.join("line.csv");
    let srv = Serve::start(
        rapidvc_testkit::rapidvc!(),
        "line",
        "tests/serve",
        &["--entry", "line", "--trace", trace.to_str().unwrap()],
    );
    let mut c = login(&srv);
    start_program(&mut c, "once");
    let tcp = |c: &mut Client| {
        let s = state(
            c,
            "/rw/motionsystem/mechunits/ROB_1/robtarget?tool=tool0&wobj=wobj0&coordinate=Base",
        );
        let f = |k: &str| s[k].as_str().unwrap().parse::<f64>().unwrap();
        [f("x"), f("y"), f("z")]
    };
    within(20, "the TCP is on the line, past its middle", || {
        let [x, y, _] = tcp(&mut c);
        (x - 900.0).abs() < 0.01 && y > -100.0
    });
    stop_program(&mut c);
    within(5, "stopped", || stopped(&mut c));
    let held = tcp(&mut c);
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(tcp(&mut c), held, "the robot stands while stopped");
    assert!(!reached(&mut c), "the program waits in its move");
    start_program(&mut c, "asis");
    within(15, "the moves end", || reached(&mut c));
    let ended = srv.stop(Duration::from_secs(20));
    assert_eq!(ended.code, Some(0), "{ended:?}");
    let trace = rapidvc_testkit::csv::Csv::read(&trace);
    let col = |name: &str| trace.col(name);
    let (instr, x, y, z, speed) = (
        col("instr"),
        col("x"),
        col("y"),
        col("z"),
        col("speed_mm_s"),
    );
    let num = |r: &Vec<String>, c: usize| r[c].parse::<f64>().unwrap();
    let line: Vec<&Vec<String>> = trace.rows.iter().filter(|r| r[instr] == "MoveL").collect();
    // On the first line (before its corner zone of 100 mm): x = 900 and z = 800 throughout,
    // the hold included.
    let mut rests = 0;
    for r in line.iter().filter(|r| num(r, y) < 199.0) {
        assert!(
            (num(r, x) - 900.0).abs() < 0.01 && (num(r, z) - 800.0).abs() < 0.01,
            "off the line at {:?}",
            [num(r, x), num(r, y), num(r, z)]
        );
        if num(r, speed) == 0.0 {
            rests += 1;
        }
    }
    assert!(rests > 50, "held on the line ({rests} cycles at rest)");
    let last = line.last().unwrap();
    assert!(
        (num(last, x) - 1200.0).abs() < 0.01 && (num(last, y) - 300.0).abs() < 0.01,
        "ends at the last target"
    );
}

#[test]
fn the_speed_ratio_scales_the_moves_planned_after_it_and_those_under_way() {
    let srv = start_moves("speedratio");
    let mut c = login(&srv);
    let set_ratio = |c: &mut Client, percent: u32| {
        let r = c.post(
            "/rw/panel/speedratio?action=setspeedratio",
            &format!("speed-ratio={percent}"),
        );
        assert_eq!(r.status, 204);
    };
    // One run of `moves`; with `half_from`, the ratio goes to 50 % once the timed move
    // (0° → 30°) has passed that joint-1 angle.
    let timed_run = |c: &mut Client, half_from: Option<f64>| -> f64 {
        start_program(c, "once");
        if let Some(at) = half_from {
            // Home first (the last run left the robot at 30°), then on the timed move.
            within(10, "the robot goes home", || j1(c) < at - 1.0);
            within(10, "the robot moves", || j1(c) > at);
            set_ratio(c, 50);
        }
        within(30, "the run ends", || reached(c) && stopped(c));
        state(c, "/rw/rapid/symbol/data/RAPID/T_ROB1/move_time")["value"]
            .as_str()
            .unwrap()
            .parse()
            .unwrap()
    };
    let full = timed_run(&mut c, None);
    set_ratio(&mut c, 50);
    let half = timed_run(&mut c, None);
    // Robot time measured by the program in one run: the ratio, not wall-clock figures.
    let ratio = half / full;
    assert!((1.6..2.4).contains(&ratio), "{half} s / {full} s = {ratio}");
    // Set while the move runs (from 3° of its 30°): the rest of it at half speed.
    set_ratio(&mut c, 100);
    let slowed = timed_run(&mut c, Some(3.0));
    let ratio = slowed / full;
    assert!(
        (1.5..2.3).contains(&ratio),
        "{slowed} s / {full} s = {ratio}"
    );
}

#[test]
fn ctrl_c_during_fly_by_moves_run_forever_voids_the_moves_on_their_way() {
    // The moves the program had already sent when Ctrl-C came were planned from where the
    // dropped moves would have ended: they must be dropped too, never run from where the
    // robot stopped (that run was a 40° jump in one cycle, reported as a joint speed error).
    for wait_ms in [700, 1300, 2100] {
        let srv = Serve::start(
            rapidvc_testkit::rapidvc!(),
            "shuttle",
            "tests/serve",
            &["--entry", "shuttle"],
        );
        let mut c = login(&srv);
        start_program(&mut c, "forever");
        std::thread::sleep(Duration::from_millis(wait_ms));
        let ended = srv.stop(Duration::from_secs(20));
        assert_eq!(ended.code, Some(0), "{ended:?}");
        assert!(!ended.stderr.contains("speed"), "{}", ended.stderr);
        assert!(!ended.stderr.contains("event:"), "{}", ended.stderr);
    }
}

#[test]
fn ctrl_c_during_a_move_brakes_the_robot_and_ends_cleanly() {
    let srv = start_moves("sigint");
    let mut c = login(&srv);
    start_program(&mut c, "once");
    within(10, "the robot moves", || j1(&mut c) > 3.0);
    let ended = srv.stop(Duration::from_secs(20));
    assert_eq!(ended.code, Some(0), "{ended:?}");
    assert!(!ended.timed_out, "{ended:?}");
    // The summary of the real-time run, with the motion thread's period error.
    assert!(ended.stderr.contains("period error"), "{}", ended.stderr);
    assert!(
        ended.stderr.contains("rapidvc serve: stopped"),
        "{}",
        ended.stderr
    );
}

/// Every task's entry of `rw/rapid/tasks`, by name: (type, excstate, active, motiontask).
fn tasks(c: &mut Client) -> Vec<(String, [String; 4])> {
    let j = c.get("/rw/rapid/tasks?json=1").json();
    j["_embedded"]["_state"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| {
            let f = |k: &str| t[k].as_str().unwrap().to_string();
            (
                f("name"),
                [f("type"), f("excstate"), f("active"), f("motiontask")],
            )
        })
        .collect()
}

/// A number the program holds, read over RWS.
fn num(c: &mut Client, path: &str) -> f64 {
    state(c, &format!("/rw/rapid/symbol/data/RAPID/{path}"))["value"]
        .as_str()
        .unwrap()
        .parse()
        .unwrap()
}

/// The next message of an external queue (waiting up to 5 s): `dipc-data` and
/// `dipc-userdef`.
fn dipc_read(c: &mut Client, queue: &str) -> Option<(String, String)> {
    let j = c
        .get(&format!(
            "/rw/dipc/{queue}?action=dipc-read&timeout=5&json=1"
        ))
        .json();
    let m = j["_embedded"]["_state"].get(0)?.clone();
    Some((
        m["dipc-data"].as_str()?.to_string(),
        m["dipc-userdef"].as_str()?.to_string(),
    ))
}

#[test]
fn a_served_system_of_three_tasks_runs_its_static_tasks_across_stops_and_talks_rmq() {
    let srv = Serve::start(
        rapidvc_testkit::rapidvc!(),
        "tasks",
        "tests/serve_tasks",
        &[],
    );
    let mut c = login(&srv);
    let t = tasks(&mut c);
    let names: Vec<&str> = t.iter().map(|t| t.0.as_str()).collect();
    assert_eq!(names, ["T_ROB1", "T_LOG", "T_CELL"]);
    assert_eq!(t[0].1, ["norm", "read", "On", "TRUE"].map(String::from));
    assert_eq!(t[1].1, ["stat", "star", "On", "FALSE"].map(String::from));
    assert_eq!(t[2].1, ["semi", "star", "On", "FALSE"].map(String::from));
    // The STATIC task counts from boot, before any start.
    let t0 = num(&mut c, "T_LOG/ticks");
    within(10, "T_LOG does not run at boot", || {
        num(&mut c, "T_LOG/ticks") >= t0 + 5.0
    });

    // A message to a task's queue before the task reads it: it waits in the queue.
    assert_eq!(
        c.post(
            "/rw/dipc?action=dipc-create",
            "dipc-queue-name=PC_Q&dipc-queue-size=10&dipc-max-msg-size=444"
        )
        .status,
        201
    );
    let send = |c: &mut Client, to: &str, data: &str| {
        c.post(
            &format!("/rw/dipc/{to}?action=dipc-send"),
            &format!(
                "dipc-src-queue-name=PC_Q&dipc-cmd=111&dipc-userdef=5&dipc-msgtype=1&dipc-data={data}"
            ),
        )
    };
    // Data without its type is refused (a task's queue holds typed RAPID data).
    let r = send(&mut c, "RMQ_T_ROB1", "hello");
    assert!(r.status == 400 || r.status == 403, "{}", r.text());
    assert!(r.text().contains("type;value"), "{}", r.text());
    assert_eq!(send(&mut c, "RMQ_T_ROB1", "string;%22hello%22").status, 204);

    // Start once: the robot moves, the shared PERS counts (seen by T_CELL), the message is
    // answered into the external queue with its type.
    start_program(&mut c, "once");
    let answer = dipc_read(&mut c, "PC_Q");
    assert_eq!(
        answer,
        Some(("string;\"got hello\"".to_string(), "7".to_string()))
    );
    within(10, "stopped(&mut c)", || stopped(&mut c));
    assert_eq!(num(&mut c, "T_ROB1/shared"), 1.0);
    within(5, "the shared PERS is one value in every task", || {
        num(&mut c, "T_CELL/Cell/shared") == 1.0
    });
    within(5, "num( &mut c, 'T_CELL/seen' ) == 1.0", || {
        num(&mut c, "T_CELL/seen") == 1.0
    });

    // Start again and stop while T_ROB1 waits for a message: only the NORMAL task stops;
    // the STATIC one keeps counting.
    start_program(&mut c, "once");
    within(10, "num( &mut c, 'T_ROB1/shared' ) == 2.0", || {
        num(&mut c, "T_ROB1/shared") == 2.0
    });
    stop_program(&mut c);
    within(5, "stopped(&mut c)", || stopped(&mut c));
    let t = tasks(&mut c);
    assert_eq!(t[0].1[1], "stop");
    assert_eq!(t[1].1[1], "star");
    let before = num(&mut c, "T_LOG/ticks");
    within(10, "T_LOG stopped with the NORMAL task", || {
        num(&mut c, "T_LOG/ticks") >= before + 5.0
    });
    // A message meanwhile waits; on start the program continues from its pointer and takes it.
    assert_eq!(send(&mut c, "T_ROB1", "string;%22again%22").status, 204);
    start_program(&mut c, "asis");
    assert_eq!(
        dipc_read(&mut c, "PC_Q"),
        Some(("string;\"got again\"".to_string(), "7".to_string()))
    );
    within(10, "stopped(&mut c)", || stopped(&mut c));
    assert_eq!(num(&mut c, "T_ROB1/answered"), 2.0);

    // Deactivated, T_ROB1 does not start (no NORMAL task is active); activated, it does.
    assert_eq!(
        c.post("/rw/rapid/tasks/T_ROB1?action=deactivate", "")
            .status,
        204
    );
    assert_eq!(tasks(&mut c)[0].1[2], "Off");
    let r = c.post("/rw/rapid/execution?action=start", "cycle=once");
    assert!(r.status >= 400, "{}", r.text());
    assert_eq!(
        c.post("/rw/rapid/tasks/T_ROB1?action=activate", "").status,
        204
    );
    // An unknown task's data is a 404.
    assert_eq!(
        c.get("/rw/rapid/symbol/data/RAPID/T_NONE/shared?json=1")
            .status,
        404
    );
    let ended = srv.stop(Duration::from_secs(20));
    assert_eq!(ended.code, Some(0), "{}", ended.stderr);
    assert!(
        ended
            .stdout
            .contains("[T_ROB1] robot: hello (a string) from PC_Q"),
        "{}",
        ended.stdout
    );
    assert!(
        ended.stdout.contains("[T_CELL] cell: shared is 2"),
        "{}",
        ended.stdout
    );
}
