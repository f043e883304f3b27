//! Values of any type in compiled form: `num` expressions through their compiled form,
//! string concatenation written into one buffer (the operands read in place, one
//! allocation for the result), places read through their compiled path; anything else on
//! the tree-walking engine's evaluator. Also the statements that store a value
//! (`place := value`) and string comparisons that read their operands in place. A string
//! computed into a string variable is written into the variable's own text when it alone
//! holds it (no allocation once the variable has its buffer).

use super::num::num;
use super::place::CPlace;
use super::{Code, Cx, StmtFn};
use crate::interp::Interp;
use crate::interp::errnum;
use crate::interp::error::{Exec, Unwind};
use crate::interp::place::same_dims;
use crate::interp::value::{MAX_STRING, RStr, Value};
use crate::ir::{BinOp, Expr, ExprKind, PathOp, Place, Root, Ty};
use crate::source::Span;

/// A compiled expression of any type.
pub(crate) type ValFn = Box<dyn Fn(&mut Interp, &Code) -> Exec<Value> + Send + Sync>;

/// Compile an expression to a value.
pub(crate) fn value(cx: &Cx, e: &Expr) -> ValFn {
    let span = e.span;
    match &e.kind {
        ExprKind::Str(s) => {
            let s = RStr::from(s);
            Box::new(move |_, _| Ok(Value::Str(s.clone())))
        }
        ExprKind::Binary(BinOp::Concat, ..) => {
            let parts = concat_parts(cx, e);
            Box::new(move |it, c| it.concat(c, &parts))
        }
        ExprKind::Load(pl) => {
            let p = CPlace::new(cx, pl);
            Box::new(move |it, c| p.load(it, c))
        }
        ExprKind::Local(slot) if !cx.is_num(e) => {
            let slot = *slot as usize;
            Box::new(move |it, _| match it.stack.get(it.bp + slot) {
                Some(Value::Absent) | None => Err(it.error(
                    errnum::ERR_NOTPRES,
                    span,
                    "the optional parameter was not passed",
                )),
                Some(v) => Ok(v.clone()),
            })
        }
        ExprKind::Global(g) if !cx.is_num(e) => {
            let g = *g as usize;
            Box::new(move |it, _| Ok(it.globals.get(g).cloned().unwrap_or(Value::Absent)))
        }
        ExprKind::Native(n, args) => match super::natives::value(cx, *n, args, span) {
            Some(f) => f,
            None => {
                let call = super::call::CNative::new(cx, *n, args, span);
                Box::new(move |it, c| it.cnative(c, &call))
            }
        },
        ExprKind::Record(es) if es.iter().all(|e| cx.is_num(e)) => {
            let es: Box<[(super::NumFn, Span)]> = es.iter().map(|e| (num(cx, e), e.span)).collect();
            Box::new(move |it, c| {
                let mut out = it.spare_record(es.len());
                for ((f, span), v) in es.iter().zip(out.iter_mut()) {
                    let x = f(it, c);
                    if x.is_nan() {
                        it.recycle(Value::Record(out));
                        return Err(it.take_pending(*span));
                    }
                    match v {
                        Value::Num(old) => *old = x,
                        v => *v = Value::Num(x),
                    }
                }
                Ok(Value::Record(out))
            })
        }
        ExprKind::Record(es) => {
            let es: Box<[ValFn]> = es.iter().map(|e| value(cx, e)).collect();
            Box::new(move |it, c| {
                let mut out = it.spare_record(es.len());
                for (f, v) in es.iter().zip(out.iter_mut()) {
                    match f(it, c) {
                        Ok(x) => {
                            let old = std::mem::replace(v, x);
                            it.recycle(old);
                        }
                        Err(u) => {
                            it.recycle(Value::Record(out));
                            return Err(u);
                        }
                    }
                }
                Ok(Value::Record(out))
            })
        }
        ExprKind::Field(base, i) => {
            let (b, i) = (value(cx, base), *i as usize);
            Box::new(move |it, c| match b(it, c)? {
                Value::Record(mut fs) if i < fs.len() => {
                    Ok(std::mem::replace(&mut fs[i], Value::Absent))
                }
                other => Err(it.type_bug(span, "record", &other)),
            })
        }
        ExprKind::Call(r, args) if !cx.is_num(e) => {
            let call = super::CCall::new(cx, *r, args, span);
            Box::new(move |it, c| it.ccall(c, &call))
        }
        _ if cx.is_num(e) => {
            let f = num(cx, e);
            Box::new(move |it, c| {
                let x = f(it, c);
                if x.is_nan() {
                    Err(it.take_pending(span))
                } else {
                    Ok(Value::Num(x))
                }
            })
        }
        _ => {
            let e = e.clone();
            Box::new(move |it, c| it.eval(&c.prog, &e))
        }
    }
}

