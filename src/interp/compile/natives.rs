//! The natives programs call most (`StrLen`, `StrPart`, `NumToStr`, and `num` functions of
//! one `num` such as `Sin`, `Sqrt`, `Trunc`), compiled straight into the call site while
//! they run their standard implementation: a string argument is read in place, numbers
//! come from their compiled form, and no argument list is built. Arguments are evaluated in order first, then checked with the same errors as
//! the natives in `builtins/` (what the differential test holds them to).

use super::num::{Leaf, num};
use super::val::{StrPart, TextFn, ValFn};
use super::{Code, Cx, NumFn};
use crate::interp::Interp;
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::value::Value;
use crate::ir::{Arg, Expr, NativeId, Ty};
use crate::source::Span;

/// `StrLen(s)`, `StrFind(s, p, set [\NotInSet])` or `StrMatch(s, p, pattern)` as a `num`
/// (NaN: an error is pending), when `n` is one of those and standard. The strings are read
/// in place; `StrFind` and `StrMatch` only when reading them cannot fail and their position
/// has no side effects (so the order their arguments are read in does not matter).
pub(crate) fn str_num(cx: &Cx, n: NativeId, args: &[Arg], span: Span) -> Option<NumFn> {
    let name = cx.standard_native(n)?;
    if name == "StrLen" {
        let [Arg::Value(s)] = args else {
            return None;
        };
        if cx.expr_ty(s) != Some(Ty::STRING) {
            return None;
        }
        let s = StrPart::new(cx, s);
        return Some(Box::new(move |it, c| {
            match s.with(it, c, |t| crate::functions::string::str_len(t) as f32) {
                Ok(x) => x,
                Err(u) => it.fail_nf(u),
            }
        }));
    }
    type Search = fn(&str, i64, &str, bool) -> crate::functions::RtResult<usize>;
    let (search, not_in_set): (Search, bool) = match (name, args) {
        ("StrFind", [_, _, _, Arg::Absent]) => (crate::functions::string::str_find, false),
        ("StrFind", [_, _, _, Arg::Switch]) => (crate::functions::string::str_find, true),
        ("StrMatch", [_, _, _]) => (
            |s, p, pat, _| crate::functions::string::str_match(s, p, pat),
            false,
        ),
        _ => return None,
    };
    let (s, pos, set) = (
        value_arg(args, 0)?,
        value_arg(args, 1)?,
        value_arg(args, 2)?,
    );
    if cx.expr_ty(s) != Some(Ty::STRING)
        || cx.expr_ty(set) != Some(Ty::STRING)
        || !cx.is_num(pos)
        || !(cx.plain_read(s) && cx.plain_read(set) && super::simple::pure(pos))
    {
        return None;
    }
    let (s, set) = (StrPart::new(cx, s), StrPart::new(cx, set));
    let pos = NumArg::new(cx, pos);
    Some(Box::new(move |it, c| {
        let r = it.str_search(c, &s, &pos, &set, span, |t, p, k| {
            search(t, p, k, not_in_set)
        });
        match r {
            Ok(i) => i as f32,
            Err(u) => it.fail_nf(u),
        }
    }))
}

/// A `num` function of one `num` (`Sin`, `Sqrt`, `Abs`, `Trunc` …) compiled at its call
/// site (NaN: an error is pending), when `n` is one of those and standard.
pub(crate) fn math(cx: &Cx, n: NativeId, args: &[Arg], span: Span) -> Option<NumFn> {
    use crate::functions::math as m;
    type F = fn(f64) -> crate::functions::RtResult<f64>;
    let name = cx.standard_native(n)?;
    let x = match args {
        [Arg::Value(x)] | [Arg::Value(x), Arg::Absent] if cx.is_num(x) => num(cx, x),
        _ => return None,
    };
    /// How the result is computed.
    enum How {
        /// `Round`/`Trunc` to whole numbers: the fast rule, else the library's.
        Whole(
            fn(f32) -> f32,
            fn(f32, i32) -> crate::functions::RtResult<f32>,
        ),
        /// A library function on f64, its result rounded to `num`.
        Lib(F),
    }
    let how = match (name, args.len()) {
        ("Round", 2) => How::Whole(f32::round, m::round_num),
        ("Trunc", 2) => How::Whole(f32::trunc, m::trunc_num),
        ("Abs", 1) => How::Lib(|v| Ok(m::abs(v))),
        ("Sqrt", 1) => How::Lib(m::sqrt),
        ("Exp", 1) => How::Lib(m::exp),
        ("Sin", 1) => How::Lib(m::sin),
        ("Cos", 1) => How::Lib(m::cos),
        ("Tan", 1) => How::Lib(m::tan),
        ("ASin", 1) => How::Lib(m::asin),
        ("ACos", 1) => How::Lib(m::acos),
        ("ATan", 1) => How::Lib(m::atan),
        _ => return None,
    };
    Some(Box::new(move |it, c| {
        let v = x(it, c);
        if v.is_nan() {
            return v;
        }
        let r = match how {
            How::Whole(f, lib) => match crate::interp::builtins::whole(v, 0, f) {
                Some(r) => Ok(r),
                None => lib(v, 0),
            },
            How::Lib(f) => f(v as f64).and_then(m::num_from_f64),
        };
        match r {
            Ok(r) => r,
            Err(e) => {
                let u = it.rt_error(e, span);
                it.fail_nf(u)
            }
        }
    }))
}

