//! Signal kinds and definitions, and the built-in signals the EGM manual's examples use.

use std::fmt;

use super::IoError;

/// The kind of an I/O signal (EIO `-SignalType`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SignalKind {
    /// Digital input (`signaldi`).
    Di,
    /// Digital output (`signaldo`).
    Do,
    /// Analog input (`signalai`).
    Ai,
    /// Analog output (`signalao`).
    Ao,
    /// Group input (`signalgi`).
    Gi,
    /// Group output (`signalgo`).
    Go,
}

impl SignalKind {
    /// Parse `DI`, `DO`, `AI`, `AO`, `GI`, `GO` (any case).
    pub fn parse(s: &str) -> Option<SignalKind> {
        Some(match s.to_ascii_uppercase().as_str() {
            "DI" => SignalKind::Di,
            "DO" => SignalKind::Do,
            "AI" => SignalKind::Ai,
            "AO" => SignalKind::Ao,
            "GI" => SignalKind::Gi,
            "GO" => SignalKind::Go,
            _ => return None,
        })
    }

    /// `DI`, `DO`, … as written in EIO.cfg.
    pub fn as_str(self) -> &'static str {
        match self {
            SignalKind::Di => "DI",
            SignalKind::Do => "DO",
            SignalKind::Ai => "AI",
            SignalKind::Ao => "AO",
            SignalKind::Gi => "GI",
            SignalKind::Go => "GO",
        }
    }

    /// The RAPID data type of a variable bound to such a signal (`signaldi`, …).
    pub fn rapid_type(self) -> &'static str {
        match self {
            SignalKind::Di => "signaldi",
            SignalKind::Do => "signaldo",
            SignalKind::Ai => "signalai",
            SignalKind::Ao => "signalao",
            SignalKind::Gi => "signalgi",
            SignalKind::Go => "signalgo",
        }
    }

    /// DO, AO or GO.
    pub fn is_output(self) -> bool {
        matches!(self, SignalKind::Do | SignalKind::Ao | SignalKind::Go)
    }

    /// DI or DO.
    pub fn is_digital(self) -> bool {
        matches!(self, SignalKind::Di | SignalKind::Do)
    }

    /// AI or AO.
    pub fn is_analog(self) -> bool {
        matches!(self, SignalKind::Ai | SignalKind::Ao)
    }

    /// GI or GO.
    pub fn is_group(self) -> bool {
        matches!(self, SignalKind::Gi | SignalKind::Go)
    }
}

impl fmt::Display for SignalKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The largest group width (bits).
pub const MAX_GROUP_BITS: u32 = 32;

/// The definition of one signal.
#[derive(Clone, Debug, PartialEq)]
pub struct SignalDef {
    /// Name as written (lookups are case-insensitive).
    pub name: String,
    /// Kind.
    pub kind: SignalKind,
    /// I/O device (`-Device`, older `-Unit`), if any; informational.
    pub device: Option<String>,
    /// Bit mapping on the device (`-DeviceMap`, older `-UnitMap`), e.g. `"0-7"`.
    pub device_map: Option<String>,
    /// Analog: smallest logical value (`-MinLog`).
    pub min_log: f64,
    /// Analog: largest logical value (`-MaxLog`).
    pub max_log: f64,
    /// Analog: physical value at `min_log` (`-MinPhys`).
    pub min_phys: f64,
    /// Analog: physical value at `max_log` (`-MaxPhys`).
    pub max_phys: f64,
    /// Group: width in bits (1 for digital, 0 for analog).
    pub bits: u32,
    /// Value at start and after a reset (`-Default`).
    pub default: f64,
}

impl SignalDef {
    /// A digital signal (DI or DO), default 0.
    pub fn digital(name: impl Into<String>, kind: SignalKind) -> SignalDef {
        SignalDef {
            name: name.into(),
            kind,
            device: None,
            device_map: None,
            min_log: 0.0,
            max_log: 1.0,
            min_phys: 0.0,
            max_phys: 1.0,
            bits: 1,
            default: 0.0,
        }
    }

    /// An analog signal (AI or AO) with logical range `min..=max` (physical range the
    /// same), default 0.
    pub fn analog(name: impl Into<String>, kind: SignalKind, min: f64, max: f64) -> SignalDef {
        SignalDef {
            name: name.into(),
            kind,
            device: None,
            device_map: None,
            min_log: min,
            max_log: max,
            min_phys: min,
            max_phys: max,
            bits: 0,
            default: 0.0,
        }
    }

    /// A group signal (GI or GO) of `bits` bits, default 0.
    pub fn group(name: impl Into<String>, kind: SignalKind, bits: u32) -> SignalDef {
        SignalDef {
            name: name.into(),
            kind,
            device: None,
            device_map: None,
            min_log: 0.0,
            max_log: 0.0,
            min_phys: 0.0,
            max_phys: 0.0,
            bits,
            default: 0.0,
        }
    }

