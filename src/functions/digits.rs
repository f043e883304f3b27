//! Arithmetic and comparison on `stringdig` text: `StrDigCalc` and `StrDigCmp`.
//!
//! A `stringdig` is a string of decimal digits for an integer 0–4294967295 (a 32-bit
//! unsigned value, more than a `num` holds exactly). An operand with anything but digits
//! (or empty) is `ERR_INT_NOTVAL`, one above 4294967295 `ERR_INT_MAXVAL`. `StrDigCalc` adds,
//! subtracts, multiplies, divides (an integer quotient) or takes the remainder; a negative
//! result is `ERR_CALC_NEG`, one above 4294967295 `ERR_CALC_OVERFLOW`, a division or modulo by
//! zero `ERR_CALC_DIVZERO`. The result has no leading zeros. The operators are the `opcalc`
//! and `opnum` constants (`OpAdd` … `OpMod`, `LT` … `GT`); another number is `ERR_ARGVALERR`.

use std::cmp::Ordering;
use std::fmt;

/// The largest `stringdig` value.
pub const MAX: u64 = 4_294_967_295;

/// Why a `stringdig` operation failed; [`DigitError::err_name`] is the RAPID error.
#[derive(Clone, Debug, PartialEq)]
pub enum DigitError {
    /// Not a string of digits.
    NotDigits(String),
    /// Above [`MAX`].
    TooLarge(String),
    /// A negative result.
    Negative,
    /// A result above [`MAX`].
    Overflow,
    /// Division or modulo by zero.
    DivZero,
    /// Not an operator constant.
    Operator(f64),
}

impl DigitError {
    /// The RAPID error constant.
    pub fn err_name(&self) -> &'static str {
        match self {
            DigitError::NotDigits(_) => "ERR_INT_NOTVAL",
            DigitError::TooLarge(_) => "ERR_INT_MAXVAL",
            DigitError::Negative => "ERR_CALC_NEG",
            DigitError::Overflow => "ERR_CALC_OVERFLOW",
            DigitError::DivZero => "ERR_CALC_DIVZERO",
            DigitError::Operator(_) => "ERR_ARGVALERR",
        }
    }
}

impl fmt::Display for DigitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DigitError::NotDigits(s) => write!(f, "{s:?} is not a string of digits"),
            DigitError::TooLarge(s) => write!(f, "{s} is larger than {MAX}"),
            DigitError::Negative => f.write_str("the result would be negative"),
            DigitError::Overflow => write!(f, "the result would be larger than {MAX}"),
            DigitError::DivZero => f.write_str("division by zero"),
            DigitError::Operator(x) => write!(f, "{x} is not an operator constant"),
        }
    }
}

/// The value of a `stringdig`.
pub fn value(s: &str) -> Result<u64, DigitError> {
    if s.is_empty() || !s.bytes().all(|b| b.is_ascii_digit()) {
        return Err(DigitError::NotDigits(s.to_string()));
    }
    let digits = s.trim_start_matches('0');
    if digits.is_empty() {
        return Ok(0);
    }
    match digits.parse::<u64>() {
        Ok(v) if digits.len() <= 10 && v <= MAX => Ok(v),
        _ => Err(DigitError::TooLarge(s.to_string())),
    }
}

/// The operator constant `x` (an integer) as a number to match on.
fn operator(x: f64) -> Result<i64, DigitError> {
    if x.fract() == 0.0 && (1.0..=6.0).contains(&x) {
        Ok(x as i64)
    } else {
        Err(DigitError::Operator(x))
    }
}

/// `StrDigCalc(a, op, b)` with `op` an `opcalc` constant (1 `OpAdd` … 5 `OpMod`).
pub fn calc(a: &str, op: f64, b: &str) -> Result<String, DigitError> {
    let (x, y) = (value(a)?, value(b)?);
    let r = match operator(op)? {
        1 => x + y,
        2 => x.checked_sub(y).ok_or(DigitError::Negative)?,
        3 => x * y,
        4 => x.checked_div(y).ok_or(DigitError::DivZero)?,
        5 => x.checked_rem(y).ok_or(DigitError::DivZero)?,
        _ => return Err(DigitError::Operator(op)),
    };
    if r > MAX {
        return Err(DigitError::Overflow);
    }
    Ok(r.to_string())
}

