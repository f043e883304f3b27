//! From RAPID source to a checked [`ir::Program`](crate::ir::Program): the one entry point the
//! CLI (`run`, `test`, `check`), the tests, the benchmarks and later services use.
//!
//! A program is the embedded stdlib plus the user's modules, checked against the signals of
//! a configuration (`EIO.cfg`, with `SIO.cfg` devices and `MOC.cfg` profiles beside it):
//!
//! * [`load`]: files and directories, with the configuration directory next to them (what
//!   `rapidvc run` and `rapidvc test` do); finding and decoding the files is [`rapid_files`].
//! * [`load_texts`]: modules given as `(name, text)` pairs and a [`config::Config`] — for a
//!   caller that holds source text rather than files (a service receiving modules, a test, a
//!   benchmark). A controller with several tasks loads each task's modules with one call.
//! * [`parse_module`] and [`check`]: the two steps underneath, for callers that keep one
//!   [`SourceMap`] across several module sets (the tasks of one controller): parse every
//!   module into the shared map, then check each set against the shared signals.
//!
//! * [`system::load_system`]: a whole system of several tasks, from a controller backup
//!   folder or from files with task prefixes (`T_ROB1=main.mod`), the tasks from SYS.cfg.
//!
//! Problems are collected in [`Loaded::diags`], never returned early: a program is produced
//! only when there is no error (warnings are allowed).

pub mod rapid_files;
pub mod runtime_loader;
pub mod system;

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
use crate::source::{SourceId, SourceMap};

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

/// The controller's default USER system module (`reg1` … `reg5`, `clock1`), parsed into
/// `sources`, when none of the `user` files has a module named USER: it joins the user's
/// modules (its data are ordinary variables), as a task's own user.sys would. A name the
/// user's modules declare themselves (`VAR num reg1;`, common in programs written without a
/// controller's user.sys at hand) is theirs: the default module leaves it out.
fn default_user_module(
    user: &[ast::File],
    sources: &mut SourceMap,
    diags: &mut Diagnostics,
) -> Option<ast::File> {
    let (name, text) = stdlib::DEFAULT_USER;
    let has_own = user
        .iter()
        .flat_map(|f| &f.modules)
        .any(|m| m.name.node.eq_ignore_ascii_case("user"));
    if has_own {
        return None;
    }
    // The names of the default module (one declaration per line: `  VAR num reg1 := 0;`)
    // that the user's modules declare themselves, read in one pass without unpacking their
    // declarations.
    let var_name = |line: &str| -> Option<String> {
        let mut words = line.split_whitespace();
        (words.next() == Some("VAR"))
            .then(|| {
                words
                    .nth(1)
                    .map(|n| n.trim_end_matches(';').to_ascii_lowercase())
            })
            .flatten()
    };
    let defaults: Vec<String> = text.lines().filter_map(var_name).collect();
    let mut taken: Vec<&str> = Vec::new();
    for f in user {
        for item in f.modules.iter().flat_map(|m| &m.items) {
            if let Some((n, _)) = item.name(f.span.source, &f.text)
                && let Some(d) = defaults.iter().find(|d| d.eq_ignore_ascii_case(n))
            {
                taken.push(d);
            }
        }
    }
    // The text itself leaves the user's names out, so that a module loaded at run time
    // (which parses the program's texts again) sees the same module.
    let text: String = text
        .lines()
        .filter(|line| var_name(line).is_none_or(|n| !taken.contains(&n.as_str())))
        .map(|line| format!("{line}\n"))
        .collect();
    let id = sources.add(name, text.clone());
    Some(parse::parse_file(id, &text, diags))
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
/// programs (a folder such as `programs/manual`, or the program modules of several tasks
/// beside the system modules they share): then each program module is checked with every
/// system module of the set (`SYSMODULE`, or a `.sys` file), with the configuration next to
/// it; system modules alone are checked on their own. Then the result says so (which name
/// two files share), for the user to see that `rapidvc run` of the same files would refuse
/// them as one program.
pub fn check_files(
    user: &[ast::File],
    paths: &[PathBuf],
    sources: &mut SourceMap,
    registry: &Registry,
    diags: &mut Diagnostics,
) -> Option<Independent> {
    let dir = config_dir(None, paths);
    let signals = load_signals(dir.as_deref(), sources, diags);
    let errors = sema_errors(user, sources, &signals, registry);
    let shared = if user.len() > 1 {
        errors.iter().find_map(|e| match &e.kind {
            sema::SemaErrorKind::Duplicate { name, first } if first.source != e.span.source => {
                Some(Independent {
                    name: name.clone(),
                    files: [
                        sources.get(first.source).name.clone(),
                        sources.get(e.span.source).name.clone(),
                    ],
                })
            }
            _ => None,
        })
    } else {
        None
    };
    if shared.is_none() {
        for e in errors {
            diags.push(e);
        }
        return None;
    }
    let is_system = |f: &ast::File, sources: &SourceMap| {
        let name = &sources.get(f.span.source).name;
        let sys_ext = Path::new(name)
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("sys"));
        sys_ext
            || f.modules.iter().any(|m| {
                m.attrs
                    .iter()
                    .any(|a| matches!(a.node, ast::ModuleAttr::SysModule))
            })
    };
    let system: Vec<ast::File> = user
        .iter()
        .filter(|f| is_system(f, sources))
        .cloned()
        .collect();
    let programs: Vec<&ast::File> = user.iter().filter(|f| !is_system(f, sources)).collect();
    // A system module's own problems are reported once, whichever program shows them.
    let mut seen = std::collections::HashSet::new();
    let alone: Vec<&ast::File> = if programs.is_empty() {
        user.iter().collect()
    } else {
        programs
    };
    for file in alone {
        let path = PathBuf::from(&sources.get(file.span.source).name);
        let dir = config_dir(None, std::slice::from_ref(&path));
        let signals = load_signals(dir.as_deref(), sources, diags);
        let mut set = vec![file.clone()];
        if !is_system(file, sources) {
            set.extend(system.iter().cloned());
        }
        for e in sema_errors(&set, sources, &signals, registry) {
            if e.span.source == file.span.source || seen.insert(format!("{e:?}")) {
                diags.push(e);
            }
        }
    }
    shared
}

