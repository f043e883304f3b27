//! The RAPID front end: text → [`ast::File`] with spans, plus structural checks.
//!
//! [`parse_file`] never panics, never overflows the stack and never fails: it returns the
//! best AST it can (broken statements and declarations are left out after recovery) and pushes
//! every problem as a [`ParseError`] into the [`Diagnostics`]. [`check_structure`] adds the
//! checks that need the whole tree but no types (duplicate names, placeholders).
//!
//! pest is used only here: `grammar/*.pest` at the crate root, bound in `parse/grammar.rs`.
//!
//! Speed (see [`ParseOptions`]): pest reads a copy of the text in which a lexical pre-pass
//! has marked names and literal aggregates (`parse/marks.rs`); a large module body is cut at
//! routine starts (`parse/split.rs`) and its pieces are built on several threads
//! (`parse/build/parallel.rs`). Neither changes the AST or the diagnostics; tests compare
//! both ways on every file of the repository and on mutated programs.

use crate::ast;
use crate::diag::Diagnostics;
use crate::source::{IntoSourceText, SourceId};

mod build;
pub mod error;
mod grammar;
pub(crate) mod jobs;
mod marks;
mod names;
mod pratt;
mod prescan;
mod recover;
mod split;
mod structure;

pub use error::{ParseError, ParseErrorKind};

/// Limit of nested brackets and blocks together (checked before pest runs). Real programs
/// nest fewer than ten levels; 64 keeps the recursive-descent parser, the builders and later
/// tree walks far inside a 2 MiB thread stack even in debug builds (where pest needs about
/// 18 KiB of stack per nested IF).
pub const MAX_NESTING: usize = 64;
/// Limit of the depth of one expression tree (long operator chains nest too).
pub const MAX_EXPR_DEPTH: usize = 256;
/// Errors reported per file before the parser stops reporting.
pub const MAX_ERRORS_PER_FILE: usize = 100;

/// Parse one file. Always returns a (possibly partial) AST; every syntax error, including
/// `ENDPROC`/`ENDFUNC` mismatches and statements outside routines, goes into `diags`.
///
/// `text` is kept in the tree ([`ast::File::text`]): give the source map's text
/// (`&map.get(id).text`) to share it rather than copy it.
pub fn parse_file(id: SourceId, text: impl IntoSourceText, diags: &mut Diagnostics) -> ast::File {
    parse_file_with(id, text, diags, &ParseOptions::default())
}

/// [`parse_file`] with explicit [`ParseOptions`]. The AST and the diagnostics do not depend
/// on the options: only the time it takes does.
pub fn parse_file_with(
    id: SourceId,
    text: impl IntoSourceText,
    diags: &mut Diagnostics,
    options: &ParseOptions,
) -> ast::File {
    let text = text.into_source_text();
    let mut file = build::parse(id, &text, diags, options);
    file.text = text;
    file
}

/// How the parser may use the machine's cores.
///
/// A module body of at least [`parallel_min_bytes`](Self::parallel_min_bytes) is cut at lines
/// that start a routine and its pieces are parsed on up to [`threads`](Self::threads) threads;
/// if any piece reports a problem, the module is parsed again in one piece, so diagnostics are
/// exactly those of a one-thread parse.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ParseOptions {
    /// Threads one file may be parsed on (1: only the calling thread).
    pub threads: usize,
    /// The smallest module body, in bytes, that is worth cutting into pieces.
    pub parallel_min_bytes: usize,
    /// Let pest read a copy of the text in which a lexical pre-pass has marked names and
    /// literal aggregates (`parse/marks.rs`): about 20% faster, same result. Off only to
    /// compare the two in tests.
    pub lexical_marks: bool,
    /// Keep each aggregate of literals only (robtargets, tool data) as its text
    /// ([`ast::ExprKind::PackedAggregate`]) rather than as a tree: about a tenth of the
    /// memory, same meaning. Off only to compare the two in tests.
    pub pack_literal_aggregates: bool,
    /// Keep the arguments of a procedure call whose arguments are all names and plain
    /// literals (`MoveL p10, v500, z10, tool0;`) as their text ([`ast::CallArgs::Packed`]):
    /// about a quarter of the memory, same meaning. Off only to compare the two in tests.
    pub pack_simple_calls: bool,
}

impl ParseOptions {
    /// Parse on the calling thread only.
    pub fn single_thread() -> Self {
        ParseOptions {
            threads: 1,
            ..ParseOptions::default()
        }
    }
}

impl Default for ParseOptions {
    /// As many threads as the machine runs in parallel (at most 8); bodies of 256 KiB and up.
    fn default() -> Self {
        // (Asked once: the answer reads cgroup files.)
        static THREADS: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
        ParseOptions {
            threads: *THREADS
                .get_or_init(|| std::thread::available_parallelism().map_or(1, |n| n.get().min(8))),
            parallel_min_bytes: 256 << 10,
            lexical_marks: true,
            pack_literal_aggregates: true,
            pack_simple_calls: true,
        }
    }
}

/// Structural checks on a parsed file: duplicate routine, data and type names in a module,
/// duplicate parameter and data names in a routine, duplicate record components, and a
/// warning for every placeholder.
pub fn check_structure(file: &ast::File, diags: &mut Diagnostics) {
    structure::check(file, diags, &ParseOptions::default())
}

/// [`check_structure`] with explicit [`ParseOptions`] (a large file's items are checked on
/// several threads); the diagnostics, and their order, do not depend on the options.
pub fn check_structure_with(file: &ast::File, diags: &mut Diagnostics, options: &ParseOptions) {
    structure::check(file, diags, options)
}
