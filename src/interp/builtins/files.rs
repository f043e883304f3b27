//! The controller's file system: `Open`/`Close` with text and binary reading and writing,
//! `Rewind`, `ClearIOBuff`, directories (`OpenDir`, `ReadDir`, `CloseDir`, `MakeDir`,
//! `RemoveDir`), files (`RemoveFile`, `RenameFile`, `CopyFile`, `IsFile`, `FileSize`,
//! `FileTime`) and `FSSize`. Paths are controller paths (`HOME:/log.txt`, `$TEMP/x`,
//! `diskram`), turned into host paths by the one sandbox rule of [`crate::mass_storage`]
//! (see [`crate::interp::files`] for how files are kept).
//!
//! Errors as ABB raises them: `ERR_FILEOPEN` when `Open` fails, `ERR_FILEEXIST` when
//! `RenameFile`/`CopyFile` would overwrite, `ERR_RCVDATA` when `ReadNum` reads no number,
//! `ERR_RANYBIN_EOF`/`ERR_RANYBIN_CHK` from `ReadAnyBin`, `ERR_FILEACC` for every other
//! access error (a path the sandbox refuses, a missing file, a full disk). At the end of a
//! file `ReadStr`/`ReadStrBin` give `"EOF"`, `ReadNum` `EOF_NUM` (9.998E36) and `ReadBin`
//! `EOF_BIN` (-1).

use std::path::PathBuf;

use super::{Ctx, Registry};
use crate::functions::format as f;
use crate::interp::errnum;
use crate::interp::error::{Exec, Unwind};
use crate::interp::files::{FsError, Handle, OpenMode};
use crate::interp::host::Output;
use crate::interp::value::{MAX_STRING, Value};

/// What `ReadNum` gives at the end of the file (`EOF_NUM`).
pub const EOF_NUM: f32 = 9.998e36;
/// What `ReadBin` gives at the end of the file (`EOF_BIN`).
pub const EOF_BIN: f32 = -1.0;
/// What `ReadStr` and `ReadStrBin` give at the end of the file.
pub const EOF_STR: &str = "EOF";

