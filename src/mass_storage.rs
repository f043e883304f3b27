//! The controller's mass storage as RAPID and services see it: named roots (`HOME`, `TEMP`,
//! `RAMDISK`, …) that map to host directories, and the one sandbox rule that turns a
//! controller path into a host path.
//!
//! Both RAPID's file instructions (`Open "HOME:" \File:="log.txt"`) and the file service of
//! Robot Web Services (`fileservice/$HOME/log.txt`) go through [`resolve`], so a path that
//! one of them refuses the other refuses too:
//!
//! * the first component names a root (`HOME`, `$HOME`, `HOME:`, any case); anything else is
//!   refused, so an absolute host path (`/etc/passwd`, `C:\…`) never reaches the host;
//! * the rest is split at `/` and `\`; empty and `.` components are skipped, `..` is refused
//!   (not resolved), and so is a component with a NUL or a drive colon;
//! * every component that exists on the host must not be a symbolic link, so a link placed
//!   inside a root cannot lead out of it.
//!
//! What remains is `root/…` on the host, which need not exist yet (a file about to be
//! created). The check and the later open are two steps; the roots belong to rapidvc's own
//! directories, so nothing else is expected to swap components in between.

use std::path::{Path, PathBuf};

/// Why a controller path was refused.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SandboxError {
    /// The path does not start with a known root.
    #[error("`{path}` does not start with a mass storage root ({known})")]
    UnknownRoot {
        /// The path as given.
        path: String,
        /// The roots there are, comma-separated.
        known: String,
    },
    /// A component tries to leave its root or is not a plain name.
    #[error("`{path}`: the component `{component}` is not allowed (no `..`, drive letters or NUL)")]
    BadComponent {
        /// The path as given.
        path: String,
        /// The component refused.
        component: String,
    },
    /// A component on the host is a symbolic link.
    #[error("`{path}`: `{component}` is a symbolic link, which file access does not follow")]
    Symlink {
        /// The path as given.
        path: String,
        /// The component that is a link.
        component: String,
    },
}

/// One named root: its name without `$` or `:` (`HOME`) and its host directory.
pub type Root = (String, PathBuf);

/// The root named by `first` (`HOME`, `$HOME`, `HOME:`, any case), if any.
fn root_named<'a>(roots: &'a [Root], first: &str) -> Option<&'a Root> {
    let name = first.trim_start_matches('$').trim_end_matches(':');
    roots.iter().find(|(n, _)| n.eq_ignore_ascii_case(name))
}

/// Split `path` into the root component and the rest. `HOME:dir/f` and `HOME:/dir/f` (RAPID's
/// device syntax) split after the colon; `$HOME/dir/f` and `HOME/dir/f` at the first separator.
fn split_root(path: &str) -> (&str, &str) {
    let trimmed = path.trim_start_matches(['/', '\\']);
    let sep = trimmed.find(['/', '\\']).unwrap_or(trimmed.len());
    match trimmed.find(':') {
        Some(colon) if colon < sep => trimmed.split_at(colon + 1),
        _ => trimmed.split_at(sep),
    }
}

/// The host path of controller path `path` under `roots`, or why it is refused (see the module
/// documentation). `$HOME` alone is the root directory itself.
pub fn resolve(roots: &[Root], path: &str) -> Result<PathBuf, SandboxError> {
    let (first, rest) = split_root(path);
    let Some((_, dir)) = root_named(roots, first) else {
        return Err(SandboxError::UnknownRoot {
            path: path.to_string(),
            known: roots
                .iter()
                .map(|(n, _)| n.as_str())
                .collect::<Vec<_>>()
                .join(", "),
        });
    };
    let mut host = dir.clone();
    for component in rest.split(['/', '\\']) {
        if component.is_empty() || component == "." {
            continue;
        }
        if component == ".." || component.contains('\0') || component.contains(':') {
            return Err(SandboxError::BadComponent {
                path: path.to_string(),
                component: component.to_string(),
            });
        }
        host.push(component);
        if is_symlink(&host) {
            return Err(SandboxError::Symlink {
                path: path.to_string(),
                component: component.to_string(),
            });
        }
    }
    Ok(host)
}

/// The mass storage of one run: `HOME` (the user's `--home DIR`, or a fresh directory),
/// `TEMP` and `RAMDISK` (always fresh). The fresh directories are made under the system's
/// temporary directory the first time a program or a service touches the file system, so a
/// run that never does leaves nothing behind; [`MassStorage::roots`] says when it made them,
/// so that the front end can print where they are.
#[derive(Debug)]
pub struct MassStorage {
    home: Option<PathBuf>,
    made: std::sync::Mutex<Option<Vec<Root>>>,
}

