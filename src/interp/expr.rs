//! Expression evaluation, with unboxed fast paths for `num` and `bool` so that arithmetic on
//! locals never allocates.

use super::Interp;
use super::errnum;
use super::error::{ErrorKind, Exec};
use super::value::{Array, MAX_STRING, RStr, Value, values_equal};
use crate::ir::{BinOp, Expr, ExprKind, ParamSlot, Program, UnOp};
use crate::source::Span;

impl Interp {
    /// Evaluate an expression to a value.
    pub(crate) fn eval(&mut self, p: &Program, e: &Expr) -> Exec<Value> {
        match &e.kind {
            ExprKind::Num(x) => Ok(Value::Num(*x)),
            ExprKind::Dnum(x) => Ok(Value::Dnum(*x)),
            ExprKind::Bool(b) => Ok(Value::Bool(*b)),
            ExprKind::Str(s) => Ok(Value::str(s)),
            ExprKind::Local(s) => {
                let (bp, _) = self.bases();
                match self.stack.get(bp + *s as usize) {
                    Some(Value::Absent) | None => Err(self.error(
                        errnum::ERR_NOTPRES,
                        e.span,
                        "the optional parameter was not passed",
                    )),
                    Some(v) => Ok(v.clone()),
                }
            }
            ExprKind::Global(g) => Ok(self
                .globals
                .get(*g as usize)
                .cloned()
                .unwrap_or(Value::Absent)),
            ExprKind::Load(pl) => self.load(p, pl),
            ExprKind::Field(base, i) => match self.eval(p, base)? {
                Value::Record(mut fs) if (*i as usize) < fs.len() => {
                    Ok(std::mem::replace(&mut fs[*i as usize], Value::Absent))
                }
                other => Err(self.type_bug(e.span, "record", &other)),
            },
            ExprKind::SignalValue(sig) => {
                let v = self.eval(p, sig)?;
                let name = match v.fields() {
                    Some([Value::Str(s)]) if !s.is_empty() => s.clone(),
                    _ => {
                        return Err(self.error(
                            errnum::ERR_NO_ALIASIO_DEF,
                            e.span,
                            "the signal variable is not connected to a configured signal",
                        ));
                    }
                };
                let x = self
                    .host
                    .read_signal(&name)
                    .map_err(|h| self.host_error(h, e.span))?;
                Ok(Value::Num(x as f32))
            }
            ExprKind::Errno => Ok(Value::Num(self.errno as f32)),
            ExprKind::Intno => Ok(Value::Num(self.intno as f32)),
            ExprKind::Present(slot) => Ok(Value::Bool(self.param_present(*slot))),
            ExprKind::Unary(op, a) => match op {
                UnOp::NumNeg => Ok(Value::Num(-self.eval_num(p, a)?)),
                UnOp::DnumNeg => Ok(Value::Dnum(-self.eval_f64(p, a)?)),
                UnOp::Not => Ok(Value::Bool(!self.eval_bool(p, a)?)),
                UnOp::PosNeg => {
                    let v = self.eval(p, a)?;
                    let [x, y, z] = self.pos_of(&v, a.span)?;
                    Ok(Value::num_record(&[-x, -y, -z]))
                }
            },
            ExprKind::Binary(op, a, b) => self.binary(p, *op, a, b, e.span),
            ExprKind::NumModDivK(..) => Ok(Value::Num(self.eval_num(p, e)?)),
            ExprKind::ToDnum(a) => Ok(Value::Dnum(self.eval_f64(p, a)?)),
            ExprKind::ToNum(a) => {
                let x = self.eval_f64(p, a)?;
                Ok(Value::Num(self.to_f32(x, e.span)?))
            }
            ExprKind::Call(r, args) => self.call_routine(p, *r, args, e.span),
            ExprKind::Native(n, args) => self.call_native(p, *n, args, e.span),
            ExprKind::Record(es) => {
                let mut out = Vec::with_capacity(es.len());
                for x in es.iter() {
                    out.push(self.eval(p, x)?);
                }
                Ok(Value::Record(out.into_boxed_slice()))
            }
            ExprKind::Array(es, sizes) => {
                let mut data = Vec::with_capacity(es.len());
                for x in es.iter() {
                    data.push(self.eval(p, x)?);
                }
                let mut dims = [1u32; 3];
                for (k, &n) in sizes.iter().take(3).enumerate() {
                    dims[k] = n;
                }
                Ok(Value::Array(Box::new(Array {
                    dims,
                    rank: sizes.len().min(3) as u8,
                    data,
                })))
            }
            ExprKind::Placeholder(ph) => Err(self.fatal(
                ErrorKind::Placeholder,
                e.span,
                format!("the placeholder {ph} cannot be evaluated"),
            )),
        }
    }

