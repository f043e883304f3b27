//! `num` expressions as closures. Operands that are constants, locals, globals or elements of
//! 1-D arrays are read inline; anything else is a nested closure, or the tree-walking path
//! for shapes without a compiled form. As there, NaN signals an error kept in
//! `Interp::pending`.

use super::place::CPlace;
use super::{Code, Cx, DivK};
use crate::interp::Interp;
use crate::interp::value::{Value, f32_int};
use crate::ir::{BinOp, Expr, ExprKind, PathOp, Place, Root, UnOp};
use crate::source::Span;

/// A compiled `num` expression (NaN: an error is pending).
pub(crate) type NumFn = Box<dyn Fn(&mut Interp, &Code) -> f32 + Send + Sync>;

/// An operand read without a call.
pub(crate) enum Leaf {
    /// A constant.
    K(f32),
    /// A local slot.
    L(u32, Span),
    /// A global.
    G(u32, Span),
    /// `a{i}` of a 1-D local or global array with a leaf index, and the IR load (slow path).
    E(Box<(Elem, Expr)>),
    /// `slot.f`, or `slot.f.g` ([`NO_FIELD`] for none), of a record held by a local (`q.x`,
    /// `p.trans.z`): one or two indexed loads, no place walk.
    F(u32, u16, u16, Span),
    /// Any other place holding a `num`, and the expression's span.
    P(Box<(CPlace, Span)>),
}

/// No second component in [`Leaf::F`].
pub(crate) const NO_FIELD: u16 = u16::MAX;

/// The local and components of `slot.f` or `slot.f.g` (a `num` read from a local record).
fn local_field(cx: &Cx, e: &Expr, pl: &Place) -> Option<(u32, u16, u16)> {
    let Root::Local(s) = pl.root else {
        return None;
    };
    if !cx.is_num(e) {
        return None;
    }
    match *pl.path {
        [PathOp::Field(f)] if f != NO_FIELD => Some((s, f, NO_FIELD)),
        [PathOp::Field(f), PathOp::Field(g)] if f != NO_FIELD && g != NO_FIELD => Some((s, f, g)),
        _ => None,
    }
}

/// The `num` at `slot.f` (or `slot.f.g`) of the current frame, when the local holds a
/// record with a `num` there (`None`: the general path decides, with its errors).
#[inline(always)]
pub(crate) fn field_num(it: &Interp, s: u32, f: u16, g: u16) -> Option<f32> {
    let Some(Value::Record(fs)) = it.stack.get(it.bp + s as usize) else {
        return None;
    };
    let mut v = fs.get(f as usize)?;
    if g != NO_FIELD {
        let Value::Record(gs) = v else {
            return None;
        };
        v = gs.get(g as usize)?;
    }
    match v {
        Value::Num(x) => Some(*x),
        _ => None,
    }
}

/// A component of a local record read inline, as its own type (see [`LocalSrc`]).
pub(crate) struct FieldSrc(pub u32, pub u16, pub u16, pub Span);

impl Src for FieldSrc {
    const FALLIBLE: bool = true;
    #[inline(always)]
    fn get(&self, it: &mut Interp, c: &Code) -> f32 {
        match field_num(it, self.0, self.1, self.2) {
            Some(x) => x,
            None => it.field_slow(c, self.0, self.1, self.2, self.3),
        }
    }
}

impl Leaf {
    /// The leaf for `e`, if it is one.
    pub(crate) fn of(cx: &Cx, e: &Expr) -> Option<Leaf> {
        Some(match &e.kind {
            ExprKind::Num(x) => Leaf::K(*x),
            ExprKind::Local(s) => Leaf::L(*s, e.span),
            ExprKind::Global(g) => Leaf::G(*g, e.span),
            ExprKind::Load(pl) => match (Elem::of(pl), local_field(cx, e, pl)) {
                (Some(el), _) => Leaf::E(Box::new((el, e.clone()))),
                (None, Some((s, f, g))) => Leaf::F(s, f, g, e.span),
                (None, None) if cx.is_num(e) => Leaf::P(Box::new((CPlace::new(cx, pl), e.span))),
                (None, None) => return None,
            },
            _ => return None,
        })
    }

