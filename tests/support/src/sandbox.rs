//! A mass-storage attack from RAPID: a fresh `home/` (the program's `--home`), an `outside/`
//! directory beside it with a file linked from HOME (`home/<link>` → `outside/<file>`,
//! `home/out` → `outside/`), and a program in `prog/` that tries to reach outside. The tests
//! compare `outside/` before and after ([`Attack::snapshot_outside`]).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The directories of one attack, removed again when dropped.
pub struct Attack {
    pub root: PathBuf,
    pub home: PathBuf,
    pub outside: PathBuf,
}

impl Attack {
    /// Fresh `home/`, `outside/` and `prog/` under a temporary directory named after `tag`;
    /// `outside/<file>` holds `content`, linked from `home/<link>`, and `home/out` links to
    /// `outside/`.
    #[cfg(unix)]
    pub fn new(tag: &str, file: &str, content: &str, link: &str) -> Attack {
        let root =
            std::env::temp_dir().join(format!("rapidvc-sandbox-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        let (home, outside) = (root.join("home"), root.join("outside"));
        for d in [&home, &outside, &root.join("prog")] {
            std::fs::create_dir_all(d).expect("sandbox directories");
        }
        std::fs::write(outside.join(file), content).expect("the file outside");
        std::os::unix::fs::symlink(outside.join(file), home.join(link)).expect("link to file");
        std::os::unix::fs::symlink(&outside, home.join("out")).expect("link to outside");
        Attack {
            root,
            home,
            outside,
        }
    }

    /// Every file and directory under `outside/` with its content.
    pub fn snapshot_outside(&self) -> BTreeMap<PathBuf, Vec<u8>> {
        snapshot(&self.outside)
    }

    /// Runs `program` (written to `prog/attack.mod`) with `--home home/`; it must succeed and
    /// print `done` last. Returns stdout and stderr.
    pub fn run(&self, mut rapidvc: Command, program: &str) -> (String, String) {
        let prog = self.root.join("prog").join("attack.mod");
        std::fs::write(&prog, program).expect("write the program");
        let out = rapidvc
            .arg("run")
            .arg("--home")
            .arg(&self.home)
            .arg(&prog)
            .env("NO_COLOR", "1")
            .output()
            .expect("run rapidvc");
        let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(out.status.success(), "{stdout}\n{stderr}");
        assert!(stdout.ends_with("done\n"), "{stdout}\n{stderr}");
        (stdout, stderr)
    }
}

impl Drop for Attack {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.root);
    }
}

/// Every file and directory under `dir` with its content (links not followed).
pub fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).expect("read dir").flatten() {
            let p = e.path();
            let m = std::fs::symlink_metadata(&p).expect("metadata");
            if m.is_dir() {
                stack.push(p.clone());
                out.insert(p, b"<dir>".to_vec());
            } else {
                out.insert(p.clone(), std::fs::read(&p).unwrap_or_default());
            }
        }
    }
    out
}
