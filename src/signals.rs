//! The I/O signal table: DI, DO, AI, AO, GI and GO signals, shared lock-free between the interpreter and the motion/EGM thread.
//!
//! Signals are defined by [`SignalDef`]s (from `EIO.cfg`, see `crate::config::eio`, plus
//! [`builtin_signals`] so the EGM manual's examples run without a configuration) and live in
//! a [`SignalTable`] behind an `Arc`. Look a name up once ([`SignalTable::lookup`],
//! case-insensitive) and keep the [`SignalId`]: every read after that is one atomic load.
//!
//! # Decisions (pinned by the tests in `signals/table.rs`)
//!
//! * Values are **logical** values stored as `f64`: digital 0/1, analog in
//!   `min_log..=max_log`, group an integer in `0..=2^bits − 1`.
//! * Setting a value outside that range is an error and leaves the signal unchanged:
//!   analog → [`IoError::AnalogOutOfRange`] (`ERR_AO_LIM`), group →
//!   [`IoError::GroupOutOfRange`] (`ERR_GO_LIM`), digital other than 0/1 or a non-finite
//!   value → [`IoError::BadValue`] (`ERR_ARGVALERR`).
//! * An analog signal whose `-MinLog` and `-MaxLog` are both left at 0 has the range 0..0,
//!   as on a controller where an unconfigured analog output refuses every value but 0.
//! * A group signal without `-DeviceMap` is 32 bits wide.
//! * Every change of a value (a set to the value it already has is not a change) increments
//!   the signal's **generation** counter and the table's total generation. The interpreter
//!   polls them for `ISignalDI`/`ISignalDO`/`ISignalAO` interrupts: a generation that moved by
//!   `n` means `n` changes happened since the last poll (for a digital signal they alternate,
//!   so edges can be reconstructed from the count and the current value).

mod definitions;
mod table;

pub use definitions::{MAX_GROUP_BITS, SignalDef, SignalKind, builtin_signals, merge_defs};
pub use table::{SignalId, SignalTable};

/// An error from the signal table.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum IoError {
    /// No signal of that name is defined.
    #[error("I/O signal `{name}` is not defined (define it in EIO.cfg)")]
    UnknownSignal {
        /// The name as written.
        name: String,
    },
    /// An analog value outside the logical range.
    #[error("value {value} is outside the logical range {min}..{max} of analog signal `{name}`")]
    AnalogOutOfRange {
        /// Signal name.
        name: String,
        /// The rejected value.
        value: f64,
        /// `-MinLog`.
        min: f64,
        /// `-MaxLog`.
        max: f64,
    },
    /// A group value that is not an integer in `0..=2^bits − 1`.
    #[error(
        "value {value} does not fit group signal `{name}`: it takes an integer 0..{max} ({bits} bits)"
    )]
    GroupOutOfRange {
        /// Signal name.
        name: String,
        /// The rejected value.
        value: f64,
        /// Width in bits.
        bits: u32,
        /// Largest value, `2^bits − 1`.
        max: u64,
    },
    /// A digital value other than 0 or 1, or a value that is not a finite number.
    #[error("value {value} is not allowed for {kind} signal `{name}`{hint}")]
    BadValue {
        /// Signal name.
        name: String,
        /// Signal kind (`DO`, …).
        kind: SignalKind,
        /// The rejected value.
        value: f64,
        /// Extra explanation (starts with `: ` when present).
        hint: &'static str,
    },
    /// The same name defined twice in one table.
    #[error("I/O signal `{name}` is defined twice")]
    DuplicateSignal {
        /// The name.
        name: String,
    },
    /// A definition that cannot be used (empty name, reversed range, default out of range).
    #[error("I/O signal `{name}`: {reason}")]
    InvalidDefinition {
        /// The name.
        name: String,
        /// What is wrong.
        reason: String,
    },
}

impl IoError {
    /// The RAPID error constant for a run-time error (`None` for definition errors, which
    /// are reported when the configuration is loaded).
    pub fn err_name(&self) -> Option<&'static str> {
        match self {
            IoError::AnalogOutOfRange { .. } => Some("ERR_AO_LIM"),
            IoError::GroupOutOfRange { .. } => Some("ERR_GO_LIM"),
            IoError::BadValue { .. } => Some("ERR_ARGVALERR"),
            IoError::UnknownSignal { .. } => Some("ERR_SIG_NAME"),
            IoError::DuplicateSignal { .. } | IoError::InvalidDefinition { .. } => None,
        }
    }
}