/// First byte of a `WriteAnyBin` record.
const ANYBIN_MAGIC: u8 = 0xA5;

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add(
        r"PROC Open(string Object, \string File, VAR iodev IODevice, \switch Read | switch Write | switch Append, \switch Bin)",
        open,
    );
    r.add("PROC Close(VAR iodev IODevice)", |cx| {
        let id = dev_id(cx, 0)?;
        let res = cx.it.files.close(id);
        cx.set(0, dev_value(0))?;
        res.map_err(|e| access(cx, &FsError::Io(e)))?;
        Ok(Value::Absent)
    });
    r.add(
        r"PROC Write(VAR iodev IODevice, string String, \num Num | dnum Dnum | bool Bool | pos Pos | orient Orient, \switch NoNewLine)",
        |cx| {
            let mut s = super::text::compose(cx, 1, 2)?;
            if !cx.present(7) {
                s.push('\n');
            }
            write(cx, s.as_bytes())
        },
    );
    r.add(
        r"PROC WriteBin(VAR iodev IODevice, num Buffer{*}, num NChar)",
        write_bin,
    );
    r.add("PROC WriteStrBin(VAR iodev IODevice, string Str)", |cx| {
        let s = cx.str(1)?.to_string();
        write(cx, s.as_bytes())
    });
    r.add("PROC WriteAnyBin(VAR iodev IODevice, anytype Data)", |cx| {
        let text = any_text(cx.value(1)?);
        let mut rec = Vec::with_capacity(text.len() + 6);
        rec.push(ANYBIN_MAGIC);
        rec.extend_from_slice(&(text.len() as u32).to_le_bytes());
        rec.extend_from_slice(text.as_bytes());
        rec.push(checksum(text.as_bytes()));
        write(cx, &rec)
    });
    r.add(
        r"PROC ReadAnyBin(VAR iodev IODevice, VAR anytype Data, \num Time)",
        read_any_bin,
    );
    r.add(r"FUNC num ReadBin(VAR iodev IODevice, \num Time)", |cx| {
        let b = with_handle(cx, 0, |h| h.read_byte())?;
        Ok(Value::Num(b.map_or(EOF_BIN, f32::from)))
    });
    r.add(
        r"FUNC string ReadStr(VAR iodev IODevice, \string Delim, \switch RemoveCR, \switch DiscardHeaders, \num Time)",
        read_str,
    );
    r.add(
        r"FUNC num ReadNum(VAR iodev IODevice, \string Delim, \num Time)",
        read_num,
    );
    r.add(
        r"FUNC string ReadStrBin(VAR iodev IODevice, num NoOfChars, \num Time)",
        |cx| {
            let n = cx.int(1, "NoOfChars")?;
            if !(0..=MAX_STRING as i64).contains(&n) {
                return Err(cx.error(
                    errnum::ERR_ARGVALERR,
                    format!("NoOfChars must be 0 … {MAX_STRING}, not {n}"),
                ));
            }
            let bytes = with_handle(cx, 0, |h| h.read_bytes(n as usize))?;
            if bytes.is_empty() && n > 0 {
                return Ok(Value::str(EOF_STR));
            }
            cx.string(decode(&bytes))
        },
    );
    r.add("PROC Rewind(VAR iodev IODevice)", |cx| {
        with_handle(cx, 0, |h| h.rewind())?;
        Ok(Value::Absent)
    });
    // A file has no input buffer to clear (the serial channels it is meant for are not
    // part of a virtual controller): it only checks that the iodev is open.
    r.add("PROC ClearIOBuff(VAR iodev IODevice)", |cx| {
        with_handle(cx, 0, |_| Ok(()))?;
        Ok(Value::Absent)
    });
    r.add("PROC OpenDir(VAR dir Dev, string Path)", |cx| {
        let host = path(cx, 1, errnum::ERR_FILEACC)?;
        let id = cx
            .it
            .files
            .open_dir(&host)
            .map_err(|e| access(cx, &FsError::Io(e)))?;
        cx.set(0, dev_value(id))?;
        Ok(Value::Absent)
    });
    r.add(
        "FUNC bool ReadDir(VAR dir Dev, VAR string FileName)",
        |cx| {
            let id = dev_id(cx, 0)?;
            match cx.it.files.read_dir(id) {
                Ok(Some(name)) => {
                    let v = cx.string(name)?;
                    cx.set(1, v)?;
                    Ok(Value::Bool(true))
                }
                Ok(None) => Ok(Value::Bool(false)),
                Err(()) => Err(cx.error(errnum::ERR_FILEACC, "the directory is not open")),
            }
        },
    );
    r.add("PROC CloseDir(VAR dir Dev)", |cx| {
        let id = dev_id(cx, 0)?;
        cx.it.files.close_dir(id);
        cx.set(0, dev_value(0))?;
        Ok(Value::Absent)
    });
    r.add("PROC MakeDir(string Path)", |cx| {
        let host = path(cx, 0, errnum::ERR_FILEACC)?;
        std::fs::create_dir(&host).map_err(|e| access(cx, &FsError::Io(e)))?;
        Ok(Value::Absent)
    });
    r.add("PROC RemoveDir(string Path)", |cx| {
        let host = path(cx, 0, errnum::ERR_FILEACC)?;
        std::fs::remove_dir(&host).map_err(|e| access(cx, &FsError::Io(e)))?;
        Ok(Value::Absent)
    });
    r.add("PROC RemoveFile(string Path)", |cx| {
        let host = path(cx, 0, errnum::ERR_FILEACC)?;
        if host.is_dir() {
            return Err(cx.error(
                errnum::ERR_FILEACC,
                format!("`{}` is a directory (RemoveDir removes it)", cx.str(0)?),
            ));
        }
        std::fs::remove_file(&host).map_err(|e| access(cx, &FsError::Io(e)))?;
        Ok(Value::Absent)
    });
    r.add("PROC RenameFile(string OldPath, string NewPath)", |cx| {
        let (from, to) = two_paths(cx)?;
        std::fs::rename(&from, &to).map_err(|e| access(cx, &FsError::Io(e)))?;
        Ok(Value::Absent)
    });
    r.add("PROC CopyFile(string OldPath, string NewPath)", |cx| {
        let (from, to) = two_paths(cx)?;
        if from.is_dir() {
            return Err(cx.error(
                errnum::ERR_FILEACC,
                format!("`{}` is a directory; CopyFile copies files", cx.str(0)?),
            ));
        }
        crate::interp::files::copy_new(&from, &to).map_err(|e| access(cx, &FsError::Io(e)))?;
        Ok(Value::Absent)
    });
    r.add(
        r"FUNC bool IsFile(string Path, \switch Directory | switch Fifo | switch RegularFile | switch BlockSpecial | switch CharSpecial)",
        is_file,
    );
    r.add("FUNC num FileSize(string Path)", |cx| {
        let host = path(cx, 0, errnum::ERR_FILEACC)?;
        let m = std::fs::metadata(&host).map_err(|e| access(cx, &FsError::Io(e)))?;
        cx.num_result(m.len() as f64)
    });
    r.add(
        r"FUNC num FileTime(string Path, \switch ModifyTime | switch AccessTime | switch StatCTime)",
        file_time,
    );
    r.add(
        r"FUNC num FSSize(string Name, \switch Total | switch Free, \switch Kbyte | switch Mbyte)",
        fs_size,
    );
}

