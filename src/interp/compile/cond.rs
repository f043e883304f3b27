//! `bool` conditions as closures: `num` comparisons with inline operands, `AND`/`OR`/`XOR`
//! (both operands always evaluated), `NOT`, constants and `bool` locals; anything else runs
//! on the tree-walking path.

use super::num::{Konst, Src, opnd};
use super::{BoolFn, Code, Cx};
use crate::interp::Interp;
use crate::interp::value::Value;
use crate::ir::{BinOp, Expr, ExprKind, UnOp};
use crate::source::Span;

/// Compile a `bool` expression.
pub(crate) fn cond(cx: &Cx, e: &Expr) -> BoolFn {
    match &e.kind {
        ExprKind::Bool(b) => {
            let b = *b;
            Box::new(move |_, _| Ok(b))
        }
        ExprKind::Binary(
            op @ (BinOp::NumLt
            | BinOp::NumLe
            | BinOp::NumGt
            | BinOp::NumGe
            | BinOp::NumEq
            | BinOp::NumNe),
            a,
            b,
        ) => {
            let (sa, sb) = (a.span, b.span);
            let b = opnd(cx, b);
            match b.konst() {
                Some(k) => cmp(*op, opnd(cx, a), sa, Konst(k), sb),
                None => cmp(*op, opnd(cx, a), sa, b, sb),
            }
        }
        ExprKind::Binary(op @ (BinOp::And | BinOp::Or | BinOp::Xor), a, b) => {
            let (a, b) = (cond(cx, a), cond(cx, b));
            macro_rules! logic {
                (|$x:ident, $y:ident| $body:expr) => {
                    Box::new(move |it, c| {
                        // Both operands are always evaluated (no short circuit).
                        let $x = a(it, c)?;
                        let $y = b(it, c)?;
                        Ok($body)
                    })
                };
            }
            match op {
                BinOp::And => logic!(|x, y| x && y),
                BinOp::Or => logic!(|x, y| x || y),
                _ => logic!(|x, y| x != y),
            }
        }
        ExprKind::Binary(op @ (BinOp::Eq | BinOp::Ne), a, b)
            if super::val::str_eq(cx, a, b, true).is_some() =>
        {
            match super::val::str_eq(cx, a, b, *op == BinOp::Eq) {
                Some(f) => f,
                None => fallback(e),
            }
        }
        ExprKind::Unary(UnOp::Not, a) => {
            let a = cond(cx, a);
            Box::new(move |it, c| Ok(!a(it, c)?))
        }
        ExprKind::Local(s) => {
            let s = *s as usize;
            let e = e.clone();
            Box::new(move |it, c| match it.stack.get(it.bp + s) {
                Some(Value::Bool(b)) => Ok(*b),
                _ => it.eval_bool(&c.prog, &e),
            })
        }
        _ => fallback(e),
    }
}

/// The tree-walking engine's evaluation of `e`.
fn fallback(e: &Expr) -> BoolFn {
    let e = e.clone();
    Box::new(move |it, c| it.eval_bool(&c.prog, &e))
}

/// A `num` comparison (a failing operand raises its error at the operand's span).
fn cmp<A: Src, B: Src>(op: BinOp, a: A, sa: Span, b: B, sb: Span) -> BoolFn {
    macro_rules! cmp {
        (|$x:ident, $y:ident| $body:expr) => {
            Box::new(move |it: &mut Interp, c: &Code| {
                let $x = a.get(it, c);
                if A::FALLIBLE && $x.is_nan() {
                    return Err(it.take_pending(sa));
                }
                let $y = b.get(it, c);
                if B::FALLIBLE && $y.is_nan() {
                    return Err(it.take_pending(sb));
                }
                Ok($body)
            })
        };
    }
    match op {
        BinOp::NumLt => cmp!(|x, y| x < y),
        BinOp::NumLe => cmp!(|x, y| x <= y),
        BinOp::NumGt => cmp!(|x, y| x > y),
        BinOp::NumGe => cmp!(|x, y| x >= y),
        BinOp::NumEq => cmp!(|x, y| x == y),
        _ => cmp!(|x, y| x != y),
    }
}