    /// Evaluate a `num` expression.
    #[inline]
    pub(crate) fn eval_num(&mut self, p: &Program, e: &Expr) -> Exec<f32> {
        let x = self.nf(p, e);
        if x.is_nan() {
            Err(self.take_pending(e.span))
        } else {
            Ok(x)
        }
    }

    /// The error behind a NaN from [`Interp::nf`].
    #[cold]
    pub(crate) fn take_pending(&mut self, span: Span) -> super::Unwind {
        match self.pending.take() {
            Some(u) => u,
            None => self.fatal(
                ErrorKind::Host,
                span,
                "internal error: a num computation failed without an error",
            ),
        }
    }

    /// Record an error for the NaN-signalling num path and return NaN.
    #[cold]
    pub(crate) fn fail_nf(&mut self, u: super::Unwind) -> f32 {
        self.pending = Some(u);
        f32::NAN
    }

    /// Evaluate a `num` expression without a `Result`: a `num` value is never NaN (every
    /// operation checks its result), so NaN signals an error, kept in `self.pending`.
    pub(crate) fn nf(&mut self, p: &Program, e: &Expr) -> f32 {
        match &e.kind {
            ExprKind::Num(x) => *x,
            ExprKind::Binary(op, a, b) if op.is_num_arith() => self.nf_binary(p, *op, a, b, e.span),
            ExprKind::NumModDivK(a, k, is_mod) => {
                let x = self.nf(p, a);
                self.mod_div_k(x, *k, *is_mod, e.span)
            }
            ExprKind::Unary(UnOp::NumNeg, a) => -self.nf(p, a),
            _ => self.nf_slow(p, e),
        }
    }

    #[inline(never)]
    pub(crate) fn nf_slow(&mut self, p: &Program, e: &Expr) -> f32 {
        let r = self.eval(p, e);
        self.nf_of(r, e.span)
    }

    /// The NaN-signalling `num` of an evaluation result (a `dnum` is converted).
    #[inline]
    pub(crate) fn nf_of(&mut self, r: Exec<Value>, span: Span) -> f32 {
        if let Ok(Value::Num(x)) = r {
            // Nothing to drop in a num (skips the value's drop code on the hot path).
            std::mem::forget(r);
            return x;
        }
        self.nf_of_other(r, span)
    }

    #[inline(never)]
    fn nf_of_other(&mut self, r: Exec<Value>, span: Span) -> f32 {
        match r {
            Ok(Value::Num(x)) => x,
            Ok(Value::Dnum(x)) => match self.to_f32(x, span) {
                Ok(x) => x,
                Err(u) => self.fail_nf(u),
            },
            Ok(other) => {
                let u = self.type_bug(span, "num", &other);
                self.fail_nf(u)
            }
            Err(u) => self.fail_nf(u),
        }
    }

    /// `x MOD k` / `x DIV k` for an evaluated `x` (NaN passes through) and a constant
    /// integer `k` ≠ 0.
    #[inline(always)]
    pub(crate) fn mod_div_k(&mut self, x: f32, k: i32, is_mod: bool, span: Span) -> f32 {
        if let Some(xi) = super::value::f32_int(x)
            && xi != i32::MIN
        {
            return if is_mod { xi % k } else { xi / k } as f32;
        }
        self.mod_div_k_slow(x, k, is_mod, span)
    }

    /// `x MOD k` / `x DIV k` with a precomputed divisor (compiled code).
    #[inline(always)]
    pub(crate) fn mod_div_c(
        &mut self,
        x: f32,
        d: &super::compile::DivK,
        is_mod: bool,
        span: Span,
    ) -> f32 {
        // `f32_int` never yields `i32::MIN`.
        match super::value::f32_int(x) {
            Some(xi) => d.apply(xi, is_mod) as f32,
            None => self.mod_div_k_slow(x, d.k(), is_mod, span),
        }
    }

    #[cold]
    #[inline(never)]
    fn mod_div_k_slow(&mut self, x: f32, k: i32, is_mod: bool, span: Span) -> f32 {
        if x.is_nan() {
            return x;
        }
        match self.int_div_mod(is_mod, x as f64, k as f64, span) {
            Ok(r) => r as f32,
            Err(u) => self.fail_nf(u),
        }
    }