/// An `iodev`/`dir` value for handle number `id` (0: not open).
fn dev_value(id: u32) -> Value {
    Value::Record(Box::new([Value::Num(id as f32)]))
}

/// The handle number in `iodev`/`dir` argument `i`.
fn dev_id(cx: &Ctx<'_>, i: usize) -> Exec<u32> {
    let v = cx.value(i)?;
    match v.fields() {
        Some([Value::Num(x)]) if *x >= 0.0 => Ok(*x as u32),
        _ => Err(cx.it.type_bug(cx.span, "iodev", v)),
    }
}

/// `ERR_FILEACC` with the reason.
fn access(cx: &Ctx<'_>, e: &FsError) -> Unwind {
    cx.error(errnum::ERR_FILEACC, e.to_string())
}

/// The host path of the controller path in string argument `i`; a refused path raises
/// `errno`.
fn path(cx: &mut Ctx<'_>, i: usize, errno: i32) -> Exec<PathBuf> {
    let p = cx.str(i)?.to_string();
    resolve(cx, &p, errno)
}

pub(super) fn resolve(cx: &mut Ctx<'_>, p: &str, errno: i32) -> Exec<PathBuf> {
    match cx.it.files.resolve(p) {
        Ok((host, note)) => {
            if let Some(n) = note {
                cx.host().output(Output::Event(n));
            }
            Ok(host)
        }
        Err(e) => Err(cx.error(errno, e.to_string())),
    }
}

/// Both paths of `RenameFile`/`CopyFile`: `ERR_FILEEXIST` when the new one exists.
fn two_paths(cx: &mut Ctx<'_>) -> Exec<(PathBuf, PathBuf)> {
    let from = path(cx, 0, errnum::ERR_FILEACC)?;
    let to = path(cx, 1, errnum::ERR_FILEACC)?;
    if std::fs::symlink_metadata(&from).is_err() {
        return Err(cx.error(
            errnum::ERR_FILEACC,
            format!("`{}` does not exist", cx.str(0)?),
        ));
    }
    if std::fs::symlink_metadata(&to).is_ok() {
        return Err(cx.error(
            errnum::ERR_FILEEXIST,
            format!("`{}` already exists", cx.str(1)?),
        ));
    }
    Ok((from, to))
}

