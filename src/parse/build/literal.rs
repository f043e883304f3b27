//! Literals: numbers (decimal, exponent, hex/binary/octal) and strings (with `""`, `\\` and
//! `\hh` escapes).

use super::Builder;
use crate::ast::{Expr, ExprKind, UnaryOp};
use crate::parse::MAX_EXPR_DEPTH;
use crate::parse::error::ParseErrorKind;
use crate::parse::grammar::Pair;
use crate::source::Span;

/// The largest finite `num` (IEEE-754 single precision).
const NUM_MAX: f64 = f32::MAX as f64;

impl Builder<'_, '_> {
    /// The value of a `number` pair; out-of-range values are reported (and kept as parsed).
    pub(crate) fn number(&mut self, p: &Pair<'_>) -> f64 {
        self.number_text(self.text_of(p), self.span(p))
    }

    /// The value of the number literal `text` written at `span`.
    pub(crate) fn number_text(&mut self, text: &str, span: Span) -> f64 {
        let value = parse_number(text);
        match value {
            Some(v) if v.is_finite() && v.abs() <= NUM_MAX => v,
            _ => {
                self.error(ParseErrorKind::NumberOutOfRange {
                    span,
                    text: text.to_string(),
                });
                value.unwrap_or(f64::INFINITY)
            }
        }
    }

    /// The value of a `string` pair with escapes decoded; invalid escapes are reported and
    /// kept as written.
    pub(crate) fn string(&mut self, p: &Pair<'_>) -> String {
        self.string_text(self.text_of(p), self.start(p))
    }

    /// The value of the string literal `raw` (with its quotes) written at byte `start`.
    pub(crate) fn string_text(&mut self, raw: &str, start: usize) -> String {
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
                        self.error(ParseErrorKind::InvalidEscape {
                            span: Span::new(self.file, at, at + len),
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
}

impl Builder<'_, '_> {
    /// A `literal_aggregate` pair: the grammar has checked its shape; read it here.
    pub(crate) fn literal_aggregate(
        &mut self,
        p: &Pair<'_>,
        depth: usize,
    ) -> Option<(Expr, usize)> {
        let text = self.text_of(p);
        let base = self.start(p);
        let mut pos = 0;
        self.lit_aggregate(text, base, &mut pos, depth)
    }

    fn lit_aggregate(
        &mut self,
        t: &str,
        base: usize,
        pos: &mut usize,
        depth: usize,
    ) -> Option<(Expr, usize)> {
        if depth > MAX_EXPR_DEPTH {
            self.error(ParseErrorKind::ExpressionTooComplex {
                span: Span::new(self.file, base + *pos, base + t.len()),
                limit: MAX_EXPR_DEPTH,
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
            let Some((item, d)) = self.lit_item(t, base, pos, depth) else {
                self.scratch.truncate(mark);
                return None;
            };
            max = max.max(d);
            self.scratch.push(item);
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

    fn lit_item(
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
            b'[' => self.lit_aggregate(t, base, pos, depth + 1),
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
                let v = self.string_text(&t[start..*pos], base + start);
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
                let (e, d) = self.lit_item(t, base, pos, depth)?;
                let op = if c == b'-' {
                    UnaryOp::Neg
                } else {
                    UnaryOp::Plus
                };
                let span = span(*pos);
                Some((
                    Expr {
                        kind: ExprKind::Unary {
                            op,
                            expr: Box::new(e),
                        },
                        span,
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
                let v = self.number_text(&t[start..i], span(i));
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
