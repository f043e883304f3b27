//! Reading literals: numbers (decimal, exponent, hex/binary/octal), strings (with `""`, `\\`
//! and `\hh` escapes) and literal aggregates. The parser reads them with this code, and a
//! packed aggregate ([`super::ExprKind::PackedAggregate`]) is unpacked with the same code, so
//! its tree is the one the parser would have built.

use super::{Arg, ArgKind, DataDecl, EcoString, Expr, ExprKind, Storage, UnaryOp};
use crate::source::{SourceId, Span, Spanned};

/// The largest finite `num` (IEEE-754 single precision).
const NUM_MAX: f64 = f32::MAX as f64;

/// A problem found while reading a literal (the parser reports it with its own wording).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Problem {
    /// A number that is not a finite `num`.
    NumberOutOfRange {
        /// The number.
        span: Span,
        /// As written.
        text: String,
    },
    /// A `\` in a string that starts no valid escape.
    InvalidEscape {
        /// The escape.
        span: Span,
        /// As written.
        text: String,
    },
    /// An aggregate nested deeper than the reader's limit.
    TooDeep {
        /// From the aggregate that is too deep to the end of the text.
        span: Span,
    },
}

/// The value of the number literal `text` written at `span`; an out-of-range value is
/// reported in `errors` (and kept as parsed).
pub(crate) fn number_value(text: &str, span: Span, errors: &mut Vec<Problem>) -> f64 {
    let value = parse_number(text);
    match value {
        Some(v) if v.is_finite() && v.abs() <= NUM_MAX => v,
        _ => {
            errors.push(Problem::NumberOutOfRange {
                span,
                text: text.to_string(),
            });
            value.unwrap_or(f64::INFINITY)
        }
    }
}

/// The value of the string literal `raw` (with its quotes) written at byte `start` of `file`,
/// escapes decoded; an invalid escape is reported in `errors` and kept as written.
pub(crate) fn decode_string(
    raw: &str,
    file: SourceId,
    start: usize,
    errors: &mut Vec<Problem>,
) -> String {
    let inner = raw.get(1..raw.len().saturating_sub(1)).unwrap_or("");
    let mut out = String::with_capacity(inner.len());
    let mut it = inner.char_indices().peekable();
    while let Some((i, c)) = it.next() {
        match c {
            '"' => {
                // The grammar only lets `""` through.
                it.next();
                out.push('"');
            }
            '\\' => {
                let rest = &inner[i + 1..];
                if rest.starts_with('\\') {
                    it.next();
                    out.push('\\');
                } else if let Some(v) = rest
                    .get(..2)
                    .filter(|h| h.bytes().all(|b| b.is_ascii_hexdigit()))
                    .and_then(|h| u8::from_str_radix(h, 16).ok())
                {
                    it.next();
                    it.next();
                    out.push(v as char);
                } else {
                    // The backslash, the hex digits that follow, and the first other
                    // character (what makes the escape invalid), if not the quote.
                    let hex = rest
                        .bytes()
                        .take(2)
                        .take_while(u8::is_ascii_hexdigit)
                        .count();
                    let other = rest[hex..]
                        .chars()
                        .next()
                        .filter(|c| *c != '"' && hex < 2)
                        .map_or(0, char::len_utf8);
                    let len = 1 + hex + other;
                    let at = start + 1 + i;
                    errors.push(Problem::InvalidEscape {
                        span: Span::new(file, at, at + len),
                        text: inner[i..i + len].to_string(),
                    });
                    out.push('\\');
                }
            }
            c => out.push(c),
        }
    }
    out
}

/// The tree of the literal aggregate `text` written at byte `start` of `file`, which the
/// parser read without a diagnostic (see [`ExprKind::PackedAggregate`]).
pub(crate) fn unpack_aggregate(file: SourceId, text: &str, start: usize) -> Expr {
    let mut scratch = Vec::new();
    let mut read = LitReader {
        file,
        build: true,
        max_depth: usize::MAX,
        scratch: &mut scratch,
        errors: Vec::new(),
    };
    let mut pos = 0;
    match read.aggregate(text, start, &mut pos, 0) {
        Some((e, _)) => e,
        // (Not reached: the same text was read without a diagnostic when it was packed. An
        // empty aggregate is refused by every type, so it would not go unnoticed.)
        None => Expr {
            kind: ExprKind::Aggregate(Vec::new()),
            span: Span::new(file, start, start + text.len()),
        },
    }
}

