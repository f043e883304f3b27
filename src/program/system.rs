//! Loading a whole system: the tasks of `SYS.cfg` and the modules of each, from a controller
//! backup folder or from files with task prefixes. What `rapidvc run` and `rapidvc serve`
//! boot.
//!
//! # Inputs
//!
//! * **A backup folder** (one directory holding `RAPID/`, see [`is_backup`]):
//!   `SYSPAR/{SYS,EIO,SIO,MOC}.cfg` is the configuration, `RAPID/TASK<n>/PROGMOD/*` and
//!   `RAPID/TASK<n>/SYSMOD/*` (`.mod`, `.modx`, `.sys`, `.prg`) are the modules of task `n`,
//!   where `TASK1` is the first task of SYS.cfg, `TASK2` the second and so on, unless the
//!   backup's `BACKINFO/backinfo.txt` says otherwise (its lines `>>TASK<n>: (NAME,…)` map
//!   folders to task names). `HOME/` is the controller's HOME: directory
//!   ([`LoadedSystem::home`]). System modules come before program modules.
//! * **Files and directories** (what [`super::load`] takes), each optionally prefixed by a
//!   task name: `T_ROB1=main.mod`, `T_LOG=logger/`. A path without a prefix belongs to the
//!   first task of SYS.cfg. The configuration is `--config DIR`, else the directory of the
//!   first path ([`super::config_dir`]).
//!
//! Without SYS.cfg the system has the one motion task `T_ROB1` and loading is exactly
//! [`super::load`]. A task of SYS.cfg that gets no module does not run (it is listed in
//! [`LoadedSystem::idle`]).
//!
//! # Checks across tasks
//!
//! Every task is its own program, checked on its own against the shared configuration. A
//! task-global `PERS` (not `TASK PERS`) of the same name in several tasks is one value: it
//! must have the same type and dimensions everywhere, else loading fails with the ABB load
//! error ("persistent … declared with different type") naming both declarations.
//!
//! # For callers (`rapidvc serve`)
//!
//! [`load_system`] returns a [`LoadedSystem`] with one [`TaskProgram`] per task that has
//! modules, in SYS.cfg order with its 1-based task number; its `sources` hold every file, so
//! one [`SourceMap`] renders the diagnostics of all tasks.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::ast;
use crate::config::{self, sys::TaskConfig};
use crate::diag::Diagnostics;
use crate::interp::Registry;
use crate::ir::{GlobalOrigin, Program, Storage};
use crate::signals::SignalTable;
use crate::source::{SourceMap, Span};

use super::{LoadProblem, check, parse_source, rapid_files, signal_table};

/// A problem of the system as a whole (not in one source file).
#[derive(Debug, Clone, PartialEq, thiserror::Error, miette::Diagnostic)]
pub enum SystemProblem {
    /// A file prefix or backup folder names a task SYS.cfg does not have.
    #[error("{what} names task `{task}`, which SYS.cfg does not define (tasks: {known})")]
    #[diagnostic(code(rapidvc::load::unknown_task))]
    UnknownTask {
        /// Where the name is written (`T_X=a.mod`, `RAPID/TASK4`).
        what: String,
        /// The task name.
        task: String,
        /// The defined tasks.
        known: String,
    },
    /// A task-global persistent declared with different types in two tasks.
    #[error(
        "persistent `{name}` is declared as `{first_ty}` in task {first_task} and as `{second_ty}` in task {second_task}: a task-global PERS is one value in every task, so the types must agree (declare it TASK PERS to keep one per task)"
    )]
    #[diagnostic(code(rapidvc::load::pers_type_mismatch))]
    PersTypeMismatch {
        /// The persistent.
        name: String,
        /// The first task and the type there.
        first_task: String,
        /// Its type there.
        first_ty: String,
        /// The second task.
        second_task: String,
        /// Its type there.
        second_ty: String,
        /// Where the second declaration is.
        #[label("declared differently in task {first_task}")]
        span: Span,
    },
}

