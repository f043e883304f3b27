//! Literals as the builder reads them: the reading is `ast/literal.rs` (a packed aggregate is
//! unpacked with the same code); here its problems become parse errors.

use super::Builder;
use crate::ast::literal::{LitReader, Problem, decode_string, number_value};
use crate::ast::{Expr, ExprKind, PackedAggregate};
use crate::parse::MAX_EXPR_DEPTH;
use crate::parse::error::ParseErrorKind;
use crate::parse::grammar::Pair;
use crate::source::Span;

impl Builder<'_, '_> {
    /// The value of a `number` pair; out-of-range values are reported (and kept as parsed).
    pub(crate) fn number(&mut self, p: &Pair<'_>) -> f64 {
        self.number_text(self.text_of(p), self.span(p))
    }

    /// The value of the number literal `text` written at `span`.
    pub(crate) fn number_text(&mut self, text: &str, span: Span) -> f64 {
        let mut errors = Vec::new();
        let v = number_value(text, span, &mut errors);
        self.report(errors);
        v
    }

    /// The value of a `string` pair with escapes decoded; invalid escapes are reported and
    /// kept as written.
    pub(crate) fn string(&mut self, p: &Pair<'_>) -> String {
        self.string_text(self.text_of(p), self.start(p))
    }

    /// The value of the string literal `raw` (with its quotes) written at byte `start`.
    pub(crate) fn string_text(&mut self, raw: &str, start: usize) -> String {
        let mut errors = Vec::new();
        let v = decode_string(raw, self.file, start, &mut errors);
        self.report(errors);
        v
    }

    /// Report what reading a literal found.
    fn report(&mut self, problems: Vec<Problem>) {
        for p in problems {
            self.error(match p {
                Problem::NumberOutOfRange { span, text } => {
                    ParseErrorKind::NumberOutOfRange { span, text }
                }
                Problem::InvalidEscape { span, text } => {
                    ParseErrorKind::InvalidEscape { span, text }
                }
                Problem::TooDeep { span } => ParseErrorKind::ExpressionTooComplex {
                    span,
                    limit: MAX_EXPR_DEPTH,
                },
            });
        }
    }
}

impl Builder<'_, '_> {
    /// A `literal_aggregate` pair: the grammar has checked its shape; read it here. An
    /// aggregate read without a diagnostic is kept packed ([`ExprKind::PackedAggregate`]):
    /// its text instead of its tree.
    pub(crate) fn literal_aggregate(
        &mut self,
        p: &Pair<'_>,
        depth: usize,
    ) -> Option<(Expr, usize)> {
        let text = self.text_of(p);
        let base = self.start(p);
        // First only check it (no tree is built), then pack it if nothing was found.
        let mut check = LitReader {
            file: self.file,
            build: false,
            max_depth: MAX_EXPR_DEPTH,
            scratch: &mut self.scratch,
            errors: Vec::new(),
        };
        let mut pos = 0;
        if self.pack
            && let Some((e, d)) = check.aggregate(text, base, &mut pos, depth)
            && check.errors.is_empty()
        {
            // (Its span is the text read, from `[` to `]`: where unpacking reads it.)
            debug_assert_eq!(e.span, Span::new(self.file, base, base + pos));
            return Some((
                Expr {
                    kind: ExprKind::PackedAggregate(PackedAggregate::new()),
                    span: e.span,
                },
                d,
            ));
        }
        let mut read = LitReader {
            file: self.file,
            build: true,
            max_depth: MAX_EXPR_DEPTH,
            scratch: &mut self.scratch,
            errors: Vec::new(),
        };
        let mut pos = 0;
        let built = read.aggregate(text, base, &mut pos, depth);
        let problems = std::mem::take(&mut read.errors);
        self.report(problems);
        built
    }
}
