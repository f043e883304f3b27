//! The files and directories a RAPID program has open: every path goes through the one
//! sandbox rule of [`crate::mass_storage`], every open file is a [`Handle`] behind an `iodev`
//! number (and every open directory a listing behind a `dir` number).
//!
//! * A file opened with `\Write` is written to a temporary file beside it and renamed over
//!   the old one at `Close` (or when the program ends), so a full disk or a stopped program
//!   never leaves a user's file half rewritten.
//! * A write that fails at the end of a file (`\Append`, a full disk) cuts the file back to
//!   its length before the write, so no half line is left behind.
//! * Other instructions that handle `iodev`s (the raw-bytes ones, serial channels) share the
//!   handles through [`Files::handle`].

use std::collections::HashMap;
use std::fs::File;
use std::io::{self, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::mass_storage::{self, MassStorage, Root, SandboxError};

/// How a file is opened (`Open`'s switches).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpenMode {
    /// `\Read`: the file must exist; reading only.
    Read,
    /// `\Write`: a new file (an existing one is replaced at `Close`); writing only.
    Write,
    /// `\Append`, the default of a text file: created if missing, written at its end.
    Append,
    /// `\Bin` without `\Read`/`\Write`/`\Append`: reading and writing, starting at the end.
    ReadWrite,
}

/// An open file.
#[derive(Debug)]
pub struct Handle {
    file: File,
    /// With `\Write`: the temporary file being written and the file it replaces at `Close`.
    pending: Option<(PathBuf, PathBuf)>,
    rbuf: Vec<u8>,
    rpos: usize,
    can_read: bool,
    can_write: bool,
    /// Opened for appending: every write goes to the end, wherever the position is.
    append: bool,
    /// Opened with `\Bin`.
    pub binary: bool,
    /// The controller path, as the program named it (for messages).
    pub name: String,
}

/// Why a file operation failed.
#[derive(Debug)]
pub enum FsError {
    /// The path was refused by the sandbox.
    Sandbox(SandboxError),
    /// The host refused or failed.
    Io(io::Error),
}

impl std::fmt::Display for FsError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FsError::Sandbox(e) => write!(f, "{e}"),
            FsError::Io(e) => write!(f, "{e}"),
        }
    }
}

impl From<io::Error> for FsError {
    fn from(e: io::Error) -> Self {
        FsError::Io(e)
    }
}

impl From<SandboxError> for FsError {
    fn from(e: SandboxError) -> Self {
        FsError::Sandbox(e)
    }
}

const READ_CHUNK: usize = 8192;

impl Handle {
    /// Open `path` (already resolved inside the sandbox).
    pub fn open(path: &Path, name: &str, mode: OpenMode, binary: bool) -> io::Result<Handle> {
        let mut o = std::fs::OpenOptions::new();
        let mut pending = None;
        let (file, can_read, can_write) = match mode {
            OpenMode::Read => (o.read(true).open(path)?, true, false),
            OpenMode::Append => (o.append(true).create(true).open(path)?, false, true),
            OpenMode::ReadWrite => {
                let mut f = o.read(true).write(true).create(true).open(path)?;
                f.seek(SeekFrom::End(0))?;
                (f, true, true)
            }
            OpenMode::Write => {
                let tmp = temp_beside(path)?;
                let f = o.write(true).create_new(true).open(&tmp)?;
                pending = Some((tmp, path.to_path_buf()));
                (f, false, true)
            }
        };
        Ok(Handle {
            file,
            pending,
            rbuf: Vec::new(),
            rpos: 0,
            can_read,
            can_write,
            append: mode == OpenMode::Append,
            binary,
            name: name.to_string(),
        })
    }

    /// Can the file be read?
    pub fn readable(&self) -> bool {
        self.can_read
    }

    /// Can the file be written?
    pub fn writable(&self) -> bool {
        self.can_write
    }

    fn not_for(&self, what: &str) -> io::Error {
        io::Error::new(
            io::ErrorKind::PermissionDenied,
            format!("`{}` is not open for {what}", self.name),
        )
    }

    /// Refill the read buffer; false at the end of the file.
    fn fill(&mut self) -> io::Result<bool> {
        if self.rpos < self.rbuf.len() {
            return Ok(true);
        }
        if !self.can_read {
            return Err(self.not_for("reading"));
        }
        self.rbuf.resize(READ_CHUNK, 0);
        self.rpos = 0;
        let n = loop {
            match self.file.read(&mut self.rbuf) {
                Ok(n) => break n,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => {
                    self.rbuf.clear();
                    return Err(e);
                }
            }
        };
        self.rbuf.truncate(n);
        Ok(n > 0)
    }

