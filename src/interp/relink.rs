//! The program changing while it runs: program modules loaded and unloaded by `Load`,
//! `StartLoad`/`WaitLoad`, `UnLoad` and `EraseModule`.
//!
//! The interpreter does not parse or check RAPID itself (the layers put the front end above
//! it): the program layer hands it a [`ModuleLoader`] that builds the whole program again
//! with one module more or less, with the same front end as at the start. The interpreter
//! then switches to that program ([`Interp::relink`]):
//!
//! * The semantic pass numbers predefined data first and then every module's data, routines
//!   and types in module order, and a loaded module is always the last one. So the modules
//!   before the first one that changed keep every number, and code already running (routines
//!   on the call stack, which the engines hold while they run) stays valid. Relinking checks
//!   this and refuses, with a clear error, when a running routine or a connected TRAP
//!   belongs to a module whose numbers would change (unloading a module that was loaded
//!   before the one running).
//! * Module data of the modules that stay keep their values (moved by module and name when
//!   their numbers change); a new module's data are initialised as at the start.
//! * Late binding (`%"name"%`, `CallByVar`) looks procedures up in the newest program, so it
//!   reaches loaded routines, and an unloaded one is `ERR_REFUNKPRC` again.

use std::sync::Arc;

use super::{Interp, Registry, compile, errnum, value};
use crate::ir::{GlobalOrigin, ModuleId, Program, RoutineId};
use crate::source::{SourceMap, Span};

/// Why a module cannot join or leave the program: the RAPID error and its text.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkError {
    /// The `ERR_*` number (`ERR_SYNTAX`, `ERR_LINKREF`, `ERR_LOADED`, …).
    pub errno: i32,
    /// What is wrong, with the diagnostic's file and line.
    pub message: String,
}

/// A module read from the controller's mass storage.
#[derive(Debug, Clone, Copy)]
pub struct NewModule<'a> {
    /// The controller path it was read from (`HOME:/lib.mod`).
    pub path: &'a str,
    /// Its text.
    pub text: &'a str,
    /// When the file was last changed (seconds since 1970), for `ModTime`.
    pub modified: Option<f64>,
}

/// What the interpreter knows about a module of the program.
#[derive(Debug, Clone)]
pub struct ModuleFile {
    /// Its text as it was loaded.
    pub text: Arc<str>,
    /// The controller path it was loaded from at run time (`None` for the modules the
    /// program started with).
    pub path: Option<String>,
    /// When its file was last changed before it was loaded (seconds since 1970).
    pub modified: Option<f64>,
}

/// Builds the program again with a module more or less (the program layer implements it
/// with the front end that built the program at the start).
pub trait ModuleLoader: Send {
    /// The program with `module` added after every other module.
    fn add(&mut self, registry: &Registry, module: NewModule<'_>) -> Result<Program, LinkError>;
    /// The program without the module called `name`.
    fn remove(&mut self, registry: &Registry, name: &str) -> Result<Program, LinkError>;
    /// The module called `name` (case-insensitive), if the program has it.
    fn module(&self, name: &str) -> Option<ModuleFile>;
    /// Every source the program's spans point into, loaded modules included (to show
    /// errors in loaded modules with their lines).
    fn sources(&self) -> &SourceMap;
}

/// The task's modules at run time: the loader and the open load sessions.
#[derive(Default)]
pub(crate) struct Modules {
    pub loader: Option<Box<dyn ModuleLoader>>,
    /// Load sessions of `StartLoad` (by session number): the module read, waiting for
    /// `WaitLoad`.
    pub sessions: Vec<(u32, Session)>,
    pub next_session: u32,
    /// `SetDataSearch`'s search and where `GetNextSym` is in it.
    pub search: Option<super::builtins::data_search::Search>,
    /// The modules loaded at run time: the host file each came from, and its name.
    pub loaded_from: Vec<(std::path::PathBuf, String)>,
    /// The values of each run-time module's persistents when it was loaded or last saved
    /// (module name, values as text), for `UnLoad \ErrIfChanged`.
    pub saved_pers: Vec<(String, String)>,
}

/// A module read by `StartLoad`.
#[derive(Debug, Clone)]
pub(crate) struct Session {
    pub path: String,
    pub text: String,
    pub modified: Option<f64>,
}

impl Interp {
    /// Let the program load and unload modules while it runs (`Load`, `UnLoad`, …); without
    /// a loader those instructions stop the program with an error saying so.
    pub fn set_module_loader(&mut self, loader: Box<dyn ModuleLoader>) {
        self.modules.loader = Some(loader);
    }

    /// The sources of the program as it is now (loaded modules included), when modules
    /// can be loaded; else `None` (the program's sources are the ones it started with).
    pub fn loaded_sources(&self) -> Option<&SourceMap> {
        self.modules.loader.as_deref().map(|l| l.sources())
    }