/// Files that [`check_files`] checked as independent programs, and the first global name two
/// of them both declare.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Independent {
    /// The name declared in both files.
    pub name: String,
    /// The file that declares it first, and the other.
    pub files: [String; 2],
}

impl std::fmt::Display for Independent {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let [a, b] = &self.files;
        write!(
            f,
            "note: {a} and {b} both declare `{}`, so they are independent programs: each \
             program module was checked on its own with the system modules; `rapidvc run` \
             loads the files it is given as one program",
            self.name
        )
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
    let default_user = default_user_module(user, sources, &mut diags);
    let env = sema::Env::from_signals(signals);
    sema::check_only(
        &sema_inputs(&std_files, default_user.as_ref(), user),
        registry.signatures(),
        &env,
    )
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
    let default_user = default_user_module(user, sources, diags);
    let env = sema::Env::from_signals(signals);
    sema::analyze(
        &sema_inputs(&std_files, default_user.as_ref(), user),
        registry.signatures(),
        &env,
        diags,
    )
}

/// The semantic pass's inputs: the stdlib's files, the default USER module, then the
/// user's files.
fn sema_inputs<'a>(
    std_files: &'a [ast::File],
    default_user: Option<&'a ast::File>,
    user: &'a [ast::File],
) -> Vec<sema::Input<'a>> {
    let stdlib = std_files
        .iter()
        .map(|file| sema::Input { file, stdlib: true });
    let user = default_user
        .into_iter()
        .chain(user)
        .map(|file| sema::Input {
            file,
            stdlib: false,
        });
    stdlib.chain(user).collect()
}

