//! `rawbytes`: a container of up to 1024 bytes with a count of valid bytes, and the byte
//! formats of `PackRawBytes`, `UnpackRawBytes`, `CopyRawBytes` and `ClearRawBytes`.
//!
//! The valid bytes are a `Vec<u8>`; bytes beyond the valid length are zero. Positions are
//! 1-based, as in RAPID.
//!
//! * **Packing** writes at `StartIndex` (1–1024); the valid length becomes
//!   `StartIndex + n − 1`, or stays when the bytes lie inside it. A gap between the old length
//!   and `StartIndex` is zero. Bytes that would end beyond 1024 are `ERR_OUTOFBND`.
//! * **Formats**: `\IntX` with the `inttypes` constants (`USINT` 1, `UINT` 2, `UDINT` 4,
//!   `ULINT` 8 bytes unsigned; `SINT`, `INT`, `DINT`, `LINT` signed, two's complement);
//!   `\Float4` (IEEE single); `\ASCII` (a string's characters, or one byte); `\Hex1` (one
//!   byte). Integers and floats are little-endian, big-endian (network order) with
//!   `\Network`.
//! * **Unpacking** reads only valid bytes: reading past the valid length is `ERR_OUTOFBND`.
//!
//! Decisions where ABB's manual says nothing: a value outside its integer format's range,
//! or not an integer, is `ERR_ARGVALERR` (never wrapped or rounded); an unpacked integer
//! that a `num` cannot hold exactly (beyond 2^24) is `ERR_ARGVALERR` (unpack into a `dnum`),
//! and a float that is not finite is `ERR_NUM_LIMIT`; a character beyond ISO-8859-1 cannot
//! be packed (`ERR_ARGVALERR`). `ClearRawBytes \FromIndex` sets the valid length to
//! `FromIndex − 1` as documented, also when that is longer than before (the new bytes are
//! zero).

use super::{RtError, RtResult};

/// The most bytes a `rawbytes` holds.
pub const CAPACITY: usize = 1024;

/// An `inttypes` format of `\IntX`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct IntFormat {
    /// Size in bytes (1, 2, 4 or 8).
    pub size: usize,
    /// Two's complement (the negative constants).
    pub signed: bool,
}

impl IntFormat {
    /// The format of an `inttypes` constant (1, 2, 4, 8 unsigned; −1, −2, −4, −8 signed).
    pub fn from_code(func: &'static str, code: f64) -> RtResult<IntFormat> {
        let size = code.abs();
        if code.fract() != 0.0 || ![1.0, 2.0, 4.0, 8.0].contains(&size) {
            return Err(RtError::arg(
                func,
                format!(
                    "\\IntX:={code} is not an integer format (USINT, UINT, UDINT, ULINT, SINT, \
                     INT, DINT or LINT)"
                ),
            ));
        }
        Ok(IntFormat {
            size: size as usize,
            signed: code < 0.0,
        })
    }

    /// The RAPID name of the format.
    pub fn name(self) -> &'static str {
        match (self.signed, self.size) {
            (false, 1) => "USINT",
            (false, 2) => "UINT",
            (false, 4) => "UDINT",
            (false, _) => "ULINT",
            (true, 1) => "SINT",
            (true, 2) => "INT",
            (true, 4) => "DINT",
            (true, _) => "LINT",
        }
    }

    /// Smallest and largest value.
    pub fn range(self) -> (i128, i128) {
        let bits = 8 * self.size as u32;
        if self.signed {
            (-(1i128 << (bits - 1)), (1i128 << (bits - 1)) - 1)
        } else {
            (0, (1i128 << bits) - 1)
        }
    }
}

