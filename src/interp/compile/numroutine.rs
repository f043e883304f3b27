//! `num` routines on a slab of `f32` frames: a FUNC or PROC whose parameters are `num`
//! value parameters and whose routine data are `num`s, with no ERROR or UNDO handler, whose
//! body uses only its own data, `num` module data (scalars and 1-D arrays), arithmetic,
//! comparisons, IF, WHILE, RETURN and calls of such routines, and which calls at least one
//! (a recursion, a function of functions: where the cost of calls dominates), runs here: its
//! slots are plain `f32`s in `Interp::nslab` (no `Value`, no value-stack bookkeeping),
//! RETURN is the result of its statement list (not an unwind through every block), errors
//! wait in `Interp::pending` instead of travelling in `Result`s, and a call pushes only the
//! frame record errors, hooks and interrupts read. Routines that call nothing stay on the
//! specialised closures, which run them faster. The commonest shapes (`local + k`,
//! `local < k`, `array{local}`) are read inline, without the dispatch of the general
//! expression.
//!
//! Everything observable is as on the general path: a step per statement, the
//! per-statement slow path (budget, hook, interrupts, tasks) at the same points, the same
//! errors at the same spans with the same call stack (the frame record is pushed as
//! always), the depth and data limits, and `ERR_FNCNORET`. Where the fast reads give up
//! (an index out of bounds, a global that is not a `num`), the general path raises the
//! error with the values computed here.

use super::DivK;
use crate::interp::error::{Exec, Unwind};
use crate::interp::expr::cmp_num as cmp;
use crate::interp::value::Value;
use crate::interp::{Frame, Interp};
use crate::ir::{
    Arg, BinOp, Block, Expr, ExprKind, ParamMode, ParamSlot, PathOp, Place, Program, Root, Routine,
    RoutineId, RoutineKind, Stmt, StmtKind, Ty, TypeId, UnOp,
};
use crate::source::Span;

/// The most parameters a routine run here may have (its arguments are evaluated into a
/// fixed array before the frame is pushed).
pub(crate) const MAX_ARGS: usize = 8;

/// A routine compiled for the slab.
pub(crate) struct NRoutine {
    rid: RoutineId,
    /// `FUNC num` (else a PROC).
    func: bool,
    /// Slots of its frame (parameters first).
    n_slots: u32,
    /// Routine data: slot and start value.
    data: Box<[(u32, f32)]>,
    /// Values a call adds to the task's data ([`crate::ir::limits`]).
    values: u64,
    /// The routine's head (where its frame record points on entry).
    head: Span,
    body: NBlock,
}

type NBlock = Box<[NStmt]>;

/// An expression and its span.
type SpannedNE = (NE, Span);

/// A statement and its span.
struct NStmt {
    k: NS,
    span: Span,
}

enum NS {
    /// `slot := value` (the value's span).
    Local(u32, NE, Span),
    /// `global := value`, and the place (general path).
    Global(u32, NE, Span, Box<Place>),
    /// `global{index} := value`.
    Elem(Box<(NElem, NE, Span)>),
    If(Box<[(NC, NBlock)]>, Option<NBlock>),
    /// `IF cond RETURN [value];`: the condition, the value and its span, and the span of
    /// the RETURN.
    IfRet(Box<(NC, Option<SpannedNE>, Span)>),
    /// RETURN, with the value of a FUNC and its span.
    Ret(Option<SpannedNE>),
    /// A PROC call.
    Call(Box<NCall>),
    /// `WHILE cond DO body ENDWHILE` (a body of at least one statement).
    While(Box<(NC, NBlock)>),
}

/// An element of a 1-D `num` array held by a global.
struct NElem {
    g: u32,
    idx: NE,
    idx_span: Span,
    /// The place as written (general path, with the computed index).
    place: Place,
    /// The whole access.
    span: Span,
}

