//! The interpreter over [`crate::ir`]: values, frames, places, statements, error recovery,
//! interrupts and natives. It owns neither time nor I/O: everything outside goes through a
//! [`Host`].
//!
//! Two engines run routine bodies ([`Engine`]), on one skeleton (the statement loop with
//! steps, budget, hook and interrupts, the ERROR handler protocol and GOTO, FOR, TEST,
//! calls and frames, places, natives):
//! * the compiled engine (the default, `compile`): every routine body becomes closures
//!   built once in [`Interp::new`], specialised by what the compiler knows of types and
//!   shapes: `num` arithmetic without boxing, places read by borrowing and written in
//!   place, string `+` and `=` on operands read in place, TEST against constants, the
//!   common string functions at their call sites, late calls matched once per call site,
//!   and a simple pure `FUNC num` inlined where it is called (when that fails, or the
//!   per-statement slow path is due, the call is made the general way, so errors and hooks
//!   see the callee's frame as always). Shapes without a specialised form fall back to the
//!   tree-walker's evaluation of their IR node.
//! * the tree-walking engine (`expr.rs`, `stmt.rs`): the plain reference, nothing
//!   specialised. `tests/interp_agree.rs` runs generated programs and every RAPID file of
//!   the repository on both and requires the same output, data, errors and step counts.
//!
//! Semantics decisions (pinned by tests under `tests/run` and `tests/rapid`):
//! * `num` is `f32`; literals are rounded to `f32` when lowered, so `x := 9E9; x = 9E9` holds.
//! * `AND`/`OR`/`XOR` evaluate both operands (no short circuit).
//! * `DIV` and `MOD` need integer operands (`ERR_NOTINTVAL`) and truncate toward zero; the
//!   sign of `MOD` follows the dividend (`-7 MOD 2 = -1`).
//! * `FOR` evaluates its bounds and step once; the default step is 1, or −1 when the start
//!   is greater than the end.
//! * An `ERROR` handler that ends without `RETRY`/`TRYNEXT`/`RETURN`/`RAISE` returns from
//!   the routine (a FUNC then raises `ERR_FNCNORET` in its caller).
//! * More than [`Interp::set_retry_limit`] consecutive `RETRY`s of one statement raise
//!   `ERR_EXCRTYMAX` in the caller.
//! * A run-time error inside an `ERROR` handler, or out of a TRAP, is fatal.

pub mod builtins;
mod call;
mod compile;
pub mod data_access;
pub mod error;
mod expr;
pub mod files;
pub mod host;
mod interrupts;
pub mod operator;
pub mod pers;
mod place;
pub mod relink;
pub mod stdlib;
mod stmt;
pub mod tasks;
pub mod value;

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

pub use crate::ir::errnum;
use crate::ir::{GlobalOrigin, Program, RoutineId, RoutineKind, Storage};
use crate::source::Span;
pub use builtins::{NativeFn, Registry};
pub use error::{ErrorKind, RuntimeError, StackEntry, Unwind};
pub use host::{Host, HostError, Output, VirtualHost};
use interrupts::Interrupts;
use place::AbsPlace;
pub use value::Value;

/// How a run ended without an error.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The entry routine returned.
    Completed,
    /// `EXIT` was executed.
    Exited,
    /// `ExitCycle` was executed.
    ExitCycle,
    /// `Stop` was executed.
    Stopped,
}

/// With a stop request ([`Interp::set_stop_request`]), the per-statement slow path runs at
/// least this often (a few microseconds of statements).
pub const STOP_CHECK_EVERY: u64 = 1024;

/// How routine bodies are executed. Both engines implement the same semantics (outputs,
/// data, errors with their spans and call stacks, step counts); `tests/interp_agree.rs`
/// runs generated programs and every RAPID file of the repository both ways and compares.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Engine {
    /// Compiled closures with specialised fast paths (the default).
    #[default]
    Compiled,
    /// The tree-walking reference: every statement and expression is interpreted from the
    /// IR, nothing specialised or inlined. Much slower; for comparing against.
    TreeWalk,
}

