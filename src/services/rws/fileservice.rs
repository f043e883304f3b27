//! The controller's files over RWS: `fileservice/$HOME|$TEMP|$RAMDISK/…` (list a directory,
//! read, upload with `PUT`, delete) and the environment variables `ctrl/$HOME`, `ctrl/$RAMDISK`,
//! … that name the roots.
//!
//! The roots come from the controller (`Request::FileRoots`); every path goes through
//! [`crate::controller::mass_storage::resolve`], the same sandbox RAPID's file instructions
//! use: no `..`, no host paths, no symbolic links.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::SystemTime;

use axum::http::{HeaderValue, Method, StatusCode, header};
use axum::response::IntoResponse;

use super::repr::{Item, RwsError, State};
use super::{Answer, Outcome, Rq, Shared};
use crate::controller::mass_storage::{self, SandboxError};
use crate::controller::service::Request;

fn sandbox_error(e: SandboxError) -> RwsError {
    match e {
        SandboxError::UnknownRoot { .. } => RwsError::not_found(e.to_string()),
        _ => RwsError::bad(e.to_string()),
    }
}

fn io_error(path: &str, e: &std::io::Error) -> RwsError {
    match e.kind() {
        std::io::ErrorKind::NotFound => RwsError::not_found(format!("no file or directory {path}")),
        _ => RwsError::bad(format!("{path}: {e}")),
    }
}

fn time_text(t: std::io::Result<SystemTime>) -> String {
    t.ok()
        .map(chrono::DateTime::<chrono::Utc>::from)
        .map(|d| d.format("%Y-%m-%d T %H:%M:%S").to_string())
        .unwrap_or_default()
}

/// The directory listing of `dir` (names sorted, directories marked `fs-dir`).
fn list(dir: &Path) -> std::io::Result<Vec<Item>> {
    let mut entries: Vec<(String, std::fs::Metadata)> = Vec::new();
    for e in std::fs::read_dir(dir)? {
        let e = e?;
        let Ok(meta) = e.path().symlink_metadata() else {
            continue;
        };
        // Links are not followed by the sandbox, so they are not listed either.
        if meta.file_type().is_symlink() {
            continue;
        }
        entries.push((e.file_name().to_string_lossy().into_owned(), meta));
    }
    entries.sort_by(|a, b| a.0.cmp(&b.0));
    Ok(entries
        .into_iter()
        .map(|(name, meta)| {
            let class = if meta.is_dir() { "fs-dir" } else { "fs-file" };
            let item = Item::new(class, name.clone())
                .link("self", name.clone())
                .field("fs-cdate", time_text(meta.created()))
                .field("fs-mdate", time_text(meta.modified()));
            if meta.is_dir() {
                item
            } else {
                item.field("fs-size", meta.len())
                    .field("fs-readonly", meta.permissions().readonly())
            }
        })
        .collect())
}

async fn roots(shared: &Arc<Shared>) -> Result<Vec<(String, PathBuf)>, RwsError> {
    shared.ask(Request::FileRoots).await
}

async fn blocking<T: Send + 'static>(
    f: impl FnOnce() -> Result<T, RwsError> + Send + 'static,
) -> Result<T, RwsError> {
    tokio::task::spawn_blocking(f)
        .await
        .map_err(|e| RwsError::bad(format!("the file operation failed: {e}")))?
}

