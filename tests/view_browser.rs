//! The view pages in a real browser: Chromium from Debian's packages (`.ci/run` installs it),
//! driven over the DevTools protocol by the headless_chrome crate. For the manual's three
//! examples and a ten-minute run the replay page must load without a console error, draw the
//! robot at slider positions with the trace's axis values (joint frames as the robot model
//! computes them, TCP as traced), highlight the traced source line and show the program's TP
//! output; screenshots go to `$CARGO_TARGET_TMPDIR/view/`.
//!
//! The tests need Chromium: they run when `RAPIDVC_CHROMIUM` names the browser at build time
//! (`.ci/run` installs Debian's `chromium` and sets it), and are reported as ignored
//! otherwise; `cargo test --test view_browser -- --include-ignored` runs them with the
//! first `chromium` on `PATH`. Without a browser they fail with a message saying so.

use rapidvc_testkit::rapidvc;
use rapidvc_testkit::view_page;

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use headless_chrome::protocol::cdp::Page::CaptureScreenshotFormatOption;
use headless_chrome::protocol::cdp::types::Event;
use headless_chrome::{Browser, LaunchOptions, Tab};
use rapidvc::output::view::kinematics::joint_origins;
use rapidvc::output::view::record::{JOINT_TOL_DEG, TCP_TOL_MM};
use rapidvc::robot::Robot;
use serde_json::Value;

const IGNORE: &str = "needs Chromium";

/// One browser at a time: three Chromiums and a real-time run on two cores time out.
static ONE_BROWSER: Mutex<()> = Mutex::new(());

fn one_browser() -> std::sync::MutexGuard<'static, ()> {
    ONE_BROWSER
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Where the pages and screenshots go.
fn out_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("view");
    std::fs::create_dir_all(&dir).expect("output directory");
    dir
}

/// The Chromium binary: `RAPIDVC_CHROMIUM` or the first of the usual names on `PATH`.
fn chromium() -> PathBuf {
    if let Some(p) = std::env::var_os("RAPIDVC_CHROMIUM") {
        return PathBuf::from(p);
    }
    let path = std::env::var_os("PATH").unwrap_or_default();
    for name in ["chromium", "chromium-browser", "google-chrome"] {
        for dir in std::env::split_paths(&path) {
            let p = dir.join(name);
            if p.is_file() {
                return p;
            }
        }
    }
    panic!(
        "{IGNORE}: no chromium on PATH (apt-get install chromium, or set RAPIDVC_CHROMIUM); this test cannot run without a browser"
    );
}

/// The flags the page is tested with: no network, no sandbox (CI runs as root), WebGL on
/// SwiftShader (no GPU here), a fresh profile.
fn launch(profile: &Path) -> Browser {
    let args: Vec<&OsStr> = [
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--use-angle=swiftshader",
        "--enable-unsafe-swiftshader",
        "--hide-scrollbars",
    ]
    .iter()
    .map(OsStr::new)
    .collect();
    let options = LaunchOptions::default_builder()
        .path(Some(chromium()))
        .headless(true)
        .sandbox(false)
        .window_size(Some((1600, 1000)))
        .user_data_dir(Some(profile.to_path_buf()))
        .args(args)
        .idle_browser_timeout(Duration::from_secs(120))
        .build()
        .expect("launch options");
    Browser::new(options).expect("start chromium")
}

/// A page open in the browser, with every console error and uncaught exception collected.
struct Page {
    _browser: Browser,
    tab: Arc<Tab>,
    problems: Arc<Mutex<Vec<String>>>,
    profile: PathBuf,
}

impl Drop for Page {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.profile);
    }
}

fn open(url: &str, name: &str) -> Page {
    let page = blank(name);
    page.go(url);
    page
}