/// Run `f` on the open file of `iodev` argument `i`; every failure is `ERR_FILEACC`.
pub(crate) fn with_handle<T>(
    cx: &mut Ctx<'_>,
    i: usize,
    f: impl FnOnce(&mut Handle) -> std::io::Result<T>,
) -> Exec<T> {
    let id = dev_id(cx, i)?;
    let Some(h) = cx.it.files.handle(id) else {
        return Err(cx.error(errnum::ERR_FILEACC, "the iodev is not open (Open it first)"));
    };
    let name = h.name.clone();
    f(h).map_err(|e| cx.error(errnum::ERR_FILEACC, format!("`{name}`: {e}")))
}

fn write(cx: &mut Ctx<'_>, bytes: &[u8]) -> Exec<Value> {
    with_handle(cx, 0, |h| h.write_bytes(bytes))?;
    Ok(Value::Absent)
}

fn open(cx: &mut Ctx<'_>) -> Exec<Value> {
    let object = cx.str(0)?.to_string();
    let full = if cx.present(1) {
        let file = cx.str(1)?;
        format!("{}/{file}", object.trim_end_matches(['/', '\\']))
    } else {
        object
    };
    let old = dev_id(cx, 2)?;
    if cx.it.files.is_open(old) {
        return Err(cx.error(
            errnum::ERR_FILEOPEN,
            "the iodev is already open (Close it before opening it again)",
        ));
    }
    let binary = cx.present(6);
    let mode = if cx.present(3) {
        OpenMode::Read
    } else if cx.present(4) {
        OpenMode::Write
    } else if cx.present(5) || !binary {
        OpenMode::Append
    } else {
        OpenMode::ReadWrite
    };
    let host = resolve(cx, &full, errnum::ERR_FILEOPEN)?;
    if host.is_dir() {
        return Err(cx.error(
            errnum::ERR_FILEOPEN,
            format!("`{full}` is a directory, not a file"),
        ));
    }
    let h = Handle::open(&host, &full, mode, binary)
        .map_err(|e| cx.error(errnum::ERR_FILEOPEN, format!("`{full}`: {e}")))?;
    let id = cx.it.files.insert(h);
    cx.set(2, dev_value(id))?;
    Ok(Value::Absent)
}

fn write_bin(cx: &mut Ctx<'_>) -> Exec<Value> {
    let n = cx.int(2, "NChar")?;
    let bytes = {
        let Value::Array(a) = cx.value(1)? else {
            return Err(cx.it.type_bug(cx.span, "num array", cx.value(1)?));
        };
        if n < 0 || n as usize > a.data.len() {
            return Err(cx.error(
                errnum::ERR_ARGVALERR,
                format!(
                    "NChar {n} is outside 0 … {} (the buffer's size)",
                    a.data.len()
                ),
            ));
        }
        let mut bytes = Vec::with_capacity(n as usize);
        for v in a.data.iter().take(n as usize) {
            match v {
                Value::Num(x) if (0.0..=255.0).contains(x) && x.fract() == 0.0 => {
                    bytes.push(*x as u8)
                }
                other => {
                    return Err(cx.error(
                        errnum::ERR_ARGVALERR,
                        format!(
                            "WriteBin writes bytes (0 … 255), not {}",
                            super::text::val_to_str(other)
                        ),
                    ));
                }
            }
        }
        bytes
    };
    write(cx, &bytes)
}

/// Bytes read from a file as text: UTF-8 (as rapidvc writes), else ISO-8859-1.
fn decode(bytes: &[u8]) -> String {
    match std::str::from_utf8(bytes) {
        Ok(s) => s.to_string(),
        Err(_) => bytes.iter().map(|&b| char::from(b)).collect(),
    }
}

