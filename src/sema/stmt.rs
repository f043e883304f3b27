//! Routine bodies and module data initialisers: routine data, statements, labels and GOTO,
//! handlers, RETURN rules, and the FUNC end-of-body check.

use std::collections::HashMap;

use super::error::SemaErrorKind as K;
use super::resolve::{Obj, PlaceRes};
use super::{Checker, LocalSym, RoutineCx};
use crate::ast::{self, ArgKind, ExprKind as AK, ParamMode, StmtKind as S, Storage};
use crate::ir::{Block, Handler, LateArg, LocalDecl, RoutineId, RoutineKind, Stmt, StmtKind, Ty};

impl<'a> Checker<'a> {
    /// Lower the initial values of module data (in their module's scope).
    pub(super) fn lower_global_inits(&mut self) {
        self.init_deps = vec![Vec::new(); self.globals.len()];
        self.has_init = vec![false; self.globals.len()];
        for gi in 0..self.globals.len() {
            let decls = self.decls_of(gi);
            let Some((m, d)) = decls.iter().find_map(|&(m, item)| {
                self.data_decl(m, item)
                    .filter(|d| d.init.is_some())
                    .map(|d| (m, d))
            }) else {
                continue;
            };
            let Some(init) = &d.init else {
                continue;
            };
            self.cur_module = m;
            self.rcx = None;
            self.deps.clear();
            let (ty, dims) = (self.globals[gi].ty, self.globals[gi].dims.clone());
            let ctx = format!("the initial value of `{}`", d.name.node);
            let dims_opt = (!dims.is_empty()).then_some(dims.as_slice());
            let v = self
                .rvalue(init, Some(ty), dims_opt)
                .and_then(|(x, xt)| self.coerce(x, xt, ty, &ctx, init.span));
            self.has_init[gi] = v.is_some();
            if self.keep_code {
                self.globals[gi].init = v.map(Box::new);
            }
            self.init_deps[gi] = std::mem::take(&mut self.deps);
        }
    }

    /// Lower every routine body.
    pub(super) fn lower_routines(&mut self) {
        for ri in 0..self.routines.len() {
            self.lower_routine(RoutineId(ri as u32));
        }
    }

    fn lower_routine(&mut self, rid: RoutineId) {
        let r: &'a ast::Routine = self.routine_asts[rid.0 as usize];
        let (module, kind, n_slots) = {
            let ir = &self.routines[rid.0 as usize];
            (ir.module, ir.kind.clone(), ir.n_slots)
        };
        self.cur_module = module;
        let mut scope = HashMap::new();
        for (i, p) in self.routines[rid.0 as usize].params.iter().enumerate() {
            scope.insert(p.name.to_ascii_uppercase(), LocalSym::Param(i));
        }
        let mut labels = HashMap::new();
        let mut all: Vec<&ast::Stmt> = Vec::new();
        collect_stmts(&r.body, &mut all);
        if let Some(h) = &r.error {
            collect_stmts(&h.body, &mut all);
        }
        if let Some(u) = &r.undo {
            collect_stmts(u, &mut all);
        }
        for s in all {
            if let S::Label(id) = &s.kind {
                let n = labels.len() as u32;
                if labels.insert(id.folded(), n).is_some() {
                    self.err(
                        K::Duplicate {
                            name: id.node.to_string(),
                            first: id.span,
                        },
                        id.span,
                    );
                }
            }
        }
        self.rcx = Some(RoutineCx {
            rid,
            func_ret: match kind {
                RoutineKind::Func(t) => Some(t),
                _ => None,
            },
            scope,
            for_vars: Vec::new(),
            n_slots,
            labels,
            block_labels: Vec::new(),
            in_handler: false,
            returns: 0,
        });
        let locals = self.routine_data(&r.data);
        self.check_routine_data(&r.name.node, &locals);
        let body = if self.incomplete.contains(&(rid.0 as usize)) {
            Block {
                stmts: vec![Stmt {
                    kind: StmtKind::Placeholder("<PAR>"),
                    span: r.head_span,
                }],
                labels: Vec::new(),
            }
        } else {
            self.block(&r.body)
        };
        let error = r.error.as_ref().map(|h| {
            let errnos = h.errnos.as_ref().map(|list| {
                list.iter()
                    .filter_map(|e| self.rvalue_as(e, Ty::NUM, "an error number"))
                    .collect()
            });
            if let Some(rcx) = &mut self.rcx {
                rcx.in_handler = true;
            }
            let body = self.block(&h.body);
            if let Some(rcx) = &mut self.rcx {
                rcx.in_handler = false;
            }
            Handler {
                errnos,
                body,
                span: h.span,
            }
        });
        let undo = r.undo.as_ref().map(|u| self.block(u));
        let rcx = self.rcx.take();
        if let (RoutineKind::Func(_), Some(rcx)) = (&kind, &rcx) {
            if rcx.returns == 0 {
                self.err(
                    K::FuncWithoutReturn {
                        name: r.name.node.to_string(),
                    },
                    r.head_span,
                );
            } else if !terminates(&r.body) {
                self.err(
                    K::FuncEndReachable {
                        name: r.name.node.to_string(),
                    },
                    r.span.end_point(),
                );
            }
        }
        let ir = &mut self.routines[rid.0 as usize];
        ir.locals = locals;
        if !self.keep_code {
            // Only the errors are wanted (`sema::check_only`).
            return;
        }
        ir.body = body;
        ir.error = error;
        ir.undo = undo;
        ir.n_slots = rcx.map(|c| c.n_slots).unwrap_or(n_slots);
        ir.simple = matches!(ir.kind, RoutineKind::Func(_))
            && ir.locals.is_empty()
            && ir.error.is_none()
            && ir.undo.is_none()
            && ir
                .params
                .iter()
                .all(|p| p.mode == ParamMode::In && !p.optional)
            && matches!(
                ir.body.stmts.as_slice(),
                [Stmt {
                    kind: StmtKind::Return(Some(_)),
                    ..
                }]
            );
    }