/// A compiled string expression that appends its text to a buffer.
pub(crate) type TextFn = Box<dyn Fn(&mut Interp, &Code, &mut String) -> Exec<()> + Send + Sync>;

/// A string operand, read in place where it can be.
pub(crate) enum StrPart {
    /// A constant.
    Lit(RStr),
    /// A local slot (an absent optional parameter fails).
    Local(u32, Span),
    /// A global.
    Global(u32, Span),
    /// Any other place.
    Place(CPlace, Span),
    /// A string computed into a buffer (a standard `NumToStr`, `StrPart`).
    Text(TextFn),
    /// A computed string.
    Dyn(ValFn, Span),
}

impl StrPart {
    pub(crate) fn new(cx: &Cx, e: &Expr) -> StrPart {
        match &e.kind {
            ExprKind::Str(s) => StrPart::Lit(RStr::from(s)),
            ExprKind::Local(s) => StrPart::Local(*s, e.span),
            ExprKind::Global(g) => StrPart::Global(*g, e.span),
            ExprKind::Load(pl) => StrPart::Place(CPlace::new(cx, pl), e.span),
            ExprKind::Native(n, args) => match super::natives::text(cx, *n, args, e.span) {
                Some(f) => StrPart::Text(f),
                None => StrPart::Dyn(value(cx, e), e.span),
            },
            _ => StrPart::Dyn(value(cx, e), e.span),
        }
    }

    /// Append the text to `buf`.
    #[inline(always)]
    pub(crate) fn append(&self, it: &mut Interp, c: &Code, buf: &mut String) -> Exec<()> {
        match self {
            StrPart::Text(f) => f(it, c, buf),
            _ => self.with(it, c, |s| super::strfast::push_text(buf, s)),
        }
    }

    /// Call `f` with the text (a computed part is evaluated first).
    #[inline(always)]
    pub(crate) fn with<R>(&self, it: &mut Interp, c: &Code, f: impl FnOnce(&str) -> R) -> Exec<R> {
        let bad = |it: &Interp, v: &Value, span: Span| it.type_bug(span, "string", v);
        match self {
            StrPart::Lit(s) => Ok(f(s)),
            StrPart::Local(s, span) => match it.stack.get(it.bp + *s as usize) {
                Some(Value::Str(t)) => Ok(f(t)),
                Some(Value::Absent) | None => Err(it.error(
                    errnum::ERR_NOTPRES,
                    *span,
                    "the optional parameter was not passed",
                )),
                Some(v) => Err(bad(it, v, *span)),
            },
            StrPart::Global(g, span) => match it.globals.get(*g as usize) {
                Some(Value::Str(t)) => Ok(f(t)),
                Some(v) => Err(bad(it, v, *span)),
                None => Err(bad(it, &Value::Absent, *span)),
            },
            StrPart::Place(p, span) => {
                let span = *span;
                match p.read(it, c, |v| match v {
                    Value::Str(t) => Ok(f(t)),
                    v => Err(v.clone()),
                })? {
                    Ok(r) => Ok(r),
                    Err(v) => Err(bad(it, &v, span)),
                }
            }
            StrPart::Text(g) => {
                let mut buf = it.strbufs.pop().unwrap_or_default();
                buf.clear();
                let r = g(it, c, &mut buf).map(|()| f(&buf));
                it.strbufs.push(buf);
                r
            }
            StrPart::Dyn(g, span) => match g(it, c)? {
                Value::Str(t) => Ok(f(&t)),
                v => Err(bad(it, &v, *span)),
            },
        }
    }
}

