//! The untyped RAPID syntax tree, as written: names keep their original spelling, every node
//! carries a [`Span`]. Produced by `parse`, consumed by `sema`.
//!
//! Names are compared case-folded everywhere (RAPID is case-insensitive); use
//! [`Ident::folded`] rather than comparing `node` strings directly.

use crate::source::{SourceId, SourceText, Span, Spanned};

mod dump;
pub(crate) mod literal;

/// A name as written: [`EcoString`] keeps up to 15 bytes without an allocation (nearly every
/// RAPID name), and reads as a `&str`.
pub use ecow::EcoString;

/// An identifier with its original spelling and position.
pub type Ident = Spanned<EcoString>;

impl Ident {
    /// The case-folded (ASCII upper-case) spelling used for all name comparisons.
    pub fn folded(&self) -> String {
        self.node.as_str().to_ascii_uppercase()
    }

    /// Case-insensitive comparison with a name.
    pub fn is(&self, name: &str) -> bool {
        self.node.eq_ignore_ascii_case(name)
    }
}

/// One parsed file: one or more modules.
#[derive(Debug, Clone)]
pub struct File {
    /// The modules, in file order.
    pub modules: Vec<Module>,
    /// The whole file.
    pub span: Span,
    /// The text of the file (shared with the [`crate::source::SourceMap`], not a copy):
    /// packed aggregates ([`ExprKind::PackedAggregate`]) and packed call arguments
    /// ([`CallArgs::Packed`]) are read from it.
    pub text: SourceText,
}

/// `MODULE name [(attrs)] … ENDMODULE`.
#[derive(Debug, Clone)]
pub struct Module {
    /// Module name.
    pub name: Ident,
    /// Attributes in parentheses after the name.
    pub attrs: Vec<Spanned<ModuleAttr>>,
    /// Declarations and routines, in source order.
    pub items: Vec<ModuleItem>,
    /// From `MODULE` to `ENDMODULE`.
    pub span: Span,
}

/// Module attributes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModuleAttr {
    /// `SYSMODULE`
    SysModule,
    /// `NOSTEPIN`
    NoStepIn,
    /// `READONLY`
    ReadOnly,
    /// `VIEWONLY`
    ViewOnly,
    /// `NOVIEW`
    NoView,
}

/// Something declared at module level. (Each kind is boxed: a large module's list of items
/// is then 16 bytes an item, and is copied once when the pieces of a module parsed on
/// several threads are put together.)
#[derive(Debug, Clone)]
pub enum ModuleItem {
    /// `RECORD … ENDRECORD`
    Record(Box<RecordDecl>),
    /// `ALIAS base name;`
    Alias(Box<AliasDecl>),
    /// `VAR`/`PERS`/`CONST` data.
    Data(Box<DataDecl>),
    /// `VAR`/`PERS`/`CONST` data of the simplest shape, kept as its text (see
    /// [`PackedData`]): most items of a large module. [`ModuleItem::data`] gives the
    /// declaration of either form.
    PackedData(PackedData),
    /// `PROC`/`FUNC`/`TRAP`.
    Routine(Box<Routine>),
    /// A placeholder (`<TDN>`, `<DDN>`, `<RDN>`) standing for a declaration.
    Placeholder(Spanned<Placeholder>),
}

impl ModuleItem {
    /// The name this item declares in its module's scope, and where (`text` is the file's,
    /// in which a packed declaration's name is read without reading the rest of it).
    pub fn name<'a>(&'a self, source: SourceId, text: &'a str) -> Option<(&'a str, Span)> {
        let ident = |id: &'a Ident| (id.node.as_str(), id.span);
        match self {
            ModuleItem::Record(r) => Some(ident(&r.name)),
            ModuleItem::Alias(a) => Some(ident(&a.name)),
            ModuleItem::Data(d) => Some(ident(&d.name)),
            ModuleItem::PackedData(d) => Some(d.name(source, text)),
            ModuleItem::Routine(r) => Some(ident(&r.name)),
            ModuleItem::Placeholder(_) => None,
        }
    }

    /// The data declaration of a [`ModuleItem::Data`] or [`ModuleItem::PackedData`] item
    /// (`None` for any other item), in the file `source` whose text is `text`
    /// ([`File::text`]).
    pub fn data(&self, source: SourceId, text: &str) -> Option<std::borrow::Cow<'_, DataDecl>> {
        match self {
            ModuleItem::Data(d) => Some(std::borrow::Cow::Borrowed(d)),
            ModuleItem::PackedData(p) => Some(std::borrow::Cow::Owned(p.unpack(source, text))),
            _ => None,
        }
    }
}

