//! Printing diagnostics and run-time errors on stderr: colour only on a terminal, width from
//! `COLUMNS` (default 100), so piped output is deterministic.

use std::io::{IsTerminal, Write};

use miette::{GraphicalReportHandler, GraphicalTheme};

use crate::diag::{Diagnostics, RapidDiagnostic, escape_controls, render_with};
use crate::interp::RuntimeError;
use crate::source::SourceMap;

/// The miette handler for stderr.
pub fn handler() -> GraphicalReportHandler {
    let color = std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none();
    let theme = if color {
        GraphicalTheme::unicode()
    } else {
        GraphicalTheme::unicode_nocolor()
    };
    let width = std::env::var("COLUMNS")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(100);
    GraphicalReportHandler::new_themed(theme)
        .with_width(width)
        .with_links(false)
}

/// Print all diagnostics.
pub fn diagnostics(diags: &Diagnostics, sources: &SourceMap) {
    if diags.is_empty() {
        return;
    }
    let mut err = std::io::stderr().lock();
    let _ = write!(err, "{}", diags.render_with(&handler(), sources));
}

/// Print an unhandled run-time error the way a controller's event log shows it: the error,
/// the source line, then the RAPID call stack.
pub fn runtime_error(e: &RuntimeError, sources: &SourceMap) {
    let mut out = String::new();
    render_with(&handler(), e as &dyn RapidDiagnostic, sources, &mut out);
    if !e.stack.is_empty() {
        out.push_str("  RAPID call stack (innermost first):\n");
        out.push_str(&escape_controls(&e.stack_text(sources)));
    }
    let mut err = std::io::stderr().lock();
    let _ = write!(err, "{out}");
}
