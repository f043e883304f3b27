//! Running compiled blocks and loops: the statement loop (steps, budget, hook, interrupts,
//! the ERROR handler protocol and GOTO, shared with the tree-walking path), FOR and TEST.

use super::{CBlock, Code, NumFn};
use crate::interp::Interp;
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::value::{Value, values_equal};
use crate::ir::Expr;
use crate::source::Span;

/// A compiled FOR loop.
pub(crate) struct CFor {
    pub slot: u32,
    pub from: (NumFn, Span),
    pub to: (NumFn, Span),
    pub step: Option<(NumFn, Span)>,
    pub body: CBlock,
    pub span: Span,
    /// `FOR i FROM a TO b [STEP c]`: where an iteration of an empty body is counted.
    pub head: Span,
}

/// A compiled TEST: the subject and case values as lowered, the bodies compiled.
pub(crate) struct CTest {
    pub subject: Expr,
    pub cases: Box<[(Box<[Expr]>, CBlock)]>,
    pub default: Option<CBlock>,
}

impl Interp {
    /// Execute a compiled statement list.
    #[inline(always)]
    pub(crate) fn exec_cblock(&mut self, c: &Code, b: &CBlock) -> Exec<()> {
        let n = b.stmts.len();
        let mut i = 0usize;
        let mut retries = 0u32;
        while i < n {
            let s = &b.stmts[i];
            self.steps += 1;
            if self.steps >= self.next_poll {
                self.poll(&c.prog, s.span)?;
            }
            match (s.run)(self, c) {
                Ok(()) => {
                    i += 1;
                    retries = 0;
                }
                Err(u) => i = self.after_unwind(&c.prog, u, &b.labels, s.span, i, &mut retries)?,
            }
        }
        Ok(())
    }

    /// A compiled `num` evaluated, or its pending error at `span`.
    #[inline(always)]
    fn cnum(&mut self, c: &Code, f: &(NumFn, Span)) -> Exec<f32> {
        let x = (f.0)(self, c);
        if x.is_nan() {
            Err(self.take_pending(f.1))
        } else {
            Ok(x)
        }
    }

    pub(crate) fn exec_cfor(&mut self, c: &Code, f: &CFor) -> Exec<()> {
        let a = self.cnum(c, &f.from)?;
        let b = self.cnum(c, &f.to)?;
        let st = match &f.step {
            Some(e) => self.cnum(c, e)?,
            None if a > b => -1.0,
            None => 1.0,
        };
        if st == 0.0 || !st.is_finite() {
            return Err(self.error(
                errnum::ERR_ARGVALERR,
                f.span,
                "the STEP of a FOR loop must not be zero",
            ));
        }
        let idx = self.bp + f.slot as usize;
        let mut i = a;
        while (st > 0.0 && i <= b) || (st < 0.0 && i >= b) {
            match self.stack.get_mut(idx) {
                Some(Value::Num(v)) => *v = i,
                Some(v) => *v = Value::Num(i),
                None => {}
            }
            if f.body.stmts.is_empty() {
                self.step(&c.prog, f.head)?;
            } else {
                self.exec_cblock(c, &f.body)?;
            }
            let next = i + st;
            if next == i {
                return Err(self.error(
                    errnum::ERR_NUM_LIMIT,
                    f.span,
                    format!("the FOR counter cannot advance past {i} in num precision"),
                ));
            }
            i = next;
        }
        Ok(())
    }

    pub(crate) fn exec_ctest(&mut self, c: &Code, t: &CTest) -> Exec<()> {
        let p = &*c.prog;
        let v = self.eval(p, &t.subject)?;
        for (vals, b) in t.cases.iter() {
            for e in vals.iter() {
                let x = self.eval(p, e)?;
                if values_equal(&v, &x) {
                    return self.exec_cblock(c, b);
                }
            }
        }
        match &t.default {
            Some(b) => self.exec_cblock(c, b),
            None => Ok(()),
        }
    }
}