/// Add one module's `text` to `sources` under `name` (what diagnostics show: a path or any
/// label), parse it and run the structural checks; problems go to `diags`.
pub fn parse_module(
    sources: &mut SourceMap,
    name: impl Into<String>,
    text: impl crate::source::IntoSourceText,
    diags: &mut Diagnostics,
) -> ast::File {
    let id = sources.add(name, text);
    parse_source(sources, id, diags)
}

/// Parse a user file already in `sources` and run the structural checks.
fn parse_source(sources: &SourceMap, id: SourceId, diags: &mut Diagnostics) -> ast::File {
    let file = parse::parse_file(id, &sources.get(id).text, diags);
    parse::check_structure(&file, diags);
    file
}

/// Load, parse and check one program given as module texts: `(name, text)` pairs, `name`
/// being what diagnostics show (a path or any label), against the configuration `config`
/// ([`config::Config::default`] for the built-in signals, devices and profiles).
pub fn load_texts<N, T>(modules: impl IntoIterator<Item = (N, T)>, config: config::Config) -> Loaded
where
    N: Into<String>,
    T: crate::source::IntoSourceText,
{
    let mut sources = SourceMap::new();
    let mut diags = Diagnostics::new();
    let user = modules
        .into_iter()
        .map(|(name, text)| parse_module(&mut sources, name, text, &mut diags))
        .collect::<Vec<_>>();
    finish(sources, diags, &user, config, false)
}