impl Engine {
    /// The engine named by the environment variable `RAPIDVC_ENGINE` (`tree-walk` or
    /// `compiled`), else the compiled one. Lets the differential tests run the command-line
    /// tool with the reference engine.
    pub fn from_env() -> Engine {
        match std::env::var("RAPIDVC_ENGINE") {
            Ok(v) if v.eq_ignore_ascii_case("tree-walk") => Engine::TreeWalk,
            _ => Engine::Compiled,
        }
    }
}

/// What the before-statement hook wants.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HookAction {
    /// Go on.
    Continue,
    /// Abort execution (reported as an `Aborted` run-time error).
    Abort,
    /// Stop the program as `Stop` does (the run ends with [`Outcome::Stopped`]); for the
    /// service hook, e.g. when a service moves the program pointer to main.
    Stop,
}

/// What the before-statement hook sees.
#[derive(Clone, Copy, Debug)]
pub struct StmtEvent<'a> {
    /// The statement about to run.
    pub span: Span,
    /// Name of the routine it is in.
    pub routine: &'a str,
    /// Call depth (1 for the entry routine).
    pub depth: usize,
    /// Statements executed so far.
    pub steps: u64,
}

/// A before-statement hook (stepping, tracing, tests).
pub type StmtHook = Box<dyn FnMut(&StmtEvent<'_>) -> HookAction + Send>;

/// The service hook: called with the interpreter between statements and on every turn of a
/// wait (see [`Interp::set_service_hook`]). It may read and write module data, and block
/// (a stopped controller keeps its program pointer by not returning).
pub type ServiceHook = Box<dyn FnMut(&mut Interp) -> HookAction + Send>;

/// With a service hook, a wait hands control back to the interpreter at least this often,
/// so the hook runs while the program waits.
pub const SERVICE_WAIT_SLICE_S: f64 = 0.01;

/// One activation record.
#[derive(Debug)]
struct Frame {
    routine: RoutineId,
    /// First value slot of the frame (names local data, e.g. an `egmident` identity).
    bp: u32,
    /// The statement currently executing (for stack traces).
    at: Span,
    /// Inside its ERROR handler: the error being handled.
    handling: Option<Box<RuntimeError>>,
    /// `RETRY`s already made of the statement whose error is being handled.
    retries: u32,
}

/// An argument of a native call.
#[derive(Debug, Clone)]
pub(crate) enum NArg {
    Absent,
    Val(Value),
    Ref(AbsPlace),
    Switch,
}

/// A RAPID program being executed.
pub struct Interp {
    prog: Arc<Program>,
    /// The program in the compiled form routine bodies run in.
    code: Arc<compile::Code>,
    natives: Arc<[NativeFn]>,
    host: Box<dyn Host>,
    globals: Vec<Value>,
    /// Value slots of all frames; `sp` is the top (slots above it are kept for reuse).
    stack: Vec<Value>,
    sp: usize,
    /// Slots of the calls running on the `num` frame slab (`compile::numroutine`): the
    /// current frame's first slot, and the first free one.
    nslab: Vec<f32>,
    nbp: usize,
    ntop: usize,
    refs: Vec<AbsPlace>,
    frames: Vec<Frame>,
    idx: Vec<i64>,
    nargs: Vec<NArg>,
    /// The current frame's first value slot and first reference slot (cached).
    bp: usize,
    rbp: usize,
    /// The value of the last `RETURN`.
    ret: Value,
    /// The error behind a NaN of the NaN-signalling `num` path.
    pending: Option<Unwind>,
    /// Buffers for building strings (kept for reuse).
    strbufs: Vec<String>,
    /// Records a store replaced, kept to build the next records in (see
    /// `compile::val`).
    spare_records: value::Spares,
    /// Late-bound calls: the procedure name being looked up, and the arguments of each
    /// call site (by its argument list's address) matched to each procedure called there.
    late_name: String,
    late_args: rustc_hash::FxHashMap<(usize, u32), call::LateArgs>,
    /// Late-bound calls: per call site (and module), the names called there and what each resolved to
    /// (cleared with `late_args` when modules are loaded or unloaded).
    late_sites: rustc_hash::FxHashMap<(usize, u32), Vec<call::LateHit>>,
    /// Stack address when the current run started, and how much stack it may use.
    stack_base: usize,
    stack_budget: usize,
    errno: i32,
    intno: i32,
    next_booked: i32,
    retry_limit: u32,
    ints: Interrupts,
    /// Where the dialogs' answers come from.
    operator: operator::Operator,
    steps: u64,
    next_poll: u64,
    budget: Option<u64>,
    hook: Option<StmtHook>,
    /// Called between statements and in waits (services of a controller that stays up).
    service: Option<ServiceHook>,
    /// Set from outside (Ctrl-C) to stop the program as `Stop` does.
    stop: Option<Arc<AtomicBool>>,
    initialised: bool,
    /// Values held by module data, and by module data plus every call in progress
    /// ([`crate::ir::limits`]).
    module_values: u64,
    data_values: u64,
    /// The mass storage and the files and directories the program has open.
    files: files::Files,
    /// Running as one task of several: shared persistents and time slices (`tasks.rs`).
    task: Option<Box<tasks::TaskLink>>,
    /// The natives and engine the program was built with, and the loader that links
    /// modules into it while it runs (`Load`, `UnLoad`, …; see [`relink`]).
    registry: Arc<Registry>,
    engine: Engine,
    modules: relink::Modules,
}

impl std::fmt::Debug for Interp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Interp")
            .field("steps", &self.steps)
            .field("frames", &self.frames.len())
            .finish()
    }
}

