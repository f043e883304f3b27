//! `num` expressions as closures. Operands that are constants, locals, globals or elements of
//! 1-D arrays are read inline; anything else is a nested closure, or the tree-walking path
//! for shapes without a compiled form. As there, NaN signals an error kept in
//! `Interp::pending`.

use super::Code;
use crate::interp::Interp;
use crate::interp::call::MAX_DEPTH;
use crate::interp::value::{Value, f32_int};
use crate::ir::{Arg, BinOp, Expr, ExprKind, PathOp, Place, Program, Root, RoutineId, Ty, UnOp};
use crate::source::Span;

/// A compiled `num` expression (NaN: an error is pending).
pub(crate) type NumFn = Box<dyn Fn(&mut Interp, &Code) -> f32 + Send + Sync>;

/// An operand of a compiled `num` operation.
pub(crate) enum Opnd {
    /// A constant.
    K(f32),
    /// A local slot.
    L(u32, Span),
    /// A global.
    G(u32, Span),
    /// `a{i}` of a 1-D local or global array with a leaf index, and the IR load (slow path).
    E(Box<(Elem, Expr)>),
    /// Anything else.
    D(NumFn),
}

impl Opnd {
    /// The operand's value (NaN: an error is pending).
    #[inline(always)]
    pub(crate) fn get(&self, it: &mut Interp, c: &Code) -> f32 {
        match self {
            Opnd::K(x) => *x,
            Opnd::L(s, span) => match it.stack.get(it.bp + *s as usize) {
                Some(Value::Num(x)) => *x,
                _ => it.leaf_slow(c, ExprKind::Local(*s), *span),
            },
            Opnd::G(g, span) => match it.globals.get(*g as usize) {
                Some(Value::Num(x)) => *x,
                _ => it.leaf_slow(c, ExprKind::Global(*g), *span),
            },
            Opnd::E(b) => match b.0.peek(it) {
                Some(x) => x,
                None => it.nf_cold(c, &b.1),
            },
            Opnd::D(f) => f(it, c),
        }
    }
}

/// An index without side effects (read twice when the fast path gives up).
#[derive(Clone, Copy)]
enum Leaf {
    K(f32),
    L(u32),
    G(u32),
}

