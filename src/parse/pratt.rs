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

use super::grammar::Rule;

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

/// The binary operator of an infix pair and its level, or `None` if the rule is not one.
pub(crate) fn infix(rule: Rule) -> Option<(BinOp, u8)> {
    Some(match rule {
        Rule::kw_or => (BinOp::Or, LEVEL_OR),
        Rule::kw_xor => (BinOp::Xor, LEVEL_OR),
        Rule::kw_and => (BinOp::And, LEVEL_AND),
        Rule::op_lt => (BinOp::Lt, LEVEL_REL),
        Rule::op_le => (BinOp::Le, LEVEL_REL),
        Rule::op_eq => (BinOp::Eq, LEVEL_REL),
        Rule::op_ge => (BinOp::Ge, LEVEL_REL),
        Rule::op_gt => (BinOp::Gt, LEVEL_REL),
        Rule::op_ne => (BinOp::Ne, LEVEL_REL),
        Rule::op_add => (BinOp::Add, LEVEL_ADD),
        Rule::op_sub => (BinOp::Sub, LEVEL_ADD),
        Rule::op_mul => (BinOp::Mul, LEVEL_MUL),
        Rule::op_div => (BinOp::Div, LEVEL_MUL),
        Rule::kw_div => (BinOp::IntDiv, LEVEL_MUL),
        Rule::kw_mod => (BinOp::Mod, LEVEL_MUL),
        _ => return None,
    })
}

/// Minimum level for the operand of a sign written where operators of level `min` and
/// above may follow: a whole term at the start of a simple expression, else one primary.
pub(crate) fn sign_operand_level(min: u8) -> u8 {
    min.max(LEVEL_MUL)
}
