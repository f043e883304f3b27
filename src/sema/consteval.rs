//! Constant folding for what must be known before running: array sizes (which may name
//! numeric constants declared anywhere).

use super::error::SemaErrorKind as K;
use super::{Checker, LocalSym};
use crate::ast::{BinOp, Expr, ExprKind, Storage, UnaryOp};
use crate::ir::limits::MAX_DECL_VALUES;
use crate::ir::{GlobalOrigin, TypeId};

/// Folding state of a global constant.
#[derive(Clone, Copy, Debug)]
pub(crate) enum ConstState {
    /// Being folded (a cycle when met again).
    InProgress,
    /// Folded (None: not a compile-time number).
    Done(Option<f64>),
}

impl Checker<'_> {
    /// Array sizes: positive integer constants (1 for each that is not, or that is larger
    /// than one declaration may hold, with a diagnostic naming the limit).
    pub(super) fn const_dims(&mut self, dims: &[Expr]) -> Vec<u32> {
        dims.iter()
            .map(|d| match self.const_num(d) {
                Some(x) if x >= 1.0 && x.fract() == 0.0 && x <= MAX_DECL_VALUES as f64 => x as u32,
                Some(x) if x >= 1.0 && x.fract() == 0.0 => {
                    self.err(K::ArraySizeTooLarge { size: x }, d.span);
                    1
                }
                Some(x) => {
                    self.err(
                        K::BadDecl {
                            why: format!("an array size must be a positive integer, not {x}"),
                        },
                        d.span,
                    );
                    1
                }
                None => {
                    self.err(
                        K::NotConstant {
                            what: "an array size (a positive integer)",
                        },
                        d.span,
                    );
                    1
                }
            })
            .collect()
    }

    /// Fold a numeric expression, if it only uses literals and numeric constants.
    pub(super) fn const_num(&mut self, e: &Expr) -> Option<f64> {
        match &e.kind {
            ExprKind::Num(x) => Some(*x),
            ExprKind::Paren(x) => self.const_num(x),
            ExprKind::Unary { op, expr } => {
                let v = self.const_num(expr)?;
                match op {
                    UnaryOp::Neg => Some(-v),
                    UnaryOp::Plus => Some(v),
                    UnaryOp::Not => None,
                }
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let a = self.const_num(lhs)?;
                let b = self.const_num(rhs)?;
                match op {
                    BinOp::Add => Some(a + b),
                    BinOp::Sub => Some(a - b),
                    BinOp::Mul => Some(a * b),
                    BinOp::Div if b != 0.0 => Some(a / b),
                    BinOp::IntDiv if b != 0.0 && a.fract() == 0.0 && b.fract() == 0.0 => {
                        Some((a as i64 / b as i64) as f64)
                    }
                    BinOp::Mod if b != 0.0 && a.fract() == 0.0 && b.fract() == 0.0 => {
                        Some((a as i64 % b as i64) as f64)
                    }
                    _ => None,
                }
            }
            ExprKind::Name(id) => {
                let key = id.folded();
                if let Some(rcx) = &self.rcx {
                    if let Some(LocalSym::Data { cval, .. }) = rcx.scope.get(&key) {
                        return *cval;
                    }
                    if rcx.scope.contains_key(&key) || rcx.for_vars.iter().any(|(n, _)| *n == key) {
                        return None;
                    }
                }
                let gid = self.lookup_global(&key)?;
                let g = &self.globals[gid.0 as usize];
                match &g.origin {
                    GlobalOrigin::ErrConst(n) => return Some(*n as f64),
                    GlobalOrigin::NumConst(x) => return Some(*x),
                    GlobalOrigin::Module(_) => {}
                    _ => return None,
                }
                if g.storage != Storage::Const
                    || !matches!(g.ty.base, TypeId::NUM | TypeId::DNUM)
                    || g.ty.rank != 0
                {
                    return None;
                }
                match self.const_state.get(&gid.0) {
                    Some(ConstState::Done(v)) => return *v,
                    Some(ConstState::InProgress) => return None,
                    None => {}
                }
                let (m, item) = self.global_decls.get(gid.0 as usize).copied().flatten()?;
                let d = self.data_decl(m, item)?;
                let init = d.init.as_ref()?;
                self.const_state.insert(gid.0, ConstState::InProgress);
                let saved = (self.cur_module, self.rcx.take());
                self.cur_module = m;
                let v = self.const_num(init);
                self.cur_module = saved.0;
                self.rcx = saved.1;
                self.const_state.insert(gid.0, ConstState::Done(v));
                v
            }
            _ => None,
        }
    }
}
