//! Calls: argument passing (values, references, switches, conditional arguments), frames,
//! routine data initialisation, returns and UNDO, natives, and late binding.

use super::builtins::Ctx;
use super::errnum;
use super::error::{ErrorKind, Exec, Unwind};
use super::place::AbsPlace;
use super::value::{Value, default_value};
use super::{Frame, Interp, NArg};
use crate::ir::{
    Arg, NativeId, ParamMode, ParamSlot, Program, Routine, RoutineId, RoutineKind, Ty,
};
use crate::source::Span;

/// The arguments of a late-bound call matched to the parameters of the procedure called:
/// per parameter, the argument as lowered and the index of the argument written (`u32::MAX`
/// for none).
pub(crate) type LateArgs = std::sync::Arc<[(Arg, u32)]>;

/// A name called at a late-bound call site, the procedure it found and the arguments
/// matched to its parameters.
pub(crate) struct LateHit {
    name: Box<str>,
    rid: RoutineId,
    args: LateArgs,
}

/// A compiled value argument of a late-bound call, and its type when it is known.
pub(crate) struct LateVal {
    pub f: super::compile::ValFn,
    pub ty: Option<crate::ir::Ty>,
}

/// Is the name remembered at a late-bound call site `name` (compared from the end, where
/// names built from a prefix and a number differ)?
#[inline]
fn same_name(known: &str, name: &str) -> bool {
    known.len() == name.len() && known.bytes().rev().eq(name.bytes().rev())
}

/// The most names a late-bound call site remembers (a site calling more looks the others
/// up on every call).
const LATE_NAMES_PER_SITE: usize = 16;

/// Deepest call nesting before execution is aborted (a runaway recursion guard).
pub(crate) const MAX_DEPTH: usize = 10_000;

/// A frame holding more values than this is dropped from the value stack when its call
/// returns, instead of staying in the slots kept for reuse.
const BIG_FRAME_VALUES: u64 = 4096;

/// An address on the current thread's stack (stacks grow down on every supported target).
#[inline(always)]
pub(crate) fn stack_addr() -> usize {
    let marker = 0u8;
    std::hint::black_box(&marker) as *const u8 as usize
}

impl Interp {
    /// Has the Rust stack used since the run started reached the budget?
    #[inline(always)]
    pub(crate) fn stack_exhausted(&self) -> bool {
        self.stack_base.saturating_sub(stack_addr()) > self.stack_budget
    }

    /// A call at `span` may nest one level deeper, unless the call depth or the Rust stack
    /// used by the run is at its limit.
    #[inline(always)]
    pub(crate) fn check_depth(&self, span: Span) -> Exec<()> {
        if self.frames.len() >= MAX_DEPTH || self.stack_exhausted() {
            return Err(self.too_deep(span));
        }
        Ok(())
    }

    #[cold]
    #[inline(never)]
    fn too_deep(&self, span: Span) -> Unwind {
        self.fatal(
            ErrorKind::Aborted,
            span,
            format!(
                "calls nested {} levels deep: the interpreter's stack is used up (runaway recursion?)",
                self.frames.len()
            ),
        )
    }

    /// Push a value onto the value stack. Slots above the top keep their last values (they
    /// are reused by the next frame instead of being dropped and pushed again).
    #[inline(always)]
    pub(crate) fn push_value(&mut self, v: Value) {
        match self.stack.get_mut(self.sp) {
            Some(slot) => {
                // What the slot held (a record of an earlier call) is kept for reuse.
                let old = std::mem::replace(slot, v);
                self.spare_records.give_value(old);
            }
            None => self.stack.push(v),
        }
        self.sp += 1;
    }

    /// Push a `num` onto the value stack (only the number is written when the slot above
    /// the top already holds one).
    #[inline(always)]
    pub(crate) fn push_num(&mut self, x: f32) {
        match self.stack.get_mut(self.sp) {
            Some(Value::Num(slot)) => *slot = x,
            _ => self.push_num_slow(x),
        }
        self.sp += 1;
    }

    #[cold]
    #[inline(never)]
    fn push_num_slow(&mut self, x: f32) {
        match self.stack.get_mut(self.sp) {
            Some(slot) => {
                let old = std::mem::replace(slot, Value::Num(x));
                self.spare_records.give_value(old);
            }
            None => self.stack.push(Value::Num(x)),
        }
    }

