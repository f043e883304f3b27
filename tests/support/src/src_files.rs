//! The crate's own Rust sources, for the tests that read the code itself (the layer rule of
//! `tests/layers.rs`, the catalogue of `tests/catalogue.rs`).

use std::path::{Path, PathBuf};

/// The crate's root directory.
pub fn root() -> PathBuf {
    crate::procs::root()
}

/// Every `.rs` file below `dir`.
pub fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("readable directory") {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}