/// Reads a literal aggregate whose shape the grammar has checked: builds its tree, or with
/// `build` false only checks its values and measures its depth (no allocation but for
/// strings). Problems are collected in `errors`, in source order.
pub(crate) struct LitReader<'s> {
    /// The file the text is in.
    pub(crate) file: SourceId,
    /// Build the tree (or only check and measure).
    pub(crate) build: bool,
    /// Aggregates nested deeper than this are a [`Problem::TooDeep`].
    pub(crate) max_depth: usize,
    /// Items of the lists being built, shared by the nested lists (see `aggregate`).
    pub(crate) scratch: &'s mut Vec<Expr>,
    /// What was found, in source order.
    pub(crate) errors: Vec<Problem>,
}

impl LitReader<'_> {
    /// The aggregate at `t[*pos..]` (`t` is written at byte `base` of the file), at nesting
    /// `depth`, and how deep its tree is; `pos` ends after its `]`.
    pub(crate) fn aggregate(
        &mut self,
        t: &str,
        base: usize,
        pos: &mut usize,
        depth: usize,
    ) -> Option<(Expr, usize)> {
        if depth > self.max_depth {
            self.errors.push(Problem::TooDeep {
                span: Span::new(self.file, base + *pos, base + t.len()),
            });
            return None;
        }
        let start = *pos;
        *pos += 1; // `[`
        // Items go to the shared scratch stack (nested aggregates push above them), then into
        // a vector of exactly their number: no reallocation while the list grows.
        let mark = self.scratch.len();
        let mut max = 0;
        loop {
            skip_trivia(t, pos);
            let Some((item, d)) = self.item(t, base, pos, depth) else {
                self.scratch.truncate(mark);
                return None;
            };
            max = max.max(d);
            if self.build {
                self.scratch.push(item);
            }
            skip_trivia(t, pos);
            match t.as_bytes().get(*pos) {
                Some(b',') => *pos += 1,
                _ => break,
            }
        }
        *pos += 1; // `]`
        let items: Vec<Expr> = self.scratch.drain(mark..).collect();
        Some((
            Expr {
                kind: ExprKind::Aggregate(items),
                span: Span::new(self.file, base + start, base + *pos),
            },
            max + 1,
        ))
    }

    fn item(
        &mut self,
        t: &str,
        base: usize,
        pos: &mut usize,
        depth: usize,
    ) -> Option<(Expr, usize)> {
        let b = t.as_bytes();
        let start = *pos;
        let file = self.file;
        let span = |end: usize| Span::new(file, base + start, base + end);
        match *b.get(start)? {
            b'[' => self.aggregate(t, base, pos, depth + 1),
            b'"' => {
                let mut i = start + 1;
                while i < b.len() {
                    if b[i] == b'"' {
                        if b.get(i + 1) == Some(&b'"') {
                            i += 2;
                            continue;
                        }
                        break;
                    }
                    i += 1;
                }
                *pos = i + 1;
                let raw = t.get(start..*pos).unwrap_or("");
                let v = decode_string(raw, file, base + start, &mut self.errors);
                Some((
                    Expr {
                        kind: ExprKind::Str(v),
                        span: span(*pos),
                    },
                    1,
                ))
            }
            c @ (b'+' | b'-') => {
                *pos += 1;
                skip_trivia(t, pos);
                let (e, d) = self.item(t, base, pos, depth)?;
                let op = if c == b'-' {
                    UnaryOp::Neg
                } else {
                    UnaryOp::Plus
                };
                let kind = if self.build {
                    ExprKind::Unary {
                        op,
                        expr: Box::new(e),
                    }
                } else {
                    e.kind
                };
                Some((
                    Expr {
                        kind,
                        span: span(*pos),
                    },
                    d + 1,
                ))
            }
            c if c.is_ascii_alphabetic() => {
                let n = t[start..]
                    .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                    .unwrap_or(t.len() - start);
                *pos = start + n;
                let v = t[start..*pos].eq_ignore_ascii_case("TRUE");
                Some((
                    Expr {
                        kind: ExprKind::Bool(v),
                        span: span(*pos),
                    },
                    1,
                ))
            }
            _ => {
                let mut i = start;
                while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
                    i += 1;
                }
                if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
                    i += 1;
                    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
                        i += 1;
                    }
                    while i < b.len() && b[i].is_ascii_digit() {
                        i += 1;
                    }
                }
                *pos = i;
                let v = number_value(&t[start..i], span(i), &mut self.errors);
                Some((
                    Expr {
                        kind: ExprKind::Num(v),
                        span: span(i),
                    },
                    1,
                ))
            }
        }
    }
}

