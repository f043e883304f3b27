//! System parameters from ABB CFG files in a configuration directory: `EIO.cfg` (I/O signals) now; `SIO.cfg` and `MOC.cfg` readers slot in next to `eio`.
//!
//! [`load_dir`] finds each domain's file case-insensitively in the directory (or in its
//! `SYSPAR` subdirectory, the layout of a controller backup), adds it to the
//! [`SourceMap`] so diagnostics can show it, parses it with the generic [`cfg`] reader and
//! hands the result to the domain reader ([`eio`]). A missing file is not an error: the
//! built-in definitions apply. Every problem is a [`ConfigError`] in the [`Diagnostics`];
//! reading never stops at the first one.
//!
//! To add a domain (e.g. SIO): write `config/sio.rs` with a `read(&CfgFile, &mut
//! Diagnostics) -> SioConfig`, add a field to [`Config`] and one `load_file` call in
//! [`load_dir`].

pub mod cfg;
pub mod eio;
mod error;

use std::path::{Path, PathBuf};

pub use error::ConfigError;

use crate::diag::Diagnostics;
use crate::io::{IoError, SignalDef, SignalTable, builtin_signals, merge_defs};
use crate::source::{SourceMap, decode_bytes};

/// Everything read from a configuration directory.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Config {
    /// The signals of `EIO.cfg`, if the directory has one.
    pub eio: Option<eio::EioConfig>,
}

impl Config {
    /// The built-in signals with EIO.cfg's definitions added (an EIO.cfg signal replaces a
    /// built-in one of the same name).
    pub fn signal_defs(&self) -> Vec<SignalDef> {
        let from_file = self.eio.as_ref().map(|e| e.defs()).unwrap_or_default();
        merge_defs(builtin_signals(), from_file)
    }

    /// A signal table of [`Config::signal_defs`].
    pub fn signal_table(&self) -> Result<SignalTable, IoError> {
        SignalTable::new(self.signal_defs())
    }
}

/// The path of `file_name` in `dir` or `dir/SYSPAR`, matching names case-insensitively.
pub fn find_file(dir: &Path, file_name: &str) -> Option<PathBuf> {
    let find_in = |d: &Path, want_dir: bool| -> Option<PathBuf> {
        std::fs::read_dir(d).ok()?.flatten().find_map(|e| {
            let path = e.path();
            let matches = e
                .file_name()
                .to_string_lossy()
                .eq_ignore_ascii_case(if want_dir { "SYSPAR" } else { file_name });
            (matches && path.is_dir() == want_dir).then_some(path)
        })
    };
    find_in(dir, false).or_else(|| find_in(&find_in(dir, true)?, false))
}

/// Read one CFG file of domain `domain` (e.g. `EIO`): add it to `sources` and parse it.
/// `None` (with a diagnostic) when it cannot be read, has no CFG header or holds another
/// domain.
pub fn load_file(
    path: &Path,
    domain: &str,
    sources: &mut SourceMap,
    diags: &mut Diagnostics,
) -> Option<cfg::CfgFile> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) => {
            diags.push(ConfigError::Io {
                path: path.display().to_string(),
                message: e.to_string(),
            });
            return None;
        }
    };
    let text = decode_bytes(&bytes);
    let id = sources.add(path.display().to_string(), text.as_str());
    let file = cfg::parse(id, &text, diags)?;
    if !file.domain.eq_ignore_ascii_case(domain) {
        diags.push(ConfigError::WrongDomain {
            src: id,
            span: file.domain_span,
            file: path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            expected: domain.to_string(),
            found: file.domain.clone(),
        });
        return None;
    }
    Some(file)
}

/// Read the configuration files in `dir` (see the module doc).
pub fn load_dir(dir: &Path, sources: &mut SourceMap, diags: &mut Diagnostics) -> Config {
    if let Err(e) = std::fs::read_dir(dir) {
        diags.push(ConfigError::Io {
            path: dir.display().to_string(),
            message: e.to_string(),
        });
        return Config::default();
    }
    let eio = find_file(dir, "EIO.cfg")
        .and_then(|p| load_file(&p, "EIO", sources, diags))
        .map(|f| eio::read(&f, diags));
    Config { eio }
}