    #[inline(never)]
    pub(crate) fn call_num_general(
        &mut self,
        p: &Program,
        rid: RoutineId,
        args: &[Arg],
        span: Span,
    ) -> f32 {
        match self.call_routine(p, rid, args, span) {
            Ok(Value::Num(x)) => x,
            Ok(other) => {
                let u = self.type_bug(span, "num", &other);
                self.pending = Some(u);
                f32::NAN
            }
            Err(u) => {
                self.pending = Some(u);
                f32::NAN
            }
        }
    }

    /// Call a user routine with lowered arguments; returns the FUNC result (or `Absent`).
    pub(crate) fn call_routine(
        &mut self,
        p: &Program,
        rid: RoutineId,
        args: &[Arg],
        span: Span,
    ) -> Exec<Value> {
        let r = p.routine(rid);
        self.check_depth(span)?;
        let bp = self.sp;
        let rbp = self.refs.len();
        if let Err(u) = self.push_args(p, r, args) {
            self.sp = bp;
            self.refs.truncate(rbp);
            return Err(u);
        }
        let code = self.code.clone();
        self.enter(&code, rid, bp, rbp, span)
    }

    /// Values a call of `rid` adds to the task's data, with its value arguments on the stack
    /// from `bp` ([`crate::ir::limits`]).
    pub(crate) fn frame_values(&self, c: &super::compile::Code, rid: RoutineId, bp: usize) -> u64 {
        let Some(cr) = c.routines.get(rid.0 as usize) else {
            return 0;
        };
        cr.frame
            .arrays
            .iter()
            .fold(cr.frame.fixed, |n, &(slot, per_elem)| {
                match self.stack.get(bp + slot as usize) {
                    Some(Value::Array(a)) => {
                        n.saturating_add((a.data.len() as u64).saturating_mul(per_elem))
                    }
                    _ => n,
                }
            })
    }

    /// `ERR_DATA_LIMIT` at `span` for a call of `r` that would add `n` values to the task.
    pub(crate) fn data_limit_error(&self, r: &Routine, n: u64, span: Span) -> Unwind {
        use crate::ir::limits::{MAX_TASK_VALUES, thousands};
        self.error(
            errnum::ERR_DATA_LIMIT,
            span,
            format!(
                "calling `{}` needs {} values (its data and value arguments); with the module data ({}) and the {} routine calls in progress the task would hold {}, over its limit of {}",
                r.name,
                thousands(n),
                thousands(self.module_values),
                self.frames.len(),
                thousands(self.data_values.saturating_add(n)),
                thousands(MAX_TASK_VALUES)
            ),
        )
    }

    /// Run routine `rid` (compiled) on a frame whose arguments are on the stacks from `bp`
    /// and `rbp`, called at `span`; pops the frame. A call that would take the task's data
    /// over [`crate::ir::limits::MAX_TASK_VALUES`] raises `ERR_DATA_LIMIT` at the call
    /// instead (the caller's ERROR handler can take it).
    pub(crate) fn enter(
        &mut self,
        c: &super::compile::Code,
        rid: RoutineId,
        bp: usize,
        rbp: usize,
        span: Span,
    ) -> Exec<Value> {
        let r = c.prog.routine(rid);
        let values = self.frame_values(c, rid, bp);
        let cr = c.routines.get(rid.0 as usize);
        self.enter_with(c, (rid, r, cr), values, bp, rbp, span)
    }