    /// The same definition with another default value.
    pub fn with_default(mut self, default: f64) -> SignalDef {
        self.default = default;
        self
    }

    /// Largest group value `2^bits − 1` (0 for non-group signals).
    pub fn group_max(&self) -> u64 {
        if self.kind.is_group() && self.bits > 0 {
            (1u64 << self.bits.min(MAX_GROUP_BITS)) - 1
        } else {
            0
        }
    }

    /// The physical value of an analog logical value (linear scaling between the logical
    /// and the physical range; the logical value itself when the logical range is empty).
    pub fn physical(&self, logical: f64) -> f64 {
        let span = self.max_log - self.min_log;
        if !self.kind.is_analog() || span == 0.0 {
            return logical;
        }
        self.min_phys + (logical - self.min_log) * (self.max_phys - self.min_phys) / span
    }

    /// Check that `value` is a valid logical value for this signal.
    pub fn check_value(&self, value: f64) -> Result<(), IoError> {
        if !value.is_finite() {
            return Err(IoError::BadValue {
                name: self.name.clone(),
                kind: self.kind,
                value,
                hint: ": not a finite number",
            });
        }
        match self.kind {
            SignalKind::Di | SignalKind::Do => {
                if value == 0.0 || value == 1.0 {
                    Ok(())
                } else {
                    Err(IoError::BadValue {
                        name: self.name.clone(),
                        kind: self.kind,
                        value,
                        hint: ": a digital signal takes 0 or 1",
                    })
                }
            }
            SignalKind::Ai | SignalKind::Ao => {
                if (self.min_log..=self.max_log).contains(&value) {
                    Ok(())
                } else {
                    Err(IoError::AnalogOutOfRange {
                        name: self.name.clone(),
                        value,
                        min: self.min_log,
                        max: self.max_log,
                    })
                }
            }
            SignalKind::Gi | SignalKind::Go => {
                let max = self.group_max();
                if value >= 0.0 && value.fract() == 0.0 && value <= max as f64 {
                    Ok(())
                } else {
                    Err(IoError::GroupOutOfRange {
                        name: self.name.clone(),
                        value,
                        bits: self.bits,
                        max,
                    })
                }
            }
        }
    }

    /// Check the definition itself: a name, a sane range and width, a valid default.
    pub fn validate(&self) -> Result<(), IoError> {
        let invalid = |reason: String| IoError::InvalidDefinition {
            name: self.name.clone(),
            reason,
        };
        if self.name.is_empty() {
            return Err(invalid("the name is empty".into()));
        }
        if self.kind.is_analog() {
            if !self.min_log.is_finite() || !self.max_log.is_finite() {
                return Err(invalid("the logical range is not finite".into()));
            }
            if self.min_log > self.max_log {
                return Err(invalid(format!(
                    "MinLog {} is greater than MaxLog {}",
                    self.min_log, self.max_log
                )));
            }
        }
        if self.kind.is_group() && !(1..=MAX_GROUP_BITS).contains(&self.bits) {
            return Err(invalid(format!(
                "a group signal has 1 to {MAX_GROUP_BITS} bits, not {}",
                self.bits
            )));
        }
        self.check_value(self.default)
            .map_err(|e| invalid(format!("the default value is not valid: {e}")))
    }
}

/// The signals rapidvc defines without any configuration: the analog outputs of the EGM
/// manual's signal example (docs/egm.md, "Signal sources"), range −2000…2000 (mm or degrees).
pub fn builtin_signals() -> Vec<SignalDef> {
    [
        "ao_MoveX", "ao_MoveY", "ao_MoveZ", "ao_RotX", "ao_RotY", "ao_RotZ",
    ]
    .into_iter()
    .map(|n| SignalDef::analog(n, SignalKind::Ao, -2000.0, 2000.0))
    .collect()
}

/// `base` with every definition of `overrides` added; an override replaces a base
/// definition of the same name (case-insensitive), keeping the base's position.
pub fn merge_defs(base: Vec<SignalDef>, overrides: Vec<SignalDef>) -> Vec<SignalDef> {
    // Position of each name (ASCII case folded) in `out`: linear in the number of signals.
    let mut at: std::collections::HashMap<String, usize> = base
        .iter()
        .enumerate()
        .map(|(i, d)| (d.name.to_ascii_lowercase(), i))
        .collect();
    let mut out = base;
    out.reserve(overrides.len());
    for o in overrides {
        match at.entry(o.name.to_ascii_lowercase()) {
            std::collections::hash_map::Entry::Occupied(i) => {
                if let Some(slot) = out.get_mut(*i.get()) {
                    *slot = o;
                }
            }
            std::collections::hash_map::Entry::Vacant(v) => {
                v.insert(out.len());
                out.push(o);
            }
        }
    }
    out
}
