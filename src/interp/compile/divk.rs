//! `DIV` and `MOD` by a constant integer with a precomputed reciprocal: a multiply-high
//! instead of a hardware division on the hot path (same truncating results).

/// Division by a constant integer `k` ≠ 0.
#[derive(Clone, Copy, Debug)]
pub(crate) struct DivK {
    k: i32,
    abs: u32,
    /// ⌈2⁶⁴ / |k|⌉ (unused for |k| = 1): for every n < 2³² and 2 ≤ d < 2³²,
    /// ⌊n·⌈2⁶⁴/d⌉ / 2⁶⁴⌋ = ⌊n/d⌋, because the excess n·e/2⁶⁴ (e < 1) stays below 2⁻³² ≤ 1/d.
    m: u64,
}

impl DivK {
    pub(crate) fn new(k: i32) -> DivK {
        let abs = k.unsigned_abs();
        let m = if abs >= 2 {
            (u64::MAX / abs as u64) + 1
        } else {
            0
        };
        DivK { k, abs, m }
    }

    /// The divisor.
    pub(crate) fn k(&self) -> i32 {
        self.k
    }

    /// `x DIV k` (truncating) or `x MOD k` (the sign follows `x`), for `x` ≠ `i32::MIN`.
    #[inline(always)]
    pub(crate) fn apply(&self, x: i32, is_mod: bool) -> i32 {
        let n = x.unsigned_abs();
        let q = if self.abs == 1 {
            n
        } else {
            ((n as u128 * self.m as u128) >> 64) as u32
        };
        if is_mod {
            let r = (n - q * self.abs) as i32;
            if x < 0 { -r } else { r }
        } else {
            let q = q as i32;
            if (x < 0) != (self.k < 0) { -q } else { q }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::DivK;

    #[test]
    fn matches_hardware_division() {
        let ks = [
            1,
            -1,
            2,
            -2,
            3,
            7,
            -7,
            10,
            100,
            -100,
            1000,
            65536,
            65537,
            999_983,
            8_388_607,
            16_777_215,
            -16_777_215,
        ];
        let mut xs: Vec<i32> = vec![
            0,
            1,
            -1,
            2,
            99,
            100,
            101,
            -101,
            i32::MAX,
            i32::MIN + 1,
            16_777_216,
            -16_777_216,
            2_147_483_520,
        ];
        let mut s = 0x9e37_79b9_u32;
        for _ in 0..20_000 {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            xs.push(s as i32);
            xs.push((s >> 8) as i32 - (1 << 23));
        }
        for &k in &ks {
            let d = DivK::new(k);
            for &x in &xs {
                if x == i32::MIN {
                    continue;
                }
                assert_eq!(d.apply(x, false), x / k, "{x} DIV {k}");
                assert_eq!(d.apply(x, true), x % k, "{x} MOD {k}");
            }
            // Multiples of k and their neighbours, where a reciprocal is most likely off.
            for q in [1i64, 2, 3, 1000, 65535, 123_456] {
                for delta in [-1i64, 0, 1] {
                    let x = q * k as i64 + delta;
                    if let Ok(x) = i32::try_from(x)
                        && x != i32::MIN
                    {
                        assert_eq!(d.apply(x, false), x / k, "{x} DIV {k}");
                        assert_eq!(d.apply(x, true), x % k, "{x} MOD {k}");
                    }
                }
            }
        }
    }
}