    /// [`Interp::enter`] for routine `rid` (`r`, compiled `cr`) whose frame adds `values`
    /// to the task's data.
    #[inline(always)]
    pub(crate) fn enter_with(
        &mut self,
        c: &super::compile::Code,
        (rid, r, cr): (RoutineId, &Routine, Option<&super::compile::CRoutine>),
        values: u64,
        bp: usize,
        rbp: usize,
        span: Span,
    ) -> Exec<Value> {
        let p = &*c.prog;
        if self.data_values.saturating_add(values) > crate::ir::limits::MAX_TASK_VALUES {
            let e = self.data_limit_error(r, values, span);
            self.stack.truncate(bp);
            self.sp = bp;
            self.refs.truncate(rbp);
            return Err(e);
        }
        self.data_values += values;
        if let Some(f) = self.frames.last_mut() {
            f.at = span;
        }
        self.frames.push(Frame {
            routine: rid,
            bp: bp as u32,
            at: r.head_span,
            handling: None,
            retries: 0,
        });
        let saved = (self.bp, self.rbp);
        (self.bp, self.rbp) = (bp, rbp);
        let res = match self.init_locals(c, r, cr, bp) {
            Ok(()) => match cr {
                Some(cr) if !c.tree_walk => self.exec_cblock(c, &cr.body),
                _ => self.exec_block(p, &r.body),
            },
            Err(u) => Err(u),
        };
        let res = self.finish_call(p, r, res);
        (self.bp, self.rbp) = saved;
        self.frames.pop();
        self.sp = bp;
        if self.refs.len() > rbp {
            self.refs.truncate(rbp);
        }
        self.data_values -= values;
        if values > BIG_FRAME_VALUES {
            // Free the frame's large data now (slots above the top are otherwise kept for
            // reuse, and would keep it alive).
            self.stack.truncate(bp);
        }
        res
    }

    fn push_args(&mut self, p: &Program, r: &Routine, args: &[Arg]) -> Exec<()> {
        for (param, arg) in r.params.iter().zip(args.iter()) {
            match param.slot {
                ParamSlot::Value(_) => {
                    let v = self.arg_value(p, arg)?;
                    self.push_value(v);
                }
                ParamSlot::Ref(_) => {
                    let a = self.arg_ref(p, arg)?;
                    self.refs.push(a);
                }
            }
        }
        Ok(())
    }

    pub(crate) fn arg_value(&mut self, p: &Program, arg: &Arg) -> Exec<Value> {
        match arg {
            Arg::Absent => Ok(Value::Absent),
            Arg::Value(e) => self.eval(p, e),
            Arg::Switch => Ok(Value::Bool(true)),
            Arg::Ref(pl) => self.load(p, pl),
            Arg::Cond { param, arg } => {
                if self.param_present(*param) {
                    self.arg_value(p, arg)
                } else {
                    Ok(Value::Absent)
                }
            }
        }
    }

    pub(crate) fn arg_ref(&mut self, p: &Program, arg: &Arg) -> Exec<AbsPlace> {
        match arg {
            Arg::Absent => Ok(AbsPlace::absent()),
            Arg::Ref(pl) => self.resolve(p, pl),
            Arg::Cond { param, arg } => {
                if self.param_present(*param) {
                    self.arg_ref(p, arg)
                } else {
                    Ok(AbsPlace::absent())
                }
            }
            _ => Err(self.fatal(
                ErrorKind::Host,
                Span::default(),
                "internal error: a reference parameter got a value argument",
            )),
        }
    }

    #[inline(always)]
    fn init_locals(
        &mut self,
        c: &super::compile::Code,
        r: &Routine,
        cr: Option<&super::compile::CRoutine>,
        bp: usize,
    ) -> Exec<()> {
        // The frame's slots past its arguments. Routine data are set below (from the last
        // call's value, in place, when it is still there); a FOR variable is set before its
        // body can read it.
        let top = bp + r.n_slots as usize;
        if self.stack.len() < top {
            self.stack.resize(top, Value::Num(0.0));
        }
        self.sp = self.sp.max(top);
        if r.locals.is_empty() {
            return Ok(());
        }
        if let Some(data) = cr.and_then(|cr| cr.num_data.as_deref()) {
            for &(s, x) in data {
                match self.stack.get_mut(bp + s as usize) {
                    Some(Value::Num(slot)) => *slot = x,
                    Some(slot) => *slot = Value::Num(x),
                    None => {}
                }
            }
            return Ok(());
        }
        for (k, l) in r.locals.iter().enumerate() {
            let cl = cr.and_then(|cr| cr.locals.get(k));
            let v = match (cl, &l.init) {
                (Some(super::compile::CLocal { init: Some(f), .. }), _) => f(self, c)?,
                (_, Some(e)) => self.eval(&c.prog, e)?,
                (Some(cl), None) => {
                    // The slot usually still holds this data from the last call: reset
                    // it in place (no allocation for records and arrays).
                    if let Some(slot) = self.stack.get_mut(bp + l.slot as usize) {
                        slot.reset_pooled(&cl.default, &mut self.spare_records);
                    }
                    continue;
                }
                (None, None) => default_value(&c.prog.types, l.ty, &l.dims),
            };
            if let Some(slot) = self.stack.get_mut(bp + l.slot as usize) {
                *slot = v;
            }
        }
        Ok(())
    }