/// A `num` expression (NaN: an error is pending, as on the general `num` path).
enum NE {
    K(f32),
    L(u32),
    /// `local + k` (`local - k` as `local + -k`: the same IEEE result), and the span of
    /// the whole (a counter step, a recursion's argument).
    LAdd(u32, f32, Span),
    G(u32, Span),
    E(Box<NElem>),
    /// `global{local}` (the index a local: read without evaluating an expression).
    EL(u32, u32, Box<NElem>),
    B(Box<(BinOp, NE, NE, Span)>),
    M(Box<(NE, DivK, bool, Span)>),
    Neg(Box<NE>),
    Call(Box<NCall>),
}

/// A condition.
enum NC {
    K(bool),
    /// `local op k`, and the local's span.
    CmpLK(BinOp, u32, f32, Span),
    Cmp(Box<(BinOp, NE, Span, NE, Span)>),
    Logic(Box<(BinOp, NC, NC)>),
    Not(Box<NC>),
}

/// A call of a routine run here: the arguments and their spans.
struct NCall {
    rid: RoutineId,
    args: Box<[(NE, Span)]>,
    span: Span,
}

/// The routines of `p` that run on the slab (index = routine id).
pub(crate) fn compile_all(p: &Program) -> Vec<Option<NRoutine>> {
    let n = p.routines.len();
    let cand: Vec<bool> = p.routines.iter().map(|r| shape_ok(p, r)).collect();
    // Compile each candidate assuming its callees qualify, noting whom it calls; then a
    // routine that calls one that does not qualify does not qualify either.
    let mut out: Vec<Option<NRoutine>> = Vec::with_capacity(n);
    let mut callers: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (i, r) in p.routines.iter().enumerate() {
        let compiled = if cand[i] {
            let calls = std::cell::RefCell::new(Vec::new());
            let c = Comp {
                p,
                r,
                cand: &cand,
                calls: &calls,
            };
            let res = c.routine(RoutineId(i as u32));
            let calls = calls.into_inner();
            // The slab pays where calls dominate (a recursion, a function of functions); a
            // routine that calls nothing runs faster on the specialised closures.
            let res = res.filter(|_| !calls.is_empty());
            for callee in calls {
                if let Some(v) = callers.get_mut(callee as usize) {
                    v.push(i as u32);
                }
            }
            res
        } else {
            None
        };
        out.push(compiled);
    }
    let mut bad: Vec<u32> = (0..n as u32)
        .filter(|&i| out[i as usize].is_none())
        .collect();
    while let Some(b) = bad.pop() {
        for &caller in &callers[b as usize] {
            if out[caller as usize].take().is_some() {
                bad.push(caller);
            }
        }
    }
    out
}

/// Parameters, data and handlers of a routine that may run here.
fn shape_ok(p: &Program, r: &Routine) -> bool {
    let kind_ok = matches!(r.kind, RoutineKind::Proc) || r.kind == RoutineKind::Func(Ty::NUM);
    kind_ok
        && r.error.is_none()
        && r.undo.is_none()
        && r.n_refs == 0
        && r.params.len() <= MAX_ARGS
        && r.params.iter().all(|q| {
            q.ty == Ty::NUM
                && !q.optional
                && q.mode == ParamMode::In
                && matches!(q.slot, ParamSlot::Value(s) if s < r.n_slots)
        })
        && r.locals.iter().all(|l| {
            l.ty == Ty::NUM
                && l.dims.is_empty()
                && l.slot < r.n_slots
                && matches!(
                    l.init.as_ref().map(|e| &e.kind),
                    None | Some(ExprKind::Num(_))
                )
        })
        && p.types.values(Ty::NUM, &[]) == 1
}

struct Comp<'a> {
    p: &'a Program,
    r: &'a Routine,
    cand: &'a [bool],
    calls: &'a std::cell::RefCell<Vec<u32>>,
}