impl Interp {
    /// An interpreter for `prog`, which must have been checked against `registry`, running
    /// on the engine [`Engine::from_env`] names (the compiled one unless the environment
    /// says otherwise).
    pub fn new(prog: Arc<Program>, registry: &Registry, host: Box<dyn Host>) -> Interp {
        Self::with_engine(prog, registry, host, Engine::from_env())
    }

    /// An interpreter for `prog` on the given engine.
    pub fn with_engine(
        prog: Arc<Program>,
        registry: &Registry,
        host: Box<dyn Host>,
        engine: Engine,
    ) -> Interp {
        let natives = registry.impls_for(&prog.natives);
        let standard = registry.standard_for(&prog.natives);
        let code = Arc::new(compile::Code::new(prog.clone(), engine, &standard));
        // What the semantic pass counted as module data (predefined data is not RAPID
        // memory).
        let module_values = prog
            .globals
            .iter()
            .filter(|g| matches!(g.origin, GlobalOrigin::Module(_)))
            .map(|g| prog.types.values(g.ty, &g.dims))
            .fold(0u64, u64::saturating_add);
        Interp {
            prog,
            code,
            natives,
            host,
            globals: Vec::new(),
            stack: Vec::with_capacity(1024),
            sp: 0,
            nslab: Vec::with_capacity(256),
            nbp: 0,
            ntop: 0,
            refs: Vec::with_capacity(64),
            frames: Vec::with_capacity(64),
            idx: Vec::with_capacity(16),
            nargs: Vec::with_capacity(32),
            bp: 0,
            rbp: 0,
            ret: Value::Absent,
            pending: None,
            strbufs: Vec::new(),
            spare_records: value::Spares::default(),
            late_name: String::new(),
            late_args: rustc_hash::FxHashMap::default(),
            late_sites: rustc_hash::FxHashMap::default(),
            stack_base: 0,
            stack_budget: 1 << 20,
            errno: 0,
            intno: 0,
            next_booked: errnum::BOOK_FIRST,
            retry_limit: 4,
            ints: Interrupts::default(),
            operator: operator::Operator::nobody(),
            steps: 0,
            next_poll: u64::MAX,
            budget: None,
            hook: None,
            service: None,
            stop: None,
            initialised: false,
            module_values,
            data_values: module_values,
            files: files::Files::default(),
            task: None,
            registry: Arc::new(registry.clone()),
            engine,
            modules: relink::Modules::default(),
        }
    }

    /// The program.
    pub fn program(&self) -> &Arc<Program> {
        &self.prog
    }

    /// The host.
    pub fn host(&self) -> &dyn Host {
        self.host.as_ref()
    }

    /// The host, mutably.
    pub fn host_mut(&mut self) -> &mut dyn Host {
        self.host.as_mut()
    }

    /// Take the host back (after a run).
    pub fn into_host(self) -> Box<dyn Host> {
        self.host
    }

