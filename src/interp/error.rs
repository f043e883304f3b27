//! Run-time errors (`RuntimeError`, with the RAPID error number, span and call stack) and the
//! non-local exits of execution (`Unwind`), kept apart from each other.

use std::fmt;

use miette::{Diagnostic, LabeledSpan};

use super::errnum;
use crate::diag::RapidDiagnostic;
use crate::diag::codes::{self, Code};
use crate::source::{SourceId, SourceMap, Span};

/// What kind of run-time error this is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    /// A RAPID error with its number (`ERRNO`); `ERROR` handlers can take it.
    Rapid(i32),
    /// An instruction or function rapidvc does not implement (yet); not recoverable.
    Unsupported,
    /// A placeholder (`<SMT>`, `<EXP>` …) was reached; not recoverable.
    Placeholder,
    /// The operation budget ran out or the before-statement hook asked to stop.
    Aborted,
    /// The host (controller) failed; not recoverable.
    Host,
    /// `Assert` failed (`rapidvc test`); not recoverable.
    Assertion,
}

/// One entry of the RAPID call stack: a routine and where it was executing.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StackEntry {
    /// Routine name.
    pub routine: String,
    /// The statement being executed in that routine (the call, for callers).
    pub span: Span,
}

/// Frames shown at each end of a deep call stack (see [`RuntimeError::stack_text`]).
pub const STACK_ENDS: usize = 10;

/// A run-time error as a controller reports it: number, name, text, source position and
/// call stack (innermost first).
#[derive(Clone, Debug, PartialEq)]
pub struct RuntimeError {
    /// Kind (and RAPID error number).
    pub kind: ErrorKind,
    /// Details for the event log.
    pub message: String,
    /// Where it happened.
    pub span: Span,
    /// Call stack at the time of the error, innermost first.
    pub stack: Vec<StackEntry>,
}

impl RuntimeError {
    /// The RAPID error number, for recoverable errors.
    pub fn errno(&self) -> Option<i32> {
        match self.kind {
            ErrorKind::Rapid(n) => Some(n),
            _ => None,
        }
    }

    /// True when an `ERROR` handler may take this error.
    pub fn is_recoverable(&self) -> bool {
        matches!(self.kind, ErrorKind::Rapid(_))
    }

    /// The call stack as text lines (`  in foo at file.mod:12:5`), innermost first. A deep
    /// stack (a runaway recursion) shows its innermost and outermost [`STACK_ENDS`] frames
    /// and one line counting the frames left out.
    pub fn stack_text(&self, sources: &SourceMap) -> String {
        let mut s = String::new();
        let n = self.stack.len();
        let cut = n > 2 * STACK_ENDS + 1;
        for (i, e) in self.stack.iter().enumerate() {
            if cut && (STACK_ENDS..n - STACK_ENDS).contains(&i) {
                if i == STACK_ENDS {
                    s.push_str(&format!("  … {} more frames …\n", n - 2 * STACK_ENDS));
                }
                continue;
            }
            s.push_str(&format!(
                "  in {} at {}\n",
                e.routine,
                sources.location(e.span)
            ));
        }
        s
    }

    fn headline(&self) -> String {
        match self.kind {
            ErrorKind::Rapid(n) => {
                let text = errnum::by_num(n)
                    .map(|e| e.text)
                    .unwrap_or("Error raised by the program");
                format!("{}: {}", errnum::describe(n), text)
            }
            ErrorKind::Unsupported => "not supported by rapidvc".into(),
            ErrorKind::Placeholder => "placeholder reached".into(),
            ErrorKind::Aborted => "execution aborted".into(),
            ErrorKind::Host => "controller error".into(),
            ErrorKind::Assertion => "assertion failed".into(),
        }
    }
}

impl fmt::Display for RuntimeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.kind {
            ErrorKind::Rapid(_) => f.write_str(&self.headline()),
            _ => f.write_str(&self.message),
        }
    }
}

impl std::error::Error for RuntimeError {}

impl Diagnostic for RuntimeError {
    fn code<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        let code = match self.kind {
            ErrorKind::Rapid(n) => match errnum::by_num(n) {
                Some(e) => codes::rapid_error_code(e.name),
                None => Code::RunUserError.to_string(),
            },
            ErrorKind::Unsupported => Code::RunUnsupported.to_string(),
            ErrorKind::Placeholder => Code::RunPlaceholder.to_string(),
            ErrorKind::Aborted => Code::RunAborted.to_string(),
            ErrorKind::Host => Code::RunHost.to_string(),
            ErrorKind::Assertion => Code::TestAssertion.to_string(),
        };
        Some(Box::new(code))
    }

    fn help<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        let h = match self.kind {
            ErrorKind::Rapid(_) => {
                "add an ERROR handler to this routine or a caller to recover from this error"
            }
            ErrorKind::Unsupported => "see the README for what rapidvc supports",
            ErrorKind::Placeholder => "replace the placeholder with real code",
            _ => return None,
        };
        Some(Box::new(h))
    }

    fn labels(&self) -> Option<Box<dyn Iterator<Item = LabeledSpan> + '_>> {
        let label = match self.kind {
            _ if !self.message.is_empty() && self.is_recoverable() => self.message.clone(),
            ErrorKind::Rapid(n) => errnum::by_num(n)
                .map(|e| e.name.to_string())
                .unwrap_or_else(|| format!("error {n} raised here")),
            ErrorKind::Unsupported | ErrorKind::Placeholder => "here".to_string(),
            _ => "stopped here".to_string(),
        };
        Some(Box::new(std::iter::once(LabeledSpan::new_with_span(
            Some(label),
            self.span,
        ))))
    }
}

impl RapidDiagnostic for RuntimeError {
    fn source_id(&self) -> Option<SourceId> {
        Some(self.span.source)
    }
}

/// Why execution left the normal statement sequence.
#[derive(Debug)]
pub enum Unwind {
    /// A RAPID error that the current routine's `ERROR` handler has not seen yet.
    Error(Box<RuntimeError>),
    /// An error on its way to the caller (no handler, `RAISE` in a handler, retry limit).
    Propagate(Box<RuntimeError>),
    /// An error no handler may take (unsupported, placeholder, error in a handler or trap).
    Fatal(Box<RuntimeError>),
    /// `RETURN [value]`; the value waits in the interpreter's return slot (`Value::Absent`
    /// for procedures), which keeps this enum two words wide.
    Return,
    /// `GOTO label`.
    Goto(u32),
    /// `RETRY` in an `ERROR` handler.
    Retry,
    /// `TRYNEXT` in an `ERROR` handler.
    TryNext,
    /// `EXIT`: end of program execution.
    Exit,
    /// `ExitCycle`: end of the current cycle.
    ExitCycle,
    /// `Stop`: program stopped.
    Stop,
}

/// Result of executing or evaluating something.
pub type Exec<T> = Result<T, Unwind>;