/// A string function compiled at its call site, if `n` is one of those and standard.
pub(crate) fn value(cx: &Cx, n: NativeId, args: &[Arg], span: Span) -> Option<ValFn> {
    let name = cx.standard_native(n)?;
    if let Some(f) = text(cx, n, args, span) {
        // Built in a scratch buffer: one allocation for the value, none for a text of
        // one ASCII character (see `Value::str`).
        return Some(Box::new(move |it, c| {
            let mut buf = it.strbufs.pop().unwrap_or_default();
            buf.clear();
            let r = f(it, c, &mut buf).map(|()| Value::str(&buf));
            it.strbufs.push(buf);
            r
        }));
    }
    match name {
        "StrLen" | "StrFind" | "StrMatch" => {
            let f = str_num(cx, n, args, span)?;
            Some(Box::new(move |it, c| {
                let x = f(it, c);
                if x.is_nan() {
                    return Err(it.take_pending(span));
                }
                Ok(Value::Num(x))
            }))
        }
        "StrPart" => {
            // The string is read first, into a scratch buffer (the other arguments may
            // change it).
            let (s, pos, len) = str_part_args(cx, args)?;
            let s = StrPart::new(cx, s);
            let (pos, len) = (NumArg::new(cx, pos), NumArg::new(cx, len));
            Some(Box::new(move |it, c| it.str_part(c, &s, &pos, &len, span)))
        }
        _ => {
            let f = math(cx, n, args, span)?;
            Some(Box::new(move |it, c| {
                let x = f(it, c);
                if x.is_nan() {
                    return Err(it.take_pending(span));
                }
                Ok(Value::Num(x))
            }))
        }
    }
}

/// A `num` argument: a constant or a variable read inline, anything else compiled.
pub(crate) enum NumArg {
    Leaf(Leaf, Span),
    Fn(NumFn, Span),
}

impl NumArg {
    fn new(cx: &Cx, e: &Expr) -> NumArg {
        match Leaf::of(cx, e) {
            Some(l @ (Leaf::K(_) | Leaf::L(..) | Leaf::G(..))) => NumArg::Leaf(l, e.span),
            _ => NumArg::Fn(num(cx, e), e.span),
        }
    }
}

/// Argument `k` of a native call, when it is a value.
fn value_arg(args: &[Arg], k: usize) -> Option<&Expr> {
    match args.get(k) {
        Some(Arg::Value(e)) => Some(e),
        _ => None,
    }
}

/// The string, position and length of a `StrPart` call, when they are known to be a
/// string and two `num`s.
fn str_part_args<'a>(cx: &Cx, args: &'a [Arg]) -> Option<(&'a Expr, &'a Expr, &'a Expr)> {
    let (s, pos, len) = (
        value_arg(args, 0)?,
        value_arg(args, 1)?,
        value_arg(args, 2)?,
    );
    (args.len() == 3 && cx.expr_ty(s) == Some(Ty::STRING) && cx.is_num(pos) && cx.is_num(len))
        .then_some((s, pos, len))
}

