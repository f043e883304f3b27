//! Fast paths of the string statements that programs which walk and build text run most:
//! `c := StrPart(s, k, 1)` (one ASCII character read by its byte position and written
//! into the text `c` holds, no allocation) and `s := s + x` of one operand (appended in
//! place, a one-byte operand without a copy call). Each one either does all of the
//! statement's work or none of it (nothing evaluated, nothing written) and then leaves
//! the statement to its general form, which also raises every error: a fast path only
//! runs where the statement cannot fail.

use super::{Cx, StmtFn};
use crate::interp::Interp;
use crate::interp::value::{MAX_STRING, Value, f32_int};
use crate::ir::{Arg, Expr, ExprKind, Root};

/// A `num` operand read with no side effect and no failure: a constant, a local or a
/// global (which holds a `num`, else the general form runs).
#[derive(Clone, Copy)]
enum Peek {
    /// A constant integer (a constant that is none is left to the general form).
    K(i32),
    L(u32),
    G(u32),
}

impl Peek {
    fn of(cx: &Cx, e: &Expr) -> Option<Peek> {
        if !cx.is_num(e) {
            return None;
        }
        match e.kind {
            ExprKind::Num(x) => f32_int(x).map(Peek::K),
            ExprKind::Local(s) => Some(Peek::L(s)),
            ExprKind::Global(g) => Some(Peek::G(g)),
            _ => None,
        }
    }

    /// The integer it holds, if it holds one within `i32`.
    #[inline(always)]
    fn int(self, it: &Interp) -> Option<i32> {
        let x = match self {
            Peek::K(i) => return Some(i),
            Peek::L(s) => match it.stack.get(it.bp + s as usize) {
                Some(Value::Num(x)) => *x,
                _ => return None,
            },
            Peek::G(g) => match it.globals.get(g as usize) {
                Some(Value::Num(x)) => *x,
                _ => return None,
            },
        };
        f32_int(x)
    }
}

/// A string read in place from a whole local or global (the general form reports one that
/// holds no string).
fn str_root(cx: &Cx, e: &Expr) -> Option<Root> {
    match e.kind {
        ExprKind::Local(s) if cx.plain_read(e) => Some(Root::Local(s)),
        ExprKind::Global(g) => Some(Root::Global(g)),
        _ => None,
    }
}

/// `dst := StrPart(s, pos, len)` with `s` a whole local or global and `pos`, `len`
/// constants or variables: one ASCII character (`len` 1) copied by its byte position
/// when the text before it is ASCII too; `general` (the statement's general form) for
/// anything else.
pub(crate) fn part(cx: &Cx, dst: Root, value: &Expr, general: StmtFn) -> StmtFn {
    let fast = match &value.kind {
        ExprKind::Native(n, args) if cx.standard_native(*n) == Some("StrPart") => match &args[..] {
            [Arg::Value(s), Arg::Value(pos), Arg::Value(len)] => {
                match (str_root(cx, s), Peek::of(cx, pos), Peek::of(cx, len)) {
                    (Some(_), _, Some(Peek::K(l))) if l != 1 => None,
                    (Some(s), Some(pos), Some(len)) => Some((s, pos, len)),
                    _ => None,
                }
            }
            _ => None,
        },
        _ => None,
    };
    match fast {
        Some((src, pos, len)) => Box::new(move |it, c| {
            if it.part_char(dst, src, pos, len) {
                Ok(())
            } else {
                general(it, c)
            }
        }),
        None => general,
    }
}

/// `dst := dst + x` with `x` a constant or a whole local or global other than `dst`:
/// appended in place when `dst` holds its text alone and the result stays within
/// [`MAX_STRING`] bytes; `general` for anything else.
pub(crate) fn append(cx: &Cx, dst: Root, x: &Expr, general: StmtFn) -> StmtFn {
    enum Src {
        Lit(Box<str>),
        Root(Root),
    }
    let src = match (&x.kind, str_root(cx, x)) {
        (ExprKind::Str(k), _) => Src::Lit(Box::from(&**k)),
        (_, Some(r)) => Src::Root(r),
        _ => return general,
    };
    if matches!(src, Src::Root(r) if r == dst) {
        return general;
    }
    Box::new(move |it, c| {
        let done = match &src {
            Src::Lit(k) => it.append_lit(dst, k),
            Src::Root(r) => it.append_root(dst, *r),
        };
        if done { Ok(()) } else { general(it, c) }
    })
}

