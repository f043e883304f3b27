//! `num`/`dnum` semantics: single-precision rounding, checked arithmetic, DIV/MOD, Round/Trunc and degree trigonometry.
//!
//! # Decisions (rapidvc; not settled by an ABB document, pinned by the tests below)
//!
//! * **`num` is an `f32`.** Literals and every result are rounded to the nearest `f32`
//!   ([`num_from_f64`]); a result outside the `f32` range or NaN is `ERR_NUM_LIMIT`
//!   ([`RtError::NumLimit`]), never an infinity. `dnum` is an `f64` with the same checks.
//! * **Arithmetic** ([`num_add`] …) is IEEE single-precision arithmetic on the `f32`
//!   operands; `x / 0` is `ERR_DIVZERO`.
//! * **DIV and MOD** truncate towards zero, as C does: `a = (a DIV b) * b + a MOD b`, so
//!   `-14 DIV 4 = -3`, `-14 MOD 4 = -2`, `14 MOD -4 = 2` (the remainder has the sign of the
//!   left operand). A non-integer operand is `ERR_NOTINTVAL`, a zero right operand
//!   `ERR_DIVZERO`. `num` DIV/MOD is exact for every integer-valued `f32` (computed on
//!   128-bit integers), the result rounded to `num`.
//! * **Round and Trunc** (`\Dec`, default 0) work on the value's shortest decimal text (see
//!   `decimal`), rounding half away from zero: `Round(0.385\Dec:=2) = 0.39`,
//!   `Trunc(0.29\Dec:=2) = 0.29` (a binary-exact truncation would give 0.28),
//!   `Round(-2.5) = -3`. `\Dec` must be an integer 0–15 (the interpreter checks
//!   integrality; a negative or larger value is `ERR_ARGVALERR`). The same limits apply to
//!   `NumToStr` in `format`.
//! * **Trigonometry is in degrees.** Arguments are reduced modulo 360 exactly, so
//!   `Sin(180) = 0`, `Cos(90) = 0`, `Sin(30) = 0.5` exactly in `num`; `Tan` at an odd
//!   multiple of 90 is `ERR_ARGVALERR`. `ASin`/`ACos` outside −1…1 are `ERR_ARGVALERR`
//!   (no clamping). `ATan2(0, 0) = 0` (as C's `atan2`). Results in degrees: ASin/ATan in
//!   −90…90, ACos in 0…180, ATan2 in −180…180.
//! * **Sqrt** of a negative value, **Pow** with a negative base and a non-integer exponent,
//!   and **Pow(0, negative)** are `ERR_ARGVALERR`; an overflowing **Pow**/**Exp** is
//!   `ERR_NUM_LIMIT` (from the narrowing to `num`).
//!
//! The math functions ([`sin`], [`sqrt`], …) take and return `f64`; the interpreter narrows
//! a `num` result with [`num_from_f64`], which also reports overflow.

use super::decimal::{Decimal, Mode};
use super::pose::{deg_to_rad, rad_to_deg};
use super::{RtError, RtResult};

/// The largest integer magnitude `num` is documented to store exactly (2²³, RRM p.80).
pub const NUM_EXACT_INT_MAX: f32 = 8_388_608.0;

/// The largest `\Dec` accepted by Round, Trunc, NumToStr and DnumToStr.
pub const MAX_DEC: i32 = 15;

/// Round an `f64` (a literal, a `dnum`, or a math result) to `num`. NaN or a value beyond
/// the `f32` range is `ERR_NUM_LIMIT`. `-0` becomes `0`.
pub fn num_from_f64(v: f64) -> RtResult<f32> {
    let n = v as f32;
    if n.is_finite() {
        Ok(n + 0.0)
    } else {
        Err(RtError::NumLimit {
            what: "conversion to num",
            ty: "num",
        })
    }
}

