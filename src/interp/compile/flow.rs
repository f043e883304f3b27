//! Running compiled blocks, FOR and TEST on the skeleton they share with the tree-walking
//! engine (`Interp::run_block`, `Interp::for_loop`, `Interp::test_case` in `stmt.rs`).

use super::cond::{Cond, WithCond};
use super::num::{Opnd, Src};
use super::val::StrPart;
use super::{CBlock, Code, NumFn, StmtFn};
use crate::interp::Interp;
use crate::interp::error::Exec;
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

/// A WHILE loop with a body, compiled around its condition's type.
pub(crate) struct While {
    pub body: CBlock,
}

impl WithCond for While {
    type Out = StmtFn;
    fn with<C: Cond>(self, cond: C) -> StmtFn {
        let body = self.body;
        Box::new(move |it, c| {
            while cond.test(it, c)? {
                it.exec_cblock(c, &body)?;
            }
            Ok(())
        })
    }
}

/// An IF with one condition (and maybe an ELSE), compiled around the condition's type.
pub(crate) struct If {
    pub then: CBlock,
    pub else_body: Option<CBlock>,
}

impl WithCond for If {
    type Out = StmtFn;
    fn with<C: Cond>(self, cond: C) -> StmtFn {
        let then = self.then;
        match self.else_body {
            Some(other) => Box::new(move |it, c| match cond.test(it, c)? {
                true => it.exec_cblock(c, &then),
                false => it.exec_cblock(c, &other),
            }),
            None => Box::new(move |it, c| match cond.test(it, c)? {
                true => it.exec_cblock(c, &then),
                false => Ok(()),
            }),
        }
    }
}

/// A compiled TEST: the subject and the case values, the bodies compiled.
pub(crate) struct CTest {
    pub cases: Cases,
    pub bodies: Box<[CBlock]>,
    pub default: Option<CBlock>,
}

/// A slot of [`Cases::Table`] that no CASE has.
pub(crate) const NO_CASE: u32 = u32::MAX;

/// The widest range of integer case values [`Cases::Table`] is built for.
const MAX_TABLE: i64 = 256;

impl Cases {
    /// The cases of a `num` subject with constant values: a table when they are integers
    /// in a small range (a CASE listed earlier wins, as in the search in order), else the
    /// values in order.
    pub(crate) fn num_consts(subject: SpannedOpnd, vals: Vec<(f32, usize)>) -> Cases {
        let ints: Option<Vec<(i64, usize)>> = vals
            .iter()
            .map(|&(x, k)| (x.fract() == 0.0 && x.abs() < 1e9).then_some((x as i64, k)))
            .collect();
        if let Some(ints) = ints
            && let (Some(lo), Some(hi)) = (
                ints.iter().map(|p| p.0).min(),
                ints.iter().map(|p| p.0).max(),
            )
            && hi - lo < MAX_TABLE
            && let Ok(lo32) = i32::try_from(lo)
        {
            let mut table = vec![NO_CASE; (hi - lo + 1) as usize];
            for (i, k) in ints {
                if let Some(slot) = table.get_mut((i - lo) as usize)
                    && *slot == NO_CASE
                {
                    *slot = k as u32;
                }
            }
            return Cases::Table(subject, lo32, table.into());
        }
        Cases::NumK(subject, vals.into())
    }
}

/// A compiled `num` and its span.
pub(crate) type SpannedNum = (NumFn, Span);

/// A `num` operand (read inline when it is a local or a constant) and its span.
pub(crate) type SpannedOpnd = (Opnd, Span);

/// The subject of a TEST and its case values, one list per CASE.
pub(crate) enum Cases {
    /// A `num` subject with constant case values: (value, index of its CASE), in order.
    NumK(SpannedOpnd, Box<[(f32, usize)]>),
    /// A `num` subject with integer constant case values in a small range: the CASE of
    /// `lo + i` at `i` ([`NO_CASE`] for none).
    Table(SpannedOpnd, i32, Box<[u32]>),
    /// A `num` subject with `num` case values, compared as numbers.
    Num(SpannedNum, Box<[Box<[SpannedNum]>]>),
    /// A string subject (read in place) with constant case strings.
    Str(StrPart, Box<[Box<[Box<str>]>]>),
    /// Anything else, as lowered (structural equality).
    Any(Expr, Box<[Box<[Expr]>]>),
}

