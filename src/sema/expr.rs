//! Expression typing and lowering: operators with their operand types, conversions between
//! num and dnum, aggregates typed from context, signals read as values, and function calls.
//! Names and places are resolved in `resolve.rs`.

use std::sync::Arc;

use super::Checker;
use super::error::SemaErrorKind as K;
use super::resolve::{NameRes, PlaceRes};
use crate::ast::{self, BinOp as AB, ExprKind as AK, UnaryOp};
use crate::ir::{BinOp, Expr, ExprKind, RoutineKind, Ty, TypeId, UnOp};
use crate::source::Span;

impl Checker<'_> {
    /// Lower an expression and convert it to `ty` (num ↔ dnum conversions are implicit).
    pub(super) fn rvalue_as(&mut self, e: &ast::Expr, ty: Ty, context: &str) -> Option<Expr> {
        let (x, xt) = self.rvalue(e, Some(ty), None)?;
        self.coerce(x, xt, ty, context, e.span)
    }

    /// Convert a lowered value of type `from` to `to`, or report a mismatch.
    pub(super) fn coerce(
        &mut self,
        x: Expr,
        from: Ty,
        to: Ty,
        context: &str,
        span: Span,
    ) -> Option<Expr> {
        if from == to {
            return Some(x);
        }
        let (x, from) = if to.rank == 0 && matches!(to.base, TypeId::NUM | TypeId::DNUM) {
            self.signal_value(x, from)
        } else {
            (x, from)
        };
        if from == to {
            return Some(x);
        }
        if from.rank == 0 && to.rank == 0 {
            match (from.base, to.base) {
                (TypeId::NUM, TypeId::DNUM) => {
                    return Some(Expr {
                        kind: ExprKind::ToDnum(Box::new(x)),
                        span,
                    });
                }
                (TypeId::DNUM, TypeId::NUM) => {
                    return Some(Expr {
                        kind: ExprKind::ToNum(Box::new(x)),
                        span,
                    });
                }
                _ => {}
            }
        }
        self.err(
            K::TypeMismatch {
                context: context.to_string(),
                expected: self.ty_name(to),
                found: self.ty_name(from),
            },
            span,
        );
        None
    }

    /// Lower an expression; `expect` types aggregates and `dnum` literals, `dims` gives the
    /// sizes an array aggregate must have.
    pub(super) fn rvalue(
        &mut self,
        e: &ast::Expr,
        expect: Option<Ty>,
        dims: Option<&[u32]>,
    ) -> Option<(Expr, Ty)> {
        let span = e.span;
        let mk = |kind| Expr { kind, span };
        match &e.kind {
            AK::Num(x) => {
                if expect == Some(Ty::DNUM) {
                    Some((mk(ExprKind::Dnum(*x)), Ty::DNUM))
                } else {
                    Some((mk(ExprKind::Num(*x as f32)), Ty::NUM))
                }
            }
            AK::Str(s) => {
                let n = s.chars().count();
                if n > 80 {
                    self.err(K::StringTooLong { len: n }, span);
                }
                Some((mk(ExprKind::Str(Arc::from(s.as_str()))), Ty::STRING))
            }
            AK::Bool(b) => Some((mk(ExprKind::Bool(*b)), Ty::BOOL)),
            AK::Name(id) => match self.resolve_name(id) {
                NameRes::Place(info) => Some(self.load_place(info)),
                NameRes::Errno => Some((mk(ExprKind::Errno), Ty::NUM)),
                NameRes::Intno => Some((mk(ExprKind::Intno), Ty::NUM)),
                NameRes::Switch(n) => {
                    self.err(K::SwitchAsValue { name: n }, span);
                    None
                }
                NameRes::Unknown => {
                    self.undeclared(id);
                    None
                }
            },
            AK::Component { base, field } => match self.place(e) {
                PlaceRes::Ok(info) => Some(self.load_place(info)),
                PlaceRes::Err => None,
                PlaceRes::NotPlace => {
                    let (b, bt) = self.rvalue(base, None, None)?;
                    let (idx, fty, _) = self.field_of(bt, field)?;
                    Some((mk(ExprKind::Field(Box::new(b), idx)), fty))
                }
            },
            AK::Index { base, .. } => match self.place(e) {
                PlaceRes::Ok(info) => Some(self.load_place(info)),
                PlaceRes::Err => None,
                PlaceRes::NotPlace => {
                    let (_, bt) = self.rvalue(base, None, None)?;
                    self.err(
                        K::NotArray {
                            ty: self.ty_name(bt),
                            given: 1,
                        },
                        span,
                    );
                    None
                }
            },
            AK::Call { name, args } => self.func_call(name, args, span),
            AK::PackedAggregate(p) => {
                self.rvalue(&p.unpack(self.text_of(span), span), expect, dims)
            }
            AK::Aggregate(items) => match expect {
                Some(ty) => self.aggregate(items, ty, dims, span),
                None => {
                    self.err(K::AggregateUntyped, span);
                    None
                }
            },
            AK::Paren(x) => {
                let (inner, ty) = self.rvalue(x, expect, dims)?;
                Some((Expr { span, ..inner }, ty))
            }
            AK::Unary { op, expr } => self.unary(*op, expr, expect, span),
            AK::Binary { op, lhs, rhs } => self.binary(*op, lhs, rhs, expect, span),
            AK::Placeholder(ph) => {
                // The parser already warned; running into it stops the program.
                Some((
                    mk(ExprKind::Placeholder(ph.as_str())),
                    expect.unwrap_or(Ty::NUM),
                ))
            }
        }
    }

    /// Is `t` one of the signal types?
    pub(super) fn is_signal_type(&self, t: Ty) -> bool {
        t.rank == 0
            && matches!(
                self.types.name(t.base).to_ascii_lowercase().as_str(),
                "signaldi" | "signaldo" | "signalai" | "signalao" | "signalgi" | "signalgo"
            )
    }

    /// A signal used where a value is needed reads the signal (`IF di1 = 1`).
    pub(super) fn signal_value(&self, x: Expr, t: Ty) -> (Expr, Ty) {
        if self.is_signal_type(t) {
            let span = x.span;
            (
                Expr {
                    kind: ExprKind::SignalValue(Box::new(x)),
                    span,
                },
                Ty::NUM,
            )
        } else {
            (x, t)
        }
    }

    fn is_pos(&self, t: Ty) -> bool {
        t.rank == 0 && Some(t.base) == self.types.lookup("pos")
    }

    fn is_orient(&self, t: Ty) -> bool {
        t.rank == 0 && Some(t.base) == self.types.lookup("orient")
    }

    fn unary(
        &mut self,
        op: UnaryOp,
        x: &ast::Expr,
        expect: Option<Ty>,
        span: Span,
    ) -> Option<(Expr, Ty)> {
        let hint = if op == UnaryOp::Not { None } else { expect };
        let (v, t) = self.rvalue(x, hint, None)?;
        let (v, t) = self.signal_value(v, t);
        let wrap = |op, v| Expr {
            kind: ExprKind::Unary(op, Box::new(v)),
            span,
        };
        match op {
            UnaryOp::Not if t == Ty::BOOL => Some((wrap(UnOp::Not, v), t)),
            UnaryOp::Neg if t == Ty::NUM => Some((wrap(UnOp::NumNeg, v), t)),
            UnaryOp::Neg if t == Ty::DNUM => Some((wrap(UnOp::DnumNeg, v), t)),
            UnaryOp::Neg if self.is_pos(t) => Some((wrap(UnOp::PosNeg, v), t)),
            UnaryOp::Plus if t == Ty::NUM || t == Ty::DNUM || self.is_pos(t) => {
                Some((Expr { span, ..v }, t))
            }
            _ => {
                let op = match op {
                    UnaryOp::Not => "NOT",
                    UnaryOp::Neg => "-",
                    UnaryOp::Plus => "+",
                };
                self.err(
                    K::BadOperands {
                        op: op.into(),
                        lhs: self.ty_name(t),
                        rhs: None,
                    },
                    span,
                );
                None
            }
        }
    }

    fn binary(
        &mut self,
        op: AB,
        lhs: &ast::Expr,
        rhs: &ast::Expr,
        expect: Option<Ty>,
        span: Span,
    ) -> Option<(Expr, Ty)> {
        let arith = matches!(
            op,
            AB::Add | AB::Sub | AB::Mul | AB::Div | AB::IntDiv | AB::Mod
        );
        let hint = if arith && expect == Some(Ty::DNUM) {
            Some(Ty::DNUM)
        } else {
            None
        };
        // An aggregate operand takes its type from the other operand (`p = [1, 2, 3]`).
        let is_agg = |e: &ast::Expr| matches!(e.kind, AK::Aggregate(_) | AK::PackedAggregate(_));
        let (l, r) = if is_agg(rhs) && !is_agg(lhs) {
            let l = self.rvalue(lhs, hint, None);
            let want = l.as_ref().map(|x| x.1);
            (l, self.rvalue(rhs, want, None))
        } else if is_agg(lhs) && !is_agg(rhs) {
            let r = self.rvalue(rhs, hint, None);
            let want = r.as_ref().map(|x| x.1);
            (self.rvalue(lhs, want, None), r)
        } else {
            (self.rvalue(lhs, hint, None), self.rvalue(rhs, hint, None))
        };
        let ((l, lt), (r, rt)) = (l?, r?);
        let ((mut l, mut lt), (mut r, mut rt)) =
            (self.signal_value(l, lt), self.signal_value(r, rt));
        // A num literal next to a dnum operand is read as dnum (no single-precision rounding).
        if lt == Ty::DNUM && rt == Ty::NUM && is_literal(rhs) {
            (r, rt) = self.rvalue(rhs, Some(Ty::DNUM), None)?;
        } else if rt == Ty::DNUM && lt == Ty::NUM && is_literal(lhs) {
            (l, lt) = self.rvalue(lhs, Some(Ty::DNUM), None)?;
        }
        let numeric = |t: Ty| t == Ty::NUM || t == Ty::DNUM;
        let both_num = lt == Ty::NUM && rt == Ty::NUM;
        let mixed_numeric = numeric(lt) && numeric(rt) && !both_num;
        let bin = |op, l, r| Expr {
            kind: ExprKind::Binary(op, Box::new(l), Box::new(r)),
            span,
        };
        let to_d = |x: Expr, t: Ty| {
            if t == Ty::NUM {
                Expr {
                    span: x.span,
                    kind: ExprKind::ToDnum(Box::new(x)),
                }
            } else {
                x
            }
        };
        let num_dnum = |nop: BinOp, dop: BinOp, res_bool: bool| -> Option<(Expr, Ty)> {
            if both_num {
                Some((
                    bin(nop, l.clone(), r.clone()),
                    if res_bool { Ty::BOOL } else { Ty::NUM },
                ))
            } else if mixed_numeric || (lt == Ty::DNUM && rt == Ty::DNUM) {
                Some((
                    bin(dop, to_d(l.clone(), lt), to_d(r.clone(), rt)),
                    if res_bool { Ty::BOOL } else { Ty::DNUM },
                ))
            } else {
                None
            }
        };
        // `x MOD 100`: a constant integer divisor is checked once, here.
        if both_num
            && matches!(op, AB::Mod | AB::IntDiv)
            && let ExprKind::Num(k) = r.kind
            && k != 0.0
            && (k as i32) as f32 == k
            && k.abs() < 16_777_216.0
        {
            return Some((
                Expr {
                    kind: ExprKind::NumModDivK(Box::new(l), k as i32, op == AB::Mod),
                    span,
                },
                Ty::NUM,
            ));
        }
        let res = match op {
            AB::Add => num_dnum(BinOp::NumAdd, BinOp::DnumAdd, false).or_else(|| {
                if lt == Ty::STRING && rt == Ty::STRING {
                    Some((bin(BinOp::Concat, l.clone(), r.clone()), Ty::STRING))
                } else if self.is_pos(lt) && self.is_pos(rt) {
                    Some((bin(BinOp::PosAdd, l.clone(), r.clone()), lt))
                } else {
                    None
                }
            }),
            AB::Sub => num_dnum(BinOp::NumSub, BinOp::DnumSub, false).or_else(|| {
                (self.is_pos(lt) && self.is_pos(rt))
                    .then(|| (bin(BinOp::PosSub, l.clone(), r.clone()), lt))
            }),
            AB::Mul => num_dnum(BinOp::NumMul, BinOp::DnumMul, false).or_else(|| {
                if numeric(lt) && self.is_pos(rt) {
                    Some((bin(BinOp::NumPos, l.clone(), r.clone()), rt))
                } else if self.is_pos(lt) && numeric(rt) {
                    Some((bin(BinOp::PosNum, l.clone(), r.clone()), lt))
                } else if self.is_pos(lt) && self.is_pos(rt) {
                    Some((bin(BinOp::PosCross, l.clone(), r.clone()), lt))
                } else if self.is_orient(lt) && self.is_orient(rt) {
                    Some((bin(BinOp::OrientMul, l.clone(), r.clone()), lt))
                } else {
                    None
                }
            }),
            AB::Div => num_dnum(BinOp::NumDiv, BinOp::DnumDiv, false),
            AB::IntDiv => num_dnum(BinOp::NumIntDiv, BinOp::DnumIntDiv, false),
            AB::Mod => num_dnum(BinOp::NumMod, BinOp::DnumMod, false),
            AB::Lt => num_dnum(BinOp::NumLt, BinOp::DnumLt, true),
            AB::Le => num_dnum(BinOp::NumLe, BinOp::DnumLe, true),
            AB::Gt => num_dnum(BinOp::NumGt, BinOp::DnumGt, true),
            AB::Ge => num_dnum(BinOp::NumGe, BinOp::DnumGe, true),
            AB::Eq | AB::Ne => {
                let is_eq = op == AB::Eq;
                if both_num {
                    let o = if is_eq { BinOp::NumEq } else { BinOp::NumNe };
                    Some((bin(o, l.clone(), r.clone()), Ty::BOOL))
                } else if (mixed_numeric && lt.rank == 0 && rt.rank == 0) || lt == rt {
                    // Arrays of a value type compare element by element (a real controller
                    // backup does `IF names = ["a", "b", "c"] THEN`); their sizes must match
                    // for `=` to be TRUE.
                    if !self.types.is_value(lt.base) {
                        self.err(
                            K::NonValue {
                                ty: self.ty_name(lt),
                                what: "compared",
                            },
                            span,
                        );
                        return None;
                    }
                    let o = if is_eq { BinOp::Eq } else { BinOp::Ne };
                    Some((bin(o, l.clone(), r.clone()), Ty::BOOL))
                } else {
                    None
                }
            }
            AB::And | AB::Or | AB::Xor => (lt == Ty::BOOL && rt == Ty::BOOL).then(|| {
                let o = match op {
                    AB::And => BinOp::And,
                    AB::Or => BinOp::Or,
                    _ => BinOp::Xor,
                };
                (bin(o, l.clone(), r.clone()), Ty::BOOL)
            }),
        };
        if res.is_none() {
            self.err(
                K::BadOperands {
                    op: op.as_str().into(),
                    lhs: self.ty_name(lt),
                    rhs: Some(self.ty_name(rt)),
                },
                span,
            );
        }
        res
    }

    /// An aggregate typed by its context.
    pub(super) fn aggregate(
        &mut self,
        items: &[ast::Expr],
        ty: Ty,
        dims: Option<&[u32]>,
        span: Span,
    ) -> Option<(Expr, Ty)> {
        if ty.rank > 0 {
            let mut flat = Vec::new();
            let mut sizes = vec![0u32; ty.rank as usize];
            self.array_items(items, ty, 0, dims, &mut sizes, &mut flat, span)?;
            return Some((
                Expr {
                    kind: ExprKind::Array(flat.into_boxed_slice(), sizes.into_boxed_slice()),
                    span,
                },
                ty,
            ));
        }
        if !self.types.is_value(ty.base) {
            self.err(
                K::NonValue {
                    ty: self.ty_name(ty),
                    what: "written as an aggregate",
                },
                span,
            );
            return None;
        }
        let Some(fields) = self.types.fields(ty.base).map(|f| f.to_vec()) else {
            self.err(
                K::TypeMismatch {
                    context: "this value".into(),
                    expected: self.ty_name(ty),
                    found: "aggregate".into(),
                },
                span,
            );
            return None;
        };
        if fields.len() != items.len() {
            self.err(
                K::AggregateSize {
                    ty: self.ty_name(ty),
                    expected: fields.len(),
                    found: items.len(),
                },
                span,
            );
            return None;
        }
        let mut out = Vec::with_capacity(items.len());
        let mut ok = true;
        for (f, item) in fields.iter().zip(items) {
            let ctx = format!("component `{}`", f.name);
            let r = if f.dims.is_empty() {
                self.rvalue_as(item, f.ty, &ctx)
            } else {
                self.rvalue(item, Some(f.ty), Some(&f.dims))
                    .and_then(|(x, xt)| self.coerce(x, xt, f.ty, &ctx, item.span))
            };
            match r {
                Some(x) => out.push(x),
                None => ok = false,
            }
        }
        ok.then(|| {
            (
                Expr {
                    kind: ExprKind::Record(out.into_boxed_slice()),
                    span,
                },
                ty,
            )
        })
    }

    #[allow(clippy::too_many_arguments)]
    fn array_items(
        &mut self,
        items: &[ast::Expr],
        ty: Ty,
        depth: usize,
        dims: Option<&[u32]>,
        sizes: &mut [u32],
        flat: &mut Vec<Expr>,
        span: Span,
    ) -> Option<()> {
        let n = items.len() as u32;
        let want = dims.and_then(|d| d.get(depth).copied());
        let size_ok = match want {
            Some(w) => w == n,
            None => sizes[depth] == 0 || sizes[depth] == n,
        };
        if !size_ok || n == 0 {
            self.err(
                K::AggregateSize {
                    ty: self.ty_name(ty),
                    expected: want.unwrap_or(sizes[depth]) as usize,
                    found: items.len(),
                },
                span,
            );
            return None;
        }
        sizes[depth] = n;
        let last = depth + 1 == ty.rank as usize;
        let mut ok = true;
        for item in items {
            if last {
                match self.rvalue_as(item, ty.elem(), "an array element") {
                    Some(x) => flat.push(x),
                    None => ok = false,
                }
            } else {
                let inner = match item.aggregate_items(self.text_of(item.span)) {
                    Some(inner) => inner,
                    None => {
                        self.err(
                            K::TypeMismatch {
                                context: "a row of a multi-dimensional array".into(),
                                expected: "aggregate".into(),
                                found: "a single value".into(),
                            },
                            item.span,
                        );
                        ok = false;
                        continue;
                    }
                };
                if self
                    .array_items(&inner, ty, depth + 1, dims, sizes, flat, item.span)
                    .is_none()
                {
                    ok = false;
                }
            }
        }
        ok.then_some(())
    }

    /// `Name(args)` in an expression.
    fn func_call(
        &mut self,
        name: &ast::Ident,
        args: &[ast::Arg],
        span: Span,
    ) -> Option<(Expr, Ty)> {
        if args
            .iter()
            .any(|a| matches!(a.kind, ast::ArgKind::Placeholder(_)))
        {
            return Some((
                Expr {
                    kind: ExprKind::Placeholder("<ARG>"),
                    span,
                },
                Ty::NUM,
            ));
        }
        let key = name.folded();
        if let Some(rid) = self.lookup_routine(&key) {
            let ret = match self.routines[rid.0 as usize].kind {
                RoutineKind::Func(t) => t,
                RoutineKind::Proc => {
                    self.err(
                        K::WrongRoutineKind {
                            name: name.node.to_string(),
                            is: "a procedure",
                            needed: "a function",
                        },
                        name.span,
                    );
                    return None;
                }
                RoutineKind::Trap => {
                    self.err(
                        K::WrongRoutineKind {
                            name: name.node.to_string(),
                            is: "a trap",
                            needed: "a function",
                        },
                        name.span,
                    );
                    return None;
                }
            };
            let a = self.lower_args(super::call::Callee::User(rid), args, name, span)?;
            return Some((
                Expr {
                    kind: ExprKind::Call(rid, a.into_boxed_slice()),
                    span,
                },
                ret,
            ));
        }
        if key == "PRESENT" {
            return self.present(args, span);
        }
        if let Some(&nid) = self.native_syms.get(&key) {
            let Some(ret) = self.native_ret(nid) else {
                self.err(
                    K::WrongRoutineKind {
                        name: name.node.to_string(),
                        is: "an instruction",
                        needed: "a function",
                    },
                    name.span,
                );
                return None;
            };
            let a = self.lower_args(super::call::Callee::Native(nid), args, name, span)?;
            return Some((
                Expr {
                    kind: ExprKind::Native(nid, a.into_boxed_slice()),
                    span,
                },
                ret,
            ));
        }
        self.err(
            K::Unsupported {
                name: name.node.to_string(),
                what: "function",
            },
            name.span,
        );
        None
    }

    /// `Present(param)`.
    fn present(&mut self, args: &[ast::Arg], span: Span) -> Option<(Expr, Ty)> {
        let [arg] = args else {
            self.err(
                K::MissingArg {
                    callee: "Present".into(),
                    param: "OptPar".into(),
                },
                span,
            );
            return None;
        };
        let ast::ArgKind::Positional(ast::Expr {
            kind: AK::Name(id), ..
        }) = &arg.kind
        else {
            self.err(
                K::NotOptional {
                    name: "this argument".into(),
                },
                arg.span,
            );
            return None;
        };
        let slot = self.optional_param_slot(id)?;
        Some((
            Expr {
                kind: ExprKind::Present(slot),
                span,
            },
            Ty::BOOL,
        ))
    }
}

/// A literal number, possibly signed or parenthesised.
fn is_literal(e: &ast::Expr) -> bool {
    match &e.kind {
        AK::Num(_) => true,
        AK::Paren(x) => is_literal(x),
        AK::Unary {
            op: UnaryOp::Neg | UnaryOp::Plus,
            expr,
        } => is_literal(expr),
        _ => false,
    }
}
