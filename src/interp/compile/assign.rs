//! Statements that compute a `num` and put it somewhere (`x := …`, `a{i} := …`,
//! `RETURN …` in a `FUNC num`), fused with the expression's top operation so that the
//! statement is a single closure.

use super::num::{Elem, GElemL, Src, bin, opnd, typed_copy, typed_left, typed_right};
use super::place::CPlace;
use super::{Code, Cx, StmtFn};
use crate::interp::Interp;
use crate::interp::error::{Exec, Unwind};
use crate::interp::value::Value;
use crate::ir::{BinOp, Expr, ExprKind, Place, Root};
use crate::source::Span;

/// Where the computed `num` goes.
pub(crate) enum Sink {
    /// A whole local slot.
    Local(u32, Place),
    /// A whole global.
    Global(u32, Place),
    /// An element of a 1-D array.
    Elem(Elem, Place),
    /// Any other place.
    Place(CPlace),
    /// The function result (`RETURN`).
    Return,
}

impl Sink {
    /// Where `place := …` writes.
    pub(crate) fn of(cx: &Cx, place: &Place) -> Sink {
        let pl = place.clone();
        match (place.root, place.path.is_empty()) {
            (Root::Local(s), true) => Sink::Local(s, pl),
            (Root::Global(g), true) => Sink::Global(g, pl),
            _ => match Elem::of(place) {
                Some(el) => Sink::Elem(el, pl),
                None => Sink::Place(CPlace::new(cx, place)),
            },
        }
    }

    /// The place written (none for `RETURN`).
    fn place(&self) -> Option<&Place> {
        match self {
            Sink::Local(_, pl) | Sink::Global(_, pl) | Sink::Elem(_, pl) => Some(pl),
            Sink::Place(pl) => Some(pl.ir()),
            Sink::Return => None,
        }
    }

    /// Store `x` (not NaN). Whole locals and globals and 1-D array elements are written in
    /// place; anything else goes through [`Interp::store`].
    #[inline(always)]
    fn put(&self, it: &mut Interp, c: &Code, x: f32) -> Exec<()> {
        match self {
            Sink::Local(s, pl) => match it.stack.get_mut(it.bp + *s as usize) {
                Some(Value::Num(old)) => *old = x,
                Some(other) => *other = Value::Num(x),
                None => return it.store(&c.prog, pl, Value::Num(x)),
            },
            Sink::Global(g, pl) => match it.globals.get_mut(*g as usize) {
                Some(Value::Num(old)) => *old = x,
                _ => return it.store(&c.prog, pl, Value::Num(x)),
            },
            Sink::Elem(el, pl) => match el.num_mut(it) {
                Some(slot) => *slot = x,
                None => return it.store(&c.prog, pl, Value::Num(x)),
            },
            Sink::Place(pl) => return pl.put_num(it, c, x),
            Sink::Return => {
                match &mut it.ret {
                    Value::Num(r) => *r = x,
                    r => *r = Value::Num(x),
                }
                return Err(Unwind::Return);
            }
        }
        Ok(())
    }
}

/// Somewhere a computed `num` is stored.
trait Put: Send + Sync + 'static {
    /// Store `x` (not NaN).
    fn put(&self, it: &mut Interp, c: &Code, x: f32) -> Exec<()>;
}

impl Put for Sink {
    #[inline(always)]
    fn put(&self, it: &mut Interp, c: &Code, x: f32) -> Exec<()> {
        Sink::put(self, it, c, x)
    }
}

/// A whole local slot, as its own type (the statement is compiled for it).
struct LocalSink(u32, Place);

impl Put for LocalSink {
    #[inline(always)]
    fn put(&self, it: &mut Interp, c: &Code, x: f32) -> Exec<()> {
        match it.stack.get_mut(it.bp + self.0 as usize) {
            Some(Value::Num(old)) => *old = x,
            Some(other) => *other = Value::Num(x),
            None => return it.store(&c.prog, &self.1, Value::Num(x)),
        }
        Ok(())
    }
}

/// `g{i}` of a global array and a local index, as its own type.
struct GElemLSink(u32, u32, Place);

impl Put for GElemLSink {
    #[inline(always)]
    fn put(&self, it: &mut Interp, c: &Code, x: f32) -> Exec<()> {
        match GElemL::num_mut(it, self.0, self.1) {
            Some(slot) => *slot = x,
            None => return it.store(&c.prog, &self.2, Value::Num(x)),
        }
        Ok(())
    }
}

/// Store a computed value, or fail with the error behind its NaN (at the value's span).
#[inline(always)]
fn finish<P: Put>(it: &mut Interp, c: &Code, sink: &P, x: f32, vs: Span) -> Exec<()> {
    if x.is_nan() {
        return Err(it.take_pending(vs));
    }
    sink.put(it, c, x)
}

/// A statement computing `value` into `sink`.
pub(crate) fn num_into(cx: &Cx, value: &Expr, sink: Sink) -> StmtFn {
    if let Sink::Local(s, _) = sink
        && let Some((k, add)) = local_step(cx, value, s)
    {
        let slow = num_into_general(cx, value, sink);
        return match add {
            true => step_local::<true>(s, k, slow),
            false => step_local::<false>(s, k, slow),
        };
    }
    let place = sink.place().cloned();
    let general = num_into_general(cx, value, sink);
    match place {
        Some(pl) => super::fast::num_into(cx, &pl, value, general),
        None => general,
    }
}

