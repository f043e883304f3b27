//! Statement execution: blocks with labels and GOTO, control flow, RAISE/RETRY/TRYNEXT and
//! the ERROR handler protocol, and the per-statement slow path (budget, hook, interrupts).

use super::errnum;
use super::error::{ErrorKind, Exec, RuntimeError, Unwind};
use super::value::{Value, values_equal};
use super::{HookAction, Interp, StmtEvent};
use crate::ir::{Block, Program, Stmt, StmtKind};
use crate::source::Span;

/// How execution continues after an ERROR handler.
enum Resume {
    /// RETRY: run the failed statement again.
    Retry,
    /// TRYNEXT: continue after it.
    Next,
}

impl Interp {
    /// Execute a statement list.
    pub(crate) fn exec_block(&mut self, p: &Program, b: &Block) -> Exec<()> {
        self.run_block(
            p,
            &b.stmts,
            &b.labels,
            |s| s.span,
            |it, s| it.exec_stmt(p, s),
        )
    }

    /// The statement loop of both engines: a step per statement (with the per-statement
    /// slow path when it is due), the ERROR handler protocol and GOTO.
    #[inline(always)]
    pub(crate) fn run_block<S>(
        &mut self,
        p: &Program,
        stmts: &[S],
        labels: &[(u32, u32)],
        span: impl Fn(&S) -> Span,
        mut run: impl FnMut(&mut Interp, &S) -> Exec<()>,
    ) -> Exec<()> {
        let n = stmts.len();
        let mut i = 0usize;
        let mut retries = 0u32;
        while i < n {
            let s = &stmts[i];
            self.steps += 1;
            if self.steps >= self.next_poll {
                self.poll(p, span(s))?;
            }
            match run(self, s) {
                Ok(()) => {
                    i += 1;
                    retries = 0;
                }
                // RETURN leaves every block of the routine: no handler, no label to look at.
                Err(Unwind::Return) => return Err(Unwind::Return),
                Err(u) => i = self.after_unwind(p, u, labels, span(s), i, &mut retries)?,
            }
        }
        Ok(())
    }

    /// Where a block goes on after statement `i` (at `span`) unwound with `u`: the error
    /// handler protocol (RETRY with its limit, TRYNEXT) and GOTO to a label of this block.
    #[inline(never)]
    pub(crate) fn after_unwind(
        &mut self,
        p: &Program,
        u: Unwind,
        labels: &[(u32, u32)],
        span: Span,
        i: usize,
        retries: &mut u32,
    ) -> Exec<usize> {
        match u {
            Unwind::Error(e) => {
                // What `RemainingRetries` reads in the handler.
                if let Some(f) = self.frames.last_mut() {
                    f.retries = *retries;
                }
                self.after_error(p, e, span, i, retries)
            }
            Unwind::Goto(l) => match labels.iter().find(|(id, _)| *id == l) {
                Some(&(_, at)) => Ok(at as usize),
                None => Err(Unwind::Goto(l)),
            },
            u => Err(u),
        }
    }

    /// After statement `i` (at `span`) raised `e`: its handler, and RETRY with its limit or
    /// TRYNEXT.
    fn after_error(
        &mut self,
        p: &Program,
        e: Box<RuntimeError>,
        span: Span,
        i: usize,
        retries: &mut u32,
    ) -> Exec<usize> {
        match self.handle_error(p, e)? {
            Resume::Retry => {
                *retries += 1;
                if *retries > self.retry_limit {
                    let e = self.make_error(
                        ErrorKind::Rapid(errnum::ERR_EXCRTYMAX),
                        span,
                        format!(
                            "the statement failed again after {} RETRYs",
                            self.retry_limit
                        ),
                    );
                    return Err(Unwind::Propagate(e));
                }
                Ok(i)
            }
            Resume::Next => {
                *retries = 0;
                Ok(i + 1)
            }
        }
    }