    #[inline(always)]
    fn finish_call(&mut self, p: &Program, r: &Routine, res: Exec<()>) -> Exec<Value> {
        let is_func = matches!(r.kind, RoutineKind::Func(_));
        match res {
            Ok(()) => {
                if is_func {
                    Err(self.fncnoret(r))
                } else {
                    Ok(Value::Absent)
                }
            }
            Err(Unwind::Return) => {
                // Every RETURN writes the slot first; a num stays there (its next write
                // then has nothing to drop).
                let v = match self.ret {
                    Value::Num(x) => Value::Num(x),
                    _ => std::mem::replace(&mut self.ret, Value::Absent),
                };
                if is_func && !v.is_present() {
                    Err(self.fncnoret(r))
                } else {
                    Ok(v)
                }
            }
            Err(Unwind::Propagate(e)) | Err(Unwind::Error(e)) => {
                self.run_undo(p, r)?;
                Err(Unwind::Error(e))
            }
            Err(u @ (Unwind::Exit | Unwind::ExitCycle)) => {
                self.run_undo(p, r)?;
                Err(u)
            }
            Err(u @ (Unwind::Stop | Unwind::Fatal(_))) => Err(u),
            Err(Unwind::Goto(_) | Unwind::Retry | Unwind::TryNext) => Err(self.fatal(
                ErrorKind::Host,
                r.span,
                "internal error: a GOTO, RETRY or TRYNEXT escaped its routine",
            )),
        }
    }

    fn fncnoret(&self, r: &Routine) -> Unwind {
        self.error(
            errnum::ERR_FNCNORET,
            r.span.end_point(),
            format!("function `{}` ended without RETURN", r.name),
        )
    }

    /// Run a routine's UNDO handler (when it is abandoned). Errors in it are fatal.
    fn run_undo(&mut self, p: &Program, r: &Routine) -> Exec<()> {
        let Some(undo) = &r.undo else {
            return Ok(());
        };
        if let Some(f) = self.frames.last_mut() {
            f.handling = None;
        }
        match self.exec_block(p, undo) {
            Ok(()) | Err(Unwind::Return) => Ok(()),
            Err(Unwind::Error(e) | Unwind::Propagate(e) | Unwind::Fatal(e)) => {
                Err(Unwind::Fatal(e))
            }
            Err(other) => Err(other),
        }
    }

    /// Call a native routine.
    pub(crate) fn call_native(
        &mut self,
        p: &Program,
        nid: NativeId,
        args: &[Arg],
        span: Span,
    ) -> Exec<Value> {
        let base = self.nargs.len();
        for arg in args.iter() {
            match self.native_arg(p, arg) {
                Ok(a) => self.nargs.push(a),
                Err(u) => {
                    self.nargs.truncate(base);
                    return Err(u);
                }
            }
        }
        self.invoke_native(p, nid, base, args, span)
    }

    /// Run native `nid` on the arguments in `self.nargs` from `base` (removed after the
    /// call); `args` is the call as lowered.
    pub(crate) fn invoke_native(
        &mut self,
        p: &Program,
        nid: NativeId,
        base: usize,
        args: &[Arg],
        span: Span,
    ) -> Exec<Value> {
        if let Some(f) = self.frames.last_mut() {
            f.at = span;
        }
        let Some(&f) = self.natives.get(nid.0 as usize) else {
            self.nargs.truncate(base);
            return Err(self.fatal(ErrorKind::Host, span, "internal error: unknown native"));
        };
        let mut ctx = Ctx {
            it: self,
            p,
            base,
            span,
            nid,
            args,
        };
        let r = f(&mut ctx);
        self.nargs.truncate(base);
        r
    }