impl crate::diag::RapidDiagnostic for SystemProblem {
    fn source_id(&self) -> Option<crate::source::SourceId> {
        match self {
            SystemProblem::PersTypeMismatch { span, .. } => Some(span.source),
            SystemProblem::UnknownTask { .. } => None,
        }
    }
}

/// One task's program.
pub struct TaskProgram {
    /// The task as SYS.cfg defines it.
    pub config: TaskConfig,
    /// Its task number (1-based, SYS.cfg order).
    pub number: usize,
    /// Its module files.
    pub files: Vec<PathBuf>,
    /// The checked program (`None` when it has errors).
    pub program: Option<Arc<Program>>,
}

/// A loaded system.
pub struct LoadedSystem {
    /// Every file of every task, the stdlib and the configuration.
    pub sources: SourceMap,
    /// Everything found while loading.
    pub diags: Diagnostics,
    /// The tasks that have modules, in SYS.cfg order.
    pub tasks: Vec<TaskProgram>,
    /// Tasks of SYS.cfg without any module (they do not run).
    pub idle: Vec<TaskConfig>,
    /// The natives the programs were checked against.
    pub registry: Registry,
    /// The I/O signals shared by every task.
    pub signals: Arc<SignalTable>,
    /// The configuration (with the tasks in `config.sys`).
    pub config: config::Config,
    /// The configuration directory used.
    pub config_dir: Option<PathBuf>,
    /// The backup's `HOME/` folder, when the input was a backup that has one.
    pub home: Option<PathBuf>,
    /// The input was a backup folder.
    pub backup: Option<PathBuf>,
    /// A file could not be read.
    pub io_failed: bool,
}

impl LoadedSystem {
    /// True when every task's program checked.
    pub fn ok(&self) -> bool {
        !self.io_failed
            && !self.diags.has_errors()
            && self.tasks.iter().all(|t| t.program.is_some())
    }
}

/// True when `dir` is a controller backup folder: a directory with a `RAPID` subdirectory
/// (any case).
pub fn is_backup(dir: &Path) -> bool {
    dir.is_dir() && (child(dir, "RAPID").is_some_and(|p| p.is_dir()))
}

/// The entry of `dir` called `name` (case-insensitive).
fn child(dir: &Path, name: &str) -> Option<PathBuf> {
    let mut found: Vec<PathBuf> = std::fs::read_dir(dir)
        .ok()?
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().eq_ignore_ascii_case(name))
        .map(|e| e.path())
        .collect();
    found.sort();
    found.into_iter().next()
}

/// Split `T_ROB1=path` into the task and the path (a prefix is a RAPID name followed by `=`;
/// anything else is a plain path).
pub fn split_task_prefix(arg: &Path) -> (Option<String>, PathBuf) {
    let text = arg.to_string_lossy();
    if let Some((task, rest)) = text.split_once('=') {
        let is_name = !task.is_empty()
            && task.starts_with(|c: char| c.is_ascii_alphabetic())
            && task.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
        if is_name && !rest.is_empty() && !arg.exists() {
            return (Some(task.to_string()), PathBuf::from(rest));
        }
    }
    (None, arg.to_path_buf())
}

/// The task folders of a backup's `BACKINFO/backinfo.txt`: `(n, name)` of each line
/// `>>TASK<n>: (NAME,…)`. Empty when there is no such file.
fn backinfo_tasks(backup: &Path) -> Vec<(usize, String)> {
    let Some(info) = child(backup, "BACKINFO").and_then(|d| child(&d, "backinfo.txt")) else {
        return Vec::new();
    };
    let Ok(bytes) = std::fs::read(&info) else {
        return Vec::new();
    };
    let text = crate::source::decode_owned(bytes);
    let mut out = Vec::new();
    for line in text.lines() {
        let Some(rest) = line.trim().strip_prefix(">>TASK") else {
            continue;
        };
        let Some((num, tail)) = rest.split_once(':') else {
            continue;
        };
        let Ok(n) = num.trim().parse::<usize>() else {
            continue;
        };
        let name = tail
            .trim()
            .trim_start_matches('(')
            .split([',', ')'])
            .next()
            .unwrap_or("")
            .trim()
            .to_string();
        if !name.is_empty() {
            out.push((n, name));
        }
    }
    out
}