impl Interp {
    /// Execute a compiled statement list.
    #[inline(always)]
    pub(crate) fn exec_cblock(&mut self, c: &Code, b: &CBlock) -> Exec<()> {
        self.run_block(
            &c.prog,
            &b.stmts,
            &b.labels,
            |s| s.span,
            |it, s| (s.run)(it, c),
        )
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

    /// A `num` operand evaluated, or its pending error at `span`.
    #[inline(always)]
    fn copnd(&mut self, c: &Code, f: &SpannedOpnd) -> Exec<f32> {
        let x = f.0.get(self, c);
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
            Some(e) => Some(self.cnum(c, e)?),
            None => None,
        };
        let idx = self.bp + f.slot as usize;
        let empty = f.body.stmts.is_empty();
        self.for_loop(&c.prog, idx, (a, b, st), f.span, f.head, empty, |it| {
            it.exec_cblock(c, &f.body)
        })
    }

    /// A compiled TEST: a jump table in a function of its own (small, so that the opcode
    /// dispatch of a program does not pay for the other kinds of cases).
    #[inline(always)]
    pub(crate) fn exec_ctest(&mut self, c: &Code, t: &CTest) -> Exec<()> {
        match &t.cases {
            Cases::Table(subject, lo, table) => self.exec_ctable(c, t, subject, *lo, table),
            _ => self.exec_ctest_search(c, t),
        }
    }

    /// A TEST whose case values are a table.
    #[inline(never)]
    fn exec_ctable(
        &mut self,
        c: &Code,
        t: &CTest,
        subject: &SpannedOpnd,
        lo: i32,
        table: &[u32],
    ) -> Exec<()> {
        let x = self.copnd(c, subject)?;
        // Only an integer can equal a case value (NaN has been refused above), and the case
        // values of a table are far inside `i32`: `x as i32` saturating at 2^31 finds no
        // case, and the difference wraps to an index past the table when `x` is below `lo`.
        let i = x as i32;
        let k = match i as f32 == x {
            true => table
                .get(i.wrapping_sub(lo) as u32 as usize)
                .copied()
                .unwrap_or(NO_CASE),
            false => NO_CASE,
        };
        match (t.bodies.get(k as usize), &t.default) {
            (Some(b), _) | (None, Some(b)) => self.exec_cblock(c, b),
            (None, None) => Ok(()),
        }
    }

    /// A TEST whose cases are searched in order.
    #[inline(never)]
    fn exec_ctest_search(&mut self, c: &Code, t: &CTest) -> Exec<()> {
        let p = &*c.prog;
        let hit = match &t.cases {
            Cases::NumK(subject, vals) => {
                let x = self.copnd(c, subject)?;
                vals.iter().find(|(v, _)| *v == x).map(|(_, k)| *k)
            }
            // Above.
            Cases::Table(..) => None,
            Cases::Num(subject, cases) => {
                let x = self.cnum(c, subject)?;
                let mut hit = None;
                'cases: for (k, vals) in cases.iter().enumerate() {
                    for v in vals.iter() {
                        if self.cnum(c, v)? == x {
                            hit = Some(k);
                            break 'cases;
                        }
                    }
                }
                hit
            }
            Cases::Str(subject, cases) => subject.with(self, c, |s| {
                cases
                    .iter()
                    .position(|vals| vals.iter().any(|v| super::strfast::eq_text(v, s)))
            })?,
            Cases::Any(subject, cases) => {
                let v = self.eval(p, subject)?;
                self.test_case(p, &v, cases.iter().map(|vals| &vals[..]))?
            }
        };
        match hit.and_then(|k| t.bodies.get(k)) {
            Some(b) => self.exec_cblock(c, b),
            None => match &t.default {
                Some(b) => self.exec_cblock(c, b),
                None => Ok(()),
            },
        }
    }
}