    pub(crate) fn native_arg(&mut self, p: &Program, arg: &Arg) -> Exec<NArg> {
        Ok(match arg {
            Arg::Absent => NArg::Absent,
            Arg::Switch => NArg::Switch,
            Arg::Value(e) => NArg::Val(self.eval(p, e)?),
            Arg::Ref(pl) => NArg::Ref(self.resolve(p, pl)?),
            Arg::Cond { param, arg } => {
                if self.param_present(*param) {
                    self.native_arg(p, arg)?
                } else {
                    NArg::Absent
                }
            }
        })
    }

    /// `% name % args;`: find the procedure at run time and call it. Value arguments are
    /// evaluated once, in parameter order, and checked against the parameter types before
    /// the call; the matching of arguments to parameters is kept per call site and
    /// procedure.
    pub(crate) fn late_call(
        &mut self,
        c: &super::compile::Code,
        name: &str,
        args: &[crate::ir::LateArg],
        compiled: Option<&[Option<LateVal>]>,
        module: crate::ir::ModuleId,
        span: Span,
    ) -> Exec<()> {
        // The callee is looked up in the program as it is now (modules may have been
        // loaded since the caller's code was built); the caller's arguments are evaluated
        // in the caller's.
        let callee = self.code.clone();
        let p = &*callee.prog;
        let site = args.as_ptr() as usize;
        // Sites without arguments share an address: the module tells their lookups apart.
        let key = (site, module.0);
        let known = self
            .late_sites
            .get(&key)
            .and_then(|hits| hits.iter().find(|h| same_name(&h.name, name)))
            .map(|h| (h.rid, h.args.clone()));
        let (rid, lowered) = match known {
            Some(k) => k,
            None => {
                let rid = self.find_late(p, name, module, span)?;
                let lowered = match self.late_args.get(&(site, rid.0)) {
                    Some(l) => l.clone(),
                    None => {
                        let l: LateArgs = self.lower_late_args(p, rid, args, span)?.into();
                        self.late_args.insert((site, rid.0), l.clone());
                        l
                    }
                };
                let hits = self.late_sites.entry(key).or_default();
                if hits.len() < LATE_NAMES_PER_SITE {
                    hits.push(LateHit {
                        name: name.into(),
                        rid,
                        args: lowered.clone(),
                    });
                }
                (rid, lowered)
            }
        };
        let r = p.routine(rid);
        if let Some(q) = r
            .params
            .iter()
            .zip(lowered.iter())
            .find(|(q, (a, _))| !q.optional && matches!(a, Arg::Absent))
        {
            return Err(self.error(
                errnum::ERR_CALLPROC,
                span,
                format!("argument for `{}` of `{}` is missing", q.0.name, r.name),
            ));
        }
        self.check_depth(span)?;
        let (bp, rbp) = (self.sp, self.refs.len());
        if let Err(u) = self.late_args_push(c, p, r, &lowered, compiled) {
            self.sp = bp;
            self.refs.truncate(rbp);
            return Err(u);
        }
        self.enter(&callee, rid, bp, rbp, span).map(drop)
    }

    /// The procedure a late-bound call in `module` at `span` names (`name` or
    /// `module:name`, in any case) in program `p`.
    fn find_late(
        &mut self,
        p: &Program,
        name: &str,
        module: crate::ir::ModuleId,
        span: Span,
    ) -> Exec<RoutineId> {
        let (modname, procname) = match name.split_once(':') {
            Some((m, r)) => (Some(m.trim()), r.trim()),
            None => (None, name.trim()),
        };
        let mut key = std::mem::take(&mut self.late_name);
        key.clear();
        key.push_str(procname);
        key.make_ascii_uppercase();
        let found = p.procs_by_name.get(key.as_str()).and_then(|list| {
            list.iter().copied().find(|&rid| {
                let r = p.routine(rid);
                let mname = &p.modules[r.module.0 as usize].name;
                let module_ok = match modname {
                    Some(m) => mname.eq_ignore_ascii_case(m),
                    None => !r.local || r.module == module,
                };
                module_ok && r.kind == RoutineKind::Proc
            })
        });
        self.late_name = key;
        found.ok_or_else(|| {
            self.error(
                errnum::ERR_REFUNKPRC,
                span,
                format!("there is no procedure `{name}`"),
            )
        })
    }

