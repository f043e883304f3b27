//! Checking one sensor correction: finite components, magnitude and age within the limits.

use super::{PathOffset, non_negative_finite};

/// Limits on what a sensor may send.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CorrectionLimits {
    /// Largest total correction |(y, z)|, mm. Default 100.
    pub max_offset: f64,
    /// Largest measurement age, s. Default 2.
    pub max_age: f64,
}

impl Default for CorrectionLimits {
    fn default() -> Self {
        CorrectionLimits {
            max_offset: 100.0,
            max_age: 2.0,
        }
    }
}

/// Why a correction was not used.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum Rejection {
    /// A component of `pos` is NaN or infinite.
    #[error("path correction {axis} is not a finite number ({value})")]
    NotFinite {
        /// `x`, `y` or `z`.
        axis: char,
        /// The value.
        value: f64,
    },
    /// The correction is larger than the limit.
    #[error("path correction of {magnitude:.3} mm exceeds the limit of {limit} mm")]
    TooLarge {
        /// |(y, z)| of the (total) correction, mm.
        magnitude: f64,
        /// The limit, mm.
        limit: f64,
    },
    /// The age is negative or not a number.
    #[error("path correction age {age} s is negative or not a number")]
    BadAge {
        /// The age, s.
        age: f64,
    },
    /// The measurement is older than the limit.
    #[error("path correction is {age} s old; the limit is {limit} s")]
    TooOld {
        /// The age, s.
        age: f64,
        /// The limit, s.
        limit: f64,
    },
}

/// Check one correction `pos` (x, y, z as sent; x is ignored) with its `age` (s) and
/// return its path-frame offset.
pub fn check_correction(
    pos: [f64; 3],
    age: f64,
    limits: &CorrectionLimits,
) -> Result<PathOffset, Rejection> {
    for (axis, value) in ['x', 'y', 'z'].into_iter().zip(pos) {
        if !value.is_finite() {
            return Err(Rejection::NotFinite { axis, value });
        }
    }
    if !non_negative_finite(age) {
        return Err(Rejection::BadAge { age });
    }
    if age > limits.max_age {
        return Err(Rejection::TooOld {
            age,
            limit: limits.max_age,
        });
    }
    let [_, y, z] = pos;
    let offset = PathOffset::new(y, z);
    check_magnitude(offset, limits)?;
    Ok(offset)
}

pub(super) fn check_magnitude(
    offset: PathOffset,
    limits: &CorrectionLimits,
) -> Result<(), Rejection> {
    let magnitude = offset.norm();
    if magnitude.is_finite() && magnitude <= limits.max_offset {
        Ok(())
    } else {
        Err(Rejection::TooLarge {
            magnitude,
            limit: limits.max_offset,
        })
    }
}