    /// Limit the number of steps executed (an operation budget: every statement is a step,
    /// and so is every iteration of a loop with an empty body); `None` = unlimited.
    pub fn set_budget(&mut self, max_statements: Option<u64>) {
        self.budget = max_statements;
        self.update_poll();
    }

    /// Install a hook called before every statement.
    pub fn set_hook(&mut self, hook: Option<StmtHook>) {
        self.hook = hook;
        self.update_poll();
    }

    /// Install the service hook: called with the interpreter before every statement and on
    /// every turn of a wait (waits then last at most [`SERVICE_WAIT_SLICE_S`] per turn).
    /// [`HookAction::Stop`] stops the program as `Stop` does; [`HookAction::Abort`] aborts.
    pub fn set_service_hook(&mut self, hook: Option<ServiceHook>) {
        self.service = hook;
        self.update_poll();
    }

    /// Run the service hook, if any (between statements and in waits).
    fn run_service_hook(&mut self) -> HookAction {
        match self.service.take() {
            Some(mut h) => {
                let action = h(self);
                if self.service.is_none() {
                    self.service = Some(h);
                }
                action
            }
            None => HookAction::Continue,
        }
    }

    /// Stop the program as `Stop` does (the run ends with [`Outcome::Stopped`]) once `flag`
    /// turns true: checked at least every [`STOP_CHECK_EVERY`] statements and on every turn
    /// of a wait. A host that blocks for long (the controller) should watch the flag too.
    pub fn set_stop_request(&mut self, flag: Arc<AtomicBool>) {
        self.stop = Some(flag);
        self.update_poll();
    }

    /// True once a stop was requested (see [`Interp::set_stop_request`]).
    pub fn stop_requested(&self) -> bool {
        self.stop
            .as_ref()
            .is_some_and(|f| f.load(Ordering::Relaxed))
    }

    /// How much of the calling thread's stack a run may use (default 1 MiB, safe on a
    /// thread with the standard 2 MiB stack); deeper RAPID recursion stops the program with
    /// a clear error instead of overflowing the stack.
    pub fn set_stack_budget(&mut self, bytes: usize) {
        self.stack_budget = bytes;
    }

    /// The controller's mass storage the program's file instructions use (default: fresh
    /// directories under the system's temporary directory, made on first use). Files still
    /// open are closed.
    pub fn set_mass_storage(&mut self, storage: Arc<crate::mass_storage::MassStorage>) {
        self.files.close_all();
        self.files = files::Files::new(storage);
    }

    /// Where the dialogs (`TPReadFK`, `UIMessageBox`, …) get their answers (default:
    /// nobody answers, see [`operator`]).
    pub fn set_operator(&mut self, op: operator::Operator) {
        self.operator = op;
    }

    /// The dialogs' answer source (e.g. to warn about answers left unused).
    pub fn operator(&self) -> &operator::Operator {
        &self.operator
    }

    /// How many consecutive `RETRY`s of one statement are allowed (default 4).
    pub fn set_retry_limit(&mut self, n: u32) {
        self.retry_limit = n;
    }

    /// Statements executed so far.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Initialise module data (VAR, CONST, and PERS without a stored value), in dependency
    /// order. Called by [`Interp::run`] when needed; call it first to override persistents.
    pub fn init(&mut self) -> Result<(), Box<RuntimeError>> {
        self.stack_base = call::stack_addr();
        let prog = self.prog.clone();
        self.globals = prog
            .globals
            .iter()
            .map(|g| value::default_value(&prog.types, g.ty, &g.dims))
            .collect();
        for (i, g) in prog.globals.iter().enumerate() {
            match &g.origin {
                GlobalOrigin::ErrConst(n) => self.globals[i] = Value::Num(*n as f32),
                GlobalOrigin::NumConst(x) => self.globals[i] = Value::Num(*x as f32),
                GlobalOrigin::Signal(name) | GlobalOrigin::MecUnit(name) => {
                    self.globals[i] = Value::Record(Box::new([Value::str(name)]));
                }
                GlobalOrigin::Module(_) => {}
            }
        }
        for &gid in &prog.init_order {
            let g = &prog.globals[gid.0 as usize];
            if let Some(init) = &g.init {
                let v = match self.eval(&prog, init) {
                    Ok(v) => v,
                    Err(u) => return Err(self.unwind_to_error(u)),
                };
                self.globals[gid.0 as usize] = v;
            }
        }
        self.initialised = true;
        Ok(())
    }

