//! Deterministic number formatting for traces and summaries: fixed decimals, no negative zero,
//! and a canonical quaternion sign.

use std::fmt::Write as _;

use crate::time::RobotTime;

/// Append `x` with `decimals` digits after the point to `out`. `-0.000` is written `0.000`,
/// so a value that rounds to zero never shows a sign; non-finite values are written `NaN`,
/// `inf` or `-inf`.
///
/// Values whose scaled magnitude fits in 2^53 are rounded as integers (`round(x·10^d)`, fast
/// and deterministic); others go through the standard formatter.
pub fn push_fixed(out: &mut String, x: f64, decimals: usize) {
    const POW10: [f64; 10] = [1.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9];
    let scaled = POW10.get(decimals).map(|p| (x * p).round());
    match scaled {
        Some(v) if v.is_finite() && v.abs() < 9.0e15 => {
            let n = v as i64;
            let unit = 10i64.pow(decimals as u32);
            let (int, frac) = (
                n.unsigned_abs() / unit as u64,
                n.unsigned_abs() % unit as u64,
            );
            if n < 0 {
                out.push('-');
            }
            let _ = write!(out, "{int}");
            if decimals > 0 {
                let _ = write!(out, ".{frac:0decimals$}");
            }
        }
        _ => {
            let start = out.len();
            let _ = write!(out, "{x:.decimals$}");
            let written = out.get(start..).unwrap_or("");
            if written.starts_with('-') && written.bytes().skip(1).all(|b| b == b'0' || b == b'.') {
                out.remove(start);
            }
        }
    }
}

/// `x` with `decimals` digits after the point (see [`push_fixed`]).
pub fn fixed(x: f64, decimals: usize) -> String {
    let mut s = String::new();
    push_fixed(&mut s, x, decimals);
    s
}

/// Robot time as seconds with microsecond resolution, computed from the integer nanoseconds
/// (exact, so every run prints the same text): `12.344000`.
pub fn push_time(out: &mut String, t: RobotTime) {
    let ns = t.as_nanos();
    let _ = write!(
        out,
        "{}.{:06}",
        ns / 1_000_000_000,
        (ns % 1_000_000_000) / 1000
    );
}

/// A quaternion `[w, x, y, z]` with the sign chosen so that the first non-zero component
/// (w first) is positive (q and −q are the same rotation; the trace shows one of them).
pub fn canonical_quat(q: [f64; 4]) -> [f64; 4] {
    match q.iter().find(|c| **c != 0.0) {
        Some(c) if *c < 0.0 => q.map(|c| -c),
        _ => q,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formatting() {
        assert_eq!(fixed(-0.00001, 3), "0.000");
        assert_eq!(fixed(-0.0, 2), "0.00");
        assert_eq!(fixed(-1.5, 1), "-1.5");
        assert_eq!(fixed(83.4981, 2), "83.50");
        assert_eq!(fixed(-0.1234567, 6), "-0.123457");
        assert_eq!(fixed(1014.62794, 4), "1014.6279");
        assert_eq!(fixed(7.0, 0), "7");
        assert_eq!(fixed(1e300, 3).len(), 305);
        assert_eq!(fixed(f64::NAN, 3), "NaN");
        assert_eq!(fixed(-2.5e-7, 6), "0.000000");
        let mut s = String::from("t=");
        push_time(&mut s, RobotTime::from_nanos(12_344_000_000));
        assert_eq!(s, "t=12.344000");
        assert_eq!(
            canonical_quat([-0.5, 0.5, 0.5, 0.5]),
            [0.5, -0.5, -0.5, -0.5]
        );
        assert_eq!(canonical_quat([0.0, -1.0, 0.0, 0.0]), [0.0, 1.0, 0.0, 0.0]);
    }
}
