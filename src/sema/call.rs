//! Call arguments: matching positional, named, optional, switch and conditional arguments
//! to the parameters of user routines and natives, with type and access-mode checks.

use super::error::SemaErrorKind as K;
use super::resolve::{Obj, PlaceRes};
use super::{Checker, LocalSym};
use crate::ast::{self, ArgKind, ParamMode};
use crate::ir::sig::SigMode;
use crate::ir::{Arg, NativeId, RoutineId, Ty, TypeId};
use crate::source::Span;

/// Parameter type as the argument checks see it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PTy {
    /// A concrete type.
    T(Ty),
    /// Any value type (arrays of rank `rank` when it is not 0; [`ANY_RANK`]: scalars and
    /// arrays of any rank).
    Any(u8),
    /// num or dnum.
    AnyNum,
    /// An I/O signal of any kind (`signaldi` … `signalgo`) or a string naming one
    /// (`AliasIO`, `ValidIO`).
    AnySignal,
    /// Any value type, an array of one, or a signal variable (`GetDataVal`'s `Value`: a
    /// signal variable is connected to the configured signal of that name).
    AnyDataOrSignal,
    /// A switch.
    Switch,
}

/// The rank of `PTy::Any` that accepts scalars and arrays alike (`anydata`).
pub(crate) const ANY_RANK: u8 = u8::MAX;

/// Access mode as the argument checks see it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PMode {
    In,
    InOut,
    Var,
    Pers,
    /// Read-only reference (natives): places are passed without copying.
    Ref,
}

/// A parameter of a user routine or native.
#[derive(Clone, Debug)]
pub(crate) struct PView {
    pub name: String,
    pub ty: PTy,
    pub mode: PMode,
    pub optional: bool,
    pub group: u16,
}

/// Who is called.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Callee {
    User(RoutineId),
    Native(NativeId),
}

