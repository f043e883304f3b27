//! Diagnostics: a collector for errors and warnings from every phase, and rendering with the
//! source attached at the edge (graphical, colour-free for tests, or JSON for editors and CI).
//!
//! Phase error enums (`ParseError`, `SemaError`, `RuntimeError`, config errors) hold spans and
//! never source text; they implement [`RapidDiagnostic`] so the renderer can find their file.

use std::fmt;

use miette::{Diagnostic, GraphicalReportHandler, GraphicalTheme, Severity};

use crate::source::{SourceId, SourceMap};

pub mod codes;
mod excerpt;

pub use codes::Code;
use excerpt::Excerpt;
pub(crate) use excerpt::escape_controls;

/// A diagnostic that knows which source file its labels point into.
pub trait RapidDiagnostic: Diagnostic + Send + Sync + 'static {
    /// The file the labels refer to, if any.
    fn source_id(&self) -> Option<SourceId>;
}

/// Accumulated diagnostics of one run of a phase (or several phases).
#[derive(Default)]
pub struct Diagnostics {
    items: Vec<Box<dyn RapidDiagnostic>>,
}

impl fmt::Debug for Diagnostics {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list()
            .entries(self.items.iter().map(|d| d.to_string()))
            .finish()
    }
}

/// Severity of a diagnostic, defaulting to error as miette does.
pub fn severity_of(d: &dyn Diagnostic) -> Severity {
    d.severity().unwrap_or(Severity::Error)
}

impl Diagnostics {
    /// An empty collector.
    pub fn new() -> Self {
        Self::default()
    }

    /// Add one diagnostic.
    pub fn push(&mut self, d: impl RapidDiagnostic) {
        self.items.push(Box::new(d));
    }

    /// Add one boxed diagnostic.
    pub fn push_boxed(&mut self, d: Box<dyn RapidDiagnostic>) {
        self.items.push(d);
    }

    /// Move every diagnostic of `other` into this one.
    pub fn extend(&mut self, other: Diagnostics) {
        self.items.extend(other.items);
    }

    /// The diagnostics, in the order they were found.
    pub fn iter(&self) -> impl Iterator<Item = &dyn RapidDiagnostic> {
        self.items.iter().map(|b| b.as_ref())
    }

    /// Number of diagnostics of any severity.
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// True when nothing was reported.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Number of error-severity diagnostics.
    pub fn error_count(&self) -> usize {
        self.items
            .iter()
            .filter(|d| severity_of(d.as_ref()) == Severity::Error)
            .count()
    }

    /// Number of warnings.
    pub fn warning_count(&self) -> usize {
        self.items
            .iter()
            .filter(|d| severity_of(d.as_ref()) == Severity::Warning)
            .count()
    }

    /// True when at least one error was reported.
    pub fn has_errors(&self) -> bool {
        self.error_count() > 0
    }

    /// Sort by file and position, keeping the order of equal positions.
    pub fn sort(&mut self) {
        self.items.sort_by_key(|d| {
            let start = d
                .labels()
                .and_then(|mut l| l.next())
                .map(|l| l.offset())
                .unwrap_or(0);
            (d.source_id(), start)
        });
    }

    /// Render every diagnostic, colour-free, at `width` columns (deterministic; for tests and
    /// non-terminal output).
    pub fn render_plain(&self, sources: &SourceMap, width: usize) -> String {
        let handler = GraphicalReportHandler::new_themed(GraphicalTheme::unicode_nocolor())
            .with_width(width)
            .with_links(false);
        let mut out = String::new();
        for d in self.iter() {
            render_with(&handler, d, sources, &mut out);
        }
        out
    }

    /// Render every diagnostic with the given miette handler (the CLI chooses colours).
    pub fn render_with(&self, handler: &GraphicalReportHandler, sources: &SourceMap) -> String {
        let mut out = String::new();
        for d in self.iter() {
            render_with(handler, d, sources, &mut out);
        }
        out
    }

    /// Machine-readable diagnostics: a JSON array of objects with `severity`, `code`,
    /// `message`, `help`, `file`, `line`, `column`, `end_line`, `end_column` and `labels`.
    pub fn to_json(&self, sources: &SourceMap) -> String {
        let mut out = String::from("[");
        for (i, d) in self.iter().enumerate() {
            if i > 0 {
                out.push(',');
            }
            out.push_str(&diagnostic_json(d, sources));
        }
        out.push(']');
        out
    }
}

/// Render one diagnostic into `out` with its source attached.
pub fn render_with(
    handler: &GraphicalReportHandler,
    d: &dyn RapidDiagnostic,
    sources: &SourceMap,
    out: &mut String,
) {
    let labels: Vec<miette::LabeledSpan> = d.labels().map(|l| l.collect()).unwrap_or_default();
    let (source, labels) = match d.source_id() {
        Some(id) => {
            let (ex, moved) = Excerpt::new(sources.get(id), &labels);
            (Some(ex), moved)
        }
        None => (None, labels),
    };
    let with = WithSource {
        inner: d,
        source,
        labels,
    };
    if handler.render_report(out, &with).is_err() {
        out.push_str(&d.to_string());
        out.push('\n');
    }
}