    fn nf_binary(&mut self, p: &Program, op: BinOp, a: &Expr, b: &Expr, span: Span) -> f32 {
        let x = self.nf(p, a);
        if x.is_nan() {
            return x;
        }
        let y = self.nf(p, b);
        if y.is_nan() {
            return y;
        }
        self.num_op(op, x, y, span)
    }

    /// A `num` arithmetic operator on evaluated operands (neither NaN), with its checks:
    /// division by zero, integer operands of DIV/MOD, results outside the range of num.
    #[inline(always)]
    pub(crate) fn num_op(&mut self, op: BinOp, x: f32, y: f32, span: Span) -> f32 {
        let r = match op {
            BinOp::NumAdd => x + y,
            BinOp::NumSub => x - y,
            BinOp::NumMul => x * y,
            BinOp::NumDiv => {
                if y == 0.0 {
                    return self.div_zero(span);
                }
                x / y
            }
            _ => return self.int_op(op == BinOp::NumMod, x, y, span),
        };
        self.num_result(r, span)
    }

    /// DIV (`is_mod` false) or MOD of evaluated operands (neither NaN).
    #[inline(always)]
    pub(crate) fn int_op(&mut self, is_mod: bool, x: f32, y: f32, span: Span) -> f32 {
        // Fast path: integer operands that fit i32 (every exact num integer does).
        if let (Some(xi), Some(yi)) = (super::value::f32_int(x), super::value::f32_int(y))
            && yi != 0
            && xi != i32::MIN
        {
            return if is_mod { xi % yi } else { xi / yi } as f32;
        }
        self.int_op_slow(is_mod, x, y, span)
    }

    #[cold]
    #[inline(never)]
    fn int_op_slow(&mut self, is_mod: bool, x: f32, y: f32, span: Span) -> f32 {
        let r = match self.int_div_mod(is_mod, x as f64, y as f64, span) {
            Ok(r) => r as f32,
            Err(u) => return self.fail_nf(u),
        };
        self.num_result(r, span)
    }

    /// A computed `num`, or `ERR_NUM_LIMIT` when it is not finite.
    #[inline(always)]
    pub(crate) fn num_result(&mut self, r: f32, span: Span) -> f32 {
        if r.is_finite() {
            r
        } else {
            self.num_limit(span)
        }
    }

    #[cold]
    #[inline(never)]
    fn num_limit(&mut self, span: Span) -> f32 {
        let u = self.error(
            errnum::ERR_NUM_LIMIT,
            span,
            "the result is outside the range of num",
        );
        self.fail_nf(u)
    }

    #[cold]
    #[inline(never)]
    pub(crate) fn div_zero(&mut self, span: Span) -> f32 {
        let u = self.error(errnum::ERR_DIVZERO, span, "division by zero");
        self.fail_nf(u)
    }

    /// Evaluate a `num` or `dnum` expression as f64.
    pub(crate) fn eval_f64(&mut self, p: &Program, e: &Expr) -> Exec<f64> {
        match &e.kind {
            ExprKind::Num(x) => return Ok(*x as f64),
            ExprKind::Dnum(x) => return Ok(*x),
            ExprKind::Local(s) => {
                let (bp, _) = self.bases();
                match self.stack.get(bp + *s as usize) {
                    Some(Value::Num(x)) => return Ok(*x as f64),
                    Some(Value::Dnum(x)) => return Ok(*x),
                    _ => {}
                }
            }
            ExprKind::Binary(op, a, b) if op.is_num_arith() => {
                return Ok(self.num_arith(p, *op, a, b, e.span)? as f64);
            }
            _ => {}
        }
        match self.eval(p, e)? {
            Value::Num(x) => Ok(x as f64),
            Value::Dnum(x) => Ok(x),
            other => Err(self.type_bug(e.span, "num", &other)),
        }
    }

    /// Evaluate a `bool` expression.
    #[inline]
    pub(crate) fn eval_bool(&mut self, p: &Program, e: &Expr) -> Exec<bool> {
        match &e.kind {
            ExprKind::Bool(b) => return Ok(*b),
            ExprKind::Binary(op, a, b) => {
                if let Some(r) = self.bool_binary_fast(p, *op, a, b, e.span) {
                    return r;
                }
            }
            ExprKind::Unary(UnOp::Not, a) => return Ok(!self.eval_bool(p, a)?),
            ExprKind::Local(s) => {
                let (bp, _) = self.bases();
                if let Some(Value::Bool(b)) = self.stack.get(bp + *s as usize) {
                    return Ok(*b);
                }
            }
            _ => {}
        }
        match self.eval(p, e)? {
            Value::Bool(b) => Ok(b),
            other => Err(self.type_bug(e.span, "bool", &other)),
        }
    }