/// The operands of `a + b + c …` (the left spine of string `+`), each with the span of the
/// `+` it completes (none for the first).
pub(crate) type Parts = Box<[(StrPart, Span)]>;

fn concat_parts(cx: &Cx, e: &Expr) -> Parts {
    concat_spine(e)
        .into_iter()
        .map(|(b, span)| (StrPart::new(cx, b), span))
        .collect()
}

/// The operand expressions of `a + b + c …` in order, each with the span of the `+` it
/// completes (the first with its own span).
fn concat_spine(e: &Expr) -> Vec<(&Expr, Span)> {
    let mut spine = Vec::new();
    let mut cur = e;
    while let ExprKind::Binary(BinOp::Concat, a, b) = &cur.kind {
        spine.push((b.as_ref(), cur.span));
        cur = a;
    }
    spine.push((cur, cur.span));
    spine.reverse();
    spine
}

/// Does evaluating `e` change nothing (no call other than a standard string or number
/// function, no signal) and read neither `root` nor a reference parameter (which could
/// be `root` under another name)?
fn leaves_alone(cx: &Cx, e: &Expr, root: Root) -> bool {
    let sub = |e: &Expr| leaves_alone(cx, e, root);
    match &e.kind {
        ExprKind::Num(_)
        | ExprKind::Dnum(_)
        | ExprKind::Bool(_)
        | ExprKind::Str(_)
        | ExprKind::Errno
        | ExprKind::Intno
        | ExprKind::Present(_) => true,
        ExprKind::Local(s) => root != Root::Local(*s),
        ExprKind::Global(g) => root != Root::Global(*g),
        ExprKind::Load(pl) => {
            pl.root != root
                && !matches!(pl.root, Root::Ref(_))
                && pl.path.iter().all(|op| match op {
                    PathOp::Field(_) => true,
                    PathOp::Index(es) => es.iter().all(sub),
                })
        }
        ExprKind::Field(a, _)
        | ExprKind::Unary(_, a)
        | ExprKind::NumModDivK(a, ..)
        | ExprKind::ToDnum(a)
        | ExprKind::ToNum(a) => sub(a),
        ExprKind::Binary(_, a, b) => sub(a) && sub(b),
        ExprKind::Record(es) | ExprKind::Array(es, _) => es.iter().all(sub),
        ExprKind::Native(n, args) => {
            matches!(
                cx.standard_native(*n),
                Some("NumToStr" | "StrPart" | "StrLen" | "StrFind" | "StrMatch" | "StrMemb")
            ) && args.iter().all(|a| match a {
                crate::ir::Arg::Value(e) => sub(e),
                crate::ir::Arg::Absent | crate::ir::Arg::Switch => true,
                _ => false,
            })
        }
        ExprKind::SignalValue(_) | ExprKind::Call(..) | ExprKind::Placeholder(_) => false,
    }
}

impl Interp {
    /// A record of `n` components to overwrite every component of: one a store replaced
    /// (so building a record where one was just replaced does not allocate), else a new one.
    #[inline]
    pub(crate) fn spare_record(&mut self, n: usize) -> Box<[Value]> {
        self.spare_records.take(n)
    }

    /// Keep a replaced value for [`Interp::spare_record`] if it is a record (anything else
    /// is dropped).
    #[inline]
    pub(crate) fn recycle(&mut self, v: Value) {
        self.spare_records.give_value(v);
    }

