//! Pair → AST builders (one file per syntactic category under `build/`), the shared
//! [`Builder`] state, and the parse entry point that ties prescan, pest and recovery together.

use std::borrow::Cow;

use pest::Parser;

use super::error::{ParseError, ParseErrorKind};
use super::grammar::{Pair, RapidParser, Rule};
use super::recover::{self, Region};
use super::{MAX_ERRORS_PER_FILE, MAX_NESTING, ParseOptions, marks, prescan};
use crate::ast::{self, EcoString, Ident};
use crate::diag::Diagnostics;
use crate::source::{SourceId, Span, Spanned};

mod decl;
mod expr;
mod literal;
mod module;
mod parallel;
mod routine;
mod stmt;

/// State shared by the builders of one file.
pub(crate) struct Builder<'t, 'd> {
    pub(crate) file: SourceId,
    /// The text as written: every token is read from it. (Pest reads a copy with the
    /// pre-pass marks, see [`Marked`].)
    pub(crate) text: &'t str,
    diags: &'d mut Diagnostics,
    /// Byte offset of the piece being built: pest parses `&text[base..]`.
    base: usize,
    /// Errors reported so far in this file.
    pub(crate) errors: usize,
    stopped: bool,
    /// Items of the lists being built (see `build/literal.rs`), reused across the file.
    scratch: Vec<ast::Expr>,
    /// Pack literal aggregates ([`ParseOptions::pack_literal_aggregates`]).
    pub(crate) pack: bool,
    /// Pack the arguments of simple calls ([`ParseOptions::pack_simple_calls`]).
    pub(crate) pack_calls: bool,
}

/// Parse and build one file (see [`super::parse_file`]).
pub(crate) fn parse(
    file: SourceId,
    text: &str,
    diags: &mut Diagnostics,
    options: &ParseOptions,
) -> ast::File {
    let whole = Span::new(file, 0, text.len());
    let mut b = Builder::new(file, text, diags);
    b.pack = options.pack_literal_aggregates;
    b.pack_calls = options.pack_simple_calls;
    let empty = ast::File {
        modules: Vec::new(),
        span: whole,
        // (The caller puts the file's text here.)
        text: Default::default(),
    };
    // Spans are u32 offsets.
    if text.len() >= u32::MAX as usize {
        b.error(ParseErrorKind::Limit {
            span: Span::new(file, 0, 0),
            reason: "the file is larger than 4 GiB".into(),
        });
        return empty;
    }
    // The nesting bound is checked on this thread while other threads mark the text.
    let threads = if text.len() >= options.parallel_min_bytes {
        options.threads
    } else {
        1
    };
    let too_deep = || prescan::too_deep(text, MAX_NESTING);
    // A large file is marked a part at a time (see `Marked`): a marked copy of the whole
    // would hold the text twice while the tree is built.
    let by_parts = options.lexical_marks && threads > 1;
    let (deep, marked) = if options.lexical_marks && !by_parts {
        let (deep, marked) = marks::mark_alongside(text, threads, too_deep);
        (deep, Cow::Owned(marked))
    } else {
        (too_deep(), marks::unmarked(text))
    };
    if let Some((start, end)) = deep {
        b.error(ParseErrorKind::NestingTooDeep {
            span: Span::new(file, start, end),
            limit: MAX_NESTING,
        });
        return empty;
    }
    let marked = Marked {
        text: marked,
        from: 0,
        by_parts,
    };
    let mut out = empty;
    b.file_pieces(&mut out, options, marked);
    out
}

/// What pest reads: the text with the pre-pass marks of `marks.rs`, from byte `from` of the
/// file to its end. A small file is marked whole up front. A large one (`by_parts`) is read
/// unmarked up to its module's body, whose pieces are marked each on its own as they are
/// parsed (`build/parallel.rs`); the rest, from where the pieces end, is marked then.
pub(crate) struct Marked<'t> {
    text: Cow<'t, str>,
    from: usize,
    by_parts: bool,
}