impl Checker<'_> {
    /// Resolved parameters of a native (cached); an unknown type is an internal error.
    pub(super) fn native_view(&mut self, nid: NativeId) -> Vec<PView> {
        if let Some(Some(v)) = self.native_params.get(nid.0 as usize) {
            return v.clone();
        }
        let sig = self.natives[nid.0 as usize].clone();
        let mut out = Vec::with_capacity(sig.params.len());
        for p in &sig.params {
            let ty = if p.ty.is_switch() {
                PTy::Switch
            } else if p.ty.is_any() {
                PTy::Any(p.ty.rank)
            } else if p.ty.is_any_data() {
                PTy::Any(ANY_RANK)
            } else if p.ty.is_anynum() {
                PTy::AnyNum
            } else if p.ty.name.eq_ignore_ascii_case("anysignal") {
                PTy::AnySignal
            } else if p.ty.name.eq_ignore_ascii_case("anydataorsignal") {
                PTy::AnyDataOrSignal
            } else {
                match self.types.lookup(&p.ty.name) {
                    Some(id) => PTy::T(Ty {
                        base: self.types.resolve(id),
                        rank: p.ty.rank,
                    }),
                    None => {
                        self.err(
                            K::BadSignature {
                                native: sig.name.clone(),
                                ty: p.ty.name.clone(),
                            },
                            Span::default(),
                        );
                        PTy::Any(p.ty.rank)
                    }
                }
            };
            out.push(PView {
                name: p.name.clone(),
                ty,
                mode: match p.mode {
                    SigMode::In => PMode::In,
                    SigMode::InOut => PMode::InOut,
                    SigMode::Var => PMode::Var,
                    SigMode::Pers => PMode::Pers,
                    SigMode::Ref => PMode::Ref,
                },
                optional: p.optional,
                group: p.group,
            });
        }
        if let Some(slot) = self.native_params.get_mut(nid.0 as usize) {
            *slot = Some(out.clone());
        }
        out
    }

    /// Result type of a native function (`None` for instructions).
    pub(super) fn native_ret(&mut self, nid: NativeId) -> Option<Ty> {
        let ret = self.natives[nid.0 as usize].ret.clone()?;
        let base = self
            .types
            .lookup(&ret.name)
            .map(|id| self.types.resolve(id))
            .unwrap_or(TypeId::NUM);
        Some(Ty {
            base,
            rank: ret.rank,
        })
    }

    fn user_view(&self, rid: RoutineId) -> Vec<PView> {
        self.routines[rid.0 as usize]
            .params
            .iter()
            .map(|p| PView {
                name: p.name.clone(),
                ty: if p.ty.base == TypeId::SWITCH {
                    PTy::Switch
                } else {
                    PTy::T(p.ty)
                },
                mode: match p.mode {
                    ParamMode::In => PMode::In,
                    ParamMode::InOut => PMode::InOut,
                    ParamMode::Var => PMode::Var,
                    ParamMode::Pers => PMode::Pers,
                },
                optional: p.optional,
                group: p.group,
            })
            .collect()
    }

    /// Lower the arguments of a call; one [`Arg`] per callee parameter.
    pub(super) fn lower_args(
        &mut self,
        callee: Callee,
        args: &[ast::Arg],
        name: &ast::Ident,
        span: Span,
    ) -> Option<Vec<Arg>> {
        let params = match callee {
            Callee::User(r) => self.user_view(r),
            Callee::Native(n) => self.native_view(n),
        };

        let callee_name = name.node.to_string();
        let mut out: Vec<Option<Arg>> = vec![None; params.len()];
        let mut next_req = 0usize;
        let mut ok = true;
        for a in args {
            let (idx, arg) = match &a.kind {
                ArgKind::Positional(e) => {
                    let Some(i) = (next_req..params.len()).find(|&i| !params[i].optional) else {
                        self.err(
                            K::TooManyArgs {
                                callee: callee_name.clone(),
                            },
                            a.span,
                        );
                        ok = false;
                        continue;
                    };
                    next_req = i + 1;
                    (i, self.arg_for(&params[i], e))
                }
                ArgKind::Named { name: pn, value } => {
                    let Some(i) = params
                        .iter()
                        .position(|p| !p.optional && p.name.eq_ignore_ascii_case(&pn.node))
                    else {
                        self.err(
                            K::UnknownNamed {
                                callee: callee_name.clone(),
                                name: pn.node.to_string(),
                            },
                            pn.span,
                        );
                        ok = false;
                        continue;
                    };
                    (i, self.arg_for(&params[i], value))
                }
                ArgKind::Optional { name: pn, value } => {
                    let Some(i) = self.optional_index(&params, pn, &callee_name) else {
                        ok = false;
                        continue;
                    };
                    let p = &params[i];
                    let arg = match (p.ty, value) {
                        (PTy::Switch, None) => Some(Arg::Switch),
                        (PTy::Switch, Some(_)) => {
                            self.err(
                                K::SwitchValue {
                                    name: p.name.clone(),
                                    is_switch: true,
                                },
                                a.span,
                            );
                            None
                        }
                        (_, Some(v)) => self.arg_for(p, v),
                        (_, None) => {
                            // `\Name` alone passes the data object of the same name.
                            let e = ast::Expr {
                                kind: ast::ExprKind::Name(pn.clone()),
                                span: pn.span,
                            };
                            self.arg_for(p, &e)
                        }
                    };
                    (i, arg)
                }
                ArgKind::Conditional { name: pn, param } => {
                    let Some(i) = self.optional_index(&params, pn, &callee_name) else {
                        ok = false;
                        continue;
                    };
                    (i, self.conditional(&params[i], param))
                }
                ArgKind::Placeholder(_) => {
                    // Calls with an `<ARG>` are lowered to a placeholder by the callers.
                    ok = false;
                    continue;
                }
            };
            if out[idx].is_some() {
                self.err(
                    K::DuplicateArg {
                        name: params[idx].name.clone(),
                    },
                    a.span,
                );
                ok = false;
                continue;
            }
            if params[idx].optional
                && let Some(j) = (0..params.len())
                    .find(|&j| j != idx && params[j].group == params[idx].group && out[j].is_some())
            {
                self.err(
                    K::ExclusiveArgs {
                        first: params[j].name.clone(),
                        second: params[idx].name.clone(),
                    },
                    a.span,
                );
                ok = false;
            }
            match arg {
                Some(x) => out[idx] = Some(x),
                None => ok = false,
            }
        }
        for (i, p) in params.iter().enumerate() {
            if !p.optional && out[i].is_none() && ok {
                self.err(
                    K::MissingArg {
                        callee: callee_name.clone(),
                        param: p.name.clone(),
                    },
                    span,
                );
                ok = false;
            }
        }
        ok.then(|| out.into_iter().map(|a| a.unwrap_or(Arg::Absent)).collect())
    }

    fn optional_index(&mut self, params: &[PView], pn: &ast::Ident, callee: &str) -> Option<usize> {
        let found = params
            .iter()
            .position(|p| p.optional && p.name.eq_ignore_ascii_case(&pn.node));
        if found.is_none() {
            let is_required = params
                .iter()
                .any(|p| !p.optional && p.name.eq_ignore_ascii_case(&pn.node));
            self.err(
                K::UnknownOptional {
                    callee: callee.to_string(),
                    name: pn.node.to_string(),
                    is_required,
                },
                pn.span,
            );
        }
        found
    }

    /// `\p ? q`: pass the caller's optional parameter `q` on when it is present.
    fn conditional(&mut self, p: &PView, q: &ast::Ident) -> Option<Arg> {
        let slot = self.optional_param_slot(q)?;
        let inner = if p.ty == PTy::Switch {
            let is_switch = self.rcx.as_ref().is_some_and(|rcx| {
                matches!(rcx.scope.get(&q.folded()), Some(LocalSym::Param(i))
                    if self.routines[rcx.rid.0 as usize].params[*i].ty.base == TypeId::SWITCH)
            });
            if !is_switch {
                self.err(
                    K::TypeMismatch {
                        context: format!("the argument for `\\{}`", p.name),
                        expected: "switch".into(),
                        found: "a value".into(),
                    },
                    q.span,
                );
                return None;
            }
            Arg::Switch
        } else {
            let e = ast::Expr {
                kind: ast::ExprKind::Name(q.clone()),
                span: q.span,
            };
            self.arg_for(p, &e)?
        };
        Some(Arg::Cond {
            param: slot,
            arg: Box::new(inner),
        })
    }

    /// Lower one argument for parameter `p`.
    fn arg_for(&mut self, p: &PView, e: &ast::Expr) -> Option<Arg> {
        let ctx = format!("the argument for `{}`", p.name);
        if p.ty == PTy::Switch {
            self.err(
                K::SwitchValue {
                    name: p.name.clone(),
                    is_switch: true,
                },
                e.span,
            );
            return None;
        }
        match p.mode {
            PMode::In => {
                let (x, xt) = match p.ty {
                    PTy::T(t) => (self.rvalue_as(e, t, &ctx)?, t),
                    _ => self.rvalue(e, None, None)?,
                };
                self.check_loose(p, xt, &ctx, e.span)?;
                Some(Arg::Value(x))
            }
            PMode::Ref => match self.place(e) {
                PlaceRes::Ok(info) => {
                    self.check_exact(p, info.ty, &ctx, e.span)?;
                    Some(Arg::Ref(info.place))
                }
                PlaceRes::Err => None,
                PlaceRes::NotPlace => {
                    let (x, xt) = self.rvalue(e, None, None)?;
                    self.check_exact(p, xt, &ctx, e.span)?;
                    Some(Arg::Value(x))
                }
            },
            PMode::InOut | PMode::Var | PMode::Pers => {
                if let (PTy::T(t), ast::ExprKind::Name(id)) = (p.ty, &e.kind)
                    && self.is_signal_type(t)
                    && !self.name_exists(id)
                {
                    self.err(
                        K::UnknownSignal {
                            name: id.node.to_string(),
                            ty: self.ty_name(t),
                        },
                        e.span,
                    );
                    return None;
                }
                let mode = match p.mode {
                    PMode::InOut => "INOUT",
                    PMode::Var => "VAR",
                    _ => "PERS",
                };
                let info = match self.place(e) {
                    PlaceRes::Ok(i) => i,
                    PlaceRes::Err => return None,
                    PlaceRes::NotPlace => {
                        self.err(
                            K::ArgMode {
                                param: p.name.clone(),
                                mode,
                                found: "an expression".into(),
                            },
                            e.span,
                        );
                        return None;
                    }
                };
                let allowed = match (p.mode, info.kind) {
                    (_, Obj::Var) => p.mode != PMode::Pers,
                    (_, Obj::RefParam(ParamMode::Var)) => p.mode != PMode::Pers,
                    (_, Obj::RefParam(ParamMode::InOut)) => p.mode != PMode::Pers || info.whole,
                    // A part of a persistent may be passed INOUT (`Incr counts{i};`): real
                    // controller backups do it (docs/rapid.md, "Routines and calls").
                    (PMode::InOut, Obj::Pers | Obj::RefParam(ParamMode::Pers)) => true,
                    (PMode::Pers, Obj::Pers | Obj::RefParam(ParamMode::Pers)) => info.whole,
                    // Predefined data is passed on as a persistent (`MoveL p, v100, fine,
                    // tool0`, `MoveHome tool0;`); only assigning it directly is refused.
                    (PMode::Pers | PMode::InOut, Obj::ReadOnlyPers) => info.whole,
                    _ => false,
                };
                if !allowed {
                    let found = match info.kind {
                        Obj::Var => "a variable".to_string(),
                        Obj::Pers if !info.whole => "a part of a persistent".into(),
                        Obj::Pers => "a persistent".into(),
                        Obj::Const => "a constant".into(),
                        Obj::InParam => "an IN parameter (read-only)".into(),
                        Obj::RefParam(m) => format!("{} parameter", mode_name(m)),
                        Obj::ForVar => "a FOR loop variable".into(),
                        Obj::ReadOnlyPers => "predefined read-only data".into(),
                    };
                    self.err(
                        K::ArgMode {
                            param: p.name.clone(),
                            mode,
                            found: format!("`{}`, {found}", info.name),
                        },
                        e.span,
                    );
                    return None;
                }
                self.check_exact(p, info.ty, &ctx, e.span)?;
                Some(Arg::Ref(info.place))
            }
        }
    }

    /// Type check for a value passed by copy (already coerced for concrete types).
    fn check_loose(&mut self, p: &PView, t: Ty, ctx: &str, span: Span) -> Option<()> {
        match p.ty {
            PTy::T(_) | PTy::Switch => Some(()),
            _ => self.check_exact(p, t, ctx, span),
        }
    }

    /// Type check for a value passed by reference: no conversions.
    fn check_exact(&mut self, p: &PView, t: Ty, ctx: &str, span: Span) -> Option<()> {
        let (ok, expected) = match p.ty {
            PTy::T(want) => (want == t, self.ty_name(want)),
            PTy::Any(ANY_RANK) => (
                self.types.is_value(t.base),
                "a value or an array of values".to_string(),
            ),
            PTy::Any(0) => (
                t.rank == 0 && self.types.is_value(t.base),
                "a value (not an array)".to_string(),
            ),
            PTy::Any(_) => (t.rank > 0, "an array".to_string()),
            PTy::AnyNum => (t == Ty::NUM || t == Ty::DNUM, "num or dnum".to_string()),
            PTy::AnySignal => (
                t.rank == 0
                    && (t.base == TypeId::STRING || self.types.name(t.base).starts_with("signal")),
                "a signal or a string".to_string(),
            ),
            PTy::AnyDataOrSignal => (
                self.types.is_value(t.base)
                    || (t.rank == 0 && self.types.name(t.base).starts_with("signal")),
                "a value, an array of values or a signal".to_string(),
            ),
            PTy::Switch => (false, "switch".to_string()),
        };
        if ok {
            Some(())
        } else {
            self.err(
                K::TypeMismatch {
                    context: ctx.to_string(),
                    expected,
                    found: self.ty_name(t),
                },
                span,
            );
            None
        }
    }
}

fn mode_name(m: ParamMode) -> &'static str {
    match m {
        ParamMode::In => "an IN",
        ParamMode::InOut => "an INOUT",
        ParamMode::Var => "a VAR",
        ParamMode::Pers => "a PERS",
    }
}
