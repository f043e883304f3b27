//! `ParseError`: every problem the front end reports (syntax, structure, placeholders), with
//! stable `rapidvc::parse::…` codes. All user-facing text of the parser lives in this file.

use std::fmt;

use miette::{Diagnostic, LabeledSpan, Severity};

use crate::diag::RapidDiagnostic;
use crate::source::{SourceId, Span};

/// A diagnostic of the parse phase about one file.
#[derive(Debug, Clone)]
pub struct ParseError {
    /// The file the spans point into.
    pub file: SourceId,
    /// What went wrong.
    pub kind: ParseErrorKind,
}

/// The kinds of parse-phase diagnostics. Spans are byte ranges into [`ParseError::file`].
#[derive(Debug, Clone, thiserror::Error, Diagnostic)]
pub enum ParseErrorKind {
    /// The text does not fit the grammar here.
    #[error("expected {expected}, found {found}")]
    #[diagnostic(code(rapidvc::parse::syntax))]
    Syntax {
        /// Where the parser stopped (may be empty: the end of the previous token).
        #[label("{label}")]
        span: Span,
        /// What would have been accepted, in words ("`;` after the statement").
        expected: String,
        /// What is there ("`ENDPROC`", "end of file").
        found: String,
        /// Label text.
        label: String,
        /// Optional hint.
        #[help]
        help: Option<String>,
    },

