//! Semantic diagnostics: one enum, with every user-facing text in `SemaError::details`.

use std::fmt;

use miette::{Diagnostic, LabeledSpan, Severity};

use crate::diag::{Code, RapidDiagnostic};
use crate::ir::limits::{MAX_DECL_VALUES, MAX_TASK_VALUES, thousands};
use crate::source::{SourceId, Span};

/// What the semantic pass found.
#[derive(Clone, Debug, PartialEq)]
pub enum SemaErrorKind {
    /// A data name that is not declared anywhere visible.
    Undeclared {
        /// The name.
        name: String,
        /// A similar visible name, if any.
        suggestion: Option<String>,
    },
    /// A signal argument that names no configured signal.
    UnknownSignal {
        /// The name.
        name: String,
        /// The signal type expected (`signaldo`, …).
        ty: String,
    },
    /// A call to an instruction or function nobody declares.
    Unsupported {
        /// The routine name.
        name: String,
        /// `instruction` or `function`.
        what: &'static str,
    },
    /// A type name that does not exist.
    UnknownType {
        /// The name.
        name: String,
    },
    /// A value of the wrong type.
    TypeMismatch {
        /// What needed the value (e.g. "the condition of IF").
        context: String,
        /// Expected type.
        expected: String,
        /// Actual type.
        found: String,
    },
    /// An operator applied to operands it does not take.
    BadOperands {
        /// The operator.
        op: String,
        /// Left operand type (or the only one).
        lhs: String,
        /// Right operand type, for binary operators.
        rhs: Option<String>,
    },
    /// Too many positional arguments.
    TooManyArgs {
        /// Callee.
        callee: String,
    },
    /// A required argument was not given.
    MissingArg {
        /// Callee.
        callee: String,
        /// Parameter.
        param: String,
    },
    /// `\Name` that is not an optional parameter of the callee.
    UnknownOptional {
        /// Callee.
        callee: String,
        /// The argument name.
        name: String,
        /// The name is a required parameter.
        is_required: bool,
    },
    /// `name := v` for a parameter that does not exist.
    UnknownNamed {
        /// Callee.
        callee: String,
        /// The argument name.
        name: String,
    },
    /// The same parameter given twice.
    DuplicateArg {
        /// Parameter.
        name: String,
    },
    /// Two mutually exclusive alternatives given together.
    ExclusiveArgs {
        /// First.
        first: String,
        /// Second.
        second: String,
    },
    /// A switch given a value, or a value parameter given as a bare switch.
    SwitchValue {
        /// Parameter.
        name: String,
        /// The parameter is a switch.
        is_switch: bool,
    },
    /// An argument for an INOUT/VAR/PERS parameter that is not the right kind of object.
    ArgMode {
        /// Parameter.
        param: String,
        /// Its mode (`INOUT`, `VAR`, `PERS`).
        mode: &'static str,
        /// What the argument is.
        found: String,
    },
    /// Assignment to something that cannot be assigned.
    NotAssignable {
        /// Name of the object.
        name: String,
        /// Why (e.g. "a CONST", "an IN parameter").
        why: String,
    },
    /// Something that needs a place (variable) got an expression.
    NotAPlace {
        /// What needed it.
        context: String,
    },
    /// `RETURN value` in a PROC or TRAP.
    ReturnValueInProc,
    /// `RETURN` without a value in a FUNC.
    MissingReturnValue,
    /// A FUNC without any `RETURN`.
    FuncWithoutReturn {
        /// The function.
        name: String,
    },
    /// The end of a FUNC can be reached (warning).
    FuncEndReachable {
        /// The function.
        name: String,
    },
    /// A name declared twice in the same scope.
    Duplicate {
        /// The name.
        name: String,
        /// Where it was first declared.
        first: Span,
    },
    /// A user module redeclares predefined stdlib data.
    PredefinedRedeclared {
        /// The name.
        name: String,
    },
    /// A PERS declared in several modules with different types.
    PersMismatch {
        /// The name.
        name: String,
        /// The first type.
        first: String,
        /// This type.
        this: String,
    },
    /// A call to a function as an instruction, or to a procedure in an expression.
    WrongRoutineKind {
        /// The name.
        name: String,
        /// What it is.
        is: &'static str,
        /// What was needed.
        needed: &'static str,
    },
    /// RETRY, TRYNEXT or `RAISE;` outside an ERROR handler.
    HandlerOnly {
        /// The statement.
        what: &'static str,
    },
    /// A GOTO to a label that does not exist or cannot be reached from here.
    BadLabel {
        /// The label.
        name: String,
        /// The label exists in the routine but inside another block.
        exists: bool,
    },
    /// An aggregate with the wrong number of items.
    AggregateSize {
        /// The type.
        ty: String,
        /// Expected count.
        expected: usize,
        /// Found count.
        found: usize,
    },
    /// An aggregate whose type cannot be told from its context.
    AggregateUntyped,
    /// Indexing something that is not an array, or with the wrong number of indices.
    NotArray {
        /// What it is.
        ty: String,
        /// Indices given.
        given: usize,
    },
    /// `.field` on something that is not a record with that component.
    UnknownComponent {
        /// The type.
        ty: String,
        /// The component.
        field: String,
    },
    /// A non-value type used as a value (aggregate, CONST, assignment, comparison).
    NonValue {
        /// The type.
        ty: String,
        /// What was attempted.
        what: &'static str,
    },
    /// An array size or other constant that cannot be computed before running.
    NotConstant {
        /// What needed the constant.
        what: &'static str,
    },
    /// Module data whose initial values depend on each other.
    InitCycle {
        /// The name.
        name: String,
    },
    /// A data declaration that is not allowed here.
    BadDecl {
        /// Why.
        why: String,
    },
    /// `Present`/conditional argument on something that is not an optional parameter.
    NotOptional {
        /// The name.
        name: String,
    },
    /// A switch parameter used as a value.
    SwitchAsValue {
        /// The name.
        name: String,
    },
    /// A string literal longer than 80 characters.
    StringTooLong {
        /// Its length.
        len: usize,
    },
    /// An array size larger than one declaration may hold ([`crate::ir::limits`]).
    ArraySizeTooLarge {
        /// The size.
        size: f64,
    },
    /// A declaration holding more values than one declaration may.
    DeclTooLarge {
        /// The data name.
        name: String,
        /// How many values it holds.
        values: u64,
    },
    /// Data that brings the task over its limit: module data, or a routine's data on top
    /// of the module data.
    TaskDataTooLarge {
        /// The declaration that crosses the limit.
        name: String,
        /// The routine, for routine data.
        routine: Option<String>,
        /// Values held up to and including it.
        values: u64,
    },
    /// A native signature names a type rapidvc does not define (an internal error).
    BadSignature {
        /// The native.
        native: String,
        /// The type.
        ty: String,
    },
}