    fn routine_data(&mut self, data: &'a [ast::DataDecl]) -> Vec<LocalDecl> {
        // (Exactly their number: the routine keeps them.)
        let mut out = Vec::with_capacity(data.len());
        for d in data {
            if d.storage == Storage::Pers {
                self.err(
                    K::BadDecl {
                        why: "PERS data must be declared at module level".into(),
                    },
                    d.span,
                );
                continue;
            }
            let Some(base) = self.resolve_type(&d.ty) else {
                continue;
            };
            let ty = Ty {
                base,
                rank: d.dims.len().min(3) as u8,
            };
            if !self.types.is_value(base) && (d.storage == Storage::Const || d.init.is_some()) {
                self.err(
                    K::NonValue {
                        ty: self.ty_name(ty),
                        what: "a CONST or given an initial value",
                    },
                    d.span,
                );
                continue;
            }
            if d.storage == Storage::Const && d.init.is_none() {
                self.err(
                    K::BadDecl {
                        why: format!("constant `{}` needs a value", d.name.node),
                    },
                    d.span,
                );
            }
            let dims = self.const_dims(&d.dims);
            let init = d.init.as_ref().and_then(|e| {
                let ctx = format!("the initial value of `{}`", d.name.node);
                let dd = (!dims.is_empty()).then_some(dims.as_slice());
                self.rvalue(e, Some(ty), dd)
                    .and_then(|(x, xt)| self.coerce(x, xt, ty, &ctx, e.span))
            });
            let cval = if d.storage == Storage::Const && ty.rank == 0 {
                d.init.as_ref().and_then(|e| self.const_num(e))
            } else {
                None
            };
            let key = d.name.folded();
            let Some(rcx) = self.rcx.as_mut() else {
                continue;
            };
            if rcx.scope.contains_key(&key) {
                self.err(
                    K::Duplicate {
                        name: d.name.node.to_string(),
                        first: d.name.span,
                    },
                    d.name.span,
                );
                continue;
            }
            let slot = rcx.n_slots;
            rcx.n_slots += 1;
            rcx.scope.insert(
                key,
                LocalSym::Data {
                    slot,
                    ty,
                    dims: dims.clone(),
                    constant: d.storage == Storage::Const,
                    cval,
                },
            );
            out.push(LocalDecl {
                name: d.name.node.to_string(),
                ty,
                dims,
                init,
                slot,
                span: d.span,
            });
        }
        out
    }

