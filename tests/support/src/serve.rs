//! A real controller for the RWS tests: `rapidvc serve` on a free loopback port, with its
//! HOME in a fresh directory; the address is read from the first line it prints. Stopped
//! with SIGINT (a clean shutdown) by [`Serve::stop`], killed when dropped.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use crate::procs::{Ended, Proc, root};

/// A running `rapidvc serve`.
pub struct Serve {
    proc: Option<Proc>,
    /// Where RWS listens.
    pub addr: SocketAddr,
    /// Its HOME: directory.
    pub home: PathBuf,
}

impl Serve {
    /// Start `rapidvc` (the test crate's binary, `cmd`) as `serve PROGRAM --rws 127.0.0.1:0
    /// --home DIR EXTRA…`; `program` is relative to the repository root.
    pub fn start(mut cmd: Command, tag: &str, program: &str, extra: &[&str]) -> Serve {
        let home = std::env::temp_dir().join(format!("rapidvc-serve-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&home);
        std::fs::create_dir_all(&home).unwrap();
        cmd.arg("serve")
            .arg(root().join(program))
            .args(["--rws", "127.0.0.1:0", "--home"])
            .arg(&home)
            .args(extra);
        let mut proc = Proc::spawn(cmd);
        let first = proc.next_line(Duration::from_secs(30));
        let Some(line) = first else {
            let ended = proc.wait(Duration::from_secs(1));
            panic!("rapidvc serve printed no address: {ended:?}");
        };
        let url = line
            .split("http://")
            .nth(1)
            .and_then(|r| r.split_whitespace().next())
            .unwrap_or_else(|| panic!("no address in {line:?}"));
        Serve {
            proc: Some(proc),
            addr: url.parse().unwrap(),
            home,
        }
    }

    /// `http://127.0.0.1:PORT`.
    pub fn url(&self) -> String {
        format!("http://{}", self.addr)
    }

    /// Its HOME: directory.
    pub fn home(&self) -> &Path {
        &self.home
    }

    /// Stop it as Ctrl-C does and wait (at most `timeout`) for the end.
    pub fn stop(mut self, timeout: Duration) -> Ended {
        let proc = self.proc.take().unwrap();
        let _ = Command::new("kill")
            .args(["-INT", &proc.id().to_string()])
            .status();
        proc.wait(timeout)
    }
}

impl Drop for Serve {
    fn drop(&mut self) {
        drop(self.proc.take());
        let _ = std::fs::remove_dir_all(&self.home);
    }
}