/// A standard `NumToStr` (without `\Exp`) or `StrPart` whose string is read in place,
/// compiled to append its text to a buffer (no value built), if `n` is one of those.
pub(crate) fn text(cx: &Cx, n: NativeId, args: &[Arg], span: Span) -> Option<TextFn> {
    match cx.standard_native(n)? {
        "StrPart" => {
            // A string read that cannot fail, with numbers that have no side effects: the
            // numbers may go first and the string be read in place after them.
            let (s, pos, len) = str_part_args(cx, args)?;
            if !(cx.plain_read(s) && super::simple::pure(pos) && super::simple::pure(len)) {
                return None;
            }
            let s = StrPart::new(cx, s);
            let (pos, len) = (NumArg::new(cx, pos), NumArg::new(cx, len));
            Some(Box::new(move |it, c, buf| {
                let (p, l) = (it.num_arg(c, &pos)?, it.num_arg(c, &len)?);
                let (p, l) = (it.int_arg(p, "ChPos", span)?, it.int_arg(l, "Len", span)?);
                match s.with(it, c, |t| part_into(t, p, l, buf))? {
                    Ok(()) => Ok(()),
                    Err(e) => Err(it.rt_error(e, span)),
                }
            }))
        }
        "NumToStr" => {
            let (x, dec) = (value_arg(args, 0)?, value_arg(args, 1)?);
            if args.len() != 3
                || !matches!(args[2], Arg::Absent)
                || !cx.is_num(x)
                || !cx.is_num(dec)
            {
                return None;
            }
            let (x, dec) = (NumArg::new(cx, x), NumArg::new(cx, dec));
            Some(Box::new(move |it, c, buf| {
                let (xv, d) = (it.num_arg(c, &x)?, it.num_arg(c, &dec)?);
                let d = it.int_arg(d, "Dec", span)?.clamp(-1, 99) as i32;
                let mut digits = [0u8; 12];
                match whole_digits(xv, d, &mut digits) {
                    Some(t) => push_ascii(buf, t),
                    None => buf.push_str(&it.num_to_str(xv, d, span)?),
                }
                Ok(())
            }))
        }
        _ => None,
    }
}

/// `StrPart(text, p, l)` with integer arguments.
fn part(text: &str, p: i64, l: i64) -> crate::functions::RtResult<Value> {
    match crate::functions::string::ascii_part(text, p, l) {
        Some(t) => Ok(Value::str(t)),
        None => crate::functions::string::str_part(text, p, l).map(|out| Value::Str(out.into())),
    }
}

/// [`part`] appended to `buf`.
fn part_into(text: &str, p: i64, l: i64, buf: &mut String) -> crate::functions::RtResult<()> {
    match crate::functions::string::ascii_part(text, p, l) {
        Some(t) => buf.push_str(t),
        None => buf.push_str(&crate::functions::string::str_part(text, p, l)?),
    }
    Ok(())
}

/// Append ASCII bytes (digits, a sign) to `buf` (no UTF-8 check of the bytes as a whole).
#[inline(always)]
fn push_ascii(buf: &mut String, bytes: &[u8]) {
    buf.reserve(bytes.len());
    for &b in bytes {
        buf.push(char::from(b));
    }
}

