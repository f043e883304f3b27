//! The pest grammar bindings: [`RapidParser`] builds the syntax tree; [`diag::DiagParser`]
//! re-parses broken regions to name the expected tokens. This is the only pest importer
//! besides the builders, which walk the pairs it produces.

pub(crate) mod diag;

/// The fast parser: punctuation is silent (no pairs), recovery rules are included.
#[derive(pest_derive::Parser)]
#[grammar = "grammar/lexical.pest"]
#[grammar = "grammar/tokens.pest"]
#[grammar = "grammar/expr.pest"]
#[grammar = "grammar/stmt.pest"]
#[grammar = "grammar/routine.pest"]
#[grammar = "grammar/module.pest"]
#[grammar = "grammar/recover.pest"]
pub(crate) struct RapidParser;

/// A pair of the fast parser.
pub(crate) type Pair<'i> = pest::iterators::Pair<'i, Rule>;