    /// A string literal without its closing quote on the same line.
    #[error("unterminated string")]
    #[diagnostic(
        code(rapidvc::parse::unterminated_string),
        help("a string ends with `\"` on the same line; write `\"\"` for a quote inside it")
    )]
    UnterminatedString {
        /// From the opening quote to the end of the line.
        #[label("this string is not closed")]
        span: Span,
    },

    /// A backslash in a string that is not `\\` or `\hh`.
    #[error("invalid escape `{text}` in string")]
    #[diagnostic(
        code(rapidvc::parse::invalid_escape),
        help("write `\\\\` for a backslash, or `\\hh` (two hex digits) for a character code")
    )]
    InvalidEscape {
        /// The backslash and what follows it.
        #[label("not a valid escape")]
        span: Span,
        /// The escape as written.
        text: String,
    },

    /// A number literal outside the range of `num` (IEEE-754 single precision).
    #[error("number `{text}` is out of range")]
    #[diagnostic(
        code(rapidvc::parse::number_out_of_range),
        help("RAPID numbers must lie within ±3.40282E+38 (single precision)")
    )]
    NumberOutOfRange {
        /// The literal.
        #[label("too large for a num")]
        span: Span,
        /// The literal as written.
        text: String,
    },

    /// Brackets and blocks nested deeper than the parser accepts.
    #[error("nesting is deeper than {limit} levels")]
    #[diagnostic(
        code(rapidvc::parse::nesting_too_deep),
        help(
            "rapidvc accepts at most {limit} nested brackets and blocks; split the expression or routine"
        )
    )]
    NestingTooDeep {
        /// The bracket or keyword that went past the limit.
        #[label("level {limit} is exceeded here")]
        span: Span,
        /// The limit.
        limit: usize,
    },

    /// An expression whose tree is deeper than the parser accepts (a very long operator chain).
    #[error("expression is too complex (more than {limit} nested operations)")]
    #[diagnostic(
        code(rapidvc::parse::expression_too_complex),
        help("split it into several assignments")
    )]
    ExpressionTooComplex {
        /// The expression.
        #[label("this expression")]
        span: Span,
        /// The limit.
        limit: usize,
    },

    /// `NOT` after an operator: RAPID allows it only at the start of an expression.
    #[error("`NOT` can only start an expression")]
    #[diagnostic(
        code(rapidvc::parse::misplaced_not),
        help("put the negated part in parentheses, e.g. `a AND (NOT b)`")
    )]
    MisplacedNot {
        /// The `NOT`.
        #[label("`NOT` after an operator")]
        span: Span,
    },

    /// `a < b < c`: relational operators do not associate.
    #[error("comparisons cannot be chained")]
    #[diagnostic(
        code(rapidvc::parse::chained_comparison),
        help("combine the comparisons with AND, e.g. `a < b AND b < c`")
    )]
    ChainedComparison {
        /// The second comparison operator.
        #[label("second comparison")]
        span: Span,
    },

    /// A block, routine, record or module whose end keyword is missing.
    #[error("missing `{keyword}`")]
    #[diagnostic(code(rapidvc::parse::missing_end))]
    MissingEnd {
        /// Where the end keyword was expected.
        #[label("expected `{keyword}` before this")]
        span: Span,
        /// The keyword that opened the construct.
        #[label("this `{opener}` is not closed")]
        opener_span: Span,
        /// `ENDIF`, `ENDPROC`, ...
        keyword: &'static str,
        /// `IF`, `PROC`, ...
        opener: String,
    },

    /// An end or continuation keyword that no open block takes.
    #[error("`{keyword}` without a matching `{opener}`")]
    #[diagnostic(code(rapidvc::parse::unmatched_keyword))]
    StrayKeyword {
        /// The keyword.
        #[label("nothing to close here")]
        span: Span,
        /// The keyword as written.
        keyword: String,
        /// What should have opened it.
        opener: &'static str,
        /// Optional hint.
        #[help]
        help: Option<&'static str>,
    },

    /// `PROC … ENDFUNC` and the like.
    #[error("{kind} `{name}` ends with `{found}`")]
    #[diagnostic(code(rapidvc::parse::end_mismatch), help("write `{expected}`"))]
    EndMismatch {
        /// The end keyword.
        #[label("expected `{expected}`")]
        span: Span,
        /// The routine head.
        #[label("{kind} starts here")]
        head_span: Span,
        /// `PROC`, `FUNC`, `TRAP`.
        kind: &'static str,
        /// Routine name.
        name: String,
        /// The end keyword as written.
        found: String,
        /// The right end keyword.
        expected: &'static str,
    },

    /// A statement at module level.
    #[error("statement outside a routine")]
    #[diagnostic(
        code(rapidvc::parse::statement_outside_routine),
        help("statements belong inside a PROC, FUNC or TRAP")
    )]
    StatementOutsideRoutine {
        /// The statement.
        #[label("not inside a routine")]
        span: Span,
    },

    /// A declaration where RAPID does not allow one.
    #[error("{what}")]
    #[diagnostic(code(rapidvc::parse::misplaced_declaration), help("{help}"))]
    MisplacedDeclaration {
        /// The declaration.
        #[label("declared here")]
        span: Span,
        /// The problem.
        what: &'static str,
        /// The rule.
        help: &'static str,
    },

    /// A keyword that is not allowed in this declaration.
    #[error("`{keyword}` is not allowed here")]
    #[diagnostic(code(rapidvc::parse::invalid_modifier), help("{help}"))]
    InvalidModifier {
        /// The keyword.
        #[label("not allowed here")]
        span: Span,
        /// The keyword as written.
        keyword: String,
        /// The rule.
        help: &'static str,
    },

    /// More than three array dimensions.
    #[error("an array has at most 3 dimensions, found {count}")]
    #[diagnostic(code(rapidvc::parse::too_many_dimensions))]
    TooManyDimensions {
        /// The dimension list.
        #[label("{count} dimensions")]
        span: Span,
        /// How many were written.
        count: usize,
    },

    /// A handler section twice, or in the wrong order.
    #[error("`{section}` section {problem}")]
    #[diagnostic(
        code(rapidvc::parse::section_order),
        help(
            "a routine ends with at most one BACKWARD, one ERROR and one UNDO section, in that order"
        )
    )]
    SectionOrder {
        /// The section keyword.
        #[label("{problem}")]
        span: Span,
        /// `BACKWARD`, `ERROR` or `UNDO`.
        section: &'static str,
        /// "appears twice" or "is out of order".
        problem: &'static str,
    },

    /// Two declarations with the same (case-folded) name in one scope.
    #[error("`{name}` is declared twice in {scope}")]
    #[diagnostic(
        code(rapidvc::parse::duplicate_name),
        help("RAPID names are case-insensitive; rename one of them")
    )]
    DuplicateName {
        /// The second declaration's name.
        #[label("declared again here")]
        span: Span,
        /// The first declaration's name.
        #[label("first declared here")]
        first: Span,
        /// The name as written the second time.
        name: String,
        /// "module `M`", "routine `r`", "record `t`".
        scope: String,
    },

    /// A placeholder of an incomplete program (a warning: it parses, but cannot run).
    #[error("placeholder `{text}` ({what})")]
    #[diagnostic(
        code(rapidvc::parse::placeholder),
        severity(Warning),
        help("the program is incomplete: replace the placeholder before running it")
    )]
    Placeholder {
        /// The placeholder.
        #[label("incomplete")]
        span: Span,
        /// As written.
        text: String,
        /// What it stands for.
        what: &'static str,
    },

    /// A file without any module.
    #[error("no MODULE in this file")]
    #[diagnostic(
        code(rapidvc::parse::no_module),
        help("a RAPID file holds one or more `MODULE name … ENDMODULE` blocks")
    )]
    NoModule {
        /// The start of the file.
        #[label("expected `MODULE`")]
        span: Span,
    },

    /// The parser gave up (only for inputs beyond its limits).
    #[error("cannot parse this file: {reason}")]
    #[diagnostic(code(rapidvc::parse::limit))]
    Limit {
        /// Where.
        #[label("here")]
        span: Span,
        /// Why.
        reason: String,
    },

    /// The error limit per file was reached; the rest is not reported.
    #[error("too many errors in this file; stopped after {count}")]
    #[diagnostic(code(rapidvc::parse::too_many_errors))]
    TooManyErrors {
        /// Where the next error would have been.
        #[label("more errors follow")]
        span: Span,
        /// How many were reported.
        count: usize,
    },
}

