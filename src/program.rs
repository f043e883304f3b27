//! Loading a program: the embedded stdlib and the user's files are parsed, the
//! configuration directory gives the I/O signals, and the semantic pass checks everything
//! and lowers it to IR. Shared by `run`, `test` and `check`.

pub mod files;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::ast;
use crate::config;
use crate::diag::Diagnostics;
use crate::interp::{Registry, stdlib};
use crate::ir::Program;
use crate::parse;
use crate::sema;
use crate::signals::SignalTable;
use crate::source::SourceMap;

/// Problems of loading that are not in a source file.
#[derive(Debug, Clone, PartialEq, thiserror::Error, miette::Diagnostic)]
pub enum LoadProblem {
    /// A file or directory cannot be read.
    #[error("{message}")]
    #[diagnostic(code(rapidvc::load::io))]
    Io {
        /// What failed.
        message: String,
    },
    /// The configured signals cannot be used together.
    #[error("the I/O configuration cannot be used: {message}")]
    #[diagnostic(code(rapidvc::config::signals))]
    Signals {
        /// What is wrong.
        message: String,
    },
}

impl crate::diag::RapidDiagnostic for LoadProblem {
    fn source_id(&self) -> Option<crate::source::SourceId> {
        None
    }
}

/// A loaded (and, when there were no errors, checked) program.
pub struct Loaded {
    /// Every file (stdlib, user, configuration).
    pub sources: SourceMap,
    /// Everything found while loading.
    pub diags: Diagnostics,
    /// The checked program (`None` when there were errors).
    pub program: Option<Arc<Program>>,
    /// The natives the program was checked against.
    pub registry: Registry,
    /// The I/O signals (built-in plus `EIO.cfg`).
    pub signals: Arc<SignalTable>,
    /// The configuration directory's system parameters (UdpUc devices of `SIO.cfg`, motion
    /// profiles of `MOC.cfg`; the built-in ones without files).
    pub config: config::Config,
    /// A file could not be read (usage or I/O error rather than a program error).
    pub io_failed: bool,
}

/// Where the configuration is: `--config DIR`, else the directory of the first path.
pub fn config_dir(explicit: Option<&Path>, paths: &[PathBuf]) -> Option<PathBuf> {
    if let Some(d) = explicit {
        return Some(d.to_path_buf());
    }
    let first = paths.first()?;
    if first.is_dir() {
        Some(first.clone())
    } else {
        first
            .parent()
            .map(|p| {
                if p.as_os_str().is_empty() {
                    Path::new(".")
                } else {
                    p
                }
            })
            .map(Path::to_path_buf)
    }
}

/// Parse the embedded stdlib into `sources`.
pub fn parse_stdlib(sources: &mut SourceMap, diags: &mut Diagnostics) -> Vec<ast::File> {
    stdlib::SOURCES
        .iter()
        .map(|(name, text)| {
            let id = sources.add(*name, *text);
            parse::parse_file(id, text, diags)
        })
        .collect()
}

/// Read the configuration (signals); problems go to `diags`.
pub fn load_signals(
    dir: Option<&Path>,
    sources: &mut SourceMap,
    diags: &mut Diagnostics,
) -> Arc<SignalTable> {
    let cfg = match dir {
        Some(d) => config::load_dir(d, sources, diags),
        None => config::Config::default(),
    };
    signal_table(&cfg, diags)
}

/// The signal table of a configuration; problems go to `diags`.
fn signal_table(cfg: &config::Config, diags: &mut Diagnostics) -> Arc<SignalTable> {
    match cfg.signal_table() {
        Ok(t) => Arc::new(t),
        Err(e) => {
            diags.push(LoadProblem::Signals {
                message: e.to_string(),
            });
            Arc::new(SignalTable::with_builtins())
        }
    }
}