    /// `a + b + …` for strings: each operand appended in order, the length checked after
    /// each `+` as the tree-walking engine checks it.
    fn concat(&mut self, c: &Code, parts: &Parts) -> Exec<Value> {
        let mut buf = self.strbufs.pop().unwrap_or_default();
        buf.clear();
        let r = self.concat_into(c, parts, 0, &mut buf);
        let v = r.map(|()| Value::Str(RStr::from(buf.as_str())));
        self.strbufs.push(buf);
        v
    }

    /// Parts `from..` appended to `buf` (which holds the text of the parts before them).
    fn concat_into(&mut self, c: &Code, parts: &Parts, from: usize, buf: &mut String) -> Exec<()> {
        for (k, (part, span)) in parts.iter().enumerate().skip(from) {
            part.append(self, c, buf)?;
            // More than MAX_STRING bytes may still be few enough characters.
            if k > 0 && buf.len() > MAX_STRING {
                let n = buf.chars().count();
                if n > MAX_STRING {
                    return Err(self.error(
                        errnum::ERR_STRTOOLNG,
                        *span,
                        format!("the result would have {n} characters (at most {MAX_STRING})"),
                    ));
                }
            }
        }
        Ok(())
    }
}

/// String `=` / `<>` (`eq` true for `=`) with the operands read in place (the left one
/// copied into a scratch buffer first, so that evaluating the right one cannot change it);
/// `None` when the operands are not known to be strings.
pub(crate) fn str_eq(cx: &Cx, a: &Expr, b: &Expr, eq: bool) -> Option<super::BoolFn> {
    if cx.expr_ty(a) != Some(Ty::STRING) || cx.expr_ty(b) != Some(Ty::STRING) {
        return None;
    }
    let (a, b) = (StrPart::new(cx, a), StrPart::new(cx, b));
    // Against a constant, nothing needs to be copied.
    if let StrPart::Lit(k) = &b {
        let k = k.clone();
        return Some(Box::new(move |it, c| {
            Ok(a.with(it, c, |s| super::strfast::eq_text(s, &k))? == eq)
        }));
    }
    if let StrPart::Lit(k) = &a {
        let k = k.clone();
        return Some(Box::new(move |it, c| {
            Ok(b.with(it, c, |s| super::strfast::eq_text(s, &k))? == eq)
        }));
    }
    Some(Box::new(move |it, c| {
        let mut tmp = it.strbufs.pop().unwrap_or_default();
        tmp.clear();
        let r = a
            .with(it, c, |s| tmp.push_str(s))
            .and_then(|()| b.with(it, c, |t| tmp.as_str() == t));
        it.strbufs.push(tmp);
        Ok(r? == eq)
    }))
}

/// Where `place := value` stores.
pub(crate) enum VSink {
    Local(u32, Place),
    Global(u32, Place),
    Place(CPlace),
}

impl VSink {
    /// The local or global, for a whole one.
    #[inline(always)]
    fn root(&self) -> Option<Root> {
        match self {
            VSink::Local(s, _) => Some(Root::Local(*s)),
            VSink::Global(g, _) => Some(Root::Global(*g)),
            VSink::Place(_) => None,
        }
    }

    pub(crate) fn of(cx: &Cx, place: &Place) -> VSink {
        match (place.root, place.path.is_empty()) {
            (Root::Local(s), true) => VSink::Local(s, place.clone()),
            (Root::Global(g), true) => VSink::Global(g, place.clone()),
            _ => VSink::Place(CPlace::new(cx, place)),
        }
    }

    /// Store `v` (as [`Interp::store`]: an array only over one of the same sizes).
    #[inline(always)]
    pub(crate) fn put(&self, it: &mut Interp, c: &Code, v: Value) -> Exec<()> {
        let (slot, pl) = match self {
            VSink::Local(s, pl) => (it.stack.get_mut(it.bp + *s as usize), pl),
            VSink::Global(g, pl) => (it.globals.get_mut(*g as usize), pl),
            VSink::Place(p) => return p.store(it, c, v),
        };
        match slot {
            Some(slot) if same_dims(slot, &v) => {
                let old = std::mem::replace(slot, v);
                it.recycle(old);
                Ok(())
            }
            Some(_) => Err(it.dims_error(pl.span)),
            None => it.store(&c.prog, pl, v),
        }
    }
}