    /// Evaluate a `string` expression.
    pub(crate) fn eval_str(&mut self, p: &Program, e: &Expr) -> Exec<RStr> {
        match self.eval(p, e)? {
            Value::Str(s) => Ok(s),
            other => Err(self.type_bug(e.span, "string", &other)),
        }
    }

    fn bool_binary_fast(
        &mut self,
        p: &Program,
        op: BinOp,
        a: &Expr,
        b: &Expr,
        span: Span,
    ) -> Option<Exec<bool>> {
        Some(match op {
            BinOp::NumLt
            | BinOp::NumLe
            | BinOp::NumGt
            | BinOp::NumGe
            | BinOp::NumEq
            | BinOp::NumNe => self.num_cmp(p, op, a, b),
            BinOp::And | BinOp::Or | BinOp::Xor => {
                // Both operands are always evaluated (no short circuit).
                let x = match self.eval_bool(p, a) {
                    Ok(x) => x,
                    Err(u) => return Some(Err(u)),
                };
                let y = match self.eval_bool(p, b) {
                    Ok(y) => y,
                    Err(u) => return Some(Err(u)),
                };
                Ok(match op {
                    BinOp::And => x && y,
                    BinOp::Or => x || y,
                    _ => x != y,
                })
            }
            _ => {
                let _ = span;
                return None;
            }
        })
    }

    fn num_cmp(&mut self, p: &Program, op: BinOp, a: &Expr, b: &Expr) -> Exec<bool> {
        let x = self.nf(p, a);
        if x.is_nan() {
            return Err(self.take_pending(a.span));
        }
        let y = self.nf(p, b);
        if y.is_nan() {
            return Err(self.take_pending(b.span));
        }
        Ok(cmp_num(op, x, y))
    }

    /// A `num` leaf (constant, local, global) without a call, if `e` is one.
    #[inline(always)]
    pub(crate) fn num_leaf(&self, e: &Expr) -> Option<f32> {
        match &e.kind {
            ExprKind::Num(x) => Some(*x),
            ExprKind::Local(s) => match self.stack.get(self.bp + *s as usize) {
                Some(Value::Num(x)) => Some(*x),
                _ => None,
            },
            ExprKind::Global(g) => match self.globals.get(*g as usize) {
                Some(Value::Num(x)) => Some(*x),
                _ => None,
            },
            _ => None,
        }
    }

    #[inline]
    fn num_arith(&mut self, p: &Program, op: BinOp, a: &Expr, b: &Expr, span: Span) -> Exec<f32> {
        let r = self.nf_binary(p, op, a, b, span);
        if r.is_nan() {
            Err(self.take_pending(span))
        } else {
            Ok(r)
        }
    }

    /// DIV/MOD with the runtime library's rules (integer operands, truncation, the sign
    /// of MOD follows the dividend).
    fn int_div_mod(&self, is_mod: bool, x: f64, y: f64, span: Span) -> Exec<f64> {
        let r = if is_mod {
            crate::functions::math::dnum_mod(x, y)
        } else {
            crate::functions::math::dnum_int_div(x, y)
        };
        r.map_err(|e| self.rt_error(e, span))
    }

