//! Decimal digit strings of num/dnum values: the one place where binary floats become decimal digits.
//!
//! Every number-to-text conversion of the runtime library starts from the *shortest* decimal
//! text that reads back as the same float (Rust's `{:e}`; for `f32` that is the shortest text
//! that round-trips through `f32`), then rounds that decimal **half away from zero**. So
//! `0.385` (stored as the f32 0.38499999…) rounds to `0.39` at two decimals, as a person
//! reading the program expects, rather than to `0.38` as C's `printf` on the binary value
//! would.

/// A finite decimal `±0.d₁d₂d₃… × 10^exp`. `digits` holds values 0–9 with no leading or
/// trailing zeros; an empty `digits` is zero.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Decimal {
    pub neg: bool,
    pub digits: Vec<u8>,
    pub exp: i32,
}

/// How to drop digits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Mode {
    /// Round half away from zero.
    Round,
    /// Drop the digits (towards zero).
    Trunc,
}

impl Decimal {
    /// Shortest round-trip digits of an `f32`. `None` for NaN or infinity.
    pub fn from_f32(v: f32) -> Option<Decimal> {
        if !v.is_finite() {
            return None;
        }
        Some(Self::parse_sci(&format!("{v:e}")))
    }

    /// Shortest round-trip digits of an `f64`. `None` for NaN or infinity.
    pub fn from_f64(v: f64) -> Option<Decimal> {
        if !v.is_finite() {
            return None;
        }
        Some(Self::parse_sci(&format!("{v:e}")))
    }

    /// Parse Rust's `{:e}` output (`-1.2345e-7`, `0e0`).
    fn parse_sci(s: &str) -> Decimal {
        let (neg, s) = match s.strip_prefix('-') {
            Some(rest) => (true, rest),
            None => (false, s),
        };
        let (mant, e) = s.split_once('e').unwrap_or((s, "0"));
        let e: i32 = e.parse().unwrap_or(0);
        let mut digits: Vec<u8> = mant
            .bytes()
            .filter(u8::is_ascii_digit)
            .map(|b| b - b'0')
            .collect();
        // The mantissa is d.ddd, so the value is 0.dddd × 10^(e+1).
        let mut exp = e + 1;
        while digits.first() == Some(&0) {
            digits.remove(0);
            exp -= 1;
        }
        while digits.last() == Some(&0) {
            digits.pop();
        }
        let mut d = Decimal { neg, digits, exp };
        d.normalise_zero();
        d
    }

    fn normalise_zero(&mut self) {
        if self.digits.is_empty() {
            self.neg = false;
            self.exp = 0;
        }
    }

    /// True for zero.
    pub fn is_zero(&self) -> bool {
        self.digits.is_empty()
    }

    /// Keep the first `keep` significant digits (which may be zero or negative: everything
    /// is dropped, and rounding looks at the implicit zero digits).
    pub fn cut(&mut self, keep: i64, mode: Mode) {
        let len = self.digits.len() as i64;
        if keep >= len {
            return;
        }
        if keep < 0 {
            self.digits.clear();
            self.normalise_zero();
            return;
        }
        let k = keep as usize;
        let round_up = mode == Mode::Round && self.digits.get(k).is_some_and(|&d| d >= 5);
        self.digits.truncate(k);
        if round_up {
            let mut i = k;
            loop {
                if i == 0 {
                    // Carry out of the first digit: 9.99 → 10.0.
                    self.digits.insert(0, 1);
                    self.exp += 1;
                    break;
                }
                i -= 1;
                if let Some(d) = self.digits.get_mut(i) {
                    if *d == 9 {
                        *d = 0;
                    } else {
                        *d += 1;
                        break;
                    }
                }
            }
        }
        while self.digits.last() == Some(&0) {
            self.digits.pop();
        }
        self.normalise_zero();
    }

    /// Round or truncate to `dec` digits after the decimal point.
    pub fn cut_decimals(&mut self, dec: u32, mode: Mode) {
        self.cut(self.exp as i64 + dec as i64, mode);
    }

    /// Round to `n` significant digits.
    pub fn round_significant(&mut self, n: u32) {
        self.cut(n as i64, Mode::Round);
    }

    /// Decimal exponent of the first digit (`x.xxx E+e`), 0 for zero.
    pub fn sci_exponent(&self) -> i32 {
        if self.is_zero() { 0 } else { self.exp - 1 }
    }

    fn digit(&self, i: i64) -> char {
        if i < 0 {
            return '0';
        }
        self.digits
            .get(i as usize)
            .map(|&d| char::from(b'0' + d))
            .unwrap_or('0')
    }

    /// Fixed-point text with exactly `dec` decimals (zero-padded, no rounding: call
    /// [`Decimal::cut_decimals`] first). No sign for zero.
    pub fn to_fixed(&self, dec: u32) -> String {
        let mut s = String::new();
        if self.neg && !self.is_zero() {
            s.push('-');
        }
        if self.exp <= 0 {
            s.push('0');
        } else {
            for i in 0..self.exp as i64 {
                s.push(self.digit(i));
            }
        }
        if dec > 0 {
            s.push('.');
            for j in 0..dec as i64 {
                s.push(self.digit(self.exp as i64 + j));
            }
        }
        s
    }

