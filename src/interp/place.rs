//! Places: where a value lives (a frame slot, a global, a path into a record or array), how
//! reference parameters point at their argument, and reading/writing through them.

use super::Interp;
use super::errnum;
use super::error::Exec;
use super::value::{Array, Value};
use crate::ir::{PathOp, Place, Program, Root};
use crate::source::Span;

/// Where a referenced object starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum AbsRoot {
    /// Absolute index into the value stack.
    Stack(u32),
    /// A global.
    Global(u32),
    /// An optional reference parameter that was not passed.
    Absent,
}

/// One resolved step: a record component or an array element (row-major offset).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Step {
    Field(u16),
    Elem(u32),
}

/// A fully resolved place, independent of the frame that computed it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct AbsPlace {
    pub root: AbsRoot,
    pub path: Vec<Step>,
}

impl AbsPlace {
    pub fn absent() -> AbsPlace {
        AbsPlace {
            root: AbsRoot::Absent,
            path: Vec::new(),
        }
    }
    pub fn global(g: u32) -> AbsPlace {
        AbsPlace {
            root: AbsRoot::Global(g),
            path: Vec::new(),
        }
    }
}

/// Why a walk failed.
pub(crate) enum WalkErr {
    NotPresent,
    OutOfBounds { idx: Vec<i64>, dims: Vec<u32> },
    Shape,
}

pub(crate) fn field(v: &Value, f: u16) -> Result<&Value, WalkErr> {
    match v {
        Value::Record(fs) => fs.get(f as usize).ok_or(WalkErr::Shape),
        Value::Absent => Err(WalkErr::NotPresent),
        _ => Err(WalkErr::Shape),
    }
}

pub(crate) fn field_mut(v: &mut Value, f: u16) -> Result<&mut Value, WalkErr> {
    match v {
        Value::Record(fs) => fs.get_mut(f as usize).ok_or(WalkErr::Shape),
        Value::Absent => Err(WalkErr::NotPresent),
        _ => Err(WalkErr::Shape),
    }
}

pub(crate) fn elem<'a>(v: &'a Value, idx: &[i64]) -> Result<&'a Value, WalkErr> {
    match v {
        Value::Array(a) => match a.offset(idx) {
            Some(o) => a.data.get(o).ok_or(WalkErr::Shape),
            None => Err(oob(a, idx)),
        },
        Value::Absent => Err(WalkErr::NotPresent),
        _ => Err(WalkErr::Shape),
    }
}

/// The element of array `v` at `idx` (one index per dimension), for writing.
pub(crate) fn elem_mut<'a>(v: &'a mut Value, idx: &[i64]) -> Result<&'a mut Value, WalkErr> {
    match v {
        Value::Array(a) => match a.offset(idx) {
            Some(o) => a.data.get_mut(o).ok_or(WalkErr::Shape),
            None => Err(oob(a, idx)),
        },
        Value::Absent => Err(WalkErr::NotPresent),
        _ => Err(WalkErr::Shape),
    }
}

pub(crate) fn oob(a: &Array, idx: &[i64]) -> WalkErr {
    WalkErr::OutOfBounds {
        idx: idx.to_vec(),
        dims: a.sizes().to_vec(),
    }
}

fn step(v: &Value, s: Step) -> Result<&Value, WalkErr> {
    match s {
        Step::Field(f) => field(v, f),
        Step::Elem(o) => match v {
            Value::Array(a) => a.data.get(o as usize).ok_or(WalkErr::Shape),
            Value::Absent => Err(WalkErr::NotPresent),
            _ => Err(WalkErr::Shape),
        },
    }
}

pub(crate) fn step_mut(v: &mut Value, s: Step) -> Result<&mut Value, WalkErr> {
    match s {
        Step::Field(f) => field_mut(v, f),
        Step::Elem(o) => match v {
            Value::Array(a) => a.data.get_mut(o as usize).ok_or(WalkErr::Shape),
            Value::Absent => Err(WalkErr::NotPresent),
            _ => Err(WalkErr::Shape),
        },
    }
}