impl Comp<'_> {
    fn routine(&self, rid: RoutineId) -> Option<NRoutine> {
        let r = self.r;
        let data = r
            .locals
            .iter()
            .map(|l| {
                let x = match l.init.as_ref().map(|e| &e.kind) {
                    Some(ExprKind::Num(x)) => *x,
                    _ => 0.0,
                };
                (l.slot, x)
            })
            .collect();
        Some(NRoutine {
            rid,
            func: matches!(r.kind, RoutineKind::Func(_)),
            n_slots: r.n_slots,
            data,
            values: super::FrameData::of(self.p, r).fixed,
            head: r.head_span,
            body: self.block(&r.body)?,
        })
    }

    fn block(&self, b: &Block) -> Option<NBlock> {
        if !b.labels.is_empty() {
            return None;
        }
        b.stmts.iter().map(|s| self.stmt(s)).collect()
    }

    fn stmt(&self, s: &Stmt) -> Option<NStmt> {
        let k = match &s.kind {
            StmtKind::AssignNum { place, value } => {
                let v = self.num(value)?;
                let vs = value.span;
                match (place.root, place.path.is_empty()) {
                    (Root::Local(slot), true) if slot < self.r.n_slots => NS::Local(slot, v, vs),
                    (Root::Global(g), true) if self.global_ty(g)? == Ty::NUM => {
                        NS::Global(g, v, vs, Box::new(place.clone()))
                    }
                    _ => NS::Elem(Box::new((self.elem(place)?, v, vs))),
                }
            }
            StmtKind::If {
                branches,
                else_body: None,
            } if branches.len() == 1
                && branches[0].1.labels.is_empty()
                && matches!(
                    branches[0].1.stmts.as_slice(),
                    [Stmt {
                        kind: StmtKind::Return(_),
                        ..
                    }]
                ) =>
            {
                let (cond, b) = &branches[0];
                let ret = self.stmt(&b.stmts[0])?;
                let NS::Ret(value) = ret.k else {
                    return None;
                };
                NS::IfRet(Box::new((self.cond(cond)?, value, ret.span)))
            }
            StmtKind::If {
                branches,
                else_body,
            } => NS::If(
                branches
                    .iter()
                    .map(|(c, b)| Some((self.cond(c)?, self.block(b)?)))
                    .collect::<Option<_>>()?,
                match else_body {
                    Some(b) => Some(self.block(b)?),
                    None => None,
                },
            ),
            // An empty body takes its step at the loop's head (general path).
            StmtKind::While { cond, body } if !body.stmts.is_empty() => {
                NS::While(Box::new((self.cond(cond)?, self.block(body)?)))
            }
            StmtKind::Return(None) if self.r.kind == RoutineKind::Proc => NS::Ret(None),
            StmtKind::Return(Some(e)) if self.r.kind == RoutineKind::Func(Ty::NUM) => {
                NS::Ret(Some((self.num(e)?, e.span)))
            }
            StmtKind::Call { routine, args } => {
                if self.p.routine(*routine).kind != RoutineKind::Proc {
                    return None;
                }
                NS::Call(Box::new(self.call(*routine, args, s.span)?))
            }
            _ => return None,
        };
        Some(NStmt { k, span: s.span })
    }

    fn global_ty(&self, g: u32) -> Option<Ty> {
        self.p.globals.get(g as usize).map(|g| g.ty)
    }

    /// `global{i}` of a 1-D `num` array.
    fn elem(&self, pl: &Place) -> Option<NElem> {
        let Root::Global(g) = pl.root else {
            return None;
        };
        let gt = self.global_ty(g)?;
        let [PathOp::Index(es)] = &*pl.path else {
            return None;
        };
        let [ie] = &**es else {
            return None;
        };
        if gt.base != TypeId::NUM || gt.rank != 1 {
            return None;
        }
        Some(NElem {
            g,
            idx: self.num(ie)?,
            idx_span: ie.span,
            place: pl.clone(),
            span: pl.span,
        })
    }

    fn call(&self, rid: RoutineId, args: &[Arg], span: Span) -> Option<NCall> {
        let callee = self.p.routine(rid);
        if !self.cand.get(rid.0 as usize).copied().unwrap_or(false)
            || callee.params.len() != args.len()
        {
            return None;
        }
        self.calls.borrow_mut().push(rid.0);
        let args = args
            .iter()
            .map(|a| match a {
                Arg::Value(e) => Some((self.num(e)?, e.span)),
                _ => None,
            })
            .collect::<Option<_>>()?;
        Some(NCall { rid, args, span })
    }

    fn num(&self, e: &Expr) -> Option<NE> {
        Some(match &e.kind {
            ExprKind::Num(x) => NE::K(*x),
            ExprKind::Local(s) if *s < self.r.n_slots => NE::L(*s),
            ExprKind::Global(g) if self.global_ty(*g)? == Ty::NUM => NE::G(*g, e.span),
            ExprKind::Load(pl) => {
                let mut el = self.elem(pl)?;
                el.span = e.span;
                match el.idx {
                    NE::L(s) => NE::EL(el.g, s, Box::new(el)),
                    _ => NE::E(Box::new(el)),
                }
            }
            ExprKind::Binary(op, a, b) if op.is_num_arith() => {
                match (*op, self.num(a)?, self.num(b)?) {
                    (BinOp::NumAdd, NE::L(s), NE::K(k)) => NE::LAdd(s, k, e.span),
                    (BinOp::NumSub, NE::L(s), NE::K(k)) => NE::LAdd(s, -k, e.span),
                    (op, x, y) => NE::B(Box::new((op, x, y, e.span))),
                }
            }
            ExprKind::NumModDivK(a, k, is_mod) if *k != 0 => {
                NE::M(Box::new((self.num(a)?, DivK::new(*k), *is_mod, e.span)))
            }
            ExprKind::Unary(UnOp::NumNeg, a) => NE::Neg(Box::new(self.num(a)?)),
            ExprKind::Call(rid, args)
                if self.p.routine(*rid).kind == RoutineKind::Func(Ty::NUM) =>
            {
                NE::Call(Box::new(self.call(*rid, args, e.span)?))
            }
            _ => return None,
        })
    }

    fn cond(&self, e: &Expr) -> Option<NC> {
        Some(match &e.kind {
            ExprKind::Bool(b) => NC::K(*b),
            ExprKind::Binary(
                op @ (BinOp::NumLt
                | BinOp::NumLe
                | BinOp::NumGt
                | BinOp::NumGe
                | BinOp::NumEq
                | BinOp::NumNe),
                a,
                b,
            ) => match (self.num(a)?, self.num(b)?) {
                (NE::L(s), NE::K(k)) => NC::CmpLK(*op, s, k, a.span),
                (x, y) => NC::Cmp(Box::new((*op, x, a.span, y, b.span))),
            },
            ExprKind::Binary(op @ (BinOp::And | BinOp::Or | BinOp::Xor), a, b) => {
                NC::Logic(Box::new((*op, self.cond(a)?, self.cond(b)?)))
            }
            ExprKind::Unary(UnOp::Not, a) => NC::Not(Box::new(self.cond(a)?)),
            _ => return None,
        })
    }
}