/// The number of a `TASK<n>` folder name.
fn task_folder_number(name: &str) -> Option<usize> {
    let upper = name.to_ascii_uppercase();
    upper.strip_prefix("TASK")?.parse().ok()
}

/// Load, parse and check a system (see the module docs). `paths` are the command line's
/// arguments (a backup folder, or files and directories with optional task prefixes),
/// `config_dir` is `--config`.
pub fn load_system(paths: &[PathBuf], config_dir: Option<&Path>) -> LoadedSystem {
    let mut sources = SourceMap::new();
    let mut diags = Diagnostics::new();
    let mut io_failed = false;
    let backup = match paths {
        [one] if is_backup(one) => Some(one.clone()),
        _ => None,
    };
    let split: Vec<(Option<String>, PathBuf)> =
        paths.iter().map(|p| split_task_prefix(p)).collect();
    let plain: Vec<PathBuf> = split.iter().map(|(_, p)| p.clone()).collect();
    let cfg_dir = match (&backup, config_dir) {
        (_, Some(d)) => Some(d.to_path_buf()),
        (Some(b), None) => Some(b.clone()),
        (None, None) => super::config_dir(None, &plain),
    };
    let cfg = match cfg_dir.as_deref() {
        Some(d) => config::load_dir(d, &mut sources, &mut diags),
        None => config::Config::default(),
    };
    let known = cfg
        .sys
        .tasks
        .iter()
        .map(|t| t.name.as_str())
        .collect::<Vec<_>>()
        .join(", ");
    // The files of each task, by index into cfg.sys.tasks.
    let mut files: Vec<Vec<PathBuf>> = vec![Vec::new(); cfg.sys.tasks.len()];
    let mut home = None;
    let task_index = |name: &str| {
        cfg.sys
            .tasks
            .iter()
            .position(|t| t.name.eq_ignore_ascii_case(name))
    };
    if let Some(b) = &backup {
        home = child(b, "HOME").filter(|p| p.is_dir());
        let info = backinfo_tasks(b);
        let rapid = child(b, "RAPID").unwrap_or_else(|| b.join("RAPID"));
        let mut folders: Vec<(usize, PathBuf)> = std::fs::read_dir(&rapid)
            .map(|rd| {
                rd.flatten()
                    .filter(|e| e.path().is_dir())
                    .filter_map(|e| {
                        task_folder_number(&e.file_name().to_string_lossy()).map(|n| (n, e.path()))
                    })
                    .collect()
            })
            .unwrap_or_default();
        folders.sort();
        if folders.is_empty() {
            fail(
                &mut diags,
                &mut io_failed,
                format!(
                    "{}: a backup's RAPID folder holds one TASK<n> folder per task (TASK1, TASK2, …); none found",
                    rapid.display()
                ),
            );
        }
        for (n, folder) in folders {
            let by_info = info
                .iter()
                .find(|(k, _)| *k == n)
                .map(|(_, name)| name.clone());
            let idx = match &by_info {
                Some(name) => task_index(name),
                None => n.checked_sub(1).filter(|i| *i < cfg.sys.tasks.len()),
            };
            let Some(idx) = idx else {
                diags.push(SystemProblem::UnknownTask {
                    what: folder.display().to_string(),
                    task: by_info.unwrap_or_else(|| format!("number {n}")),
                    known: known.clone(),
                });
                io_failed = true;
                continue;
            };
            // System modules first, then program modules; anything else in the folder is
            // left alone (a backup keeps other files there).
            for sub in ["SYSMOD", "PROGMOD"] {
                let Some(dir) = child(&folder, sub).filter(|p| p.is_dir()) else {
                    continue;
                };
                match rapid_files::find_rapid_files(std::slice::from_ref(&dir)) {
                    Ok(found) => files[idx].extend(found),
                    Err(rapid_files::LoadError::NoRapidFiles { .. }) => {}
                    Err(e) => fail(&mut diags, &mut io_failed, e.to_string()),
                }
            }
        }
    } else {
        for (task, path) in &split {
            let idx = match task {
                None => Some(0),
                Some(t) => task_index(t),
            };
            let Some(idx) = idx else {
                diags.push(SystemProblem::UnknownTask {
                    what: format!("`{}={}`", task.as_deref().unwrap_or(""), path.display()),
                    task: task.clone().unwrap_or_default(),
                    known: known.clone(),
                });
                io_failed = true;
                continue;
            };
            match rapid_files::find_rapid_files(std::slice::from_ref(path)) {
                Ok(found) => files[idx].extend(found),
                Err(e) => fail(&mut diags, &mut io_failed, e.to_string()),
            }
        }
    }
    let registry = Registry::standard();
    let signals = signal_table(&cfg, &mut diags);
    let mut parsed: Vec<(TaskConfig, usize, Vec<PathBuf>, Vec<ast::File>)> = Vec::new();
    let mut idle = Vec::new();
    for (i, (task, task_files)) in cfg.sys.tasks.iter().zip(files).enumerate() {
        if task_files.is_empty() {
            idle.push(task.clone());
            continue;
        }
        let mut user = Vec::new();
        for path in &task_files {
            match rapid_files::load_file(&mut sources, path) {
                Ok(id) => user.push(parse_source(&sources, id, &mut diags)),
                Err(e) => fail(&mut diags, &mut io_failed, e.to_string()),
            }
        }
        parsed.push((task.clone(), i + 1, task_files, user));
    }
    let mut tasks = Vec::new();
    let failed_early = diags.has_errors() || io_failed;
    for (config, number, files, user) in parsed {
        let program = if failed_early {
            None
        } else {
            check(&user, &mut sources, &signals, &registry, &mut diags).map(Arc::new)
        };
        tasks.push(TaskProgram {
            config,
            number,
            files,
            program,
        });
    }
    check_shared_pers(&tasks, &mut diags);
    LoadedSystem {
        sources,
        diags,
        tasks,
        idle,
        registry,
        signals,
        config: cfg,
        config_dir: cfg_dir,
        home,
        backup,
        io_failed,
    }
}