    /// The value (NaN: an error is pending).
    #[inline(always)]
    pub(crate) fn get(&self, it: &mut Interp, c: &Code) -> f32 {
        match self {
            Leaf::K(x) => *x,
            Leaf::L(s, span) => match it.stack.get(it.bp + *s as usize) {
                Some(Value::Num(x)) => *x,
                _ => it.leaf_slow(c, ExprKind::Local(*s), *span),
            },
            Leaf::G(g, span) => match it.globals.get(*g as usize) {
                Some(Value::Num(x)) => *x,
                _ => it.leaf_slow(c, ExprKind::Global(*g), *span),
            },
            Leaf::E(b) => elem_get(b, it, c),
            Leaf::F(s, f, g, span) => match field_num(it, *s, *f, *g) {
                Some(x) => x,
                None => it.field_slow(c, *s, *f, *g, *span),
            },
            Leaf::P(b) => b.0.num(it, c, b.1),
        }
    }
}

/// The value of an array element operand.
#[inline(never)]
fn elem_get(b: &(Elem, Expr), it: &mut Interp, c: &Code) -> f32 {
    match b.0.peek(it) {
        Some(x) => x,
        None => it.nf_cold(c, &b.1),
    }
}

/// An operand of a compiled `num` operation.
pub(crate) enum Opnd {
    /// A leaf.
    V(Leaf),
    /// `a op b` (`+ - * / DIV MOD`) of two leaves, computed inline.
    B(Box<(BinOp, Leaf, Leaf, Span)>),
    /// `a MOD k` or `a DIV k` (`true` for MOD) of a leaf, computed inline.
    M(Box<(Leaf, DivK, bool, Span)>),
    /// Anything else: a closure.
    D(NumFn),
}

/// Something a compiled operation reads a `num` from.
pub(crate) trait Src: Send + Sync + 'static {
    /// Whether `get` can fail (return NaN).
    const FALLIBLE: bool;
    /// The value (NaN: an error is pending).
    fn get(&self, it: &mut Interp, c: &Code) -> f32;
}

/// A constant operand, known not to fail.
pub(crate) struct Konst(pub f32);

impl Src for Konst {
    const FALLIBLE: bool = false;
    #[inline(always)]
    fn get(&self, _: &mut Interp, _: &Code) -> f32 {
        self.0
    }
}

impl Src for Opnd {
    const FALLIBLE: bool = true;
    #[inline(always)]
    fn get(&self, it: &mut Interp, c: &Code) -> f32 {
        match self {
            Opnd::V(l) => l.get(it, c),
            Opnd::B(b) => {
                let (op, l, r, span) = &**b;
                let x = l.get(it, c);
                if x.is_nan() {
                    return x;
                }
                let y = r.get(it, c);
                if y.is_nan() {
                    return y;
                }
                it.num_op(*op, x, y, *span)
            }
            Opnd::M(m) => {
                let (l, d, is_mod, span) = &**m;
                let x = l.get(it, c);
                it.mod_div_c(x, d, *is_mod, *span)
            }
            Opnd::D(f) => f(it, c),
        }
    }
}

/// A local slot read inline, as its own type: an operation on it is compiled for exactly
/// this operand (no run-time choice of the operand's kind).
pub(crate) struct LocalSrc(pub u32, pub Span);

impl Src for LocalSrc {
    const FALLIBLE: bool = true;
    #[inline(always)]
    fn get(&self, it: &mut Interp, c: &Code) -> f32 {
        match it.stack.get(it.bp + self.0 as usize) {
            Some(Value::Num(x)) => *x,
            _ => it.leaf_slow(c, ExprKind::Local(self.0), self.1),
        }
    }
}

/// `a MOD k` (`MOD` true) or `a DIV k` of a typed operand and a constant integer `k`.
pub(crate) struct ModDivSrc<A, const MOD: bool>(pub A, pub DivK, pub Span);

impl<A: Src, const MOD: bool> Src for ModDivSrc<A, MOD> {
    const FALLIBLE: bool = true;
    #[inline(always)]
    fn get(&self, it: &mut Interp, c: &Code) -> f32 {
        let x = self.0.get(it, c);
        it.mod_div_c(x, &self.1, MOD, self.2)
    }
}