    /// Switch to `new`, the program with a module more or less (see the module
    /// documentation for what is kept).
    pub(crate) fn relink(&mut self, new: Program) -> Result<(), LinkError> {
        let old = self.prog.clone();
        let refuse = |message: String| LinkError {
            errno: errnum::ERR_UNLOAD,
            message,
        };
        // The modules before `k` are the same in both programs.
        let k = old
            .modules
            .iter()
            .zip(&new.modules)
            .take_while(|(a, b)| a.name.eq_ignore_ascii_case(&b.name) && a.source == b.source)
            .count() as u32;
        let kept = |m: ModuleId| m.0 < k;
        let kept_routine = |r: RoutineId| kept(old.routine(r).module);
        // Their routines and data must have kept their numbers.
        for (i, r) in old.routines.iter().enumerate() {
            if kept(r.module) {
                let same = new
                    .routines
                    .get(i)
                    .is_some_and(|n| n.name.eq_ignore_ascii_case(&r.name) && n.module == r.module);
                if !same {
                    return Err(refuse(format!(
                        "rapidvc cannot relink the program: routine `{}` would move",
                        r.name
                    )));
                }
            }
        }
        for (i, g) in old.globals.iter().enumerate() {
            let in_kept = match g.origin {
                GlobalOrigin::Module(m) => kept(m),
                _ => true,
            };
            if in_kept
                && !new
                    .globals
                    .get(i)
                    .is_some_and(|n| n.name.eq_ignore_ascii_case(&g.name) && n.origin == g.origin)
            {
                return Err(refuse(format!(
                    "rapidvc cannot relink the program: data `{}` would move",
                    g.name
                )));
            }
        }
        // What runs (the call stack, connected TRAPs) must be in those modules.
        if let Some(f) = self.frames.iter().find(|f| !kept_routine(f.routine)) {
            let r = old.routine(f.routine);
            return Err(refuse(format!(
                "routine `{}` of module `{}` is running; rapidvc changes the program only \
                 after the modules the running routines belong to",
                r.name, old.modules[r.module.0 as usize].name
            )));
        }
        let remap = |rid: RoutineId| -> Option<RoutineId> {
            if kept_routine(rid) {
                return Some(rid);
            }
            let r = old.routine(rid);
            let mname = &old.modules[r.module.0 as usize].name;
            new.routines
                .iter()
                .position(|n| {
                    n.name.eq_ignore_ascii_case(&r.name)
                        && new.modules[n.module.0 as usize]
                            .name
                            .eq_ignore_ascii_case(mname)
                })
                .map(|i| RoutineId(i as u32))
        };
        if let Some(trap) = self.ints.traps_not_in(|rid| remap(rid).is_some()) {
            return Err(refuse(format!(
                "the TRAP `{}` is connected to an interrupt and would be unloaded \
                 (IDelete its interrupt first)",
                old.routine(trap).name
            )));
        }
        self.ints.remap_traps(|rid| remap(rid).unwrap_or(rid));

        // Module data: kept by number, else by module and name; new ones initialised.
        let mut globals: Vec<Option<value::Value>> = vec![None; new.globals.len()];
        for (i, (g, v)) in old.globals.iter().zip(self.globals.iter()).enumerate() {
            let to = match g.origin {
                GlobalOrigin::Module(m) if !kept(m) => {
                    let mname = &old.modules[m.0 as usize].name;
                    new.globals.iter().position(|n| {
                        n.name.eq_ignore_ascii_case(&g.name)
                            && matches!(n.origin, GlobalOrigin::Module(nm)
                                if new.modules[nm.0 as usize].name.eq_ignore_ascii_case(mname))
                            && n.ty == g.ty
                            && n.dims == g.dims
                    })
                }
                _ => Some(i),
            };
            if let Some(slot) = to.and_then(|t| globals.get_mut(t)) {
                *slot = Some(v.clone());
            }
        }
        let new = Arc::new(new);
        let fresh: Vec<bool> = globals.iter().map(Option::is_none).collect();
        self.globals = globals
            .into_iter()
            .zip(&new.globals)
            .map(|(v, g)| v.unwrap_or_else(|| value::default_value(&new.types, g.ty, &g.dims)))
            .collect();
        self.natives = self.registry.impls_for(&new.natives);
        let standard = self.registry.standard_for(&new.natives);
        self.code = Arc::new(compile::Code::new(new.clone(), self.engine, &standard));
        self.prog = new.clone();
        self.late_args.clear();
        self.late_sites.clear();
        self.module_values = new
            .globals
            .iter()
            .filter(|g| matches!(g.origin, GlobalOrigin::Module(_)))
            .map(|g| new.types.values(g.ty, &g.dims))
            .fold(0u64, u64::saturating_add);
        for &gid in &new.init_order {
            let i = gid.0 as usize;
            if !fresh.get(i).copied().unwrap_or(false) {
                continue;
            }
            if let Some(init) = &new.globals[i].init {
                match self.eval(&new, init) {
                    Ok(v) => self.globals[i] = v,
                    Err(u) => {
                        let e = self.unwind_to_error(u);
                        return Err(LinkError {
                            errno: errnum::ERR_LINKREF,
                            message: format!(
                                "the data `{}` of the loaded module cannot be initialised: {}",
                                new.globals[i].name, e.message
                            ),
                        });
                    }
                }
            }
        }
        self.relink_shared().map_err(|message| LinkError {
            errno: errnum::ERR_LINKREF,
            message,
        })
    }

    /// The loader, or the error of an instruction that needs one.
    pub(crate) fn loader_or(&mut self, span: Span, what: &str) -> super::error::Exec<()> {
        if self.modules.loader.is_some() {
            return Ok(());
        }
        Err(self.fatal(
            super::ErrorKind::Unsupported,
            span,
            format!(
                "`{what}` needs a program that can change while it runs; this run of rapidvc \
                 has no module loader (rapidvc run and rapidvc test have one)"
            ),
        ))
    }
}
