//! `bool` conditions as closures: `num` comparisons with inline operands, `AND`/`OR`/`XOR`
//! (both operands always evaluated), `NOT`, constants and `bool` locals; anything else runs
//! on the tree-walking path.

use super::fast::Pk;
use super::num::{Src, opnd, typed_left, typed_right};
use super::{BoolFn, Code, Cx};
use crate::interp::Interp;
use crate::interp::error::Exec;
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
            BinOp::NumLt | BinOp::NumLe | BinOp::NumGt | BinOp::NumGe | BinOp::NumEq | BinOp::NumNe,
            ..,
        ) => with_cond(cx, e, Boxed),
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
        ExprKind::Local(_) => with_cond(cx, e, Boxed),
        _ => fallback(e),
    }
}

/// The tree-walking engine's evaluation of `e`.
fn fallback(e: &Expr) -> BoolFn {
    let e = e.clone();
    Box::new(move |it, c| it.eval_bool(&c.prog, &e))
}

/// A compiled condition of a known type (see [`with_cond`]).
pub(crate) trait Cond: Send + Sync + 'static {
    /// Whether the condition holds.
    fn test(&self, it: &mut Interp, c: &Code) -> Exec<bool>;
}

impl Cond for BoolFn {
    #[inline(always)]
    fn test(&self, it: &mut Interp, c: &Code) -> Exec<bool> {
        self(it, c)
    }
}

/// What is built from a condition, for the condition's own type: a statement testing a
/// comparison of locals and constants is compiled for exactly that comparison.
pub(crate) trait WithCond {
    /// What is built.
    type Out;
    /// Build it around `cond`.
    fn with<C: Cond>(self, cond: C) -> Self::Out;
}

/// The condition itself, as a closure.
struct Boxed;

impl WithCond for Boxed {
    type Out = BoolFn;
    fn with<C: Cond>(self, cond: C) -> BoolFn {
        Box::new(move |it, c| cond.test(it, c))
    }
}

/// A `bool` local (any other value: the tree-walking engine's evaluation of the expression).
pub(crate) struct BoolLocal(u32, Expr);

impl Cond for BoolLocal {
    #[inline(always)]
    fn test(&self, it: &mut Interp, c: &Code) -> Exec<bool> {
        match it.stack.get(it.bp + self.0 as usize) {
            Some(Value::Bool(b)) => Ok(*b),
            _ => it.eval_bool(&c.prog, &self.1),
        }
    }
}

/// The comparison operators of [`Cmp`].
const LT: u8 = 0;
const LE: u8 = 1;
const GT: u8 = 2;
const GE: u8 = 3;
const EQ: u8 = 4;
const NE: u8 = 5;

/// `$m!(OP)` for the `num` comparison operator `$op`, `$other` for any other operator.
macro_rules! by_cmp {
    ($op:expr, $m:ident, $other:expr) => {
        match $op {
            BinOp::NumLt => $m!(LT),
            BinOp::NumLe => $m!(LE),
            BinOp::NumGt => $m!(GT),
            BinOp::NumGe => $m!(GE),
            BinOp::NumEq => $m!(EQ),
            BinOp::NumNe => $m!(NE),
            _ => $other,
        }
    };
}

/// A `num` comparison `a OP b` (a failing operand raises its error at the operand's span).
pub(crate) struct Cmp<A, B, const OP: u8> {
    a: A,
    sa: Span,
    b: B,
    sb: Span,
}

impl<A: Src, B: Src, const OP: u8> Cond for Cmp<A, B, OP> {
    #[inline(always)]
    fn test(&self, it: &mut Interp, c: &Code) -> Exec<bool> {
        let x = self.a.get(it, c);
        if A::FALLIBLE && x.is_nan() {
            return Err(it.take_pending(self.sa));
        }
        let y = self.b.get(it, c);
        if B::FALLIBLE && y.is_nan() {
            return Err(it.take_pending(self.sb));
        }
        Ok(cmp::<OP>(x, y))
    }
}

/// `w` built around condition `e`: a `num` comparison with its operands typed (locals,
/// constants, `MOD`/`DIV` of a local by a constant), anything else as a closure.
pub(crate) fn with_cond<W: WithCond>(cx: &Cx, e: &Expr, w: W) -> W::Out {
    if let ExprKind::Local(s) = e.kind {
        return w.with(BoolLocal(s, e.clone()));
    }
    let ExprKind::Binary(op, a, b) = &e.kind else {
        return w.with(cond(cx, e));
    };
    if let (Some(pa), Some(pb)) = (Pk::of(cx, a), Pk::of(cx, b))
        && (pa.is_elem() || pb.is_elem())
    {
        // An array element compared: read in place when it is a plain `num`, else the
        // comparison's general form (compiled as below), which raises the errors.
        macro_rules! fast {
            ($op:expr) => {
                w.with(FastCmp::<{ $op }> {
                    a: pa,
                    b: pb,
                    general: with_cond_general(cx, e, Boxed),
                })
            };
        }
        return by_cmp!(op, fast, w.with(cond(cx, e)));
    }
    with_cond_general(cx, e, w)
}

/// A `num` comparison of operands read without side effects (see [`Pk`]), with the
/// comparison's general form for when a value is not a plain `num`.
struct FastCmp<const OP: u8> {
    a: Pk,
    b: Pk,
    general: BoolFn,
}

impl<const OP: u8> Cond for FastCmp<OP> {
    #[inline(always)]
    fn test(&self, it: &mut Interp, c: &Code) -> Exec<bool> {
        let (Some(x), Some(y)) = (self.a.get(it), self.b.get(it)) else {
            return (self.general)(it, c);
        };
        Ok(cmp::<OP>(x, y))
    }
}

/// `x OP y`.
#[inline(always)]
fn cmp<const OP: u8>(x: f32, y: f32) -> bool {
    match OP {
        LT => x < y,
        LE => x <= y,
        GT => x > y,
        GE => x >= y,
        EQ => x == y,
        _ => x != y,
    }
}

/// [`with_cond`] of a comparison without array elements.
fn with_cond_general<W: WithCond>(cx: &Cx, e: &Expr, w: W) -> W::Out {
    let ExprKind::Binary(op, a, b) = &e.kind else {
        return w.with(cond(cx, e));
    };
    let (sa, sb) = (a.span, b.span);
    macro_rules! cmp {
        ($op:expr) => {
            typed_left!(opnd(cx, a), |a| typed_right!(opnd(cx, b), |b| w
                .with(Cmp::<_, _, { $op }> { a, sa, b, sb })))
        };
    }
    by_cmp!(op, cmp, w.with(cond(cx, e)))
}