    /// Lower a statement list, recording the labels it defines.
    fn block(&mut self, stmts: &'a [ast::Stmt]) -> Block {
        let own: Vec<u32> = stmts
            .iter()
            .filter_map(|s| match &s.kind {
                S::Label(id) => self.rcx.as_ref()?.labels.get(&id.folded()).copied(),
                _ => None,
            })
            .collect();
        if let Some(rcx) = &mut self.rcx {
            rcx.block_labels.push(own);
        }
        let mut out = Block::default();
        for s in stmts {
            if let Some(st) = self.stmt(s) {
                if let StmtKind::Label(l) = st.kind {
                    out.labels.push((l, out.stmts.len() as u32));
                }
                out.stmts.push(st);
            }
        }
        if let Some(rcx) = &mut self.rcx {
            rcx.block_labels.pop();
        }
        out
    }

    fn in_handler(&self) -> bool {
        self.rcx.as_ref().is_some_and(|r| r.in_handler)
    }

    fn stmt(&mut self, s: &'a ast::Stmt) -> Option<Stmt> {
        let span = s.span;
        let kind = match &s.kind {
            S::Assign { target, value } => self.assign(target, value)?,
            S::Call { name, args } => {
                self.proc_call(name, &args.items(name, self.text_of(name.span)), span)?
            }
            S::LateCall { name, args } => {
                let n = self.rvalue_as(name, Ty::STRING, "the procedure name of a late-bound call");
                let largs = self.late_args(args);
                StmtKind::LateCall {
                    name: n?,
                    args: largs?,
                    module: self.cur_module,
                }
            }
            S::If {
                cond,
                then_body,
                elseifs,
                else_body,
            } => {
                let c = self.rvalue_as(cond, Ty::BOOL, "the condition of IF");
                let mut branches = Vec::new();
                let tb = self.block(then_body);
                if let Some(c) = c {
                    branches.push((c, tb));
                }
                for (ec, eb) in elseifs {
                    let c = self.rvalue_as(ec, Ty::BOOL, "the condition of ELSEIF");
                    let b = self.block(eb);
                    if let Some(c) = c {
                        branches.push((c, b));
                    }
                }
                let else_body = else_body.as_ref().map(|b| self.block(b));
                StmtKind::If {
                    branches,
                    else_body,
                }
            }
            S::CompactIf { cond, stmt } => {
                let c = self.rvalue_as(cond, Ty::BOOL, "the condition of IF");
                let inner = self.block(std::slice::from_ref(stmt.as_ref()));
                StmtKind::If {
                    branches: vec![(c?, inner)],
                    else_body: None,
                }
            }
            S::While { cond, body } => {
                let c = self.rvalue_as(cond, Ty::BOOL, "the condition of WHILE");
                let b = self.block(body);
                StmtKind::While { cond: c?, body: b }
            }
            S::For {
                var,
                from,
                to,
                step,
                body,
            } => {
                let f = self.rvalue_as(from, Ty::NUM, "the start of FOR");
                let t = self.rvalue_as(to, Ty::NUM, "the end of FOR");
                let st = step
                    .as_ref()
                    .map(|e| self.rvalue_as(e, Ty::NUM, "the STEP of FOR"));
                let rcx = self.rcx.as_mut()?;
                let slot = rcx.n_slots;
                rcx.n_slots += 1;
                rcx.for_vars.push((var.folded(), slot));
                let b = self.block(body);
                if let Some(rcx) = self.rcx.as_mut() {
                    rcx.for_vars.pop();
                }
                let step = match st {
                    Some(x) => Some(x?),
                    None => None,
                };
                StmtKind::For {
                    slot,
                    from: f?,
                    to: t?,
                    step,
                    body: b,
                }
            }
            S::Test {
                subject,
                cases,
                default,
            } => {
                let sub = self.rvalue(subject, None, None);
                let mut out = Vec::new();
                let sty = sub.as_ref().map(|s| s.1);
                if let Some(t) = sty
                    && (t.rank > 0 || !self.types.is_value(t.base))
                {
                    self.err(
                        K::TypeMismatch {
                            context: "the value of TEST".into(),
                            expected: "a value type".into(),
                            found: self.ty_name(t),
                        },
                        subject.span,
                    );
                }
                for c in cases {
                    let mut vals = Vec::new();
                    for v in &c.values {
                        if let Some(t) = sty
                            && let Some(x) = self.rvalue_as(v, t, "a CASE value")
                        {
                            vals.push(x);
                        }
                    }
                    let b = self.block(&c.body);
                    out.push((vals, b));
                }
                let default = default.as_ref().map(|b| self.block(b));
                StmtKind::Test {
                    subject: sub?.0,
                    cases: out,
                    default,
                }
            }
            S::Label(id) => StmtKind::Label(*self.rcx.as_ref()?.labels.get(&id.folded())?),
            S::Goto(id) => {
                let rcx = self.rcx.as_ref()?;
                match rcx.labels.get(&id.folded()) {
                    None => {
                        self.err(
                            K::BadLabel {
                                name: id.node.to_string(),
                                exists: false,
                            },
                            span,
                        );
                        return None;
                    }
                    Some(&l) if rcx.block_labels.iter().any(|b| b.contains(&l)) => {
                        StmtKind::Goto(l)
                    }
                    Some(_) => {
                        self.err(
                            K::BadLabel {
                                name: id.node.to_string(),
                                exists: true,
                            },
                            span,
                        );
                        return None;
                    }
                }
            }
            S::Return(e) => {
                let ret = self.rcx.as_ref()?.func_ret;
                if let Some(rcx) = self.rcx.as_mut() {
                    rcx.returns += 1;
                }
                match (ret, e) {
                    (Some(t), Some(e)) => {
                        StmtKind::Return(Some(self.rvalue_as(e, t, "the returned value")?))
                    }
                    (Some(_), None) => {
                        self.err(K::MissingReturnValue, span);
                        return None;
                    }
                    (None, Some(e)) => {
                        self.err(K::ReturnValueInProc, e.span);
                        return None;
                    }
                    (None, None) => StmtKind::Return(None),
                }
            }
            S::Raise(e) => match e {
                Some(e) => StmtKind::Raise(Some(self.rvalue_as(e, Ty::NUM, "an error number")?)),
                None => {
                    if !self.in_handler() {
                        self.err(
                            K::HandlerOnly {
                                what: "RAISE without an error number",
                            },
                            span,
                        );
                        return None;
                    }
                    StmtKind::Raise(None)
                }
            },
            S::Retry | S::TryNext => {
                if !self.in_handler() {
                    let what = if matches!(s.kind, S::Retry) {
                        "RETRY"
                    } else {
                        "TRYNEXT"
                    };
                    self.err(K::HandlerOnly { what }, span);
                    return None;
                }
                if matches!(s.kind, S::Retry) {
                    StmtKind::Retry
                } else {
                    StmtKind::TryNext
                }
            }
            S::Exit => StmtKind::Exit,
            S::Connect { target, trap } => self.connect(target, trap)?,
            S::Placeholder(ph) => StmtKind::Placeholder(ph.as_str()),
        };
        Some(Stmt { kind, span })
    }