/// A module data declaration kept as its text in the file ([`File::text`]): `[LOCAL] [TASK]
/// VAR|PERS|CONST type name [:= value];` without array dimensions, the value a name, a plain
/// literal or a literal aggregate, as target and tool data are written. It is 8 bytes inside
/// its [`ModuleItem`] instead of a boxed [`DataDecl`] of 160. The parser packs a declaration
/// only when reading its text back gives the declaration it built, spans included
/// (`ast/literal.rs`), so unpacking cannot fail.
#[derive(Clone, Copy, PartialEq, Eq)]
pub struct PackedData {
    /// The first byte of the declaration.
    start: u32,
    /// The byte after its `;`.
    end: u32,
}

impl PackedData {
    /// The declaration `decl` written in `text` (the text of the file `source`), packed when
    /// reading it back gives `decl` again.
    pub(crate) fn pack(source: SourceId, text: &str, decl: &DataDecl) -> Option<Self> {
        let (start, end) = (decl.span.start as usize, decl.span.end as usize);
        let simple = decl.dims.is_empty()
            && match decl.init.as_ref().map(|e| &e.kind) {
                None
                | Some(
                    ExprKind::PackedAggregate(_)
                    | ExprKind::Num(_)
                    | ExprKind::Str(_)
                    | ExprKind::Bool(_)
                    | ExprKind::Name(_)
                    | ExprKind::Unary { .. },
                ) => true,
                Some(_) => false,
            };
        // (A packed aggregate value was just read by the parser: its end is known.)
        let aggregate_end = match &decl.init {
            Some(Expr {
                kind: ExprKind::PackedAggregate(_),
                span,
            }) => (span.end as usize).checked_sub(start),
            _ => None,
        };
        let read = literal::read_data_decl(source, text.get(start..end)?, start, aggregate_end);
        (simple && read.as_ref() == Some(decl)).then_some(PackedData {
            start: start as u32,
            end: end as u32,
        })
    }

    /// The declaration as written in the file's `text`.
    pub fn text<'t>(&self, text: &'t str) -> &'t str {
        text.get(self.start as usize..self.end as usize)
            .unwrap_or("")
    }

    /// The whole declaration, in the file `source`.
    pub fn span(&self, source: SourceId) -> Span {
        Span::new(source, self.start as usize, self.end as usize)
    }

    /// The declared name as written in the file's `text`, and where (in the file `source`),
    /// without reading the rest of the declaration.
    pub fn name<'t>(&self, source: SourceId, text: &'t str) -> (&'t str, Span) {
        let mut pos = 0;
        let (a, z) = literal::read_data_head(self.text(text), &mut pos).map_or((0, 0), |h| h.name);
        let at = self.start as usize;
        (
            text.get(at + a..at + z).unwrap_or(""),
            Span::new(source, at + a, at + z),
        )
    }

    /// The [`DataDecl`] of this declaration in the file `source` whose text is `text`: the one
    /// the parser built, node for node.
    pub fn unpack(&self, source: SourceId, text: &str) -> DataDecl {
        literal::read_data_decl(source, self.text(text), self.start as usize, None).unwrap_or_else(
            || {
                // (Not reached: the text was read back when it was packed. A declaration without
                // a type would be reported as an unknown type, so it would not go unnoticed.)
                let span = self.span(source);
                DataDecl {
                    local: false,
                    task: false,
                    storage: Storage::Var,
                    ty: Spanned::new(EcoString::new(), span),
                    name: Spanned::new(EcoString::new(), span),
                    dims: Vec::new(),
                    init: None,
                    span,
                }
            },
        )
    }
}

