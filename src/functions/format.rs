//! RAPID text output and input: TPWrite/ValToStr number formatting, NumToStr/DnumToStr, record text, and StrToVal parsing.
//!
//! # Decisions (rapidvc; the ABB rules are recalled, not documented — each is pinned below)
//!
//! **Digits.** Every conversion starts from the shortest decimal text that reads back as the
//! same value (for a `num`, the shortest text that round-trips through `f32`) and rounds that
//! decimal half away from zero. So `0.385` prints as `0.39` with two decimals even though the
//! stored `f32` is 0.38499999…
//!
//! **`num` ([`format_num`]; TPWrite `\Num`, ValToStr, `\Pos`/`\Orient` components):**
//! 1. *Integer rule*: when the fractional part of |v| is below 0.000005 or above 0.999995
//!    and the rounded integer is at most 8 388 608 (2²³, the largest integer `num` is
//!    documented to store exactly), the value prints as that integer: `23` → `23`,
//!    `2.9999999` → `3`, `1234567` → `1234567`, `8388608` → `8388608`, `0.000001` → `0`
//!    (the rule also applies below 1, as the recalled TPWrite text says). A negative value
//!    that rounds to 0 prints `0`.
//! 2. Otherwise C's `%G` with 6 significant digits: trailing zeros removed, exponent form
//!    when the decimal exponent is below −4 or at least 6, written `E`, a sign and at least
//!    two digits: `1.141367` → `1.14137`, `0.000494947` → `0.000494947`, `9.60894E-05`,
//!    `123456.7` → `123457`, `1234567.5` → `1.23457E+06`, `9E9` → `9E+09`,
//!    `16777216` → `1.67772E+07` (integers above 2²³ take this branch).
//! 3. NaN/infinity (which the interpreter never stores) print as `NAN`, `INF`, `-INF`.
//!
//! **`dnum` ([`format_dnum`]; TPWrite `\Dnum`, ValToStr):** `%G` with 15 significant
//! digits, no integer rule (`%.15G` already prints every integer below 10¹⁵ in full):
//! `0.1 + 0.2` → `0.3`, `123456789012345` → `123456789012345`, `1E15` → `1E+15`.
//!
//! **`bool`:** `TRUE` / `FALSE`.
//!
//! **Records and arrays** ([`format_list`], [`format_pos`], [`format_orient`]): `[a,b,c]`,
//! components comma-separated with no spaces, nested for sub-records:
//! `[[1,2,3],[1,0,0,0]]`.
//!
//! **Strings in ValToStr** ([`quote_string`]): written as a RAPID string literal, in double
//! quotes, `"` doubled, `\` doubled, and control characters (below 0x20, 0x7F–0x9F) as
//! `\hh` with upper-case hex. This applies to string components of records (`wobjdata`'s
//! `ufmec`) and, by the same rule, to a string passed to ValToStr on its own, so that
//! `StrToVal(ValToStr(x), y)` gives `y = x` for every value type.
//!
//! **NumToStr / DnumToStr** ([`num_to_str`], [`dnum_to_str`]): `dec` decimals, rounded half
//! away from zero on the decimal text, **zero-padded** (`NumToStr(2, 2)` → `2.00`), no sign
//! on a result that rounds to zero (`NumToStr(-0.001, 2)` → `0.00`). With `\Exp`: one digit,
//! `dec` decimals and a C-style exponent (`NumToStr(0.38521, 3 \Exp)` → `3.852E-01`).
//! `dec` must be 0–15 (`ERR_ARGVALERR`); a result longer than 80 characters is
//! `ERR_STRTOOLNG` (only possible for huge `dnum` values). `NumToStr(v, d)` is always the
//! text of `Round(v \Dec:=d)`.
//!
//! **StrToVal** ([`parse_value`] and the typed `str_to_*`): the text of a RAPID literal
//! value: an optionally signed decimal number (`-1.5`, `.5`, `1.`, `9E+09`, no hex),
//! `TRUE`/`FALSE` in any case, a quoted string with RAPID escapes, or an aggregate
//! `[…, …]` of those (nested). Whitespace around tokens is allowed; anything else, an empty
//! aggregate, trailing text, or a number outside the target type's range is a failure
//! (`None`, which StrToVal returns as FALSE). A string target needs the quoted form.