/// The arguments of a procedure call statement from the text `t` that follows its name up to
/// and including the `;` (written at byte `start` of `file`), when every argument is a name, a
/// plain literal or a call of a function with such arguments: positional (`p10`, `-1.5`,
/// `"text"`, `TRUE`, `Offs(p10, 0, 0, 50)`) or optional (`\Switch`, `\Name:=value`). `None`
/// for anything else (the parser then keeps the tree it built, see [`super::CallArgs`]).
pub(crate) fn read_call_args(file: SourceId, t: &str, start: usize) -> Option<Vec<Arg>> {
    let mut scratch = Vec::new();
    let mut read = LitReader {
        file,
        build: true,
        max_depth: 0,
        scratch: &mut scratch,
        errors: Vec::new(),
    };
    let mut pos = 0;
    let out = read_args(&mut read, t, start, &mut pos, b';', 0)?;
    (pos == t.len() && read.errors.is_empty()).then_some(out)
}

/// The deepest nesting of function calls [`read_call_args`] reads (deeper ones are left to
/// the parser's tree).
const MAX_CALL_DEPTH: usize = 4;

/// The arguments at `t[*pos..]` up to the byte `close` (`;` after a procedure call's
/// arguments, `)` after a function call's), `depth` function calls deep; `pos` ends after
/// `close`.
fn read_args(
    read: &mut LitReader<'_>,
    t: &str,
    start: usize,
    pos: &mut usize,
    close: u8,
    depth: usize,
) -> Option<Vec<Arg>> {
    let b = t.as_bytes();
    let file = read.file;
    let span = |a: usize, z: usize| Span::new(file, start + a, start + z);
    let mut out = Vec::new();
    skip_trivia(t, pos);
    if b.get(*pos) == Some(&close) {
        *pos += 1;
        return Some(out);
    }
    loop {
        skip_trivia(t, pos);
        let at = *pos;
        if b.get(*pos) == Some(&b'\\') {
            *pos += 1;
            skip_trivia(t, pos);
            let name_at = *pos;
            let name = word(t, pos)?;
            let name = Spanned::new(EcoString::from(name), span(name_at, *pos));
            skip_trivia(t, pos);
            let value = if t[*pos..].starts_with(":=") {
                *pos += 2;
                skip_trivia(t, pos);
                Some(Box::new(call_value(read, t, start, pos, depth)?))
            } else {
                None
            };
            let end = value.as_ref().map_or(name.span.end, |v| v.span.end);
            out.push(Arg {
                kind: ArgKind::Optional { name, value },
                span: Span::new(file, start + at, end as usize),
            });
        } else {
            let e = call_value(read, t, start, pos, depth)?;
            out.push(Arg {
                span: e.span,
                kind: ArgKind::Positional(e),
            });
        }
        skip_trivia(t, pos);
        match b.get(*pos) {
            Some(b',') => *pos += 1,
            Some(b'\\') => {}
            Some(&c) if c == close => {
                *pos += 1;
                break;
            }
            _ => return None,
        }
    }
    Some(out)
}

