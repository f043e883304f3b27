//! The view options of `rapidvc run`: `--view FILE.html` (a replay page written when the run
//! ends) and `--view-live [ADDR]` (a page served while the program runs, with the robot's
//! state streamed over a WebSocket). See [`crate::output::view`].

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;
use std::str::FromStr;
use std::sync::Arc;
use std::time::Duration;

use crate::controller::TickSink;
use crate::interp::Interp;
use crate::output::FeedRx;
use crate::output::view::live::LiveServer;
use crate::output::view::{Scene, ViewSession};
use crate::robot::Robot;
use crate::source::SourceMap;

/// Where the live view listens when `--view-live` names no address: loopback, a free port.
pub const DEFAULT_LIVE_ADDR: SocketAddr = SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), 0);

/// View options of `rapidvc run`.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ViewArgs {
    /// Write a self-contained HTML page that replays the run in 3D (robot, TCP path, source,
    /// TP output, events, EGM and path correction); it needs no network.
    #[arg(long, value_name = "FILE.html")]
    pub view: Option<PathBuf>,
    /// Serve the view while the program runs (in real time) and stream the robot's state to
    /// it: `PORT`, `HOST:PORT` or nothing (127.0.0.1 on a free port); the URL is printed.
    #[arg(long, value_name = "ADDR", num_args = 0..=1, default_missing_value = "127.0.0.1:0")]
    pub view_live: Option<LiveAddr>,
}

/// `--view-live` address: `PORT`, `IP:PORT`, `localhost:PORT` or `[IPv6]:PORT`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LiveAddr(pub SocketAddr);

impl FromStr for LiveAddr {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let s = s.trim();
        if let Ok(port) = s.parse::<u16>() {
            return Ok(LiveAddr(SocketAddr::new(DEFAULT_LIVE_ADDR.ip(), port)));
        }
        if let Some(port) = s.strip_prefix("localhost:")
            && let Ok(port) = port.parse::<u16>()
        {
            return Ok(LiveAddr(SocketAddr::new(DEFAULT_LIVE_ADDR.ip(), port)));
        }
        s.parse::<SocketAddr>().map(LiveAddr).map_err(|_| {
            format!(
                "`{s}` is not an address to serve the live view on: give PORT or HOST:PORT (e.g. 127.0.0.1:8080)"
            )
        })
    }
}

/// The view of one run, between start and finish.
pub struct ViewRun {
    session: ViewSession,
    page: Option<PathBuf>,
    server: Option<LiveServer>,
}

impl ViewArgs {
    /// True when a view was asked for.
    pub fn wanted(&self) -> bool {
        self.view.is_some() || self.view_live.is_some()
    }

    /// The live view runs the program in real time.
    pub fn needs_realtime(&self) -> bool {
        self.view_live.is_some()
    }

    /// Start the view of a run of `files` (shown in the page) on `robot`; the live server
    /// starts listening now and its URL is printed.
    pub fn start(
        &self,
        title: String,
        robot: &Robot,
        period_ms: f64,
        sources: &Arc<SourceMap>,
        files: Vec<crate::source::SourceId>,
    ) -> Result<Option<ViewRun>, String> {
        if !self.wanted() {
            return Ok(None);
        }
        if let Some(path) = &self.view {
            // Fail before the run, not after it, when the page has nowhere to go.
            let dir = path
                .parent()
                .filter(|d| !d.as_os_str().is_empty())
                .unwrap_or(std::path::Path::new("."));
            if !dir.is_dir() {
                return Err(format!(
                    "cannot create the view {}: {} is not a directory",
                    path.display(),
                    dir.display()
                ));
            }
            if path.is_dir() {
                return Err(format!(
                    "cannot create the view {}: it is a directory",
                    path.display()
                ));
            }
        }
        let period = Duration::try_from_secs_f64(period_ms / 1e3).unwrap_or(Duration::ZERO);
        let session = ViewSession::new(Scene {
            title,
            robot: robot.clone(),
            period,
            files,
            sources: Arc::clone(sources),
            frames: Vec::new(),
        });
        let server = match self.view_live {
            Some(LiveAddr(addr)) => {
                let server = LiveServer::start(addr, session.clone())?;
                let local = server.local_addr();
                if !local.ip().is_loopback() {
                    eprintln!(
                        "warning: the live view has no authentication; anyone who reaches {local} can watch"
                    );
                }
                eprintln!("live view: http://{local}/ (streams while the program runs)");
                Some(server)
            }
            None => None,
        };
        Ok(Some(ViewRun {
            session,
            page: self.view.clone(),
            server,
        }))
    }
}

impl ViewRun {
    /// The controller's sink for this view (`feed`: EGM and path-correction samples).
    pub fn sink(&self, feed: Option<FeedRx>) -> Box<dyn TickSink> {
        Box::new(self.session.sink(feed))
    }

    /// The session, for the output tee.
    pub fn session(&self) -> ViewSession {
        self.session.clone()
    }

    /// After the program's data is initialised: the work objects to draw.
    pub fn after_init(&self, it: &Interp) {
        self.session.set_frames_from(&it.persistents());
    }

    /// The run is over: note how it ended, write the page, stop the live server.
    pub fn finish(self, ended: &str) -> Result<(), String> {
        self.session.end(ended);
        if let Some(server) = self.server {
            let viewers = server.viewers_total();
            server.stop();
            eprintln!(
                "live view: {viewers} viewer{} connected during the run",
                if viewers == 1 { "" } else { "s" }
            );
        }
        if let Some(path) = &self.page {
            let size = self.session.write_page(path)?;
            eprintln!("view: {} ({:.1} kB)", path.display(), size as f64 / 1024.0);
        }
        Ok(())
    }
}

/// The page's last log line: how the program ended (`code` and whether the robot finished
/// its moves, as `rapidvc run` decided).
pub fn ended_text(code: &std::process::ExitCode, drained: bool) -> &'static str {
    if *code == std::process::ExitCode::SUCCESS {
        if drained {
            "program ended"
        } else {
            "program stopped"
        }
    } else {
        "program stopped on an error (see the terminal)"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn live_addresses() {
        let a = |s: &str| s.parse::<LiveAddr>().map(|a| a.0.to_string());
        assert_eq!(a("8080").unwrap(), "127.0.0.1:8080");
        assert_eq!(a("localhost:9000").unwrap(), "127.0.0.1:9000");
        assert_eq!(a("0.0.0.0:80").unwrap(), "0.0.0.0:80");
        assert_eq!(a("[::1]:81").unwrap(), "[::1]:81");
        assert_eq!(a("127.0.0.1:0").unwrap(), "127.0.0.1:0");
        let e = a("prog.mod").unwrap_err();
        assert!(e.contains("HOST:PORT"), "{e}");
        assert!(a("70000").is_err());
    }
}