/// `$body` with `$a` bound to operand `$o` as a typed source when it is a local, a component
/// of a local record, or `a MOD k` / `a DIV k` of a local (the left operand of comparisons
/// and arithmetic), else as itself.
macro_rules! typed_left {
    ($o:expr, |$a:ident| $body:expr) => {
        match $o {
            $crate::interp::compile::num::Opnd::V($crate::interp::compile::num::Leaf::L(s, sp)) => {
                let $a = $crate::interp::compile::num::LocalSrc(s, sp);
                $body
            }
            $crate::interp::compile::num::Opnd::V($crate::interp::compile::num::Leaf::F(
                s,
                f,
                g,
                sp,
            )) => {
                let $a = $crate::interp::compile::num::FieldSrc(s, f, g, sp);
                $body
            }
            $crate::interp::compile::num::Opnd::M(m) => match *m {
                ($crate::interp::compile::num::Leaf::L(s, sp), d, true, span) => {
                    let src = $crate::interp::compile::num::LocalSrc(s, sp);
                    let $a = $crate::interp::compile::num::ModDivSrc::<_, true>(src, d, span);
                    $body
                }
                ($crate::interp::compile::num::Leaf::L(s, sp), d, false, span) => {
                    let src = $crate::interp::compile::num::LocalSrc(s, sp);
                    let $a = $crate::interp::compile::num::ModDivSrc::<_, false>(src, d, span);
                    $body
                }
                other => {
                    let $a = $crate::interp::compile::num::Opnd::M(Box::new(other));
                    $body
                }
            },
            o => {
                let $a = o;
                $body
            }
        }
    };
}

/// `$body` with `$b` bound to operand `$o` as a constant or a local when it is one (the right
/// operand of comparisons and arithmetic), else as itself.
macro_rules! typed_right {
    ($o:expr, |$b:ident| $body:expr) => {
        match $o {
            $crate::interp::compile::num::Opnd::V($crate::interp::compile::num::Leaf::K(k)) => {
                let $b = $crate::interp::compile::num::Konst(k);
                $body
            }
            $crate::interp::compile::num::Opnd::V($crate::interp::compile::num::Leaf::L(s, sp)) => {
                let $b = $crate::interp::compile::num::LocalSrc(s, sp);
                $body
            }
            o => {
                let $b = o;
                $body
            }
        }
    };
}
pub(crate) use {typed_left, typed_right};

/// `a` then `b` (stopping at the first failure), then `f` on both values.
#[inline(always)]
pub(crate) fn bin<A: Src, B: Src>(
    it: &mut Interp,
    c: &Code,
    a: &A,
    b: &B,
    f: impl FnOnce(&mut Interp, f32, f32) -> f32,
) -> f32 {
    let x = a.get(it, c);
    if A::FALLIBLE && x.is_nan() {
        return x;
    }
    let y = b.get(it, c);
    if B::FALLIBLE && y.is_nan() {
        return y;
    }
    f(it, x, y)
}

/// An index without side effects (read twice when the fast path gives up).
#[derive(Clone, Copy)]
enum Idx {
    K(f32),
    L(u32),
    G(u32),
}

/// An element `a{i}` of a 1-D `num` array held by a local or a global.
pub(crate) struct Elem {
    root: Root,
    idx: Idx,
}

impl Elem {
    /// The element access a place denotes, if it has this shape.
    pub(crate) fn of(pl: &Place) -> Option<Elem> {
        let [PathOp::Index(es)] = &*pl.path else {
            return None;
        };
        let [ie] = &**es else {
            return None;
        };
        if matches!(pl.root, Root::Ref(_)) {
            return None;
        }
        let idx = match ie.kind {
            ExprKind::Num(x) => Idx::K(x),
            ExprKind::Local(s) => Idx::L(s),
            ExprKind::Global(g) => Idx::G(g),
            _ => return None,
        };
        Some(Elem { root: pl.root, idx })
    }

    /// The 0-based offset of the element, if the index is an integer in bounds of a 1-D
    /// array (`None`: the general path decides, with its errors).
    #[inline(always)]
    fn offset(&self, it: &Interp) -> Option<usize> {
        let x = match self.idx {
            Idx::K(x) => x,
            Idx::L(s) => match it.stack.get(it.bp + s as usize) {
                Some(Value::Num(x)) => *x,
                _ => return None,
            },
            Idx::G(g) => match it.globals.get(g as usize) {
                Some(Value::Num(x)) => *x,
                _ => return None,
            },
        };
        let i = f32_int(x)?;
        (i >= 1).then_some((i - 1) as usize)
    }

