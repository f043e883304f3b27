//! Simulated seam sensors: a seam's offset from the programmed path (constant, ramp or sine)
//! as a function of arc length, and its text form.

use std::fmt;
use std::str::FromStr;

use super::{PathOffset, Tracker};

/// A seam's offset from the programmed path in the path frame as a function of arc length
/// from the start of the corrected sequence (mm); the module doc gives the text form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SeamProfile {
    /// `const:y=…,z=…`: the same offset everywhere.
    Const {
        /// y offset, mm.
        y: f64,
        /// z offset, mm.
        z: f64,
    },
    /// `ramp:y=…,z=…,len=…`: zero at the start, growing linearly to `(y, z)` at `len`, then
    /// constant.
    Ramp {
        /// y offset at the end of the ramp, mm.
        y: f64,
        /// z offset at the end of the ramp, mm.
        z: f64,
        /// Ramp length, mm (> 0).
        len: f64,
    },
    /// `sine:y=…,z=…,period=…[,phase=…]`: `(y, z) · sin(360° · s / period + phase)`.
    Sine {
        /// y amplitude, mm.
        y: f64,
        /// z amplitude, mm.
        z: f64,
        /// Period along the path, mm (> 0).
        period: f64,
        /// Phase, degrees.
        phase: f64,
    },
}

impl SeamProfile {
    /// The seam offset at arc length `s` (mm); zero for a non-finite `s`.
    pub fn offset_at(&self, s: f64) -> PathOffset {
        if !s.is_finite() {
            return PathOffset::ZERO;
        }
        match *self {
            SeamProfile::Const { y, z } => PathOffset::new(y, z),
            SeamProfile::Ramp { y, z, len } => {
                let k = (s / len).clamp(0.0, 1.0);
                PathOffset::new(y * k, z * k)
            }
            SeamProfile::Sine {
                y,
                z,
                period,
                phase,
            } => {
                // Cycles along the path plus the phase as a fraction of a cycle.
                let cycles = s / period + phase / 360.0;
                let k = (std::f64::consts::TAU * cycles.fract()).sin();
                PathOffset::new(y * k, z * k)
            }
        }
    }

    /// What a simulated sensor of kind `tracker` reports with the TCP at arc length
    /// `tcp_s`: the seam under the sensor (at the TCP for APTR, `look_ahead` ahead for
    /// LATR).
    pub fn sensed_at(&self, tracker: Tracker, tcp_s: f64) -> PathOffset {
        match tracker {
            Tracker::Aptr => self.offset_at(tcp_s),
            Tracker::Latr { look_ahead } => self.offset_at(tcp_s + look_ahead),
        }
    }
}

/// Why a seam pattern text cannot be read.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SeamError {
    /// Nothing given.
    #[error("the pattern is empty")]
    Empty,
    /// Not const, ramp or sine.
    #[error("`{0}` is not a seam pattern; use const, ramp or sine")]
    UnknownKind(String),
    /// A key the kind does not take.
    #[error("{kind} takes {allowed}, not `{key}`")]
    UnknownKey {
        /// The kind.
        kind: &'static str,
        /// The key as written.
        key: String,
        /// The keys it takes.
        allowed: &'static str,
    },
    /// Two commas with nothing between them.
    #[error("an empty item between commas")]
    EmptyItem,
    /// `key` without `=value`.
    #[error("`{0}` needs a value: `{0}=NUMBER`")]
    MissingValue(String),
    /// A value that is not a finite number.
    #[error("`{key}={value}`: not a number")]
    BadNumber {
        /// The key.
        key: String,
        /// The value as written.
        value: String,
    },
    /// The same key twice.
    #[error("`{0}` is given twice")]
    Duplicate(String),
    /// A required key is missing.
    #[error("{kind} needs `{key}=`")]
    Missing {
        /// The kind.
        kind: &'static str,
        /// The key.
        key: &'static str,
    },
    /// A length that must be positive.
    #[error("`{key}` must be greater than 0 mm, not {value}")]
    NotPositive {
        /// The key.
        key: &'static str,
        /// The value.
        value: String,
    },
}

