//! Pair → AST builders (one file per syntactic category under `build/`), the shared
//! [`Builder`] state, and the parse entry point that ties prescan, pest and recovery together.

use pest::Parser;

use super::error::{ParseError, ParseErrorKind};
use super::grammar::{Pair, RapidParser, Rule};
use super::recover::{self, Region};
use super::{MAX_ERRORS_PER_FILE, MAX_NESTING, prescan};
use crate::ast::{self, Ident};
use crate::diag::Diagnostics;
use crate::source::{SourceId, Span, Spanned};

mod decl;
mod expr;
mod literal;
mod module;
mod routine;
mod stmt;

/// State shared by the builders of one file.
pub(crate) struct Builder<'t, 'd> {
    pub(crate) file: SourceId,
    pub(crate) text: &'t str,
    diags: &'d mut Diagnostics,
    /// Errors reported so far in this file.
    pub(crate) errors: usize,
    stopped: bool,
}

/// Parse and build one file (see [`super::parse_file`]).
pub(crate) fn parse(file: SourceId, text: &str, diags: &mut Diagnostics) -> ast::File {
    let whole = Span::new(file, 0, text.len());
    let mut b = Builder {
        file,
        text,
        diags,
        errors: 0,
        stopped: false,
    };
    let empty = ast::File {
        modules: Vec::new(),
        span: whole,
    };
    // Spans are u32 offsets.
    if text.len() >= u32::MAX as usize {
        b.error(ParseErrorKind::Limit {
            span: Span::new(file, 0, 0),
            reason: "the file is larger than 4 GiB".into(),
        });
        return empty;
    }
    if let Some((start, end)) = prescan::too_deep(text, MAX_NESTING) {
        b.error(ParseErrorKind::NestingTooDeep {
            span: Span::new(file, start, end),
            limit: MAX_NESTING,
        });
        return empty;
    }
    let file_pair = match RapidParser::parse(Rule::file, text) {
        Ok(mut pairs) => pairs.next(),
        Err(e) => {
            let pos = match e.location {
                pest::error::InputLocation::Pos(p) => p,
                pest::error::InputLocation::Span((p, _)) => p,
            };
            b.error(ParseErrorKind::Limit {
                span: Span::new(file, pos, pos),
                reason: e.variant.message().into_owned(),
            });
            return empty;
        }
    };
    let mut out = empty;
    if let Some(p) = file_pair {
        b.file_(p, &mut out);
    }
    out
}

impl<'t> Builder<'t, '_> {
    /// The span of a pair.
    pub(crate) fn span(&self, p: &Pair<'_>) -> Span {
        let s = p.as_span();
        Span::new(self.file, s.start(), s.end())
    }

    /// An identifier from an `ident` (or `<ID>`) pair.
    pub(crate) fn ident(&self, p: &Pair<'_>) -> Ident {
        Spanned::new(p.as_str().to_string(), self.span(p))
    }

    /// Report an error (up to [`MAX_ERRORS_PER_FILE`] per file).
    pub(crate) fn error(&mut self, kind: ParseErrorKind) {
        if self.errors >= MAX_ERRORS_PER_FILE {
            if !self.stopped {
                self.stopped = true;
                let span = ParseError::new(self.file, kind).span();
                self.diags.push(ParseError::new(
                    self.file,
                    ParseErrorKind::TooManyErrors {
                        span,
                        count: self.errors,
                    },
                ));
            }
            return;
        }
        self.errors += 1;
        self.diags.push(ParseError::new(self.file, kind));
    }

    /// Report a region the fast parser skipped.
    pub(crate) fn skipped(&mut self, p: &Pair<'_>, region: Region) {
        if self.errors >= MAX_ERRORS_PER_FILE {
            // Do not re-parse what will not be reported.
            self.error(ParseErrorKind::Limit {
                span: self.span(p),
                reason: String::new(),
            });
            return;
        }
        let s = p.as_span();
        let kind = recover::diagnose(self.file, self.text, s.start(), s.end(), region);
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
        let span = self.token_span(end.as_span().start());
        self.error(ParseErrorKind::MissingEnd {
            span,
            opener_span: self.span(opener),
            keyword,
            opener: opener.as_str().to_ascii_uppercase(),
        });
    }

    fn file_(&mut self, p: Pair<'_>, out: &mut ast::File) {
        let mut reported_top = false;
        for item in p.into_inner() {
            match item.as_rule() {
                Rule::module => {
                    if let Some(m) = self.module(item) {
                        out.modules.push(m);
                    }
                }
                Rule::bad_top => {
                    self.skipped(&item, Region::Top);
                    reported_top = true;
                }
                _ => {}
            }
        }
        if out.modules.is_empty() && !reported_top {
            let end = self.text.len();
            self.error(ParseErrorKind::NoModule {
                span: Span::new(self.file, end, end),
            });
        }
    }
}
