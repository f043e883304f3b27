//! Places in compiled form: the path of a place with its indices compiled, read by
//! borrowing (a component of a record is read without copying the record) and written in
//! place. Indices are evaluated first, in order, then the path is walked, with the errors
//! of [`Interp::load`] and [`Interp::store`].

use super::num::{Opnd, Src, opnd};
use super::{Code, Cx};
use crate::interp::Interp;
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::place::{WalkErr, elem, elem_mut, field, field_mut, same_dims, step_mut};
use crate::interp::value::{Value, f32_int};
use crate::ir::{BinOp, Expr, ExprKind, PathOp, Place, Root};
use crate::source::Span;

/// Most indices a compiled place evaluates (more fall back to the IR walk).
const MAX_INDICES: usize = 6;

/// One array index.
enum CIdx {
    /// A `num` index, compiled.
    Num(Opnd, Span),
    /// An index of another type (evaluated as the tree-walking engine does).
    Other(Expr),
}

/// One step of a compiled path: a record component, or an element with this many indices.
#[derive(Clone, Copy)]
enum CStep {
    Field(u16),
    Elem(u8),
}

/// A place of components only of a local (`q.x`, `p.trans.z`), for the reads and writes
/// that walk it without a loop.
#[derive(Clone, Copy)]
enum Short {
    /// `slot.f`.
    Field(u32, u16),
    /// `slot.f.g`.
    Field2(u32, u16, u16),
    /// `a{i}` of a local or global array with one `num` index: the element is read and
    /// written without a walk (a 1-D array of `num`s; anything else takes the walk).
    Elem1,
    /// Any other place.
    No,
}

/// A compiled place.
pub(crate) struct CPlace {
    /// The shape of a short place.
    short: Short,
    root: Root,
    /// The index of an [`Short::Elem1`] place of the form `i + k` / `i - k` (`i` a local,
    /// `k` a constant): `i`'s slot and the number added (computed without a dispatch).
    kidx: Option<(u32, f32)>,
    steps: Box<[CStep]>,
    idx: Box<[CIdx]>,
    /// The place as lowered (for the IR walk when there are too many indices).
    ir: Place,
}

impl CPlace {
    pub(crate) fn new(cx: &Cx, pl: &Place) -> CPlace {
        let mut steps = Vec::new();
        let mut idx = Vec::new();
        for op in pl.path.iter() {
            match op {
                PathOp::Field(f) => steps.push(CStep::Field(*f)),
                PathOp::Index(es) => {
                    steps.push(CStep::Elem(es.len().min(255) as u8));
                    idx.extend(es.iter().map(|e| match cx.is_num(e) {
                        true => CIdx::Num(opnd(cx, e), e.span),
                        false => CIdx::Other(e.clone()),
                    }));
                }
            }
        }
        let short = match (pl.root, steps.as_slice()) {
            (Root::Local(s), [CStep::Field(f)]) => Short::Field(s, *f),
            (Root::Local(s), [CStep::Field(f), CStep::Field(g)]) => Short::Field2(s, *f, *g),
            (Root::Local(_) | Root::Global(_), [CStep::Elem(1)])
                if matches!(idx.as_slice(), [CIdx::Num(..)]) =>
            {
                Short::Elem1
            }
            _ => Short::No,
        };
        let kidx = match (short, &*pl.path) {
            (Short::Elem1, [PathOp::Index(es)]) => match es.first().map(|e| &e.kind) {
                Some(ExprKind::Binary(op @ (BinOp::NumAdd | BinOp::NumSub), a, b)) => {
                    match (&a.kind, &b.kind) {
                        (ExprKind::Local(s), ExprKind::Num(k)) if cx.is_num(a) => {
                            Some((*s, if *op == BinOp::NumSub { -*k } else { *k }))
                        }
                        _ => None,
                    }
                }
                _ => None,
            },
            _ => None,
        };
        CPlace {
            short,
            kidx,
            root: pl.root,
            steps: steps.into(),
            idx: idx.into(),
            ir: pl.clone(),
        }
    }

    /// The place as lowered.
    pub(crate) fn ir(&self) -> &Place {
        &self.ir
    }