/// A seam pattern text that cannot be read, with the text.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "bad seam pattern `{input}`: {error} (examples: `const:y=3,z=-2`, `ramp:y=5,z=0,len=400`, `sine:y=2,z=0,period=100`)"
)]
pub struct SeamParseError {
    /// The text.
    pub input: String,
    /// What is wrong.
    pub error: SeamError,
}

impl SeamProfile {
    /// Read the text form (module doc); kinds and keys are case-insensitive, spaces around
    /// them are ignored, missing `y`/`z`/`phase` are 0.
    pub fn parse(text: &str) -> Result<SeamProfile, SeamParseError> {
        Self::parse_inner(text).map_err(|error| SeamParseError {
            input: text.to_string(),
            error,
        })
    }

    fn parse_inner(text: &str) -> Result<SeamProfile, SeamError> {
        let text = text.trim();
        if text.is_empty() {
            return Err(SeamError::Empty);
        }
        let (kind, params) = match text.split_once(':') {
            Some((k, p)) => (k.trim(), p.trim()),
            None => (text, ""),
        };
        let (kind, allowed): (&'static str, &'static str) = match kind.to_ascii_lowercase().as_str()
        {
            "const" => ("const", "y and z"),
            "ramp" => ("ramp", "y, z and len"),
            "sine" => ("sine", "y, z, period and phase"),
            _ => return Err(SeamError::UnknownKind(kind.to_string())),
        };
        // Values of y, z, len, period, phase.
        let mut values: [Option<f64>; 5] = [None; 5];
        if !params.is_empty() {
            for part in params.split(',').map(str::trim) {
                if part.is_empty() {
                    return Err(SeamError::EmptyItem);
                }
                let Some((key, value)) = part.split_once('=').map(|(k, v)| (k.trim(), v.trim()))
                else {
                    return Err(SeamError::MissingValue(part.to_string()));
                };
                let slot = match (kind, key.to_ascii_lowercase().as_str()) {
                    (_, "y") => 0,
                    (_, "z") => 1,
                    ("ramp", "len") => 2,
                    ("sine", "period") => 3,
                    ("sine", "phase") => 4,
                    _ => {
                        return Err(SeamError::UnknownKey {
                            kind,
                            key: key.to_string(),
                            allowed,
                        });
                    }
                };
                let number = value
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| SeamError::BadNumber {
                        key: key.to_string(),
                        value: value.to_string(),
                    })?;
                match values.get_mut(slot) {
                    Some(Some(_)) => return Err(SeamError::Duplicate(key.to_string())),
                    Some(v) => *v = Some(number),
                    None => {}
                }
            }
        }
        let get = |i: usize| values.get(i).copied().flatten();
        let y = get(0).unwrap_or(0.0);
        let z = get(1).unwrap_or(0.0);
        let required_positive = |i: usize, key: &'static str| -> Result<f64, SeamError> {
            match get(i) {
                None => Err(SeamError::Missing { kind, key }),
                Some(v) if v > 0.0 => Ok(v),
                Some(v) => Err(SeamError::NotPositive {
                    key,
                    value: v.to_string(),
                }),
            }
        };
        Ok(match kind {
            "const" => SeamProfile::Const { y, z },
            "ramp" => SeamProfile::Ramp {
                y,
                z,
                len: required_positive(2, "len")?,
            },
            _ => SeamProfile::Sine {
                y,
                z,
                period: required_positive(3, "period")?,
                phase: get(4).unwrap_or(0.0),
            },
        })
    }
}

impl FromStr for SeamProfile {
    type Err = SeamParseError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        SeamProfile::parse(s)
    }
}

impl fmt::Display for SeamProfile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            SeamProfile::Const { y, z } => write!(f, "const:y={y},z={z}"),
            SeamProfile::Ramp { y, z, len } => write!(f, "ramp:y={y},z={z},len={len}"),
            SeamProfile::Sine {
                y,
                z,
                period,
                phase,
            } => {
                write!(f, "sine:y={y},z={z},period={period}")?;
                if phase != 0.0 {
                    write!(f, ",phase={phase}")?;
                }
                Ok(())
            }
        }
    }
}