/// Check a `num` result: NaN or infinite is `ERR_NUM_LIMIT` (`what` names the operation).
pub fn check_num(v: f32, what: &'static str) -> RtResult<f32> {
    if v.is_finite() {
        Ok(v + 0.0)
    } else {
        Err(RtError::NumLimit { what, ty: "num" })
    }
}

/// Check a `dnum` result: NaN or infinite is `ERR_NUM_LIMIT`.
pub fn check_dnum(v: f64, what: &'static str) -> RtResult<f64> {
    if v.is_finite() {
        Ok(v + 0.0)
    } else {
        Err(RtError::NumLimit { what, ty: "dnum" })
    }
}

/// True when `v` is a finite integer value.
pub fn is_integer(v: f64) -> bool {
    v.is_finite() && v.fract() == 0.0
}

/// `a + b` in `num`.
pub fn num_add(a: f32, b: f32) -> RtResult<f32> {
    check_num(a + b, "+")
}

/// `a - b` in `num`.
pub fn num_sub(a: f32, b: f32) -> RtResult<f32> {
    check_num(a - b, "-")
}

/// `a * b` in `num`.
pub fn num_mul(a: f32, b: f32) -> RtResult<f32> {
    check_num(a * b, "*")
}

/// `a / b` in `num`; `b = 0` is `ERR_DIVZERO`.
pub fn num_div(a: f32, b: f32) -> RtResult<f32> {
    if b == 0.0 {
        return Err(RtError::DivZero);
    }
    check_num(a / b, "/")
}

/// `a + b` in `dnum`.
pub fn dnum_add(a: f64, b: f64) -> RtResult<f64> {
    check_dnum(a + b, "+")
}

/// `a - b` in `dnum`.
pub fn dnum_sub(a: f64, b: f64) -> RtResult<f64> {
    check_dnum(a - b, "-")
}

/// `a * b` in `dnum`.
pub fn dnum_mul(a: f64, b: f64) -> RtResult<f64> {
    check_dnum(a * b, "*")
}

/// `a / b` in `dnum`; `b = 0` is `ERR_DIVZERO`.
pub fn dnum_div(a: f64, b: f64) -> RtResult<f64> {
    if b == 0.0 {
        return Err(RtError::DivZero);
    }
    check_dnum(a / b, "/")
}

fn int_operands(a: f64, b: f64, op: &'static str) -> RtResult<()> {
    let (left, right) = match op {
        "DIV" => ("left operand of DIV", "right operand of DIV"),
        _ => ("left operand of MOD", "right operand of MOD"),
    };
    if !is_integer(a) {
        return Err(RtError::NotInteger {
            what: left,
            value: a,
        });
    }
    if !is_integer(b) {
        return Err(RtError::NotInteger {
            what: right,
            value: b,
        });
    }
    if b == 0.0 {
        return Err(RtError::DivZero);
    }
    Ok(())
}

/// Exact truncating quotient and remainder of two integer-valued `f32`s, as magnitudes.
fn num_divmod(a: f32, b: f32) -> (u128, u128) {
    // Every finite f32 magnitude is below 2^128, and an integer-valued one converts exactly.
    let ma = a.abs() as u128;
    let mb = b.abs() as u128;
    if mb == 0 {
        return (0, 0);
    }
    (ma / mb, ma % mb)
}

/// `a DIV b` for `num`: integer division truncating towards zero.
pub fn num_int_div(a: f32, b: f32) -> RtResult<f32> {
    int_operands(a as f64, b as f64, "DIV")?;
    let (q, _) = num_divmod(a, b);
    let q = q as f32;
    Ok(if (a < 0.0) != (b < 0.0) { -q } else { q } + 0.0)
}

/// `a MOD b` for `num`: remainder with the sign of `a`.
pub fn num_mod(a: f32, b: f32) -> RtResult<f32> {
    int_operands(a as f64, b as f64, "MOD")?;
    let (_, r) = num_divmod(a, b);
    let r = r as f32;
    Ok(if a < 0.0 { -r } else { r } + 0.0)
}