/// An element `a{i}` of a 1-D `num` array held by a local or a global.
pub(crate) struct Elem {
    root: Root,
    idx: Leaf,
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
            ExprKind::Num(x) => Leaf::K(x),
            ExprKind::Local(s) => Leaf::L(s),
            ExprKind::Global(g) => Leaf::G(g),
            _ => return None,
        };
        Some(Elem { root: pl.root, idx })
    }

    /// The 0-based offset of the element, if the index is an integer in bounds of a 1-D
    /// array (`None`: the general path decides, with its errors).
    #[inline(always)]
    fn offset(&self, it: &Interp) -> Option<usize> {
        let x = match self.idx {
            Leaf::K(x) => x,
            Leaf::L(s) => match it.stack.get(it.bp + s as usize) {
                Some(Value::Num(x)) => *x,
                _ => return None,
            },
            Leaf::G(g) => match it.globals.get(g as usize) {
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

/// An operand for `e`.
pub(crate) fn opnd(p: &Program, e: &Expr) -> Opnd {
    match &e.kind {
        ExprKind::Num(x) => Opnd::K(*x),
        ExprKind::Local(s) => Opnd::L(*s, e.span),
        ExprKind::Global(g) => Opnd::G(*g, e.span),
        ExprKind::Load(pl) => match Elem::of(pl) {
            Some(el) => Opnd::E(Box::new((el, e.clone()))),
            None => Opnd::D(num(p, e)),
        },
        _ => Opnd::D(num(p, e)),
    }
}

/// Compile a `num` expression.
pub(crate) fn num(p: &Program, e: &Expr) -> NumFn {
    let span = e.span;
    match &e.kind {
        ExprKind::Num(x) => {
            let x = *x;
            Box::new(move |_, _| x)
        }
        ExprKind::Local(_) | ExprKind::Global(_) => {
            let o = opnd(p, e);
            Box::new(move |it, c| o.get(it, c))
        }
        ExprKind::Load(pl) if Elem::of(pl).is_some() => {
            let o = opnd(p, e);
            Box::new(move |it, c| o.get(it, c))
        }
        ExprKind::Binary(op, a, b) if is_num_arith(*op) => arith(*op, opnd(p, a), opnd(p, b), span),
        ExprKind::NumModDivK(a, k, is_mod) => {
            let (a, k, is_mod) = (opnd(p, a), *k, *is_mod);
            Box::new(move |it, c| {
                let x = a.get(it, c);
                it.mod_div_k(x, k, is_mod, span)
            })
        }
        ExprKind::Unary(UnOp::NumNeg, a) => {
            let a = opnd(p, a);
            Box::new(move |it, c| -a.get(it, c))
        }
        ExprKind::Call(r, args) => {
            if p.routine(*r).simple {
                let call = SCall::new(p, *r, args, span);
                Box::new(move |it, c| it.call_simple_c(c, &call))
            } else {
                let call = super::CCall::new(p, *r, args, span);
                Box::new(move |it, c| {
                    let r = it.ccall(c, &call);
                    it.nf_of(r, span)
                })
            }
        }
        _ => fallback(e),
    }
}

/// The tree-walking path for `e`.
fn fallback(e: &Expr) -> NumFn {
    let e = e.clone();
    Box::new(move |it, c| it.nf(&c.prog, &e))
}

/// `+ - * / DIV MOD` on `num`.
fn is_num_arith(op: BinOp) -> bool {
    matches!(
        op,
        BinOp::NumAdd
            | BinOp::NumSub
            | BinOp::NumMul
            | BinOp::NumDiv
            | BinOp::NumIntDiv
            | BinOp::NumMod
    )
}

/// `a op b` for a `num` arithmetic operator.
fn arith(op: BinOp, a: Opnd, b: Opnd, span: Span) -> NumFn {
    macro_rules! bin {
        (|$it:ident, $x:ident, $y:ident| $body:expr) => {
            Box::new(move |$it: &mut Interp, c: &Code| {
                let $x = a.get($it, c);
                if $x.is_nan() {
                    return $x;
                }
                let $y = b.get($it, c);
                if $y.is_nan() {
                    return $y;
                }
                $body
            })
        };
    }
    match op {
        BinOp::NumAdd => bin!(|it, x, y| it.num_result(x + y, span)),
        BinOp::NumSub => bin!(|it, x, y| it.num_result(x - y, span)),
        BinOp::NumMul => bin!(|it, x, y| it.num_result(x * y, span)),
        BinOp::NumIntDiv => bin!(|it, x, y| it.int_op(false, x, y, span)),
        BinOp::NumMod => bin!(|it, x, y| it.int_op(true, x, y, span)),
        _ => bin!(|it, x, y| it.num_op(op, x, y, span)),
    }
}

/// A call of a simple function (see [`crate::ir::Routine::simple`]).
pub(crate) struct SCall {
    rid: RoutineId,
    args: Box<[SArg]>,
    /// The arguments as lowered (for the general path).
    ir_args: Box<[Arg]>,
    span: Span,
    /// The callee's number of value slots.
    n_slots: usize,
    /// The callee's `RETURN` expression calls nothing and has no side effects, so it can be
    /// evaluated without a frame and evaluated again, with its frame, if it fails.
    pure: bool,
}

enum SArg {
    Num(Opnd),
    Val(Arg),
}

impl SCall {
    fn new(p: &Program, rid: RoutineId, args: &[Arg], span: Span) -> SCall {
        let r = p.routine(rid);
        let cargs = r
            .params
            .iter()
            .zip(args.iter())
            .map(|(param, arg)| match arg {
                Arg::Value(e) if param.ty == Ty::NUM => SArg::Num(opnd(p, e)),
                _ => SArg::Val(arg.clone()),
            })
            .collect();
        let pure = match r.body.stmts.as_slice() {
            [
                crate::ir::Stmt {
                    kind: crate::ir::StmtKind::Return(Some(e)),
                    ..
                },
            ] => pure(e),
            _ => false,
        };
        SCall {
            rid,
            args: cargs,
            ir_args: args.into(),
            span,
            n_slots: r.n_slots as usize,
            pure,
        }
    }
}

/// Does evaluating `e` leave everything as it was (no call, no I/O)?
fn pure(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Num(_)
        | ExprKind::Dnum(_)
        | ExprKind::Bool(_)
        | ExprKind::Str(_)
        | ExprKind::Local(_)
        | ExprKind::Global(_)
        | ExprKind::Errno
        | ExprKind::Intno
        | ExprKind::Present(_) => true,
        ExprKind::Load(pl) => pl.path.iter().all(|op| match op {
            PathOp::Field(_) => true,
            PathOp::Index(es) => es.iter().all(pure),
        }),
        ExprKind::Field(a, _)
        | ExprKind::Unary(_, a)
        | ExprKind::NumModDivK(a, ..)
        | ExprKind::ToDnum(a)
        | ExprKind::ToNum(a) => pure(a),
        ExprKind::Binary(_, a, b) => pure(a) && pure(b),
        ExprKind::Record(es) | ExprKind::Array(es, _) => es.iter().all(pure),
        ExprKind::SignalValue(_)
        | ExprKind::Call(..)
        | ExprKind::Native(..)
        | ExprKind::Placeholder(_) => false,
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

    /// The tree-walking path for an expression whose fast path gave up before any side
    /// effect.
    #[cold]
    #[inline(never)]
    fn nf_cold(&mut self, c: &Code, e: &Expr) -> f32 {
        self.nf(&c.prog, e)
    }

    /// Call a simple `FUNC num`: arguments pushed onto the value stack, the `RETURN`
    /// expression evaluated directly (no statement loop, no `Value` result). A pure body
    /// runs without a call frame unless the per-statement slow path is due or it fails; it
    /// is then evaluated again with its frame, so hooks, interrupts and errors see exactly
    /// what the general path shows.
    fn call_simple_c(&mut self, c: &Code, sc: &SCall) -> f32 {
        let p = &*c.prog;
        let ret = c
            .routines
            .get(sc.rid.0 as usize)
            .and_then(|r| r.ret_num.as_ref());
        let Some((body, st_span)) = ret else {
            return self.call_num_general(p, sc.rid, &sc.ir_args, sc.span);
        };
        if self.frames.len() >= MAX_DEPTH || self.stack_exhausted() {
            return self.call_num_general(p, sc.rid, &sc.ir_args, sc.span);
        }
        let bp = self.sp;
        // Arguments are pushed as they are computed (nested calls made while evaluating
        // one use the stack above it and leave it as they found it).
        for arg in sc.args.iter() {
            match arg {
                SArg::Num(o) => {
                    let x = o.get(self, c);
                    if x.is_nan() {
                        self.sp = bp;
                        return x;
                    }
                    self.push_num(x);
                }
                SArg::Val(a) => match self.arg_value(p, a) {
                    Ok(v) => self.push_value(v),
                    Err(u) => {
                        self.sp = bp;
                        return self.fail_nf(u);
                    }
                },
            }
        }
        while self.sp < bp + sc.n_slots {
            self.push_num(0.0);
        }
        let saved = (self.bp, self.rbp);
        self.bp = bp;
        self.steps += 1;
        let mut x = f32::NAN;
        if sc.pure && self.steps < self.next_poll {
            x = body(self, c);
            if x.is_nan() {
                self.pending = None;
            }
        }
        if x.is_nan() {
            x = self.simple_framed(c, sc, body, *st_span);
        }
        (self.bp, self.rbp) = saved;
        self.sp = bp;
        x
    }

    /// The body of a simple call with its frame (and the per-statement slow path when due).
    #[inline(never)]
    fn simple_framed(&mut self, c: &Code, sc: &SCall, body: &NumFn, st_span: Span) -> f32 {
        if let Some(f) = self.frames.last_mut() {
            f.at = sc.span;
        }
        self.frames.push(crate::interp::Frame {
            routine: sc.rid,
            at: st_span,
            handling: None,
        });
        let x = if self.steps >= self.next_poll {
            match self.poll(&c.prog, st_span) {
                Ok(()) => body(self, c),
                Err(u) => self.fail_nf(u),
            }
        } else {
            body(self, c)
        };
        self.frames.pop();
        x
    }
}