/// Read up to [`MAX_STRING`] characters up to one of `delims` (taken, not returned);
/// `None` at the end of the file.
fn read_line(cx: &mut Ctx<'_>, delims: &[u8], skip_leading: bool) -> Exec<Option<Vec<u8>>> {
    with_handle(cx, 0, |h| {
        if skip_leading {
            while let Some(b) = h.peek_byte()? {
                if !delims.contains(&b) {
                    break;
                }
                h.read_byte()?;
            }
        }
        let mut out = Vec::new();
        let mut chars = 0;
        loop {
            match h.peek_byte()? {
                None if out.is_empty() => return Ok(None),
                None => return Ok(Some(out)),
                Some(b) if delims.contains(&b) => {
                    h.read_byte()?;
                    return Ok(Some(out));
                }
                Some(b) => {
                    // Count characters, not bytes (a UTF-8 character has one leading byte).
                    if b & 0xC0 != 0x80 {
                        if chars == MAX_STRING {
                            return Ok(Some(out));
                        }
                        chars += 1;
                    }
                    h.read_byte()?;
                    out.push(b);
                }
            }
        }
    })
}

fn delimiters(cx: &Ctx<'_>, i: usize) -> Exec<Vec<u8>> {
    if cx.present(i) {
        Ok(cx.str(i)?.bytes().collect())
    } else {
        Ok(vec![b'\n'])
    }
}

fn read_str(cx: &mut Ctx<'_>) -> Exec<Value> {
    let delims = delimiters(cx, 1)?;
    let skip = cx.present(3);
    let Some(mut line) = read_line(cx, &delims, skip)? else {
        return Ok(Value::str(EOF_STR));
    };
    if cx.present(2) && line.last() == Some(&b'\r') {
        line.pop();
    }
    cx.string(decode(&line))
}

fn read_num(cx: &mut Ctx<'_>) -> Exec<Value> {
    let delims = delimiters(cx, 1)?;
    let Some(line) = read_line(cx, &delims, false)? else {
        return Ok(Value::Num(EOF_NUM));
    };
    let text = decode(&line);
    match f::str_to_num(text.trim()) {
        Some(x) => Ok(Value::Num(x)),
        None => Err(cx.error(
            errnum::ERR_RCVDATA,
            format!("ReadNum read `{}`, which is not a number", text.trim()),
        )),
    }
}

/// The text `WriteAnyBin` stores: a RAPID literal whose numbers keep every bit.
fn any_text(v: &Value) -> String {
    match v {
        Value::Num(x) => format!("{x:e}"),
        Value::Dnum(x) => format!("{x:e}"),
        Value::Bool(b) => f::format_bool(*b).to_string(),
        Value::Str(s) => f::quote_string(s),
        Value::Record(fs) => f::format_list(fs.iter().map(any_text)),
        Value::Array(a) => f::format_list(a.data.iter().map(any_text)),
        Value::Absent => String::new(),
    }
}

fn checksum(bytes: &[u8]) -> u8 {
    bytes.iter().fold(0u8, |a, b| a.wrapping_add(*b))
}