impl Interp {
    /// Current frame's (value base, reference base).
    #[inline]
    pub(crate) fn bases(&self) -> (usize, usize) {
        (self.bp, self.rbp)
    }

    pub(crate) fn walk_err(&self, e: WalkErr, span: Span) -> super::Unwind {
        match e {
            WalkErr::NotPresent => self.error(
                errnum::ERR_NOTPRES,
                span,
                "the optional parameter was not passed",
            ),
            WalkErr::OutOfBounds { idx, dims } => {
                let i: Vec<String> = idx.iter().map(|x| x.to_string()).collect();
                let d: Vec<String> = dims.iter().map(|x| x.to_string()).collect();
                self.error(
                    errnum::ERR_OUTOFBND,
                    span,
                    format!(
                        "index {{{}}} is outside the array bounds {{{}}}",
                        i.join(","),
                        d.join(",")
                    ),
                )
            }
            WalkErr::Shape => self.fatal(
                super::ErrorKind::Host,
                span,
                "internal error: value does not have the checked shape",
            ),
        }
    }

    /// The value an absolute place points at.
    pub(crate) fn abs_get(&self, p: &AbsPlace) -> Result<&Value, WalkErr> {
        let mut v = match p.root {
            AbsRoot::Stack(i) => self.stack.get(i as usize).ok_or(WalkErr::Shape)?,
            AbsRoot::Global(g) => self.globals.get(g as usize).ok_or(WalkErr::Shape)?,
            AbsRoot::Absent => return Err(WalkErr::NotPresent),
        };
        for &s in &p.path {
            v = step(v, s)?;
        }
        Ok(v)
    }

    /// The value an absolute place points at, mutably.
    pub(crate) fn abs_get_mut(&mut self, p: &AbsPlace) -> Result<&mut Value, WalkErr> {
        let mut v = match p.root {
            AbsRoot::Stack(i) => self.stack.get_mut(i as usize).ok_or(WalkErr::Shape)?,
            AbsRoot::Global(g) => self.globals.get_mut(g as usize).ok_or(WalkErr::Shape)?,
            AbsRoot::Absent => return Err(WalkErr::NotPresent),
        };
        for &s in &p.path {
            v = step_mut(v, s)?;
        }
        Ok(v)
    }

    /// Evaluate an array index: a `num` with an integer value.
    #[inline(always)]
    pub(crate) fn eval_index(&mut self, p: &Program, e: &crate::ir::Expr) -> Exec<i64> {
        if let Some(i) = self.num_leaf(e).and_then(super::value::f32_int) {
            return Ok(i as i64);
        }
        self.eval_index_slow(p, e)
    }

    #[inline(never)]
    fn eval_index_slow(&mut self, p: &Program, e: &crate::ir::Expr) -> Exec<i64> {
        let x = self.eval_f64(p, e)?;
        let i = x as i64;
        if i as f64 != x {
            return Err(self.error(
                errnum::ERR_NOTINTVAL,
                e.span,
                format!("array index {x} is not an integer"),
            ));
        }
        Ok(i)
    }

    /// Evaluate every index of a place onto the index stack; returns the mark to truncate to.
    fn push_indices(&mut self, p: &Program, pl: &Place) -> Exec<usize> {
        let mark = self.idx.len();
        for op in pl.path.iter() {
            if let PathOp::Index(es) = op {
                for e in es.iter() {
                    match self.eval_index(p, e) {
                        Ok(i) => self.idx.push(i),
                        Err(u) => {
                            self.idx.truncate(mark);
                            return Err(u);
                        }
                    }
                }
            }
        }
        Ok(mark)
    }

