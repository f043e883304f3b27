//! The EIO domain: `EIO_SIGNAL` instances of an `EIO.cfg` file as I/O signal definitions.
//!
//! | attribute | meaning | rapidvc |
//! |---|---|---|
//! | `-Name` | signal name (required) | lookup is case-insensitive |
//! | `-SignalType` | `DI`, `DO`, `AI`, `AO`, `GI`, `GO` (required) | |
//! | `-Device` (RW6+), `-Unit` (RW5) | I/O device | kept, informational |
//! | `-DeviceMap`, `-UnitMap` | bits on the device: `"0"`, `"0-7"`, `"0-3,8-11"` | the bit count is a group signal's width (32 without a map) |
//! | `-MinLog`, `-MaxLog` | analog logical range | default 0 and 0 (a warning: such a signal only takes 0) |
//! | `-MinPhys`, `-MaxPhys` | analog physical range | default: the logical range |
//! | `-Default` | value at start | must be valid for the signal |
//!
//! Accepted and ignored without a warning (they change nothing in a virtual controller):
//! `-Access`, `-Category`, `-Label`, `-Invert`, `-FiltPas`, `-FiltAct`, `-SysfailReset`,
//! `-Store`, `-SafeLevel`, `-EncType`, `-MinBitVal`, `-MaxBitVal`, `-MinPhysLimit`,
//! `-MaxPhysLimit`. Any other attribute is a warning.
//!
//! `SYSSIG_OUT` instances (`-Status "MotOnState" -Signal "doMotorOn"`, `-Arg1` a mechanical
//! unit, `-Arg2` a task) are the controller's system outputs: the statuses the controller
//! drives are listed in [`SYSTEM_OUTPUTS`] (`controller::system_outputs` sets them); another
//! status is a warning, a signal that is no DO of the file an error. Other sections
//! (`EIO_BUS`, `EIO_UNIT`, `SYSSIG_IN`, …) are skipped; `EIO_CROSS` (cross connections, which
//! would change signal behaviour) gets an "is not supported" warning.

use std::collections::HashMap;
use std::collections::hash_map::Entry;

use crate::diag::Diagnostics;
use crate::signals::{IoError, MAX_GROUP_BITS, SignalDef, SignalKind};
use crate::source::{SourceId, Span};

use super::ConfigError;
use super::attr::{keep, missing_attr, num_attr, text_attr, warn_unknown};
use super::cfg::{CfgFile, CfgInstance};

/// The section that defines signals.
pub const SIGNAL_SECTION: &str = "EIO_SIGNAL";

/// Attributes of `EIO_SIGNAL` that rapidvc reads.
const USED: &[&str] = &[
    "Name",
    "SignalType",
    "Device",
    "Unit",
    "DeviceMap",
    "UnitMap",
    "MinLog",
    "MaxLog",
    "MinPhys",
    "MaxPhys",
    "Default",
];

/// Attributes of `EIO_SIGNAL` that are valid but have no effect in rapidvc.
const IGNORED: &[&str] = &[
    "Access",
    "Category",
    "Label",
    "Invert",
    "FiltPas",
    "FiltAct",
    "SysfailReset",
    "Store",
    "SafeLevel",
    "EncType",
    "MinBitVal",
    "MaxBitVal",
    "MinPhysLimit",
    "MaxPhysLimit",
];

/// Sections that would change signal behaviour but are not implemented.
const UNSUPPORTED_SECTIONS: &[&str] = &["EIO_CROSS"];

/// The `SYSSIG_OUT` statuses rapidvc drives (`controller::system_outputs`).
pub const SYSTEM_OUTPUTS: &[&str] = &[
    "MotOnState",
    "MotorOnState",
    "MotorOn",
    "MotOffState",
    "MotorOffState",
    "MotorOff",
    "AutoOn",
    "CycleOn",
    "RunchOk",
    "MotSupOn",
    "EmStop",
    "SmbBatteryChargeLow",
    "TaskExecuting",
    "Error",
    "ProdExecError",
    "MechUnitNotMoving",
];

/// One `SYSSIG_OUT` instance: a digital output the controller drives.
#[derive(Clone, Debug, PartialEq)]
pub struct SystemOutput {
    /// The status, as one of [`SYSTEM_OUTPUTS`] is written.
    pub status: &'static str,
    /// The signal's name.
    pub signal: String,
    /// `-Arg1` (a mechanical unit for `MechUnitNotMoving`).
    pub arg1: Option<String>,
    /// `-Arg2` (a task for `TaskExecuting`, `Error`).
    pub arg2: Option<String>,
}

/// One signal read from EIO.cfg.
#[derive(Clone, Debug, PartialEq)]
pub struct EioSignal {
    /// The definition.
    pub def: SignalDef,
    /// Where its `-Name` value is written.
    pub span: Span,
}