impl std::fmt::Debug for PackedData {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "PackedData({}..{})", self.start, self.end)
    }
}

/// `[LOCAL] RECORD name  type comp; …  ENDRECORD`.
#[derive(Debug, Clone)]
pub struct RecordDecl {
    /// `LOCAL` was given.
    pub local: bool,
    /// Type name.
    pub name: Ident,
    /// Components in order.
    pub fields: Vec<RecordField>,
    /// From `RECORD` (or `LOCAL`) to `ENDRECORD`.
    pub span: Span,
}

/// One `type name [{dims}];` line of a record.
#[derive(Debug, Clone)]
pub struct RecordField {
    /// Component type name.
    pub ty: Ident,
    /// Component name.
    pub name: Ident,
    /// Array dimensions, empty for a scalar.
    pub dims: Vec<Expr>,
    /// The whole line.
    pub span: Span,
}

/// `[LOCAL] ALIAS base name;`.
#[derive(Debug, Clone)]
pub struct AliasDecl {
    /// `LOCAL` was given.
    pub local: bool,
    /// The existing type.
    pub base: Ident,
    /// The new name.
    pub name: Ident,
    /// The whole declaration.
    pub span: Span,
}

/// Storage class of data.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Storage {
    /// `VAR`
    Var,
    /// `PERS`
    Pers,
    /// `CONST`
    Const,
}

/// `[LOCAL|TASK] VAR|PERS|CONST type name [{dims}] [:= init];`.
#[derive(Debug, Clone, PartialEq)]
pub struct DataDecl {
    /// `LOCAL` was given.
    pub local: bool,
    /// `TASK` was given.
    pub task: bool,
    /// VAR, PERS or CONST.
    pub storage: Storage,
    /// Type name.
    pub ty: Ident,
    /// Data name.
    pub name: Ident,
    /// Array dimensions (`{n}`, `{n,m}`, `{n,m,k}`), empty for a scalar.
    pub dims: Vec<Expr>,
    /// Initial value.
    pub init: Option<Expr>,
    /// The whole declaration including `;`.
    pub span: Span,
}

/// Routine kinds.
#[derive(Debug, Clone)]
pub enum RoutineKind {
    /// `PROC`
    Proc,
    /// `FUNC type`
    Func(Ident),
    /// `TRAP`
    Trap,
}

/// `PROC`, `FUNC` or `TRAP` with its data, statements and handlers.
#[derive(Debug, Clone)]
pub struct Routine {
    /// `LOCAL` was given.
    pub local: bool,
    /// Proc, func (with return type) or trap.
    pub kind: RoutineKind,
    /// Routine name.
    pub name: Ident,
    /// Parameters; each entry is one parameter or a group of mutually exclusive optional
    /// alternatives (`\switch On | switch Off`).
    pub params: Vec<ParamGroup>,
    /// Routine data declarations (VAR/CONST, before the statements).
    pub data: Vec<DataDecl>,
    /// Statements.
    pub body: Vec<Stmt>,
    /// `BACKWARD` section (parsed, never executed).
    pub backward: Option<Vec<Stmt>>,
    /// `ERROR [(errnos)]` section.
    pub error: Option<ErrorHandler>,
    /// `UNDO` section.
    pub undo: Option<Vec<Stmt>>,
    /// From the first keyword to the end keyword.
    pub span: Span,
    /// The header (`PROC name(...)`) only, for diagnostics.
    pub head_span: Span,
}

/// `ERROR [(n1, n2, …)]` handler.
#[derive(Debug, Clone)]
pub struct ErrorHandler {
    /// The error numbers it takes; `None` takes every error.
    pub errnos: Option<Vec<Expr>>,
    /// Handler statements.
    pub body: Vec<Stmt>,
    /// The `ERROR` keyword and list.
    pub span: Span,
}

/// One parameter, or several mutually exclusive optional alternatives.
#[derive(Debug, Clone)]
pub struct ParamGroup {
    /// One entry for a plain parameter; two or more for `\a | b | c`.
    pub alternatives: Vec<Param>,
    /// The whole group.
    pub span: Span,
}