    /// Evaluate the indices into `buf`.
    #[inline(always)]
    fn indices(&self, it: &mut Interp, c: &Code, buf: &mut [i64; MAX_INDICES]) -> Exec<()> {
        for (k, ix) in self.idx.iter().enumerate() {
            let i = match ix {
                CIdx::Num(o, span) => {
                    let x = o.get(it, c);
                    match f32_int(x) {
                        Some(i) => i as i64,
                        None => it.index_of(x, *span)?,
                    }
                }
                CIdx::Other(e) => it.eval_index(&c.prog, e)?,
            };
            if let Some(b) = buf.get_mut(k) {
                *b = i;
            }
        }
        Ok(())
    }

    /// The value at the place, borrowed.
    #[inline(always)]
    fn walk<'a>(&self, it: &'a Interp, idx: &[i64]) -> Result<&'a Value, WalkErr> {
        let mut v = match self.root {
            Root::Local(s) => it.stack.get(it.bp + s as usize).ok_or(WalkErr::Shape)?,
            Root::Global(g) => it.globals.get(g as usize).ok_or(WalkErr::Shape)?,
            Root::Ref(k) => {
                let r = it.refs.get(it.rbp + k as usize).ok_or(WalkErr::Shape)?;
                it.abs_get(r)?
            }
        };
        let mut ii = 0;
        for s in self.steps.iter() {
            match *s {
                CStep::Field(f) => v = field(v, f)?,
                CStep::Elem(n) => {
                    let n = n as usize;
                    v = elem(v, idx.get(ii..ii + n).ok_or(WalkErr::Shape)?)?;
                    ii += n;
                }
            }
        }
        if let Value::Absent = v {
            return Err(WalkErr::NotPresent);
        }
        Ok(v)
    }

    /// Read a `num` (NaN: an error is pending); `span` is the expression's.
    #[inline(always)]
    pub(crate) fn num(&self, it: &mut Interp, c: &Code, span: Span) -> f32 {
        match self.fields_num(it) {
            Some(x) => x,
            None => self.num_indexed(it, c, span),
        }
    }

    /// The `num` held by a place of components only (`q.x`, `p.trans.z` of a local or a
    /// global): nothing to evaluate first, nothing that can fail. `None` for any other
    /// place or value (the general path decides).
    #[inline(always)]
    fn fields_num(&self, it: &Interp) -> Option<f32> {
        fn comp(v: &Value, f: u16) -> Option<&Value> {
            match v {
                Value::Record(fs) => fs.get(f as usize),
                _ => None,
            }
        }
        let v = match self.short {
            Short::Field(s, f) => comp(it.stack.get(it.bp + s as usize)?, f),
            Short::Field2(s, f, g) => comp(comp(it.stack.get(it.bp + s as usize)?, f)?, g),
            Short::Elem1 => return None,
            Short::No => return self.fields_num_walk(it),
        };
        match v {
            Some(Value::Num(x)) => Some(*x),
            _ => None,
        }
    }

    /// [`CPlace::fields_num`] of a place that is not short.
    #[inline(always)]
    fn fields_num_walk(&self, it: &Interp) -> Option<f32> {
        if !self.idx.is_empty() {
            return None;
        }
        let mut v = match self.root {
            Root::Local(s) => it.stack.get(it.bp + s as usize)?,
            Root::Global(g) => it.globals.get(g as usize)?,
            Root::Ref(_) => return None,
        };
        for s in self.steps.iter() {
            v = match (*s, v) {
                (CStep::Field(f), Value::Record(fs)) => fs.get(f as usize)?,
                _ => return None,
            };
        }
        match v {
            Value::Num(x) => Some(*x),
            _ => None,
        }
    }

    /// The index of an [`Short::Elem1`] place, evaluated (NaN: an error is pending), and its
    /// span.
    #[inline(always)]
    fn elem1_index(&self, it: &mut Interp, c: &Code) -> (f32, Span) {
        match self.idx.first() {
            Some(CIdx::Num(o, span)) => {
                // `i ± k`: a result that is not finite takes the general path, which fails
                // with its error.
                if let Some((s, k)) = self.kidx
                    && let Some(Value::Num(x)) = it.stack.get(it.bp + s as usize)
                    && (*x + k).is_finite()
                {
                    return (*x + k, *span);
                }
                (o.get(it, c), *span)
            }
            // Not built for other places.
            _ => (f32::NAN, self.ir.span),
        }
    }

    /// The 0-based offset of element `x` of a 1-D array, when `x` is an integer ≥ 1.
    #[inline(always)]
    fn elem1_offset(x: f32) -> Option<usize> {
        let i = f32_int(x)?;
        usize::try_from(i).ok()?.checked_sub(1)
    }

    /// Is this `a{i}` of a local or global array with one `num` index (see
    /// [`CPlace::elem1_num`])?
    pub(crate) fn is_elem1(&self) -> bool {
        matches!(self.short, Short::Elem1)
    }

    /// `a{i}` of a [`Short::Elem1`] place: the element read in place when it is a `num`
    /// inside the bounds of a 1-D array, else the walk with its errors (out of line, so that
    /// the operand reads it is called from stay small).
    #[inline(never)]
    pub(crate) fn elem1_num(&self, it: &mut Interp, c: &Code, span: Span) -> f32 {
        let (x, ispan) = self.elem1_index(it, c);
        if let Some(o) = Self::elem1_offset(x) {
            let arr = match self.root {
                Root::Local(s) => it.stack.get(it.bp + s as usize),
                Root::Global(g) => it.globals.get(g as usize),
                Root::Ref(_) => None,
            };
            if let Some(Value::Array(a)) = arr
                && a.rank == 1
                && o < a.dims[0] as usize
                && let Some(Value::Num(v)) = a.data.get(o)
            {
                return *v;
            }
        }
        self.elem1_num_slow(it, x, ispan, span)
    }

    /// [`CPlace::elem1_num`] off the fast path: the index checked and the walk, as
    /// [`CPlace::num_indexed`] does them.
    #[cold]
    #[inline(never)]
    fn elem1_num_slow(&self, it: &mut Interp, x: f32, ispan: Span, span: Span) -> f32 {
        let i = match f32_int(x) {
            Some(i) => i as i64,
            None => match it.index_of(x, ispan) {
                Ok(i) => i,
                Err(u) => return it.fail_nf(u),
            },
        };
        self.num_at(it, &[i], span)
    }

    /// Write `x` (not NaN): a [`Short::Elem1`] element in place, a `num` component in
    /// place, anything else through [`CPlace::store`].
    #[inline(always)]
    pub(crate) fn put_num(&self, it: &mut Interp, c: &Code, x: f32) -> Exec<()> {
        if let Short::Elem1 = self.short {
            return self.elem1_put(it, c, x);
        }
        match self.fields_num_mut(it) {
            Some(slot) => {
                *slot = x;
                Ok(())
            }
            None => self.store(it, c, Value::Num(x)),
        }
    }

    /// [`CPlace::put_num`] of a [`Short::Elem1`] place (out of line, as
    /// [`CPlace::elem1_num`]).
    #[inline(never)]
    fn elem1_put(&self, it: &mut Interp, c: &Code, x: f32) -> Exec<()> {
        let (i, ispan) = self.elem1_index(it, c);
        if let Some(o) = Self::elem1_offset(i) {
            let arr = match self.root {
                Root::Local(s) => it.stack.get_mut(it.bp + s as usize),
                Root::Global(g) => it.globals.get_mut(g as usize),
                Root::Ref(_) => None,
            };
            if let Some(Value::Array(a)) = arr
                && a.rank == 1
                && o < a.dims[0] as usize
                && let Some(Value::Num(v)) = a.data.get_mut(o)
            {
                *v = x;
                return Ok(());
            }
        }
        self.elem1_store_slow(it, i, ispan, Value::Num(x))
    }

    /// [`CPlace::put_num`] of a [`Short::Elem1`] place off the fast path: the index checked
    /// and the store, as [`CPlace::store`] does them.
    #[cold]
    #[inline(never)]
    fn elem1_store_slow(&self, it: &mut Interp, x: f32, ispan: Span, v: Value) -> Exec<()> {
        let i = match f32_int(x) {
            Some(i) => i as i64,
            None => it.index_of(x, ispan)?,
        };
        self.store_at(it, &[i], v)
    }

    /// [`CPlace::num`] of any other place (indices to evaluate, a reference, an error to
    /// report): kept out of line, so that the component reads above stay small where they
    /// are inlined.
    #[inline(never)]
    fn num_indexed(&self, it: &mut Interp, c: &Code, span: Span) -> f32 {
        if self.idx.is_empty()
            && let Ok(Value::Num(x)) = self.walk(it, &[])
        {
            return *x;
        }
        if self.idx.len() > MAX_INDICES {
            return it.nf_cold(c, &self.load_expr(span));
        }
        let mut buf = [0i64; MAX_INDICES];
        if let Err(u) = self.indices(it, c, &mut buf) {
            return it.fail_nf(u);
        }
        self.num_at(it, &buf[..self.idx.len()], span)
    }

    /// The `num` at the place with its indices evaluated (NaN: an error is pending).
    #[inline]
    fn num_at(&self, it: &mut Interp, idx: &[i64], span: Span) -> f32 {
        match self.walk(it, idx) {
            Ok(Value::Num(x)) => *x,
            Ok(other) => {
                let v = other.clone();
                it.nf_of(Ok(v), span)
            }
            Err(e) => {
                let u = it.walk_err(e, self.ir.span);
                it.fail_nf(u)
            }
        }
    }

    /// The `num` held by a place of components only (`q.x`, `p.trans.z` of a local or a
    /// global), to write; `None` for any other place or value (the general path decides).
    #[inline(always)]
    pub(crate) fn fields_num_mut<'a>(&self, it: &'a mut Interp) -> Option<&'a mut f32> {
        fn comp(v: &mut Value, f: u16) -> Option<&mut Value> {
            match v {
                Value::Record(fs) => fs.get_mut(f as usize),
                _ => None,
            }
        }
        let bp = it.bp;
        let v = match self.short {
            Short::Field(s, f) => comp(it.stack.get_mut(bp + s as usize)?, f),
            Short::Field2(s, f, g) => comp(comp(it.stack.get_mut(bp + s as usize)?, f)?, g),
            Short::Elem1 => return None,
            Short::No => return self.fields_num_mut_walk(it),
        };
        match v {
            Some(Value::Num(x)) => Some(x),
            _ => None,
        }
    }

    /// [`CPlace::fields_num_mut`] of a place that is not short.
    #[inline(always)]
    fn fields_num_mut_walk<'a>(&self, it: &'a mut Interp) -> Option<&'a mut f32> {
        if !self.idx.is_empty() {
            return None;
        }
        let mut v = match self.root {
            Root::Local(s) => it.stack.get_mut(it.bp + s as usize)?,
            Root::Global(g) => it.globals.get_mut(g as usize)?,
            Root::Ref(_) => return None,
        };
        for s in self.steps.iter() {
            match *s {
                CStep::Field(f) => v = field_mut(v, f).ok()?,
                CStep::Elem(_) => return None,
            }
        }
        match v {
            Value::Num(x) => Some(x),
            _ => None,
        }
    }

    /// Call `f` with the value, borrowed.
    #[inline]
    pub(crate) fn read<R>(
        &self,
        it: &mut Interp,
        c: &Code,
        f: impl FnOnce(&Value) -> R,
    ) -> Exec<R> {
        if self.idx.len() > MAX_INDICES {
            let v = it.load(&c.prog, &self.ir)?;
            return Ok(f(&v));
        }
        let mut buf = [0i64; MAX_INDICES];
        self.indices(it, c, &mut buf)?;
        match self.walk(it, &buf[..self.idx.len()]) {
            Ok(v) => Ok(f(v)),
            Err(e) => Err(it.walk_err(e, self.ir.span)),
        }
    }

    /// Read the value (a copy).
    pub(crate) fn load(&self, it: &mut Interp, c: &Code) -> Exec<Value> {
        if self.idx.len() > MAX_INDICES {
            return it.load(&c.prog, &self.ir);
        }
        let mut buf = [0i64; MAX_INDICES];
        self.indices(it, c, &mut buf)?;
        match self.walk(it, &buf[..self.idx.len()]) {
            Ok(v) => Ok(v.clone()),
            Err(e) => Err(it.walk_err(e, self.ir.span)),
        }
    }

    /// Write `v` (an array only over an array of the same sizes).
    pub(crate) fn store(&self, it: &mut Interp, c: &Code, v: Value) -> Exec<()> {
        if self.idx.len() > MAX_INDICES {
            return it.store(&c.prog, &self.ir, v);
        }
        let mut buf = [0i64; MAX_INDICES];
        self.indices(it, c, &mut buf)?;
        self.store_at(it, &buf[..self.idx.len()], v)
    }

    /// Write `v` at the place with its indices evaluated.
    fn store_at(&self, it: &mut Interp, idx: &[i64], v: Value) -> Exec<()> {
        // `a{i} := v` of a 1-D array held by a local or global (an array of records), when
        // the index is in bounds and neither is an array: the element is replaced directly.
        if let ([CStep::Elem(1)], [i]) = (&*self.steps, idx)
            && !matches!(v, Value::Array(_))
            && let Some(Value::Array(a)) = it.root_slot(self.root)
            && a.rank == 1
            && *i >= 1
            && *i <= a.dims[0] as i64
            && let Some(cur) = a.data.get_mut((*i - 1) as usize)
            && !matches!(cur, Value::Array(_))
        {
            let old = std::mem::replace(cur, v);
            it.recycle(old);
            return Ok(());
        }
        let (bp, rbp) = (it.bp, it.rbp);
        let Interp {
            stack,
            globals,
            refs,
            ..
        } = &mut *it;
        let r = (|| {
            let mut cur: &mut Value = match self.root {
                Root::Local(s) => stack.get_mut(bp + s as usize).ok_or(WalkErr::Shape)?,
                Root::Global(g) => globals.get_mut(g as usize).ok_or(WalkErr::Shape)?,
                Root::Ref(k) => {
                    let r = refs.get(rbp + k as usize).ok_or(WalkErr::Shape)?;
                    let mut c = match r.root {
                        crate::interp::place::AbsRoot::Stack(i) => {
                            stack.get_mut(i as usize).ok_or(WalkErr::Shape)?
                        }
                        crate::interp::place::AbsRoot::Global(g) => {
                            globals.get_mut(g as usize).ok_or(WalkErr::Shape)?
                        }
                        crate::interp::place::AbsRoot::Absent => {
                            return Err(WalkErr::NotPresent);
                        }
                    };
                    for &s in &r.path {
                        c = step_mut(c, s)?;
                    }
                    c
                }
            };
            let mut ii = 0;
            for s in self.steps.iter() {
                match *s {
                    CStep::Field(f) => cur = field_mut(cur, f)?,
                    CStep::Elem(n) => {
                        let n = n as usize;
                        let ix = idx.get(ii..ii + n).ok_or(WalkErr::Shape)?;
                        cur = elem_mut(cur, ix)?;
                        ii += n;
                    }
                }
            }
            if !same_dims(cur, &v) {
                return Ok(None);
            }
            Ok(Some(match (cur, v) {
                (Value::Num(old), Value::Num(x)) => {
                    *old = x;
                    Value::Absent
                }
                (cur, v) => std::mem::replace(cur, v),
            }))
        })();
        match r {
            Ok(Some(old)) => {
                it.recycle(old);
                Ok(())
            }
            Ok(None) => Err(it.dims_error(self.ir.span)),
            Err(e) => Err(it.walk_err(e, self.ir.span)),
        }
    }

    /// The place as an expression (for the IR walk).
    fn load_expr(&self, span: Span) -> Expr {
        Expr {
            kind: crate::ir::ExprKind::Load(Box::new(self.ir.clone())),
            span,
        }
    }
}

impl Interp {
    /// An index that is not an `i32` integer: the integer it is, or `ERR_NOTINTVAL` (as the
    /// tree-walking engine's index evaluation).
    #[cold]
    #[inline(never)]
    pub(crate) fn index_of(&mut self, x: f32, span: Span) -> Exec<i64> {
        if x.is_nan() {
            return Err(self.take_pending(span));
        }
        let x = x as f64;
        let i = x as i64;
        if i as f64 != x {
            return Err(self.error(
                errnum::ERR_NOTINTVAL,
                span,
                format!("array index {x} is not an integer"),
            ));
        }
        Ok(i)
    }
}