    /// Push the arguments of a late-bound call of `r` (in program `callee`): the value
    /// arguments evaluated in parameter order and checked against the parameter types,
    /// then the references.
    fn late_args_push(
        &mut self,
        c: &super::compile::Code,
        callee: &Program,
        r: &Routine,
        lowered: &[(Arg, u32)],
        compiled: Option<&[Option<LateVal>]>,
    ) -> Exec<()> {
        let p = &*c.prog;
        for (q, (a, k)) in r.params.iter().zip(lowered.iter()) {
            match (q.slot, a) {
                (_, Arg::Value(e)) => {
                    let f = compiled
                        .and_then(|fs| fs.get(*k as usize))
                        .and_then(Option::as_ref);
                    let (v, known) = match f {
                        Some(f) => ((f.f)(self, c)?, f.ty),
                        None => (self.eval(p, e)?, None),
                    };
                    // A value of an atomic type known when the call was compiled fits a
                    // parameter of that type (their ids are the same in every program).
                    let sure = known == Some(q.ty)
                        && [Ty::NUM, Ty::DNUM, Ty::BOOL, Ty::STRING].contains(&q.ty);
                    if !sure && !super::pers::fits(&callee.types, q.ty, &v) {
                        return Err(self.error(
                            errnum::ERR_CALLPROC,
                            e.span,
                            format!(
                                "argument for `{}` of `{}` must be {}",
                                q.name,
                                r.name,
                                callee.types.display(q.ty)
                            ),
                        ));
                    }
                    match q.slot {
                        ParamSlot::Value(_) => self.push_value(v),
                        ParamSlot::Ref(_) => {
                            return Err(self.fatal(
                                ErrorKind::Host,
                                e.span,
                                "internal error: a reference parameter got a value argument",
                            ));
                        }
                    }
                }
                (ParamSlot::Value(_), a) => {
                    let v = self.arg_value(p, a)?;
                    self.push_value(v);
                }
                (ParamSlot::Ref(_), _) => {}
            }
        }
        for (q, (a, _)) in r.params.iter().zip(lowered.iter()) {
            if let ParamSlot::Ref(_) = q.slot {
                let a = self.arg_ref(p, a)?;
                self.refs.push(a);
            }
        }
        Ok(())
    }

    /// The arguments of a late-bound call matched to the parameters of `rid`.
    fn lower_late_args(
        &self,
        p: &Program,
        rid: RoutineId,
        args: &[crate::ir::LateArg],
        _span: Span,
    ) -> Exec<Vec<(Arg, u32)>> {
        let r = p.routine(rid);
        let mut lowered: Vec<(Arg, u32)> = vec![(Arg::Absent, u32::MAX); r.params.len()];
        let mut next_req = 0usize;
        for (k, a) in args.iter().enumerate() {
            let idx = match &a.name {
                Some(n) => r.params.iter().position(|q| q.name.eq_ignore_ascii_case(n)),
                None => {
                    let i = r
                        .params
                        .iter()
                        .enumerate()
                        .skip(next_req)
                        .find(|(_, q)| !q.optional)
                        .map(|(i, _)| i);
                    if let Some(i) = i {
                        next_req = i + 1;
                    }
                    i
                }
            };
            let Some(i) = idx else {
                return Err(self.error(
                    errnum::ERR_CALLPROC,
                    a.span,
                    format!("`{}` has no parameter for this argument", r.name),
                ));
            };
            let q = &r.params[i];
            let arg = if q.ty.base == crate::ir::TypeId::SWITCH {
                Arg::Switch
            } else if q.mode == ParamMode::In {
                match &a.value {
                    Some(e) => Arg::Value(e.clone()),
                    None => Arg::Switch,
                }
            } else {
                match &a.place {
                    Some(pl) => Arg::Ref(pl.clone()),
                    None => {
                        return Err(self.error(
                            errnum::ERR_ARGNOTVAR,
                            a.span,
                            format!("parameter `{}` of `{}` needs a variable", q.name, r.name),
                        ));
                    }
                }
            };
            lowered[i] = (arg, k as u32);
        }
        Ok(lowered)
    }
}