/// Parameter access modes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamMode {
    /// No keyword: a local copy.
    In,
    /// `INOUT`
    InOut,
    /// `VAR`
    Var,
    /// `PERS`
    Pers,
}

/// `[\][mode] type name [{*[,*[,*]]}]`.
#[derive(Debug, Clone)]
pub struct Param {
    /// Declared with a leading `\` (or inside an alternatives group).
    pub optional: bool,
    /// Access mode.
    pub mode: ParamMode,
    /// Type name (`switch` for switches).
    pub ty: Ident,
    /// Parameter name.
    pub name: Ident,
    /// Number of open-array dimensions (`{*}` = 1, `{*,*}` = 2, …), 0 for a scalar.
    pub open_dims: u8,
    /// The parameter, or a `<PAR>`/`<ALT>` placeholder standing for one.
    pub placeholder: Option<Placeholder>,
    /// Its text.
    pub span: Span,
}

/// A statement.
#[derive(Debug, Clone)]
pub struct Stmt {
    /// What it is.
    pub kind: StmtKind,
    /// From its first token to its `;` or end keyword.
    pub span: Span,
}

/// Statement shapes.
#[derive(Debug, Clone)]
pub enum StmtKind {
    /// `target := value;` (target: name, element or component chain).
    Assign {
        /// Assigned place.
        target: Box<Expr>,
        /// New value.
        value: Box<Expr>,
    },
    /// `Name arg, …;` — procedure call (instructions included).
    Call {
        /// Procedure name.
        name: Ident,
        /// Arguments in written order ([`CallArgs::items`] reads them).
        args: CallArgs,
    },
    /// `% expr % arg, …;` — late-bound procedure call.
    LateCall {
        /// Expression giving the procedure name.
        name: Box<Expr>,
        /// Arguments.
        args: Box<[Arg]>,
    },
    /// `IF … THEN … ELSEIF … ELSE … ENDIF`. (Finished lists are boxed slices, 16 bytes
    /// each rather than a vector's 24: this is the largest statement shape, and every
    /// statement takes its size.)
    If {
        /// Condition.
        cond: Box<Expr>,
        /// THEN part.
        then_body: Box<[Stmt]>,
        /// ELSEIF parts in order.
        elseifs: Box<[(Expr, Vec<Stmt>)]>,
        /// ELSE part.
        else_body: Option<Box<[Stmt]>>,
    },
    /// Compact `IF cond stmt;`.
    CompactIf {
        /// Condition.
        cond: Box<Expr>,
        /// The single simple statement.
        stmt: Box<Stmt>,
    },
    /// `WHILE cond DO … ENDWHILE`.
    While {
        /// Condition.
        cond: Box<Expr>,
        /// Body.
        body: Box<[Stmt]>,
    },
    /// `FOR var FROM a TO b [STEP s] DO … ENDFOR`.
    For {
        /// Loop variable (implicitly declared num).
        var: Box<Ident>,
        /// Start.
        from: Box<Expr>,
        /// End.
        to: Box<Expr>,
        /// Step.
        step: Option<Box<Expr>>,
        /// Body.
        body: Box<[Stmt]>,
    },
    /// `TEST e CASE …: … DEFAULT: … ENDTEST`.
    Test {
        /// The tested value.
        subject: Box<Expr>,
        /// CASE clauses in order.
        cases: Box<[TestCase]>,
        /// DEFAULT clause.
        default: Option<Box<[Stmt]>>,
    },
    /// `name:` label.
    Label(Ident),
    /// `GOTO name;`
    Goto(Ident),
    /// `RETURN [expr];`
    Return(Option<Box<Expr>>),
    /// `RAISE [expr];`
    Raise(Option<Box<Expr>>),
    /// `RETRY;`
    Retry,
    /// `TRYNEXT;`
    TryNext,
    /// `EXIT;`
    Exit,
    /// `CONNECT target WITH trap;`
    Connect {
        /// The interrupt variable.
        target: Box<Expr>,
        /// The trap routine.
        trap: Ident,
    },
    /// A placeholder such as `<SMT>` standing for a statement.
    Placeholder(Placeholder),
}

