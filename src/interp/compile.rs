//! The compiled engine: every routine body becomes a block of statement closures, with
//! `num` arithmetic, `bool` conditions, loops, places, strings, TEST, user and native calls
//! specialised (operands read inline or borrowed, no `Value` boxing, no dispatch on the
//! IR's shape at run time). What has no specialised form keeps its IR node and runs on
//! the tree-walking engine's evaluator; both engines share the skeleton of statement
//! execution (errors, spans, budget, hook, interrupts), and `tests/interp_agree.rs` holds
//! the specialised forms to the reference.

mod assign;
mod call;
mod cond;
mod divk;
mod fast;
mod flow;
mod natives;
mod num;
mod numroutine;
mod place;
mod simple;
mod strfast;
mod val;

use std::sync::Arc;

use super::error::Exec;
use super::{Engine, Interp};
use crate::ir::{Block, Program, Routine, RoutineKind, Stmt, StmtKind, Ty};
use crate::source::Span;
pub(crate) use call::CCall;
pub(crate) use divk::DivK;
pub(crate) use num::NumFn;
pub(crate) use val::ValFn;

/// A compiled `bool` expression.
pub(crate) type BoolFn = Box<dyn Fn(&mut Interp, &Code) -> Exec<bool> + Send + Sync>;
/// A compiled statement.
pub(crate) type StmtFn = Box<dyn Fn(&mut Interp, &Code) -> Exec<()> + Send + Sync>;

/// A program in compiled form, next to the IR it came from.
pub(crate) struct Code {
    /// The program.
    pub prog: Arc<Program>,
    /// Compiled routines (index = [`crate::ir::RoutineId`]).
    pub routines: Box<[CRoutine]>,
    /// Routine bodies run on the tree-walking reference engine (their compiled form is
    /// empty then).
    pub tree_walk: bool,
}

/// A compiled routine.
pub(crate) struct CRoutine {
    /// Its statements.
    pub body: CBlock,
    /// What a call adds to the task's data.
    pub frame: FrameData,
    /// For a simple `FUNC num` (see [`Routine::simple`]): the returned expression and the
    /// span of the `RETURN` statement.
    pub ret_num: Option<(NumFn, Span)>,
    /// Its routine data in declaration order, as each call initialises them.
    pub locals: Box<[CLocal]>,
    /// When every routine data is a `num` without an initial value: their slots and the
    /// value each starts with (written without looking at the declarations).
    pub num_data: Option<Box<[(u32, f32)]>>,
    /// The routine compiled for the `num` frame slab, when it qualifies (see
    /// [`numroutine`]); calls of it run there.
    pub slab: Option<numroutine::NRoutine>,
}

/// A routine data declaration: the value it starts with, or its compiled initial value
/// (none for the tree-walking engine, which evaluates the declaration's expression).
pub(crate) struct CLocal {
    pub default: crate::interp::Value,
    pub init: Option<val::ValFn>,
}

/// The slots and start values of routine data that are all `num`s without initial values.
fn num_data(r: &Routine, locals: &[CLocal]) -> Option<Box<[(u32, f32)]>> {
    r.locals
        .iter()
        .zip(locals.iter())
        .map(|(l, cl)| match (&l.init, &cl.default) {
            (None, crate::interp::Value::Num(x)) => Some((l.slot, *x)),
            _ => None,
        })
        .collect()
}

impl CLocal {
    fn of(cx: &Cx, l: &crate::ir::LocalDecl) -> CLocal {
        CLocal {
            default: crate::interp::value::default_value(&cx.p.types, l.ty, &l.dims),
            init: l.init.as_ref().map(|e| val::value(cx, e)),
        }
    }
}

/// What a call of a routine adds to the task's data, in values ([`crate::ir::limits`]).
pub(crate) struct FrameData {
    /// Routine data and the value parameters that are not arrays.
    pub fixed: u64,
    /// Array value parameters (their size is the argument's): value slot and values per
    /// element.
    pub arrays: Box<[(u32, u64)]>,
}