/// Append `s` to `d` (a one-byte text without a copy call).
#[inline(always)]
pub(crate) fn push_text(d: &mut String, s: &str) {
    match s.as_bytes() {
        [b] if b.is_ascii() => d.push(char::from(*b)),
        _ => d.push_str(s),
    }
}

/// Are two texts equal (lengths first, short texts compared byte by byte without a
/// call)?
#[inline(always)]
pub(crate) fn eq_text(a: &str, b: &str) -> bool {
    match (a.as_bytes(), b.as_bytes()) {
        (a, b) if a.len() != b.len() => false,
        ([x], [y]) => x == y,
        (a, b) if a.len() <= 16 => a.iter().zip(b).all(|(x, y)| x == y),
        (a, b) => a == b,
    }
}

impl Interp {
    /// The slot of a whole local or global, to read.
    #[inline(always)]
    fn root_ref(&self, r: Root) -> Option<&Value> {
        match r {
            Root::Local(s) => self.stack.get(self.bp + s as usize),
            Root::Global(g) => self.globals.get(g as usize),
            Root::Ref(_) => None,
        }
    }

    /// The slot of a whole local or global, to write.
    #[inline(always)]
    fn root_mut(&mut self, r: Root) -> Option<&mut Value> {
        match r {
            Root::Local(s) => self.stack.get_mut(self.bp + s as usize),
            Root::Global(g) => self.globals.get_mut(g as usize),
            Root::Ref(_) => None,
        }
    }

    /// The slots of two different whole locals or globals: `dst` to write, `src` to read.
    #[inline(always)]
    fn root_pair(&mut self, dst: Root, src: Root) -> Option<(&mut Value, &Value)> {
        let bp = self.bp;
        match (dst, src) {
            (Root::Local(a), Root::Local(b)) => {
                let [x, y] = self
                    .stack
                    .get_disjoint_mut([bp + a as usize, bp + b as usize])
                    .ok()?;
                Some((x, &*y))
            }
            (Root::Global(a), Root::Global(b)) => {
                let [x, y] = self
                    .globals
                    .get_disjoint_mut([a as usize, b as usize])
                    .ok()?;
                Some((x, &*y))
            }
            (Root::Local(a), Root::Global(b)) => Some((
                self.stack.get_mut(bp + a as usize)?,
                self.globals.get(b as usize)?,
            )),
            (Root::Global(a), Root::Local(b)) => Some((
                self.globals.get_mut(a as usize)?,
                self.stack.get(bp + b as usize)?,
            )),
            _ => None,
        }
    }

    /// `dst := StrPart(src, pos, len)` when `len` is 1 and the text up to character
    /// `pos` is ASCII (false, nothing done, otherwise).
    #[inline(always)]
    fn part_char(&mut self, dst: Root, src: Root, pos: Peek, len: Peek) -> bool {
        let (Some(p), Some(1)) = (pos.int(self), len.int(self)) else {
            return false;
        };
        let Some(i) = usize::try_from(p).ok().filter(|&i| i > 0) else {
            return false;
        };
        let b = match self.root_ref(src) {
            Some(Value::Str(t)) => match t.as_bytes().get(..i) {
                Some(head) if head.is_ascii() => match head.last() {
                    Some(b) => *b,
                    None => return false,
                },
                _ => return false,
            },
            _ => return false,
        };
        match self.root_mut(dst) {
            Some(Value::Str(t)) => {
                t.set_ascii(b);
                true
            }
            _ => false,
        }
    }

    /// `dst := dst + k` in place (false, nothing done, when `dst` shares its text or the
    /// result could pass the limit).
    #[inline(always)]
    fn append_lit(&mut self, dst: Root, k: &str) -> bool {
        match self.root_mut(dst) {
            Some(Value::Str(t)) => match t.unique_mut() {
                Some(d) if d.len() + k.len() <= MAX_STRING => {
                    push_text(d, k);
                    true
                }
                _ => false,
            },
            _ => false,
        }
    }

    /// `dst := dst + src` in place, `src` another whole local or global (false, nothing
    /// done, when `dst` shares its text, `src` holds no string or the result could pass
    /// the limit).
    #[inline(always)]
    fn append_root(&mut self, dst: Root, src: Root) -> bool {
        match self.root_pair(dst, src) {
            Some((Value::Str(t), Value::Str(s))) => match t.unique_mut() {
                Some(d) if d.len() + s.len() <= MAX_STRING => {
                    push_text(d, s);
                    true
                }
                _ => false,
            },
            _ => false,
        }
    }
}