/// The signals of one EIO.cfg, valid and distinct (case-insensitive names), in file order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EioConfig {
    /// The signals.
    pub signals: Vec<EioSignal>,
    /// The system outputs the controller drives.
    pub system_outputs: Vec<SystemOutput>,
}

impl EioConfig {
    /// The signal definitions.
    pub fn defs(&self) -> Vec<SignalDef> {
        self.signals.iter().map(|s| s.def.clone()).collect()
    }
}

/// The number of bits a device map covers (`"0-7"` → 8, `"0,2,4-5"` → 4, `"7-0"` → 8).
pub fn device_map_bits(map: &str) -> Option<u32> {
    let mut bits: u32 = 0;
    for part in map.split(',') {
        let part = part.trim();
        let (a, b) = match part.split_once('-') {
            Some((a, b)) => (a.trim(), b.trim()),
            None => (part, part),
        };
        let a: u32 = a.parse().ok()?;
        let b: u32 = b.parse().ok()?;
        bits = bits.checked_add(a.abs_diff(b).checked_add(1)?)?;
    }
    Some(bits)
}

/// Read every `EIO_SIGNAL` instance of `file`. Invalid instances are reported and left out.
pub fn read(file: &CfgFile, diags: &mut Diagnostics) -> EioConfig {
    let src = file.source;
    let mut out = EioConfig::default();
    for section in &file.sections {
        if UNSUPPORTED_SECTIONS
            .iter()
            .any(|s| s.eq_ignore_ascii_case(&section.name))
        {
            diags.push(ConfigError::UnsupportedSection {
                src,
                span: section.span,
                section: section.name.clone(),
            });
        }
    }
    // Names seen so far (ASCII case folded) and where each was defined first: one hash
    // look-up per signal, so a file of 200,000 signals loads in linear time.
    let mut seen: HashMap<String, Span> = HashMap::new();
    for section in file.sections_named(SIGNAL_SECTION) {
        for inst in &section.instances {
            let Some(sig) = signal(src, &section.name, inst, diags) else {
                continue;
            };
            match seen.entry(sig.def.name.to_ascii_lowercase()) {
                Entry::Occupied(first) => diags.push(ConfigError::DuplicateSignal {
                    src,
                    span: sig.span,
                    first: *first.get(),
                    name: sig.def.name.clone(),
                }),
                Entry::Vacant(slot) => {
                    slot.insert(sig.span);
                    out.signals.push(sig);
                }
            }
        }
    }
    out.system_outputs = system_outputs(src, file, &out.signals, diags);
    out
}

/// The `SYSSIG_OUT` instances whose status rapidvc drives, on digital outputs of `signals`.
fn system_outputs(
    src: SourceId,
    file: &CfgFile,
    signals: &[EioSignal],
    diags: &mut Diagnostics,
) -> Vec<SystemOutput> {
    let dos: HashMap<String, ()> = signals
        .iter()
        .filter(|s| s.def.kind == SignalKind::Do)
        .map(|s| (s.def.name.to_ascii_lowercase(), ()))
        .collect();
    let text = |inst: &CfgInstance, name: &str| {
        inst.get(name)
            .and_then(|a| a.as_text().map(|t| (t.to_string(), a.value_or_name_span())))
    };
    let mut out = Vec::new();
    for section in file.sections_named("SYSSIG_OUT") {
        for inst in &section.instances {
            let (Some((status, status_span)), Some((signal, signal_span))) =
                (text(inst, "Status"), text(inst, "Signal"))
            else {
                continue;
            };
            let Some(known) = SYSTEM_OUTPUTS
                .iter()
                .find(|s| s.eq_ignore_ascii_case(&status))
            else {
                diags.push(ConfigError::UnsupportedSystemOutput {
                    src,
                    span: status_span,
                    status,
                    signal,
                });
                continue;
            };
            if !dos.contains_key(&signal.to_ascii_lowercase()) {
                diags.push(ConfigError::SystemOutputSignal {
                    src,
                    span: signal_span,
                    status,
                    signal,
                });
                continue;
            }
            out.push(SystemOutput {
                status: known,
                signal,
                arg1: text(inst, "Arg1").map(|t| t.0),
                arg2: text(inst, "Arg2").map(|t| t.0),
            });
        }
    }
    out
}

