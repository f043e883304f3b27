//! The files of a run: output paths checked before anything runs (their directory exists
//! and is writable, no output is an input of the run or another output), and user files
//! replaced atomically (a temporary file in the same directory, renamed over the old one),
//! so a full disk or a crash never leaves a truncated file behind.

use std::io::Write;
use std::path::{Path, PathBuf};

/// `--home DIR`: an existing directory, kept as given (a relative one made absolute, so a
/// program sees the same directory wherever the run changes to).
pub fn home_dir(s: &str) -> Result<PathBuf, String> {
    let p = PathBuf::from(s);
    match std::fs::metadata(&p) {
        Ok(m) if m.is_dir() => std::path::absolute(&p).map_err(|e| format!("{s}: {e}")),
        Ok(_) => Err(format!("{s} is not a directory")),
        Err(e) => Err(format!("{s}: {e} (the directory must exist)")),
    }
}

/// A file of a run and what it is to the run (`--trace`, "the program file").
#[derive(Clone, Debug)]
pub struct Role<'a> {
    /// How messages name it: the option (`--trace`) or what it is (`program file`).
    pub what: String,
    /// The path as given.
    pub path: &'a Path,
}

impl<'a> Role<'a> {
    /// A file named `what` at `path`.
    pub fn new(what: impl Into<String>, path: &'a Path) -> Self {
        Role {
            what: what.into(),
            path,
        }
    }
}

/// Where a path leads: the canonical path (symbolic links resolved) and, for a file that
/// exists, its device and inode (a hard link is the same file too).
#[derive(Clone, Debug, PartialEq)]
struct Identity {
    canonical: PathBuf,
    inode: Option<(u64, u64)>,
}

impl Identity {
    fn same(&self, other: &Identity) -> bool {
        self.canonical == other.canonical
            || matches!((self.inode, other.inode), (Some(a), Some(b)) if a == b)
    }
}

#[cfg(unix)]
fn inode(meta: &std::fs::Metadata) -> Option<(u64, u64)> {
    use std::os::unix::fs::MetadataExt;
    Some((meta.dev(), meta.ino()))
}

#[cfg(not(unix))]
fn inode(_: &std::fs::Metadata) -> Option<(u64, u64)> {
    None
}

/// The identity of an existing input file.
fn input_identity(path: &Path) -> Option<Identity> {
    let canonical = std::fs::canonicalize(path).ok()?;
    let inode = std::fs::metadata(&canonical).ok().as_ref().and_then(inode);
    Some(Identity { canonical, inode })
}

/// The directory a file path is in (`.` for a bare file name).
fn dir_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// The identity of an output file (which may not exist yet); an error when it cannot be
/// written there: its directory is missing or not writable, or the path is a directory.
/// `None` for an existing special file (`/dev/null`, a FIFO, a terminal), which is written
/// as it is and compared with nothing.
fn output_identity(role: &Role<'_>) -> Result<Option<Identity>, String> {
    let path = role.path;
    let what = &role.what;
    if path.is_dir() {
        return Err(format!("{what} {}: is a directory", path.display()));
    }
    if std::fs::metadata(path).is_ok_and(|m| !m.is_file()) {
        return Ok(None);
    }
    let dir = dir_of(path);
    if !dir.is_dir() {
        return Err(format!(
            "{what} {}: the directory {} does not exist",
            path.display(),
            dir.display()
        ));
    }
    let Some(name) = path.file_name() else {
        return Err(format!("{what} {}: not a file name", path.display()));
    };
    // A file created and removed again: the directory takes new files.
    tempfile::Builder::new()
        .prefix(".rapidvc-probe")
        .tempfile_in(dir)
        .map_err(|e| {
            format!(
                "{what} {}: cannot write in {}: {e}",
                path.display(),
                dir.display()
            )
        })?;
    let canonical = match std::fs::canonicalize(path) {
        Ok(p) => p,
        Err(_) => std::fs::canonicalize(dir)
            .map_err(|e| format!("{what} {}: {e}", path.display()))?
            .join(name),
    };
    let inode = std::fs::metadata(&canonical).ok().as_ref().and_then(inode);
    Ok(Some(Identity { canonical, inode }))
}