/// `NumToStr(x, 0)` of an integer below 2^24 in magnitude (the text `int_to_str` writes),
/// written into `buf` (`dec` must be 0): its ASCII bytes.
fn whole_digits(x: f32, dec: i32, buf: &mut [u8; 12]) -> Option<&[u8]> {
    let i = crate::interp::value::f32_int(x)?;
    if dec != 0 || i.unsigned_abs() >= 16_777_216 {
        return None;
    }
    let mut k = buf.len();
    let mut n = i.unsigned_abs();
    loop {
        k -= 1;
        buf[k] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    if i < 0 {
        k -= 1;
        buf[k] = b'-';
    }
    buf.get(k..)
}

impl Interp {
    /// An evaluated `num` argument.
    #[inline(always)]
    fn num_arg(&mut self, c: &Code, a: &NumArg) -> Exec<f32> {
        let (x, span) = match a {
            NumArg::Leaf(l, span) => (l.get(self, c), *span),
            NumArg::Fn(f, span) => (f(self, c), *span),
        };
        if x.is_nan() {
            return Err(self.take_pending(span));
        }
        Ok(x)
    }

    /// An integer argument of a native called at `span` (as `Ctx::int`).
    #[inline(always)]
    fn int_arg(&self, x: f32, what: &str, span: Span) -> Exec<i64> {
        // A whole number within i32 (every position and length a program uses) without
        // the floating-point `fract` (a library call on this target).
        if let Some(i) = crate::interp::value::f32_int(x) {
            return Ok(i as i64);
        }
        self.int_arg_slow(x, what, span)
    }

    #[cold]
    #[inline(never)]
    fn int_arg_slow(&self, x: f32, what: &str, span: Span) -> Exec<i64> {
        let x = x as f64;
        if x.fract() != 0.0 || !x.is_finite() {
            return Err(self.error(
                errnum::ERR_ARGVALERR,
                span,
                format!("{what} must be an integer, not {x}"),
            ));
        }
        Ok(x as i64)
    }

    /// A search `f(text, position, set)` of `StrFind` / `StrMatch` (the set read in place
    /// when it is a constant, else copied first).
    #[inline(always)]
    fn str_search(
        &mut self,
        c: &Code,
        s: &StrPart,
        pos: &NumArg,
        set: &StrPart,
        span: Span,
        f: impl Fn(&str, i64, &str) -> crate::functions::RtResult<usize>,
    ) -> Exec<usize> {
        let p = self.num_arg(c, pos)?;
        let p = self.int_arg(p, "ChPos", span)?;
        let r = match set {
            StrPart::Lit(k) => s.with(self, c, |t| f(t, p, k))?,
            _ => {
                let mut k = self.strbufs.pop().unwrap_or_default();
                k.clear();
                let r = set
                    .with(self, c, |t| k.push_str(t))
                    .and_then(|()| s.with(self, c, |t| f(t, p, &k)));
                self.strbufs.push(k);
                r?
            }
        };
        r.map_err(|e| self.rt_error(e, span))
    }

    fn str_part(
        &mut self,
        c: &Code,
        s: &StrPart,
        pos: &NumArg,
        len: &NumArg,
        span: Span,
    ) -> Exec<Value> {
        // The text is read before the other arguments are evaluated.
        let mut text = self.strbufs.pop().unwrap_or_default();
        text.clear();
        let r = (|| {
            s.with(self, c, |t| text.push_str(t))?;
            let (p, l) = (self.num_arg(c, pos)?, self.num_arg(c, len)?);
            let (p, l) = (
                self.int_arg(p, "ChPos", span)?,
                self.int_arg(l, "Len", span)?,
            );
            part(&text, p, l).map_err(|e| self.rt_error(e, span))
        })();
        self.strbufs.push(text);
        r
    }

    /// The text of `NumToStr(x, d)` of a number no faster rule wrote (`d` clamped).
    #[inline(never)]
    fn num_to_str(&mut self, x: f32, d: i32, span: Span) -> Exec<String> {
        if let Some(s) = crate::interp::builtins::int_to_str(x, d) {
            return Ok(s);
        }
        let s = crate::functions::format::num_to_str(x, d, false)
            .map_err(|e| self.rt_error(e, span))?;
        let n = s.chars().count();
        if n > crate::interp::value::MAX_STRING {
            return Err(self.error(
                errnum::ERR_STRTOOLNG,
                span,
                format!(
                    "the result would have {n} characters (at most {})",
                    crate::interp::value::MAX_STRING
                ),
            ));
        }
        Ok(s)
    }
}

#[cfg(test)]
mod tests {
    use super::whole_digits;

    fn whole_text(x: f32) -> Option<String> {
        whole_digits(x, 0, &mut [0u8; 12]).map(|b| String::from_utf8_lossy(b).into_owned())
    }

    /// The stack-written text of a whole number is the one `NumToStr(x, 0)` writes.
    #[test]
    fn whole_text_matches_num_to_str() {
        for x in [
            0.0f32,
            -0.0,
            1.0,
            7.0,
            -7.0,
            9.0,
            10.0,
            99.0,
            -100.0,
            12345.0,
            16_777_215.0,
            -16_777_215.0,
        ] {
            let want = crate::interp::builtins::int_to_str(x, 0).expect("a whole number");
            assert_eq!(whole_text(x), Some(want), "{x}");
        }
        assert_eq!(whole_text(0.5), None);
        assert_eq!(whole_text(16_777_216.0), None);
        assert_eq!(whole_text(f32::NAN), None);
        assert_eq!(
            whole_digits(1.0, 1, &mut [0u8; 12]),
            None,
            "decimals go the general way"
        );
    }
}