/// Where `n` bytes at 1-based `start` go: checks `start` (1–1024) and the end.
fn span(func: &'static str, start: f64, n: usize) -> RtResult<usize> {
    if start.fract() != 0.0 || !(1.0..=CAPACITY as f64).contains(&start) {
        return Err(RtError::OutOfBounds {
            func,
            reason: format!("index {start} is outside 1–{CAPACITY}"),
        });
    }
    let at = start as usize - 1;
    if at + n > CAPACITY {
        return Err(RtError::OutOfBounds {
            func,
            reason: format!(
                "{n} bytes from index {start} would end at {} (a rawbytes holds {CAPACITY})",
                at + n
            ),
        });
    }
    Ok(at)
}

/// Write `bytes` at 1-based `start`, growing the valid length when they end beyond it.
pub fn place(func: &'static str, raw: &mut Vec<u8>, start: f64, bytes: &[u8]) -> RtResult<()> {
    let at = span(func, start, bytes.len())?;
    let end = at + bytes.len();
    if raw.len() < end {
        raw.resize(end, 0);
    }
    if let Some(dst) = raw.get_mut(at..end) {
        dst.copy_from_slice(bytes);
    }
    Ok(())
}

/// The `n` valid bytes at 1-based `start`.
pub fn take<'a>(func: &'static str, raw: &'a [u8], start: f64, n: usize) -> RtResult<&'a [u8]> {
    let at = span(func, start, n)?;
    raw.get(at..at + n).ok_or_else(|| RtError::OutOfBounds {
        func,
        reason: format!(
            "{n} bytes from index {start} go beyond the {} valid bytes",
            raw.len()
        ),
    })
}

/// The bytes of integer `value` in `fmt`.
pub fn int_bytes(
    func: &'static str,
    value: f64,
    fmt: IntFormat,
    network: bool,
) -> RtResult<Vec<u8>> {
    let (lo, hi) = fmt.range();
    // A finite integer-valued f64 converts exactly (saturating far beyond any range here).
    let v = value as i128;
    if !value.is_finite() || value.fract() != 0.0 || v < lo || v > hi {
        return Err(RtError::arg(
            func,
            format!("{value} is not an integer of {} ({lo} to {hi})", fmt.name()),
        ));
    }
    let le = v.to_le_bytes();
    let mut out: Vec<u8> = le.iter().take(fmt.size).copied().collect();
    if network {
        out.reverse();
    }
    Ok(out)
}

/// The integer that `bytes` hold in `fmt`.
pub fn int_value(bytes: &[u8], fmt: IntFormat, network: bool) -> i128 {
    let mut le: Vec<u8> = bytes.to_vec();
    if network {
        le.reverse();
    }
    let mut v: u128 = 0;
    for (i, b) in le.iter().enumerate() {
        v |= u128::from(*b) << (8 * i);
    }
    let bits = 8 * fmt.size as u32;
    if fmt.signed && bits > 0 && v >> (bits - 1) & 1 == 1 {
        v as i128 - (1i128 << bits)
    } else {
        v as i128
    }
}

/// An unpacked integer as a `num` (`ERR_ARGVALERR` when a `num` cannot hold it exactly).
pub fn int_as_num(func: &'static str, v: i128) -> RtResult<f32> {
    let f = v as f32;
    if f as i128 != v {
        return Err(RtError::arg(
            func,
            format!("{v} does not fit a num exactly (unpack it into a dnum)"),
        ));
    }
    Ok(f)
}

/// An unpacked integer as a `dnum` (`ERR_ARGVALERR` when a `dnum` cannot hold it exactly).
pub fn int_as_dnum(func: &'static str, v: i128) -> RtResult<f64> {
    let f = v as f64;
    if f as i128 != v {
        return Err(RtError::arg(
            func,
            format!("{v} does not fit a dnum exactly"),
        ));
    }
    Ok(f)
}

/// The 4 bytes of `value` as an IEEE single.
pub fn float4_bytes(func: &'static str, value: f64, network: bool) -> RtResult<[u8; 4]> {
    let f = value as f32;
    if !f.is_finite() {
        return Err(RtError::NumLimit {
            what: func,
            ty: "a 4-byte float",
        });
    }
    Ok(if network {
        f.to_be_bytes()
    } else {
        f.to_le_bytes()
    })
}