/// `place := value` for values of any type. Data copied from a local or global into
/// another whole local or global goes into what the target holds (no allocation when the
/// shapes agree).
pub(crate) fn assign(cx: &Cx, place: &Place, value: &Expr) -> StmtFn {
    // The source is read after the target was taken out of its slot: it must not evaluate
    // anything (no array index) that could read the target.
    let root = |e: &Expr| match &e.kind {
        ExprKind::Local(s) => Some(Root::Local(*s)),
        ExprKind::Global(g) => Some(Root::Global(*g)),
        ExprKind::Load(pl) if pl.path.iter().all(|op| matches!(op, PathOp::Field(_))) => {
            Some(pl.root)
        }
        _ => None,
    };
    if place.path.is_empty()
        && !cx.is_num(value)
        && !matches!(place.root, Root::Ref(_))
        && let Some(src_root) = root(value)
        && src_root != place.root
        && !matches!(src_root, Root::Ref(_))
        && let Some(src) = super::call::Copied::of(cx, value)
    {
        let (root, span) = (place.root, place.span);
        return Box::new(move |it, c| {
            let slot = match root {
                Root::Local(s) => it.stack.get_mut(it.bp + s as usize),
                Root::Global(g) => it.globals.get_mut(g as usize),
                Root::Ref(_) => None,
            };
            let Some(slot) = slot else {
                return Err(it.type_bug(span, "data", &Value::Absent));
            };
            let mut dst = std::mem::replace(slot, Value::Absent);
            let r = src.copy_into(it, c, &mut dst, same_dims);
            let slot = match root {
                Root::Local(s) => it.stack.get_mut(it.bp + s as usize),
                Root::Global(g) => it.globals.get_mut(g as usize),
                Root::Ref(_) => None,
            };
            if let Some(slot) = slot {
                *slot = dst;
            }
            match r? {
                true => Ok(()),
                false => Err(it.dims_error(span)),
            }
        });
    }
    if let Some(f) = assign_text(cx, place, value).or_else(|| assign_nums(cx, place, value)) {
        return f;
    }
    let v = self::value(cx, value);
    let sink = VSink::of(cx, place);
    Box::new(move |it, c| {
        let x = v(it, c)?;
        sink.put(it, c, x)
    })
}

/// Most components of a record of numbers written in place.
const MAX_NUMS: usize = 8;

/// `p := [x, y, z]` for a record of `num` components (`pos`, `orient`, a user record) held
/// by a whole local or global: every component computed first, in order, then written into
/// the record the variable holds (no record built when it holds one of that length).
fn assign_nums(cx: &Cx, place: &Place, value: &Expr) -> Option<StmtFn> {
    let ExprKind::Record(es) = &value.kind else {
        return None;
    };
    if !place.path.is_empty()
        || matches!(place.root, Root::Ref(_))
        || es.len() > MAX_NUMS
        || !es.iter().all(|e| cx.is_num(e))
    {
        return None;
    }
    let fs: Box<[(super::NumFn, Span)]> = es.iter().map(|e| (num(cx, e), e.span)).collect();
    let sink = VSink::of(cx, place);
    Some(Box::new(move |it, c| {
        let mut xs = [0f32; MAX_NUMS];
        for ((f, span), x) in fs.iter().zip(xs.iter_mut()) {
            *x = f(it, c);
            if x.is_nan() {
                return Err(it.take_pending(*span));
            }
        }
        let xs = &xs[..fs.len()];
        let slot = match &sink {
            VSink::Local(s, _) => it.stack.get_mut(it.bp + *s as usize),
            VSink::Global(g, _) => it.globals.get_mut(*g as usize),
            VSink::Place(_) => None,
        };
        if let Some(Value::Record(r)) = slot
            && r.len() == xs.len()
            && r.iter().all(|v| matches!(v, Value::Num(_)))
        {
            for (v, x) in r.iter_mut().zip(xs) {
                if let Value::Num(v) = v {
                    *v = *x;
                }
            }
            return Ok(());
        }
        let mut out = it.spare_record(xs.len());
        for (v, x) in out.iter_mut().zip(xs) {
            match v {
                Value::Num(v) => *v = *x,
                v => *v = Value::Num(*x),
            }
        }
        sink.put(it, c, Value::Record(out))
    }))
}