impl NRoutine {
    /// What a call returns to general code.
    #[inline(always)]
    pub(crate) fn result(&self, x: f32) -> Value {
        match self.func {
            true => Value::Num(x),
            false => Value::Absent,
        }
    }
}

/// How a statement (list) ended; `Fail`: its error waits in `Interp::pending` (kept in a
/// register, unlike a `Result` with an unwind).
#[derive(Clone, Copy)]
enum St {
    Next,
    Ret(f32),
    Fail,
}

impl Interp {
    /// Run `nr` on arguments pushed onto the value stack from `bp` (a late-bound or
    /// lowered call), unless one is not a `num` (`None`: the general path runs it).
    pub(crate) fn slab_from_stack(
        &mut self,
        c: &super::Code,
        nr: &NRoutine,
        bp: usize,
        rbp: usize,
        span: Span,
    ) -> Option<Exec<Value>> {
        let mut argv = [0f32; MAX_ARGS];
        let args = self.stack.get(bp..self.sp)?;
        if args.len() > MAX_ARGS {
            return None;
        }
        for (v, slot) in args.iter().zip(argv.iter_mut()) {
            match v {
                Value::Num(x) => *slot = *x,
                _ => return None,
            }
        }
        let n = args.len();
        self.sp = bp;
        self.refs.truncate(rbp);
        Some(
            self.slab_enter(c, nr, &argv[..n], span)
                .map(|x| nr.result(x)),
        )
    }

