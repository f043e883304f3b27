//! Calls of user routines from compiled code: `num` arguments evaluated inline, the others
//! (values of other types, references, absent and conditional arguments) as lowered.

use super::num::{Opnd, Src, opnd};
use super::place::CPlace;
use super::val::{ValFn, value};
use super::{Code, Cx};
use crate::interp::Interp;
use crate::interp::NArg;
use crate::interp::error::Exec;
use crate::interp::value::Value;
use crate::ir::{Arg, NativeId, ParamSlot, RoutineId, Ty};
use crate::source::Span;

/// A compiled call of a user routine.
pub(crate) struct CCall {
    rid: RoutineId,
    args: Box<[CArg]>,
    span: Span,
    /// What a call adds to the task's data, when no argument decides it (no array value
    /// parameter).
    values: Option<u64>,
    /// Every argument is a `num` for a value parameter ([`CArg::Num`]): they are pushed
    /// without looking at the parameters.
    all_num: bool,
}

/// A compiled argument, for the callee's parameter at the same index.
enum CArg {
    /// A `num` value for an IN parameter, and the expression's span.
    Num(Opnd, Span),
    /// A value of another type for an IN parameter.
    Val(ValFn),
    /// Data of another type for an IN parameter, copied into the slot (reusing what the
    /// slot holds from the last call).
    Copy(Copied),
    /// Anything else, as lowered.
    Ir(Arg),
}

impl CCall {
    pub(crate) fn new(cx: &Cx, rid: RoutineId, args: &[Arg], span: Span) -> CCall {
        let r = cx.p.routine(rid);
        let cargs: Box<[CArg]> = r
            .params
            .iter()
            .zip(args.iter())
            .map(|(param, arg)| match (param.slot, arg) {
                (ParamSlot::Value(_), Arg::Value(e)) if param.ty == Ty::NUM => {
                    CArg::Num(opnd(cx, e), e.span)
                }
                (ParamSlot::Value(_), Arg::Value(e)) => match Copied::of(cx, e) {
                    Some(src) => CArg::Copy(src),
                    None => CArg::Val(value(cx, e)),
                },
                _ => CArg::Ir(arg.clone()),
            })
            .collect();
        let fd = super::FrameData::of(cx.p, r);
        let all_num = r.params.len() == cargs.len()
            && r.params
                .iter()
                .all(|q| matches!(q.slot, ParamSlot::Value(_)))
            && cargs.iter().all(|a| matches!(a, CArg::Num(..)));
        CCall {
            rid,
            args: cargs,
            span,
            values: fd.arrays.is_empty().then_some(fd.fixed),
            all_num,
        }
    }
}

impl Interp {
    /// Call a user routine from compiled code; returns the FUNC result (or `Absent`).
    pub(crate) fn ccall(&mut self, c: &Code, call: &CCall) -> Exec<Value> {
        let p = &*c.prog;
        self.check_depth(call.span)?;
        let r = p.routine(call.rid);
        let bp = self.sp;
        let rbp = self.refs.len();
        if call.all_num
            && let Some(nr) = Self::slab_routine(c, call.rid)
        {
            return self.slab_call(c, nr, call);
        }
        if call.all_num {
            for arg in call.args.iter() {
                if let CArg::Num(o, span) = arg {
                    let x = o.get(self, c);
                    if x.is_nan() {
                        self.sp = bp;
                        return Err(self.take_pending(*span));
                    }
                    self.push_num(x);
                }
            }
            let cr = c.routines.get(call.rid.0 as usize);
            let values = match call.values {
                Some(v) => v,
                None => self.frame_values(c, call.rid, bp),
            };
            return self.enter_with(c, (call.rid, r, cr), values, bp, rbp, call.span);
        }
        for (param, arg) in r.params.iter().zip(call.args.iter()) {
            let res = match (param.slot, arg) {
                (_, CArg::Num(o, span)) => {
                    let x = o.get(self, c);
                    if x.is_nan() {
                        Err(self.take_pending(*span))
                    } else {
                        self.push_num(x);
                        Ok(())
                    }
                }
                (_, CArg::Val(f)) => f(self, c).map(|v| self.push_value(v)),
                (_, CArg::Copy(src)) => self.push_copy(c, src),
                (ParamSlot::Value(_), CArg::Ir(a)) => {
                    self.arg_value(p, a).map(|v| self.push_value(v))
                }
                (ParamSlot::Ref(_), CArg::Ir(a)) => self.arg_ref(p, a).map(|a| self.refs.push(a)),
            };
            if let Err(u) = res {
                self.sp = bp;
                self.refs.truncate(rbp);
                return Err(u);
            }
        }
        let cr = c.routines.get(call.rid.0 as usize);
        let values = match call.values {
            Some(v) => v,
            None => self.frame_values(c, call.rid, bp),
        };
        self.enter_with(c, (call.rid, r, cr), values, bp, rbp, call.span)
    }
}

/// Data read where it is (a local, a global, a place) to be copied.
pub(crate) enum Copied {
    Local(u32, Span),
    Global(u32),
    Place(CPlace),
}