/// The module data declaration `t` (its whole text, from its first keyword to its `;`,
/// written at byte `start` of `file`) when it has the simplest shape: `[LOCAL] [TASK]
/// VAR|PERS|CONST type name [:= value];` without array dimensions, the value a name, a plain
/// literal or a literal aggregate (kept packed, [`ExprKind::PackedAggregate`]). `None` for
/// anything else (the parser then keeps the tree it built, see [`super::PackedData`]).
///
/// `aggregate_end`, when known, is where a literal aggregate value ends in `t` (the parser has
/// just read it: it is not read again).
pub(crate) fn read_data_decl(
    file: SourceId,
    t: &str,
    start: usize,
    aggregate_end: Option<usize>,
) -> Option<DataDecl> {
    let span = |a: usize, z: usize| Span::new(file, start + a, start + z);
    let mut pos = 0;
    let head = read_data_head(t, &mut pos)?;
    let ident = |(a, z): (usize, usize)| Spanned::new(EcoString::from(&t[a..z]), span(a, z));
    let (local, task, storage) = (head.local, head.task, head.storage);
    let (ty, name) = (ident(head.ty), ident(head.name));
    skip_trivia(t, &mut pos);
    let init = if t[pos..].starts_with(":=") {
        pos += 2;
        skip_trivia(t, &mut pos);
        let mut scratch = Vec::new();
        let mut read = LitReader {
            file,
            build: false,
            max_depth: usize::MAX,
            scratch: &mut scratch,
            errors: Vec::new(),
        };
        let value = if t.as_bytes().get(pos) == Some(&b'[') {
            let at = pos;
            match aggregate_end {
                Some(end) if end > pos && end <= t.len() => pos = end,
                _ => {
                    read.aggregate(t, start, &mut pos, 0)?;
                }
            }
            Expr {
                kind: ExprKind::PackedAggregate(super::PackedAggregate::new()),
                span: span(at, pos),
            }
        } else {
            read.build = true;
            call_value(&mut read, t, start, &mut pos, MAX_CALL_DEPTH)?
        };
        if !read.errors.is_empty() {
            return None;
        }
        skip_trivia(t, &mut pos);
        Some(value)
    } else {
        None
    };
    (t.as_bytes().get(pos) == Some(&b';') && pos + 1 == t.len()).then(|| DataDecl {
        local,
        task,
        storage,
        ty,
        name,
        dims: Vec::new(),
        init,
        span: span(0, t.len()),
    })
}

/// The words before the value of a data declaration (see [`read_data_decl`]).
pub(crate) struct DataHead {
    /// `LOCAL` was written.
    pub(crate) local: bool,
    /// `TASK` was written.
    pub(crate) task: bool,
    /// `VAR`, `PERS` or `CONST`.
    pub(crate) storage: Storage,
    /// Where the type name is in the text.
    pub(crate) ty: (usize, usize),
    /// Where the data name is in the text.
    pub(crate) name: (usize, usize),
}

/// The keywords, type and name at the start of the data declaration `t`; `pos` ends after
/// the name.
pub(crate) fn read_data_head(t: &str, pos: &mut usize) -> Option<DataHead> {
    let (mut local, mut task) = (false, false);
    let storage = loop {
        skip_trivia(t, pos);
        let w = word(t, pos)?;
        if w.eq_ignore_ascii_case("LOCAL") && !local && !task {
            local = true;
        } else if w.eq_ignore_ascii_case("TASK") && !task {
            task = true;
        } else if w.eq_ignore_ascii_case("VAR") {
            break Storage::Var;
        } else if w.eq_ignore_ascii_case("PERS") {
            break Storage::Pers;
        } else if w.eq_ignore_ascii_case("CONST") {
            break Storage::Const;
        } else {
            return None;
        }
    };
    let mut ident = || {
        skip_trivia(t, pos);
        let at = *pos;
        word(t, pos)?;
        Some((at, *pos))
    };
    let ty = ident()?;
    let name = ident()?;
    Some(DataHead {
        local,
        task,
        storage,
        ty,
        name,
    })
}

