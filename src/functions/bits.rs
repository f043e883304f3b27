//! Bit operations and number bases: `BitAnd`, `BitOr`, `BitXOr`, `BitNeg`, `BitLSh`,
//! `BitRSh`, `BitCheck`, `BitSet`, `BitClear` on `byte` values and their `…Dnum` forms on
//! `dnum` values, and `DecToHex`/`HexToDec` on decimal and hexadecimal text.
//!
//! * A `byte` holds an integer 0–255 (8 bits); the `dnum` forms work on the integers
//!   0–4503599627370495 (2⁵² − 1, the 52 bits a `dnum` holds exactly). Bits are numbered from
//!   1 (the least significant) to 8 or 52; shifts move 1–8 or 1–52 steps, and bits shifted out
//!   are lost, so `BitLSh(38, 3)` is 48 and `BitNeg` of a `dnum` stays within 52 bits.
//! * An operand that is not an integer in range, a bit position or a shift outside its range
//!   is `ERR_ARGVALERR` (ABB documents the ranges, not the error; rapidvc raises the error
//!   for any argument value outside what a function accepts).
//! * `DecToHex` takes decimal digits for 0–9223372036854775807 and returns upper-case hex
//!   digits without leading zeros (`"99999999"` → `"5F5E0FF"`); `HexToDec` takes hex digits of
//!   either case for 0–7FFFFFFFFFFFFFFF and returns decimal digits. Anything else (a sign,
//!   spaces, an empty string, a larger value) is `ERR_ARGVALERR`.

use super::{RtError, RtResult};

/// The operand width of a bit function.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Width {
    /// `byte`: 8 bits.
    Byte,
    /// `dnum`: 52 bits.
    Dnum,
}

impl Width {
    /// Number of bits.
    pub fn bits(self) -> u32 {
        match self {
            Width::Byte => 8,
            Width::Dnum => 52,
        }
    }

    /// The largest value.
    pub fn max(self) -> u64 {
        (1u64 << self.bits()) - 1
    }

    fn name(self) -> &'static str {
        match self {
            Width::Byte => "a byte",
            Width::Dnum => "a bit-wise dnum",
        }
    }
}

/// An operand: an integer from 0 to the width's largest value.
pub fn operand(width: Width, x: f64, func: &'static str) -> RtResult<u64> {
    if x.is_finite() && x.fract() == 0.0 && x >= 0.0 && x <= width.max() as f64 {
        Ok(x as u64)
    } else {
        Err(RtError::arg(
            func,
            format!(
                "{x} is not {} (an integer from 0 to {})",
                width.name(),
                width.max()
            ),
        ))
    }
}

fn steps(width: Width, x: f64, func: &'static str, what: &str) -> RtResult<u32> {
    if x.is_finite() && x.fract() == 0.0 && x >= 1.0 && x <= f64::from(width.bits()) {
        Ok(x as u32)
    } else {
        Err(RtError::arg(
            func,
            format!("{what} {x} is outside 1 to {}", width.bits()),
        ))
    }
}

/// A bit position, 1 to the width's number of bits.
pub fn bit_pos(width: Width, x: f64, func: &'static str) -> RtResult<u32> {
    steps(width, x, func, "the bit position")
}

/// A shift, 1 to the width's number of bits.
pub fn shift(width: Width, x: f64, func: &'static str) -> RtResult<u32> {
    steps(width, x, func, "the number of shift steps")
}

/// `BitNeg`: every bit of the width inverted.
pub fn neg(width: Width, a: u64) -> u64 {
    !a & width.max()
}

/// `BitLSh`: shifted left, the bits beyond the width lost.
pub fn lsh(width: Width, a: u64, steps: u32) -> u64 {
    a.checked_shl(steps).unwrap_or(0) & width.max()
}

/// `BitRSh`: shifted right.
pub fn rsh(a: u64, steps: u32) -> u64 {
    a.checked_shr(steps).unwrap_or(0)
}

/// `BitCheck`: whether bit `pos` (from 1) is set.
pub fn check(a: u64, pos: u32) -> bool {
    pos >= 1 && a & (1u64 << (pos - 1)) != 0
}

/// `BitSet`: `a` with bit `pos` (from 1) set.
pub fn set(a: u64, pos: u32) -> u64 {
    a | (1u64 << pos.saturating_sub(1))
}

/// `BitClear`: `a` with bit `pos` (from 1) cleared.
pub fn clear(a: u64, pos: u32) -> u64 {
    a & !(1u64 << pos.saturating_sub(1))
}