impl Copied {
    /// `e` as data to copy, if it is a local, a global or a place.
    pub(crate) fn of(cx: &Cx, e: &crate::ir::Expr) -> Option<Copied> {
        Some(match &e.kind {
            crate::ir::ExprKind::Local(s) => Copied::Local(*s, e.span),
            crate::ir::ExprKind::Global(g) => Copied::Global(*g),
            crate::ir::ExprKind::Load(pl) => Copied::Place(CPlace::new(cx, pl)),
            _ => return None,
        })
    }

    /// Make `dst` equal to the data (reusing its allocations); `check` may refuse first.
    #[inline]
    pub(crate) fn copy_into(
        &self,
        it: &mut Interp,
        c: &Code,
        dst: &mut Value,
        check: impl FnOnce(&Value, &Value) -> bool,
    ) -> Exec<bool> {
        match self {
            Copied::Local(s, span) => {
                let Interp {
                    stack,
                    spare_records,
                    bp,
                    ..
                } = it;
                match stack.get(*bp + *s as usize) {
                    Some(Value::Absent) | None => Err(it.error(
                        crate::interp::errnum::ERR_NOTPRES,
                        *span,
                        "the optional parameter was not passed",
                    )),
                    Some(v) => Ok(check(dst, v) && {
                        dst.reset_pooled(v, spare_records);
                        true
                    }),
                }
            }
            Copied::Global(g) => {
                let Interp {
                    globals,
                    spare_records,
                    ..
                } = it;
                let v = globals.get(*g as usize).unwrap_or(&Value::Absent);
                Ok(check(dst, v) && {
                    dst.reset_pooled(v, spare_records);
                    true
                })
            }
            Copied::Place(p) => {
                // The pool is lent out while the place is borrowed (an index evaluated
                // meanwhile finds it empty).
                let mut pool = std::mem::take(&mut it.spare_records);
                let r = p.read(it, c, |v| {
                    check(dst, v) && {
                        dst.reset_pooled(v, &mut pool);
                        true
                    }
                });
                it.spare_records = pool;
                r
            }
        }
    }
}

impl Interp {
    /// [`Interp::ccall`] of a routine run on the `num` frame slab.
    #[inline(never)]
    fn slab_call(
        &mut self,
        c: &Code,
        nr: &super::numroutine::NRoutine,
        call: &CCall,
    ) -> Exec<Value> {
        let mut argv = [0f32; super::numroutine::MAX_ARGS];
        for (arg, slot) in call.args.iter().zip(argv.iter_mut()) {
            if let CArg::Num(o, span) = arg {
                let x = o.get(self, c);
                if x.is_nan() {
                    return Err(self.take_pending(*span));
                }
                *slot = x;
            }
        }
        let n = call.args.len().min(argv.len());
        let x = self.slab_enter(c, nr, &argv[..n], call.span)?;
        Ok(nr.result(x))
    }

    /// Push a copy of `src` (into the slot above the top, reusing what it holds).
    fn push_copy(&mut self, c: &Code, src: &Copied) -> Exec<()> {
        let mut dst = match self.stack.get_mut(self.sp) {
            Some(slot) => std::mem::replace(slot, Value::Absent),
            None => Value::Absent,
        };
        src.copy_into(self, c, &mut dst, |_, _| true)?;
        self.push_value(dst);
        Ok(())
    }
}

/// A compiled call of a native: value arguments evaluated by their compiled form.
pub(crate) struct CNative {
    nid: NativeId,
    args: Box<[NArgC]>,
    /// The arguments as lowered (what the native sees of its call).
    ir_args: Box<[Arg]>,
    span: Span,
}

/// A compiled argument of a native.
enum NArgC {
    /// A value (IN) argument.
    Val(ValFn),
    /// Anything else (absent, switch, reference, conditional), as lowered.
    Ir(Arg),
}

impl CNative {
    pub(crate) fn new(cx: &Cx, nid: NativeId, args: &[Arg], span: Span) -> CNative {
        CNative {
            nid,
            args: args
                .iter()
                .map(|a| match a {
                    Arg::Value(e) => NArgC::Val(value(cx, e)),
                    other => NArgC::Ir(other.clone()),
                })
                .collect(),
            ir_args: args.into(),
            span,
        }
    }
}

impl Interp {
    /// Call a native from compiled code.
    pub(crate) fn cnative(&mut self, c: &Code, n: &CNative) -> Exec<Value> {
        let p = &*c.prog;
        let base = self.nargs.len();
        for arg in n.args.iter() {
            let a = match arg {
                NArgC::Val(f) => f(self, c).map(NArg::Val),
                NArgC::Ir(a) => self.native_arg(p, a),
            };
            match a {
                Ok(a) => self.nargs.push(a),
                Err(u) => {
                    self.nargs.truncate(base);
                    return Err(u);
                }
            }
        }
        self.invoke_native(p, n.nid, base, &n.ir_args, n.span)
    }
}