    /// Run a procedure without arguments (usually `main`) to its end.
    pub fn run(&mut self, entry: &str) -> Result<Outcome, Box<RuntimeError>> {
        if !self.initialised {
            self.init()?;
        }
        self.stack_base = call::stack_addr();
        let prog = self.prog.clone();
        let rid = Self::entry_point(&prog, entry)?;
        let r = prog.routine(rid);
        let args: Vec<crate::ir::Arg> = r.params.iter().map(|_| crate::ir::Arg::Absent).collect();
        let res = self.call_routine(&prog, rid, &args, r.head_span);
        self.publish_shared();
        self.data_values = self.module_values;
        self.frames.clear();
        self.stack.clear();
        self.sp = 0;
        self.refs.clear();
        (self.bp, self.rbp) = (0, 0);
        match res {
            Ok(_) => Ok(Outcome::Completed),
            Err(Unwind::Exit) => Ok(Outcome::Exited),
            Err(Unwind::ExitCycle) => Ok(Outcome::ExitCycle),
            Err(Unwind::Stop) => Ok(Outcome::Stopped),
            Err(u) => Err(self.unwind_to_error(u)),
        }
    }

    /// The procedure `entry` names, if a run can start there (a PROC without required
    /// parameters); front ends check it before they start anything.
    pub fn entry_point(prog: &Program, entry: &str) -> Result<RoutineId, Box<RuntimeError>> {
        let Some(rid) = prog.find_proc(entry) else {
            return Err(Box::new(RuntimeError {
                kind: ErrorKind::Rapid(errnum::ERR_REFUNKPRC),
                message: if entry.trim().is_empty() {
                    "the name of the procedure to start is empty".to_string()
                } else {
                    format!("there is no procedure `{entry}` to start")
                },
                span: Span::default(),
                stack: Vec::new(),
            }));
        };
        let r = prog.routine(rid);
        if r.kind != RoutineKind::Proc || r.params.iter().any(|p| !p.optional) {
            return Err(Box::new(RuntimeError {
                kind: ErrorKind::Rapid(errnum::ERR_CALLPROC),
                message: format!("`{}` is not a procedure without parameters", r.name),
                span: r.head_span,
                stack: Vec::new(),
            }));
        }
        Ok(rid)
    }

    /// Turn an unexpected unwind at the top level into an error.
    fn unwind_to_error(&self, u: Unwind) -> Box<RuntimeError> {
        match u {
            Unwind::Error(e) | Unwind::Propagate(e) | Unwind::Fatal(e) => e,
            other => Box::new(RuntimeError {
                kind: ErrorKind::Aborted,
                message: format!("unexpected {other:?} at the top level"),
                span: Span::default(),
                stack: Vec::new(),
            }),
        }
    }

    /// Current values of the program's persistents (the stdlib's are not included).
    pub fn persistents(&self) -> Vec<pers::PersValue> {
        self.prog
            .globals
            .iter()
            .enumerate()
            .filter(|(_, g)| g.storage == Storage::Pers)
            .filter(|(_, g)| match g.origin {
                GlobalOrigin::Module(m) => !self.prog.modules[m.0 as usize].stdlib,
                _ => false,
            })
            .filter_map(|(i, g)| {
                Some(pers::PersValue {
                    name: g.name.clone(),
                    ty: self.prog.types.name(g.ty.base).to_string(),
                    dims: g.dims.clone(),
                    task: g.task,
                    value: self.globals.get(i)?.clone(),
                })
            })
            .collect()
    }

    /// Names and current values of the program's module data (VAR, PERS and CONST of its
    /// own modules, in declaration order; the stdlib's are not included).
    pub fn module_data(&self) -> Vec<(String, Value)> {
        self.prog
            .globals
            .iter()
            .zip(&self.globals)
            .filter(|(g, _)| match g.origin {
                GlobalOrigin::Module(m) => !self.prog.modules[m.0 as usize].stdlib,
                _ => false,
            })
            .map(|(g, v)| (g.name.clone(), v.clone()))
            .collect()
    }

