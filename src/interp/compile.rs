//! The compiled form the interpreter runs: every routine body becomes a block of statement
//! closures, with `num` arithmetic, `bool` conditions, loops and user calls specialised
//! (operands read inline, no `Value` boxing, no dispatch on the IR's shape at run time).
//! Whatever has no specialised form keeps its IR node and runs on the tree-walking path, so
//! both paths share one set of semantics (errors, spans, budget, hook, interrupts).

mod assign;
mod call;
mod cond;
mod divk;
mod flow;
mod num;
mod simple;

use std::sync::Arc;

use super::error::Exec;
use super::{Engine, Interp};
use crate::ir::{Block, Program, Routine, RoutineKind, Stmt, StmtKind, Ty};
use crate::source::Span;
pub(crate) use call::CCall;
pub(crate) use divk::DivK;
pub(crate) use num::NumFn;

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
    fn of(p: &Program, r: &Routine) -> FrameData {
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
    pub(crate) fn new(prog: Arc<Program>, engine: Engine) -> Code {
        let tree_walk = engine == Engine::TreeWalk;
        let routines = prog
            .routines
            .iter()
            .map(|r| match tree_walk {
                false => routine(&prog, r),
                true => CRoutine {
                    body: CBlock {
                        stmts: Box::new([]),
                        labels: Box::new([]),
                    },
                    frame: FrameData::of(&prog, r),
                    ret_num: None,
                },
            })
            .collect();
        Code {
            prog,
            routines,
            tree_walk,
        }
    }
}

fn routine(p: &Program, r: &Routine) -> CRoutine {
    let cx = Cx {
        p,
        ret: match r.kind {
            RoutineKind::Func(t) => Some(t),
            _ => None,
        },
    };
    let ret_num = match (r.simple, r.body.stmts.as_slice()) {
        (
            true,
            [
                Stmt {
                    kind: StmtKind::Return(Some(e)),
                    span,
                },
            ],
        ) if cx.ret == Some(Ty::NUM) => Some((num::num(p, e), *span)),
        _ => None,
    };
    CRoutine {
        body: cx.block(&r.body),
        frame: FrameData::of(p, r),
        ret_num,
    }
}

/// The head of a FOR statement at `span` (`FOR i FROM a TO b [STEP c]`), where each
/// iteration is counted against the budget.
pub(crate) fn loop_head(span: Span, to: &crate::ir::Expr, step: Option<&crate::ir::Expr>) -> Span {
    span.start_point().merge(step.unwrap_or(to).span)
}

/// The head of a WHILE statement at `span` (`WHILE cond DO`), where each iteration of an
/// empty body is counted.
pub(crate) fn while_head(span: Span, cond: &crate::ir::Expr) -> Span {
    span.start_point().merge(cond.span)
}

/// What statement compilation needs to know about the routine.
struct Cx<'p> {
    p: &'p Program,
    /// The FUNC's return type.
    ret: Option<Ty>,
}

impl Cx<'_> {
    fn block(&self, b: &Block) -> CBlock {
        CBlock {
            stmts: b.stmts.iter().map(|s| self.stmt(s)).collect(),
            labels: b.labels.clone().into(),
        }
    }

    fn stmt(&self, s: &Stmt) -> CStmt {
        let p = self.p;
        let run: StmtFn = match &s.kind {
            StmtKind::AssignNum { place, value } => {
                assign::num_into(p, value, assign::Sink::of(place))
            }
            StmtKind::Call { routine, args } => {
                let call = CCall::new(p, *routine, args, s.span);
                Box::new(move |it, c| it.ccall(c, &call).map(drop))
            }
            StmtKind::If {
                branches,
                else_body,
            } => {
                let branches: Box<[(BoolFn, CBlock)]> = branches
                    .iter()
                    .map(|(e, b)| (cond::cond(p, e), self.block(b)))
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
                let cond = cond::cond(p, cond);
                let body = self.block(body);
                if body.stmts.is_empty() {
                    // No statement counts the iterations: the loop head does.
                    Box::new(move |it, c| {
                        while cond(it, c)? {
                            it.step(&c.prog, head)?;
                        }
                        Ok(())
                    })
                } else {
                    Box::new(move |it, c| {
                        while cond(it, c)? {
                            it.exec_cblock(c, &body)?;
                        }
                        Ok(())
                    })
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
                    from: (num::num(p, from), from.span),
                    to: (num::num(p, to), to.span),
                    step: step.as_ref().map(|e| (num::num(p, e), e.span)),
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
                    subject: subject.clone(),
                    cases: cases
                        .iter()
                        .map(|(vals, b)| (vals.clone().into(), self.block(b)))
                        .collect(),
                    default: default.as_ref().map(|b| self.block(b)),
                };
                Box::new(move |it, c| it.exec_ctest(c, &t))
            }
            StmtKind::Return(Some(e)) if self.ret == Some(Ty::NUM) => {
                assign::num_into(p, e, assign::Sink::Return)
            }
            _ => {
                let s = s.clone();
                Box::new(move |it, c| it.exec_stmt(&c.prog, &s))
            }
        };
        CStmt { run, span: s.span }
    }
}