/// Load, parse and check the program in `paths` (files or directories), with the
/// configuration in `config`, else in the directory of the first path ([`config_dir`]).
pub fn load(paths: &[PathBuf], config: Option<&Path>) -> Loaded {
    let mut sources = SourceMap::new();
    let mut diags = Diagnostics::new();
    let mut io_failed = false;
    let mut user = Vec::new();
    match rapid_files::find_rapid_files(paths) {
        Ok(files) => {
            for path in &files {
                match rapid_files::load_file(&mut sources, path) {
                    Ok(id) => user.push(parse_source(&sources, id, &mut diags)),
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
    finish(sources, diags, &user, cfg, io_failed)
}

/// The signals of `cfg`, then the semantic check of `user` when nothing failed so far.
fn finish(
    mut sources: SourceMap,
    mut diags: Diagnostics,
    user: &[ast::File],
    cfg: config::Config,
    io_failed: bool,
) -> Loaded {
    let registry = Registry::standard();
    let signals = signal_table(&cfg, &mut diags);
    let program = if diags.has_errors() || io_failed {
        None
    } else {
        check(user, &mut sources, &signals, &registry, &mut diags).map(Arc::new)
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

#[cfg(test)]
mod tests {
    use std::sync::{Arc, Mutex};

    use super::*;
    use crate::interp::{Interp, Output, VirtualHost};

    const MAIN: &str = "MODULE MainModule\n  PROC main()\n    greet 3;\n  ENDPROC\nENDMODULE\n";
    const LIB: &str =
        "MODULE Lib\n  PROC greet(num n)\n    TPWrite \"hello \"\\Num:=n;\n  ENDPROC\nENDMODULE\n";

    /// The TP lines of running `main` of a loaded program.
    fn tp_lines(loaded: &Loaded) -> Vec<String> {
        let lines = Arc::new(Mutex::new(Vec::new()));
        let sink = Arc::clone(&lines);
        let host = VirtualHost::new().with_sink(move |o| {
            if let (Output::TpWrite(s), Ok(mut l)) = (o, sink.lock()) {
                l.push(s.clone());
            }
        });
        let program = loaded.program.clone().expect("the program checks");
        let mut it = Interp::new(program, &loaded.registry, Box::new(host));
        it.init().expect("init");
        it.run("main").expect("runs");
        lines.lock().expect("lines").clone()
    }

    #[test]
    fn texts_load_as_files_do() {
        let from_text = load_texts(
            [("main.mod", MAIN), ("lib.mod", LIB)],
            config::Config::default(),
        );
        assert!(!from_text.diags.has_errors(), "{:?}", from_text.diags);
        assert_eq!(tp_lines(&from_text), ["hello 3"]);

        let dir = std::env::temp_dir().join(format!("rapidvc-program-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        std::fs::write(dir.join("main.mod"), MAIN).expect("write");
        std::fs::write(dir.join("lib.mod"), LIB).expect("write");
        let from_files = load(std::slice::from_ref(&dir), None);
        std::fs::remove_dir_all(&dir).expect("clean up");
        assert!(!from_files.diags.has_errors(), "{:?}", from_files.diags);
        assert_eq!(tp_lines(&from_files), tp_lines(&from_text));
    }

    #[test]
    fn text_errors_name_their_module() {
        let text = "MODULE Broken\n  PROC main()\n    TPWrite nothing;\n  ENDPROC\nENDMODULE\n";
        let loaded = load_texts([("task2/broken.mod", text)], config::Config::default());
        assert!(loaded.program.is_none());
        assert!(!loaded.io_failed);
        let err = loaded.diags.iter().next().expect("one diagnostic");
        assert_eq!(
            err.code().map(|c| c.to_string()).as_deref(),
            Some("rapidvc::sema::undeclared")
        );
        let id = err.source_id().expect("in a module");
        assert_eq!(loaded.sources.get(id).name, "task2/broken.mod");
    }

    #[test]
    fn programs_of_several_tasks_are_checked_with_their_system_modules() {
        // Two tasks' program modules (both with `main`) beside the system module they share,
        // as in a backup or a ROS driver's folder.
        let mut sources = SourceMap::new();
        let mut diags = Diagnostics::new();
        let registry = Registry::standard();
        let shared = "MODULE shared(SYSMODULE)\n  PROC greet(num n)\n    TPWrite \"hi\"\\Num:=n;\n  ENDPROC\nENDMODULE\n";
        let t1 = "MODULE t1\n  PROC main()\n    greet 1;\n  ENDPROC\nENDMODULE\n";
        let t2 = "MODULE t2\n  PROC main()\n    greet 2;\n    missing_one;\n  ENDPROC\nENDMODULE\n";
        let files = [
            parse_module(&mut sources, "d/shared.sys", shared, &mut diags),
            parse_module(&mut sources, "d/t1.mod", t1, &mut diags),
            parse_module(&mut sources, "d/t2.mod", t2, &mut diags),
        ];
        let paths = [PathBuf::from("d/t1.mod")];
        let independent = check_files(&files, &paths, &mut sources, &registry, &mut diags);
        assert_eq!(
            independent.map(|i| i.files),
            Some(["d/t1.mod".to_string(), "d/t2.mod".to_string()])
        );
        // (The folder does not exist, so its configuration cannot be read: not asserted.)
        let errors: Vec<String> = diags
            .iter()
            .map(|d| d.to_string())
            .filter(|d| !d.starts_with("cannot read"))
            .collect();
        assert_eq!(errors, ["`missing_one` is not declared"]);
    }

    #[test]
    fn modules_of_several_sets_share_one_source_map() {
        let mut sources = SourceMap::new();
        let mut diags = Diagnostics::new();
        let registry = Registry::standard();
        let signals = SignalTable::with_builtins();
        let task1 = [
            parse_module(&mut sources, "t1/main.mod", MAIN, &mut diags),
            parse_module(&mut sources, "t1/lib.mod", LIB, &mut diags),
        ];
        let task2 = [parse_module(
            &mut sources,
            "t2/main.mod",
            "MODULE Other\n  PROC main()\n    TPWrite \"two\";\n  ENDPROC\nENDMODULE\n",
            &mut diags,
        )];
        let p1 = check(&task1, &mut sources, &signals, &registry, &mut diags);
        let p2 = check(&task2, &mut sources, &signals, &registry, &mut diags);
        assert!(!diags.has_errors(), "{diags:?}");
        assert!(p1.is_some() && p2.is_some());
        // `main` of the second set is its own: the first set's modules are not part of it.
        let again = check(
            &[task1[0].clone()],
            &mut sources,
            &signals,
            &registry,
            &mut diags,
        );
        assert!(again.is_none(), "MainModule alone does not find greet");
    }
}