    /// Is routine `rid` of `c` run on the slab?
    #[inline(always)]
    pub(crate) fn slab_routine(c: &super::Code, rid: RoutineId) -> Option<&NRoutine> {
        c.routines.get(rid.0 as usize).and_then(|r| r.slab.as_ref())
    }

    /// Call `nr` from general code with `args` (evaluated by the caller, after the depth
    /// check) at `span`; the FUNC's result (0 for a PROC).
    pub(crate) fn slab_enter(
        &mut self,
        c: &super::Code,
        nr: &NRoutine,
        args: &[f32],
        span: Span,
    ) -> Exec<f32> {
        let base = self.ntop;
        let top = base + nr.n_slots as usize;
        if self.nslab.len() < top {
            self.nslab.resize(top, 0.0);
        }
        for (k, x) in args.iter().enumerate() {
            if let Some(slot) = self.nslab.get_mut(base + k) {
                *slot = *x;
            }
        }
        let x = self.slab_run(c, nr, base, span);
        if x.is_nan() {
            Err(self.take_pending(span))
        } else {
            Ok(x)
        }
    }

    /// Run `nr` on the frame at `base` of the slab (its arguments written) for a call at
    /// `span`: the result (0 for a PROC; NaN: the error is pending).
    #[inline(always)]
    fn slab_run(&mut self, c: &super::Code, nr: &NRoutine, base: usize, span: Span) -> f32 {
        if self.data_values.saturating_add(nr.values) > crate::ir::limits::MAX_TASK_VALUES {
            let u = self.data_limit_error(c.prog.routine(nr.rid), nr.values, span);
            return self.fail_nf(u);
        }
        self.data_values += nr.values;
        if let Some(f) = self.frames.last_mut() {
            f.at = span;
        }
        self.frames.push(Frame {
            routine: nr.rid,
            bp: self.sp as u32,
            at: nr.head,
            handling: None,
            retries: 0,
        });
        for &(s, x) in nr.data.iter() {
            if let Some(slot) = self.nslab.get_mut(base + s as usize) {
                *slot = x;
            }
        }
        let saved = (self.nbp, self.ntop);
        (self.nbp, self.ntop) = (base, base + nr.n_slots as usize);
        let st = self.nblock(c, &nr.body);
        (self.nbp, self.ntop) = saved;
        let x = match st {
            St::Ret(x) => x,
            St::Next if nr.func => {
                let u = self.fncnoret(c.prog.routine(nr.rid));
                self.fail_nf(u)
            }
            St::Next => 0.0,
            St::Fail => self.returned_error(),
        };
        self.frames.pop();
        self.data_values -= nr.values;
        x
    }

    /// The pending error of a call that failed, as its caller sees it (NaN).
    #[cold]
    #[inline(never)]
    fn returned_error(&mut self) -> f32 {
        self.pending = match self.pending.take() {
            Some(Unwind::Propagate(e)) => Some(Unwind::Error(e)),
            other => other,
        };
        f32::NAN
    }