/// The names of the roots, in the order [`MassStorage::roots`] lists them.
pub const ROOT_NAMES: [&str; 3] = ["HOME", "TEMP", "RAMDISK"];

impl MassStorage {
    /// Storage whose `HOME` is `home` (an existing directory), or a fresh one when `None`.
    pub fn new(home: Option<PathBuf>) -> Self {
        MassStorage {
            home,
            made: std::sync::Mutex::new(None),
        }
    }

    /// The roots, if a program or service has used them yet.
    pub fn made_roots(&self) -> Option<Vec<Root>> {
        self.made.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }

    /// The roots, making the fresh directories on first use. The second value is a line
    /// for the user the first time they were made ("HOME: is /tmp/…").
    pub fn roots(&self) -> std::io::Result<(Vec<Root>, Option<String>)> {
        let mut made = self.made.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(r) = made.as_ref() {
            return Ok((r.clone(), None));
        }
        let base = fresh_dir()?;
        let mut roots = Vec::with_capacity(ROOT_NAMES.len());
        for name in ROOT_NAMES {
            let dir = match (&self.home, name) {
                (Some(h), "HOME") => h.clone(),
                _ => {
                    let d = base.join(name.to_ascii_lowercase());
                    std::fs::create_dir(&d)?;
                    d
                }
            };
            roots.push((name.to_string(), dir));
        }
        let shown = roots
            .iter()
            .map(|(n, d)| format!("{n}: is {}", d.display()))
            .collect::<Vec<_>>()
            .join(", ");
        let note = format!("mass storage: {shown}");
        *made = Some(roots.clone());
        Ok((roots, Some(note)))
    }
}

/// A new directory `rapidvc-<pid>-<n>` under the system's temporary directory.
fn fresh_dir() -> std::io::Result<PathBuf> {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let tmp = std::env::temp_dir();
    let stamp = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.subsec_nanos())
        .unwrap_or(0);
    let mut attempt = 0;
    loop {
        let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let d = tmp.join(format!("rapidvc-{}-{stamp:08x}-{n}", std::process::id()));
        match std::fs::create_dir(&d) {
            Ok(()) => return Ok(d),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && attempt < 100 => {
                attempt += 1;
            }
            Err(e) => return Err(e),
        }
    }
}

fn is_symlink(p: &Path) -> bool {
    std::fs::symlink_metadata(p).is_ok_and(|m| m.file_type().is_symlink())
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    fn roots(dir: &Path) -> Vec<Root> {
        vec![
            ("HOME".into(), dir.join("home")),
            ("RAMDISK".into(), dir.join("ramdisk")),
        ]
    }

    fn tmp(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("rapidvc-ms-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(d.join("home/sub")).unwrap();
        std::fs::create_dir_all(d.join("ramdisk")).unwrap();
        d
    }

    #[test]
    fn every_spelling_of_a_root_resolves_inside_it() {
        let d = tmp("spell");
        let r = roots(&d);
        for p in [
            "$HOME/sub/a.txt",
            "HOME:sub/a.txt",
            "HOME:/sub/a.txt",
            "home/sub/a.txt",
            "/$home\\sub\\a.txt",
            "$HOME/./sub//a.txt",
        ] {
            assert_eq!(resolve(&r, p), Ok(d.join("home/sub/a.txt")), "{p}");
        }
        assert_eq!(resolve(&r, "$RAMDISK"), Ok(d.join("ramdisk")));
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn escapes_and_host_paths_are_refused() {
        let d = tmp("escape");
        let r = roots(&d);
        for p in ["/etc/passwd", "C:/Windows", "$TEMP/x", "", "$HOMEX/a"] {
            assert!(
                matches!(resolve(&r, p), Err(SandboxError::UnknownRoot { .. })),
                "{p}"
            );
        }
        for p in ["$HOME/../x", "$HOME/sub/../../x", "HOME:..\\x", "$HOME/c:x"] {
            assert!(
                matches!(resolve(&r, p), Err(SandboxError::BadComponent { .. })),
                "{p}"
            );
        }
        let _ = std::fs::remove_dir_all(&d);
    }

    #[cfg(unix)]
    #[test]
    fn a_symbolic_link_inside_a_root_is_not_followed() {
        let d = tmp("link");
        let r = roots(&d);
        std::os::unix::fs::symlink("/etc", d.join("home/out")).unwrap();
        let err = resolve(&r, "$HOME/out/passwd").unwrap_err();
        assert!(matches!(err, SandboxError::Symlink { ref component, .. } if component == "out"));
        assert!(err.to_string().contains("symbolic link"));
        let _ = std::fs::remove_dir_all(&d);
    }
}