/// The IEEE single that 4 bytes hold (`ERR_NUM_LIMIT` when it is not a finite number).
pub fn float4_value(func: &'static str, bytes: &[u8], network: bool) -> RtResult<f32> {
    let mut b = [0u8; 4];
    for (d, s) in b.iter_mut().zip(bytes) {
        *d = *s;
    }
    let f = if network {
        f32::from_be_bytes(b)
    } else {
        f32::from_le_bytes(b)
    };
    if !f.is_finite() {
        return Err(RtError::NumLimit {
            what: func,
            ty: "num",
        });
    }
    Ok(f)
}

/// One byte from a `byte` value (an integer 0–255).
pub fn byte_of(func: &'static str, value: f64) -> RtResult<u8> {
    if value.fract() != 0.0 || !(0.0..=255.0).contains(&value) {
        return Err(RtError::arg(
            func,
            format!("{value} is not a byte (an integer 0–255)"),
        ));
    }
    Ok(value as u8)
}

/// The bytes of a string's characters (ISO-8859-1, one byte each).
pub fn text_bytes(func: &'static str, text: &str) -> RtResult<Vec<u8>> {
    if text.is_empty() {
        return Err(RtError::arg(
            func,
            "\\ASCII packs 1–80 characters, not an empty string",
        ));
    }
    text.chars()
        .map(|c| {
            u8::try_from(u32::from(c)).map_err(|_| {
                RtError::arg(
                    func,
                    format!("the character {c:?} is not in ISO-8859-1 (one byte per character)"),
                )
            })
        })
        .collect()
}

/// The string that bytes spell (one character each, ISO-8859-1).
pub fn bytes_text(bytes: &[u8]) -> String {
    bytes.iter().map(|&b| char::from(b)).collect()
}

/// `CopyRawBytes`: `count` valid bytes of `from` (default: all from `from_index` to its
/// valid length) to `to` at `to_index`.
pub fn copy(
    from: &[u8],
    from_index: f64,
    to: &mut Vec<u8>,
    to_index: f64,
    count: Option<f64>,
) -> RtResult<()> {
    const F: &str = "CopyRawBytes";
    let n = match count {
        Some(c) => {
            if c.fract() != 0.0 || !(1.0..=CAPACITY as f64).contains(&c) {
                return Err(RtError::arg(
                    F,
                    format!("\\NoOfBytes:={c} is not 1–{CAPACITY}"),
                ));
            }
            c as usize
        }
        None => {
            span(F, from_index, 0)?;
            (from.len() + 1).saturating_sub(from_index as usize)
        }
    };
    if n == 0 {
        return Ok(());
    }
    let bytes = take(F, from, from_index, n)?.to_vec();
    place(F, to, to_index, &bytes)
}