/// `s := text` for a string held by a whole local or global, when the text is computed
/// (a constant, a concatenation, a standard `NumToStr` or `StrPart`): the text is built in
/// a scratch buffer (everything evaluated before anything is stored, as for any value),
/// which then becomes the variable's own text when it alone holds it (its old buffer is
/// kept for scratch); a text another value shares is left alone and replaced.
/// `s := s + …` where the operands after `s` neither read nor change `s` appends to the
/// text `s` holds alone, and puts it back as it was if an operand fails.
fn assign_text(cx: &Cx, place: &Place, value: &Expr) -> Option<StmtFn> {
    // (A native's type is not known here: only the string natives `natives::text` takes
    // become a `StrPart::Text`.)
    if !place.path.is_empty()
        || matches!(place.root, Root::Ref(_))
        || (cx.expr_ty(value) != Some(Ty::STRING) && !matches!(value.kind, ExprKind::Native(..)))
    {
        return None;
    }
    enum Src {
        Concat(Parts),
        Part(StrPart),
    }
    let src = match &value.kind {
        ExprKind::Binary(BinOp::Concat, ..) => Src::Concat(concat_parts(cx, value)),
        ExprKind::Str(_) | ExprKind::Native(..) => match StrPart::new(cx, value) {
            p @ (StrPart::Lit(_) | StrPart::Text(_)) => Src::Part(p),
            _ => return None,
        },
        _ => return None,
    };
    let sink = VSink::of(cx, place);
    // `s := s + a + b …` where nothing after `s` reads or changes `s`: appended to the
    // text `s` holds, when it holds it alone.
    let appends = matches!(src, Src::Concat(_))
        && match concat_spine(value).as_slice() {
            [(first, _), rest @ ..] => {
                let same = match (&first.kind, place.root) {
                    (ExprKind::Local(s), Root::Local(t)) => *s == t,
                    (ExprKind::Global(g), Root::Global(h)) => *g == h,
                    _ => false,
                };
                same && rest.iter().all(|(e, _)| leaves_alone(cx, e, place.root))
            }
            [] => false,
        };
    let root = sink.root();
    let spine = concat_spine(value);
    let f: StmtFn = match src {
        Src::Concat(parts) if appends => Box::new(move |it, c| {
            match it.text_in_place(sink.root(), |it, t| it.concat_into(c, &parts, 1, t)) {
                Some(r) => r,
                None => it.store_text(c, &sink, |it, buf| it.concat_into(c, &parts, 0, buf)),
            }
        }),
        Src::Concat(parts) => Box::new(move |it, c| {
            it.store_text(c, &sink, |it, buf| it.concat_into(c, &parts, 0, buf))
        }),
        Src::Part(p) => {
            Box::new(move |it, c| it.store_text(c, &sink, |it, buf| p.append(it, c, buf)))
        }
    };
    // The shapes `strfast` runs without the general machinery when it can.
    Some(match (root, spine.as_slice()) {
        (Some(root), [_, (x, _)]) if appends => super::strfast::append(cx, root, x, f),
        (Some(root), _) => super::strfast::part(cx, root, value, f),
        (None, _) => f,
    })
}