    /// Fixed-point text with just the decimals the digits need (`%G`-style trailing-zero
    /// removal).
    pub fn to_fixed_trimmed(&self) -> String {
        let dec = (self.digits.len() as i64 - self.exp as i64).max(0) as u32;
        self.to_fixed(dec)
    }

    /// Scientific text `d.ddd` + `E±XX` with exactly `dec` mantissa decimals (zero-padded;
    /// round with [`Decimal::round_significant`] first). The exponent has a sign and at
    /// least two digits, as C's `%E` writes it.
    pub fn to_sci(&self, dec: u32) -> String {
        let mut s = String::new();
        if self.neg && !self.is_zero() {
            s.push('-');
        }
        s.push(self.digit(0));
        if dec > 0 {
            s.push('.');
            for j in 1..=dec as i64 {
                s.push(self.digit(j));
            }
        }
        s.push_str(&exp_suffix(self.sci_exponent()));
        s
    }

    /// Scientific text with trailing zeros of the mantissa removed.
    pub fn to_sci_trimmed(&self) -> String {
        self.to_sci(self.digits.len().saturating_sub(1) as u32)
    }

    /// Plain text that Rust parses back (`-0.385e0` form).
    fn to_parse_text(&self) -> String {
        let mut s = String::new();
        if self.neg {
            s.push('-');
        }
        s.push_str("0.");
        if self.digits.is_empty() {
            s.push('0');
        }
        for &d in &self.digits {
            s.push(char::from(b'0' + d));
        }
        s.push('e');
        s.push_str(&self.exp.to_string());
        s
    }

    /// The nearest `f32` (may be infinite if the decimal is beyond the range).
    pub fn to_f32(&self) -> f32 {
        self.to_parse_text().parse::<f32>().unwrap_or(f32::NAN) + 0.0
    }

    /// The nearest `f64`.
    pub fn to_f64(&self) -> f64 {
        self.to_parse_text().parse::<f64>().unwrap_or(f64::NAN) + 0.0
    }
}

/// `E+05`, `E-12`, `E+123`.
fn exp_suffix(e: i32) -> String {
    let sign = if e < 0 { '-' } else { '+' };
    format!("E{sign}{:02}", e.unsigned_abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn d32(v: f32) -> Decimal {
        Decimal::from_f32(v).unwrap()
    }

    #[test]
    fn shortest_digits() {
        assert_eq!(
            d32(0.385),
            Decimal {
                neg: false,
                digits: vec![3, 8, 5],
                exp: 0
            }
        );
        assert_eq!(
            d32(-120.0),
            Decimal {
                neg: true,
                digits: vec![1, 2],
                exp: 3
            }
        );
        assert!(d32(0.0).is_zero());
        assert!(!d32(-0.0).neg);
        assert_eq!(Decimal::from_f32(f32::NAN), None);
        assert_eq!(Decimal::from_f64(f64::INFINITY), None);
    }

    #[test]
    fn rounding_half_away_and_carry() {
        let mut d = d32(0.385);
        d.cut_decimals(2, Mode::Round);
        assert_eq!(d.to_fixed(2), "0.39");
        let mut d = d32(-0.385);
        d.cut_decimals(2, Mode::Round);
        assert_eq!(d.to_fixed(2), "-0.39");
        let mut d = d32(9.995);
        d.cut_decimals(2, Mode::Round);
        assert_eq!(d.to_fixed(2), "10.00");
        let mut d = d32(0.29);
        d.cut_decimals(2, Mode::Trunc);
        assert_eq!(d.to_fixed(2), "0.29");
        let mut d = d32(0.4);
        d.cut_decimals(0, Mode::Round);
        assert_eq!(d.to_fixed(0), "0");
        let mut d = d32(0.5);
        d.cut_decimals(0, Mode::Round);
        assert_eq!(d.to_fixed(0), "1");
        let mut d = d32(0.001);
        d.cut_decimals(1, Mode::Round);
        assert!(d.is_zero());
        assert_eq!(d.to_fixed(1), "0.0");
        let mut d = d32(-0.001);
        d.cut_decimals(1, Mode::Round);
        assert_eq!(d.to_fixed(1), "0.0");
    }

    #[test]
    fn sci_text() {
        let mut d = d32(0.38521);
        d.round_significant(4);
        assert_eq!(d.to_sci(3), "3.852E-01");
        assert_eq!(d32(9e9).to_sci_trimmed(), "9E+09");
        assert_eq!(d32(0.0).to_sci(2), "0.00E+00");
        assert_eq!(Decimal::from_f64(1e-300).unwrap().to_sci(0), "1E-300");
    }

    #[test]
    fn back_to_float() {
        let mut d = d32(0.385);
        d.cut_decimals(2, Mode::Round);
        assert_eq!(d.to_f32(), 0.39f32);
        assert_eq!(d32(-0.0).to_f32().to_bits(), 0.0f32.to_bits());
        assert_eq!(Decimal::from_f64(0.1).unwrap().to_f64(), 0.1);
    }
}