pub(super) async fn fileservice(shared: &Arc<Shared>, rq: &Rq, rest: &[&str]) -> Outcome {
    let roots = roots(shared).await?;
    if rest.is_empty() {
        if rq.method != Method::GET {
            return Err(rq.method_error());
        }
        let mut st = State::new("fileservice", "fileservice/", "");
        for (name, _) in &roots {
            st = st
                .item(Item::new("fs-device", format!("${name}")).link("self", format!("${name}")));
        }
        return Ok(Answer::Ok(st));
    }
    let cpath = rest.join("/");
    let host = mass_storage::resolve(&roots, &cpath).map_err(sandbox_error)?;
    let shown = format!("/fileservice/{cpath}");
    match rq.method {
        Method::GET => {
            if rq.action().is_some() {
                return Err(rq.unknown_action());
            }
            let h = host.clone();
            let s = shown.clone();
            let meta =
                blocking(move || std::fs::metadata(&h).map_err(|e| io_error(&s, &e))).await?;
            if meta.is_dir() {
                let h = host.clone();
                let s = shown.clone();
                let items = blocking(move || list(&h).map_err(|e| io_error(&s, &e))).await?;
                let mut st = State::new("fileservice", &format!("fileservice/{cpath}/"), "");
                st.items = items;
                Ok(Answer::Ok(st))
            } else {
                let s = shown.clone();
                let bytes =
                    blocking(move || std::fs::read(&host).map_err(|e| io_error(&s, &e))).await?;
                Ok(Answer::Raw(
                    (
                        [(
                            header::CONTENT_TYPE,
                            HeaderValue::from_static("application/octet-stream"),
                        )],
                        bytes,
                    )
                        .into_response(),
                ))
            }
        }
        Method::PUT => {
            let body = rq.body.clone();
            let s = shown.clone();
            let created =
                blocking(move || upload(&host, &body).map_err(|e| io_error(&s, &e))).await?;
            let status = if created {
                StatusCode::CREATED
            } else {
                StatusCode::OK
            };
            Ok(Answer::Raw(
                (
                    status,
                    [(header::CONTENT_TYPE, HeaderValue::from_static("text/plain"))],
                    "",
                )
                    .into_response(),
            ))
        }
        Method::DELETE => {
            let s = shown.clone();
            blocking(move || {
                let meta = std::fs::symlink_metadata(&host).map_err(|e| io_error(&s, &e))?;
                if meta.is_dir() {
                    std::fs::remove_dir(&host).map_err(|e| {
                        RwsError::bad(format!("{s}: only an empty directory can be deleted ({e})"))
                    })
                } else {
                    std::fs::remove_file(&host).map_err(|e| io_error(&s, &e))
                }
            })
            .await?;
            Ok(Answer::NoContent)
        }
        _ => Err(rq.method_error()),
    }
}

/// Write `body` to `path` through a temporary file in the same directory and a rename, so a
/// failed upload never leaves half a file. `true` when the file is new.
fn upload(path: &Path, body: &[u8]) -> std::io::Result<bool> {
    let dir = path
        .parent()
        .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::NotFound, "no directory"))?;
    if !dir.is_dir() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::NotFound,
            "the directory does not exist",
        ));
    }
    if path.is_dir() {
        return Err(std::io::Error::other("a directory of that name exists"));
    }
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dir.join(format!(
        ".{name}.{}.rapidvc-upload",
        super::auth::random_hex(4)
    ));
    let created = !path.exists();
    let result = std::fs::write(&tmp, body).and_then(|()| std::fs::rename(&tmp, path));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.map(|()| created)
}

/// `ctrl/$HOME`, `ctrl/$RAMDISK`, …: the path a client uses in `fileservice/` for that root.
pub(super) async fn env_var(shared: &Arc<Shared>, rq: &Rq, var: &str) -> Outcome {
    if rq.method != Method::GET || rq.action().is_some() {
        return Err(rq.unknown_action());
    }
    let Some(name) = var.strip_prefix('$') else {
        return Err(RwsError::not_found(format!("no resource {}", rq.path)));
    };
    let roots = roots(shared).await?;
    let (root, _) = super::find_ci(&roots, name, |(n, _)| n)
        .ok_or_else(|| RwsError::not_found(format!("no environment variable ${name}")))?;
    Ok(Answer::Ok(
        State::new("ctrl", "ctrl/", var.to_string())
            .item(Item::new("ctrl-env", format!("${root}")).field("_value", format!("${root}"))),
    ))
}