impl<'t, 'd> Builder<'t, 'd> {
    /// A builder for `text` that reports into `diags`.
    pub(crate) fn new(file: SourceId, text: &'t str, diags: &'d mut Diagnostics) -> Self {
        Builder {
            file,
            text,
            diags,
            base: 0,
            errors: 0,
            stopped: false,
            scratch: Vec::new(),
            pack: true,
            pack_calls: true,
        }
    }
}

impl<'t> Builder<'t, '_> {
    /// The span of a pair.
    pub(crate) fn span(&self, p: &Pair<'_>) -> Span {
        let s = p.as_span();
        Span::new(self.file, self.base + s.start(), self.base + s.end())
    }

    /// The byte offset in the file where a pair starts.
    pub(crate) fn start(&self, p: &Pair<'_>) -> usize {
        self.base + p.as_span().start()
    }

    /// The byte offset in the file where a pair ends.
    pub(crate) fn end(&self, p: &Pair<'_>) -> usize {
        self.base + p.as_span().end()
    }

    /// The text of a pair as written. (Pest reads a copy with the pre-pass marks of
    /// `marks.rs`: a pair's own `as_str` may hold a mark instead of a name's first letter.)
    pub(crate) fn text_of(&self, p: &Pair<'_>) -> &'t str {
        let s = p.as_span();
        self.text
            .get(self.base + s.start()..self.base + s.end())
            .unwrap_or("")
    }

    /// An identifier from an `ident` (or `<ID>`) pair.
    pub(crate) fn ident(&self, p: &Pair<'_>) -> Ident {
        Spanned::new(EcoString::from(self.text_of(p)), self.span(p))
    }

    /// Report an error (up to [`MAX_ERRORS_PER_FILE`] per file).
    pub(crate) fn error(&mut self, kind: ParseErrorKind) {
        if self.errors >= MAX_ERRORS_PER_FILE {
            self.too_many_errors(ParseError::new(self.file, kind).span());
            return;
        }
        self.errors += 1;
        self.diags.push(ParseError::new(self.file, kind));
    }

    /// Note once that errors from `span` on are not reported.
    fn too_many_errors(&mut self, span: Span) {
        if !self.stopped {
            self.stopped = true;
            self.diags.push(ParseError::new(
                self.file,
                ParseErrorKind::TooManyErrors {
                    span,
                    count: self.errors,
                },
            ));
        }
    }

    /// Report a region the fast parser skipped.
    pub(crate) fn skipped(&mut self, p: &Pair<'_>, region: Region) {
        if self.errors >= MAX_ERRORS_PER_FILE {
            // Do not re-parse what will not be reported; note the cut once.
            self.too_many_errors(self.span(p));
            return;
        }
        let kind = recover::diagnose(self.file, self.text, self.start(p), self.end(p), region);
        self.error(kind);
    }

    /// The span of the token at byte `pos` (for "expected X before this"); at the end of the
    /// file, the end of the last token.
    pub(crate) fn token_span(&self, pos: usize) -> Span {
        if self
            .text
            .get(pos..)
            .is_none_or(|rest| rest.trim().is_empty())
        {
            let end = recover::prev_token_end(self.text, pos);
            return Span::new(self.file, end, end);
        }
        let (_, (s, e)) = recover::describe(self.text, pos);
        Span::new(self.file, s, e)
    }

    /// Report a missing end keyword: `end` is the `missing_end`-like pair, `opener` the
    /// keyword that opened the construct.
    pub(crate) fn missing_end(&mut self, end: &Pair<'_>, opener: &Pair<'_>, keyword: &'static str) {
        self.missing_end_at(
            self.start(end),
            self.span(opener),
            self.text_of(opener),
            keyword,
        );
    }

    /// Report a missing end keyword expected at byte `pos`.
    pub(crate) fn missing_end_at(
        &mut self,
        pos: usize,
        opener: Span,
        opener_text: &str,
        keyword: &'static str,
    ) {
        let span = self.token_span(pos);
        self.error(ParseErrorKind::MissingEnd {
            span,
            opener_span: opener,
            keyword,
            opener: opener_text.to_ascii_uppercase(),
        });
    }

    /// Parse and build the file piece by piece: outside a module, one `entry_top` at a time
    /// (header, module head, or junk); inside, one `entry_module` (up to 16 items, or the end).
    fn file_pieces(&mut self, out: &mut ast::File, options: &ParseOptions, mut marked: Marked<'_>) {
        let mut pos: usize = 0;
        let mut module: Option<ModuleUnderConstruction<'t>> = None;
        // Whether the open module's body was offered to `parallel_items`.
        let mut offered = false;
        let mut reported_top = false;
        let mut stalls = 0;
        loop {
            let rule = if module.is_some() {
                Rule::entry_module
            } else {
                Rule::entry_top
            };
            let rest = pos
                .checked_sub(marked.from)
                .and_then(|at| marked.text.get(at..))
                .unwrap_or("");
            let piece = match RapidParser::parse(rule, rest) {
                Ok(mut pairs) => pairs.next(),
                Err(e) => {
                    let at = match e.location {
                        pest::error::InputLocation::Pos(p) => p,
                        pest::error::InputLocation::Span((p, _)) => p,
                    };
                    self.error(ParseErrorKind::Limit {
                        span: Span::new(self.file, pos + at, pos + at),
                        reason: e.variant.message().into_owned(),
                    });
                    None
                }
            };
            let Some(piece) = piece else { break };
            self.base = pos;
            let len = piece.as_span().end();
            let mut done = false;
            for item in piece.into_inner() {
                match item.as_rule() {
                    Rule::module_open => {
                        module = Some(self.module_open(item));
                        offered = false;
                    }
                    Rule::bad_top => {
                        self.skipped(&item, Region::Top);
                        reported_top = true;
                    }
                    Rule::module_end => {
                        if let Some(m) = module.take() {
                            out.modules.push(self.module_end(m, item));
                        }
                    }
                    Rule::EOI => done = true,
                    _ => {
                        if let Some(m) = module.as_mut() {
                            self.module_item(m, item);
                        }
                    }
                }
            }
            pos += len;
            if done {
                break;
            }
            if let Some(m) = module.as_mut()
                && !offered
            {
                offered = true;
                let parallel = self.parallel_items(m, pos, options);
                if marked.by_parts {
                    // The rest of the file, from where the pieces end (or the whole body
                    // when it was not cut), is marked in one go.
                    let from = parallel.unwrap_or(pos);
                    marked = Marked {
                        text: Cow::Owned(marks::mark_range(self.text, from, self.text.len())),
                        from,
                        by_parts: false,
                    };
                }
                if let Some(end) = parallel {
                    pos = end;
                    stalls = 0;
                    continue;
                }
            }
            // Only a module's missing end consumes nothing, and the next piece then does:
            // two empty pieces in a row would mean a loop.
            stalls = if len == 0 { stalls + 1 } else { 0 };
            if stalls > 1 {
                self.error(ParseErrorKind::Limit {
                    span: Span::new(self.file, pos, pos),
                    reason: "the parser made no progress here".into(),
                });
                break;
            }
        }
        if let Some(m) = module.take() {
            out.modules.push(m.module);
        }
        if out.modules.is_empty() && !reported_top {
            let end = self.text.len();
            self.error(ParseErrorKind::NoModule {
                span: Span::new(self.file, end, end),
            });
        }
    }
}

/// A module whose items are being built (see `build/module.rs`).
pub(crate) struct ModuleUnderConstruction<'t> {
    /// The module so far.
    pub(crate) module: ast::Module,
    /// The `MODULE` keyword (for "this MODULE is not closed").
    pub(crate) opener: Span,
    /// Its text, for the error message.
    pub(crate) opener_text: &'t str,
}