    /// A call from slab code (NaN: the error is pending).
    #[inline(never)]
    fn ncall(&mut self, c: &super::Code, call: &NCall) -> f32 {
        if let Err(u) = self.check_depth(call.span) {
            return self.fail_nf(u);
        }
        let Some(nr) = Self::slab_routine(c, call.rid) else {
            return self.not_slab(call.span);
        };
        let base = self.ntop;
        let top = base + nr.n_slots as usize;
        if self.nslab.len() < top {
            self.nslab.resize(top, 0.0);
        }
        // The frame is taken while the arguments are computed (calls made meanwhile run
        // above it), and they are written straight into it.
        self.ntop = top;
        for (k, (e, span)) in call.args.iter().enumerate() {
            let x = self.ne(c, e);
            if x.is_nan() {
                self.ntop = base;
                self.nan_fail(*span);
                return f32::NAN;
            }
            if let Some(slot) = self.nslab.get_mut(base + k) {
                *slot = x;
            }
        }
        self.ntop = base;
        self.slab_run(c, nr, base, call.span)
    }

    #[cold]
    #[inline(never)]
    fn not_slab(&mut self, span: Span) -> f32 {
        let u = self.fatal(
            crate::interp::ErrorKind::Host,
            span,
            "internal error: a slab routine calls one that is not",
        );
        self.fail_nf(u)
    }

    /// A NaN from an expression at `span` as a failed statement (its error is pending).
    #[cold]
    #[inline(never)]
    fn nan_fail(&mut self, span: Span) -> St {
        if self.pending.is_none() {
            let u = self.take_pending(span);
            self.pending = Some(u);
        }
        St::Fail
    }

    /// A failed operation of a statement: its error made pending.
    #[cold]
    #[inline(never)]
    fn fail_st(&mut self, u: Unwind) -> St {
        self.pending = Some(u);
        St::Fail
    }

    /// What the ERROR handler protocol makes of the pending error of a statement in a
    /// routine without a handler (see `Interp::after_unwind`): on its way to the caller.
    #[cold]
    #[inline(never)]
    fn unhandled(&mut self) {
        if let Some(u) = self.pending.take() {
            self.pending = Some(match u {
                Unwind::Error(e) if e.errno().is_some() => Unwind::Propagate(e),
                Unwind::Error(e) => Unwind::Fatal(e),
                u => u,
            });
        }
    }

    fn nblock(&mut self, c: &super::Code, b: &[NStmt]) -> St {
        for s in b {
            self.steps += 1;
            if self.steps >= self.next_poll
                && let Err(u) = self.poll(&c.prog, s.span)
            {
                return self.fail_st(u);
            }
            match self.nstmt(c, s) {
                St::Next => {}
                St::Fail => {
                    self.unhandled();
                    return St::Fail;
                }
                ret => return ret,
            }
        }
        St::Next
    }

    #[inline(always)]
    fn nslot(&mut self, s: u32) -> Option<&mut f32> {
        self.nslab.get_mut(self.nbp + s as usize)
    }

    #[inline(always)]
    fn nstmt(&mut self, c: &super::Code, s: &NStmt) -> St {
        match &s.k {
            NS::Local(slot, e, vs) => {
                let x = self.ne(c, e);
                if x.is_nan() {
                    return self.nan_fail(*vs);
                }
                if let Some(v) = self.nslot(*slot) {
                    *v = x;
                }
            }
            NS::IfRet(b) => {
                let (cond, ret, ret_span) = &**b;
                match self.nc(c, cond) {
                    Some(true) => {
                        // The RETURN is a statement of the IF's block.
                        self.steps += 1;
                        if self.steps >= self.next_poll
                            && let Err(u) = self.poll(&c.prog, *ret_span)
                        {
                            return self.fail_st(u);
                        }
                        return match ret {
                            None => St::Ret(0.0),
                            Some((e, vs)) => {
                                let x = self.ne(c, e);
                                if x.is_nan() {
                                    return self.nan_fail(*vs);
                                }
                                St::Ret(x)
                            }
                        };
                    }
                    Some(false) => {}
                    None => return St::Fail,
                }
            }
            NS::Ret(None) => return St::Ret(0.0),
            NS::Ret(Some((e, vs))) => {
                let x = self.ne(c, e);
                if x.is_nan() {
                    return self.nan_fail(*vs);
                }
                return St::Ret(x);
            }
            _ => return self.nstmt_other(c, s),
        }
        St::Next
    }

