//! RAPID operator precedence, applied by precedence climbing over the flat operand/operator
//! list that the grammar's `expr` rule yields.
//!
//! Levels, loosest first: `OR`/`XOR` (1) < `NOT` prefix < `AND` (2) < relational (3,
//! non-associative) < `+`/`-` and sign (4) < `*` `/` `DIV` `MOD` (5). Two RAPID rules are
//! encoded on purpose:
//! * `NOT` may only start an expression, and its operand extends over a whole `AND` chain:
//!   `NOT a AND b` is `NOT (a AND b)`; `a AND NOT b` is an error (write `a AND (NOT b)`).
//! * A sign may start any simple expression (`x = -1`); after `*`, `/`, `DIV`, `MOD` or a
//!   binary `+`/`-` it is accepted too (`a * -b`) and then applies to the next primary only.

use crate::ast::BinOp;

/// `OR`, `XOR`.
pub(crate) const LEVEL_OR: u8 = 1;
/// `AND`; also the level of `NOT`'s operand.
pub(crate) const LEVEL_AND: u8 = 2;
/// `<` `<=` `=` `>=` `>` `<>`.
pub(crate) const LEVEL_REL: u8 = 3;
/// Binary `+` `-`, and the operand of a sign at the start of a simple expression.
pub(crate) const LEVEL_ADD: u8 = 4;
/// `*` `/` `DIV` `MOD`.
pub(crate) const LEVEL_MUL: u8 = 5;

/// The binary operator written as `text` (an `infix_op` pair) and its level.
pub(crate) fn infix(text: &str) -> Option<(BinOp, u8)> {
    Some(match text.as_bytes() {
        b"+" => (BinOp::Add, LEVEL_ADD),
        b"-" => (BinOp::Sub, LEVEL_ADD),
        b"*" => (BinOp::Mul, LEVEL_MUL),
        b"/" => (BinOp::Div, LEVEL_MUL),
        b"<" => (BinOp::Lt, LEVEL_REL),
        b"<=" => (BinOp::Le, LEVEL_REL),
        b"=" => (BinOp::Eq, LEVEL_REL),
        b">=" => (BinOp::Ge, LEVEL_REL),
        b">" => (BinOp::Gt, LEVEL_REL),
        b"<>" => (BinOp::Ne, LEVEL_REL),
        _ if text.eq_ignore_ascii_case("AND") => (BinOp::And, LEVEL_AND),
        _ if text.eq_ignore_ascii_case("OR") => (BinOp::Or, LEVEL_OR),
        _ if text.eq_ignore_ascii_case("XOR") => (BinOp::Xor, LEVEL_OR),
        _ if text.eq_ignore_ascii_case("DIV") => (BinOp::IntDiv, LEVEL_MUL),
        _ if text.eq_ignore_ascii_case("MOD") => (BinOp::Mod, LEVEL_MUL),
        _ => return None,
    })
}

/// Minimum level for the operand of a sign written where operators of level `min` and
/// above may follow: a whole term at the start of a simple expression, else one primary.
pub(crate) fn sign_operand_level(min: u8) -> u8 {
    min.max(LEVEL_MUL)
}