    /// The next byte without taking it; `None` at the end of the file.
    pub fn peek_byte(&mut self) -> io::Result<Option<u8>> {
        if !self.fill()? {
            return Ok(None);
        }
        Ok(self.rbuf.get(self.rpos).copied())
    }

    /// The next byte; `None` at the end of the file.
    pub fn read_byte(&mut self) -> io::Result<Option<u8>> {
        let b = self.peek_byte()?;
        if b.is_some() {
            self.rpos += 1;
        }
        Ok(b)
    }

    /// Up to `n` bytes (fewer only at the end of the file).
    pub fn read_bytes(&mut self, n: usize) -> io::Result<Vec<u8>> {
        let mut out = Vec::with_capacity(n.min(READ_CHUNK));
        while out.len() < n && self.fill()? {
            let take = (n - out.len()).min(self.rbuf.len() - self.rpos);
            out.extend_from_slice(self.rbuf.get(self.rpos..self.rpos + take).unwrap_or(&[]));
            self.rpos += take;
        }
        Ok(out)
    }

    /// Write `data` at the current position. When the write fails at the end of the file
    /// (a full disk), the file is cut back to where it ended before.
    pub fn write_bytes(&mut self, data: &[u8]) -> io::Result<()> {
        if !self.can_write {
            return Err(self.not_for("writing"));
        }
        let unread = self.rbuf.len().saturating_sub(self.rpos);
        if unread > 0 {
            self.file.seek(SeekFrom::Current(-(unread as i64)))?;
        }
        self.rbuf.clear();
        self.rpos = 0;
        let len = self.file.metadata()?.len();
        let at = self.file.stream_position().unwrap_or(len);
        match self.file.write_all(data).and_then(|()| self.file.flush()) {
            Ok(()) => Ok(()),
            Err(e) => {
                if self.append || at >= len {
                    let _ = self.file.set_len(len);
                    let _ = self.file.seek(SeekFrom::Start(len));
                }
                Err(e)
            }
        }
    }

    /// Back to the start of the file (`Rewind`).
    pub fn rewind(&mut self) -> io::Result<()> {
        self.rbuf.clear();
        self.rpos = 0;
        self.file.seek(SeekFrom::Start(0)).map(|_| ())
    }

    /// Close: a `\Write` file replaces the file it was opened for.
    pub fn close(mut self) -> io::Result<()> {
        self.commit()
    }

    fn commit(&mut self) -> io::Result<()> {
        let Some((tmp, target)) = self.pending.take() else {
            return Ok(());
        };
        let done = self
            .file
            .sync_all()
            .and_then(|()| std::fs::rename(&tmp, &target));
        if done.is_err() {
            let _ = std::fs::remove_file(&tmp);
        }
        done
    }
}

impl Drop for Handle {
    fn drop(&mut self) {
        let _ = self.commit();
    }
}

/// A temporary file name beside `path` (same directory, so the rename is atomic).
fn temp_beside(path: &Path) -> io::Result<PathBuf> {
    let dir = path.parent().unwrap_or(Path::new("."));
    let base = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    for i in 0..100u32 {
        let t = dir.join(format!(".{base}.rapidvc-{}-{i}", std::process::id()));
        if std::fs::symlink_metadata(&t).is_err() {
            return Ok(t);
        }
    }
    Err(io::Error::new(
        io::ErrorKind::AlreadyExists,
        "no free temporary file name",
    ))
}

/// Copy `from` to `to` (which must not exist) through a temporary file, so a failed copy
/// leaves no partial `to`.
pub fn copy_new(from: &Path, to: &Path) -> io::Result<()> {
    let tmp = temp_beside(to)?;
    let done = (|| {
        let mut src = File::open(from)?;
        let mut dst = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)?;
        io::copy(&mut src, &mut dst)?;
        dst.sync_all()?;
        if std::fs::symlink_metadata(to).is_ok() {
            return Err(io::Error::new(
                io::ErrorKind::AlreadyExists,
                "the destination appeared during the copy",
            ));
        }
        std::fs::rename(&tmp, to)
    })();
    if done.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    done
}

/// An open directory listing (`OpenDir`).
#[derive(Debug)]
struct Listing {
    names: Vec<String>,
    next: usize,
}

/// The mass storage and the program's open files and directories.
#[derive(Debug)]
pub struct Files {
    storage: Arc<MassStorage>,
    roots: Option<Vec<Root>>,
    handles: HashMap<u32, Handle>,
    dirs: HashMap<u32, Listing>,
    next: u32,
}

impl Default for Files {
    fn default() -> Self {
        Files::new(Arc::new(MassStorage::new(None)))
    }
}

