//! The semantic pass: resolves names across all loaded modules (routine scope, `LOCAL`,
//! global, stdlib, predefined), checks types, storage classes, parameter modes and routine
//! signatures (user routines and natives), and lowers the AST to [`crate::ir::Program`].
//!
//! Entry point: [`analyze`]. Every problem becomes a [`SemaError`] with a
//! `rapidvc::sema::…` code; errors are accumulated, and a program is returned only when
//! there are none (warnings are allowed).

mod base;
mod call;
mod collect;
mod consteval;
pub mod error;
mod expr;
mod limits;
pub mod options;
mod order;
mod predef;
mod resolve;
mod stmt;
mod suggest;

use std::collections::HashMap;
use std::sync::Arc;

use crate::ast;
use crate::diag::Diagnostics;
use crate::ir::{
    Global, GlobalId, ModuleId, ModuleInfo, NativeId, NativeSig, Program, Routine, RoutineId, Ty,
    TypeTable,
};
pub use crate::signals::SignalKind;
use crate::source::Span;
pub use error::{SemaError, SemaErrorKind};

/// What the program's surroundings define: I/O signals and mechanical units.
#[derive(Clone, Debug)]
pub struct Env {
    /// Configured I/O signals (name, kind); they become global data of type `signaldi` …
    pub signals: Vec<(String, SignalKind)>,
    /// Mechanical units (`ROB_1`).
    pub mecunits: Vec<String>,
}

impl Env {
    /// The signals of a signal table and the default mechanical unit.
    pub fn from_signals(table: &crate::signals::SignalTable) -> Self {
        Env {
            signals: table
                .iter()
                .map(|(_, d)| (d.name.clone(), d.kind))
                .collect(),
            ..Env::default()
        }
    }
}

impl Default for Env {
    fn default() -> Self {
        Env {
            signals: Vec::new(),
            mecunits: vec!["ROB_1".to_string()],
        }
    }
}

/// One parsed file to analyse.
#[derive(Clone, Copy, Debug)]
pub struct Input<'a> {
    /// The parsed file.
    pub file: &'a ast::File,
    /// Part of rapidvc's embedded stdlib (its global data may not be redeclared).
    pub stdlib: bool,
}