    fn assign(&mut self, target: &'a ast::Expr, value: &'a ast::Expr) -> Option<StmtKind> {
        let info = match self.place(target) {
            PlaceRes::Ok(i) => i,
            PlaceRes::Err => {
                let _ = self.rvalue(value, None, None);
                return None;
            }
            PlaceRes::NotPlace => {
                let readonly =
                    matches!(&target.kind, AK::Name(id) if id.is("ERRNO") || id.is("INTNO"));
                if readonly {
                    let name = match &target.kind {
                        AK::Name(id) => id.node.to_string(),
                        _ => String::new(),
                    };
                    self.err(
                        K::NotAssignable {
                            name,
                            why: "a read-only system variable".into(),
                        },
                        target.span,
                    );
                } else {
                    self.err(
                        K::NotAPlace {
                            context: "the target of an assignment".into(),
                        },
                        target.span,
                    );
                }
                return None;
            }
        };
        let why = match info.kind {
            Obj::Const => Some("a constant (CONST)"),
            Obj::InParam => Some("an IN parameter (pass it INOUT to change it)"),
            Obj::ForVar => Some("a FOR loop variable"),
            Obj::ReadOnlyPers => Some("predefined data of a READONLY system module"),
            _ => None,
        };
        if let Some(why) = why {
            self.err(
                K::NotAssignable {
                    name: info.name.clone(),
                    why: why.into(),
                },
                target.span,
            );
            return None;
        }
        if !self.types.is_value(info.ty.base) {
            self.err(
                K::NonValue {
                    ty: self.ty_name(info.ty),
                    what: "assigned",
                },
                target.span,
            );
            return None;
        }
        let ctx = format!("the value assigned to `{}`", place_text(target));
        let (x, xt) = self.rvalue(value, Some(info.ty), info.dims.as_deref())?;
        let x = self.coerce(x, xt, info.ty, &ctx, value.span)?;
        if info.ty == Ty::NUM {
            return Some(StmtKind::AssignNum {
                place: info.place,
                value: x,
            });
        }
        Some(StmtKind::Assign {
            place: info.place,
            value: x,
        })
    }