/// Render one diagnostic colour-free at `width` columns.
pub fn render_one_plain(d: &dyn RapidDiagnostic, sources: &SourceMap, width: usize) -> String {
    let handler = GraphicalReportHandler::new_themed(GraphicalTheme::unicode_nocolor())
        .with_width(width)
        .with_links(false);
    let mut out = String::new();
    render_with(&handler, d, sources, &mut out);
    out
}

/// A diagnostic with its source attached (miette's "delayed source code"): the excerpt of its
/// file around its labels, the labels moved onto the excerpt, and every text that may quote
/// source with its control characters made visible (see `diag/excerpt.rs`).
struct WithSource<'a> {
    inner: &'a dyn RapidDiagnostic,
    source: Option<Excerpt>,
    labels: Vec<miette::LabeledSpan>,
}

impl fmt::Debug for WithSource<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(&self.inner.to_string(), f)
    }
}

impl fmt::Display for WithSource<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&escape_controls(&self.inner.to_string()))
    }
}

impl std::error::Error for WithSource<'_> {}

impl Diagnostic for WithSource<'_> {
    fn code<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        self.inner.code()
    }
    fn severity(&self) -> Option<Severity> {
        self.inner.severity()
    }
    fn help<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        let help = self.inner.help()?.to_string();
        Some(Box::new(escape_controls(&help).into_owned()))
    }
    fn url<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        self.inner.url()
    }
    fn source_code(&self) -> Option<&dyn miette::SourceCode> {
        self.source.as_ref().map(|s| s as &dyn miette::SourceCode)
    }
    fn labels(&self) -> Option<Box<dyn Iterator<Item = miette::LabeledSpan> + '_>> {
        if self.labels.is_empty() {
            return None;
        }
        Some(Box::new(self.labels.iter().cloned()))
    }
    fn related<'a>(&'a self) -> Option<Box<dyn Iterator<Item = &'a dyn Diagnostic> + 'a>> {
        self.inner.related()
    }
    fn diagnostic_source(&self) -> Option<&dyn Diagnostic> {
        self.inner.diagnostic_source()
    }
}

fn json_str(s: &str) -> String {
    let mut o = String::with_capacity(s.len() + 2);
    o.push('"');
    for c in s.chars() {
        match c {
            '"' => o.push_str("\\\""),
            '\\' => o.push_str("\\\\"),
            '\n' => o.push_str("\\n"),
            '\r' => o.push_str("\\r"),
            '\t' => o.push_str("\\t"),
            // (DEL, C1 controls and the bidirectional overrides too: valid JSON either way,
            // and none of them reaches a terminal that shows the output.)
            c if excerpt::is_terminal_control(c) => o.push_str(&format!("\\u{:04x}", c as u32)),
            c => o.push(c),
        }
    }
    o.push('"');
    o
}

fn diagnostic_json(d: &dyn RapidDiagnostic, sources: &SourceMap) -> String {
    let sev = match severity_of(d) {
        Severity::Error => "error",
        Severity::Warning => "warning",
        Severity::Advice => "advice",
    };
    let code = d.code().map(|c| c.to_string()).unwrap_or_default();
    let help = d.help().map(|h| h.to_string());
    let file = d.source_id().map(|id| sources.get(id));
    let labels: Vec<miette::LabeledSpan> = d.labels().map(|l| l.collect()).unwrap_or_default();
    let pos =
        |off: usize| -> (usize, usize) { file.map(|f| f.line_col(off as u32)).unwrap_or((0, 0)) };
    let mut o = format!(
        "{{\"severity\":\"{sev}\",\"code\":{},\"message\":{}",
        json_str(&code),
        json_str(&d.to_string())
    );
    if let Some(h) = help {
        o.push_str(&format!(",\"help\":{}", json_str(&h)));
    }
    if let Some(f) = file {
        o.push_str(&format!(",\"file\":{}", json_str(&f.name)));
    }
    if let Some(first) = labels.first() {
        let (l, c) = pos(first.offset());
        let (el, ec) = pos(first.offset() + first.len());
        o.push_str(&format!(
            ",\"line\":{l},\"column\":{c},\"end_line\":{el},\"end_column\":{ec}"
        ));
    }
    o.push_str(",\"labels\":[");
    for (i, lab) in labels.iter().enumerate() {
        if i > 0 {
            o.push(',');
        }
        let (l, c) = pos(lab.offset());
        o.push_str(&format!(
            "{{\"line\":{l},\"column\":{c},\"offset\":{},\"length\":{},\"text\":{}}}",
            lab.offset(),
            lab.len(),
            json_str(lab.label().unwrap_or(""))
        ));
    }
    o.push_str("]}");
    o
}