/// `a DIV b` for `dnum`: integer division truncating towards zero.
pub fn dnum_int_div(a: f64, b: f64) -> RtResult<f64> {
    int_operands(a, b, "DIV")?;
    // The IEEE remainder with truncation (`%`) is exact; a - r is a multiple of b.
    let r = a % b;
    check_dnum(((a - r) / b).trunc() + 0.0, "DIV")
}

/// `a MOD b` for `dnum`: remainder with the sign of `a`.
pub fn dnum_mod(a: f64, b: f64) -> RtResult<f64> {
    int_operands(a, b, "MOD")?;
    Ok((a % b) + 0.0)
}

pub(crate) fn check_dec(func: &'static str, dec: i32) -> RtResult<u32> {
    if (0..=MAX_DEC).contains(&dec) {
        Ok(dec as u32)
    } else {
        Err(RtError::arg(
            func,
            format!("\\Dec must be between 0 and {MAX_DEC}, not {dec}"),
        ))
    }
}

/// `Round(v \Dec:=dec)` for `num` (half away from zero on the shortest decimal text).
pub fn round_num(v: f32, dec: i32) -> RtResult<f32> {
    cut_num("Round", v, dec, Mode::Round)
}

/// `Trunc(v \Dec:=dec)` for `num`.
pub fn trunc_num(v: f32, dec: i32) -> RtResult<f32> {
    cut_num("Trunc", v, dec, Mode::Trunc)
}

/// `Round(v \Dec:=dec)` for `dnum` (RoundDnum).
pub fn round_dnum(v: f64, dec: i32) -> RtResult<f64> {
    cut_dnum("Round", v, dec, Mode::Round)
}

/// `Trunc(v \Dec:=dec)` for `dnum` (TruncDnum).
pub fn trunc_dnum(v: f64, dec: i32) -> RtResult<f64> {
    cut_dnum("Trunc", v, dec, Mode::Trunc)
}

fn cut_num(func: &'static str, v: f32, dec: i32, mode: Mode) -> RtResult<f32> {
    let dec = check_dec(func, dec)?;
    let Some(mut d) = Decimal::from_f32(v) else {
        return Err(RtError::NumLimit {
            what: func,
            ty: "num",
        });
    };
    d.cut_decimals(dec, mode);
    check_num(d.to_f32(), func)
}

fn cut_dnum(func: &'static str, v: f64, dec: i32, mode: Mode) -> RtResult<f64> {
    let dec = check_dec(func, dec)?;
    let Some(mut d) = Decimal::from_f64(v) else {
        return Err(RtError::NumLimit {
            what: func,
            ty: "dnum",
        });
    };
    d.cut_decimals(dec, mode);
    check_dnum(d.to_f64(), func)
}

/// `Abs(v)` (any numeric type; the result is exact).
pub fn abs(v: f64) -> f64 {
    v.abs()
}

fn finite_arg(func: &'static str, v: f64) -> RtResult<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(RtError::arg(func, "the argument is not a finite number"))
    }
}

/// Sine and cosine of an angle in degrees, with exact reduction to −45…45 degrees so that
/// multiples of 90 give exact 0 and ±1.
pub(crate) fn sin_cos_deg(func: &'static str, deg: f64) -> RtResult<(f64, f64)> {
    let deg = finite_arg(func, deg)?;
    // `%` is exact in IEEE arithmetic; so are q * 90 and the subtraction for |r| < 360.
    let r = deg % 360.0;
    let q = (r / 90.0).round();
    let rem = r - q * 90.0;
    let (s, c) = deg_to_rad(rem).sin_cos();
    let quadrant = (q as i64).rem_euclid(4);
    let (sin, cos) = match quadrant {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    };
    Ok((sin + 0.0, cos + 0.0))
}

/// `Sin(deg)`.
pub fn sin(deg: f64) -> RtResult<f64> {
    Ok(sin_cos_deg("Sin", deg)?.0)
}

/// `Cos(deg)`.
pub fn cos(deg: f64) -> RtResult<f64> {
    Ok(sin_cos_deg("Cos", deg)?.1)
}