/// The semantic check of `rapidvc check`: the given files are one program (the modules of a
/// task), unless two files declare the same global name, which means they are independent
/// programs (a folder such as `programs/manual`): then each file is checked on its own, with
/// the configuration next to it.
pub fn check_files(
    user: &[ast::File],
    paths: &[PathBuf],
    sources: &mut SourceMap,
    registry: &Registry,
    diags: &mut Diagnostics,
) {
    let dir = config_dir(None, paths);
    let signals = load_signals(dir.as_deref(), sources, diags);
    let errors = sema_errors(user, sources, &signals, registry);
    let independent = user.len() > 1
        && errors.iter().any(|e| {
            matches!(e.kind, sema::SemaErrorKind::Duplicate { first, .. }
                if first.source != e.span.source)
        });
    if !independent {
        for e in errors {
            diags.push(e);
        }
        return;
    }
    for file in user {
        let path = PathBuf::from(&sources.get(file.span.source).name);
        let dir = config_dir(None, std::slice::from_ref(&path));
        let signals = load_signals(dir.as_deref(), sources, diags);
        for e in sema_errors(std::slice::from_ref(file), sources, &signals, registry) {
            diags.push(e);
        }
    }
}

fn sema_errors(
    user: &[ast::File],
    sources: &mut SourceMap,
    signals: &SignalTable,
    registry: &Registry,
) -> Vec<sema::SemaError> {
    let mut diags = Diagnostics::new();
    let std_files = parse_stdlib(sources, &mut diags);
    let mut inputs: Vec<sema::Input<'_>> = std_files
        .iter()
        .map(|f| sema::Input {
            file: f,
            stdlib: true,
        })
        .collect();
    inputs.extend(user.iter().map(|f| sema::Input {
        file: f,
        stdlib: false,
    }));
    let env = sema::Env::from_signals(signals);
    sema::analyze_to_vec(&inputs, registry.signatures(), &env).1
}

/// Run the semantic pass over already parsed user files (plus the stdlib).
pub fn check(
    user: &[ast::File],
    sources: &mut SourceMap,
    signals: &SignalTable,
    registry: &Registry,
    diags: &mut Diagnostics,
) -> Option<Program> {
    let std_files = parse_stdlib(sources, diags);
    let mut inputs: Vec<sema::Input<'_>> = std_files
        .iter()
        .map(|f| sema::Input {
            file: f,
            stdlib: true,
        })
        .collect();
    inputs.extend(user.iter().map(|f| sema::Input {
        file: f,
        stdlib: false,
    }));
    let env = sema::Env::from_signals(signals);
    sema::analyze(&inputs, registry.signatures(), &env, diags)
}

/// Load, parse and check the program in `paths` (files or directories).
pub fn load(paths: &[PathBuf], config: Option<&Path>) -> Loaded {
    let mut sources = SourceMap::new();
    let mut diags = Diagnostics::new();
    let registry = Registry::standard();
    let mut io_failed = false;
    let mut user = Vec::new();
    match files::find_rapid_files(paths) {
        Ok(files) => {
            for path in &files {
                match files::load_file(&mut sources, path) {
                    Ok(id) => {
                        let file = parse::parse_file(id, &sources.get(id).text, &mut diags);
                        parse::check_structure(&file, &mut diags);
                        user.push(file);
                    }
                    Err(e) => {
                        diags.push(LoadProblem::Io {
                            message: e.to_string(),
                        });
                        io_failed = true;
                    }
                }
            }
        }
        Err(e) => {
            diags.push(LoadProblem::Io {
                message: e.to_string(),
            });
            io_failed = true;
        }
    }
    let dir = config_dir(config, paths);
    let cfg = match dir.as_deref() {
        Some(d) => config::load_dir(d, &mut sources, &mut diags),
        None => config::Config::default(),
    };
    let signals = signal_table(&cfg, &mut diags);
    let program = if diags.has_errors() || io_failed {
        None
    } else {
        check(&user, &mut sources, &signals, &registry, &mut diags).map(Arc::new)
    };
    Loaded {
        sources,
        diags,
        program,
        registry,
        signals,
        config: cfg,
        io_failed,
    }
}