    /// The element's value when the fast path applies.
    #[inline(always)]
    fn peek(&self, it: &Interp) -> Option<f32> {
        let o = self.offset(it)?;
        let arr = match self.root {
            Root::Local(s) => it.stack.get(it.bp + s as usize),
            Root::Global(g) => it.globals.get(g as usize),
            Root::Ref(_) => None,
        };
        match arr {
            Some(Value::Array(a)) if a.rank == 1 && o < a.dims[0] as usize => match a.data.get(o) {
                Some(Value::Num(x)) => Some(*x),
                _ => None,
            },
            _ => None,
        }
    }

    /// The element, for writing, when the fast path applies.
    #[inline(always)]
    pub(crate) fn num_mut<'a>(&self, it: &'a mut Interp) -> Option<&'a mut f32> {
        let o = self.offset(it)?;
        let arr = match self.root {
            Root::Local(s) => it.stack.get_mut(it.bp + s as usize),
            Root::Global(g) => it.globals.get_mut(g as usize),
            Root::Ref(_) => None,
        };
        match arr {
            Some(Value::Array(a)) if a.rank == 1 && o < a.dims[0] as usize => {
                match a.data.get_mut(o) {
                    Some(Value::Num(x)) => Some(x),
                    _ => None,
                }
            }
            _ => None,
        }
    }
}

/// An operand for `e`: a leaf, an operation on leaves, or a closure.
pub(crate) fn opnd(cx: &Cx, e: &Expr) -> Opnd {
    if let Some(l) = Leaf::of(cx, e) {
        return Opnd::V(l);
    }
    match &e.kind {
        ExprKind::Binary(op, a, b) if op.is_num_arith() => {
            if let (Some(a), Some(b)) = (Leaf::of(cx, a), Leaf::of(cx, b)) {
                return Opnd::B(Box::new((*op, a, b, e.span)));
            }
        }
        ExprKind::NumModDivK(a, k, is_mod) => {
            if let Some(a) = Leaf::of(cx, a) {
                return Opnd::M(Box::new((a, DivK::new(*k), *is_mod, e.span)));
            }
        }
        _ => {}
    }
    Opnd::D(num(cx, e))
}

/// Compile a `num` expression.
pub(crate) fn num(cx: &Cx, e: &Expr) -> NumFn {
    let span = e.span;
    match &e.kind {
        ExprKind::Num(x) => {
            let x = *x;
            Box::new(move |_, _| x)
        }
        ExprKind::Local(_) | ExprKind::Global(_) => {
            let o = opnd(cx, e);
            Box::new(move |it, c| o.get(it, c))
        }
        ExprKind::Load(pl) if Elem::of(pl).is_some() || cx.is_num(e) => {
            let o = opnd(cx, e);
            Box::new(move |it, c| o.get(it, c))
        }
        ExprKind::Binary(op, a, b) if op.is_num_arith() => {
            arith(*op, opnd(cx, a), opnd(cx, b), span)
        }
        ExprKind::NumModDivK(a, k, is_mod) => {
            let (a, d) = (opnd(cx, a), DivK::new(*k));
            macro_rules! modk {
                ($m:literal) => {
                    Box::new(move |it, c| {
                        let x = a.get(it, c);
                        it.mod_div_c(x, &d, $m, span)
                    })
                };
            }
            match is_mod {
                true => modk!(true),
                false => modk!(false),
            }
        }
        ExprKind::Unary(UnOp::NumNeg, a) => {
            let a = opnd(cx, a);
            Box::new(move |it, c| -a.get(it, c))
        }
        ExprKind::Call(r, args) => {
            if cx.p.routine(*r).simple {
                let call = super::simple::SCall::new(cx, *r, args, span);
                Box::new(move |it, c| it.call_simple(c, &call))
            } else {
                let call = super::CCall::new(cx, *r, args, span);
                Box::new(move |it, c| {
                    let r = it.ccall(c, &call);
                    it.nf_of(r, span)
                })
            }
        }
        ExprKind::Native(n, args) if super::natives::str_num(cx, *n, args, span).is_some() => {
            super::natives::str_num(cx, *n, args, span).unwrap_or_else(|| fallback(e))
        }
        ExprKind::Native(n, args) if super::natives::math(cx, *n, args, span).is_some() => {
            super::natives::math(cx, *n, args, span).unwrap_or_else(|| fallback(e))
        }
        ExprKind::Native(n, args) => {
            let call = super::call::CNative::new(cx, *n, args, span);
            Box::new(move |it, c| {
                let r = it.cnative(c, &call);
                it.nf_of(r, span)
            })
        }
        _ => fallback(e),
    }
}