/// `Tan(deg)`; an odd multiple of 90 degrees is `ERR_ARGVALERR`.
pub fn tan(deg: f64) -> RtResult<f64> {
    let (s, c) = sin_cos_deg("Tan", deg)?;
    if c == 0.0 {
        return Err(RtError::arg(
            "Tan",
            format!("the tangent of {deg} degrees is infinite"),
        ));
    }
    Ok(s / c)
}

/// `ASin(x)` in degrees (−90…90); `|x| > 1` is `ERR_ARGVALERR`.
pub fn asin(x: f64) -> RtResult<f64> {
    let x = finite_arg("ASin", x)?;
    if !(-1.0..=1.0).contains(&x) {
        return Err(RtError::arg(
            "ASin",
            format!("the argument must be between -1 and 1, not {x}"),
        ));
    }
    Ok(rad_to_deg(x.asin()) + 0.0)
}

/// `ACos(x)` in degrees (0…180); `|x| > 1` is `ERR_ARGVALERR`.
pub fn acos(x: f64) -> RtResult<f64> {
    let x = finite_arg("ACos", x)?;
    if !(-1.0..=1.0).contains(&x) {
        return Err(RtError::arg(
            "ACos",
            format!("the argument must be between -1 and 1, not {x}"),
        ));
    }
    Ok(rad_to_deg(x.acos()) + 0.0)
}

/// `ATan(x)` in degrees (−90…90).
pub fn atan(x: f64) -> RtResult<f64> {
    let x = finite_arg("ATan", x)?;
    Ok(rad_to_deg(x.atan()) + 0.0)
}

/// `ATan2(y, x)` in degrees (−180…180); `ATan2(0, 0) = 0`.
pub fn atan2(y: f64, x: f64) -> RtResult<f64> {
    let y = finite_arg("ATan2", y)?;
    let x = finite_arg("ATan2", x)?;
    Ok(rad_to_deg(y.atan2(x)) + 0.0)
}

/// `Sqrt(x)`; a negative argument is `ERR_ARGVALERR`.
pub fn sqrt(x: f64) -> RtResult<f64> {
    let x = finite_arg("Sqrt", x)?;
    if x < 0.0 {
        return Err(RtError::arg(
            "Sqrt",
            format!("the argument must not be negative, not {x}"),
        ));
    }
    Ok(x.sqrt())
}

/// `Pow(base, exponent)`.
pub fn pow(base: f64, exponent: f64) -> RtResult<f64> {
    let base = finite_arg("Pow", base)?;
    let exponent = finite_arg("Pow", exponent)?;
    if base < 0.0 && !is_integer(exponent) {
        return Err(RtError::arg(
            "Pow",
            format!("a negative base ({base}) needs an integer exponent, not {exponent}"),
        ));
    }
    if base == 0.0 && exponent < 0.0 {
        return Err(RtError::arg(
            "Pow",
            format!("zero to a negative power ({exponent}) is infinite"),
        ));
    }
    check_dnum(base.powf(exponent), "Pow")
}

