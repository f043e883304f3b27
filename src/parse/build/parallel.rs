//! A large module body parsed on several threads.
//!
//! The body is cut at lines that start a routine (`split.rs` says why such a line is always
//! between two items of a clean program). Each piece is parsed and built on its own thread,
//! with its own [`Builder`] and diagnostics, as a run of module items that must end exactly at
//! the next cut. The last routine and the module's end stay with the ordinary driver. When any
//! piece reports a problem or does not end at its cut, every piece is dropped and the driver
//! parses the body in one go, so the diagnostics of a broken file are exactly those of a
//! one-thread parse (the cost of a broken file is at most one extra parse of its body).

use std::borrow::Cow;

use pest::Parser;

use super::{Builder, ModuleUnderConstruction};
use crate::ast::{Module, ModuleItem};
use crate::diag::Diagnostics;
use crate::parse::grammar::{RapidParser, Rule};
use crate::parse::{ParseOptions, jobs, marks, split};
use crate::source::{SourceId, Span, Spanned};

/// The size of a piece of a large module body: small enough that the marked copies of the
/// pieces being parsed are a small part of the memory, large enough that the pieces' own
/// costs (a builder, a vector of items) do not matter.
const PIECE_BYTES: usize = 1 << 20;

/// The items built from one piece and the span they cover.
type Piece = (Vec<ModuleItem>, Span);

impl<'t> Builder<'t, '_> {
    /// Build the items of the module `m`, whose body starts at `from`, on several threads, up to
    /// the start of its last routine. Returns where the ordinary driver goes on, or `None` when
    /// the body is too small, cannot be cut, or a piece reported a problem (then nothing was
    /// added to `m`).
    pub(crate) fn parallel_items(
        &mut self,
        m: &mut ModuleUnderConstruction<'t>,
        from: usize,
        options: &ParseOptions,
    ) -> Option<usize> {
        let threads = options.threads;
        let min = options.parallel_min_bytes;
        if threads < 2 || self.errors > 0 || self.text.len().saturating_sub(from) < min {
            return None;
        }
        let starts = split::routine_starts(self.text, from, min / (threads * 4));
        let last = *starts.last()?;
        if last - from < min {
            return None;
        }
        // Cuts at about equal distances, each at the first routine start past its mark: at
        // least one piece per thread, and pieces of about PIECE_BYTES (each piece is marked
        // for pest on its own, so only the pieces being parsed are held twice).
        let count = threads.max((last - from) / PIECE_BYTES);
        let mut cuts = vec![from];
        for k in 1..count {
            let mark = from + (last - from) * k / count;
            let i = starts.partition_point(|&s| s < mark);
            if let Some(&c) = starts.get(i)
                && c > *cuts.last()?
                && c < last
            {
                cuts.push(c);
            }
        }
        cuts.push(last);
        if cuts.len() < 3 {
            return None;
        }
        let (file, text) = (self.file, self.text);
        let runs: Vec<(usize, usize)> = cuts.windows(2).map(|w| (w[0], w[1])).collect();
        let (_, pieces) = jobs::run(
            threads,
            runs,
            |(a, b)| piece(file, text, a, b, options),
            || (),
        );
        let pieces = pieces
            .into_iter()
            .map(Option::flatten)
            .collect::<Option<Vec<Piece>>>()?;
        // (One allocation of the right size: growing by doubling would hold the old and the
        // new list at once, three times the items of a large module.)
        m.module
            .items
            .reserve(pieces.iter().map(|(items, _)| items.len()).sum());
        for (items, span) in pieces {
            m.module.items.extend(items);
            m.module.span = m.module.span.merge(span);
        }
        Some(last)
    }
}

/// Parse and build the items of `text[from..to]`, which must be whole module items only;
/// `None` if anything in it is not. (Pest parses a copy of the piece with the pre-pass marks,
/// see `marks.rs`, or without them when `options` say so.)
fn piece(
    file: SourceId,
    text: &str,
    from: usize,
    to: usize,
    options: &ParseOptions,
) -> Option<Piece> {
    let mut diags = Diagnostics::new();
    let marked = if options.lexical_marks {
        Cow::Owned(marks::mark_range(text, from, to))
    } else {
        marks::unmarked(text.get(from..to)?)
    };
    let mut b = Builder::new(file, text, &mut diags);
    b.pack = options.pack_literal_aggregates;
    b.pack_calls = options.pack_simple_calls;
    let at = Span::new(file, from, from);
    let mut m = ModuleUnderConstruction {
        module: Module {
            name: Spanned::new(crate::ast::EcoString::new(), at),
            attrs: Vec::new(),
            items: Vec::new(),
            span: at,
        },
        opener: at,
        opener_text: "",
    };
    let mut pos = from;
    loop {
        let piece = RapidParser::parse(Rule::entry_module, marked.get(pos - from..)?)
            .ok()?
            .next()?;
        b.base = pos;
        let len = piece.as_span().end();
        for item in piece.into_inner() {
            if item.as_rule() == Rule::module_end {
                // Only "no ENDMODULE" at the very end of the piece ends it well.
                let end = item.into_inner().next()?;
                let clean = end.as_rule() == Rule::missing_endmodule && b.start(&end) == to;
                drop(b);
                return (clean && diags.is_empty()).then_some((m.module.items, m.module.span));
            }
            b.module_item(&mut m, item);
        }
        if len == 0 || b.errors > 0 {
            return None;
        }
        pos += len;
    }
}