/// A browser started with an empty tab that collects console errors and exceptions (started
/// before a live run, so the run does not end while a loaded machine starts Chromium).
fn blank(name: &str) -> Page {
    let profile = out_dir().join(format!("profile-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&profile);
    let browser = launch(&profile);
    let tab = browser.new_tab().expect("tab");
    let problems = Arc::new(Mutex::new(Vec::new()));
    let sink = Arc::clone(&problems);
    tab.add_event_listener(Arc::new(move |event: &Event| {
        let text = match event {
            Event::RuntimeConsoleAPICalled(e) => {
                let kind = format!("{:?}", e.params.Type).to_ascii_lowercase();
                (kind.contains("error") || kind.contains("assert")).then(|| {
                    let args: Vec<String> = e
                        .params
                        .args
                        .iter()
                        .map(|a| format!("{:?}", a.value))
                        .collect();
                    format!("console.{kind}: {}", args.join(" "))
                })
            }
            Event::RuntimeExceptionThrown(e) => Some(format!(
                "exception: {}",
                e.params
                    .exception_details
                    .exception
                    .as_ref()
                    .and_then(|x| x.description.clone())
                    .unwrap_or_else(|| e.params.exception_details.text.clone())
            )),
            Event::LogEntryAdded(e) => {
                let level = format!("{:?}", e.params.entry.level).to_ascii_lowercase();
                (level.contains("error")).then(|| format!("log: {}", e.params.entry.text))
            }
            _ => None,
        };
        if let Some(t) = text {
            sink.lock().unwrap().push(t);
        }
    }))
    .expect("listener");
    tab.enable_runtime().expect("runtime events");
    tab.enable_log().expect("log events");
    Page {
        _browser: browser,
        tab,
        problems,
        profile,
    }
}

impl Page {
    /// Navigates to `url` and waits until the view is ready.
    fn go(&self, url: &str) {
        let page = self;
        page.tab.navigate_to(url).expect("navigate");
        page.tab.wait_until_navigated().expect("loaded");
        let deadline = Instant::now() + Duration::from_secs(60);
        while page.eval("!!(window.rapidvc && window.rapidvc.ready)") != Value::Bool(true) {
            assert!(
                Instant::now() < deadline,
                "{url} did not become ready: {:?}",
                page.problems()
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    fn eval(&self, js: &str) -> Value {
        self.tab
            .evaluate(js, true)
            .unwrap_or_else(|e| panic!("evaluate {js}: {e}"))
            .value
            .unwrap_or(Value::Null)
    }

    /// Move the time slider to `ms` as a user would and return what the next frame drew.
    fn slide_to(&self, ms: i64) -> Value {
        let js = format!(
            "(() => {{ const s = document.getElementById('slider'); s.value = '{ms}';
               s.dispatchEvent(new Event('input'));
               return new Promise(r => requestAnimationFrame(() => requestAnimationFrame(
                 () => r(JSON.stringify({{ drawn: rapidvc.drawn,
                   line: (document.querySelector('.ln.cur') || {{dataset: {{}}}}).dataset.n || null,
                   tp: [...document.querySelectorAll('#tp > div:not([hidden]) .tp')].map(e => e.textContent) }}))))); }})()"
        );
        let text = self.eval(&js);
        serde_json::from_str(text.as_str().expect("JSON text")).expect("drawn state")
    }

    fn screenshot(&self, path: &Path) {
        let png = self
            .tab
            .capture_screenshot(CaptureScreenshotFormatOption::Png, None, None, true)
            .expect("screenshot");
        std::fs::write(path, png).expect("write screenshot");
    }

    fn problems(&self) -> Vec<String> {
        self.problems.lock().unwrap().clone()
    }
}

fn nums(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

/// Run `rapidvc run FILE --view … --trace …`; (page, trace, stdout).
fn replay(program: &Path, name: &str) -> (PathBuf, PathBuf, String) {
    let dir = out_dir();
    let page = dir.join(format!("{name}.html"));
    let trace = dir.join(format!("{name}.csv"));
    let out = rapidvc!()
        .arg("run")
        .arg(program)
        .arg("--view")
        .arg(&page)
        .arg("--trace")
        .arg(&trace)
        .output()
        .expect("run rapidvc");
    assert!(
        out.status.success(),
        "{name}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    (
        page,
        trace,
        String::from_utf8_lossy(&out.stdout).into_owned(),
    )
}

/// Open `page`, check it at slider positions against `trace`, save screenshots; returns the
/// page's size (bytes) and its load time (ms, navigation start to the first frame drawn).
fn check_page(name: &str, page: &Path, trace: &Path, tp_lines: &[&str]) -> (u64, f64) {
    let size = std::fs::metadata(page).expect("page").len();
    let url = format!("file://{}", page.display());
    let p = open(&url, name);
    let load_ms = p.eval("rapidvc.loadMs").as_f64().expect("load time");
    assert!(
        p.eval("rapidvc.frames").as_u64().unwrap_or(0) > 0,
        "{name}: WebGL drew nothing"
    );
    let rows = view_page::read_trace(trace);
    let robot = Robot::default();
    let period_us = 4000;
    let end = rows.last().expect("trace rows").t;
    let mut checked = 0;
    for frac in [0.0, 0.13, 0.29, 0.5, 0.64, 0.83, 1.0] {
        // A slider position on a motion cycle, so the trace has the exact values.
        let t = ((end as f64 * frac) / period_us as f64).round() as i64 * period_us;
        let row = rows.iter().find(|r| r.t == t).expect("trace row at t");
        let state = p.slide_to(t / 1000);
        let drawn = &state["drawn"];
        assert_eq!(drawn["t"].as_f64(), Some(t as f64), "{name}: time");
        let joints = nums(&drawn["joints"]);
        for (a, (d, e)) in joints.iter().zip(row.joints).enumerate() {
            assert!(
                (d - e).abs() <= JOINT_TOL_DEG + 6e-4,
                "{name} at {t} µs: J{} drawn {d}, traced {e}",
                a + 1
            );
        }
        let tcp = nums(&drawn["tcp"]);
        for (d, e) in tcp.iter().zip(row.tcp) {
            assert!(
                (d - e).abs() <= TCP_TOL_MM + 6e-3,
                "{name} at {t} µs: TCP drawn {tcp:?}, traced {:?}",
                row.tcp
            );
        }
        // The joint frames the page drew are the robot model's for the drawn axes, and
        // within the tolerance of the traced axes' (the flange included).
        let drawn_q: [f64; 6] = std::array::from_fn(|a| joints[a]);
        let model = joint_origins(&robot, &drawn_q);
        let traced = joint_origins(&robot, &row.joints);
        for (k, o) in drawn["origins"]
            .as_array()
            .expect("origins")
            .iter()
            .enumerate()
        {
            let o = nums(o);
            for a in 0..3 {
                assert!(
                    (o[a] - model[k][a]).abs() < 1e-6,
                    "{name}: joint frame {k} drawn at {o:?}, model {:?}",
                    model[k]
                );
                assert!(
                    (o[a] - traced[k][a]).abs() < 0.5,
                    "{name}: joint frame {k} drawn at {o:?}, traced joints give {:?}",
                    traced[k]
                );
            }
        }
        // The executing line is highlighted.
        let line = state["line"].as_str().and_then(|s| s.parse::<u32>().ok());
        assert_eq!(line, row.line, "{name} at {t} µs: highlighted line");
        if frac == 1.0 {
            let shown: Vec<String> = state["tp"]
                .as_array()
                .expect("tp")
                .iter()
                .map(|v| v.as_str().unwrap_or("").to_string())
                .collect();
            assert_eq!(shown, tp_lines, "{name}: TP output at the end");
        }
        if [0.29, 0.64, 1.0].contains(&frac) {
            p.screenshot(&out_dir().join(format!("{name}_{:03}s.png", t / 1_000_000)));
        }
        checked += 1;
    }
    assert_eq!(checked, 7);
    assert!(p.problems().is_empty(), "{name}: {:?}", p.problems());
    eprintln!(
        "{name}: {size} bytes, loaded in {load_ms:.0} ms; screenshots in {}",
        out_dir().display()
    );
    (size, load_ms)
}

#[test]
#[cfg_attr(
    not(rapidvc_chromium),
    ignore = "needs Chromium: build with RAPIDVC_CHROMIUM=/usr/bin/chromium (.ci/run installs Debian's chromium and sets it) or run with --include-ignored"
)]
fn manual_examples_replay_in_chromium() {
    let _one = one_browser();
    for name in [
        "position_guidance_signals",
        "path_correction",
        "position_guidance_udpuc",
    ] {
        let program = root().join(format!("programs/manual/{name}.mod"));
        let (page, trace, stdout) = replay(&program, name);
        let tp: Vec<&str> = stdout.lines().collect();
        check_page(name, &page, &trace, &tp);
    }
}

#[test]
#[cfg_attr(
    not(rapidvc_chromium),
    ignore = "needs Chromium: build with RAPIDVC_CHROMIUM=/usr/bin/chromium (.ci/run installs Debian's chromium and sets it) or run with --include-ignored"
)]
fn ten_minute_run_replays_in_chromium() {
    let _one = one_browser();
    let (page, trace, stdout) = replay(&root().join("tests/view/long_run.mod"), "long_run");
    let rows = view_page::read_trace(&trace);
    assert!(
        rows.last().unwrap().t >= 600_000_000,
        "the run lasts ten minutes"
    );
    let tp: Vec<&str> = stdout.lines().collect();
    let (size, _) = check_page("long_run", &page, &trace, &tp);
    assert!(size < 1_000_000, "a ten-minute run's page is {size} bytes");
}

