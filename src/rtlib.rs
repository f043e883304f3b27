//! Pure runtime-library functions behind RAPID's built-ins: number text, num/dnum arithmetic, strings and poses.
//!
//! Everything here works on plain Rust types (`f32` for `num`, `f64` for `dnum`, `&str`,
//! `[f64; 3]` positions, `[f64; 4]` quaternions) and never touches interpreter state. The
//! interpreter wraps these functions as RAPID natives. Every failure is an [`RtError`]; its
//! [`RtError::err_name`] is the RAPID `ERR_*` constant the interpreter raises (so a RAPID
//! `ERROR` handler can catch it), and its `Display` text is the message for the event log.
//!
//! Decisions that are not settled by an ABB document are listed in the doc of each module and
//! pinned by unit tests there.

mod decimal;
pub mod format;
pub mod math;
pub mod pose;
pub mod string;

/// An error raised by a runtime-library function.
///
/// The mapping to RAPID error names ([`RtError::err_name`]) is a rapidvc decision where no
/// ABB document settles it; the names themselves all exist in RobotWare.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RtError {
    /// Division (`/`, `DIV`, `MOD`) by zero. RAPID: `ERR_DIVZERO`.
    #[error("division by zero")]
    DivZero,
    /// An operand that must be an integer is not (DIV/MOD operands). RAPID: `ERR_NOTINTVAL`.
    #[error("{what} must be an integer value, not {value}")]
    NotInteger {
        /// What was expected to be an integer (e.g. "left operand of DIV").
        what: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A result or value does not fit the data type (outside the IEEE single range for
    /// `num`, double range for `dnum`, or not a number). RAPID: `ERR_NUM_LIMIT`.
    #[error("{what}: the value is outside the range of {ty}")]
    NumLimit {
        /// The operation or function.
        what: &'static str,
        /// `num` or `dnum`.
        ty: &'static str,
    },
    /// An argument value is not allowed (domain errors such as `Sqrt(-1)`, `ASin(2)`, a
    /// negative `\Dec`). RAPID: `ERR_ARGVALERR`.
    #[error("{func}: {reason}")]
    ArgValue {
        /// The RAPID function name.
        func: &'static str,
        /// Why the argument is not allowed.
        reason: String,
    },
    /// A string would be longer than RAPID's 80 characters. RAPID: `ERR_STRTOOLNG`.
    #[error("string too long: {len} characters (a RAPID string holds at most 80)")]
    StrTooLong {
        /// The length the string would have had.
        len: usize,
    },
    /// A character position or length outside the string. RAPID: `ERR_OUTOFBND`.
    #[error("{func}: {reason}")]
    OutOfBounds {
        /// The RAPID function name.
        func: &'static str,
        /// Which position was wrong, with the string length.
        reason: String,
    },
    /// An orientation that is not a usable quaternion (all zero or not finite). RAPID:
    /// `ERR_ILLQUAT`.
    #[error("{func}: the orientation is not a valid quaternion (it is zero or not finite)")]
    IllQuat {
        /// The RAPID function name.
        func: &'static str,
    },
}

impl RtError {
    /// The RAPID error constant the interpreter raises for this error (its `ERRNO`).
    pub fn err_name(&self) -> &'static str {
        match self {
            RtError::DivZero => "ERR_DIVZERO",
            RtError::NotInteger { .. } => "ERR_NOTINTVAL",
            RtError::NumLimit { .. } => "ERR_NUM_LIMIT",
            RtError::ArgValue { .. } => "ERR_ARGVALERR",
            RtError::StrTooLong { .. } => "ERR_STRTOOLNG",
            RtError::OutOfBounds { .. } => "ERR_OUTOFBND",
            RtError::IllQuat { .. } => "ERR_ILLQUAT",
        }
    }

    pub(crate) fn arg(func: &'static str, reason: impl Into<String>) -> RtError {
        RtError::ArgValue {
            func,
            reason: reason.into(),
        }
    }
}

/// Result of a runtime-library function.
pub type RtResult<T> = Result<T, RtError>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn error_names_are_rapid_constants() {
        assert_eq!(RtError::DivZero.err_name(), "ERR_DIVZERO");
        assert_eq!(
            RtError::NotInteger {
                what: "x",
                value: 1.5
            }
            .err_name(),
            "ERR_NOTINTVAL"
        );
        assert_eq!(
            RtError::NumLimit {
                what: "x",
                ty: "num"
            }
            .err_name(),
            "ERR_NUM_LIMIT"
        );
        assert_eq!(RtError::arg("Sqrt", "negative").err_name(), "ERR_ARGVALERR");
        assert_eq!(RtError::StrTooLong { len: 81 }.err_name(), "ERR_STRTOOLNG");
        assert_eq!(
            RtError::OutOfBounds {
                func: "StrPart",
                reason: String::new()
            }
            .err_name(),
            "ERR_OUTOFBND"
        );
        assert_eq!(
            RtError::IllQuat { func: "NOrient" }.err_name(),
            "ERR_ILLQUAT"
        );
        assert_eq!(
            RtError::StrTooLong { len: 81 }.to_string(),
            "string too long: 81 characters (a RAPID string holds at most 80)"
        );
    }
}