impl Interp {
    /// Store the text `fill` writes into a scratch buffer in the string `sink` (a whole
    /// local or global): the buffer becomes the text it holds when it holds it alone.
    #[inline(always)]
    fn store_text(
        &mut self,
        c: &Code,
        sink: &VSink,
        fill: impl FnOnce(&mut Interp, &mut String) -> Exec<()>,
    ) -> Exec<()> {
        let mut buf = self.strbufs.pop().unwrap_or_default();
        buf.clear();
        let r = fill(self, &mut buf).and_then(|()| match self.sink_slot(sink) {
            Some(Value::Str(t)) => {
                // The new text's buffer goes to the variable, its old one is kept for
                // scratch (no copy).
                match t.unique_mut() {
                    Some(dst) => std::mem::swap(dst, &mut buf),
                    None => *t = RStr::from(buf.as_str()),
                }
                Ok(())
            }
            _ => sink.put(self, c, Value::Str(RStr::from(buf.as_str()))),
        });
        self.strbufs.push(buf);
        r
    }

    /// The slot of a whole local or global sink.
    #[inline(always)]
    fn sink_slot(&mut self, sink: &VSink) -> Option<&mut Value> {
        self.root_slot(sink.root()?)
    }

    /// The slot of a local or global.
    #[inline(always)]
    pub(super) fn root_slot(&mut self, root: Root) -> Option<&mut Value> {
        match root {
            Root::Local(s) => self.stack.get_mut(self.bp + s as usize),
            Root::Global(g) => self.globals.get_mut(g as usize),
            Root::Ref(_) => None,
        }
    }

    /// Append to a string held by a local or global in place, when it holds its text
    /// alone (`None` when it does not: nothing was evaluated). The text is taken out of
    /// the value while `fill` appends to it (`fill` must leave the variable alone), and put
    /// back with what `fill` appended, or as it was on an error.
    #[inline(always)]
    fn text_in_place(
        &mut self,
        root: Option<Root>,
        fill: impl FnOnce(&mut Interp, &mut String) -> Exec<()>,
    ) -> Option<Exec<()>> {
        let root = root?;
        let mut text = match self.root_slot(root) {
            Some(Value::Str(t)) => std::mem::take(t.unique_mut()?),
            _ => return None,
        };
        let old = text.len();
        let r = fill(self, &mut text);
        if r.is_err() {
            text.truncate(old);
        }
        match self.root_slot(root) {
            Some(Value::Str(t)) => match t.unique_mut() {
                Some(dst) => *dst = text,
                None => *t = RStr::from(text),
            },
            Some(slot) => *slot = Value::Str(RStr::from(text)),
            None => {}
        }
        Some(r)
    }
}

/// `RETURN value` in a FUNC. A record held by routine data or a value parameter is moved
/// out of its slot, not copied: nothing reads the frame's slots after its RETURN, and the
/// next call sets every routine data and parameter slot again (from the pool of spare
/// records, [`crate::interp::value::Spares`], where the caller's store puts the record it
/// replaced).
pub(crate) fn ret(cx: &Cx, value: &Expr) -> StmtFn {
    if let ExprKind::Local(s) = value.kind
        && !cx.is_num(value)
    {
        let (s, span) = (s as usize, value.span);
        return Box::new(move |it, _| {
            let bp = it.bp;
            match it.stack.get_mut(bp + s) {
                Some(slot @ Value::Record(_)) => {
                    let v = std::mem::replace(slot, Value::Absent);
                    it.set_ret(v);
                    Err(Unwind::Return)
                }
                Some(Value::Absent) | None => Err(it.error(
                    errnum::ERR_NOTPRES,
                    span,
                    "the optional parameter was not passed",
                )),
                Some(v) => {
                    let v = v.clone();
                    it.set_ret(v);
                    Err(Unwind::Return)
                }
            }
        });
    }
    let v = self::value(cx, value);
    Box::new(move |it, c| {
        let v = v(it, c)?;
        it.set_ret(v);
        Err(Unwind::Return)
    })
}

impl Interp {
    /// Make `v` the FUNC's result (what the slot held, a scalar or nothing after the last
    /// call's result was taken, goes to the pool of spare records or is let go).
    #[inline(always)]
    fn set_ret(&mut self, v: Value) {
        let old = std::mem::replace(&mut self.ret, v);
        self.recycle(old);
    }
}
