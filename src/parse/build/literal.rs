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
        self.number_text(p.as_str(), self.span(p))
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
        self.string_text(p.as_str(), self.start(p))
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
        let text = p.as_str();
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
        let mut items = Vec::new();
        let mut max = 0;
        loop {
            skip_trivia(t, pos);
            let (item, d) = self.lit_item(t, base, pos, depth)?;
            max = max.max(d);
            items.push(item);
            skip_trivia(t, pos);
            match t.as_bytes().get(*pos) {
                Some(b',') => *pos += 1,
                _ => break,
            }
        }
        *pos += 1; // `]`
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
                while *pos < b.len() && b[*pos] != b'\n' {
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
    let radix = |digits: &str, r: u32| u64::from_str_radix(digits, r).ok().map(|v| v as f64);
    let lower = |s: &str| s.get(..2).map(|p| p.to_ascii_lowercase());
    match lower(text).as_deref() {
        Some("0x") => radix(&text[2..], 16),
        Some("0b") => radix(&text[2..], 2),
        Some("0o") => radix(&text[2..], 8),
        _ => text.parse::<f64>().ok(),
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
    }
}
