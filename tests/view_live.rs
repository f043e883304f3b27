//! `rapidvc run --view-live`: a real-time run serves the view page over HTTP and streams the
//! robot's state to a real WebSocket client (tokio-tungstenite) while the program runs; a
//! viewer that never reads cannot hold the run up. The router also works mounted under
//! `/view` of another axum server.

use rapidvc_testkit::rapidvc;
use rapidvc_testkit::view_page::LiveRun;
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use futures_util::StreamExt;
use rapidvc::output::view::{Scene, ViewSession};
use rapidvc::robot::Robot;
use rapidvc::source::SourceMap;
use serde_json::Value;
use tokio_tungstenite::tungstenite::Message;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// `GET path` over a plain socket: (status line, body).
fn http_get(addr: SocketAddr, path: &str) -> (String, String) {
    let mut s = TcpStream::connect_timeout(&addr, Duration::from_secs(5)).expect("connect");
    s.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    write!(
        s,
        "GET {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let mut text = String::new();
    s.read_to_string(&mut text).expect("response");
    let status = text.lines().next().unwrap_or("").to_string();
    let body = text
        .split_once("\r\n\r\n")
        .map(|(_, b)| b.to_string())
        .unwrap_or_default();
    (status, body)
}

/// Read WebSocket messages until the stream ends (or 30 s pass); the JSON messages.
async fn read_stream(url: &str) -> Vec<Value> {
    let (mut ws, _) = tokio_tungstenite::connect_async(url)
        .await
        .expect("websocket");
    let mut out = Vec::new();
    let deadline = tokio::time::Instant::now() + Duration::from_secs(30);
    loop {
        let next = tokio::time::timeout_at(deadline, ws.next()).await;
        match next {
            Ok(Some(Ok(Message::Text(t)))) => out.push(serde_json::from_str(&t).expect("JSON")),
            Ok(Some(Ok(Message::Close(_)))) | Ok(None) => break,
            Ok(Some(Ok(_))) => {}
            Ok(Some(Err(e))) => panic!("websocket error: {e}"),
            Err(_) => panic!("the stream did not end within 30 s"),
        }
    }
    out
}

#[test]
fn a_live_run_streams_the_robot_to_a_websocket_client() {
    let live = LiveRun::start(rapidvc!(), &root(), "tests/view/live_run.mod");
    let url = live
        .url
        .strip_prefix("http://")
        .and_then(|r| r.split('/').next())
        .unwrap_or_else(|| panic!("no address in {}", live.url));
    let addr: SocketAddr = url.parse().expect("address");
    assert!(addr.ip().is_loopback(), "binds loopback by default: {addr}");

    // A viewer that connects and never reads: it must not hold the run (or the others) up.
    let mut stalled = TcpStream::connect(addr).expect("stalled viewer");
    write!(
        stalled,
        "GET /ws HTTP/1.1\r\nHost: {addr}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n\
         Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n"
    )
    .unwrap();

    let (status, page) = http_get(addr, "/");
    assert!(status.contains("200"), "{status}");
    assert!(
        page.contains(r#""live":true"#),
        "the page connects to the stream"
    );
    let (status, _) = http_get(addr, "/nothing-here");
    assert!(status.contains("404"), "{status}");

    let started = Instant::now();
    let rt = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    let msgs = rt.block_on(read_stream(&format!("ws://{addr}/ws")));
    let streamed_for = started.elapsed();

    let kinds: Vec<&str> = msgs.iter().map(|m| m["type"].as_str().unwrap()).collect();
    assert_eq!(kinds.first(), Some(&"snapshot"));
    assert_eq!(kinds.last(), Some(&"end"));
    let snapshot = &msgs[0]["data"];
    assert_eq!(snapshot["live"], true);
    assert_eq!(snapshot["scene"]["robot"]["name"], "IRB 2600-12/1.85");
    let rows: Vec<&Value> = msgs.iter().filter(|m| m["type"] == "row").collect();
    let times: Vec<i64> = rows.iter().map(|r| r["t"].as_i64().unwrap()).collect();
    assert!(times.windows(2).all(|w| w[0] < w[1]), "rows in time order");
    // The program moves for three seconds of robot time, streamed at 50 rows a second.
    assert!(rows.len() >= 100, "{} rows", rows.len());
    let j1: Vec<f64> = rows.iter().map(|r| r["j"][0].as_f64().unwrap()).collect();
    let top = j1.iter().cloned().fold(f64::MIN, f64::max);
    assert!((top - 30.0).abs() < 0.01, "J1 reaches 30°: {top}");
    assert!(j1.last().unwrap().abs() < 0.01, "and returns to 0°");
    assert!(
        streamed_for >= Duration::from_millis(1500),
        "the stream follows the robot in real time ({streamed_for:?})"
    );
    let tp: Vec<&str> = msgs
        .iter()
        .filter(|m| m["type"] == "log" && m["entry"][1] == "tp")
        .map(|m| m["entry"][2].as_str().unwrap())
        .collect();
    let in_snapshot = rapidvc_testkit::view_page::tp_lines(&snapshot["log"]);
    let mut all: Vec<&str> = in_snapshot.clone();
    all.extend(tp.iter().filter(|l| !in_snapshot.contains(l)));
    assert_eq!(all, ["to b 1", "to a 1", "to b 2", "to a 2"]);
    assert!(msgs.iter().any(|m| m["type"] == "instr"));

    let (status, rest) = live.finish();
    drop(stalled);
    assert!(status.success(), "{rest}");
    assert!(rest.contains("period error"), "real time: {rest}");
}

#[test]
fn the_router_serves_under_a_prefix_of_another_router() {
    let mut sources = SourceMap::new();
    let id = sources.add("prog.mod", "MODULE m\nENDMODULE\n");
    let session = ViewSession::new(Scene {
        title: "prog.mod".into(),
        robot: Robot::default(),
        period: Duration::from_millis(4),
        files: vec![id],
        sources: Arc::new(sources),
        frames: Vec::new(),
    });
    session.enable_live();
    let app = axum::Router::new().nest(
        "/view",
        rapidvc::output::view::live::router(session.clone()),
    );
    let rt = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    rt.block_on(async move {
        let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
        let addr = listener.local_addr().unwrap();
        let server = tokio::spawn(async move { axum::serve(listener, app).await });
        let (status, page) = tokio::task::spawn_blocking(move || http_get(addr, "/view"))
            .await
            .unwrap();
        assert!(status.contains("200"), "{status}");
        assert!(page.contains("prog.mod"));
        let (mut ws, _) = tokio_tungstenite::connect_async(format!("ws://{addr}/view/ws"))
            .await
            .expect("websocket under /view");
        let first = tokio::time::timeout(Duration::from_secs(10), ws.next())
            .await
            .expect("snapshot in time")
            .expect("a message")
            .expect("no error");
        let m: Value = serde_json::from_str(first.to_text().unwrap()).unwrap();
        assert_eq!(m["type"], "snapshot");
        session.close_live();
        let end = tokio::time::timeout(Duration::from_secs(10), ws.next())
            .await
            .expect("end in time")
            .expect("a message")
            .expect("no error");
        let m: Value = serde_json::from_str(end.to_text().unwrap()).unwrap();
        assert_eq!(m["type"], "end");
        server.abort();
    });
}
