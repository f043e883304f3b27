//! Finding and reading RAPID source files: directory walking with the RAPID extensions, and
//! decoding (UTF-8, else Latin-1) into a [`SourceMap`].

use std::path::{Path, PathBuf};

use crate::source::{SourceId, SourceMap, decode_owned};

/// File extensions of RAPID sources, compared case-insensitively.
pub const RAPID_EXTENSIONS: [&str; 4] = ["mod", "modx", "sys", "prg"];

/// Largest file [`load_file`] accepts (spans are 32-bit byte offsets).
pub const MAX_FILE_SIZE: u64 = 1 << 30;

/// Why files could not be found or read.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// A path given by the user does not exist.
    #[error("{}: no such file or directory", path.display())]
    NotFound {
        /// The path.
        path: PathBuf,
    },
    /// A directory holds no RAPID file.
    #[error("{}: no RAPID files (.mod, .modx, .sys, .prg) found", path.display())]
    NoRapidFiles {
        /// The directory.
        path: PathBuf,
    },
    /// A file is larger than [`MAX_FILE_SIZE`].
    #[error("{}: file is too large ({size} bytes; the limit is 1 GiB)", path.display())]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size.
        size: u64,
    },
    /// The file is not text: it holds NUL bytes (a module encrypted for a RobotWare add-in,
    /// a binary file, or UTF-16 text).
    #[error(
        "{}: not a RAPID text file (it holds NUL bytes: an encrypted or binary module, or UTF-16 text, which rapidvc cannot read)",
        path.display()
    )]
    NotText {
        /// The file.
        path: PathBuf,
    },
    /// Reading failed.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
}

/// True when `path` has one of the [`RAPID_EXTENSIONS`] (any case).
pub fn is_rapid_file(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| RAPID_EXTENSIONS.iter().any(|r| e.eq_ignore_ascii_case(r)))
}

/// The RAPID files named by `paths`: a file is taken as given (whatever its extension); a
/// directory is searched recursively for files with a RAPID extension, skipping hidden
/// entries (names starting with `.`) and not following symbolic links to directories.
/// Directory results are sorted by path; the order of `paths` is kept; duplicates are dropped.
pub fn find_rapid_files(paths: &[PathBuf]) -> Result<Vec<PathBuf>, LoadError> {
    let mut out: Vec<PathBuf> = Vec::new();
    for path in paths {
        let meta = std::fs::metadata(path).map_err(|e| match e.kind() {
            std::io::ErrorKind::NotFound => LoadError::NotFound { path: path.clone() },
            _ => LoadError::Io {
                path: path.clone(),
                source: e,
            },
        })?;
        if meta.is_dir() {
            let mut found = Vec::new();
            walk(path, &mut found)?;
            if found.is_empty() {
                return Err(LoadError::NoRapidFiles { path: path.clone() });
            }
            found.sort();
            out.extend(found);
        } else {
            out.push(path.clone());
        }
    }
    let mut seen = std::collections::HashSet::new();
    out.retain(|p| seen.insert(p.clone()));
    Ok(out)
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) -> Result<(), LoadError> {
    let io = |e| LoadError::Io {
        path: dir.to_path_buf(),
        source: e,
    };
    for entry in std::fs::read_dir(dir).map_err(io)? {
        let entry = entry.map_err(io)?;
        let path = entry.path();
        if entry.file_name().to_string_lossy().starts_with('.') {
            continue;
        }
        let ty = entry.file_type().map_err(io)?;
        if ty.is_dir() {
            walk(&path, out)?;
        } else if (ty.is_file() || (ty.is_symlink() && path.is_file())) && is_rapid_file(&path) {
            out.push(path);
        }
    }
    Ok(())
}

/// Read one file into `map`: UTF-8 when valid (a BOM is dropped), otherwise Latin-1 (one
/// char per byte). Nothing else is changed (CRLF stays, so spans match the file).
pub fn load_file(map: &mut SourceMap, path: &Path) -> Result<SourceId, LoadError> {
    let err = |e| LoadError::Io {
        path: path.to_path_buf(),
        source: e,
    };
    let size = std::fs::metadata(path).map_err(err)?.len();
    if size > MAX_FILE_SIZE {
        return Err(LoadError::TooLarge {
            path: path.to_path_buf(),
            size,
        });
    }
    let bytes = std::fs::read(path).map_err(err)?;
    // Text never holds NUL; without this an encrypted module reads as Latin-1 garbage and
    // fails with a confusing syntax error at its first byte.
    if bytes.contains(&0) {
        return Err(LoadError::NotText {
            path: path.to_path_buf(),
        });
    }
    let text = decode_owned(bytes);
    Ok(map.add(path.display().to_string(), text))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn binary_files_are_not_read_as_text() {
        let dir = std::env::temp_dir().join(format!("rapidvc-bin-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let f = dir.join("enc.sys");
        std::fs::write(&f, [0xfe_u8, 0xd0, 0x05, 0x00, 0x00, 0x01]).expect("write");
        let mut map = SourceMap::new();
        let e = load_file(&mut map, &f).expect_err("binary");
        assert!(matches!(e, LoadError::NotText { .. }));
        assert!(e.to_string().contains("not a RAPID text file"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn walks_directories_sorted_and_filtered() {
        let root = std::env::temp_dir().join(format!("rapidvc-load-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        for f in [
            "b/z.MOD",
            "b/a.sys",
            "a.prg",
            "x.modx",
            "notes.txt",
            ".hidden/h.mod",
            "c/empty/",
        ] {
            let path = root.join(f);
            if f.ends_with('/') {
                std::fs::create_dir_all(&path).unwrap();
                continue;
            }
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(&path, "MODULE m\nENDMODULE\n").unwrap();
        }
        let found = find_rapid_files(std::slice::from_ref(&root)).unwrap();
        let rel: Vec<String> = found
            .iter()
            .map(|p| {
                p.strip_prefix(&root)
                    .unwrap()
                    .to_string_lossy()
                    .replace('\\', "/")
            })
            .collect();
        assert_eq!(rel, ["a.prg", "b/a.sys", "b/z.MOD", "x.modx"]);
        // A file named explicitly is taken whatever its extension; duplicates are dropped.
        let txt = root.join("notes.txt");
        let again = find_rapid_files(&[txt.clone(), txt.clone(), root.join("a.prg")]).unwrap();
        assert_eq!(again, [txt, root.join("a.prg")]);
        assert!(matches!(
            find_rapid_files(&[root.join("c")]),
            Err(LoadError::NoRapidFiles { .. })
        ));
        assert!(matches!(
            find_rapid_files(&[root.join("missing")]),
            Err(LoadError::NotFound { .. })
        ));
        // Latin-1 fallback, CRLF kept.
        let latin = root.join("l.mod");
        std::fs::write(&latin, b"! caf\xe9\r\nMODULE m\r\nENDMODULE\r\n").unwrap();
        let mut map = SourceMap::new();
        let id = load_file(&mut map, &latin).unwrap();
        assert_eq!(
            &*map.get(id).text,
            "! caf\u{e9}\r\nMODULE m\r\nENDMODULE\r\n"
        );
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn extensions_any_case() {
        assert!(is_rapid_file(Path::new("a/B.MOD")));
        assert!(is_rapid_file(Path::new("x.Modx")));
        assert!(is_rapid_file(Path::new("x.sys")));
        assert!(is_rapid_file(Path::new("x.prg")));
        assert!(!is_rapid_file(Path::new("x.txt")));
        assert!(!is_rapid_file(Path::new("mod")));
    }
}
