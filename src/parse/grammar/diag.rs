//! The diagnostic parser: the same grammar with visible punctuation rules and strict entry
//! rules, used only to explain a region the fast parser had to skip.

/// Same rules as [`super::RapidParser`], but `;`, `,`, `)` ... are named rules, so pest's
/// "expected" list can name them.
#[derive(pest_derive::Parser)]
#[grammar = "grammar/lexical.pest"]
#[grammar = "grammar/marks_diag.pest"]
#[grammar = "grammar/tokens_diag.pest"]
#[grammar = "grammar/expr.pest"]
#[grammar = "grammar/stmt.pest"]
#[grammar = "grammar/stmt_diag.pest"]
#[grammar = "grammar/routine.pest"]
#[grammar = "grammar/module.pest"]
#[grammar = "grammar/recover.pest"]
#[grammar = "grammar/diag.pest"]
pub(crate) struct DiagParser;