    #[inline(never)]
    fn nstmt_other(&mut self, c: &super::Code, s: &NStmt) -> St {
        match &s.k {
            NS::Local(..) | NS::IfRet(..) | NS::Ret(..) => return self.nstmt(c, s),
            NS::Global(g, e, vs, pl) => {
                let x = self.ne(c, e);
                if x.is_nan() {
                    return self.nan_fail(*vs);
                }
                match self.globals.get_mut(*g as usize) {
                    Some(Value::Num(old)) => *old = x,
                    _ => {
                        if let Err(u) = self.store(&c.prog, pl, Value::Num(x)) {
                            return self.fail_st(u);
                        }
                    }
                }
            }
            NS::Elem(b) => {
                let (el, e, vs) = &**b;
                // The value first, then the place (as a store does).
                let x = self.ne(c, e);
                if x.is_nan() {
                    return self.nan_fail(*vs);
                }
                let i = self.ne(c, &el.idx);
                if i.is_nan() {
                    return self.nan_fail(el.idx_span);
                }
                match self.elem_mut(el.g, i) {
                    Some(slot) => *slot = x,
                    None => {
                        let pl = el.with_index(i);
                        if let Err(u) = self.store(&c.prog, &pl, Value::Num(x)) {
                            return self.fail_st(u);
                        }
                    }
                }
            }
            NS::If(branches, else_body) => {
                for (cond, b) in branches.iter() {
                    match self.nc(c, cond) {
                        Some(true) => return self.nblock(c, b),
                        Some(false) => {}
                        None => return St::Fail,
                    }
                }
                if let Some(b) = else_body {
                    return self.nblock(c, b);
                }
            }
            NS::Call(call) => {
                if self.ncall(c, call).is_nan() {
                    return St::Fail;
                }
            }
            NS::While(w) => {
                let (cond, body) = &**w;
                loop {
                    match self.nc(c, cond) {
                        Some(true) => match self.nblock(c, body) {
                            St::Next => {}
                            end => return end,
                        },
                        Some(false) => break,
                        None => return St::Fail,
                    }
                }
            }
        }
        St::Next
    }

    /// A `num` element of 1-D global array `g` at index `i`, when it is in bounds.
    #[inline(always)]
    fn elem_mut(&mut self, g: u32, i: f32) -> Option<&mut f32> {
        let o = crate::interp::value::f32_int(i)?;
        let o = usize::try_from(o).ok()?.checked_sub(1)?;
        match self.globals.get_mut(g as usize) {
            Some(Value::Array(a)) if a.rank == 1 && o < a.dims[0] as usize => {
                match a.data.get_mut(o) {
                    Some(Value::Num(x)) => Some(x),
                    _ => None,
                }
            }
            _ => None,
        }
    }

    /// A `num` expression (NaN: an error is pending).
    #[inline(always)]
    fn ne(&mut self, c: &super::Code, e: &NE) -> f32 {
        match e {
            NE::K(x) => *x,
            NE::L(s) => match self.nslab.get(self.nbp + *s as usize) {
                Some(x) => *x,
                None => f32::NAN,
            },
            NE::LAdd(s, k, span) => match self.nslab.get(self.nbp + *s as usize) {
                Some(x) => {
                    let r = *x + *k;
                    if r.is_finite() {
                        r
                    } else {
                        self.num_result(r, *span)
                    }
                }
                None => f32::NAN,
            },
            NE::Call(call) => self.ncall(c, call),
            NE::EL(g, s, el) => {
                let i = match self.nslab.get(self.nbp + *s as usize) {
                    Some(i) => *i,
                    None => return f32::NAN,
                };
                match self.elem_mut(*g, i) {
                    Some(x) => *x,
                    None => self.elem_slow(c, el, i),
                }
            }
            _ => self.ne_op(c, e),
        }
    }