use super::decimal::{Decimal, Mode};
use super::math::check_dec;
use super::string::check_len;
use super::{RtError, RtResult};

/// The error type of the formatting functions (the runtime library's [`RtError`]).
pub type FormatError = RtError;

/// The largest integer the `num` integer rule prints in full (2²³).
const NUM_INT_RULE_MAX: f64 = 8_388_608.0;

fn non_finite(v: f64) -> String {
    if v.is_nan() {
        "NAN".to_string()
    } else if v > 0.0 {
        "INF".to_string()
    } else {
        "-INF".to_string()
    }
}

/// `%G` with `prec` significant digits on the decimal `d`.
fn format_g(mut d: Decimal, prec: u32) -> String {
    d.round_significant(prec);
    if d.is_zero() {
        return "0".to_string();
    }
    let x = d.sci_exponent();
    if x < -4 || x >= prec as i32 {
        d.to_sci_trimmed()
    } else {
        d.to_fixed_trimmed()
    }
}

/// A `num` as TPWrite `\Num` and ValToStr write it (see the module doc).
pub fn format_num(v: f32) -> String {
    let Some(d) = Decimal::from_f32(v) else {
        return non_finite(v as f64);
    };
    let x = v as f64;
    let ax = x.abs();
    let frac = ax - ax.floor();
    if ax.round() <= NUM_INT_RULE_MAX && !(0.000005..=0.999995).contains(&frac) {
        let n = x.round() as i64;
        return n.to_string();
    }
    format_g(d, 6)
}

/// A `dnum` as TPWrite `\Dnum` and ValToStr write it (`%G`, 15 significant digits).
pub fn format_dnum(v: f64) -> String {
    match Decimal::from_f64(v) {
        Some(d) => format_g(d, 15),
        None => non_finite(v),
    }
}

/// `TRUE` or `FALSE`.
pub fn format_bool(b: bool) -> &'static str {
    if b { "TRUE" } else { "FALSE" }
}

/// `NumToStr(Val, Dec [\Exp])`.
pub fn num_to_str(value: f32, dec: i32, exp: bool) -> RtResult<String> {
    let dec = check_dec("NumToStr", dec)?;
    let d = Decimal::from_f32(value).ok_or(RtError::NumLimit {
        what: "NumToStr",
        ty: "num",
    })?;
    fixed_or_exp(d, dec, exp)
}

/// `DnumToStr(Val, Dec [\Exp])`.
pub fn dnum_to_str(value: f64, dec: i32, exp: bool) -> RtResult<String> {
    let dec = check_dec("DnumToStr", dec)?;
    let d = Decimal::from_f64(value).ok_or(RtError::NumLimit {
        what: "DnumToStr",
        ty: "dnum",
    })?;
    fixed_or_exp(d, dec, exp)
}

fn fixed_or_exp(mut d: Decimal, dec: u32, exp: bool) -> RtResult<String> {
    let s = if exp {
        d.round_significant(dec + 1);
        d.to_sci(dec)
    } else {
        d.cut_decimals(dec, Mode::Round);
        d.to_fixed(dec)
    };
    check_len(&s)?;
    Ok(s)
}

/// `[a,b,c]`: components already formatted, joined with `,` and no spaces.
pub fn format_list<I, S>(items: I) -> String
where
    I: IntoIterator<Item = S>,
    S: AsRef<str>,
{
    let mut out = String::from("[");
    for (i, item) in items.into_iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        out.push_str(item.as_ref());
    }
    out.push(']');
    out
}

/// A `pos` as TPWrite `\Pos` writes it: `[x,y,z]`.
pub fn format_pos(p: &[f32; 3]) -> String {
    format_list(p.iter().map(|&c| format_num(c)))
}

/// An `orient` as TPWrite `\Orient` writes it: `[q1,q2,q3,q4]`.
pub fn format_orient(q: &[f32; 4]) -> String {
    format_list(q.iter().map(|&c| format_num(c)))
}

/// A `pose` as ValToStr writes it: `[[x,y,z],[q1,q2,q3,q4]]`.
pub fn format_pose(trans: &[f32; 3], rot: &[f32; 4]) -> String {
    format_list([format_pos(trans), format_orient(rot)])
}