/// A name (letters, digits, `_`, starting with a letter) at `t[*pos..]`; `pos` ends after it.
fn word<'t>(t: &'t str, pos: &mut usize) -> Option<&'t str> {
    let rest = t.get(*pos..)?;
    if !rest.starts_with(|c: char| c.is_ascii_alphabetic()) {
        return None;
    }
    let n = rest
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    *pos += n;
    rest.get(..n)
}

/// One argument value of [`read_call_args`]: a name, `TRUE`/`FALSE`, a number (with a sign),
/// a string, or a call of a function with such arguments (`depth` calls deep).
fn call_value(
    read: &mut LitReader<'_>,
    t: &str,
    start: usize,
    pos: &mut usize,
    depth: usize,
) -> Option<Expr> {
    let at = *pos;
    match *t.as_bytes().get(at)? {
        c if c.is_ascii_alphabetic() => {
            let w = word(t, pos)?;
            let span = Span::new(read.file, start + at, start + *pos);
            let mut open = *pos;
            skip_trivia(t, &mut open);
            if t.as_bytes().get(open) == Some(&b'(') {
                if depth >= MAX_CALL_DEPTH {
                    return None;
                }
                *pos = open + 1;
                let args = read_args(read, t, start, pos, b')', depth + 1)?;
                return Some(Expr {
                    kind: ExprKind::Call {
                        name: Box::new(Spanned::new(EcoString::from(w), span)),
                        args: args.into_boxed_slice(),
                    },
                    span: Span::new(read.file, start + at, start + *pos),
                });
            }
            let kind = if w.eq_ignore_ascii_case("TRUE") {
                ExprKind::Bool(true)
            } else if w.eq_ignore_ascii_case("FALSE") {
                ExprKind::Bool(false)
            } else {
                ExprKind::Name(Spanned::new(EcoString::from(w), span))
            };
            Some(Expr { kind, span })
        }
        b'"' | b'+' | b'-' | b'.' | b'0'..=b'9' => read.item(t, start, pos, 0).map(|(e, _)| e),
        _ => None,
    }
}

/// Skip white space and comments inside a literal aggregate.
fn skip_trivia(t: &str, pos: &mut usize) {
    let b = t.as_bytes();
    while let Some(&c) = b.get(*pos) {
        match c {
            b' ' | b'\t' | b'\n' | b'\r' | 0x0B | 0x0C => *pos += 1,
            b'!' => {
                while *pos < b.len() && b[*pos] != b'\n' && b[*pos] != b'\r' {
                    *pos += 1;
                }
            }
            c if c >= 0x80 => match t[*pos..].chars().next() {
                Some(ch) if ch.is_whitespace() => *pos += ch.len_utf8(),
                _ => return,
            },
            _ => return,
        }
    }
}

/// Parse a number literal as written (no sign).
pub(crate) fn parse_number(text: &str) -> Option<f64> {
    let b = text.as_bytes();
    // Most literals are small integers: read them directly (exact: below 2^53), the float
    // parser gives the same value.
    if !b.is_empty() && b.len() <= 15 && b.iter().all(u8::is_ascii_digit) {
        let v = b.iter().fold(0u64, |v, d| v * 10 + u64::from(d - b'0'));
        return Some(v as f64);
    }
    let radix = |digits: &str, r: u32| u64::from_str_radix(digits, r).ok().map(|v| v as f64);
    match b {
        [b'0', b'x' | b'X', ..] => radix(&text[2..], 16),
        [b'0', b'b' | b'B', ..] => radix(&text[2..], 2),
        [b'0', b'o' | b'O', ..] => radix(&text[2..], 8),
        _ => exact_decimal(b).or_else(|| text.parse::<f64>().ok()),
    }
}