    #[inline(never)]
    pub(crate) fn exec_stmt(&mut self, p: &Program, s: &Stmt) -> Exec<()> {
        match &s.kind {
            StmtKind::AssignNum { place, value } => self.assign_num(p, place, value),
            StmtKind::Assign { place, value } => {
                let v = self.eval(p, value)?;
                self.store(p, place, v)
            }
            StmtKind::Call { routine, args } => {
                self.call_routine(p, *routine, args, s.span).map(drop)
            }
            StmtKind::Native { native, args } => {
                self.call_native(p, *native, args, s.span).map(drop)
            }
            StmtKind::LateCall { name, args, module } => {
                let n = self.eval_str(p, name)?;
                let code = self.code.clone();
                self.late_call(&code, &n, args, None, *module, s.span)
            }
            StmtKind::If {
                branches,
                else_body,
            } => {
                for (c, b) in branches {
                    if self.eval_bool(p, c)? {
                        return self.exec_block(p, b);
                    }
                }
                match else_body {
                    Some(b) => self.exec_block(p, b),
                    None => Ok(()),
                }
            }
            StmtKind::While { cond, body } => {
                let head = super::compile::while_head(s.span, cond);
                while self.eval_bool(p, cond)? {
                    if body.stmts.is_empty() {
                        self.step(p, head)?;
                    } else {
                        self.exec_block(p, body)?;
                    }
                }
                Ok(())
            }
            StmtKind::For {
                slot,
                from,
                to,
                step,
                body,
            } => self.exec_for(p, *slot, from, to, step.as_ref(), body, s.span),
            StmtKind::Test {
                subject,
                cases,
                default,
            } => self.exec_test(p, subject, cases, default.as_ref()),
            StmtKind::Label(_) => Ok(()),
            StmtKind::Goto(l) => Err(Unwind::Goto(*l)),
            StmtKind::Return(e) => {
                self.ret = match e {
                    Some(e) => self.eval(p, e)?,
                    None => Value::Absent,
                };
                Err(Unwind::Return)
            }
            StmtKind::Raise(e) => self.exec_raise(p, e.as_ref(), s.span),
            StmtKind::Retry => Err(Unwind::Retry),
            StmtKind::TryNext => Err(Unwind::TryNext),
            StmtKind::Exit => Err(Unwind::Exit),
            StmtKind::Connect { place, trap } => self.connect(p, place, *trap, s.span),
            StmtKind::Placeholder(ph) => Err(self.fatal(
                ErrorKind::Placeholder,
                s.span,
                format!("the placeholder {ph} cannot be executed"),
            )),
        }
    }

    /// `place := value` for `num`.
    fn assign_num(
        &mut self,
        p: &Program,
        place: &crate::ir::Place,
        value: &crate::ir::Expr,
    ) -> Exec<()> {
        let x = self.eval_num(p, value)?;
        self.store(p, place, Value::Num(x))
    }