/// Check the outputs of a run before it starts: each can be written, none is one of the
/// `inputs` (the program's files, its configuration, …) and no two are the same file. A
/// role may appear among both (`--pers` is read and written); it is not compared with
/// itself.
pub fn check_outputs(inputs: &[Role<'_>], outputs: &[Role<'_>]) -> Result<(), String> {
    let ins: Vec<(&Role<'_>, Identity)> = inputs
        .iter()
        .filter_map(|r| input_identity(r.path).map(|id| (r, id)))
        .collect();
    let mut outs: Vec<(&Role<'_>, Identity)> = Vec::with_capacity(outputs.len());
    for out in outputs {
        let Some(id) = output_identity(out)? else {
            continue;
        };
        if let Some((input, _)) = ins.iter().find(|(r, i)| r.what != out.what && i.same(&id)) {
            return Err(format!(
                "{} {} is an input of this run ({} {}): refusing to overwrite it",
                out.what,
                out.path.display(),
                input.what,
                input.path.display()
            ));
        }
        if let Some((other, _)) = outs.iter().find(|(_, i)| i.same(&id)) {
            return Err(format!(
                "{} {} and {} {} are the same file: give each output a file of its own",
                other.what,
                other.path.display(),
                out.what,
                out.path.display()
            ));
        }
        outs.push((out, id));
    }
    Ok(())
}

/// Replace `path` with what `write` writes, atomically: the text goes to a temporary file
/// in the same directory, which is flushed to disk and renamed over `path` only when every
/// write succeeded. On any error `path` is untouched and the temporary file removed. An
/// existing file keeps its permissions; a path that exists but is not a regular file (a
/// device, a FIFO) is refused, never replaced.
pub fn replace_with(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    // Through a symbolic link: replace the file it points to, not the link.
    let resolved = std::fs::canonicalize(path).ok();
    let path = resolved.as_deref().unwrap_or(path);
    if std::fs::metadata(path).is_ok_and(|m| !m.is_file()) {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "not a regular file",
        ));
    }
    let dir = dir_of(path);
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut tmp = tempfile::Builder::new()
        .prefix(&format!(".{name}."))
        .suffix(".tmp")
        .tempfile_in(dir)?;
    {
        let mut w = std::io::BufWriter::new(tmp.as_file_mut());
        write(&mut w)?;
        w.flush()?;
    }
    tmp.as_file().sync_all()?;
    if let Ok(meta) = std::fs::metadata(path) {
        tmp.as_file().set_permissions(meta.permissions())?;
    }
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// [`replace_with`] for a whole text.
pub fn replace(path: &Path, text: &str) -> std::io::Result<()> {
    replace_with(path, |w| w.write_all(text.as_bytes()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp_dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("rapidvc-files-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap_or_default();
        d
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .map(|r| {
                r.flatten()
                    .map(|e| e.file_name().to_string_lossy().into_owned())
                    .collect()
            })
            .unwrap_or_default();
        v.sort();
        v
    }

    /// A writer that fails half-way (a full disk): the old file stays whole, nothing is left
    /// behind.
    #[test]
    fn a_failed_write_leaves_the_old_file_whole() {
        let dir = temp_dir("fail");
        let path = dir.join("state.pers");
        std::fs::write(&path, "PERS num runs := 5;\n").unwrap_or_default();
        let r = replace_with(&path, |w| {
            w.write_all(b"PERS num runs := 6")?;
            Err(std::io::Error::new(
                std::io::ErrorKind::StorageFull,
                "No space left on device",
            ))
        });
        assert_eq!(
            r.map_err(|e| e.kind()),
            Err(std::io::ErrorKind::StorageFull)
        );
        assert_eq!(
            std::fs::read_to_string(&path).unwrap_or_default(),
            "PERS num runs := 5;\n"
        );
        assert_eq!(names(&dir), ["state.pers"]);
        assert!(replace(&path, "PERS num runs := 6;\n").is_ok());
        assert_eq!(
            std::fs::read_to_string(&path).unwrap_or_default(),
            "PERS num runs := 6;\n"
        );
        assert_eq!(names(&dir), ["state.pers"]);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn outputs_that_are_inputs_or_each_other_are_refused() {
        let dir = temp_dir("roles");
        let prog = dir.join("prog.mod");
        std::fs::write(&prog, "MODULE m\nENDMODULE\n").unwrap_or_default();
        let inputs = [Role::new("program file", &prog)];
        // The same file under another spelling.
        let dotted = dir.join(".").join("prog.mod");
        let e = check_outputs(&inputs, &[Role::new("--trace", &dotted)]).unwrap_err();
        assert!(e.contains("is an input of this run"), "{e}");
        let csv = dir.join("out.csv");
        let e = check_outputs(
            &inputs,
            &[Role::new("--trace", &csv), Role::new("--egm-log", &csv)],
        )
        .unwrap_err();
        assert!(e.contains("are the same file"), "{e}");
        let missing = dir.join("nowhere").join("out.csv");
        let e = check_outputs(&inputs, &[Role::new("--plot", &missing)]).unwrap_err();
        assert!(e.contains("does not exist"), "{e}");
        let e = check_outputs(&inputs, &[Role::new("--plot", &dir)]).unwrap_err();
        assert!(e.contains("is a directory"), "{e}");
        assert!(check_outputs(&inputs, &[Role::new("--trace", &csv)]).is_ok());
        // Special files are written as they are, also twice, but never replaced (a rename
        // over a device or FIFO would put a regular file in its place).
        let fifo = dir.join("fifo");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        assert!(made.is_ok_and(|s| s.success()));
        assert!(
            check_outputs(
                &inputs,
                &[Role::new("--trace", &fifo), Role::new("--egm-log", &fifo)]
            )
            .is_ok()
        );
        assert!(replace(&fifo, "x").is_err());
        assert!(std::fs::metadata(&fifo).is_ok_and(|m| !m.is_file()));
        let _ = std::fs::remove_file(&fifo);
        assert_eq!(names(&dir), ["prog.mod"]);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