/// Check and lower a whole program (stdlib inputs first). Diagnostics go to `diags`; the
/// program is returned when there are no errors.
pub fn analyze(
    inputs: &[Input<'_>],
    natives: Arc<[NativeSig]>,
    env: &Env,
    diags: &mut Diagnostics,
) -> Option<Program> {
    let (program, errors) = analyze_to_vec(inputs, natives, env);
    for e in errors {
        diags.push(e);
    }
    program
}

/// Only the diagnostics of [`analyze_to_vec`], for `rapidvc check`: the lowered code is
/// dropped as soon as it is checked (each routine body and each data initialiser once
/// lowered), so the memory needed is the syntax tree's rather than the tree's plus the whole
/// program's.
pub fn check_only(inputs: &[Input<'_>], natives: Arc<[NativeSig]>, env: &Env) -> Vec<SemaError> {
    Checker::run(inputs, natives, env, false).0.errors
}

/// Like [`analyze`], returning the diagnostics as [`SemaError`]s (sorted by position) for
/// callers that inspect them.
pub fn analyze_to_vec(
    inputs: &[Input<'_>],
    natives: Arc<[NativeSig]>,
    env: &Env,
) -> (Option<Program>, Vec<SemaError>) {
    let (mut c, init_order) = Checker::run(inputs, natives, env, true);
    let errors = std::mem::take(&mut c.errors);
    if errors.iter().any(|e| !e.is_warning()) {
        return (None, errors);
    }
    let mut procs_by_name: HashMap<String, Vec<RoutineId>, rustc_hash::FxBuildHasher> =
        HashMap::default();
    for (i, r) in c.routines.iter().enumerate() {
        procs_by_name
            .entry(r.name.to_ascii_uppercase())
            .or_default()
            .push(RoutineId(i as u32));
    }
    let program = Program {
        types: c.types,
        modules: c.modules,
        globals: c.globals,
        routines: c.routines,
        natives: c.natives,
        init_order,
        procs_by_name,
    };
    (Some(program), errors)
}

/// What a local name in a routine stands for.
#[derive(Clone, Debug)]
enum LocalSym {
    /// A parameter (index into the routine's params).
    Param(usize),
    /// Routine data.
    Data {
        slot: u32,
        ty: Ty,
        dims: Vec<u32>,
        constant: bool,
        /// The value of a numeric CONST, when it is known before running.
        cval: Option<f64>,
    },
}

/// Per-routine lowering state.
struct RoutineCx {
    rid: RoutineId,
    func_ret: Option<Ty>,
    scope: HashMap<String, LocalSym>,
    for_vars: Vec<(String, u32)>,
    n_slots: u32,
    /// Label name → id, for the whole routine.
    labels: HashMap<String, u32>,
    /// Labels of the blocks enclosing the statement being lowered, innermost last.
    block_labels: Vec<Vec<u32>>,
    in_handler: bool,
    returns: u32,
}

/// The checker's state across the whole program.
pub(crate) struct Checker<'a> {
    errors: Vec<SemaError>,
    types: TypeTable,
    /// Types declared by a module (with the declaring span), for duplicate reports.
    type_spans: HashMap<String, Span>,
    natives: Arc<[NativeSig]>,
    native_syms: HashMap<String, NativeId>,
    native_params: Vec<Option<Vec<call::PView>>>,
    modules: Vec<ModuleInfo>,
    module_asts: Vec<&'a ast::Module>,
    /// The text of each input file (packed aggregates and call arguments are read from it).
    texts: HashMap<crate::source::SourceId, &'a str, rustc_hash::FxBuildHasher>,
    globals: Vec<Global>,
    /// The declaration behind each module global: a data item ([`ast::ModuleItem::Data`] or
    /// [`ast::ModuleItem::PackedData`], read with [`Checker::data_decl`]) of a module. (16
    /// bytes a global; the rare further declarations of a shared PERS are in
    /// `shared_decls`.)
    global_decls: Vec<Option<(ModuleId, &'a ast::ModuleItem)>>,
    /// The further declarations of shared PERS globals, by global.
    shared_decls: HashMap<u32, Vec<(ModuleId, &'a ast::ModuleItem)>>,
    /// Globals by upper-cased name. (A module of 250,000 data declarations holds as many
    /// entries: a name of up to 15 bytes is kept inline, and the list is sized exactly.)
    data_syms: HashMap<ast::EcoString, Box<[GlobalId]>, rustc_hash::FxBuildHasher>,
    routines: Vec<Routine>,
    routine_asts: Vec<&'a ast::Routine>,
    routine_syms: HashMap<String, Vec<RoutineId>>,
    cur_module: ModuleId,
    rcx: Option<RoutineCx>,
    /// Globals referenced while lowering a global initialiser.
    deps: Vec<GlobalId>,
    init_deps: Vec<Vec<GlobalId>>,
    /// Which globals have a (well-formed) initial value, by global.
    has_init: Vec<bool>,
    const_state: HashMap<u32, consteval::ConstState>,
    pending_records: Vec<(crate::ir::TypeId, ModuleId, &'a ast::RecordDecl)>,
    /// Routines with a placeholder parameter (their body stops the program).
    incomplete: std::collections::HashSet<usize>,
    /// Values held by all module data ([`crate::ir::limits`]).
    module_values: u64,
    /// Keep the lowered routine bodies and data initialisers (false: only the errors are
    /// wanted, see [`check_only`]).
    keep_code: bool,
    /// "Did you mean" for undeclared names, with its index and its bounded work.
    suggester: suggest::Suggester,
}

impl<'a> Checker<'a> {
    /// Every pass over `inputs`; the checker (errors sorted by position) and the order in
    /// which module data is initialised.
    fn run(
        inputs: &[Input<'a>],
        natives: Arc<[NativeSig]>,
        env: &Env,
        keep_code: bool,
    ) -> (Self, Vec<GlobalId>) {
        let mut c = Checker::new(natives);
        c.keep_code = keep_code;
        for inp in inputs {
            c.texts.insert(inp.file.span.source, &inp.file.text);
            for m in &inp.file.modules {
                c.add_module(m, inp.stdlib);
            }
        }
        c.collect_types();
        c.predefined_data(env);
        c.collect_globals();
        c.check_module_data();
        c.collect_routines();
        c.check_native_signatures();
        c.lower_global_inits();
        let init_order = c.init_order();
        c.lower_routines();
        c.errors.sort_by_key(|e| (e.span.source, e.span.start));
        (c, init_order)
    }

    fn new(natives: Arc<[NativeSig]>) -> Self {
        let native_syms = natives
            .iter()
            .enumerate()
            .map(|(i, s)| (s.name.to_ascii_uppercase(), NativeId(i as u32)))
            .collect();
        let n = natives.len();
        Checker {
            errors: Vec::new(),
            types: predef::builtin_types(),
            type_spans: HashMap::new(),
            natives,
            native_syms,
            native_params: vec![None; n],
            modules: Vec::new(),
            module_asts: Vec::new(),
            texts: HashMap::default(),
            globals: Vec::new(),
            global_decls: Vec::new(),
            shared_decls: HashMap::new(),
            data_syms: HashMap::default(),
            routines: Vec::new(),
            routine_asts: Vec::new(),
            routine_syms: HashMap::new(),
            cur_module: ModuleId(0),
            rcx: None,
            deps: Vec::new(),
            init_deps: Vec::new(),
            has_init: Vec::new(),
            const_state: HashMap::new(),
            pending_records: Vec::new(),
            incomplete: Default::default(),
            module_values: 0,
            keep_code: true,
            suggester: suggest::Suggester::default(),
        }
    }

    fn err(&mut self, kind: SemaErrorKind, span: Span) {
        self.errors.push(SemaError::new(kind, span));
    }

    fn add_module(&mut self, m: &'a ast::Module, stdlib: bool) {
        let sysmodule = m
            .attrs
            .iter()
            .any(|a| matches!(a.node, ast::ModuleAttr::SysModule));
        self.modules.push(ModuleInfo {
            name: m.name.node.to_string(),
            source: m.span.source,
            stdlib,
            system: stdlib || sysmodule,
        });
        self.module_asts.push(m);
    }

    /// The declaration of the data item `item` of module `m` (`None` for an item that is
    /// not data).
    fn data_decl(
        &self,
        m: ModuleId,
        item: &'a ast::ModuleItem,
    ) -> Option<std::borrow::Cow<'a, ast::DataDecl>> {
        let source = self.modules.get(m.0 as usize)?.source;
        let text = self.texts.get(&source).copied().unwrap_or("");
        item.data(source, text)
    }

    /// Every declaration behind the global `gi`, the first one first.
    fn decls_of(&self, gi: usize) -> Vec<(ModuleId, &'a ast::ModuleItem)> {
        let first = self.global_decls.get(gi).copied().flatten();
        let more = self.shared_decls.get(&(gi as u32));
        first
            .into_iter()
            .chain(more.into_iter().flatten().copied())
            .collect()
    }

    /// The text of the file `span` is in ("" for a file that is not an input).
    fn text_of(&self, span: Span) -> &'a str {
        self.texts.get(&span.source).copied().unwrap_or("")
    }

    fn is_stdlib(&self, m: ModuleId) -> bool {
        self.modules.get(m.0 as usize).is_some_and(|mi| mi.stdlib)
    }

    fn ty_name(&self, ty: Ty) -> String {
        self.types.display(ty)
    }
}