    /// TEST: the index of the first case list holding a value equal to the subject `v`
    /// (`None`: the DEFAULT), case values evaluated in order up to the match.
    pub(crate) fn test_case<'a>(
        &mut self,
        p: &Program,
        v: &Value,
        cases: impl Iterator<Item = &'a [crate::ir::Expr]>,
    ) -> Exec<Option<usize>> {
        for (k, vals) in cases.enumerate() {
            for e in vals {
                let c = self.eval(p, e)?;
                if values_equal(v, &c) {
                    return Ok(Some(k));
                }
            }
        }
        Ok(None)
    }

    /// FOR with evaluated bounds and step: the loop variable in value slot `idx` (absolute)
    /// takes each value in turn while `body` runs; an empty body counts a step at `head`
    /// per iteration.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn for_loop(
        &mut self,
        p: &Program,
        idx: usize,
        (a, b, step): (f32, f32, Option<f32>),
        span: Span,
        head: Span,
        empty: bool,
        mut body: impl FnMut(&mut Interp) -> Exec<()>,
    ) -> Exec<()> {
        let st = match step {
            Some(st) => st,
            None if a > b => -1.0,
            None => 1.0,
        };
        if st == 0.0 || !st.is_finite() {
            return Err(self.error(
                errnum::ERR_ARGVALERR,
                span,
                "the STEP of a FOR loop must not be zero",
            ));
        }
        let mut i = a;
        while (st > 0.0 && i <= b) || (st < 0.0 && i >= b) {
            match self.stack.get_mut(idx) {
                Some(Value::Num(v)) => *v = i,
                Some(v) => *v = Value::Num(i),
                None => {}
            }
            if empty {
                self.step(p, head)?;
            } else {
                body(self)?;
            }
            let next = i + st;
            if next == i {
                return Err(self.error(
                    errnum::ERR_NUM_LIMIT,
                    span,
                    format!("the FOR counter cannot advance past {i} in num precision"),
                ));
            }
            i = next;
        }
        Ok(())
    }

    #[inline(never)]
    fn exec_test(
        &mut self,
        p: &Program,
        subject: &crate::ir::Expr,
        cases: &[(Vec<crate::ir::Expr>, Block)],
        default: Option<&Block>,
    ) -> Exec<()> {
        let v = self.eval(p, subject)?;
        match self.test_case(p, &v, cases.iter().map(|(vals, _)| vals.as_slice()))? {
            Some(k) => self.exec_block(p, &cases[k].1),
            None => match default {
                Some(b) => self.exec_block(p, b),
                None => Ok(()),
            },
        }
    }

    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn exec_for(
        &mut self,
        p: &Program,
        slot: u32,
        from: &crate::ir::Expr,
        to: &crate::ir::Expr,
        step: Option<&crate::ir::Expr>,
        body: &Block,
        span: Span,
    ) -> Exec<()> {
        let a = self.eval_num(p, from)?;
        let b = self.eval_num(p, to)?;
        let st = match step {
            Some(e) => Some(self.eval_num(p, e)?),
            None => None,
        };
        let idx = self.bp + slot as usize;
        let head = super::compile::loop_head(span, to, step);
        self.for_loop(
            p,
            idx,
            (a, b, st),
            span,
            head,
            body.stmts.is_empty(),
            |it| it.exec_block(p, body),
        )
    }

    #[inline(never)]
    fn exec_raise(&mut self, p: &Program, e: Option<&crate::ir::Expr>, span: Span) -> Exec<()> {
        let handling = self.frames.last().and_then(|f| f.handling.clone());
        let Some(e) = e else {
            // `RAISE;` in a handler: pass the same error to the caller.
            return match handling {
                Some(err) => Err(Unwind::Propagate(err)),
                None => Err(self.error(
                    errnum::ERR_ILLRAISE,
                    span,
                    "RAISE without an error number outside an ERROR handler",
                )),
            };
        };
        let x = self.eval_f64(p, e)?;
        let n = x as i32;
        let valid = x.fract() == 0.0
            && ((1..=90).contains(&n)
                || (errnum::BOOK_FIRST..self.next_booked).contains(&n)
                || errnum::by_num(n).is_some());
        let err = if valid {
            self.make_error(ErrorKind::Rapid(n), span, "")
        } else {
            self.make_error(
                ErrorKind::Rapid(errnum::ERR_ILLRAISE),
                span,
                format!("RAISE {x}: user error numbers are 1–90 or booked with BookErrNo"),
            )
        };
        if handling.is_some() {
            Err(Unwind::Propagate(err))
        } else {
            Err(Unwind::Error(err))
        }
    }

    /// Offer an error to the current routine's ERROR handler.
    #[inline(never)]
    fn handle_error(&mut self, p: &Program, e: Box<RuntimeError>) -> Exec<Resume> {
        let Some(errno) = e.errno() else {
            return Err(Unwind::Fatal(e));
        };
        let Some(f) = self.frames.last() else {
            return Err(Unwind::Propagate(e));
        };
        if f.handling.is_some() {
            // An error inside an ERROR handler goes to the system handler.
            return Err(Unwind::Fatal(e));
        }
        let r = p.routine(f.routine);
        let Some(h) = &r.error else {
            return Err(Unwind::Propagate(e));
        };
        if let Some(list) = &h.errnos {
            let mut hit = false;
            for x in list {
                let n = self.eval_f64(p, x)?;
                if n == errno as f64 || n == f64::from(crate::ir::errnum::LONG_JMP_ALL_ERR) {
                    hit = true;
                    break;
                }
            }
            if !hit {
                return Err(Unwind::Propagate(e));
            }
        }
        self.errno = errno;
        if let Some(f) = self.frames.last_mut() {
            f.handling = Some(e);
        }
        let res = self.exec_block(p, &h.body);
        if let Some(f) = self.frames.last_mut() {
            f.handling = None;
        }
        match res {
            Ok(()) => {
                self.ret = Value::Absent;
                Err(Unwind::Return)
            }
            Err(Unwind::Retry) => Ok(Resume::Retry),
            Err(Unwind::TryNext) => Ok(Resume::Next),
            Err(other) => Err(other),
        }
    }

    /// Count one step at `span` against the budget, taking the slow path (budget, hook,
    /// interrupts) when it is due. Every statement is a step, and so is every iteration of
    /// a loop whose body is empty (counted at the loop's head), so every loop iteration
    /// counts and `WHILE TRUE DO ENDWHILE` ends at the budget too.
    #[inline]
    pub(crate) fn step(&mut self, p: &Program, span: Span) -> Exec<()> {
        self.steps += 1;
        if self.steps >= self.next_poll {
            self.poll(p, span)?;
        }
        Ok(())
    }

    /// The per-statement slow path: budget, hook, interrupts.
    #[cold]
    #[inline(never)]
    pub(crate) fn poll(&mut self, p: &Program, span: Span) -> Exec<()> {
        if self.stop_requested() {
            return Err(Unwind::Stop);
        }
        if let Some(b) = self.budget
            && self.steps > b
        {
            return Err(self.fatal(
                ErrorKind::Aborted,
                span,
                format!("the operation budget of {b} steps is exhausted"),
            ));
        }
        if let Some(mut h) = self.hook.take() {
            let routine = self
                .frames
                .last()
                .map(|f| p.routine(f.routine).name.as_str())
                .unwrap_or("");
            let ev = StmtEvent {
                span,
                routine,
                depth: self.frames.len(),
                steps: self.steps,
            };
            let action = h(&ev);
            self.hook = Some(h);
            if action != HookAction::Continue {
                return Err(self.fatal(
                    ErrorKind::Aborted,
                    span,
                    "execution stopped by the before-statement hook",
                ));
            }
        }
        if self.service.is_some() {
            if let Some(f) = self.frames.last_mut() {
                f.at = span;
            }
            match self.run_service_hook() {
                HookAction::Continue => {}
                HookAction::Stop => return Err(Unwind::Stop),
                HookAction::Abort => {
                    return Err(self.fatal(
                        ErrorKind::Aborted,
                        span,
                        "execution stopped by the service hook",
                    ));
                }
            }
        }
        if self.ints.armed() {
            if let Some(f) = self.frames.last_mut() {
                f.at = span;
            }
            self.service_interrupts(p, span)?;
        }
        if self.task.is_some() {
            self.task_slice_due()
                .map_err(|e| self.host_error(e, span))?;
        }
        self.update_poll();
        Ok(())
    }
}