fn signal(
    src: SourceId,
    section: &str,
    inst: &CfgInstance,
    diags: &mut Diagnostics,
) -> Option<EioSignal> {
    warn_unknown(src, section, inst, &[USED, IGNORED], diags);
    let missing =
        |name: &str, diags: &mut Diagnostics| missing_attr(src, section, inst, name, diags);
    let mut failed = false;
    let f = &mut failed;
    let name = keep(text_attr(src, inst, &["Name"], diags), f);
    let kind_text = keep(text_attr(src, inst, &["SignalType"], diags), f);
    let device = keep(text_attr(src, inst, &["Device", "Unit"], diags), f);
    let map = keep(text_attr(src, inst, &["DeviceMap", "UnitMap"], diags), f);
    let min_log = keep(num_attr(src, inst, "MinLog", diags), f);
    let max_log = keep(num_attr(src, inst, "MaxLog", diags), f);
    let min_phys = keep(num_attr(src, inst, "MinPhys", diags), f);
    let max_phys = keep(num_attr(src, inst, "MaxPhys", diags), f);
    let default = keep(num_attr(src, inst, "Default", diags), f);

    let Some((name, name_span)) = name else {
        if !failed {
            missing("Name", diags);
        }
        return None;
    };
    if name.is_empty() {
        diags.push(ConfigError::BadValue {
            src,
            span: name_span,
            name: "Name".into(),
            expected: "a non-empty name".into(),
            found: "an empty text".into(),
        });
        return None;
    }
    let Some((kind_text, kind_span)) = kind_text else {
        if !failed {
            missing("SignalType", diags);
        }
        return None;
    };
    let Some(kind) = SignalKind::parse(&kind_text) else {
        diags.push(ConfigError::BadValue {
            src,
            span: kind_span,
            name: "SignalType".into(),
            expected: "DI, DO, AI, AO, GI or GO".into(),
            found: format!("\"{kind_text}\""),
        });
        return None;
    };
    let bits = match &map {
        Some((m, span)) => match device_map_bits(m) {
            Some(b) => Some((b, *span)),
            None => {
                diags.push(ConfigError::BadValue {
                    src,
                    span: *span,
                    name: "DeviceMap".into(),
                    expected: "bit numbers and ranges such as \"0-7\" or \"0,2,4-5\"".into(),
                    found: format!("\"{m}\""),
                });
                return None;
            }
        },
        None => None,
    };
    if failed {
        return None;
    }

    let mut def = match kind {
        SignalKind::Di | SignalKind::Do => SignalDef::digital(&name, kind),
        SignalKind::Ai | SignalKind::Ao => {
            let lo = min_log.map(|v| v.0).unwrap_or(0.0);
            let hi = max_log.map(|v| v.0).unwrap_or(0.0);
            let mut d = SignalDef::analog(&name, kind, lo, hi);
            if let Some((v, _)) = min_phys {
                d.min_phys = v;
            }
            if let Some((v, _)) = max_phys {
                d.max_phys = v;
            }
            d
        }
        SignalKind::Gi | SignalKind::Go => {
            SignalDef::group(&name, kind, bits.map(|b| b.0).unwrap_or(32))
        }
    };
    def.device = device.map(|d| d.0);
    def.device_map = map.map(|m| m.0);
    if let Some((v, _)) = default {
        def.default = v;
    }

    let invalid = |span: Span, reason: String, label: &str, diags: &mut Diagnostics| {
        diags.push(ConfigError::InvalidSignal {
            src,
            span,
            name: name.clone(),
            reason,
            label: label.to_string(),
        });
    };
    if kind.is_analog() && def.min_log > def.max_log {
        let span = min_log.or(max_log).map(|v| v.1).unwrap_or(name_span);
        let reason = format!(
            "-MinLog {} is greater than -MaxLog {}",
            def.min_log, def.max_log
        );
        invalid(span, reason, "greater than -MaxLog", diags);
        return None;
    }
    if kind.is_group() && !(1..=MAX_GROUP_BITS).contains(&def.bits) {
        let span = bits.map(|b| b.1).unwrap_or(name_span);
        let reason = format!(
            "-DeviceMap maps {} bits; a group signal has 1 to {MAX_GROUP_BITS}",
            def.bits
        );
        invalid(span, reason, &format!("{} bits", def.bits), diags);
        return None;
    }
    if let (Some((v, span)), Err(_)) = (default, def.check_value(def.default)) {
        let reason = match kind {
            SignalKind::Di | SignalKind::Do => format!("-Default {v} is not 0 or 1"),
            SignalKind::Ai | SignalKind::Ao => format!(
                "-Default {v} is outside the logical range {}..{}",
                def.min_log, def.max_log
            ),
            SignalKind::Gi | SignalKind::Go => format!(
                "-Default {v} is not an integer 0..{} ({} bits)",
                def.group_max(),
                def.bits
            ),
        };
        invalid(span, reason, "not a valid value for this signal", diags);
        return None;
    }
    // Anything the checks above missed (a definition the signal table would refuse).
    if let Err(e) = def.validate() {
        let reason = match e {
            IoError::InvalidDefinition { reason, .. } => reason,
            other => other.to_string(),
        };
        invalid(name_span, reason, "this signal", diags);
        return None;
    }
    if kind.is_analog() && def.min_log == 0.0 && def.max_log == 0.0 {
        diags.push(ConfigError::EmptyRange {
            src,
            span: name_span,
            name: name.clone(),
        });
    }
    Some(EioSignal {
        def,
        span: name_span,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::SourceMap;

    fn read_text(text: &str) -> (SourceMap, EioConfig, Diagnostics) {
        let mut map = SourceMap::new();
        let id = map.add("EIO.cfg", text);
        let mut diags = Diagnostics::new();
        let file = super::super::cfg::parse(id, text, &mut diags).unwrap();
        let eio = read(&file, &mut diags);
        (map, eio, diags)
    }

    #[test]
    fn device_maps() {
        assert_eq!(device_map_bits("0"), Some(1));
        assert_eq!(device_map_bits("0-7"), Some(8));
        assert_eq!(device_map_bits("7-0"), Some(8));
        assert_eq!(device_map_bits("0-3, 8-11"), Some(8));
        assert_eq!(device_map_bits("0,2,4-5"), Some(4));
        assert_eq!(device_map_bits("96-127"), Some(32));
        assert_eq!(device_map_bits(""), None);
        assert_eq!(device_map_bits("a-b"), None);
        assert_eq!(device_map_bits("0-"), None);
        assert_eq!(device_map_bits("1,,2"), None);
    }

    #[test]
    fn every_kind() {
        let (map, eio, diags) = read_text(
            "EIO:CFG_1.0:5:0::\n#\nEIO_SIGNAL:\n\n\
             -Name \"di1\" -SignalType \"DI\" -Unit \"board\" -UnitMap \"3\" -Default 1\n\n\
             -Name \"do1\" -SignalType \"do\" -Access \"All\" -SysfailReset\n\n\
             -Name \"ai1\" -SignalType \"AI\" -MinLog -10 -MaxLog 10 -MinPhys 0 -MaxPhys 20\n\n\
             -Name \"ao1\" -SignalType \"AO\" -MaxLog 24000 -MaxBitVal 32767 -Default 5\n\n\
             -Name \"gi1\" -SignalType \"GI\" -Device \"d1\" -DeviceMap \"0-7\"\n\n\
             -Name \"go1\" -SignalType \"GO\"\n",
        );
        assert!(diags.is_empty(), "{}", diags.render_plain(&map, 80));
        let d = eio.defs();
        assert_eq!(d.len(), 6);
        assert_eq!(d[0].kind, SignalKind::Di);
        assert_eq!(d[0].default, 1.0);
        assert_eq!(d[0].device.as_deref(), Some("board"));
        assert_eq!(d[0].device_map.as_deref(), Some("3"));
        assert_eq!(d[1].kind, SignalKind::Do);
        assert_eq!((d[2].min_log, d[2].max_log), (-10.0, 10.0));
        assert_eq!((d[2].min_phys, d[2].max_phys), (0.0, 20.0));
        assert_eq!(d[2].physical(0.0), 10.0);
        assert_eq!(
            (d[3].min_log, d[3].max_log, d[3].default),
            (0.0, 24000.0, 5.0)
        );
        assert_eq!(d[4].bits, 8);
        assert_eq!(d[5].bits, 32);
        assert_eq!(eio.signals[4].span, {
            let s = eio.signals[4].span;
            assert_eq!(map.snippet(s), "\"gi1\"");
            s
        });
    }

    #[test]
    fn group_default_and_numbers_in_quotes() {
        let (map, eio, diags) = read_text(
            "EIO:CFG_1.0:6:1::\n#\nEIO_SIGNAL:\n  -Name \"g\" -SignalType \"GO\" -DeviceMap \"0-3\" -Default 16\n  -Name \"a\" -SignalType AO -MaxLog \"5\"\n",
        );
        assert_eq!(diags.error_count(), 1);
        assert!(
            diags
                .render_plain(&map, 80)
                .contains("-Default 16 is not an integer 0..15 (4 bits)")
        );
        assert_eq!(eio.signals.len(), 1);
        assert_eq!(eio.signals[0].def.max_log, 5.0);
    }

    #[test]
    fn unsupported_and_unknown_are_warnings() {
        let (_, eio, diags) = read_text(
            "EIO:CFG_1.0:6:1::\n#\nEIO_CROSS:\n  -Res \"a\" -Act1 \"b\"\n#\nEIO_SIGNAL:\n  -Name \"a\" -SignalType \"DO\" -Colour \"red\"\n",
        );
        assert_eq!(diags.error_count(), 0);
        assert_eq!(diags.warning_count(), 2);
        assert_eq!(eio.signals.len(), 1);
    }
}