/// One `CASE v1, v2: body`.
#[derive(Debug, Clone)]
pub struct TestCase {
    /// Values compared with `=`.
    pub values: Vec<Expr>,
    /// Statements.
    pub body: Vec<Stmt>,
    /// The `CASE …:` head.
    pub span: Span,
}

/// The arguments of a procedure call statement: a tree, or, for a call whose arguments are
/// all names and plain literals (`MoveL p10, v500, z10, tool0\WObj:=wobj0;`, most of the
/// statements of real programs), their text from the end of the procedure's name to the `;`
/// (about a quarter of the memory of the tree). [`CallArgs::items`] gives the tree either way.
#[derive(Debug, Clone)]
pub enum CallArgs {
    /// Built as a tree.
    Tree(Box<[Arg]>),
    /// Kept as the text after the name (see [`PackedArgs`]).
    Packed(PackedArgs),
}

impl CallArgs {
    /// The arguments of the call whose procedure name is `name`: the tree the parser builds
    /// for them, spans included, whether packed or not. `text` is the text of the file
    /// ([`File::text`]).
    pub fn items(&self, name: &Ident, text: &str) -> std::borrow::Cow<'_, [Arg]> {
        match self {
            CallArgs::Tree(args) => std::borrow::Cow::Borrowed(args),
            CallArgs::Packed(p) => std::borrow::Cow::Owned(p.unpack(text, name.span.end_point())),
        }
    }
}

/// A call's arguments kept as their text in the file ([`File::text`]): from the end of the
/// procedure's name up to and including the `;`, which is where this holds. The parser packs
/// arguments only when reading this text back gives the tree it built (`ast/literal.rs`,
/// [`literal::read_call_args`]), so unpacking cannot fail.
#[derive(Clone, Copy, PartialEq, Eq)]
pub struct PackedArgs {
    /// The byte after the `;`.
    end: u32,
}

impl PackedArgs {
    /// Arguments that read back as the ones the parser built, written up to byte `end` (the
    /// byte after the `;`).
    pub(crate) fn new(end: usize) -> Self {
        PackedArgs { end: end as u32 }
    }

    /// The arguments as written in the file's `text`, from `at` (the end of the procedure's
    /// name) to the `;`.
    pub fn text<'t>(&self, text: &'t str, at: Span) -> &'t str {
        text.get(at.start as usize..self.end as usize).unwrap_or("")
    }

    /// The argument tree of these arguments in the file's `text`, written at `at` (the end of
    /// the procedure's name).
    pub fn unpack(&self, text: &str, at: Span) -> Vec<Arg> {
        // (Not reached: the text was read back when it was packed. No arguments at all
        // would be reported as missing ones, so it would not go unnoticed.)
        literal::read_call_args(at.source, self.text(text, at), at.start as usize)
            .unwrap_or_default()
    }
}

impl std::fmt::Debug for PackedArgs {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "PackedArgs(..{})", self.end)
    }
}

/// An argument in a procedure or function call.
#[derive(Debug, Clone, PartialEq)]
pub struct Arg {
    /// What form it has.
    pub kind: ArgKind,
    /// Its text (including a leading `\`).
    pub span: Span,
}

/// Argument forms.
#[derive(Debug, Clone, PartialEq)]
pub enum ArgKind {
    /// `expr` — positional required argument.
    Positional(Expr),
    /// `name := expr` — named required argument.
    Named {
        /// Parameter name.
        name: Ident,
        /// Value.
        value: Box<Expr>,
    },
    /// `\name` (switch, or the same-named object) or `\name := expr`.
    Optional {
        /// Parameter name.
        name: Ident,
        /// Value, if written.
        value: Option<Box<Expr>>,
    },
    /// `\name ? param` — passed only when the caller's optional `param` is present.
    Conditional {
        /// Parameter name of the callee.
        name: Ident,
        /// Caller's optional parameter.
        param: Box<Ident>,
    },
    /// `<ARG>` placeholder.
    Placeholder(Placeholder),
}

/// An expression.
#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    /// What it is.
    pub kind: ExprKind,
    /// Its text.
    pub span: Span,
}