    #[inline(never)]
    fn ne_op(&mut self, c: &super::Code, e: &NE) -> f32 {
        match e {
            NE::K(_) | NE::L(_) | NE::LAdd(..) | NE::Call(_) | NE::EL(..) => self.ne(c, e),
            NE::G(g, span) => match self.globals.get(*g as usize) {
                Some(Value::Num(x)) => *x,
                _ => self.nf_slow(
                    &c.prog,
                    &Expr {
                        kind: ExprKind::Global(*g),
                        span: *span,
                    },
                ),
            },
            NE::E(el) => {
                let i = self.ne(c, &el.idx);
                if i.is_nan() {
                    return i;
                }
                match self.elem_mut(el.g, i) {
                    Some(x) => *x,
                    None => self.elem_slow(c, el, i),
                }
            }
            NE::B(b) => {
                let (op, a, b, span) = &**b;
                let x = self.ne(c, a);
                if x.is_nan() {
                    return x;
                }
                let y = self.ne(c, b);
                if y.is_nan() {
                    return y;
                }
                self.num_op(*op, x, y, *span)
            }
            NE::M(m) => {
                let (a, d, is_mod, span) = &**m;
                let x = self.ne(c, a);
                self.mod_div_c(x, d, *is_mod, *span)
            }
            NE::Neg(a) => -self.ne(c, a),
        }
    }

    /// An element the fast read gave up on (out of bounds, not a `num`): the general path
    /// reads it or raises its error.
    #[cold]
    #[inline(never)]
    fn elem_slow(&mut self, c: &super::Code, el: &NElem, i: f32) -> f32 {
        let pl = el.with_index(i);
        self.nf_slow(
            &c.prog,
            &Expr {
                kind: ExprKind::Load(Box::new(pl)),
                span: el.span,
            },
        )
    }

    /// A condition (`None`: its error is pending).
    #[inline(always)]
    fn nc(&mut self, c: &super::Code, e: &NC) -> Option<bool> {
        match e {
            NC::CmpLK(op, s, k, sa) => match self.nslab.get(self.nbp + *s as usize) {
                Some(x) => Some(cmp(*op, *x, *k)),
                None => {
                    self.nan_fail(*sa);
                    None
                }
            },
            NC::Cmp(b) => {
                let (op, a, sa, b, sb) = &**b;
                let x = self.ne(c, a);
                if x.is_nan() {
                    self.nan_fail(*sa);
                    return None;
                }
                let y = self.ne(c, b);
                if y.is_nan() {
                    self.nan_fail(*sb);
                    return None;
                }
                Some(cmp(*op, x, y))
            }
            _ => self.nc_op(c, e),
        }
    }

    #[inline(never)]
    fn nc_op(&mut self, c: &super::Code, e: &NC) -> Option<bool> {
        match e {
            NC::K(b) => Some(*b),
            NC::CmpLK(..) | NC::Cmp(_) => self.nc(c, e),
            NC::Logic(b) => {
                // Both operands are always evaluated (no short circuit).
                let (op, a, b) = &**b;
                let x = self.nc(c, a)?;
                let y = self.nc(c, b)?;
                Some(match op {
                    BinOp::And => x && y,
                    BinOp::Or => x || y,
                    _ => x != y,
                })
            }
            NC::Not(a) => Some(!self.nc(c, a)?),
        }
    }
}

impl NElem {
    /// The place with its index replaced by the value computed (the general path raises
    /// the index's error without evaluating it again).
    #[cold]
    fn with_index(&self, i: f32) -> Place {
        let mut pl = self.place.clone();
        if let Some(PathOp::Index(es)) = pl.path.first_mut()
            && let Some(ie) = es.first_mut()
        {
            *ie = Expr {
                kind: ExprKind::Num(i),
                span: self.idx_span,
            };
        }
        pl
    }
}
