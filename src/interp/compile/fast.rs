//! `num` statements over elements of module arrays (`stack{sp - 1} := stack{sp - 1} +
//! stack{sp}`, `reg{code{pc}} := stack{sp}`, `pc := pc + 1`): a fast path that only reads
//! plain `num`s (no error can arise, nothing is written until the result is known), and the
//! statement's general form when anything is off — a value that is not a `num`, an index
//! that is not an integer in bounds, a result that is not finite. The general form then
//! runs from the start, so every error and its place is the general form's.

use super::{Cx, StmtFn};
use crate::interp::Interp;
use crate::interp::value::{Value, f32_int};
use crate::ir::{BinOp, Expr, ExprKind, PathOp, Place, Root};

/// An index read without side effects.
#[derive(Clone, Copy)]
pub(crate) enum Ix {
    /// A constant.
    K(f32),
    /// A local.
    L(u32),
    /// A local plus a constant (`i - 1` is `i + -1`, the same IEEE operation).
    Lk(u32, f32),
}

/// A `num` operand read without side effects: `None` stands for "take the general form".
#[derive(Clone, Copy)]
pub(crate) enum Pk {
    /// A constant.
    K(f32),
    /// A local.
    L(u32),
    /// A local plus a constant.
    Lk(u32, f32),
    /// `g{i}` of a global 1-D array.
    Ga(u32, Ix),
    /// `g{h{i}}` of global 1-D arrays.
    Gga(u32, u32, Ix),
}

/// Where a statement of this module writes.
#[derive(Clone, Copy)]
pub(crate) enum Dst {
    /// A whole local.
    L(u32),
    /// `g{i}` of a global 1-D array.
    Ga(u32, Ix),
    /// `g{h{i}}` of global 1-D arrays.
    Gga(u32, u32, Ix),
}

/// The 0-based offset of index `x`, when it is an integer ≥ 1 (a too large offset is
/// refused by the bounds check of the array).
#[inline(always)]
fn off(x: f32) -> Option<usize> {
    let i = x as i32;
    (i as f32 == x && i >= 1).then(|| (i - 1) as usize)
}

/// The `num` a value holds.
#[inline(always)]
fn num(v: Option<&Value>) -> Option<f32> {
    match v {
        Some(Value::Num(x)) => Some(*x),
        _ => None,
    }
}

/// Element `o` of a 1-D array of `num`s.
#[inline(always)]
fn elem(v: Option<&Value>, o: usize) -> Option<f32> {
    match v {
        Some(Value::Array(a)) if a.rank == 1 && o < a.dims[0] as usize => num(a.data.get(o)),
        _ => None,
    }
}

/// Element `o` of a 1-D array of `num`s, to write.
#[inline(always)]
fn elem_mut(v: Option<&mut Value>, o: usize) -> Option<&mut f32> {
    match v {
        Some(Value::Array(a)) if a.rank == 1 && o < a.dims[0] as usize => match a.data.get_mut(o) {
            Some(Value::Num(x)) => Some(x),
            _ => None,
        },
        _ => None,
    }
}

impl Ix {
    /// The index of `e`, if it has one of these shapes.
    fn of(cx: &Cx, e: &Expr) -> Option<Ix> {
        match Pk::of_leaf(cx, e)? {
            Pk::K(x) => Some(Ix::K(x)),
            Pk::L(s) => Some(Ix::L(s)),
            Pk::Lk(s, k) => Some(Ix::Lk(s, k)),
            _ => None,
        }
    }

    /// The 0-based offset.
    #[inline(always)]
    fn off(self, it: &Interp) -> Option<usize> {
        off(match self {
            Ix::K(x) => x,
            Ix::L(s) => num(it.stack.get(it.bp + s as usize))?,
            Ix::Lk(s, k) => num(it.stack.get(it.bp + s as usize))? + k,
        })
    }
}