/// Expression shapes.
#[derive(Debug, Clone, PartialEq)]
pub enum ExprKind {
    /// Numeric literal (value as parsed in f64; the interpreter rounds `num` to f32).
    Num(f64),
    /// String literal, escapes decoded (`""` → `"`, `\\` → `\`, `\hh` → byte hh as a char).
    Str(String),
    /// `TRUE` / `FALSE`.
    Bool(bool),
    /// A data name.
    Name(Ident),
    /// `base.field`.
    Component {
        /// Record value.
        base: Box<Expr>,
        /// Component name (boxed: an inline name would make every expression 8 bytes
        /// larger, and component access is rare next to names and literals).
        field: Box<Ident>,
    },
    /// `base{i[,j[,k]]}`.
    Index {
        /// Array value.
        base: Box<Expr>,
        /// Indices (1-based).
        indices: Vec<Expr>,
    },
    /// `F(args)` — function call.
    Call {
        /// Function name.
        name: Box<Ident>,
        /// Arguments.
        args: Box<[Arg]>,
    },
    /// `[e1, e2, …]` — record or array aggregate, typed from context.
    Aggregate(Vec<Expr>),
    /// An aggregate of literals only (numbers with an optional sign, strings, `TRUE`,
    /// `FALSE`, nested aggregates of these), as robtargets and tool data are written, kept as
    /// its text: most of the bytes of real programs are such aggregates, and the text is
    /// about a tenth of the tree. [`Expr::aggregate_items`] and [`PackedAggregate::unpack`]
    /// give the [`ExprKind::Aggregate`] tree the parser would have built, spans included.
    PackedAggregate(PackedAggregate),
    /// Prefix operator.
    Unary {
        /// Operator.
        op: UnaryOp,
        /// Operand.
        expr: Box<Expr>,
    },
    /// Infix operator.
    Binary {
        /// Operator.
        op: BinOp,
        /// Left operand.
        lhs: Box<Expr>,
        /// Right operand.
        rhs: Box<Expr>,
    },
    /// `( e )` — kept so printing and diagnostics can show the parentheses.
    Paren(Box<Expr>),
    /// A placeholder such as `<EXP>` or `<VAR>`.
    Placeholder(Placeholder),
}

/// A literal aggregate kept as its text in the file ([`File::text`]): from its `[` to its
/// `]`, the span of the expression that holds it (see [`ExprKind::PackedAggregate`]). It
/// takes no memory of its own. The parser packs an aggregate only when reading it reported
/// nothing, so unpacking cannot fail.
#[derive(Clone, Copy, PartialEq, Eq)]
pub struct PackedAggregate(());

impl PackedAggregate {
    /// An aggregate the parser has read without a diagnostic.
    pub(crate) fn new() -> Self {
        PackedAggregate(())
    }

    /// The aggregate as written in the file's `text`, at `span` (the span of the expression
    /// that holds it).
    pub fn text<'t>(&self, text: &'t str, span: Span) -> &'t str {
        text.get(span.start as usize..span.end as usize)
            .unwrap_or("")
    }

    /// The [`ExprKind::Aggregate`] tree of this aggregate in the file's `text`, written at
    /// `span` (the span of the expression that holds it): the tree the parser builds for it,
    /// node for node.
    pub fn unpack(&self, text: &str, span: Span) -> Expr {
        literal::unpack_aggregate(span.source, self.text(text, span), span.start as usize)
    }
}

impl std::fmt::Debug for PackedAggregate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "PackedAggregate")
    }
}

impl Expr {
    /// The items of an aggregate, packed or not, in the file's `text` ([`File::text`]);
    /// `None` for any other expression.
    pub fn aggregate_items(&self, text: &str) -> Option<std::borrow::Cow<'_, [Expr]>> {
        match &self.kind {
            ExprKind::Aggregate(items) => Some(std::borrow::Cow::Borrowed(items)),
            ExprKind::PackedAggregate(p) => match p.unpack(text, self.span).kind {
                ExprKind::Aggregate(items) => Some(std::borrow::Cow::Owned(items)),
                _ => None,
            },
            _ => None,
        }
    }

    /// This expression with a packed aggregate unpacked from the file's `text` (borrowed as
    /// it is otherwise).
    pub fn unpacked(&self, text: &str) -> std::borrow::Cow<'_, Expr> {
        match &self.kind {
            ExprKind::PackedAggregate(p) => std::borrow::Cow::Owned(p.unpack(text, self.span)),
            _ => std::borrow::Cow::Borrowed(self),
        }
    }
}

