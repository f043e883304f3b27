//! The resolved program the interpreter walks: names are gone (data live in numbered slots,
//! calls point at routines or natives by index), types are checked, spans are kept for
//! run-time errors. Produced by `sema`, consumed by `interp`.

pub mod errnum;
pub mod limits;
pub mod sig;
pub mod types;

use std::collections::HashMap;
use std::sync::Arc;

pub use crate::ast::{ParamMode, Storage};
use crate::source::{SourceId, Span};
pub use sig::{NativeSig, SigParam, SigType};
pub use types::{Field, Ty, TypeDef, TypeId, TypeKind, TypeTable};

/// Index of a module in [`Program::modules`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ModuleId(pub u32);
/// Index of a routine in [`Program::routines`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct RoutineId(pub u32);
/// Index of a native (built-in) routine in the native registry the program was checked with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct NativeId(pub u32);
/// Index of a module-level data object in [`Program::globals`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct GlobalId(pub u32);

/// A checked program: every loaded module (stdlib included), ready to run.
#[derive(Debug)]
pub struct Program {
    /// All types.
    pub types: TypeTable,
    /// Modules in load order (stdlib first).
    pub modules: Vec<ModuleInfo>,
    /// Module-level data (and predefined data such as `ERR_*` and I/O signals).
    pub globals: Vec<Global>,
    /// Routines of every module.
    pub routines: Vec<Routine>,
    /// Names of the natives the program was checked against (index = [`NativeId`]).
    pub natives: Arc<[NativeSig]>,
    /// Order in which module data are initialised (constants before their users).
    pub init_order: Vec<GlobalId>,
    /// Procedures reachable by name at run time (late binding, entry points): folded name →
    /// routines with that name (global ones and `LOCAL` ones of each module).
    pub procs_by_name: HashMap<String, Vec<RoutineId>, rustc_hash::FxBuildHasher>,
}

impl Program {
    /// The routine with this id.
    pub fn routine(&self, id: RoutineId) -> &Routine {
        &self.routines[id.0 as usize]
    }

    /// A global procedure without parameters, by case-insensitive name (an entry point).
    pub fn find_proc(&self, name: &str) -> Option<RoutineId> {
        let list = self.procs_by_name.get(&name.to_ascii_uppercase())?;
        list.iter()
            .copied()
            .find(|&r| !self.routine(r).local)
            .or_else(|| list.first().copied())
    }
}

/// One loaded module.
#[derive(Debug, Clone)]
pub struct ModuleInfo {
    /// Module name as written.
    pub name: String,
    /// File it came from.
    pub source: SourceId,
    /// Part of the embedded stdlib.
    pub stdlib: bool,
    /// A system module: the stdlib's, or one declared `(SYSMODULE)` (a task's user.sys).
    pub system: bool,
}

/// Where a global came from.
#[derive(Debug, Clone, PartialEq)]
pub enum GlobalOrigin {
    /// Declared in a module.
    Module(ModuleId),
    /// A predefined error number constant (`ERR_*`).
    ErrConst(i32),
    /// A numeric predefined constant (e.g. `pi`).
    NumConst(f64),
    /// An I/O signal from the configuration: its name.
    Signal(String),
    /// A mechanical unit (`ROB_1`).
    MecUnit(String),
}

/// A module-level data object.
#[derive(Debug, Clone)]
pub struct Global {
    /// Name as declared.
    pub name: String,
    /// Origin.
    pub origin: GlobalOrigin,
    /// `LOCAL` to its module.
    pub local: bool,
    /// `TASK PERS`.
    pub task: bool,
    /// VAR, PERS or CONST.
    pub storage: Storage,
    /// Its type.
    pub ty: Ty,
    /// Array sizes (empty for scalars).
    pub dims: Vec<u32>,
    /// Initial value (absent: default value, or for PERS the stored value). Boxed: a large
    /// module holds hundreds of thousands of globals, and `rapidvc check` keeps none.
    pub init: Option<Box<Expr>>,
    /// The declaration.
    pub span: Span,
}

/// Kinds of routines.
#[derive(Debug, Clone, PartialEq)]
pub enum RoutineKind {
    /// PROC
    Proc,
    /// FUNC with its return type.
    Func(Ty),
    /// TRAP
    Trap,
}

/// Where a parameter lives in its frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamSlot {
    /// A value slot (IN parameters and switches).
    Value(u32),
    /// A reference slot (INOUT, VAR, PERS).
    Ref(u32),
}

/// A parameter of a user routine.
#[derive(Debug, Clone)]
pub struct ParamInfo {
    /// Name as declared.
    pub name: String,
    /// Type (`switch` for switches).
    pub ty: Ty,
    /// Access mode.
    pub mode: ParamMode,
    /// Optional (`\`).
    pub optional: bool,
    /// Index of its alternatives group (parameters of one `\a | b` group share it).
    pub group: u16,
    /// Frame slot.
    pub slot: ParamSlot,
    /// Declaration span.
    pub span: Span,
}