    fn read_walk(&self, pl: &Place, mark: usize) -> Result<&Value, WalkErr> {
        let (bp, rbp) = self.bases();
        let mut v = match pl.root {
            Root::Local(s) => self.stack.get(bp + s as usize).ok_or(WalkErr::Shape)?,
            Root::Global(g) => self.globals.get(g as usize).ok_or(WalkErr::Shape)?,
            Root::Ref(k) => {
                let r = self.refs.get(rbp + k as usize).ok_or(WalkErr::Shape)?;
                self.abs_get(r)?
            }
        };
        let mut ii = mark;
        for op in pl.path.iter() {
            match op {
                PathOp::Field(f) => v = field(v, *f)?,
                PathOp::Index(es) => {
                    let n = es.len();
                    v = elem(v, &self.idx[ii..ii + n])?;
                    ii += n;
                }
            }
        }
        if let Value::Absent = v {
            return Err(WalkErr::NotPresent);
        }
        Ok(v)
    }

    /// Read the value of a place (a copy).
    pub(crate) fn load(&mut self, p: &Program, pl: &Place) -> Exec<Value> {
        let mark = self.push_indices(p, pl)?;
        let r = match self.read_walk(pl, mark) {
            Ok(v) => Ok(v.clone()),
            Err(e) => Err(self.walk_err(e, pl.span)),
        };
        self.idx.truncate(mark);
        r
    }

    /// `a{i}` on a 1-D array: the element's offset, or the walk error.
    #[inline(always)]
    fn elem1_offset(a: &Array, i: i64) -> Result<usize, WalkErr> {
        if a.rank == 1 && i >= 1 && i <= a.dims[0] as i64 {
            Ok((i - 1) as usize)
        } else {
            Err(oob(a, &[i]))
        }
    }

    /// Resolve a place to an absolute reference (for reference arguments).
    pub(crate) fn resolve(&mut self, p: &Program, pl: &Place) -> Exec<AbsPlace> {
        let (bp, rbp) = self.bases();
        let mut ap = match pl.root {
            Root::Local(s) => AbsPlace {
                root: AbsRoot::Stack((bp + s as usize) as u32),
                path: Vec::new(),
            },
            Root::Global(g) => AbsPlace::global(g),
            Root::Ref(k) => match self.refs.get(rbp + k as usize) {
                Some(r) => r.clone(),
                None => return Err(self.walk_err(WalkErr::Shape, pl.span)),
            },
        };
        if ap.root == AbsRoot::Absent {
            return Err(self.walk_err(WalkErr::NotPresent, pl.span));
        }
        for op in pl.path.iter() {
            match op {
                PathOp::Field(f) => ap.path.push(super::place::Step::Field(*f)),
                PathOp::Index(es) => {
                    let mut idx = [0i64; 3];
                    let n = es.len().min(3);
                    for (k, e) in es.iter().take(3).enumerate() {
                        idx[k] = self.eval_index(p, e)?;
                    }
                    let off = match self.abs_get(&ap) {
                        Ok(Value::Array(a)) => match a.offset(&idx[..n]) {
                            Some(o) => o,
                            None => return Err(self.walk_err(oob(a, &idx[..n]), pl.span)),
                        },
                        Ok(_) => return Err(self.walk_err(WalkErr::Shape, pl.span)),
                        Err(e) => return Err(self.walk_err(e, pl.span)),
                    };
                    ap.path.push(Step::Elem(off as u32));
                }
            }
        }
        Ok(ap)
    }

