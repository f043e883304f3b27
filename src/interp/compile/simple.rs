//! Calls of simple functions (a single `RETURN expr`, see [`crate::ir::Routine::simple`])
//! in `num` expressions: arguments pushed onto the value stack, the returned expression
//! evaluated directly. A pure body (no calls, no I/O) is compiled into the call site and
//! runs without a call frame unless the per-statement slow path is due or it fails; it is
//! then evaluated again with its frame, so hooks, interrupts and errors see exactly what
//! the general path shows.

use super::num::{NumFn, Opnd, Src, num, opnd};
use super::{Code, Cx};
use crate::interp::Interp;
use crate::interp::call::MAX_DEPTH;
use crate::ir::{Arg, Expr, ExprKind, PathOp, RoutineId, Stmt, StmtKind, Ty};
use crate::source::Span;

/// A compiled call of a simple function.
pub(crate) struct SCall {
    rid: RoutineId,
    args: Box<[SArg]>,
    /// The arguments as lowered (for the general path).
    ir_args: Box<[Arg]>,
    span: Span,
    /// The callee's number of value slots.
    n_slots: usize,
    /// Values its arguments add to the task's data; `u64::MAX` when one is an array (such
    /// calls go the general way, which counts the array).
    values: u64,
    /// A pure `FUNC num` body compiled for this call, and the span of its `RETURN`.
    inline: Option<(NumFn, Span)>,
    /// That body with its parameters replaced by the arguments (all reads without side
    /// effects), evaluated in the caller's frame.
    inlined: Option<NumFn>,
}

enum SArg {
    Num(Opnd),
    Val(Arg),
}

impl SCall {
    pub(crate) fn new(cx: &Cx, rid: RoutineId, args: &[Arg], span: Span) -> SCall {
        let p = cx.p;
        let r = p.routine(rid);
        let cargs = r
            .params
            .iter()
            .zip(args.iter())
            .map(|(param, arg)| match arg {
                Arg::Value(e) if param.ty == Ty::NUM => SArg::Num(opnd(cx, e)),
                _ => SArg::Val(arg.clone()),
            })
            .collect();
        let func_num = r.kind == crate::ir::RoutineKind::Func(Ty::NUM);
        let arrays = r.params.iter().any(|q| q.ty.rank > 0);
        let values = if arrays {
            u64::MAX
        } else {
            r.params
                .iter()
                .map(|q| p.types.values(q.ty, &[]))
                .fold(0u64, u64::saturating_add)
        };
        let body = match r.body.stmts.as_slice() {
            [
                Stmt {
                    kind: StmtKind::Return(Some(e)),
                    span,
                },
            ] if func_num && !arrays && pure(e) => Some((e, *span)),
            _ => None,
        };
        let callee = Cx::new(p, r);
        let inline = body.map(|(e, span)| (num(&callee, e), span));
        let inlined = body
            .and_then(|(e, _)| Subst::new(r, args)?.apply(e))
            .map(|e| num(cx, &e));
        SCall {
            rid,
            args: cargs,
            ir_args: args.into(),
            span,
            n_slots: r.n_slots as usize,
            values,
            inline,
            inlined,
        }
    }
}

/// Parameters of a simple function replaced by its arguments, when every argument is a
/// `num` read without side effects (a constant, a local, a global, an array element with
/// such indices).
struct Subst<'a> {
    /// Argument for each value slot of the callee.
    by_slot: Vec<Option<&'a Expr>>,
    /// How often each slot is read.
    uses: std::cell::RefCell<Vec<u32>>,
}

impl<'a> Subst<'a> {
    fn new(r: &crate::ir::Routine, args: &'a [Arg]) -> Option<Subst<'a>> {
        let mut by_slot = vec![None; r.n_slots as usize];
        for (param, arg) in r.params.iter().zip(args.iter()) {
            let (crate::ir::ParamSlot::Value(s), Arg::Value(e)) = (param.slot, arg) else {
                return None;
            };
            if param.ty != Ty::NUM || !read_only(e) {
                return None;
            }
            *by_slot.get_mut(s as usize)? = Some(e);
        }
        if r.params.len() != args.len() {
            return None;
        }
        let uses = std::cell::RefCell::new(vec![0; by_slot.len()]);
        Some(Subst { by_slot, uses })
    }

    /// `e` with the parameters replaced, if every parameter read is a plain `num` read and
    /// every argument that could fail is read at least once (so a failing argument still
    /// fails, and the call is then made the general way).
    fn apply(&self, e: &Expr) -> Option<Expr> {
        let out = self.expr(e)?;
        let uses = self.uses.borrow();
        for (arg, n) in self.by_slot.iter().zip(uses.iter()) {
            if let Some(a) = arg
                && *n == 0
                && !matches!(a.kind, ExprKind::Num(_))
            {
                return None;
            }
        }
        Some(out)
    }

    fn expr(&self, e: &Expr) -> Option<Expr> {
        let kind = match &e.kind {
            ExprKind::Local(s) => {
                let a = (*self.by_slot.get(*s as usize)?)?;
                if let Some(n) = self.uses.borrow_mut().get_mut(*s as usize) {
                    *n += 1;
                }
                return Some(a.clone());
            }
            ExprKind::Num(_) | ExprKind::Global(_) => e.kind.clone(),
            ExprKind::Load(pl) => {
                if !matches!(pl.root, crate::ir::Root::Global(_)) {
                    return None;
                }
                let mut pl = (**pl).clone();
                for op in pl.path.iter_mut() {
                    if let PathOp::Index(es) = op {
                        for ie in es.iter_mut() {
                            *ie = self.expr(ie)?;
                        }
                    }
                }
                ExprKind::Load(Box::new(pl))
            }
            ExprKind::Unary(op, a) => ExprKind::Unary(*op, Box::new(self.expr(a)?)),
            ExprKind::Binary(op, a, b) => {
                ExprKind::Binary(*op, Box::new(self.expr(a)?), Box::new(self.expr(b)?))
            }
            ExprKind::NumModDivK(a, k, m) => ExprKind::NumModDivK(Box::new(self.expr(a)?), *k, *m),
            _ => return None,
        };
        Some(Expr { kind, span: e.span })
    }
}

/// Is `e` a `num` read without side effects that can be repeated (a constant, a local, a
/// global, an element of an array held by a local or a global with such indices)?
fn read_only(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Num(_) | ExprKind::Local(_) | ExprKind::Global(_) => true,
        ExprKind::Load(pl) => {
            !matches!(pl.root, crate::ir::Root::Ref(_))
                && pl.path.iter().all(|op| match op {
                    PathOp::Field(_) => true,
                    PathOp::Index(es) => es.iter().all(|i| {
                        matches!(
                            i.kind,
                            ExprKind::Num(_) | ExprKind::Local(_) | ExprKind::Global(_)
                        )
                    }),
                })
        }
        _ => false,
    }
}