#[test]
#[cfg_attr(
    not(rapidvc_chromium),
    ignore = "needs Chromium: build with RAPIDVC_CHROMIUM=/usr/bin/chromium (.ci/run installs Debian's chromium and sets it) or run with --include-ignored"
)]
fn live_page_follows_a_real_time_run_in_chromium() {
    let _one = one_browser();
    let p = blank("live");
    let live = view_page::LiveRun::start(rapidvc!(), &root(), "tests/view/live_run.mod");
    p.go(&live.url);
    // Rows arrive while the program runs; the page ends on the run's last state.
    let deadline = Instant::now() + Duration::from_secs(30);
    while p.eval("document.getElementById('status').textContent") != "live · run ended" {
        assert!(Instant::now() < deadline, "the live page never saw the end");
        std::thread::sleep(Duration::from_millis(100));
    }
    let rows = p.eval("rapidvc.rows()").as_u64().unwrap_or(0);
    assert!(rows >= 100, "{rows} rows streamed");
    let drawn = p.eval("JSON.stringify(rapidvc.seek(rapidvc.duration()))");
    let drawn: Value = serde_json::from_str(drawn.as_str().unwrap()).unwrap();
    let j = nums(&drawn["joints"]);
    let home = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];
    for (d, e) in j.iter().zip(home) {
        assert!((d - e).abs() < 0.02, "ends at {j:?}");
    }
    p.screenshot(&out_dir().join("live_end.png"));
    assert!(p.problems().is_empty(), "{:?}", p.problems());
    let (status, rest) = live.finish();
    assert!(status.success(), "{rest}");
    eprintln!("with the live page connected: {}", rest.trim());
}