    /// Store a value into a place.
    pub(crate) fn store(&mut self, p: &Program, pl: &Place, v: Value) -> Exec<()> {
        // Fast path: a whole local or global.
        if pl.path.is_empty() {
            let (bp, _) = self.bases();
            let slot = match pl.root {
                Root::Local(s) => self.stack.get_mut(bp + s as usize),
                Root::Global(g) => self.globals.get_mut(g as usize),
                Root::Ref(_) => None,
            };
            if let Some(slot) = slot {
                return match same_dims(slot, &v) {
                    true => {
                        *slot = v;
                        Ok(())
                    }
                    false => Err(self.dims_error(pl.span)),
                };
            }
        }
        // Fast path: `a{i} := v` on a 1-D local or global array.
        if let [PathOp::Index(es)] = &*pl.path
            && let [ie] = &**es
            && !matches!(pl.root, Root::Ref(_))
            && !matches!(v, Value::Array(_))
        {
            let i = self.eval_index(p, ie)?;
            let slot = match pl.root {
                Root::Local(s) => self.stack.get_mut(self.bp + s as usize),
                _ => match pl.root {
                    Root::Global(g) => self.globals.get_mut(g as usize),
                    _ => None,
                },
            };
            let r = match slot {
                Some(Value::Array(a)) => match Self::elem1_offset(a, i) {
                    Ok(o) => match a.data.get_mut(o) {
                        Some(e) => {
                            match (e, v) {
                                (Value::Num(old), Value::Num(x)) => *old = x,
                                (e, v) => *e = v,
                            }
                            return Ok(());
                        }
                        None => WalkErr::Shape,
                    },
                    Err(e) => e,
                },
                Some(Value::Absent) => WalkErr::NotPresent,
                _ => WalkErr::Shape,
            };
            return Err(self.walk_err(r, pl.span));
        }
        let mark = self.push_indices(p, pl)?;
        let res = self.write_walk(pl, mark, v);
        self.idx.truncate(mark);
        match res {
            Ok(true) => Ok(()),
            Ok(false) => Err(self.dims_error(pl.span)),
            Err(e) => Err(self.walk_err(e, pl.span)),
        }
    }

    /// Store through a place whose indices are on the index stack from `mark` (no
    /// allocation); `Ok(false)` when an array would change its sizes.
    fn write_walk(&mut self, pl: &Place, mark: usize, v: Value) -> Result<bool, WalkErr> {
        let (bp, rbp) = self.bases();
        let Interp {
            stack,
            globals,
            refs,
            idx,
            ..
        } = self;
        let mut cur: &mut Value = match pl.root {
            Root::Local(s) => stack.get_mut(bp + s as usize).ok_or(WalkErr::Shape)?,
            Root::Global(g) => globals.get_mut(g as usize).ok_or(WalkErr::Shape)?,
            Root::Ref(k) => {
                let r = refs.get(rbp + k as usize).ok_or(WalkErr::Shape)?;
                let mut c = match r.root {
                    AbsRoot::Stack(i) => stack.get_mut(i as usize).ok_or(WalkErr::Shape)?,
                    AbsRoot::Global(g) => globals.get_mut(g as usize).ok_or(WalkErr::Shape)?,
                    AbsRoot::Absent => return Err(WalkErr::NotPresent),
                };
                for &s in &r.path {
                    c = step_mut(c, s)?;
                }
                c
            }
        };
        let mut ii = mark;
        for op in pl.path.iter() {
            match op {
                PathOp::Field(f) => cur = field_mut(cur, *f)?,
                PathOp::Index(es) => {
                    let n = es.len();
                    let ix = idx.get(ii..ii + n).ok_or(WalkErr::Shape)?;
                    cur = elem_mut(cur, ix)?;
                    ii += n;
                }
            }
        }
        if !same_dims(cur, &v) {
            return Ok(false);
        }
        *cur = v;
        Ok(true)
    }

    /// Store a value through an absolute place.
    pub(crate) fn store_abs(&mut self, ap: &AbsPlace, v: Value, span: Span) -> Exec<()> {
        match self.abs_get_mut(ap) {
            Ok(slot) => {
                if same_dims(slot, &v) {
                    *slot = v;
                    Ok(())
                } else {
                    Err(self.dims_error(span))
                }
            }
            Err(e) => Err(self.walk_err(e, span)),
        }
    }

    pub(crate) fn dims_error(&self, span: Span) -> super::Unwind {
        self.error(
            errnum::ERR_NOTEQDIM,
            span,
            "the array sizes of the value and the target differ",
        )
    }
}

/// Arrays may only be replaced by arrays of the same sizes.
pub(crate) fn same_dims(old: &Value, new: &Value) -> bool {
    match (old, new) {
        (Value::Array(a), Value::Array(b)) => a.dims == b.dims && a.rank == b.rank,
        _ => true,
    }
}