/// Does evaluating `e` leave everything as it was (no call, no I/O)?
pub(crate) fn pure(e: &Expr) -> bool {
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
    /// Call a simple function whose result is a `num` (NaN: an error is pending). An
    /// inlined body is tried first when the per-statement slow path is not due; if it fails,
    /// its error is dropped and the call is made the general way, which raises it again
    /// (nothing it read has changed) with the callee's frame and the argument spans.
    #[inline(always)]
    pub(crate) fn call_simple(&mut self, c: &Code, sc: &SCall) -> f32 {
        if let Some(f) = &sc.inlined
            && self.frames.len() < MAX_DEPTH
            && !self.stack_exhausted()
        {
            self.steps += 1;
            if self.steps < self.next_poll {
                let x = f(self, c);
                if !x.is_nan() {
                    return x;
                }
                self.pending = None;
            }
            self.steps -= 1;
        }
        self.call_simple_framed(c, sc)
    }

    /// [`Interp::call_simple`] with arguments on the value stack.
    #[inline(never)]
    fn call_simple_framed(&mut self, c: &Code, sc: &SCall) -> f32 {
        let (body, st_span) = match &sc.inline {
            Some((b, s)) => (b, *s),
            None => match c.routines.get(sc.rid.0 as usize) {
                Some(super::CRoutine {
                    ret_num: Some((b, s)),
                    ..
                }) => (b, *s),
                _ => return self.simple_general(c, sc),
            },
        };
        if self.frames.len() >= MAX_DEPTH
            || self.stack_exhausted()
            || self.data_values.saturating_add(sc.values) > crate::ir::limits::MAX_TASK_VALUES
        {
            return self.simple_general(c, sc);
        }
        let bp = self.sp;
        // Arguments are pushed as they are computed (nested calls made while evaluating
        // one use the stack above it and leave it as they found it).
        for arg in sc.args.iter() {
            let x = match arg {
                SArg::Num(o) => o.get(self, c),
                SArg::Val(a) => match self.arg_value(&c.prog, a) {
                    Ok(v) => {
                        self.push_value(v);
                        continue;
                    }
                    Err(u) => self.fail_nf(u),
                },
            };
            if x.is_nan() {
                self.sp = bp;
                return x;
            }
            self.push_num(x);
        }
        while self.sp < bp + sc.n_slots {
            self.push_num(0.0);
        }
        let saved = self.bp;
        self.bp = bp;
        self.data_values += sc.values;
        self.steps += 1;
        let mut x = f32::NAN;
        if sc.inline.is_some() && self.steps < self.next_poll {
            x = body(self, c);
            if x.is_nan() {
                // Evaluated again below, with its frame, for the error's call stack.
                self.pending = None;
            }
        }
        if x.is_nan() {
            x = self.simple_framed(c, sc, body, st_span);
        }
        self.data_values -= sc.values;
        self.bp = saved;
        self.sp = bp;
        x
    }

    #[cold]
    #[inline(never)]
    fn simple_general(&mut self, c: &Code, sc: &SCall) -> f32 {
        self.call_num_general(&c.prog, sc.rid, &sc.ir_args, sc.span)
    }

    /// The body of a simple call with its frame (and the per-statement slow path when due).
    #[inline(never)]
    fn simple_framed(&mut self, c: &Code, sc: &SCall, body: &NumFn, st_span: Span) -> f32 {
        if let Some(f) = self.frames.last_mut() {
            f.at = sc.span;
        }
        self.frames.push(crate::interp::Frame {
            routine: sc.rid,
            bp: self.bp as u32,
            at: st_span,
            handling: None,
            retries: 0,
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
