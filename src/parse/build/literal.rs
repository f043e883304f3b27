//! Literals: numbers (decimal, exponent, hex/binary/octal) and strings (with `""`, `\\` and
//! `\hh` escapes).

use super::Builder;
use crate::parse::error::ParseErrorKind;
use crate::parse::grammar::Pair;
use crate::source::Span;

/// The largest finite `num` (IEEE-754 single precision).
const NUM_MAX: f64 = f32::MAX as f64;

impl Builder<'_, '_> {
    /// The value of a `number` pair; out-of-range values are reported (and kept as parsed).
    pub(crate) fn number(&mut self, p: &Pair<'_>) -> f64 {
        let text = p.as_str();
        let value = parse_number(text);
        match value {
            Some(v) if v.is_finite() && v.abs() <= NUM_MAX => v,
            _ => {
                self.error(ParseErrorKind::NumberOutOfRange {
                    span: self.span(p),
                    text: text.to_string(),
                });
                value.unwrap_or(f64::INFINITY)
            }
        }
    }

    /// The value of a `string` pair with escapes decoded; invalid escapes are reported and
    /// kept as written.
    pub(crate) fn string(&mut self, p: &Pair<'_>) -> String {
        let raw = p.as_str();
        let start = p.as_span().start();
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
                        let len = 1 + rest
                            .chars()
                            .take(2)
                            .take_while(|c| *c != '"')
                            .map(char::len_utf8)
                            .sum::<usize>();
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