/// How data is counted against the limits (shown with every data-limit diagnostic).
const DATA_LIMIT_HELP: &str = "a num, dnum, bool or string is one value, a record holds the values of its components (a robtarget 17); see \"Data limits\" in the README";

/// A semantic error or warning at a span.
#[derive(Clone, Debug, PartialEq)]
pub struct SemaError {
    /// What.
    pub kind: SemaErrorKind,
    /// Where.
    pub span: Span,
}

/// Rendered parts of a diagnostic.
struct Details {
    code: Code,
    message: String,
    label: String,
    help: Option<String>,
    warning: bool,
}

impl SemaError {
    /// A diagnostic of `kind` at `span`.
    pub fn new(kind: SemaErrorKind, span: Span) -> Self {
        SemaError { kind, span }
    }

    /// True for warnings (the program can still run).
    pub fn is_warning(&self) -> bool {
        self.details().warning
    }

    fn details(&self) -> Details {
        use SemaErrorKind as K;
        let d = |code, message: String, label: &str, help: Option<String>| Details {
            code,
            message,
            label: label.to_string(),
            help,
            warning: false,
        };
        // A name of a RobotWare option rapidvc does not have says which option.
        let (name, what) = match &self.kind {
            K::Unsupported { name, what } => (Some(name), *what),
            K::UnknownType { name } => (Some(name), "data type"),
            _ => (None, ""),
        };
        if let Some(name) = name
            && let Some(option) = super::options::lookup(name)
        {
            return needs_option(name, what, option);
        }
        match &self.kind {
            K::Undeclared { name, suggestion } => d(
                Code::SemaUndeclared,
                format!("`{name}` is not declared"),
                "not declared in this routine, its module or any global scope",
                suggestion.as_ref().map(|s| format!("did you mean `{s}`?")),
            ),
            K::UnknownSignal { name, ty } => d(
                Code::SemaUnknownSignal,
                format!("`{name}` is not a configured I/O signal"),
                &format!("needs a `{ty}`"),
                Some(format!(
                    "define `{name}` in EIO.cfg (an EIO_SIGNAL instance) in the configuration directory (--config, default: the program's directory)"
                )),
            ),
            K::Unsupported { name, what } if super::base::is_base_routine(name) => d(
                Code::SemaUnsupported,
                format!("`{name}` is not supported by rapidvc"),
                &format!("{what} of base RobotWare that rapidvc does not implement"),
                Some(format!(
                    "no routine named `{name}` is declared in the loaded modules either"
                )),
            ),
            // Not ABB's: the program's own routine, missing from the loaded modules.
            K::Unsupported { name, what } => d(
                Code::SemaUnknownRoutine,
                format!("`{name}` is not declared"),
                &format!("unknown {what}"),
                Some(format!(
                    "no routine named `{name}` is declared in the loaded modules, and RAPID has no {what} of that name; is a module missing?"
                )),
            ),
            K::UnknownType { name } => d(
                Code::SemaUnknownType,
                format!("unknown data type `{name}`"),
                "no RECORD or ALIAS of this name, and not a built-in type",
                None,
            ),
            K::TypeMismatch {
                context,
                expected,
                found,
            } => d(
                Code::SemaTypeMismatch,
                format!(
                    "{context} must be {}, not {}",
                    quote(expected),
                    quote(found)
                ),
                &format!("this is {}", quote(found)),
                None,
            ),
            K::BadOperands { op, lhs, rhs } => d(
                Code::SemaBadOperands,
                match rhs {
                    Some(r) => format!("`{op}` cannot combine `{lhs}` and `{r}`"),
                    None => format!("`{op}` cannot be applied to `{lhs}`"),
                },
                "operator used here",
                None,
            ),
            K::TooManyArgs { callee } => d(
                Code::SemaTooManyArgs,
                format!("too many arguments for `{callee}`"),
                "no parameter left for this argument",
                None,
            ),
            K::MissingArg { callee, param } => d(
                Code::SemaMissingArg,
                format!("`{callee}` needs an argument for `{param}`"),
                &format!("`{param}` is missing"),
                None,
            ),
            K::UnknownOptional {
                callee,
                name,
                is_required,
            } => d(
                Code::SemaUnknownOptional,
                format!("`\\{name}` is not an optional parameter of `{callee}`"),
                "unknown optional argument",
                is_required
                    .then(|| format!("`{name}` is a required parameter: pass it without `\\`")),
            ),
            K::UnknownNamed { callee, name } => d(
                Code::SemaUnknownNamed,
                format!("`{callee}` has no parameter `{name}`"),
                "unknown parameter name",
                None,
            ),
            K::DuplicateArg { name } => d(
                Code::SemaDuplicateArg,
                format!("the argument for `{name}` is given twice"),
                "second time",
                None,
            ),
            K::ExclusiveArgs { first, second } => d(
                Code::SemaExclusiveArgs,
                format!("`\\{first}` and `\\{second}` cannot be used together"),
                "alternative to an argument already given",
                None,
            ),
            K::SwitchValue { name, is_switch } => {
                if *is_switch {
                    d(
                        Code::SemaSwitchValue,
                        format!("the switch `\\{name}` takes no value"),
                        "remove `:= …`",
                        None,
                    )
                } else {
                    d(
                        Code::SemaSwitchValue,
                        format!("`\\{name}` needs a value"),
                        "write `\\Name := value`",
                        Some(format!(
                            "`\\{name}` alone passes data named `{name}`, but there is none"
                        )),
                    )
                }
            }
            K::ArgMode { param, mode, found } => d(
                Code::SemaArgMode,
                format!("the {mode} parameter `{param}` needs {}", mode_need(mode)),
                &format!("this is {found}"),
                None,
            ),
            K::NotAssignable { name, why } => d(
                Code::SemaNotAssignable,
                format!("`{name}` cannot be changed: it is {why}"),
                "assigned here",
                None,
            ),
            K::NotAPlace { context } => d(
                Code::SemaNotAPlace,
                format!("{context} must be a data object, not an expression"),
                "not a variable or persistent",
                None,
            ),
            K::ReturnValueInProc => d(
                Code::SemaReturnValue,
                "a procedure or trap cannot return a value".into(),
                "remove this value",
                None,
            ),
            K::MissingReturnValue => d(
                Code::SemaReturnValue,
                "RETURN in a function needs a value".into(),
                "RETURN without a value",
                None,
            ),
            K::FuncWithoutReturn { name } => d(
                Code::SemaMissingReturn,
                format!("function `{name}` has no RETURN"),
                "this function never returns a value",
                None,
            ),
            K::FuncEndReachable { name } => Details {
                warning: true,
                ..d(
                    Code::SemaMissingReturn,
                    format!("function `{name}` can reach its end without RETURN"),
                    "ERR_FNCNORET is raised if execution gets here",
                    None,
                )
            },
            K::Duplicate { name, .. } => d(
                Code::SemaDuplicate,
                format!("`{name}` is declared more than once"),
                "declared again here",
                None,
            ),
            K::PredefinedRedeclared { name } => d(
                Code::SemaPredefined,
                format!("`{name}` is predefined and cannot be redeclared"),
                "redeclares predefined data",
                Some("declare it LOCAL to shadow the predefined data in this module only".into()),
            ),
            K::PersMismatch { name, first, this } => d(
                Code::SemaPersMismatch,
                format!("persistent `{name}` is `{first}` elsewhere but `{this}` here"),
                "all declarations of a PERS must have the same type",
                None,
            ),
            K::WrongRoutineKind { name, is, needed } => d(
                Code::SemaRoutineKind,
                format!("`{name}` is {is}, not {needed}"),
                &format!("{needed} expected"),
                None,
            ),
            K::HandlerOnly { what } => d(
                Code::SemaHandlerOnly,
                format!("{what} is only allowed in an ERROR handler"),
                "outside an ERROR handler",
                None,
            ),
            K::BadLabel { name, exists } => d(
                Code::SemaLabel,
                if *exists {
                    format!("GOTO cannot jump into the block that holds label `{name}`")
                } else {
                    format!("there is no label `{name}` in this routine")
                },
                "jump from here",
                exists.then(|| "GOTO may leave blocks but not enter them".to_string()),
            ),
            K::AggregateSize {
                ty,
                expected,
                found,
            } => d(
                Code::SemaAggregate,
                format!("`{ty}` needs {expected} items, this aggregate has {found}"),
                "wrong number of items",
                None,
            ),
            K::AggregateUntyped => d(
                Code::SemaAggregate,
                "the type of this aggregate cannot be told from where it is used".into(),
                "untyped aggregate",
                Some("assign it to data of a known type first".into()),
            ),
            K::NotArray { ty, given } => d(
                Code::SemaIndex,
                format!("`{ty}` cannot be indexed with {given} indices"),
                "indexed here",
                None,
            ),
            K::UnknownComponent { ty, field } => d(
                Code::SemaComponent,
                format!("`{ty}` has no component `{field}`"),
                "unknown component",
                None,
            ),
            K::NonValue { ty, what } => d(
                Code::SemaNonValue,
                format!("`{ty}` is not a value type: it cannot be {what}"),
                "non-value data",
                None,
            ),
            K::NotConstant { what } => d(
                Code::SemaNotConstant,
                format!("{what} must be a constant"),
                "not computable before the program runs",
                None,
            ),
            K::InitCycle { name } => d(
                Code::SemaInitCycle,
                format!("the initial value of `{name}` depends on itself"),
                "circular initialisation",
                None,
            ),
            K::BadDecl { why } => d(Code::SemaDeclaration, why.clone(), "here", None),
            K::NotOptional { name } => d(
                Code::SemaNotOptional,
                format!("`{name}` is not an optional parameter of this routine"),
                "needs an optional parameter",
                None,
            ),
            K::SwitchAsValue { name } => d(
                Code::SemaSwitchAsValue,
                format!("the switch `{name}` has no value"),
                "used as a value",
                Some(format!("test it with Present({name})")),
            ),
            K::StringTooLong { len } => d(
                Code::SemaStringTooLong,
                format!("string of {len} characters; RAPID strings hold at most 80"),
                "too long",
                None,
            ),
            K::ArraySizeTooLarge { size } => d(
                Code::SemaDataLimit,
                format!(
                    "array size {size} is too large: one declaration holds at most {} values",
                    thousands(MAX_DECL_VALUES)
                ),
                "too large",
                Some(DATA_LIMIT_HELP.into()),
            ),
            K::DeclTooLarge { name, values } => d(
                Code::SemaDataLimit,
                format!(
                    "`{name}` holds {} values: one declaration holds at most {}",
                    thousands(*values),
                    thousands(MAX_DECL_VALUES)
                ),
                "too much data",
                Some(DATA_LIMIT_HELP.into()),
            ),
            K::TaskDataTooLarge {
                name,
                routine,
                values,
            } => d(
                Code::SemaDataLimit,
                match routine {
                    None => format!(
                        "with `{name}`, the module data holds {} values: a task holds at most {}",
                        thousands(*values),
                        thousands(MAX_TASK_VALUES)
                    ),
                    Some(r) => format!(
                        "with `{name}`, the data of `{r}` and the module data hold {} values: a task holds at most {}",
                        thousands(*values),
                        thousands(MAX_TASK_VALUES)
                    ),
                },
                "over the task's data limit",
                Some(DATA_LIMIT_HELP.into()),
            ),
            K::BadSignature { native, ty } => d(
                Code::SemaInternal,
                format!("internal error: built-in `{native}` uses unknown type `{ty}`"),
                "here",
                None,
            ),
        }
    }
}