/// A routine-level data declaration, initialised on every call.
#[derive(Debug, Clone)]
pub struct LocalDecl {
    /// Name.
    pub name: String,
    /// Type.
    pub ty: Ty,
    /// Array sizes.
    pub dims: Vec<u32>,
    /// Initial value.
    pub init: Option<Expr>,
    /// Value slot.
    pub slot: u32,
    /// Declaration span.
    pub span: Span,
}

/// A PROC, FUNC or TRAP.
#[derive(Debug, Clone)]
pub struct Routine {
    /// Name as declared.
    pub name: String,
    /// Its module.
    pub module: ModuleId,
    /// `LOCAL`.
    pub local: bool,
    /// Kind.
    pub kind: RoutineKind,
    /// Parameters in declaration order (alternatives flattened).
    pub params: Vec<ParamInfo>,
    /// Routine data, in declaration order.
    pub locals: Vec<LocalDecl>,
    /// Number of value slots (parameters, locals, FOR variables).
    pub n_slots: u32,
    /// Number of reference slots.
    pub n_refs: u32,
    /// Statements.
    pub body: Block,
    /// ERROR handler.
    pub error: Option<Handler>,
    /// UNDO handler.
    pub undo: Option<Block>,
    /// Whole routine.
    pub span: Span,
    /// Header.
    pub head_span: Span,
    /// The body is a single `RETURN expr` with no routine data, handlers or reference
    /// parameters (the interpreter calls such functions without a statement loop).
    pub simple: bool,
}

/// An `ERROR [(…)]` handler.
#[derive(Debug, Clone)]
pub struct Handler {
    /// Error numbers it takes (`None`: all).
    pub errnos: Option<Vec<Expr>>,
    /// Statements.
    pub body: Block,
    /// The `ERROR` keyword.
    pub span: Span,
}

/// A statement list with the labels defined directly in it.
#[derive(Debug, Clone, Default)]
pub struct Block {
    /// Statements.
    pub stmts: Vec<Stmt>,
    /// (label id, index of the label statement).
    pub labels: Vec<(u32, u32)>,
}

/// A statement.
#[derive(Debug, Clone)]
pub struct Stmt {
    /// What it does.
    pub kind: StmtKind,
    /// Source.
    pub span: Span,
}

/// Statement shapes.
#[derive(Debug, Clone)]
pub enum StmtKind {
    /// `place := value`.
    Assign {
        /// Target.
        place: Place,
        /// Value.
        value: Expr,
    },
    /// `place := value` where both are `num` (evaluated without boxing the value).
    AssignNum {
        /// Target.
        place: Place,
        /// Value.
        value: Expr,
    },
    /// Call of a user procedure.
    Call {
        /// Callee.
        routine: RoutineId,
        /// One entry per callee parameter.
        args: Box<[Arg]>,
    },
    /// Call of a native instruction.
    Native {
        /// Callee.
        native: NativeId,
        /// One entry per native parameter.
        args: Box<[Arg]>,
    },
    /// `% name % args;`
    LateCall {
        /// Procedure name expression.
        name: Expr,
        /// Arguments as written.
        args: Vec<LateArg>,
        /// Calling module (for `LOCAL` lookup).
        module: ModuleId,
    },
    /// IF / ELSEIF / ELSE (compact IF too).
    If {
        /// Condition and branch, in order.
        branches: Vec<(Expr, Block)>,
        /// ELSE branch.
        else_body: Option<Block>,
    },
    /// WHILE.
    While {
        /// Condition.
        cond: Expr,
        /// Body.
        body: Block,
    },
    /// FOR.
    For {
        /// Slot of the loop variable.
        slot: u32,
        /// Start.
        from: Expr,
        /// End.
        to: Expr,
        /// Step.
        step: Option<Expr>,
        /// Body.
        body: Block,
    },
    /// TEST.
    Test {
        /// Tested value.
        subject: Expr,
        /// CASE lists and bodies.
        cases: Vec<(Vec<Expr>, Block)>,
        /// DEFAULT body.
        default: Option<Block>,
    },
    /// A label (no effect).
    Label(u32),
    /// GOTO label.
    Goto(u32),
    /// RETURN.
    Return(Option<Expr>),
    /// RAISE.
    Raise(Option<Expr>),
    /// RETRY.
    Retry,
    /// TRYNEXT.
    TryNext,
    /// EXIT.
    Exit,
    /// CONNECT intno WITH trap.
    Connect {
        /// The interrupt variable.
        place: Place,
        /// The trap.
        trap: RoutineId,
    },
    /// A placeholder left in the program (running into it is an error).
    Placeholder(&'static str),
}

/// An argument of a call, lowered for the callee's parameter at the same index.
#[derive(Debug, Clone)]
pub enum Arg {
    /// Optional parameter not passed.
    Absent,
    /// An IN argument.
    Value(Expr),
    /// An INOUT/VAR/PERS argument.
    Ref(Place),
    /// A switch that was passed.
    Switch,
    /// `\p ? q`: passed only when the caller's optional parameter is present.
    Cond {
        /// The caller's parameter.
        param: ParamSlot,
        /// What is passed when it is present.
        arg: Box<Arg>,
    },
}

/// An argument of a late-bound call (matched to parameters at run time).
#[derive(Debug, Clone)]
pub struct LateArg {
    /// `\name` or `name :=` for optional/named arguments.
    pub name: Option<String>,
    /// The value; `None` for a switch.
    pub value: Option<Expr>,
    /// The argument as a place when it is one (passed by reference to INOUT/VAR/PERS).
    pub place: Option<Place>,
    /// Source.
    pub span: Span,
}

/// A storage location expression.
#[derive(Debug, Clone)]
pub struct Place {
    /// Where the chain starts.
    pub root: Root,
    /// Components and elements, outermost first.
    pub path: Box<[PathOp]>,
    /// Source.
    pub span: Span,
}

/// The start of a place.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Root {
    /// A value slot in the current frame.
    Local(u32),
    /// A reference slot in the current frame (INOUT/VAR/PERS parameter).
    Ref(u32),
    /// Module-level data.
    Global(u32),
}