    fn binary(&mut self, p: &Program, op: BinOp, a: &Expr, b: &Expr, span: Span) -> Exec<Value> {
        use BinOp::*;
        match op {
            NumAdd | NumSub | NumMul | NumDiv | NumIntDiv | NumMod => {
                Ok(Value::Num(self.num_arith(p, op, a, b, span)?))
            }
            NumLt | NumLe | NumGt | NumGe | NumEq | NumNe | And | Or | Xor => {
                match self.bool_binary_fast(p, op, a, b, span) {
                    Some(r) => Ok(Value::Bool(r?)),
                    None => Err(self.type_bug(span, "bool operator", &Value::Absent)),
                }
            }
            DnumAdd | DnumSub | DnumMul | DnumDiv | DnumIntDiv | DnumMod => {
                let x = self.eval_f64(p, a)?;
                let y = self.eval_f64(p, b)?;
                let r = match op {
                    DnumAdd => x + y,
                    DnumSub => x - y,
                    DnumMul => x * y,
                    DnumDiv => {
                        if y == 0.0 {
                            return Err(self.error(errnum::ERR_DIVZERO, span, "division by zero"));
                        }
                        x / y
                    }
                    _ => self.int_div_mod(op == DnumMod, x, y, span)?,
                };
                if !r.is_finite() {
                    return Err(self.error(
                        errnum::ERR_NUM_LIMIT,
                        span,
                        "the result is outside the range of dnum",
                    ));
                }
                Ok(Value::Dnum(r))
            }
            DnumLt | DnumLe | DnumGt | DnumGe => {
                let x = self.eval_f64(p, a)?;
                let y = self.eval_f64(p, b)?;
                Ok(Value::Bool(match op {
                    DnumLt => x < y,
                    DnumLe => x <= y,
                    DnumGt => x > y,
                    _ => x >= y,
                }))
            }
            Concat => {
                let x = self.eval_str(p, a)?;
                let y = self.eval_str(p, b)?;
                let n = x.chars().count() + y.chars().count();
                if n > MAX_STRING {
                    return Err(self.error(
                        errnum::ERR_STRTOOLNG,
                        span,
                        format!("the result would have {n} characters (at most {MAX_STRING})"),
                    ));
                }
                let mut s = String::with_capacity(x.len() + y.len());
                s.push_str(&x);
                s.push_str(&y);
                Ok(Value::Str(RStr::from(s)))
            }
            Eq | Ne => {
                let x = self.eval(p, a)?;
                let y = self.eval(p, b)?;
                let eq = values_equal(&x, &y);
                Ok(Value::Bool(if op == Eq { eq } else { !eq }))
            }
            PosAdd | PosSub | PosCross => {
                let x = self.eval(p, a)?;
                let y = self.eval(p, b)?;
                let u = self.pos_of(&x, a.span)?;
                let v = self.pos_of(&y, b.span)?;
                let r = match op {
                    PosAdd => [u[0] + v[0], u[1] + v[1], u[2] + v[2]],
                    PosSub => [u[0] - v[0], u[1] - v[1], u[2] - v[2]],
                    _ => [
                        u[1] * v[2] - u[2] * v[1],
                        u[2] * v[0] - u[0] * v[2],
                        u[0] * v[1] - u[1] * v[0],
                    ],
                };
                Ok(Value::num_record(&r))
            }
            NumPos | PosNum => {
                let (ne, pe) = if op == NumPos { (a, b) } else { (b, a) };
                let k = self.eval_f64(p, ne)?;
                let v = self.eval(p, pe)?;
                let u = self.pos_of(&v, pe.span)?;
                Ok(Value::num_record(&[k * u[0], k * u[1], k * u[2]]))
            }
            OrientMul => {
                let x = self.eval(p, a)?;
                let y = self.eval(p, b)?;
                let (Some(q), Some(r)) = (x.num_fields::<4>(), y.num_fields::<4>()) else {
                    return Err(self.type_bug(span, "orient", &x));
                };
                Ok(Value::num_record(&quat_mul(q, r)))
            }
        }
    }

    fn pos_of(&self, v: &Value, span: Span) -> Exec<[f64; 3]> {
        v.num_fields::<3>()
            .ok_or_else(|| self.type_bug(span, "pos", v))
    }

    /// dnum → num, failing outside the single-precision range.
    pub(crate) fn to_f32(&self, x: f64, span: Span) -> Exec<f32> {
        let r = x as f32;
        if x.is_finite() && !r.is_finite() {
            return Err(self.error(
                errnum::ERR_NUM_LIMIT,
                span,
                format!("{x} is outside the range of num"),
            ));
        }
        Ok(r)
    }

    /// Is an optional parameter of the current routine present?
    pub(crate) fn param_present(&self, slot: ParamSlot) -> bool {
        let (bp, rbp) = self.bases();
        match slot {
            ParamSlot::Value(s) => self
                .stack
                .get(bp + s as usize)
                .is_some_and(|v| v.is_present()),
            ParamSlot::Ref(k) => self
                .refs
                .get(rbp + k as usize)
                .is_some_and(|r| r.root != super::place::AbsRoot::Absent),
        }
    }

    /// A value of the wrong type reached an operator: sema should have prevented it.
    pub(crate) fn type_bug(&self, span: Span, expected: &str, got: &Value) -> super::Unwind {
        self.fatal(
            ErrorKind::Host,
            span,
            format!("internal error: expected a {expected} value, got {got:?}"),
        )
    }
}

/// Hamilton product of quaternions `[w, x, y, z]`.
pub(crate) fn quat_mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// A `num` comparison (`op` one of the six) of evaluated operands.
#[inline(always)]
pub(crate) fn cmp_num(op: BinOp, x: f32, y: f32) -> bool {
    match op {
        BinOp::NumLt => x < y,
        BinOp::NumLe => x <= y,
        BinOp::NumGt => x > y,
        BinOp::NumGe => x >= y,
        BinOp::NumEq => x == y,
        _ => x != y,
    }
}