/// A string as a RAPID string literal (for ValToStr): quotes, `""`, `\\`, `\hh`.
pub fn quote_string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\"\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 || (0x7f..=0x9f).contains(&(c as u32)) => {
                out.push_str(&format!("\\{:02X}", c as u32));
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A value read from RAPID literal text by [`parse_value`].
#[derive(Clone, Debug, PartialEq)]
pub enum LitValue {
    /// A number, as parsed in `f64` (narrow it with [`LitValue::as_num`]).
    Num(f64),
    /// `TRUE` or `FALSE`.
    Bool(bool),
    /// A string literal, escapes decoded.
    Str(String),
    /// An aggregate `[…]` (never empty).
    List(Vec<LitValue>),
}

impl LitValue {
    /// The value as a `num` (a number within the `f32` range).
    pub fn as_num(&self) -> Option<f32> {
        match self {
            LitValue::Num(v) => {
                let n = *v as f32;
                n.is_finite().then_some(n + 0.0)
            }
            _ => None,
        }
    }

    /// The value as a `dnum`.
    pub fn as_dnum(&self) -> Option<f64> {
        match self {
            LitValue::Num(v) if v.is_finite() => Some(*v + 0.0),
            _ => None,
        }
    }

    /// The value as a `bool`.
    pub fn as_bool(&self) -> Option<bool> {
        match self {
            LitValue::Bool(b) => Some(*b),
            _ => None,
        }
    }

    /// The value as a `string`.
    pub fn as_str(&self) -> Option<&str> {
        match self {
            LitValue::Str(s) => Some(s),
            _ => None,
        }
    }

    /// The components of an aggregate.
    pub fn as_list(&self) -> Option<&[LitValue]> {
        match self {
            LitValue::List(items) => Some(items),
            _ => None,
        }
    }

    /// An aggregate of exactly `N` nums.
    pub fn as_nums<const N: usize>(&self) -> Option<[f32; N]> {
        let items = self.as_list()?;
        if items.len() != N {
            return None;
        }
        let mut out = [0.0f32; N];
        for (slot, item) in out.iter_mut().zip(items) {
            *slot = item.as_num()?;
        }
        Some(out)
    }
}

/// Parse the text of a RAPID literal value (StrToVal's input). `None` when the text is not
/// exactly one value.
pub fn parse_value(text: &str) -> Option<LitValue> {
    let mut p = LitParser {
        chars: text.chars().collect(),
        i: 0,
        depth: 0,
    };
    let v = p.value()?;
    p.skip_ws();
    (p.i == p.chars.len()).then_some(v)
}

/// StrToVal for `num`.
pub fn str_to_num(text: &str) -> Option<f32> {
    parse_value(text)?.as_num()
}

/// StrToVal for `dnum`.
pub fn str_to_dnum(text: &str) -> Option<f64> {
    parse_value(text)?.as_dnum()
}

/// StrToVal for `bool` (`TRUE`/`FALSE` in any case).
pub fn str_to_bool(text: &str) -> Option<bool> {
    parse_value(text)?.as_bool()
}

/// StrToVal for `string` (the quoted literal form).
pub fn str_to_string(text: &str) -> Option<String> {
    match parse_value(text)? {
        LitValue::Str(s) => Some(s),
        _ => None,
    }
}

/// StrToVal for `pos`: `[x,y,z]`.
pub fn str_to_pos(text: &str) -> Option<[f32; 3]> {
    parse_value(text)?.as_nums::<3>()
}

/// StrToVal for `orient`: `[q1,q2,q3,q4]`.
pub fn str_to_orient(text: &str) -> Option<[f32; 4]> {
    parse_value(text)?.as_nums::<4>()
}

/// StrToVal for `pose`: `[[x,y,z],[q1,q2,q3,q4]]`.
pub fn str_to_pose(text: &str) -> Option<([f32; 3], [f32; 4])> {
    let v = parse_value(text)?;
    match v.as_list()? {
        [t, r] => Some((t.as_nums::<3>()?, r.as_nums::<4>()?)),
        _ => None,
    }
}

/// Maximum aggregate nesting StrToVal accepts (RAPID has 3-D arrays of nested records; 32
/// is far beyond any real value and bounds the recursion).
const MAX_DEPTH: usize = 32;

struct LitParser {
    chars: Vec<char>,
    i: usize,
    depth: usize,
}