/// `k` and whether it is added (else subtracted), when `value` is `x + k` or `x - k` of the
/// local in `slot` itself and a constant (`pc := pc + 1`).
fn local_step(cx: &Cx, value: &Expr, slot: u32) -> Option<(f32, bool)> {
    let ExprKind::Binary(op @ (BinOp::NumAdd | BinOp::NumSub), a, b) = &value.kind else {
        return None;
    };
    match (&a.kind, &b.kind) {
        (ExprKind::Local(s), ExprKind::Num(k)) if *s == slot && cx.is_num(a) => {
            Some((*k, *op == BinOp::NumAdd))
        }
        _ => None,
    }
}

/// `x := x + k` (`ADD`) or `x := x - k` of a local: the slot touched once when it holds a
/// `num` and the result is finite; anything else is `slow`, the statement's general form
/// (nothing has been written before it runs).
fn step_local<const ADD: bool>(s: u32, k: f32, slow: StmtFn) -> StmtFn {
    Box::new(move |it, c| {
        if let Some(Value::Num(x)) = it.stack.get_mut(it.bp + s as usize) {
            let r = if ADD { *x + k } else { *x - k };
            if r.is_finite() {
                *x = r;
                return Ok(());
            }
        }
        slow(it, c)
    })
}

/// [`num_into`] without the fused shapes.
fn num_into_general(cx: &Cx, value: &Expr, sink: Sink) -> StmtFn {
    let vs = value.span;
    match &value.kind {
        ExprKind::Binary(op, a, b) if op.is_num_arith() => {
            let (op, a, b) = (*op, opnd(cx, a), opnd(cx, b));
            match sink {
                Sink::Local(s, pl) => {
                    let sink = LocalSink(s, pl);
                    typed_left!(a, |a| typed_right!(b, |b| arith_into(op, a, b, vs, sink)))
                }
                sink => match b {
                    // `q.x := q.x + q.vx`: a component of a local record on the right too.
                    super::num::Opnd::V(super::num::Leaf::F(s, f, g, sp)) => {
                        let b = super::num::FieldSrc(s, f, g, sp);
                        typed_left!(a, |a| arith_into(op, a, b, vs, sink))
                    }
                    b => typed_left!(a, |a| typed_right!(b, |b| arith_into(op, a, b, vs, sink))),
                },
            }
        }
        ExprKind::NumModDivK(a, k, is_mod) => {
            let (a, d, m) = (opnd(cx, a), super::DivK::new(*k), *is_mod);
            match sink {
                Sink::Local(s, pl) => {
                    let sink = LocalSink(s, pl);
                    typed_right!(a, |a| modk_into(a, d, m, vs, sink))
                }
                sink => typed_right!(a, |a| modk_into(a, d, m, vs, sink)),
            }
        }
        _ => {
            // A constant or a local is read by the statement itself; anything else is its
            // own closure.
            let a = opnd(cx, value);
            match sink {
                Sink::Local(s, pl) => {
                    let sink = LocalSink(s, pl);
                    typed_copy!(a, |a| copy_into(a, vs, sink))
                }
                Sink::Elem(el, pl) if el.global_local().is_some() => {
                    let (g, s) = el.global_local().unwrap_or_default();
                    let sink = GElemLSink(g, s, pl);
                    typed_copy!(a, |a| copy_into(a, vs, sink))
                }
                sink => typed_copy!(a, |a| copy_into(a, vs, sink)),
            }
        }
    }
}

/// `a` stored into `sink`.
fn copy_into<A: Src, P: Put>(a: A, vs: Span, sink: P) -> StmtFn {
    Box::new(move |it, c| {
        let x = a.get(it, c);
        finish(it, c, &sink, x, vs)
    })
}

/// `a MOD k` (`is_mod`) or `a DIV k` stored into `sink`.
fn modk_into<A: Src, P: Put>(a: A, d: super::DivK, is_mod: bool, vs: Span, sink: P) -> StmtFn {
    // One closure for MOD and one for DIV: the choice is made here, not per run.
    macro_rules! modk {
        ($m:literal) => {
            Box::new(move |it, c| {
                let x = a.get(it, c);
                let x = it.mod_div_c(x, &d, $m, vs);
                finish(it, c, &sink, x, vs)
            })
        };
    }
    match is_mod {
        true => modk!(true),
        false => modk!(false),
    }
}

fn arith_into<A: Src, B: Src, P: Put>(op: BinOp, a: A, b: B, span: Span, sink: P) -> StmtFn {
    macro_rules! op {
        (|$it:ident, $x:ident, $y:ident| $body:expr) => {
            Box::new(move |it: &mut Interp, c: &Code| {
                let x = bin(it, c, &a, &b, |$it, $x, $y| $body);
                finish(it, c, &sink, x, span)
            })
        };
    }
    match op {
        BinOp::NumAdd => op!(|it, x, y| it.num_result(x + y, span)),
        BinOp::NumSub => op!(|it, x, y| it.num_result(x - y, span)),
        BinOp::NumMul => op!(|it, x, y| it.num_result(x * y, span)),
        BinOp::NumIntDiv => op!(|it, x, y| it.int_op(false, x, y, span)),
        BinOp::NumMod => op!(|it, x, y| it.int_op(true, x, y, span)),
        _ => op!(|it, x, y| it.num_op(op, x, y, span)),
    }
}