/// The array element a place or a load denotes: `(g, None, i)` for `g{i}`, `(g, Some(h),
/// i)` for `g{h{i}}`.
fn global_elem(cx: &Cx, pl: &Place) -> Option<(u32, Option<u32>, Ix)> {
    let (Root::Global(g), [PathOp::Index(es)]) = (pl.root, &*pl.path) else {
        return None;
    };
    let [ie] = &**es else {
        return None;
    };
    if !cx.is_num(ie) {
        return None;
    }
    if let Some(ix) = Ix::of(cx, ie) {
        return Some((g, None, ix));
    }
    match &ie.kind {
        ExprKind::Load(inner) => match global_elem(cx, inner)? {
            (h, None, ix) => Some((g, Some(h), ix)),
            _ => None,
        },
        _ => None,
    }
}

impl Pk {
    /// A constant, a local or a local plus a constant.
    fn of_leaf(cx: &Cx, e: &Expr) -> Option<Pk> {
        match &e.kind {
            ExprKind::Num(x) => Some(Pk::K(*x)),
            ExprKind::Local(s) if cx.is_num(e) => Some(Pk::L(*s)),
            ExprKind::Binary(op @ (BinOp::NumAdd | BinOp::NumSub), a, b) if cx.is_num(a) => {
                match (&a.kind, &b.kind) {
                    (ExprKind::Local(s), ExprKind::Num(k)) => {
                        Some(Pk::Lk(*s, if *op == BinOp::NumSub { -*k } else { *k }))
                    }
                    _ => None,
                }
            }
            _ => None,
        }
    }

    /// The operand `e`, if it has one of these shapes.
    pub(crate) fn of(cx: &Cx, e: &Expr) -> Option<Pk> {
        if let Some(p) = Pk::of_leaf(cx, e) {
            return Some(p);
        }
        match &e.kind {
            ExprKind::Load(pl) if cx.is_num(e) => match global_elem(cx, pl)? {
                (g, None, ix) => Some(Pk::Ga(g, ix)),
                (g, Some(h), ix) => Some(Pk::Gga(g, h, ix)),
            },
            _ => None,
        }
    }

    /// Whether this is an array element.
    pub(crate) fn is_elem(self) -> bool {
        matches!(self, Pk::Ga(..) | Pk::Gga(..))
    }

    /// The value, or `None`: take the general form.
    #[inline(always)]
    pub(crate) fn get(self, it: &Interp) -> Option<f32> {
        match self {
            Pk::K(x) => Some(x),
            Pk::L(s) => num(it.stack.get(it.bp + s as usize)),
            Pk::Lk(s, k) => {
                let r = num(it.stack.get(it.bp + s as usize))? + k;
                r.is_finite().then_some(r)
            }
            Pk::Ga(g, ix) => elem(it.globals.get(g as usize), ix.off(it)?),
            Pk::Gga(g, h, ix) => {
                let i = elem(it.globals.get(h as usize), ix.off(it)?)?;
                elem(it.globals.get(g as usize), off(i)?)
            }
        }
    }
}

impl Dst {
    /// Where `place := …` writes, if it has one of these shapes.
    pub(crate) fn of(cx: &Cx, pl: &Place) -> Option<Dst> {
        match (pl.root, pl.path.is_empty()) {
            (Root::Local(s), true) => Some(Dst::L(s)),
            _ => match global_elem(cx, pl)? {
                (g, None, ix) => Some(Dst::Ga(g, ix)),
                (g, Some(h), ix) => Some(Dst::Gga(g, h, ix)),
            },
        }
    }
}

/// A [`Dst`] of one kind, as its own type (a statement is compiled for its target's kind).
trait Poke: Copy + Send + Sync + 'static {
    /// The `num` to overwrite, or `None`: take the general form.
    fn slot(self, it: &mut Interp) -> Option<&mut f32>;
}

/// [`Dst::L`].
#[derive(Clone, Copy)]
struct ToL(u32);

impl Poke for ToL {
    #[inline(always)]
    fn slot(self, it: &mut Interp) -> Option<&mut f32> {
        match it.stack.get_mut(it.bp + self.0 as usize) {
            Some(Value::Num(x)) => Some(x),
            _ => None,
        }
    }
}

/// [`Dst::Ga`].
#[derive(Clone, Copy)]
struct ToGa(u32, Ix);

impl Poke for ToGa {
    #[inline(always)]
    fn slot(self, it: &mut Interp) -> Option<&mut f32> {
        let o = self.1.off(it)?;
        elem_mut(it.globals.get_mut(self.0 as usize), o)
    }
}

/// [`Dst::Gga`].
#[derive(Clone, Copy)]
struct ToGga(u32, u32, Ix);