/// The tree-walking path for `e`.
fn fallback(e: &Expr) -> NumFn {
    let e = e.clone();
    Box::new(move |it, c| it.nf(&c.prog, &e))
}

/// `a op b` for a `num` arithmetic operator (a constant right operand is read without
/// checks).
fn arith(op: BinOp, a: Opnd, b: Opnd, span: Span) -> NumFn {
    // Components of local records (`a.x`) and their products (`a.x * b.y`, the terms of
    // pose math) are read as their own types too.
    use RecOpnd::{F, M, O};
    match (RecOpnd::of(a), RecOpnd::of(b)) {
        (F(a), F(b)) => arith_t(op, a, b, span),
        (M(a), M(b)) => arith_t(op, a, b, span),
        (F(a), M(b)) => arith_t(op, a, b, span),
        (M(a), F(b)) => arith_t(op, a, b, span),
        (M(a), O(b)) => arith_t(op, a, b, span),
        (O(a), M(b)) => arith_t(op, a, b, span),
        (F(a), O(b)) => typed_right!(b, |b| arith_t(op, a, b, span)),
        (O(a), F(b)) => typed_left!(a, |a| arith_t(op, a, b, span)),
        (O(a), O(b)) => typed_left!(a, |a| typed_right!(b, |b| arith_t(op, a, b, span))),
    }
}

/// An operand of arithmetic, with components of local records set apart.
enum RecOpnd {
    /// `r.f` of a local record.
    F(FieldSrc),
    /// `r.f * s.g` of local records.
    M(MulSrc),
    /// Anything else.
    O(Opnd),
}

impl RecOpnd {
    fn of(o: Opnd) -> RecOpnd {
        match o {
            Opnd::V(Leaf::F(s, f, g, sp)) => RecOpnd::F(FieldSrc(s, f, g, sp)),
            Opnd::B(b) => match *b {
                (BinOp::NumMul, Leaf::F(s, f, g, sp), Leaf::F(t, h, k, tp), span) => {
                    RecOpnd::M(MulSrc(FieldSrc(s, f, g, sp), FieldSrc(t, h, k, tp), span))
                }
                other => RecOpnd::O(Opnd::B(Box::new(other))),
            },
            o => RecOpnd::O(o),
        }
    }
}

/// `a.f * b.g` of two components of local records, as its own type.
pub(crate) struct MulSrc(FieldSrc, FieldSrc, Span);

impl Src for MulSrc {
    const FALLIBLE: bool = true;
    #[inline(always)]
    fn get(&self, it: &mut Interp, c: &Code) -> f32 {
        let span = self.2;
        bin(it, c, &self.0, &self.1, |it, x, y| {
            it.num_result(x * y, span)
        })
    }
}

fn arith_t<A: Src, B: Src>(op: BinOp, a: A, b: B, span: Span) -> NumFn {
    macro_rules! op {
        (|$it:ident, $x:ident, $y:ident| $body:expr) => {
            Box::new(move |it: &mut Interp, c: &Code| bin(it, c, &a, &b, |$it, $x, $y| $body))
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

impl Interp {
    /// A leaf that is not a plain `num` (a missing optional parameter, a `dnum`): the
    /// tree-walking path decides.
    #[cold]
    #[inline(never)]
    fn leaf_slow(&mut self, c: &Code, kind: ExprKind, span: Span) -> f32 {
        self.nf_slow(&c.prog, &Expr { kind, span })
    }

    /// A [`Leaf::F`] whose local holds no record with a `num` there (a missing optional
    /// parameter): the tree-walking path decides, on the place as lowered (whose span is
    /// the expression's).
    #[cold]
    #[inline(never)]
    pub(crate) fn field_slow(&mut self, c: &Code, s: u32, f: u16, g: u16, span: Span) -> f32 {
        let mut path = vec![PathOp::Field(f)];
        if g != NO_FIELD {
            path.push(PathOp::Field(g));
        }
        let pl = Place {
            root: Root::Local(s),
            path: path.into(),
            span,
        };
        self.nf_slow(
            &c.prog,
            &Expr {
                kind: ExprKind::Load(Box::new(pl)),
                span,
            },
        )
    }

    /// The tree-walking path for an expression whose fast path gave up before any side
    /// effect.
    #[cold]
    #[inline(never)]
    pub(crate) fn nf_cold(&mut self, c: &Code, e: &Expr) -> f32 {
        self.nf(&c.prog, e)
    }
}