impl FrameData {
    pub(crate) fn of(p: &Program, r: &Routine) -> FrameData {
        let mut fixed = r
            .locals
            .iter()
            .map(|l| p.types.values(l.ty, &l.dims))
            .fold(0u64, u64::saturating_add);
        let mut arrays = Vec::new();
        for param in &r.params {
            if let crate::ir::ParamSlot::Value(slot) = param.slot {
                if param.ty.rank > 0 {
                    arrays.push((slot, p.types.values(param.ty.elem(), &[])));
                } else {
                    fixed = fixed.saturating_add(p.types.values(param.ty, &[]));
                }
            }
        }
        FrameData {
            fixed,
            arrays: arrays.into(),
        }
    }
}

/// A compiled statement list with the labels defined directly in it.
pub(crate) struct CBlock {
    pub stmts: Box<[CStmt]>,
    pub labels: Box<[(u32, u32)]>,
}

/// A compiled statement and its source.
pub(crate) struct CStmt {
    pub run: StmtFn,
    pub span: Span,
}

impl Code {
    /// Compile every routine of `prog` (for the tree-walking engine, only what a call
    /// needs to know about its frame).
    pub(crate) fn new(prog: Arc<Program>, engine: Engine, standard: &[bool]) -> Code {
        let tree_walk = engine == Engine::TreeWalk;
        let mut slab = match tree_walk {
            false => numroutine::compile_all(&prog),
            true => Vec::new(),
        }
        .into_iter();
        let routines = prog
            .routines
            .iter()
            .map(|r| match tree_walk {
                false => CRoutine {
                    slab: slab.next().flatten(),
                    ..routine(&prog, r, standard)
                },
                true => {
                    let locals: Box<[CLocal]> = r
                        .locals
                        .iter()
                        .map(|l| CLocal {
                            default: crate::interp::value::default_value(
                                &prog.types,
                                l.ty,
                                &l.dims,
                            ),
                            init: None,
                        })
                        .collect();
                    CRoutine {
                        body: CBlock {
                            stmts: Box::new([]),
                            labels: Box::new([]),
                        },
                        frame: FrameData::of(&prog, r),
                        ret_num: None,
                        num_data: num_data(r, &locals),
                        locals,
                        slab: None,
                    }
                }
            })
            .collect();
        Code {
            prog,
            routines,
            tree_walk,
        }
    }
}

fn routine(p: &Program, r: &Routine, standard: &[bool]) -> CRoutine {
    let mut cx = Cx::new(p, r);
    cx.standard = standard;
    let ret_num = match (r.simple, r.body.stmts.as_slice()) {
        (
            true,
            [
                Stmt {
                    kind: StmtKind::Return(Some(e)),
                    span,
                },
            ],
        ) if cx.ret == Some(Ty::NUM) => Some((num::num(&cx, e), *span)),
        _ => None,
    };
    let locals: Box<[CLocal]> = r.locals.iter().map(|l| CLocal::of(&cx, l)).collect();
    CRoutine {
        body: cx.block(&r.body),
        frame: FrameData::of(p, r),
        ret_num,
        num_data: num_data(r, &locals),
        locals,
        slab: None,
    }
}

/// The head of a FOR statement at `span` (`FOR i FROM a TO b [STEP c]`), where each
/// iteration is counted against the budget.
pub(crate) fn loop_head(span: Span, to: &crate::ir::Expr, step: Option<&crate::ir::Expr>) -> Span {
    span.start_point().merge(step.unwrap_or(to).span)
}

fn set(v: &mut [Option<Ty>], slot: u32, ty: Ty) {
    if let Some(t) = v.get_mut(slot as usize) {
        *t = Some(ty);
    }
}

/// The head of a WHILE statement at `span` (`WHILE cond DO`), where each iteration of an
/// empty body is counted.
pub(crate) fn while_head(span: Span, cond: &crate::ir::Expr) -> Span {
    span.start_point().merge(cond.span)
}

/// What compilation needs to know about the routine being compiled.
pub(crate) struct Cx<'p> {
    pub p: &'p Program,
    /// The FUNC's return type.
    pub ret: Option<Ty>,
    /// Types of the value slots (parameters, routine data, FOR variables).
    slots: Vec<Option<Ty>>,
    /// Types of the reference slots.
    refs: Vec<Option<Ty>>,
    /// The value slots of routine data (never absent, unlike optional parameters).
    data: Vec<bool>,
    /// Per native: the standard implementation (see [`natives`]).
    standard: &'p [bool],
}