fn read_any_bin(cx: &mut Ctx<'_>) -> Exec<Value> {
    enum Got {
        Eof,
        Bad(&'static str),
        Text(String),
    }
    let got = with_handle(cx, 0, |h| {
        let Some(magic) = h.read_byte()? else {
            return Ok(Got::Eof);
        };
        if magic != ANYBIN_MAGIC {
            return Ok(Got::Bad("the data was not written by WriteAnyBin"));
        }
        let len = h.read_bytes(4)?;
        let Ok(len) = <[u8; 4]>::try_from(len.as_slice()) else {
            return Ok(Got::Eof);
        };
        let len = u32::from_le_bytes(len) as usize;
        if len > 1 << 24 {
            return Ok(Got::Bad("the record is longer than any RAPID value"));
        }
        let body = h.read_bytes(len)?;
        let sum = h.read_byte()?;
        if body.len() < len || sum.is_none() {
            return Ok(Got::Eof);
        }
        if sum != Some(checksum(&body)) {
            return Ok(Got::Bad("checksum error"));
        }
        Ok(match String::from_utf8(body) {
            Ok(s) => Got::Text(s),
            Err(_) => Got::Bad("the record is not text"),
        })
    })?;
    let text = match got {
        Got::Eof => {
            return Err(cx.error(
                errnum::ERR_RANYBIN_EOF,
                "the end of the file came before the data",
            ));
        }
        Got::Bad(why) => return Err(cx.error(errnum::ERR_RANYBIN_CHK, why)),
        Got::Text(t) => t,
    };
    let mut v = cx.value(1)?.clone();
    let filled = f::parse_value(&text).is_some_and(|lit| super::fill_literal(&mut v, &lit));
    if !filled {
        return Err(cx.error(
            errnum::ERR_RANYBIN_CHK,
            "the data read does not fit the variable's type",
        ));
    }
    cx.set(1, v)?;
    Ok(Value::Absent)
}

fn is_file(cx: &mut Ctx<'_>) -> Exec<Value> {
    let host = path(cx, 0, errnum::ERR_FILEACC)?;
    let Ok(m) = std::fs::symlink_metadata(&host) else {
        return Ok(Value::Bool(false));
    };
    let t = m.file_type();
    #[cfg(unix)]
    let (fifo, block, chr) = {
        use std::os::unix::fs::FileTypeExt;
        (t.is_fifo(), t.is_block_device(), t.is_char_device())
    };
    #[cfg(not(unix))]
    let (fifo, block, chr) = (false, false, false);
    let ok = if cx.present(1) {
        t.is_dir()
    } else if cx.present(2) {
        fifo
    } else if cx.present(3) {
        t.is_file()
    } else if cx.present(4) {
        block
    } else if cx.present(5) {
        chr
    } else {
        true
    };
    Ok(Value::Bool(ok))
}

fn file_time(cx: &mut Ctx<'_>) -> Exec<Value> {
    let host = path(cx, 0, errnum::ERR_FILEACC)?;
    let m = std::fs::metadata(&host).map_err(|e| access(cx, &FsError::Io(e)))?;
    let secs = if cx.present(3) {
        status_change(&m)
    } else {
        let t = if cx.present(2) {
            m.accessed()
        } else {
            m.modified()
        };
        t.ok()
            .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
            .map(|d| d.as_secs() as f64)
    };
    match secs {
        Some(s) => cx.num_result(s),
        None => Err(cx.error(
            errnum::ERR_FILEACC,
            format!("the host keeps no such time for `{}`", cx.str(0)?),
        )),
    }
}

#[cfg(unix)]
fn status_change(m: &std::fs::Metadata) -> Option<f64> {
    use std::os::unix::fs::MetadataExt;
    Some(m.ctime() as f64)
}

#[cfg(not(unix))]
fn status_change(_: &std::fs::Metadata) -> Option<f64> {
    None
}

fn fs_size(cx: &mut Ctx<'_>) -> Exec<Value> {
    let host = path(cx, 0, errnum::ERR_FILEACC)?;
    let (total, free) = space(&host).map_err(|e| access(cx, &FsError::Io(e)))?;
    let bytes = (if cx.present(1) { total } else { free }) as f64;
    let scaled = if cx.present(3) {
        bytes / 1024.0
    } else if cx.present(4) {
        bytes / (1024.0 * 1024.0)
    } else {
        bytes
    };
    cx.num_result(scaled.floor())
}

/// (total, free) bytes of the file system holding `p`.
#[cfg(unix)]
fn space(p: &std::path::Path) -> std::io::Result<(u64, u64)> {
    let s = rustix::fs::statvfs(p).map_err(std::io::Error::from)?;
    Ok((
        s.f_blocks.saturating_mul(s.f_frsize),
        s.f_bavail.saturating_mul(s.f_frsize),
    ))
}

#[cfg(not(unix))]
fn space(_: &std::path::Path) -> std::io::Result<(u64, u64)> {
    Err(std::io::Error::new(
        std::io::ErrorKind::Unsupported,
        "FSSize needs a Unix host",
    ))
}