/// Report a file that cannot be read.
fn fail(diags: &mut Diagnostics, io_failed: &mut bool, message: String) {
    diags.push(LoadProblem::Io { message });
    *io_failed = true;
}

/// The task-global persistents of a program's own modules: (name, type text, span).
pub fn shared_pers(prog: &Program) -> impl Iterator<Item = (&str, String, Span)> + '_ {
    prog.globals
        .iter()
        .filter(|g| g.storage == Storage::Pers && !g.task)
        .filter(move |g| match g.origin {
            GlobalOrigin::Module(m) => prog.modules.get(m.0 as usize).is_some_and(|m| !m.stdlib),
            _ => false,
        })
        .map(move |g| {
            let ty = format!(
                "{}{}",
                prog.types.name(g.ty.base),
                crate::interp::pers::dims_text(&g.dims)
            );
            (g.name.as_str(), ty, g.span)
        })
}

/// A task-global PERS must have one type in every task.
fn check_shared_pers(tasks: &[TaskProgram], diags: &mut Diagnostics) {
    let mut seen: Vec<(String, String, String)> = Vec::new();
    for t in tasks {
        let Some(prog) = &t.program else { continue };
        for (name, ty, span) in shared_pers(prog) {
            match seen.iter().find(|(n, _, _)| n.eq_ignore_ascii_case(name)) {
                Some((_, first_ty, first_task)) if !first_ty.eq_ignore_ascii_case(&ty) => {
                    diags.push(SystemProblem::PersTypeMismatch {
                        name: name.to_string(),
                        first_task: first_task.clone(),
                        first_ty: first_ty.clone(),
                        second_task: t.config.name.clone(),
                        second_ty: ty,
                        span,
                    });
                }
                Some(_) => {}
                None => seen.push((name.to_string(), ty, t.config.name.clone())),
            }
        }
    }
}