/// `Exp(x)` = e^x.
pub fn exp(x: f64) -> RtResult<f64> {
    let x = finite_arg("Exp", x)?;
    check_dnum(x.exp(), "Exp")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn n(v: f64) -> f32 {
        num_from_f64(v).unwrap()
    }

    #[test]
    fn literals_round_to_f32() {
        assert_eq!(n(9e9), 9e9f32);
        assert_eq!(n(9e9) as f64, 8_999_999_488.0);
        assert_eq!(n(16_777_217.0), 16_777_216.0);
        assert_eq!(n(0.1), 0.1f32);
        assert_eq!(n(-0.0).to_bits(), 0.0f32.to_bits());
        assert_eq!(n(3.4028235e38), f32::MAX);
        assert_eq!(num_from_f64(1e39).unwrap_err().err_name(), "ERR_NUM_LIMIT");
        assert_eq!(
            num_from_f64(f64::NAN).unwrap_err().err_name(),
            "ERR_NUM_LIMIT"
        );
        assert_eq!(
            num_from_f64(f64::NEG_INFINITY).unwrap_err().err_name(),
            "ERR_NUM_LIMIT"
        );
    }

    #[test]
    fn num_arithmetic_is_single_precision() {
        assert_eq!(num_add(16_777_216.0, 1.0).unwrap(), 16_777_216.0);
        assert_eq!(num_add(0.1, 0.2).unwrap(), 0.1f32 + 0.2f32);
        assert_eq!(num_mul(3e38, 10.0).unwrap_err().err_name(), "ERR_NUM_LIMIT");
        assert_eq!(
            num_sub(-3e38, 3e38).unwrap_err().err_name(),
            "ERR_NUM_LIMIT"
        );
        assert_eq!(num_div(1.0, 0.0).unwrap_err(), RtError::DivZero);
        assert_eq!(num_div(0.0, 0.0).unwrap_err(), RtError::DivZero);
        assert_eq!(num_div(1.0, 4.0).unwrap(), 0.25);
        assert_eq!(num_div(1e-38, 1e10).unwrap(), 1e-38f32 / 1e10f32);
        assert_eq!(dnum_div(1.0, 0.0).unwrap_err(), RtError::DivZero);
        assert_eq!(
            dnum_mul(1e308, 10.0).unwrap_err().err_name(),
            "ERR_NUM_LIMIT"
        );
        assert_eq!(dnum_add(0.1, 0.2).unwrap(), 0.1 + 0.2);
        assert_eq!(dnum_sub(1.0, 0.5).unwrap(), 0.5);
    }

    #[test]
    fn div_mod_truncate_towards_zero() {
        assert_eq!(num_int_div(14.0, 4.0).unwrap(), 3.0);
        assert_eq!(num_mod(14.0, 4.0).unwrap(), 2.0);
        assert_eq!(num_int_div(-14.0, 4.0).unwrap(), -3.0);
        assert_eq!(num_mod(-14.0, 4.0).unwrap(), -2.0);
        assert_eq!(num_int_div(14.0, -4.0).unwrap(), -3.0);
        assert_eq!(num_mod(14.0, -4.0).unwrap(), 2.0);
        assert_eq!(num_int_div(-14.0, -4.0).unwrap(), 3.0);
        assert_eq!(num_mod(-14.0, -4.0).unwrap(), -2.0);
        assert_eq!(num_int_div(3.0, 4.0).unwrap(), 0.0);
        assert_eq!(num_int_div(-3.0, 4.0).unwrap().to_bits(), 0.0f32.to_bits());
        assert_eq!(num_mod(-4.0, 4.0).unwrap().to_bits(), 0.0f32.to_bits());
        // Exact on large integer-valued f32s (a float division would round).
        assert_eq!(num_mod(1e30, 7.0).unwrap(), (1e30f32 as u128 % 7) as f32);
        assert_eq!(num_int_div(f32::MAX, 1.0).unwrap(), f32::MAX);
    }

    #[test]
    fn div_mod_errors() {
        assert_eq!(
            num_int_div(14.5, 4.0).unwrap_err(),
            RtError::NotInteger {
                what: "left operand of DIV",
                value: 14.5
            }
        );
        assert_eq!(
            num_mod(14.0, 0.5).unwrap_err(),
            RtError::NotInteger {
                what: "right operand of MOD",
                value: 0.5
            }
        );
        assert_eq!(num_int_div(14.0, 0.0).unwrap_err(), RtError::DivZero);
        assert_eq!(num_mod(14.0, 0.0).unwrap_err(), RtError::DivZero);
        assert_eq!(
            num_mod(f32::INFINITY, 2.0).unwrap_err().err_name(),
            "ERR_NOTINTVAL"
        );
        assert_eq!(
            dnum_int_div(1.5, 1.0).unwrap_err().err_name(),
            "ERR_NOTINTVAL"
        );
        assert_eq!(dnum_mod(1.0, 0.0).unwrap_err(), RtError::DivZero);
    }

    #[test]
    fn dnum_div_mod() {
        assert_eq!(dnum_int_div(-14.0, 4.0).unwrap(), -3.0);
        assert_eq!(dnum_mod(-14.0, 4.0).unwrap(), -2.0);
        assert_eq!(dnum_mod(14.0, -4.0).unwrap(), 2.0);
        assert_eq!(
            dnum_int_div(4_503_599_627_370_497.0, 2.0).unwrap(),
            2_251_799_813_685_248.0
        );
        assert_eq!(dnum_mod(4_503_599_627_370_497.0, 2.0).unwrap(), 1.0);
    }

    #[test]
    fn round_and_trunc_on_decimal_text() {
        assert_eq!(round_num(0.38521, 3).unwrap(), 0.385);
        assert_eq!(round_num(0.385, 2).unwrap(), 0.39);
        assert_eq!(round_num(1.5, 0).unwrap(), 2.0);
        assert_eq!(round_num(2.5, 0).unwrap(), 3.0);
        assert_eq!(round_num(-2.5, 0).unwrap(), -3.0);
        assert_eq!(round_num(-0.4, 0).unwrap().to_bits(), 0.0f32.to_bits());
        assert_eq!(round_num(123.456, 1).unwrap(), 123.5);
        assert_eq!(round_num(9.9999, 2).unwrap(), 10.0);
        assert_eq!(round_num(1e30, 2).unwrap(), 1e30);
        assert_eq!(trunc_num(0.29, 2).unwrap(), 0.29);
        assert_eq!(trunc_num(-1.99, 0).unwrap(), -1.0);
        assert_eq!(trunc_num(1.99, 1).unwrap(), 1.9);
        assert_eq!(trunc_num(1e-7, 6).unwrap(), 0.0);
        assert_eq!(round_dnum(2.675, 2).unwrap(), 2.68);
        assert_eq!(trunc_dnum(-2.675, 2).unwrap(), -2.67);
        assert_eq!(round_dnum(0.1 + 0.2, 15).unwrap(), 0.3);
        assert_eq!(round_num(f32::MAX, 0).unwrap(), f32::MAX);
    }

    #[test]
    fn dec_limits() {
        assert_eq!(round_num(1.0, -1).unwrap_err().err_name(), "ERR_ARGVALERR");
        assert_eq!(trunc_num(1.0, 16).unwrap_err().err_name(), "ERR_ARGVALERR");
        assert_eq!(round_dnum(1.0, 15).unwrap(), 1.0);
        assert_eq!(
            round_num(f32::NAN, 0).unwrap_err().err_name(),
            "ERR_NUM_LIMIT"
        );
    }

    fn nf(v: RtResult<f64>) -> f32 {
        num_from_f64(v.unwrap()).unwrap()
    }

    #[test]
    fn trig_in_degrees_exact_at_quadrants() {
        assert_eq!(sin(0.0).unwrap(), 0.0);
        assert_eq!(sin(90.0).unwrap(), 1.0);
        assert_eq!(sin(180.0).unwrap().to_bits(), 0.0f64.to_bits());
        assert_eq!(sin(270.0).unwrap(), -1.0);
        assert_eq!(sin(-90.0).unwrap(), -1.0);
        assert_eq!(sin(720.0).unwrap(), 0.0);
        assert_eq!(cos(90.0).unwrap(), 0.0);
        assert_eq!(cos(180.0).unwrap(), -1.0);
        assert_eq!(cos(-180.0).unwrap(), -1.0);
        assert_eq!(cos(360.0).unwrap(), 1.0);
        assert_eq!(nf(sin(30.0)), 0.5);
        assert_eq!(nf(cos(60.0)), 0.5);
        assert_eq!(nf(sin(45.0)), std::f32::consts::FRAC_1_SQRT_2);
        assert_eq!(nf(tan(45.0)), 1.0);
        assert_eq!(nf(tan(-45.0)), -1.0);
        assert_eq!(tan(180.0).unwrap(), 0.0);
        assert_eq!(tan(90.0).unwrap_err().err_name(), "ERR_ARGVALERR");
        assert_eq!(tan(-270.0).unwrap_err().err_name(), "ERR_ARGVALERR");
        assert_eq!(sin(f64::NAN).unwrap_err().err_name(), "ERR_ARGVALERR");
        assert!((sin(1e6).unwrap() - deg_to_rad(1e6 % 360.0).sin()).abs() < 1e-12);
    }

    #[test]
    fn inverse_trig() {
        assert_eq!(nf(asin(1.0)), 90.0);
        assert_eq!(nf(asin(-1.0)), -90.0);
        assert_eq!(nf(asin(0.5)), 30.0);
        assert_eq!(nf(acos(-1.0)), 180.0);
        assert_eq!(nf(acos(0.0)), 90.0);
        assert_eq!(nf(acos(1.0)), 0.0);
        assert_eq!(nf(atan(1.0)), 45.0);
        assert_eq!(nf(atan2(1.0, -1.0)), 135.0);
        assert_eq!(nf(atan2(-1.0, -1.0)), -135.0);
        assert_eq!(atan2(0.0, -1.0).unwrap(), 180.0);
        assert_eq!(atan2(0.0, 0.0).unwrap(), 0.0);
        assert_eq!(
            asin(1.0000001).unwrap_err().to_string(),
            "ASin: the argument must be between -1 and 1, not 1.0000001"
        );
        assert_eq!(acos(-2.0).unwrap_err().err_name(), "ERR_ARGVALERR");
    }

    #[test]
    fn sqrt_pow_exp_abs() {
        assert_eq!(sqrt(16.0).unwrap(), 4.0);
        assert_eq!(sqrt(0.0).unwrap(), 0.0);
        assert_eq!(sqrt(-1.0).unwrap_err().err_name(), "ERR_ARGVALERR");
        assert_eq!(pow(2.0, 10.0).unwrap(), 1024.0);
        assert_eq!(pow(-2.0, 3.0).unwrap(), -8.0);
        assert_eq!(pow(2.0, -1.0).unwrap(), 0.5);
        assert_eq!(pow(0.0, 0.0).unwrap(), 1.0);
        assert_eq!(
            pow(-8.0, 1.0 / 3.0).unwrap_err().err_name(),
            "ERR_ARGVALERR"
        );
        assert_eq!(pow(0.0, -1.0).unwrap_err().err_name(), "ERR_ARGVALERR");
        assert_eq!(pow(10.0, 400.0).unwrap_err().err_name(), "ERR_NUM_LIMIT");
        // Fits dnum but not num: the narrowing reports it.
        assert_eq!(
            num_from_f64(pow(10.0, 39.0).unwrap())
                .unwrap_err()
                .err_name(),
            "ERR_NUM_LIMIT"
        );
        assert_eq!(exp(0.0).unwrap(), 1.0);
        assert_eq!(nf(exp(1.0)), std::f32::consts::E);
        assert_eq!(exp(1000.0).unwrap_err().err_name(), "ERR_NUM_LIMIT");
        assert_eq!(abs(-3.5), 3.5);
        assert_eq!(abs(0.0), 0.0);
    }

    #[test]
    fn integers_and_checks() {
        assert!(is_integer(3.0));
        assert!(is_integer(-1e30));
        assert!(!is_integer(3.5));
        assert!(!is_integer(f64::INFINITY));
        assert!(!is_integer(f64::NAN));
        assert_eq!(
            check_num(f32::INFINITY, "x").unwrap_err().err_name(),
            "ERR_NUM_LIMIT"
        );
        assert_eq!(
            check_dnum(f64::NAN, "x").unwrap_err().err_name(),
            "ERR_NUM_LIMIT"
        );
        assert_eq!(NUM_EXACT_INT_MAX, 8_388_608.0);
    }
}
