//! System parameters from ABB CFG files in a configuration directory: `EIO.cfg` (I/O signals), `SIO.cfg` (UdpUc devices), `MOC.cfg` (External Motion Interface Data) and `SYS.cfg` (the RAPID tasks, [`sys`]; and `ReadCfgData`).
//!
//! [`load_dir`] finds each domain's file case-insensitively in the directory (or in its
//! `SYSPAR` subdirectory, the layout of a controller backup), adds it to the
//! [`SourceMap`] so diagnostics can show it, parses it with the generic [`cfg`](mod@cfg) reader and
//! hands the result to the domain reader ([`eio`], [`sio`], [`moc`]). A missing file is not
//! an error: the built-in definitions apply (the built-in signals, the built-in sensor for
//! every device, the predefined motion profile `"default"`). Every problem is a
//! [`ConfigError`] in the [`Diagnostics`]; reading never stops at the first one.
//!
//! [`devices`] combines SIO.cfg with the command line's `--device` overrides into the table
//! that decides where an EGM device name points.
//!
//! To add a domain: write `config/<domain>.rs` with a `read(&CfgFile, &mut Diagnostics) ->
//! …Config`, add a field to [`Config`] and one `load_file` call in [`load_dir_with`].

mod attr;
pub mod cfg;
pub mod devices;
pub mod eio;
mod error;
pub mod moc;
pub mod sio;
pub mod sys;

use std::path::{Path, PathBuf};

pub use error::ConfigError;

use crate::diag::Diagnostics;
use crate::signals::{IoError, SignalDef, SignalTable, builtin_signals, merge_defs};
use crate::source::{SourceMap, decode_owned};

/// Everything read from a configuration directory.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Config {
    /// The signals of `EIO.cfg`, if the directory has one.
    pub eio: Option<eio::EioConfig>,
    /// The devices of `SIO.cfg`, if the directory has one (`None` makes every device the
    /// built-in sensor; see [`devices`]).
    pub sio: Option<sio::SioConfig>,
    /// The motion profiles: the predefined `"default"` plus those of `MOC.cfg`.
    pub moc: moc::MocConfig,
    /// Every CFG file read, as parsed (`EIO.cfg`, `SIO.cfg`, `MOC.cfg` and `SYS.cfg`): the
    /// configuration database `ReadCfgData` reads (`system::cfg_data`).
    pub files: Vec<cfg::CfgFile>,
    /// The RAPID tasks of `SYS.cfg` (`CAB_TASKS`); one motion task `T_ROB1` without it.
    pub sys: sys::SysConfig,
}

/// How [`load_dir_with`] reads the files.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// SIO.cfg options (the section names holding devices).
    pub sio: sio::SioOptions,
}

impl Config {
    /// The device table of SIO.cfg with the `--device` overrides.
    pub fn device_table(
        &self,
        overrides: &[devices::DeviceOverride],
    ) -> Result<devices::DeviceTable, devices::DeviceOverrideError> {
        devices::DeviceTable::new(self.sio.as_ref(), overrides)
    }

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

/// The path of `file_name` in `dir` or `dir/SYSPAR`, matching names case-insensitively. A
/// file is preferred to a directory of the same name; a directory is returned when nothing
/// else matches, so that [`load_file`] reports it instead of it being silently skipped.
pub fn find_file(dir: &Path, file_name: &str) -> Option<PathBuf> {
    let find_in = |d: &Path, name: &str| -> Option<PathBuf> {
        let mut found: Vec<PathBuf> = std::fs::read_dir(d)
            .ok()?
            .flatten()
            .filter(|e| e.file_name().to_string_lossy().eq_ignore_ascii_case(name))
            .map(|e| e.path())
            .collect();
        found.sort_by_key(|p| p.is_dir());
        found.into_iter().next()
    };
    find_in(dir, file_name).or_else(|| {
        let syspar = find_in(dir, "SYSPAR").filter(|p| p.is_dir())?;
        find_in(&syspar, file_name)
    })
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
    if path.is_dir() {
        diags.push(ConfigError::Io {
            path: path.display().to_string(),
            message: "it is a directory, not a configuration file".into(),
        });
        return None;
    }
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
    let text = decode_owned(bytes);
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

/// Read the configuration files in `dir` (see the module doc) with the default options.
pub fn load_dir(dir: &Path, sources: &mut SourceMap, diags: &mut Diagnostics) -> Config {
    load_dir_with(dir, &LoadOptions::default(), sources, diags)
}

/// Read the configuration files in `dir` (see the module doc).
pub fn load_dir_with(
    dir: &Path,
    options: &LoadOptions,
    sources: &mut SourceMap,
    diags: &mut Diagnostics,
) -> Config {
    if let Err(e) = std::fs::read_dir(dir) {
        diags.push(ConfigError::Io {
            path: dir.display().to_string(),
            message: e.to_string(),
        });
        return Config::default();
    }
    let load = |domain: &str, sources: &mut SourceMap, diags: &mut Diagnostics| {
        find_file(dir, &format!("{domain}.cfg")).and_then(|p| load_file(&p, domain, sources, diags))
    };
    let eio_file = load("EIO", sources, diags);
    let eio = eio_file.as_ref().map(|f| eio::read(f, diags));
    let sio_file = load("SIO", sources, diags);
    let sio = sio_file
        .as_ref()
        .map(|f| sio::read_with(f, &options.sio, diags));
    let moc_file = load("MOC", sources, diags);
    let moc = moc_file
        .as_ref()
        .map(|f| moc::read(f, diags))
        .unwrap_or_default();
    // SYS.cfg: the tasks, and the configuration database.
    let sys_file = load("SYS", sources, diags);
    let sys = sys_file
        .as_ref()
        .map(|f| sys::read(f, diags))
        .unwrap_or_default();
    let files = [eio_file, sio_file, moc_file, sys_file]
        .into_iter()
        .flatten()
        .collect();
    Config {
        eio,
        sio,
        moc,
        files,
        sys,
    }
}