/// Prefix operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnaryOp {
    /// `-e`
    Neg,
    /// `+e`
    Plus,
    /// `NOT e`
    Not,
}

/// Infix operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `DIV`
    IntDiv,
    /// `MOD`
    Mod,
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `=`
    Eq,
    /// `>=`
    Ge,
    /// `>`
    Gt,
    /// `<>`
    Ne,
    /// `AND`
    And,
    /// `OR`
    Or,
    /// `XOR`
    Xor,
}

impl BinOp {
    /// The operator as written in RAPID.
    pub fn as_str(self) -> &'static str {
        match self {
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::IntDiv => "DIV",
            BinOp::Mod => "MOD",
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Lt => "<",
            BinOp::Le => "<=",
            BinOp::Eq => "=",
            BinOp::Ge => ">=",
            BinOp::Gt => ">",
            BinOp::Ne => "<>",
            BinOp::And => "AND",
            BinOp::Or => "OR",
            BinOp::Xor => "XOR",
        }
    }
}

/// RAPID placeholders for incomplete programs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Placeholder {
    /// `<TDN>` type definition
    Tdn,
    /// `<DDN>` data declaration
    Ddn,
    /// `<RDN>` routine declaration
    Rdn,
    /// `<PAR>` parameter
    Par,
    /// `<ALT>` alternative parameter
    Alt,
    /// `<DIM>` array dimension
    Dim,
    /// `<SMT>` statement
    Smt,
    /// `<VAR>` data object reference
    Var,
    /// `<EIT>` ELSEIF clause
    Eit,
    /// `<CSE>` CASE clause
    Cse,
    /// `<EXP>` expression
    Exp,
    /// `<ARG>` argument
    Arg,
    /// `<ID>` identifier
    Id,
}

impl Placeholder {
    /// As written, e.g. `<SMT>`.
    pub fn as_str(self) -> &'static str {
        match self {
            Placeholder::Tdn => "<TDN>",
            Placeholder::Ddn => "<DDN>",
            Placeholder::Rdn => "<RDN>",
            Placeholder::Par => "<PAR>",
            Placeholder::Alt => "<ALT>",
            Placeholder::Dim => "<DIM>",
            Placeholder::Smt => "<SMT>",
            Placeholder::Var => "<VAR>",
            Placeholder::Eit => "<EIT>",
            Placeholder::Cse => "<CSE>",
            Placeholder::Exp => "<EXP>",
            Placeholder::Arg => "<ARG>",
            Placeholder::Id => "<ID>",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A large module holds millions of these nodes: a field that makes them larger shows up
    /// as memory (`cargo bench --bench check_memory`). Box rare large shapes instead.
    #[test]
    fn node_sizes_do_not_grow() {
        eprintln!(
            "SIZES span {} ident {} expr {} arg {} stmt {} stmtkind {} item {} data {} callargs {}",
            size_of::<Span>(),
            size_of::<Ident>(),
            size_of::<Expr>(),
            size_of::<Arg>(),
            size_of::<Stmt>(),
            size_of::<StmtKind>(),
            size_of::<ModuleItem>(),
            size_of::<DataDecl>(),
            size_of::<CallArgs>()
        );
        assert!(size_of::<Span>() <= 12, "Span {}", size_of::<Span>());
        assert!(size_of::<Ident>() <= 32, "Ident {}", size_of::<Ident>());
        assert!(size_of::<Expr>() <= 56, "Expr {}", size_of::<Expr>());
        assert!(size_of::<Arg>() <= 72, "Arg {}", size_of::<Arg>());
        assert!(size_of::<Stmt>() <= 80, "Stmt {}", size_of::<Stmt>());
        assert!(
            size_of::<ModuleItem>() <= 16,
            "ModuleItem {}",
            size_of::<ModuleItem>()
        );
    }
}