impl<'p> Cx<'p> {
    /// The context of routine `r`.
    pub(crate) fn new(p: &'p Program, r: &Routine) -> Cx<'p> {
        let mut slots = vec![None; r.n_slots as usize];
        let mut refs = vec![None; r.n_refs as usize];
        for q in &r.params {
            match q.slot {
                crate::ir::ParamSlot::Value(s) => set(&mut slots, s, q.ty),
                crate::ir::ParamSlot::Ref(k) => set(&mut refs, k, q.ty),
            }
        }
        let mut data = vec![false; r.n_slots as usize];
        for l in &r.locals {
            set(&mut slots, l.slot, l.ty);
            if let Some(d) = data.get_mut(l.slot as usize) {
                *d = true;
            }
        }
        let mut blocks: Vec<&Block> = vec![&r.body];
        blocks.extend(r.error.as_ref().map(|h| &h.body));
        blocks.extend(r.undo.as_ref());
        while let Some(b) = blocks.pop() {
            for s in &b.stmts {
                match &s.kind {
                    StmtKind::For { slot, body, .. } => {
                        set(&mut slots, *slot, Ty::NUM);
                        blocks.push(body);
                    }
                    StmtKind::If {
                        branches,
                        else_body,
                    } => {
                        blocks.extend(branches.iter().map(|(_, b)| b));
                        blocks.extend(else_body.as_ref());
                    }
                    StmtKind::While { body, .. } => blocks.push(body),
                    StmtKind::Test { cases, default, .. } => {
                        blocks.extend(cases.iter().map(|(_, b)| b));
                        blocks.extend(default.as_ref());
                    }
                    _ => {}
                }
            }
        }
        Cx {
            p,
            ret: match r.kind {
                RoutineKind::Func(t) => Some(t),
                _ => None,
            },
            slots,
            refs,
            data,
            standard: &[],
        }
    }

    /// Can reading `e` neither fail nor depend on evaluating anything (a constant, routine
    /// data, a global)?
    pub(crate) fn plain_read(&self, e: &crate::ir::Expr) -> bool {
        match e.kind {
            crate::ir::ExprKind::Str(_) | crate::ir::ExprKind::Global(_) => true,
            crate::ir::ExprKind::Local(s) => self.data.get(s as usize).copied() == Some(true),
            _ => false,
        }
    }

    /// The name of native `n` when it runs its standard implementation.
    pub(crate) fn standard_native(&self, n: crate::ir::NativeId) -> Option<&'p str> {
        match self.standard.get(n.0 as usize) {
            Some(true) => self.p.natives.get(n.0 as usize).map(|s| s.name.as_str()),
            _ => None,
        }
    }

    /// The type of a place, when it is known.
    pub(crate) fn place_ty(&self, pl: &crate::ir::Place) -> Option<Ty> {
        let mut ty = match pl.root {
            crate::ir::Root::Local(s) => (*self.slots.get(s as usize)?)?,
            crate::ir::Root::Ref(k) => (*self.refs.get(k as usize)?)?,
            crate::ir::Root::Global(g) => self.p.globals.get(g as usize)?.ty,
        };
        for op in pl.path.iter() {
            ty = match op {
                crate::ir::PathOp::Field(f) if ty.rank == 0 => {
                    self.p.types.fields(ty.base)?.get(*f as usize)?.ty
                }
                crate::ir::PathOp::Index(_) if ty.rank > 0 => ty.elem(),
                _ => return None,
            };
        }
        Some(ty)
    }