/// The largest value `DecToHex` and `HexToDec` handle.
pub const HEX_MAX: u64 = i64::MAX as u64;

/// `DecToHex`.
pub fn dec_to_hex(s: &str) -> RtResult<String> {
    let v = parse_digits(s, 10, "DecToHex")?;
    Ok(format!("{v:X}"))
}

/// `HexToDec`.
pub fn hex_to_dec(s: &str) -> RtResult<String> {
    let v = parse_digits(s, 16, "HexToDec")?;
    Ok(v.to_string())
}

fn parse_digits(s: &str, radix: u32, func: &'static str) -> RtResult<u64> {
    let what = if radix == 10 {
        "decimal"
    } else {
        "hexadecimal"
    };
    if s.is_empty() || !s.chars().all(|c| c.is_digit(radix)) {
        return Err(RtError::arg(
            func,
            format!("{s:?} is not a string of {what} digits"),
        ));
    }
    match u64::from_str_radix(s, radix) {
        Ok(v) if v <= HEX_MAX => Ok(v),
        _ => Err(RtError::arg(
            func,
            format!(
                "{s:?} is larger than {}",
                if radix == 10 {
                    HEX_MAX.to_string()
                } else {
                    format!("{HEX_MAX:X}")
                }
            ),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_operations() {
        let b = Width::Byte;
        // The values of ABB's examples for the byte functions.
        assert_eq!(38 & 34, 34);
        assert_eq!(neg(b, 38), 217);
        assert_eq!(lsh(b, 38, 3), 48);
        assert_eq!(rsh(38, 3), 4);
        assert!(check(130, 8));
        assert!(!check(2, 8));
        assert_eq!(set(2, 8), 130);
        assert_eq!(clear(130, 8), 2);
        assert_eq!(lsh(b, 255, 8), 0);
        assert_eq!(rsh(255, 8), 0);
    }

    #[test]
    fn dnum_operations() {
        let d = Width::Dnum;
        assert_eq!(d.max(), 4_503_599_627_370_495);
        assert_eq!(neg(d, 0), d.max());
        assert_eq!(lsh(d, d.max(), 1), d.max() - 1);
        assert!(check(d.max(), 52));
        assert_eq!(set(0, 52), 1 << 51);
        assert_eq!(lsh(d, 1, 52), 0);
    }

    #[test]
    fn ranges() {
        let b = Width::Byte;
        assert_eq!(operand(b, 255.0, "BitAnd"), Ok(255));
        for bad in [-1.0, 256.0, 1.5, f64::NAN, f64::INFINITY] {
            let e = operand(b, bad, "BitAnd").unwrap_err();
            assert_eq!(e.err_name(), "ERR_ARGVALERR", "{bad}");
        }
        assert!(operand(Width::Dnum, 4_503_599_627_370_496.0, "BitAndDnum").is_err());
        assert_eq!(bit_pos(b, 8.0, "BitSet"), Ok(8));
        for bad in [0.0, 9.0, 2.5] {
            assert!(bit_pos(b, bad, "BitSet").is_err(), "{bad}");
        }
        assert_eq!(shift(Width::Dnum, 52.0, "BitLShDnum"), Ok(52));
        assert!(shift(Width::Dnum, 53.0, "BitLShDnum").is_err());
    }

    #[test]
    fn hex() {
        // ABB's examples.
        assert_eq!(dec_to_hex("99999999").unwrap(), "5F5E0FF");
        assert_eq!(hex_to_dec("5F5E0FF").unwrap(), "99999999");
        assert_eq!(hex_to_dec("5f5e0ff").unwrap(), "99999999");
        assert_eq!(dec_to_hex("0").unwrap(), "0");
        assert_eq!(
            dec_to_hex("9223372036854775807").unwrap(),
            "7FFFFFFFFFFFFFFF"
        );
        assert_eq!(
            hex_to_dec("7FFFFFFFFFFFFFFF").unwrap(),
            "9223372036854775807"
        );
        assert_eq!(dec_to_hex("0010").unwrap(), "A");
        for bad in [
            "",
            "-1",
            "+1",
            " 1",
            "1A",
            "9223372036854775808",
            "99999999999999999999",
        ] {
            assert_eq!(
                dec_to_hex(bad).unwrap_err().err_name(),
                "ERR_ARGVALERR",
                "{bad:?}"
            );
        }
        for bad in ["", "G", "0x10", "8000000000000000"] {
            assert!(hex_to_dec(bad).is_err(), "{bad:?}");
        }
    }
}