impl Poke for ToGga {
    #[inline(always)]
    fn slot(self, it: &mut Interp) -> Option<&mut f32> {
        let i = elem(it.globals.get(self.1 as usize), self.2.off(it)?)?;
        elem_mut(it.globals.get_mut(self.0 as usize), off(i)?)
    }
}

/// `$body` with `$d` bound to `$dst` as its own type.
macro_rules! with_poke {
    ($dst:expr, |$d:ident| $body:expr) => {
        match $dst {
            Dst::L(s) => {
                let $d = ToL(s);
                $body
            }
            Dst::Ga(g, ix) => {
                let $d = ToGa(g, ix);
                $body
            }
            Dst::Gga(g, h, ix) => {
                let $d = ToGga(g, h, ix);
                $body
            }
        }
    };
}

/// The operations of [`op`].
const ADD: u8 = 0;
const SUB: u8 = 1;
const MUL: u8 = 2;
const DIV: u8 = 3;
const INT_DIV: u8 = 4;
const MOD: u8 = 5;

/// `x OP y` when it is a finite `num` that the general form computes without an error (the
/// same IEEE operations as `Interp::num_op`).
#[inline(always)]
fn op<const OP: u8>(x: f32, y: f32) -> Option<f32> {
    let r = match OP {
        ADD => x + y,
        SUB => x - y,
        MUL => x * y,
        DIV if y != 0.0 => x / y,
        DIV => return None,
        _ => {
            let (xi, yi) = (f32_int(x)?, f32_int(y)?);
            if yi == 0 || xi == i32::MIN {
                return None;
            }
            return Some(if OP == MOD { xi % yi } else { xi / yi } as f32);
        }
    };
    r.is_finite().then_some(r)
}

/// `place := value` with a fast path, when the place and the value have the shapes of this
/// module and one of them is an array element (statements of locals and constants only
/// are compiled well already); `general` is the statement's general form.
pub(crate) fn num_into(cx: &Cx, place: &Place, value: &Expr, general: StmtFn) -> StmtFn {
    let Some(dst) = Dst::of(cx, place) else {
        return general;
    };
    let dst_elem = !matches!(dst, Dst::L(_));
    if let Some(a) = Pk::of(cx, value) {
        if !(dst_elem || a.is_elem()) {
            return general;
        }
        return with_poke!(dst, |d| copy(a, d, general));
    }
    let ExprKind::Binary(bop, a, b) = &value.kind else {
        return general;
    };
    let (Some(a), Some(b)) = (Pk::of(cx, a), Pk::of(cx, b)) else {
        return general;
    };
    if !(dst_elem || a.is_elem() || b.is_elem()) {
        return general;
    }
    match bop {
        BinOp::NumAdd => with_poke!(dst, |d| arith::<_, ADD>(a, b, d, general)),
        BinOp::NumSub => with_poke!(dst, |d| arith::<_, SUB>(a, b, d, general)),
        BinOp::NumMul => with_poke!(dst, |d| arith::<_, MUL>(a, b, d, general)),
        BinOp::NumDiv => with_poke!(dst, |d| arith::<_, DIV>(a, b, d, general)),
        BinOp::NumIntDiv => with_poke!(dst, |d| arith::<_, INT_DIV>(a, b, d, general)),
        BinOp::NumMod => with_poke!(dst, |d| arith::<_, MOD>(a, b, d, general)),
        _ => general,
    }
}

/// `d := a`.
fn copy<D: Poke>(a: Pk, d: D, general: StmtFn) -> StmtFn {
    Box::new(move |it, c| {
        if let Some(x) = a.get(it)
            && let Some(slot) = d.slot(it)
        {
            *slot = x;
            return Ok(());
        }
        general(it, c)
    })
}

/// `d := a OP b`.
fn arith<D: Poke, const OP: u8>(a: Pk, b: Pk, d: D, general: StmtFn) -> StmtFn {
    Box::new(move |it, c| {
        if let (Some(x), Some(y)) = (a.get(it), b.get(it))
            && let Some(r) = op::<OP>(x, y)
            && let Some(slot) = d.slot(it)
        {
            *slot = r;
            return Ok(());
        }
        general(it, c)
    })
}