/// `StrDigCmp(a, rel, b)` with `rel` an `opnum` constant (1 `LT`, 2 `LTEQ`, 3 `EQ`, 4 `NOTEQ`,
/// 5 `GTEQ`, 6 `GT`).
pub fn compare(a: &str, rel: f64, b: &str) -> Result<bool, DigitError> {
    let o = value(a)?.cmp(&value(b)?);
    Ok(match operator(rel)? {
        1 => o == Ordering::Less,
        2 => o != Ordering::Greater,
        3 => o == Ordering::Equal,
        4 => o != Ordering::Equal,
        5 => o != Ordering::Less,
        _ => o == Ordering::Greater,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn calc_and_its_errors() {
        // ABB's StrDigCalc example: "10" OpAdd "20" is "30".
        assert_eq!(calc("10", 1.0, "20").unwrap(), "30");
        assert_eq!(calc("4294967295", 2.0, "4294967295").unwrap(), "0");
        assert_eq!(calc("007", 3.0, "6").unwrap(), "42");
        assert_eq!(calc("7", 4.0, "2").unwrap(), "3");
        assert_eq!(calc("7", 5.0, "2").unwrap(), "1");
        assert_eq!(calc("0000", 1.0, "0").unwrap(), "0");
        let err = |a, op, b| calc(a, op, b).unwrap_err().err_name();
        assert_eq!(err("1", 2.0, "2"), "ERR_CALC_NEG");
        assert_eq!(err("4294967295", 1.0, "1"), "ERR_CALC_OVERFLOW");
        assert_eq!(err("65536", 3.0, "65536"), "ERR_CALC_OVERFLOW");
        assert_eq!(err("1", 4.0, "0"), "ERR_CALC_DIVZERO");
        assert_eq!(err("1", 5.0, "000"), "ERR_CALC_DIVZERO");
        assert_eq!(err("1a", 1.0, "1"), "ERR_INT_NOTVAL");
        assert_eq!(err("", 1.0, "1"), "ERR_INT_NOTVAL");
        assert_eq!(err("-1", 1.0, "1"), "ERR_INT_NOTVAL");
        assert_eq!(err("1", 1.0, "4294967296"), "ERR_INT_MAXVAL");
        assert_eq!(err("1", 1.0, "99999999999999999999999"), "ERR_INT_MAXVAL");
        assert_eq!(err("1", 6.0, "1"), "ERR_ARGVALERR");
        assert_eq!(err("1", 1.5, "1"), "ERR_ARGVALERR");
    }

    #[test]
    fn compare_all_relations() {
        // ABB's StrDigCmp example: "1234" LT "1256" is TRUE.
        assert!(compare("1234", 1.0, "1256").unwrap());
        let rel = |r| {
            [("1", "2"), ("2", "2"), ("3", "2")]
                .iter()
                .map(|(a, b)| compare(a, r, b).unwrap())
                .collect::<Vec<_>>()
        };
        assert_eq!(rel(1.0), [true, false, false]);
        assert_eq!(rel(2.0), [true, true, false]);
        assert_eq!(rel(3.0), [false, true, false]);
        assert_eq!(rel(4.0), [true, false, true]);
        assert_eq!(rel(5.0), [false, true, true]);
        assert_eq!(rel(6.0), [false, false, true]);
        assert!(compare("0010", 3.0, "10").unwrap());
        assert_eq!(
            compare("1", 0.0, "1").unwrap_err().err_name(),
            "ERR_ARGVALERR"
        );
        assert_eq!(
            compare("x", 1.0, "1").unwrap_err().err_name(),
            "ERR_INT_NOTVAL"
        );
    }
}