    /// Overwrite persistents with stored values (after [`Interp::init`]). Returns the
    /// entries the program does not declare (to keep them) and warnings for entries whose
    /// value does not fit the declared type (the program's value is kept for those).
    pub fn load_persistents(
        &mut self,
        entries: &[pers::PersEntry],
    ) -> (Vec<pers::PersEntry>, Vec<String>) {
        let mut unknown = Vec::new();
        let mut warnings = Vec::new();
        for e in entries {
            let idx = self.prog.globals.iter().position(|g| {
                g.storage == Storage::Pers
                    && g.name.eq_ignore_ascii_case(&e.name)
                    && matches!(g.origin, GlobalOrigin::Module(m)
                        if !self.prog.modules[m.0 as usize].stdlib)
            });
            let Some(i) = idx else {
                unknown.push(e.clone());
                continue;
            };
            let g = &self.prog.globals[i];
            let declared = self.prog.types.name(g.ty.base);
            if !declared.eq_ignore_ascii_case(&e.ty) || g.dims != e.dims {
                warnings.push(format!(
                    "line {}: persistent `{}` is stored as `{}{}` but declared as `{declared}{}`; the declared value is used",
                    e.line,
                    e.name,
                    e.ty,
                    pers::dims_text(&e.dims),
                    pers::dims_text(&g.dims)
                ));
                continue;
            }
            let Some(slot) = self.globals.get_mut(i) else {
                continue;
            };
            let mut v = slot.clone();
            if pers::fill(&mut v, &e.value) {
                *slot = v;
            } else {
                warnings.push(format!(
                    "line {}: stored value of persistent `{}` does not fit its declaration; the declared value is used",
                    e.line, e.name
                ));
            }
        }
        (unknown, warnings)
    }

    /// Recompute when the per-statement slow path must run.
    fn update_poll(&mut self) {
        let every = self.hook.is_some() || self.service.is_some() || self.ints.armed();
        self.next_poll = if every {
            self.steps + 1
        } else {
            match self.budget {
                Some(b) => b.max(self.steps + 1),
                None => u64::MAX,
            }
        };
        if self.stop.is_some() {
            self.next_poll = self.next_poll.min(self.steps + STOP_CHECK_EVERY);
        }
        self.next_poll = self.next_poll.min(self.next_task_switch());
    }

    /// Build a RAPID error at `span` with the current call stack.
    fn error(&self, errno: i32, span: Span, message: impl Into<String>) -> Unwind {
        Unwind::Error(self.make_error(ErrorKind::Rapid(errno), span, message))
    }

    /// Build a fatal error at `span` with the current call stack.
    fn fatal(&self, kind: ErrorKind, span: Span, message: impl Into<String>) -> Unwind {
        Unwind::Fatal(self.make_error(kind, span, message))
    }

    fn make_error(
        &self,
        kind: ErrorKind,
        span: Span,
        message: impl Into<String>,
    ) -> Box<RuntimeError> {
        let mut stack = Vec::with_capacity(self.frames.len());
        for (k, f) in self.frames.iter().enumerate().rev() {
            let at = if k + 1 == self.frames.len() {
                span
            } else {
                f.at
            };
            stack.push(StackEntry {
                routine: self.prog.routine(f.routine).name.clone(),
                span: at,
            });
        }
        Box::new(RuntimeError {
            kind,
            message: message.into(),
            span,
            stack,
        })
    }

    /// A runtime-library failure as the RAPID error it names.
    fn rt_error(&self, e: crate::functions::RtError, span: Span) -> Unwind {
        match errnum::by_name(e.err_name()) {
            Some(d) => self.error(d.num, span, e.to_string()),
            None => self.fatal(ErrorKind::Host, span, e.to_string()),
        }
    }

    fn host_error(&self, e: HostError, span: Span) -> Unwind {
        // A host that gave up because a stop was requested: the program stops.
        if self.stop_requested() {
            return Unwind::Stop;
        }
        match e.errno {
            Some(n) => self.error(n, span, e.message),
            None => self.fatal(ErrorKind::Host, span, e.message),
        }
    }
}
