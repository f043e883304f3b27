//! The program's modules while it runs: the [`ModuleLoader`] the interpreter uses for
//! `Load`, `WaitLoad`, `UnLoad`, `EraseModule` and `Save`. It keeps the parsed modules of
//! the program and builds the whole program again, with the same parser and semantic pass
//! as at the start, when one is added or taken away (a loaded module always comes after
//! every other; see `interp::relink` for why that keeps running code valid).

use std::sync::Arc;

use crate::ast;
use crate::diag::{Diagnostics, RapidDiagnostic};
use crate::interp::Registry;
use crate::interp::errnum;
use crate::interp::relink::{LinkError, ModuleFile, ModuleLoader, NewModule};
use crate::ir::Program;
use crate::parse;
use crate::sema;
use crate::source::SourceMap;

/// One user module of the program.
struct UserModule {
    name: String,
    file: ast::File,
    text: crate::source::SourceText,
    /// The controller path it was loaded from at run time.
    path: Option<String>,
    modified: Option<f64>,
}

/// The modules of one task's program, able to take one more or one less.
pub struct RuntimeLoader {
    sources: SourceMap,
    std_files: Vec<ast::File>,
    user: Vec<UserModule>,
    env: sema::Env,
}

impl RuntimeLoader {
    /// The loader of a checked program: `sources` holds every file its spans point into
    /// (the `sources` of [`super::Loaded`]); `signals` are the ones it was checked against.
    pub fn new(
        program: &Program,
        sources: &SourceMap,
        signals: &crate::signals::SignalTable,
    ) -> RuntimeLoader {
        let mut diags = Diagnostics::new();
        let mut std_files = Vec::new();
        let mut user = Vec::new();
        let mut seen = Vec::new();
        for m in &program.modules {
            if seen.contains(&m.source) {
                continue;
            }
            seen.push(m.source);
            let f = sources.get(m.source);
            let file = parse::parse_file(m.source, &f.text, &mut diags);
            if m.stdlib {
                std_files.push(file);
                continue;
            }
            let modified = std::fs::metadata(&f.name)
                .and_then(|md| md.modified())
                .ok()
                .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
                .map(|d| d.as_secs() as f64);
            for (k, am) in file.modules.iter().enumerate() {
                user.push(UserModule {
                    name: am.name.node.to_string(),
                    // A file of several modules is one entry (its first module's name
                    // stands for it; the others are found by `module` below).
                    file: if k == 0 {
                        file.clone()
                    } else {
                        ast::File {
                            modules: Vec::new(),
                            span: file.span,
                            text: file.text.clone(),
                        }
                    },
                    text: f.text.clone(),
                    path: None,
                    modified,
                });
            }
        }
        RuntimeLoader {
            sources: sources.clone(),
            std_files,
            user,
            env: sema::Env::from_signals(signals),
        }
    }

    /// The program of the current modules.
    fn build(&self, registry: &Registry) -> Result<Program, LinkError> {
        let inputs: Vec<sema::Input<'_>> = self
            .std_files
            .iter()
            .map(|file| sema::Input { file, stdlib: true })
            .chain(self.user.iter().map(|m| sema::Input {
                file: &m.file,
                stdlib: false,
            }))
            .collect();
        let (program, errors) = sema::analyze_to_vec(&inputs, registry.signatures(), &self.env);
        match program {
            Some(p) => Ok(p),
            None => {
                let first = errors.iter().find(|e| !e.is_warning());
                let message = first.map_or_else(
                    || "the program does not check".to_string(),
                    |e| self.describe(e),
                );
                Err(LinkError {
                    errno: errnum::ERR_LINKREF,
                    message,
                })
            }
        }
    }

    /// `file:line:col: message` of a diagnostic.
    fn describe(&self, d: &dyn RapidDiagnostic) -> String {
        let at = d.source_id().and_then(|id| {
            let offset = d.labels()?.next()?.offset();
            let f = self.sources.get(id);
            let (l, c) = f.line_col(offset as u32);
            Some(format!("{}:{l}:{c}: ", f.name))
        });
        let help = d.help().map(|h| format!(" ({h})")).unwrap_or_default();
        format!("{}{d}{help}", at.unwrap_or_default())
    }
}

impl ModuleLoader for RuntimeLoader {
    fn add(&mut self, registry: &Registry, module: NewModule<'_>) -> Result<Program, LinkError> {
        let mut diags = Diagnostics::new();
        let id = self.sources.add(module.path, module.text);
        let file = parse::parse_file(id, &self.sources.get(id).text, &mut diags);
        parse::check_structure(&file, &mut diags);
        if let Some(d) = diags
            .iter()
            .find(|d| crate::diag::severity_of(*d) == miette::Severity::Error)
        {
            return Err(LinkError {
                errno: errnum::ERR_SYNTAX,
                message: self.describe(d),
            });
        }
        let [m] = file.modules.as_slice() else {
            return Err(LinkError {
                errno: errnum::ERR_SYNTAX,
                message: format!(
                    "`{}` holds {} modules; a file loaded at run time holds one",
                    module.path,
                    file.modules.len()
                ),
            });
        };
        let name = m.name.node.clone();
        if self.user.iter().any(|u| u.name.eq_ignore_ascii_case(&name)) {
            return Err(LinkError {
                errno: errnum::ERR_LOADED,
                message: format!("module `{name}` is already loaded"),
            });
        }
        self.user.push(UserModule {
            name: name.to_string(),
            text: file.text.clone(),
            file,
            path: Some(module.path.to_string()),
            modified: module.modified,
        });
        let built = self.build(registry);
        if built.is_err() {
            self.user.pop();
        }
        built
    }

    fn remove(&mut self, registry: &Registry, name: &str) -> Result<Program, LinkError> {
        let Some(i) = self
            .user
            .iter()
            .position(|u| u.name.eq_ignore_ascii_case(name))
        else {
            return Err(LinkError {
                errno: errnum::ERR_MODULE,
                message: format!("no module `{name}`"),
            });
        };
        if self.user[i].file.modules.len() != 1 {
            return Err(LinkError {
                errno: errnum::ERR_UNLOAD,
                message: format!(
                    "module `{name}` shares its file with other modules; rapidvc unloads \
                     modules of their own files only"
                ),
            });
        }
        let taken = self.user.remove(i);
        let built = self.build(registry);
        if built.is_err() {
            self.user.insert(i, taken);
        }
        built.map_err(|e| LinkError {
            errno: errnum::ERR_UNLOAD,
            message: format!(
                "the program does not check without module `{name}`: {}",
                e.message
            ),
        })
    }

    fn module(&self, name: &str) -> Option<ModuleFile> {
        self.user
            .iter()
            .find(|u| u.name.eq_ignore_ascii_case(name))
            .map(|u| ModuleFile {
                // (A copy: only a module saved or unloaded at run time asks for it.)
                text: Arc::from(u.text.as_str()),
                path: u.path.clone(),
                modified: u.modified,
            })
    }

    fn sources(&self) -> &SourceMap {
        &self.sources
    }
}