    /// The type of an expression, when it is known (what the compiler specialises on).
    pub(crate) fn expr_ty(&self, e: &crate::ir::Expr) -> Option<Ty> {
        use crate::ir::{BinOp::*, ExprKind as K, UnOp};
        Some(match &e.kind {
            K::Num(_) | K::SignalValue(_) | K::Errno | K::Intno | K::NumModDivK(..) => Ty::NUM,
            K::ToNum(_) => Ty::NUM,
            K::Dnum(_) | K::ToDnum(_) => Ty::DNUM,
            K::Bool(_) | K::Present(_) => Ty::BOOL,
            K::Str(_) => Ty::STRING,
            K::Local(s) => (*self.slots.get(*s as usize)?)?,
            K::Global(g) => self.p.globals.get(*g as usize)?.ty,
            K::Load(pl) => self.place_ty(pl)?,
            K::Field(b, f) => {
                let t = self.expr_ty(b)?;
                if t.rank > 0 {
                    return None;
                }
                self.p.types.fields(t.base)?.get(*f as usize)?.ty
            }
            K::Unary(UnOp::NumNeg, _) => Ty::NUM,
            K::Unary(UnOp::DnumNeg, _) => Ty::DNUM,
            K::Unary(UnOp::Not, _) => Ty::BOOL,
            K::Binary(op, ..) => match op {
                NumAdd | NumSub | NumMul | NumDiv | NumIntDiv | NumMod => Ty::NUM,
                DnumAdd | DnumSub | DnumMul | DnumDiv | DnumIntDiv | DnumMod => Ty::DNUM,
                NumLt | NumLe | NumGt | NumGe | NumEq | NumNe | DnumLt | DnumLe | DnumGt
                | DnumGe | And | Or | Xor | Eq | Ne => Ty::BOOL,
                Concat => Ty::STRING,
                _ => return None,
            },
            K::Call(r, _) => match self.p.routine(*r).kind {
                RoutineKind::Func(t) => t,
                _ => return None,
            },
            _ => return None,
        })
    }

    /// Is `e` known to be a `num`?
    pub(crate) fn is_num(&self, e: &crate::ir::Expr) -> bool {
        self.expr_ty(e) == Some(Ty::NUM)
    }

    fn block(&self, b: &Block) -> CBlock {
        CBlock {
            stmts: b.stmts.iter().map(|s| self.stmt(s)).collect(),
            labels: b.labels.clone().into(),
        }
    }

    /// The subject and case values of a TEST, specialised for `num` and for strings
    /// against constants.
    fn test_cases(
        &self,
        subject: &crate::ir::Expr,
        cases: &[(Vec<crate::ir::Expr>, Block)],
    ) -> flow::Cases {
        let all =
            |f: &dyn Fn(&crate::ir::Expr) -> bool| cases.iter().all(|(vals, _)| vals.iter().all(f));
        if self.is_num(subject) && all(&|e| matches!(e.kind, crate::ir::ExprKind::Num(_))) {
            let vals = cases
                .iter()
                .enumerate()
                .flat_map(|(k, (vals, _))| {
                    vals.iter().filter_map(move |e| match e.kind {
                        crate::ir::ExprKind::Num(x) => Some((x, k)),
                        _ => None,
                    })
                })
                .collect();
            return flow::Cases::num_consts((num::opnd(self, subject), subject.span), vals);
        }
        if self.is_num(subject) && all(&|e| self.is_num(e)) {
            let vals = cases
                .iter()
                .map(|(vals, _)| vals.iter().map(|e| (num::num(self, e), e.span)).collect())
                .collect();
            return flow::Cases::Num((num::num(self, subject), subject.span), vals);
        }
        if self.expr_ty(subject) == Some(Ty::STRING)
            && all(&|e| matches!(e.kind, crate::ir::ExprKind::Str(_)))
        {
            let vals = cases
                .iter()
                .map(|(vals, _)| {
                    vals.iter()
                        .filter_map(|e| match &e.kind {
                            crate::ir::ExprKind::Str(s) => Some(Box::<str>::from(&**s)),
                            _ => None,
                        })
                        .collect()
                })
                .collect();
            return flow::Cases::Str(val::StrPart::new(self, subject), vals);
        }
        flow::Cases::Any(
            subject.clone(),
            cases.iter().map(|(vals, _)| vals.clone().into()).collect(),
        )
    }