impl Files {
    /// Files on `storage`.
    pub fn new(storage: Arc<MassStorage>) -> Files {
        Files {
            storage,
            roots: None,
            handles: HashMap::new(),
            dirs: HashMap::new(),
            next: 0,
        }
    }

    /// The host path of controller path `path`; the second value is the line announcing the
    /// run's fresh directories, the first time they are made.
    pub fn resolve(&mut self, path: &str) -> Result<(PathBuf, Option<String>), FsError> {
        let mut note = None;
        if self.roots.is_none() {
            let (r, n) = self.storage.roots()?;
            self.roots = Some(r);
            note = n;
        }
        let roots = self.roots.as_deref().unwrap_or(&[]);
        Ok((mass_storage::resolve(roots, path)?, note))
    }

    fn take_id(&mut self) -> u32 {
        loop {
            self.next = self.next.wrapping_add(1).max(1);
            if !self.handles.contains_key(&self.next) && !self.dirs.contains_key(&self.next) {
                return self.next;
            }
        }
    }

    /// Keep an open file; its `iodev` number.
    pub fn insert(&mut self, h: Handle) -> u32 {
        let id = self.take_id();
        self.handles.insert(id, h);
        id
    }

    /// The open file behind `iodev` number `id`.
    pub fn handle(&mut self, id: u32) -> Option<&mut Handle> {
        self.handles.get_mut(&id)
    }

    /// Is `iodev` number `id` open?
    pub fn is_open(&self, id: u32) -> bool {
        self.handles.contains_key(&id)
    }

    /// Close `iodev` number `id` (nothing when it is not open).
    pub fn close(&mut self, id: u32) -> io::Result<()> {
        match self.handles.remove(&id) {
            Some(h) => h.close(),
            None => Ok(()),
        }
    }

    /// List directory `host` (names sorted, `.` and `..` first as the controller lists
    /// them); its `dir` number.
    pub fn open_dir(&mut self, host: &Path) -> io::Result<u32> {
        let mut names: Vec<String> = std::fs::read_dir(host)?
            .map(|e| e.map(|e| e.file_name().to_string_lossy().into_owned()))
            .collect::<io::Result<_>>()?;
        names.sort();
        names.splice(0..0, [".".to_string(), "..".to_string()]);
        let id = self.take_id();
        self.dirs.insert(id, Listing { names, next: 0 });
        Ok(id)
    }

    /// The next name of open directory `id`: `None` past the last, `Err` when `id` is not
    /// an open directory.
    pub(crate) fn read_dir(&mut self, id: u32) -> Result<Option<String>, ()> {
        let l = self.dirs.get_mut(&id).ok_or(())?;
        let name = l.names.get(l.next).cloned();
        if name.is_some() {
            l.next += 1;
        }
        Ok(name)
    }

    /// Close directory `id`.
    pub fn close_dir(&mut self, id: u32) {
        self.dirs.remove(&id);
    }

    /// Close everything (the end of a run): `\Write` files replace their targets.
    pub fn close_all(&mut self) {
        for (_, h) in self.handles.drain() {
            let _ = h.close();
        }
        self.dirs.clear();
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    fn tmp(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("rapidvc-files-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn write_mode_replaces_the_file_only_at_close() {
        let d = tmp("write");
        let p = d.join("a.txt");
        std::fs::write(&p, "old\n").unwrap();
        let mut h = Handle::open(&p, "HOME:/a.txt", OpenMode::Write, false).unwrap();
        h.write_bytes(b"new\n").unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "old\n");
        h.close().unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "new\n");
        assert_eq!(
            std::fs::read_dir(&d).unwrap().count(),
            1,
            "no temporary file left"
        );
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn read_write_binary_mixes_reads_and_writes() {
        let d = tmp("rw");
        let p = d.join("b.bin");
        std::fs::write(&p, [1u8, 2, 3]).unwrap();
        let mut h = Handle::open(&p, "b", OpenMode::ReadWrite, true).unwrap();
        assert_eq!(h.read_byte().unwrap(), None, "starts at the end");
        h.write_bytes(&[4]).unwrap();
        h.rewind().unwrap();
        assert_eq!(h.read_bytes(10).unwrap(), vec![1, 2, 3, 4]);
        let _ = std::fs::remove_dir_all(&d);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_full_disk_is_an_error_not_a_panic() {
        // /dev/full answers every write with ENOSPC.
        let mut h = Handle::open(Path::new("/dev/full"), "full", OpenMode::Append, false).unwrap();
        let e = h.write_bytes(b"x").unwrap_err();
        assert_eq!(e.raw_os_error(), Some(28), "{e}");
    }
}