/// A type name in backquotes; a description (with spaces) as it is.
/// "`ArcL` needs the option 633-4 Arc, which rapidvc does not have".
fn needs_option(name: &str, what: &str, option: &super::options::RobotOption) -> Details {
    Details {
        code: Code::SemaNeedsOption,
        message: format!("`{name}` needs the option {option}, which rapidvc does not have"),
        label: format!("{what} of the RobotWare option {}", option.name),
        help: Some(format!(
            "rapidvc implements base RobotWare; {} is an option it does not have (docs/rapid.md, \"RobotWare options\")",
            option.name
        )),
        warning: false,
    }
}

fn quote(s: &str) -> String {
    if s.contains(' ') {
        s.to_string()
    } else {
        format!("`{s}`")
    }
}

fn mode_need(mode: &str) -> &'static str {
    match mode {
        "PERS" => "an entire persistent (PERS)",
        "VAR" => "a variable (VAR data, an element or a component)",
        _ => "a variable or an entire persistent",
    }
}

impl fmt::Display for SemaError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.details().message)
    }
}

impl std::error::Error for SemaError {}

impl Diagnostic for SemaError {
    fn code<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        Some(Box::new(self.details().code))
    }

    fn severity(&self) -> Option<Severity> {
        Some(if self.is_warning() {
            Severity::Warning
        } else {
            Severity::Error
        })
    }

    fn help<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        self.details()
            .help
            .map(|h| Box::new(h) as Box<dyn fmt::Display>)
    }

    fn labels(&self) -> Option<Box<dyn Iterator<Item = LabeledSpan> + '_>> {
        let mut v = vec![LabeledSpan::new_with_span(
            Some(self.details().label),
            self.span,
        )];
        if let SemaErrorKind::Duplicate { first, .. } = &self.kind
            && first.source == self.span.source
        {
            v.push(LabeledSpan::new_with_span(
                Some("first declared here".into()),
                *first,
            ));
        }
        Some(Box::new(v.into_iter()))
    }
}

impl RapidDiagnostic for SemaError {
    fn source_id(&self) -> Option<SourceId> {
        Some(self.span.source)
    }
}