/// Powers of ten that are exact in an `f64`.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// A decimal literal (`digits[.digits][e[+|-]digits]`) whose digits fit in 53 bits and whose
/// scale is at most 10^22 either way: one exact multiplication or division, hence correctly
/// rounded (Clinger's fast path, the same value as `str::parse`). `None` for anything else.
fn exact_decimal(b: &[u8]) -> Option<f64> {
    const LIMIT: u64 = 1 << 53;
    let mut mant: u64 = 0;
    let mut scale: i64 = 0;
    let mut i = 0;
    let mut digits = 0;
    while let Some(d) = b.get(i).filter(|c| c.is_ascii_digit()) {
        mant = mant * 10 + u64::from(d - b'0');
        if mant >= LIMIT {
            return None;
        }
        i += 1;
        digits += 1;
    }
    if b.get(i) == Some(&b'.') {
        i += 1;
        while let Some(d) = b.get(i).filter(|c| c.is_ascii_digit()) {
            mant = mant * 10 + u64::from(d - b'0');
            if mant >= LIMIT {
                return None;
            }
            scale -= 1;
            i += 1;
            digits += 1;
        }
    }
    if digits == 0 {
        return None;
    }
    if let Some(b'e' | b'E') = b.get(i) {
        i += 1;
        let negative = match b.get(i) {
            Some(b'-') => {
                i += 1;
                true
            }
            Some(b'+') => {
                i += 1;
                false
            }
            _ => false,
        };
        let start = i;
        let mut exp: i64 = 0;
        while let Some(d) = b.get(i).filter(|c| c.is_ascii_digit()) {
            exp = (exp * 10 + i64::from(d - b'0')).min(1_000);
            i += 1;
        }
        if i == start {
            return None;
        }
        scale += if negative { -exp } else { exp };
    }
    if i != b.len() {
        return None;
    }
    let m = mant as f64;
    match usize::try_from(scale.unsigned_abs()) {
        _ if mant == 0 => Some(0.0),
        Ok(k) if k < POW10.len() => Some(if scale < 0 {
            m / POW10[k]
        } else {
            m * POW10[k]
        }),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::parse_number;

    #[test]
    fn number_forms() {
        assert_eq!(parse_number("1"), Some(1.0));
        assert_eq!(parse_number("1."), Some(1.0));
        assert_eq!(parse_number(".5"), Some(0.5));
        assert_eq!(parse_number("9E+09"), Some(9e9));
        assert_eq!(parse_number("1e-3"), Some(0.001));
        assert_eq!(parse_number("1.e2"), Some(100.0));
        assert_eq!(parse_number("0xFF"), Some(255.0));
        assert_eq!(parse_number("0B101"), Some(5.0));
        assert_eq!(parse_number("0o17"), Some(15.0));
        assert_eq!(parse_number("0x"), None);
        assert_eq!(parse_number("0"), Some(0.0));
        assert_eq!(parse_number("007"), Some(7.0));
        assert_eq!(parse_number("999999999999999"), Some(999999999999999.0));
        assert_eq!(parse_number("9999999999999999"), Some(1e16));
        assert_eq!(
            parse_number("12345678901234567890"),
            Some(1.2345678901234567e19)
        );
        assert_eq!(parse_number("0.0356"), Some(0.0356));
        assert_eq!(parse_number("1e-300"), Some(1e-300));
        assert_eq!(parse_number("1e400"), Some(f64::INFINITY));
    }

    /// The fast path for decimals gives exactly what the standard parser gives.
    #[test]
    fn decimals_match_the_standard_parser() {
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = |n: u64| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x % n
        };
        for _ in 0..200_000 {
            let mut t = String::new();
            for _ in 0..next(18) {
                t.push(char::from(b'0' + next(10) as u8));
            }
            if next(3) > 0 {
                t.push('.');
                for _ in 0..next(18) {
                    t.push(char::from(b'0' + next(10) as u8));
                }
            }
            if next(3) == 0 {
                t.push(['e', 'E'][next(2) as usize]);
                t.push_str(["", "+", "-"][next(3) as usize]);
                t.push_str(&next(40).to_string());
            }
            let std = t.parse::<f64>().ok();
            if std.is_some() {
                assert_eq!(
                    parse_number(&t).map(f64::to_bits),
                    std.map(f64::to_bits),
                    "{t}"
                );
            }
        }
    }
}