    fn stmt(&self, s: &Stmt) -> CStmt {
        let run: StmtFn = match &s.kind {
            StmtKind::AssignNum { place, value } => {
                assign::num_into(self, value, assign::Sink::of(self, place))
            }
            StmtKind::Call { routine, args } => {
                let call = CCall::new(self, *routine, args, s.span);
                Box::new(move |it, c| it.ccall(c, &call).map(drop))
            }
            StmtKind::If {
                branches,
                else_body,
            } if branches.len() == 1 => {
                let (e, then) = &branches[0];
                let w = flow::If {
                    then: self.block(then),
                    else_body: else_body.as_ref().map(|b| self.block(b)),
                };
                cond::with_cond(self, e, w)
            }
            StmtKind::If {
                branches,
                else_body,
            } => {
                let branches: Box<[(BoolFn, CBlock)]> = branches
                    .iter()
                    .map(|(e, b)| (cond::cond(self, e), self.block(b)))
                    .collect();
                let else_body = else_body.as_ref().map(|b| self.block(b));
                Box::new(move |it, c| {
                    for (cond, b) in branches.iter() {
                        if cond(it, c)? {
                            return it.exec_cblock(c, b);
                        }
                    }
                    match &else_body {
                        Some(b) => it.exec_cblock(c, b),
                        None => Ok(()),
                    }
                })
            }
            StmtKind::While { cond, body } => {
                let head = while_head(s.span, cond);
                let body = self.block(body);
                if body.stmts.is_empty() {
                    // No statement counts the iterations: the loop head does.
                    let cond = cond::cond(self, cond);
                    Box::new(move |it, c| {
                        while cond(it, c)? {
                            it.step(&c.prog, head)?;
                        }
                        Ok(())
                    })
                } else {
                    cond::with_cond(self, cond, flow::While { body })
                }
            }
            StmtKind::For {
                slot,
                from,
                to,
                step,
                body,
            } => {
                let f = flow::CFor {
                    slot: *slot,
                    from: (num::num(self, from), from.span),
                    to: (num::num(self, to), to.span),
                    step: step.as_ref().map(|e| (num::num(self, e), e.span)),
                    body: self.block(body),
                    span: s.span,
                    head: loop_head(s.span, to, step.as_ref()),
                };
                Box::new(move |it, c| it.exec_cfor(c, &f))
            }
            StmtKind::Test {
                subject,
                cases,
                default,
            } => {
                let t = flow::CTest {
                    cases: self.test_cases(subject, cases),
                    bodies: cases.iter().map(|(_, b)| self.block(b)).collect(),
                    default: default.as_ref().map(|b| self.block(b)),
                };
                Box::new(move |it, c| it.exec_ctest(c, &t))
            }
            StmtKind::Assign { place, value } => val::assign(self, place, value),
            StmtKind::LateCall { name, args, module } => {
                let (nspan, span, name_e) = (name.span, s.span, name);
                let module = *module;
                let values: Box<[Option<crate::interp::call::LateVal>]> = args
                    .iter()
                    .map(|a| {
                        a.value.as_ref().map(|e| crate::interp::call::LateVal {
                            f: val::value(self, e),
                            ty: self.expr_ty(e),
                        })
                    })
                    .collect();
                let args = args.clone();
                if let crate::ir::ExprKind::Binary(crate::ir::BinOp::Concat, ..) = name_e.kind {
                    // `%"prefix" + …%`: the name is built in a scratch buffer (no string
                    // value made for each call).
                    let parts = val::concat_parts(self, name_e);
                    return CStmt {
                        run: Box::new(move |it, c| {
                            let mut buf = it.strbufs.pop().unwrap_or_default();
                            buf.clear();
                            let r = match it.concat_into(c, &parts, 0, &mut buf) {
                                Ok(()) => it.late_call(c, &buf, &args, Some(&values), module, span),
                                Err(u) => Err(u),
                            };
                            it.strbufs.push(buf);
                            r
                        }),
                        span,
                    };
                }
                let name = val::value(self, name_e);
                Box::new(move |it, c| match name(it, c)? {
                    crate::interp::Value::Str(n) => {
                        it.late_call(c, &n, &args, Some(&values), module, span)
                    }
                    other => Err(it.type_bug(nspan, "string", &other)),
                })
            }
            StmtKind::Native { native, args } => {
                let call = call::CNative::new(self, *native, args, s.span);
                Box::new(move |it, c| it.cnative(c, &call).map(drop))
            }
            StmtKind::Return(Some(e)) if self.ret == Some(Ty::NUM) => {
                assign::num_into(self, e, assign::Sink::Return)
            }
            StmtKind::Return(Some(e)) => val::ret(self, e),
            _ => {
                let s = s.clone();
                Box::new(move |it, c| it.exec_stmt(&c.prog, &s))
            }
        };
        CStmt { run, span: s.span }
    }
}