/// `ClearRawBytes`: zero from `from_index` (default 1) on; the valid length becomes
/// `from_index − 1`.
pub fn clear(raw: &mut Vec<u8>, from_index: Option<f64>) -> RtResult<()> {
    let at = match from_index {
        Some(i) => span("ClearRawBytes", i, 0)?,
        None => 0,
    };
    raw.resize(at, 0);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fmt(code: f64) -> IntFormat {
        IntFormat::from_code("t", code).unwrap()
    }

    #[test]
    fn integer_formats_round_trip_in_both_orders() {
        // RAPID reference, PackRawBytes example 1: DINT 8 is 08 00 00 00 (little-endian).
        assert_eq!(int_bytes("t", 8.0, fmt(-4.0), false).unwrap(), [8, 0, 0, 0]);
        assert_eq!(int_bytes("t", 8.0, fmt(-4.0), true).unwrap(), [0, 0, 0, 8]);
        // Example 2: UDINT 4294967295 fills 4 bytes; example 3: LINT takes 8.
        assert_eq!(
            int_bytes("t", 4294967295.0, fmt(4.0), false).unwrap(),
            [255; 4]
        );
        assert_eq!(
            int_bytes("t", 4294967295.0, fmt(-8.0), false).unwrap(),
            [255, 255, 255, 255, 0, 0, 0, 0]
        );
        for (code, v) in [(-1.0, -128.0), (-2.0, -2.0), (2.0, 65535.0), (8.0, 9e15)] {
            let f = fmt(code);
            for net in [false, true] {
                let b = int_bytes("t", v, f, net).unwrap();
                assert_eq!(b.len(), f.size);
                assert_eq!(int_value(&b, f, net) as f64, v, "{} {net}", f.name());
            }
        }
        assert!(int_bytes("t", 256.0, fmt(1.0), false).is_err());
        assert!(int_bytes("t", -1.0, fmt(4.0), false).is_err());
        assert!(int_bytes("t", 1.5, fmt(-4.0), false).is_err());
        // 2^64 is one more than the largest ULINT.
        assert!(int_bytes("t", 18_446_744_073_709_551_616.0, fmt(8.0), false).is_err());
        assert!(IntFormat::from_code("t", 3.0).is_err());
        assert_eq!(int_as_num("t", 16_777_216).unwrap(), 16_777_216.0);
        assert!(int_as_num("t", 16_777_217).is_err());
    }

    #[test]
    fn floats_and_text() {
        // Example 4: 13.4 as \Float4.
        let b = float4_bytes("t", 13.4, false).unwrap();
        assert_eq!(b, 13.4f32.to_le_bytes());
        assert_eq!(float4_value("t", &b, false).unwrap(), 13.4f32);
        let n = float4_bytes("t", -2.5, true).unwrap();
        assert_eq!(n, [0xC0, 0x20, 0, 0]);
        assert!(float4_value("t", &[0, 0, 0xC0, 0x7F], false).is_err());
        assert!(float4_bytes("t", 1e300, false).is_err());
        // Examples 5 and 6: byte 122 is "z"; "abcdefg" is 7 bytes.
        assert_eq!(byte_of("t", 122.0).unwrap(), b'z');
        assert_eq!(text_bytes("t", "abcdefg").unwrap(), b"abcdefg");
        assert_eq!(bytes_text(&[0x41, 0xC4]), "AÄ");
        assert!(text_bytes("t", "€").is_err());
        assert!(byte_of("t", 256.0).is_err());
    }

    #[test]
    fn lengths_follow_the_packs() {
        let mut raw = Vec::new();
        place("t", &mut raw, 5.0, &[1, 2]).unwrap();
        assert_eq!(raw, [0, 0, 0, 0, 1, 2]);
        // Inside the valid bytes: the length stays.
        place("t", &mut raw, 1.0, &[9]).unwrap();
        assert_eq!(raw.len(), 6);
        assert!(place("t", &mut raw, 1024.0, &[1, 2]).is_err());
        assert!(place("t", &mut raw, 0.0, &[1]).is_err());
        place("t", &mut raw, 1024.0, &[7]).unwrap();
        assert_eq!(raw.len(), CAPACITY);
        assert_eq!(take("t", &raw, 5.0, 2).unwrap(), [1, 2]);
        clear(&mut raw, Some(3.0)).unwrap();
        assert_eq!(raw, [9, 0]);
        assert!(take("t", &raw, 2.0, 2).is_err());
        let mut to = vec![5];
        copy(&[1, 2, 3, 4], 2.0, &mut to, 2.0, None).unwrap();
        assert_eq!(to, [5, 2, 3, 4]);
        copy(&[1, 2, 3, 4], 5.0, &mut to, 1.0, None).unwrap();
        assert_eq!(to, [5, 2, 3, 4]);
        assert!(copy(&[1, 2], 1.0, &mut to, 1.0, Some(3.0)).is_err());
        clear(&mut to, None).unwrap();
        assert!(to.is_empty());
    }
}