impl LitParser {
    fn peek(&self) -> Option<char> {
        self.chars.get(self.i).copied()
    }

    fn bump(&mut self) -> Option<char> {
        let c = self.peek()?;
        self.i += 1;
        Some(c)
    }

    fn skip_ws(&mut self) {
        while self.peek().is_some_and(char::is_whitespace) {
            self.i += 1;
        }
    }

    fn value(&mut self) -> Option<LitValue> {
        self.skip_ws();
        match self.peek()? {
            '[' => self.list(),
            '"' => self.string().map(LitValue::Str),
            c if c.is_ascii_alphabetic() => self.word(),
            _ => self.number().map(LitValue::Num),
        }
    }

    fn list(&mut self) -> Option<LitValue> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return None;
        }
        self.bump(); // '['
        let mut items = Vec::new();
        loop {
            items.push(self.value()?);
            self.skip_ws();
            match self.bump()? {
                ',' => continue,
                ']' => break,
                _ => return None,
            }
        }
        self.depth -= 1;
        Some(LitValue::List(items))
    }

    fn word(&mut self) -> Option<LitValue> {
        let start = self.i;
        while self
            .peek()
            .is_some_and(|c| c.is_ascii_alphanumeric() || c == '_')
        {
            self.i += 1;
        }
        let w: String = self.chars.get(start..self.i)?.iter().collect();
        if w.eq_ignore_ascii_case("TRUE") {
            Some(LitValue::Bool(true))
        } else if w.eq_ignore_ascii_case("FALSE") {
            Some(LitValue::Bool(false))
        } else {
            None
        }
    }

    fn digits(&mut self, out: &mut String) -> usize {
        let mut n = 0;
        while let Some(c) = self.peek().filter(char::is_ascii_digit) {
            out.push(c);
            self.i += 1;
            n += 1;
        }
        n
    }

    fn number(&mut self) -> Option<f64> {
        let mut s = String::new();
        if let Some(sign) = self.peek().filter(|&c| c == '-' || c == '+') {
            s.push(sign);
            self.i += 1;
        }
        let int_digits = self.digits(&mut s);
        let mut frac_digits = 0;
        if self.peek() == Some('.') {
            self.i += 1;
            s.push('.');
            frac_digits = self.digits(&mut s);
            if frac_digits == 0 {
                s.push('0');
            }
        }
        if int_digits == 0 && frac_digits == 0 {
            return None;
        }
        if let Some(e) = self.peek().filter(|&c| c == 'e' || c == 'E') {
            s.push(e);
            self.i += 1;
            if let Some(sign) = self.peek().filter(|&c| c == '-' || c == '+') {
                s.push(sign);
                self.i += 1;
            }
            if self.digits(&mut s) == 0 {
                return None;
            }
        }
        let v: f64 = s.parse().ok()?;
        v.is_finite().then_some(v + 0.0)
    }

    fn string(&mut self) -> Option<String> {
        self.bump(); // '"'
        let mut out = String::new();
        loop {
            match self.bump()? {
                '"' => {
                    if self.peek() == Some('"') {
                        self.i += 1;
                        out.push('"');
                    } else {
                        return Some(out);
                    }
                }
                '\\' => {
                    if self.peek() == Some('\\') {
                        self.i += 1;
                        out.push('\\');
                    } else {
                        let hi = self.bump()?.to_digit(16)?;
                        let lo = self.bump()?.to_digit(16)?;
                        out.push(char::from_u32(hi * 16 + lo)?);
                    }
                }
                '\n' | '\r' => return None,
                c => out.push(c),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The TPWrite \Num table: every rule of the module doc.
    #[test]
    fn num_table() {
        let table: &[(f32, &str)] = &[
            (0.0, "0"),
            (-0.0, "0"),
            (23.0, "23"),
            (-23.0, "-23"),
            (1.141367, "1.14137"),
            (0.5, "0.5"),
            (-0.5, "-0.5"),
            (0.1, "0.1"),
            (1.5, "1.5"),
            (3.125_5, "3.1255"),
            (2.718_281_7, "2.71828"),
            (100.25, "100.25"),
            (2.9999999, "3"),
            (2.999994, "2.99999"),
            (5.000004, "5"),
            (5.00001, "5.00001"),
            (0.000001, "0"),
            (-0.000001, "0"),
            (0.0000051, "5.1E-06"),
            (0.000494947, "0.000494947"),
            (0.0000960894, "9.60894E-05"),
            (0.0001, "0.0001"),
            (0.00012345678, "0.000123457"),
            (999999.0, "999999"),
            (123456.7, "123457"),
            (999999.5, "1E+06"),
            (1234567.0, "1234567"),
            (1234567.5, "1.23457E+06"),
            (8388608.0, "8388608"),
            (-8388608.0, "-8388608"),
            (8388609.0, "8.38861E+06"),
            (16777216.0, "1.67772E+07"),
            (9e9, "9E+09"),
            (-9e9, "-9E+09"),
            (1e-30, "0"),
            (0.00001, "1E-05"),
            (f32::MAX, "3.40282E+38"),
            (1817.3, "1817.3"),
            (905.17, "905.17"),
            (0.96593, "0.96593"),
            (0.258819, "0.258819"),
            (0.707_108, "0.707108"),
            (std::f32::consts::FRAC_1_SQRT_2, "0.707107"),
            (-123.456_79, "-123.457"),
            (0.1 + 0.2, "0.3"),
            (f32::NAN, "NAN"),
            (f32::INFINITY, "INF"),
            (f32::NEG_INFINITY, "-INF"),
        ];
        for &(v, want) in table {
            assert_eq!(format_num(v), want, "format_num({v:e})");
        }
    }

    #[test]
    fn dnum_table() {
        let table: &[(f64, &str)] = &[
            (0.0, "0"),
            (-0.0, "0"),
            (1.0, "1"),
            (0.1 + 0.2, "0.3"),
            (1.0 / 3.0, "0.333333333333333"),
            (2.0 / 3.0, "0.666666666666667"),
            (123456789012345.0, "123456789012345"),
            (1e15, "1E+15"),
            (4503599627370496.0, "4.5035996273705E+15"),
            (-1.5e-7, "-1.5E-07"),
            (0.0001, "0.0001"),
            (9e9, "9000000000"),
            (1e300, "1E+300"),
            (f64::NAN, "NAN"),
        ];
        for &(v, want) in table {
            assert_eq!(format_dnum(v), want, "format_dnum({v:e})");
        }
    }

    #[test]
    fn bool_and_records() {
        assert_eq!(format_bool(true), "TRUE");
        assert_eq!(format_bool(false), "FALSE");
        assert_eq!(
            format_pos(&[1817.3, 905.17, 879.11]),
            "[1817.3,905.17,879.11]"
        );
        assert_eq!(
            format_orient(&[0.96593, 0.0, 0.25882, 0.0]),
            "[0.96593,0,0.25882,0]"
        );
        assert_eq!(
            format_pose(&[0.0, 0.0, 0.0], &[1.0, 0.0, 0.0, 0.0]),
            "[[0,0,0],[1,0,0,0]]"
        );
        assert_eq!(
            format_list(["FALSE", "TRUE", "\"\"", "[[0,0,0],[1,0,0,0]]"]),
            "[FALSE,TRUE,\"\",[[0,0,0],[1,0,0,0]]]"
        );
        assert_eq!(format_list(Vec::<String>::new()), "[]");
    }

    #[test]
    fn quoting() {
        assert_eq!(quote_string(""), "\"\"");
        assert_eq!(quote_string("abc"), "\"abc\"");
        assert_eq!(quote_string("say \"hi\""), "\"say \"\"hi\"\"\"");
        assert_eq!(quote_string("a\\b"), "\"a\\\\b\"");
        assert_eq!(quote_string("\u{7}x\n"), "\"\\07x\\0A\"");
        assert_eq!(quote_string("é"), "\"é\"");
        for s in ["", "abc", "a\"b\\c\u{1}é"] {
            assert_eq!(str_to_string(&quote_string(s)).as_deref(), Some(s));
        }
    }

    #[test]
    fn num_to_str_table() {
        let table: &[(f32, i32, bool, &str)] = &[
            (0.38521, 3, false, "0.385"),
            (0.31852, 2, false, "0.32"),
            (2.0, 2, false, "2.00"),
            (0.385, 2, false, "0.39"),
            (-0.385, 2, false, "-0.39"),
            (1.5, 0, false, "2"),
            (2.5, 0, false, "3"),
            (-0.001, 2, false, "0.00"),
            (0.0, 0, false, "0"),
            (123.0, 0, false, "123"),
            (9.995, 2, false, "10.00"),
            (1234.5, 4, false, "1234.5000"),
            // f32 cannot hold 1234.5678; its shortest text is 1234.5677.
            (1234.5678, 4, false, "1234.5677"),
            (0.1, 10, false, "0.1000000000"),
            (9e9, 0, false, "9000000000"),
            (0.38521, 3, true, "3.852E-01"),
            (0.0, 2, true, "0.00E+00"),
            (123456.0, 2, true, "1.23E+05"),
            (9.99, 1, true, "1.0E+01"),
            (-1e-10, 0, true, "-1E-10"),
        ];
        for &(v, dec, exp, want) in table {
            assert_eq!(
                num_to_str(v, dec, exp).unwrap(),
                want,
                "NumToStr({v}, {dec}, exp={exp})"
            );
        }
        assert_eq!(
            num_to_str(1.0, -1, false).unwrap_err().err_name(),
            "ERR_ARGVALERR"
        );
        assert_eq!(
            num_to_str(1.0, 16, false).unwrap_err().err_name(),
            "ERR_ARGVALERR"
        );
        assert_eq!(
            num_to_str(f32::NAN, 1, false).unwrap_err().err_name(),
            "ERR_NUM_LIMIT"
        );
        // NumToStr(v, d) is the text of Round(v \Dec:=d).
        for v in [0.385f32, 1.005, -7.25, 123.456] {
            let r = super::super::math::round_num(v, 2).unwrap();
            assert_eq!(
                num_to_str(v, 2, false).unwrap(),
                num_to_str(r, 2, false).unwrap()
            );
        }
    }

    #[test]
    fn dnum_to_str_table() {
        assert_eq!(dnum_to_str(2.675, 2, false).unwrap(), "2.68");
        assert_eq!(
            dnum_to_str(1.0 / 3.0, 15, false).unwrap(),
            "0.333333333333333"
        );
        assert_eq!(
            dnum_to_str(1e20, 0, false).unwrap(),
            "100000000000000000000"
        );
        assert_eq!(dnum_to_str(1e300, 0, true).unwrap(), "1E+300");
        assert_eq!(
            dnum_to_str(1e300, 0, false).unwrap_err(),
            RtError::StrTooLong { len: 301 }
        );
    }

    #[test]
    fn parse_numbers() {
        assert_eq!(str_to_num("3.85"), Some(3.85));
        assert_eq!(str_to_num("  -1.5 "), Some(-1.5));
        assert_eq!(str_to_num("+2"), Some(2.0));
        assert_eq!(str_to_num(".5"), Some(0.5));
        assert_eq!(str_to_num("1."), Some(1.0));
        assert_eq!(str_to_num("9E+09"), Some(9e9));
        assert_eq!(str_to_num("9e9"), Some(9e9));
        assert_eq!(str_to_num("-245E-2"), Some(-2.45));
        assert_eq!(str_to_num("1E39"), None);
        assert_eq!(str_to_dnum("1E39"), Some(1e39));
        assert_eq!(str_to_dnum("1E400"), None);
        assert_eq!(str_to_num(""), None);
        assert_eq!(str_to_num("-"), None);
        assert_eq!(str_to_num("."), None);
        assert_eq!(str_to_num("1E"), None);
        assert_eq!(str_to_num("1 2"), None);
        assert_eq!(str_to_num("0x10"), None);
        assert_eq!(str_to_num("12abc"), None);
        assert_eq!(str_to_num("TRUE"), None);
        assert_eq!(str_to_num("[1]"), None);
        assert_eq!(str_to_num("- 1"), None);
    }

    #[test]
    fn parse_bools_strings_records() {
        assert_eq!(str_to_bool("TRUE"), Some(true));
        assert_eq!(str_to_bool("false"), Some(false));
        assert_eq!(str_to_bool(" True "), Some(true));
        assert_eq!(str_to_bool("yes"), None);
        assert_eq!(str_to_bool("1"), None);
        assert_eq!(
            str_to_string("\"ab\"\"c\\41\\\\\""),
            Some("ab\"cA\\".to_string())
        );
        assert_eq!(str_to_string("abc"), None);
        assert_eq!(str_to_string("\"abc"), None);
        assert_eq!(str_to_string("\"\\4\""), None);
        assert_eq!(str_to_pos("[600, 500, 225.3]"), Some([600.0, 500.0, 225.3]));
        assert_eq!(str_to_pos("[600,500]"), None);
        assert_eq!(str_to_pos("[600,500,1,2]"), None);
        assert_eq!(str_to_pos("[600,500,TRUE]"), None);
        assert_eq!(str_to_pos("[1,2,3"), None);
        assert_eq!(str_to_pos("[1,2,3]]"), None);
        assert_eq!(str_to_pos("[1,,3]"), None);
        assert_eq!(str_to_orient("[1,0,0,0]"), Some([1.0, 0.0, 0.0, 0.0]));
        assert_eq!(
            str_to_pose("[[1,2,3],[0.5,0.5,0.5,0.5]]"),
            Some(([1.0, 2.0, 3.0], [0.5, 0.5, 0.5, 0.5]))
        );
        assert_eq!(str_to_pose("[[1,2,3],[1,0,0]]"), None);
        assert_eq!(parse_value("[]"), None);
        assert_eq!(
            parse_value("[FALSE, TRUE, \"\", [[0,0,0],[1,0,0,0]]]"),
            Some(LitValue::List(vec![
                LitValue::Bool(false),
                LitValue::Bool(true),
                LitValue::Str(String::new()),
                LitValue::List(vec![
                    LitValue::List(vec![LitValue::Num(0.0); 3]),
                    LitValue::List(vec![
                        LitValue::Num(1.0),
                        LitValue::Num(0.0),
                        LitValue::Num(0.0),
                        LitValue::Num(0.0)
                    ]),
                ]),
            ]))
        );
        let deep = format!("{}1{}", "[".repeat(40), "]".repeat(40));
        assert_eq!(parse_value(&deep), None);
        let ok = format!("{}1{}", "[".repeat(10), "]".repeat(10));
        assert!(parse_value(&ok).is_some());
    }

    #[test]
    fn val_to_str_round_trips() {
        for v in [0.0f32, 1.5, -23.0, 1234567.0, 9e9, 0.000494947, 1.141367] {
            let back = str_to_num(&format_num(v)).unwrap();
            // Six significant digits: equal to within the printed precision.
            assert!((back - v).abs() <= v.abs() * 1e-5, "{v} -> {back}");
        }
        let p = [1817.3f32, 905.17, 879.11];
        assert_eq!(str_to_pos(&format_pos(&p)), Some(p));
        assert_eq!(str_to_bool(format_bool(false)), Some(false));
    }

    mod props {
        use super::super::*;
        use proptest::prelude::*;

        proptest! {
            /// TPWrite \Num text reads back within the 6 printed digits (or the integer rule).
            #[test]
            fn format_num_reads_back(v in proptest::num::f32::NORMAL | proptest::num::f32::ZERO) {
                let back = str_to_num(&format_num(v)).unwrap() as f64;
                let v = v as f64;
                let tol = (v.abs() * 5.01e-6).max(0.0000051);
                prop_assert!((back - v).abs() <= tol, "{} -> {}", v, back);
            }

            /// NumToStr reads back within half a unit of the last decimal.
            #[test]
            fn num_to_str_reads_back(v in -1e6f32..1e6f32, dec in 0i32..6) {
                let text = num_to_str(v, dec, false).unwrap();
                let back = text.parse::<f64>().unwrap();
                let tol = 0.5 * 10f64.powi(-dec) + (v as f64).abs() * 1.2e-7;
                prop_assert!((back - v as f64).abs() <= tol, "{} {} -> {}", v, dec, text);
                let decimals = text.split_once('.').map(|(_, f)| f.len()).unwrap_or(0);
                prop_assert_eq!(decimals as i32, dec);
            }

            /// The StrToVal parser never panics and never accepts trailing garbage.
            #[test]
            fn parse_value_total(text in ".{0,40}") {
                if let Some(v) = parse_value(&text) {
                    prop_assert!(!matches!(v, LitValue::List(ref l) if l.is_empty()));
                }
            }
        }
    }
}