/// One step of a place.
#[derive(Debug, Clone)]
pub enum PathOp {
    /// Record component by index.
    Field(u16),
    /// Array element (1-based indices).
    Index(Box<[Expr]>),
}

/// An expression with its source.
#[derive(Debug, Clone)]
pub struct Expr {
    /// What it computes.
    pub kind: ExprKind,
    /// Source.
    pub span: Span,
}

/// Expression shapes.
#[derive(Debug, Clone)]
pub enum ExprKind {
    /// `num` constant (already rounded to single precision).
    Num(f32),
    /// `dnum` constant.
    Dnum(f64),
    /// `bool` constant.
    Bool(bool),
    /// `string` constant.
    Str(Arc<str>),
    /// Whole value of a local slot.
    Local(u32),
    /// Whole value of a global.
    Global(u32),
    /// Any other place (references, components, elements).
    Load(Box<Place>),
    /// A component of a computed record (`CRobT().trans`).
    Field(Box<Expr>, u16),
    /// The current value of an I/O signal used as a number (`di1 = 1`).
    SignalValue(Box<Expr>),
    /// The system variable `ERRNO`.
    Errno,
    /// The system variable `INTNO`.
    Intno,
    /// `Present(param)`.
    Present(ParamSlot),
    /// Prefix operator.
    Unary(UnOp, Box<Expr>),
    /// Infix operator.
    Binary(BinOp, Box<Expr>, Box<Expr>),
    /// `num MOD k` or `num DIV k` with a constant integer `k` ≠ 0 (true for MOD).
    NumModDivK(Box<Expr>, i32, bool),
    /// num → dnum.
    ToDnum(Box<Expr>),
    /// dnum → num.
    ToNum(Box<Expr>),
    /// User function call.
    Call(RoutineId, Box<[Arg]>),
    /// Native function call.
    Native(NativeId, Box<[Arg]>),
    /// Record aggregate.
    Record(Box<[Expr]>),
    /// Array aggregate (row-major elements) with its sizes.
    Array(Box<[Expr]>, Box<[u32]>),
    /// A placeholder such as `<EXP>`.
    Placeholder(&'static str),
}

/// Typed prefix operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnOp {
    /// `-num`
    NumNeg,
    /// `-dnum`
    DnumNeg,
    /// `-pos`
    PosNeg,
    /// `NOT bool`
    Not,
}

/// Typed infix operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    /// num + num
    NumAdd,
    /// num - num
    NumSub,
    /// num * num
    NumMul,
    /// num / num
    NumDiv,
    /// num DIV num
    NumIntDiv,
    /// num MOD num
    NumMod,
    /// num < num
    NumLt,
    /// num <= num
    NumLe,
    /// num > num
    NumGt,
    /// num >= num
    NumGe,
    /// num = num
    NumEq,
    /// num <> num
    NumNe,
    /// dnum + dnum
    DnumAdd,
    /// dnum - dnum
    DnumSub,
    /// dnum * dnum
    DnumMul,
    /// dnum / dnum
    DnumDiv,
    /// dnum DIV dnum
    DnumIntDiv,
    /// dnum MOD dnum
    DnumMod,
    /// dnum < dnum
    DnumLt,
    /// dnum <= dnum
    DnumLe,
    /// dnum > dnum
    DnumGt,
    /// dnum >= dnum
    DnumGe,
    /// string + string
    Concat,
    /// bool AND bool
    And,
    /// bool OR bool
    Or,
    /// bool XOR bool
    Xor,
    /// pos + pos
    PosAdd,
    /// pos - pos
    PosSub,
    /// pos * pos (cross product)
    PosCross,
    /// num * pos
    NumPos,
    /// pos * num
    PosNum,
    /// orient * orient (quaternion product)
    OrientMul,
    /// Structural equality of any value type.
    Eq,
    /// Structural inequality.
    Ne,
}

impl BinOp {
    /// `+ - * / DIV MOD` on `num`.
    pub fn is_num_arith(self) -> bool {
        matches!(
            self,
            BinOp::NumAdd
                | BinOp::NumSub
                | BinOp::NumMul
                | BinOp::NumDiv
                | BinOp::NumIntDiv
                | BinOp::NumMod
        )
    }
}