impl ParseError {
    /// A diagnostic about `file`.
    pub fn new(file: SourceId, kind: ParseErrorKind) -> Self {
        ParseError { file, kind }
    }

    /// The main span of the diagnostic.
    pub fn span(&self) -> Span {
        use ParseErrorKind as K;
        match &self.kind {
            K::Syntax { span, .. }
            | K::UnterminatedString { span }
            | K::InvalidEscape { span, .. }
            | K::NumberOutOfRange { span, .. }
            | K::NestingTooDeep { span, .. }
            | K::ExpressionTooComplex { span, .. }
            | K::MisplacedNot { span }
            | K::ChainedComparison { span }
            | K::MissingEnd { span, .. }
            | K::StrayKeyword { span, .. }
            | K::EndMismatch { span, .. }
            | K::StatementOutsideRoutine { span }
            | K::MisplacedDeclaration { span, .. }
            | K::InvalidModifier { span, .. }
            | K::TooManyDimensions { span, .. }
            | K::SectionOrder { span, .. }
            | K::DuplicateName { span, .. }
            | K::Placeholder { span, .. }
            | K::NoModule { span }
            | K::Limit { span, .. }
            | K::TooManyErrors { span, .. } => *span,
        }
    }
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.kind, f)
    }
}

impl std::error::Error for ParseError {}

impl Diagnostic for ParseError {
    fn code<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        self.kind.code()
    }
    fn severity(&self) -> Option<Severity> {
        self.kind.severity()
    }
    fn help<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        self.kind.help()
    }
    fn labels(&self) -> Option<Box<dyn Iterator<Item = LabeledSpan> + '_>> {
        self.kind.labels()
    }
}

impl RapidDiagnostic for ParseError {
    fn source_id(&self) -> Option<SourceId> {
        Some(self.file)
    }
}