    fn proc_call(
        &mut self,
        name: &ast::Ident,
        args: &[ast::Arg],
        span: crate::source::Span,
    ) -> Option<StmtKind> {
        if args
            .iter()
            .any(|a| matches!(a.kind, ArgKind::Placeholder(_)))
        {
            return Some(StmtKind::Placeholder("<ARG>"));
        }
        let key = name.folded();
        if let Some(rid) = self.lookup_routine(&key) {
            let is = match self.routines[rid.0 as usize].kind {
                RoutineKind::Proc => None,
                RoutineKind::Func(_) => Some("a function"),
                RoutineKind::Trap => Some("a trap (run by interrupts)"),
            };
            if let Some(is) = is {
                self.err(
                    K::WrongRoutineKind {
                        name: name.node.to_string(),
                        is,
                        needed: "a procedure",
                    },
                    name.span,
                );
                return None;
            }
            let a = self.lower_args(super::call::Callee::User(rid), args, name, span)?;
            return Some(StmtKind::Call {
                routine: rid,
                args: a.into_boxed_slice(),
            });
        }
        if let Some(&nid) = self.native_syms.get(&key) {
            if self.natives[nid.0 as usize].is_func() {
                self.err(
                    K::WrongRoutineKind {
                        name: name.node.to_string(),
                        is: "a function",
                        needed: "an instruction",
                    },
                    name.span,
                );
                return None;
            }
            let a = self.lower_args(super::call::Callee::Native(nid), args, name, span)?;
            return Some(StmtKind::Native {
                native: nid,
                args: a.into_boxed_slice(),
            });
        }
        for a in args {
            let value = match &a.kind {
                ArgKind::Positional(e) => e,
                ArgKind::Named { value, .. } => value.as_ref(),
                _ => continue,
            };
            let _ = self.rvalue(value, None, None);
        }
        self.err(
            K::Unsupported {
                name: name.node.to_string(),
                what: "instruction",
            },
            name.span,
        );
        None
    }

    fn late_args(&mut self, args: &'a [ast::Arg]) -> Option<Vec<LateArg>> {
        let mut out = Vec::new();
        let mut ok = true;
        for a in args {
            let (name, expr): (Option<String>, Option<&ast::Expr>) = match &a.kind {
                ArgKind::Positional(e) => (None, Some(e)),
                ArgKind::Named { name, value } => {
                    (Some(name.node.to_string()), Some(value.as_ref()))
                }
                ArgKind::Optional { name, value } => {
                    (Some(name.node.to_string()), value.as_deref())
                }
                ArgKind::Conditional { .. } | ArgKind::Placeholder(_) => {
                    self.err(
                        K::BadDecl {
                            why: "conditional arguments and placeholders cannot be passed to a late-bound call".into(),
                        },
                        a.span,
                    );
                    ok = false;
                    continue;
                }
            };
            let (value, place) = match expr {
                Some(e) => {
                    let place = match self.place(e) {
                        PlaceRes::Ok(i) => Some(i.place),
                        _ => None,
                    };
                    let v = self.rvalue(e, None, None).map(|x| x.0);
                    if v.is_none() {
                        ok = false;
                    }
                    (v, place)
                }
                None => (None, None),
            };
            out.push(LateArg {
                name,
                value,
                place,
                span: a.span,
            });
        }
        ok.then_some(out)
    }

    fn connect(&mut self, target: &'a ast::Expr, trap: &ast::Ident) -> Option<StmtKind> {
        let info = match self.place(target) {
            PlaceRes::Ok(i) => i,
            PlaceRes::Err => return None,
            PlaceRes::NotPlace => {
                self.err(
                    K::NotAPlace {
                        context: "the interrupt of CONNECT".into(),
                    },
                    target.span,
                );
                return None;
            }
        };
        let var_ok = matches!(
            info.kind,
            Obj::Var | Obj::RefParam(ParamMode::Var) | Obj::RefParam(ParamMode::InOut)
        );
        if !var_ok || info.ty != Ty::NUM {
            self.err(
                K::ArgMode {
                    param: "interrupt".into(),
                    mode: "VAR",
                    found: format!("`{}` ({})", info.name, self.ty_name(info.ty)),
                },
                target.span,
            );
            return None;
        }
        let key = trap.folded();
        let Some(rid) = self.lookup_routine(&key) else {
            self.err(
                K::Undeclared {
                    name: trap.node.to_string(),
                    suggestion: None,
                },
                trap.span,
            );
            return None;
        };
        if self.routines[rid.0 as usize].kind != RoutineKind::Trap {
            self.err(
                K::WrongRoutineKind {
                    name: trap.node.to_string(),
                    is: "not a trap",
                    needed: "a TRAP routine",
                },
                trap.span,
            );
            return None;
        }
        Some(StmtKind::Connect {
            place: info.place,
            trap: rid,
        })
    }
}

/// Every statement, nested ones included.
fn collect_stmts<'x>(stmts: &'x [ast::Stmt], out: &mut Vec<&'x ast::Stmt>) {
    for s in stmts {
        out.push(s);
        match &s.kind {
            S::If {
                then_body,
                elseifs,
                else_body,
                ..
            } => {
                collect_stmts(then_body, out);
                for (_, b) in elseifs {
                    collect_stmts(b, out);
                }
                if let Some(b) = else_body {
                    collect_stmts(b, out);
                }
            }
            S::CompactIf { stmt, .. } => collect_stmts(std::slice::from_ref(stmt.as_ref()), out),
            S::While { body, .. } | S::For { body, .. } => collect_stmts(body, out),
            S::Test { cases, default, .. } => {
                for c in cases {
                    collect_stmts(&c.body, out);
                }
                if let Some(b) = default {
                    collect_stmts(b, out);
                }
            }
            _ => {}
        }
    }
}

/// Can execution not fall off the end of this statement list? (Conservative.)
fn terminates(stmts: &[ast::Stmt]) -> bool {
    let Some(last) = stmts.iter().rev().find(|s| !matches!(s.kind, S::Label(_))) else {
        return false;
    };
    match &last.kind {
        S::Return(_) | S::Raise(_) | S::Exit | S::Goto(_) | S::Retry | S::TryNext => true,
        S::Call { name, .. } => name.is("Stop") || name.is("ExitCycle"),
        S::If {
            then_body,
            elseifs,
            else_body: Some(eb),
            ..
        } => terminates(then_body) && elseifs.iter().all(|(_, b)| terminates(b)) && terminates(eb),
        S::Test {
            cases,
            default: Some(d),
            ..
        } => cases.iter().all(|c| terminates(&c.body)) && terminates(d),
        S::While { cond, .. } => matches!(cond.kind, AK::Bool(true)),
        _ => false,
    }
}

/// A place as written (`t.trans.x`, `a{…}`), for messages.
fn place_text(e: &ast::Expr) -> String {
    match &e.kind {
        AK::Name(id) => id.node.to_string(),
        AK::Component { base, field } => format!("{}.{}", place_text(base), field.node),
        AK::Index { base, .. } => format!("{}{{…}}", place_text(base)),
        _ => "…".to_string(),
    }
}
