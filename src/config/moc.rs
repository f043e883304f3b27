//! The MOC domain: External Motion Interface Data profiles (`EXT_MOTION_DATA`) of a `MOC.cfg` file, named by the EGM setup instructions.
//!
//! ```text
//! MOC:CFG_1.0:6:0::
//! #
//! EXT_MOTION_DATA:
//!
//!       -name "pathCorr" -ext_motion_level 2
//! ```
//!
//! | attribute | parameter | allowed | default |
//! |---|---|---|---|
//! | `-name` | Name (required) | 1 to 32 characters | — |
//! | `-ext_motion_level` | Level | 0 (raw), 1 (filtering), 2 (path correction) | 1 |
//! | `-ramp_time` | Default Ramp Time | 0.005 to 10 s | 0.5 s |
//! | `-ext_motion_Kp` | Default Proportional Position Gain | 0 to 20 | 5 |
//! | `-ext_motion_filter_bandwidth` | Default Low Pass Filter Bandwidth | 0 to 100 Hz | 20 Hz |
//! | `-do_not_restart_after_motors_off` | Do Not Restart After Motors Off | a flag (also `TRUE`/`FALSE`) | false |
//!
//! `-max_allowed_speed_factor` (read by a public check script, undocumented) is accepted and
//! ignored; any other attribute is a warning. The attribute of "Return to Programmed Position
//! when Stopped" has never been seen in a public file, so rapidvc cannot read it (the
//! parameter is false). Other MOC sections (a controller backup has dozens) are skipped.
//!
//! RobotWare predefines a profile `"default"`; [`MocConfig`] always holds it (with the
//! defaults above), even without a MOC.cfg, and a file may redefine it. Profile names are
//! looked up case-insensitively. A profile with an invalid value is reported and left out.

use crate::diag::{Diagnostics, RapidDiagnostic};
use crate::source::{SourceId, Span};

use super::ConfigError;
use super::attr::{
    found_text, int_attr, keep, missing_attr, ranged_num_attr, text_attr, warn_unknown,
};
use super::cfg::{CfgFile, CfgInstance, CfgValue};

/// The section of External Motion Interface Data.
pub const PROFILE_SECTION: &str = "EXT_MOTION_DATA";

/// The name of the predefined profile.
pub const DEFAULT_PROFILE: &str = "default";

/// The longest profile name.
pub const MAX_NAME_LEN: usize = 32;

/// Allowed Default Ramp Time, seconds.
pub const RAMP_TIME_RANGE: (f64, f64) = (0.005, 10.0);
/// Allowed Default Proportional Position Gain.
pub const KP_RANGE: (f64, f64) = (0.0, 20.0);
/// Allowed Default Low Pass Filter Bandwidth, Hz.
pub const BANDWIDTH_RANGE: (f64, f64) = (0.0, 100.0);

const USED: &[&str] = &[
    "name",
    "ext_motion_level",
    "ramp_time",
    "ext_motion_Kp",
    "ext_motion_filter_bandwidth",
    "do_not_restart_after_motors_off",
];
const IGNORED: &[&str] = &["max_allowed_speed_factor"];

/// Level: where the corrections enter the motion system.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MotionLevel {
    /// 0: raw corrections added just before the servos (needs low-pass filtering).
    Raw,
    /// 1: extra filtering, extra latency (the default).
    Filtering,
    /// 2: path correction (required by EGMMoveL/EGMMoveC).
    Path,
}

impl MotionLevel {
    /// The level of `-ext_motion_level`.
    pub fn from_number(n: i64) -> Option<MotionLevel> {
        match n {
            0 => Some(MotionLevel::Raw),
            1 => Some(MotionLevel::Filtering),
            2 => Some(MotionLevel::Path),
            _ => None,
        }
    }

    /// The number written in MOC.cfg.
    pub fn number(self) -> u8 {
        match self {
            MotionLevel::Raw => 0,
            MotionLevel::Filtering => 1,
            MotionLevel::Path => 2,
        }
    }
}

/// One External Motion Interface Data profile.
#[derive(Clone, Debug, PartialEq)]
pub struct ExtMotionProfile {
    /// The name as written.
    pub name: String,
    /// Level.
    pub level: MotionLevel,
    /// Default Ramp Time, seconds.
    pub ramp_time: f64,
    /// Default Proportional Position Gain (k of the EGM control law, 1/s).
    pub kp: f64,
    /// Default Low Pass Filter Bandwidth, Hz.
    pub filter_bandwidth: f64,
    /// Do Not Restart After Motors Off.
    pub do_not_restart_after_motors_off: bool,
    /// Where its `-name` value is written; `None` for the built-in `"default"`.
    pub span: Option<Span>,
}

impl ExtMotionProfile {
    /// A profile called `name` with RobotWare's default values.
    pub fn with_defaults(name: &str) -> Self {
        ExtMotionProfile {
            name: name.to_string(),
            level: MotionLevel::Filtering,
            ramp_time: 0.5,
            kp: 5.0,
            filter_bandwidth: 20.0,
            do_not_restart_after_motors_off: false,
            span: None,
        }
    }

    /// The predefined profile `"default"`.
    pub fn builtin_default() -> Self {
        Self::with_defaults(DEFAULT_PROFILE)
    }
}

/// The profiles: the predefined `"default"` (possibly redefined) and those of MOC.cfg.
#[derive(Clone, Debug, PartialEq)]
pub struct MocConfig {
    profiles: Vec<ExtMotionProfile>,
}

impl Default for MocConfig {
    fn default() -> Self {
        MocConfig {
            profiles: vec![ExtMotionProfile::builtin_default()],
        }
    }
}

impl MocConfig {
    /// Every profile; `"default"` first.
    pub fn profiles(&self) -> &[ExtMotionProfile] {
        &self.profiles
    }

    /// The profile called `name` (case-insensitive).
    pub fn get(&self, name: &str) -> Option<&ExtMotionProfile> {
        self.profiles
            .iter()
            .find(|p| p.name.eq_ignore_ascii_case(name))
    }

    /// The profile called `name`, or an error naming the profiles that exist.
    pub fn profile(&self, name: &str) -> Result<&ExtMotionProfile, UnknownProfile> {
        self.get(name).ok_or_else(|| UnknownProfile {
            name: name.to_string(),
            known: self
                .profiles
                .iter()
                .map(|p| format!("\"{}\"", p.name))
                .collect::<Vec<_>>()
                .join(", "),
        })
    }

    /// Add or replace a profile (a file's `"default"` replaces the built-in one).
    fn insert(&mut self, profile: ExtMotionProfile) {
        match self
            .profiles
            .iter_mut()
            .find(|p| p.name.eq_ignore_ascii_case(&profile.name))
        {
            Some(p) => *p = profile,
            None => self.profiles.push(profile),
        }
    }
}

/// An ExtConfigName that names no profile.
#[derive(Debug, Clone, PartialEq, thiserror::Error, miette::Diagnostic)]
#[error("External Motion Interface Data \"{name}\" is not defined (defined: {known})")]
#[diagnostic(
    code(rapidvc::config::unknown_profile),
    help(
        "define it in MOC.cfg of the configuration directory, type EXT_MOTION_DATA, e.g. \
         `-name \"{name}\" -ext_motion_level 2` for path correction"
    )
)]
pub struct UnknownProfile {
    /// The name asked for.
    pub name: String,
    /// The defined names, quoted and comma-separated.
    pub known: String,
}

impl RapidDiagnostic for UnknownProfile {
    fn source_id(&self) -> Option<SourceId> {
        None
    }
}

/// Read the profiles of `file` on top of the built-in `"default"`.
pub fn read(file: &CfgFile, diags: &mut Diagnostics) -> MocConfig {
    let src = file.source;
    let mut out = MocConfig::default();
    let mut seen: Vec<(String, Span)> = Vec::new();
    for section in file.sections_named(PROFILE_SECTION) {
        for inst in &section.instances {
            let Some(p) = profile(src, &section.name, inst, diags) else {
                continue;
            };
            let span = p.span.unwrap_or(inst.span);
            if let Some((_, first)) = seen.iter().find(|(n, _)| n.eq_ignore_ascii_case(&p.name)) {
                diags.push(ConfigError::DuplicateProfile {
                    src,
                    span,
                    first: *first,
                    name: p.name.clone(),
                });
                continue;
            }
            seen.push((p.name.clone(), span));
            out.insert(p);
        }
    }
    out
}

fn profile(
    src: SourceId,
    section: &str,
    inst: &CfgInstance,
    diags: &mut Diagnostics,
) -> Option<ExtMotionProfile> {
    warn_unknown(src, section, inst, &[USED, IGNORED], diags);
    let mut failed = false;
    let f = &mut failed;
    let name = keep(text_attr(src, inst, &["name"], diags), f);
    let level = keep(
        int_attr(
            src,
            inst,
            &["ext_motion_level"],
            (0, 2),
            "0 (raw), 1 (filtering) or 2 (path correction)",
            diags,
        ),
        f,
    );
    let ramp = keep(
        ranged_num_attr(
            src,
            inst,
            "ramp_time",
            RAMP_TIME_RANGE,
            "a time 0.005 to 10 (seconds)",
            diags,
        ),
        f,
    );
    let kp = keep(
        ranged_num_attr(
            src,
            inst,
            "ext_motion_Kp",
            KP_RANGE,
            "a gain 0 to 20",
            diags,
        ),
        f,
    );
    let bandwidth = keep(
        ranged_num_attr(
            src,
            inst,
            "ext_motion_filter_bandwidth",
            BANDWIDTH_RANGE,
            "a bandwidth 0 to 100 (Hz)",
            diags,
        ),
        f,
    );
    let no_restart = match inst.get("do_not_restart_after_motors_off") {
        None => false,
        Some(attr) => match &attr.value {
            CfgValue::Flag => true,
            CfgValue::Str(s) | CfgValue::Word(s) if s.eq_ignore_ascii_case("true") => true,
            CfgValue::Str(s) | CfgValue::Word(s) if s.eq_ignore_ascii_case("false") => false,
            other => {
                diags.push(ConfigError::BadValue {
                    src,
                    span: attr.value_or_name_span(),
                    name: attr.name.clone(),
                    expected: "no value (a flag: present means true)".into(),
                    found: found_text(other),
                });
                failed = true;
                false
            }
        },
    };

    let Some((name, name_span)) = name else {
        if !failed {
            missing_attr(src, section, inst, "name", diags);
        }
        return None;
    };
    let len = name.chars().count();
    if len == 0 || len > MAX_NAME_LEN {
        let found = if len == 0 {
            "an empty text".to_string()
        } else {
            format!("{len} characters")
        };
        diags.push(ConfigError::BadValue {
            src,
            span: name_span,
            name: "name".into(),
            expected: format!("a name of 1 to {MAX_NAME_LEN} characters"),
            found,
        });
        return None;
    }
    if failed {
        return None;
    }
    let mut p = ExtMotionProfile::with_defaults(&name);
    p.span = Some(name_span);
    if let Some(level) = level.and_then(|(n, _)| MotionLevel::from_number(n)) {
        p.level = level;
    }
    if let Some((v, _)) = ramp {
        p.ramp_time = v;
    }
    if let Some((v, _)) = kp {
        p.kp = v;
    }
    if let Some((v, _)) = bandwidth {
        p.filter_bandwidth = v;
    }
    p.do_not_restart_after_motors_off = no_restart;
    Some(p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::SourceMap;

    fn read_text(text: &str) -> (SourceMap, MocConfig, Diagnostics) {
        let mut map = SourceMap::new();
        let id = map.add("MOC.cfg", text);
        let mut diags = Diagnostics::new();
        let file = super::super::cfg::parse(id, text, &mut diags).unwrap();
        let moc = read(&file, &mut diags);
        (map, moc, diags)
    }

    #[test]
    fn default_profile_without_a_file() {
        let moc = MocConfig::default();
        let d = moc.profile("Default").unwrap();
        assert_eq!(d.level, MotionLevel::Filtering);
        assert_eq!((d.ramp_time, d.kp, d.filter_bandwidth), (0.5, 5.0, 20.0));
        assert!(!d.do_not_restart_after_motors_off);
        assert_eq!(d.span, None);
        let e = moc.profile("pathCorr").unwrap_err();
        assert_eq!(
            e.to_string(),
            "External Motion Interface Data \"pathCorr\" is not defined (defined: \"default\")"
        );
    }

    #[test]
    fn profiles_and_overridden_default() {
        let (map, moc, diags) = read_text(
            "MOC:CFG_1.0:6:0::\n#\nROBOT:\n  -name \"ROB_1\" -use_robot_serial_number \"x\"\n#\nEXT_MOTION_DATA:\n\n  -name \"pathCorr\" -ext_motion_level 2\n\n  -name \"raw_fast\" -ext_motion_level 0 -ramp_time 0.1 -ext_motion_Kp 10\\\n  -ext_motion_filter_bandwidth 40 -do_not_restart_after_motors_off\n\n  -name \"DEFAULT\" -ramp_time 1 -max_allowed_speed_factor 2\n\n  -name \"t\" -do_not_restart_after_motors_off \"TRUE\"\n",
        );
        assert!(diags.is_empty(), "{}", diags.render_plain(&map, 80));
        let names: Vec<&str> = moc.profiles().iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["DEFAULT", "pathCorr", "raw_fast", "t"]);
        assert_eq!(moc.profile("PATHCORR").unwrap().level, MotionLevel::Path);
        let raw = moc.get("raw_fast").unwrap();
        assert_eq!(raw.level.number(), 0);
        assert_eq!(
            (raw.ramp_time, raw.kp, raw.filter_bandwidth),
            (0.1, 10.0, 40.0)
        );
        assert!(raw.do_not_restart_after_motors_off);
        let d = moc.get("default").unwrap();
        assert_eq!((d.ramp_time, d.kp), (1.0, 5.0));
        assert!(d.span.is_some());
        assert!(moc.get("t").unwrap().do_not_restart_after_motors_off);
    }

    #[test]
    fn ranges_are_checked() {
        let (map, moc, diags) = read_text(
            "MOC:CFG_1.0:6:0::\n#\nEXT_MOTION_DATA:\n\
             -name \"a\" -ext_motion_level 3\n\
             -name \"b\" -ramp_time 0.001\n\
             -name \"c\" -ramp_time 10.5\n\
             -name \"d\" -ext_motion_Kp 21\n\
             -name \"e\" -ext_motion_filter_bandwidth -1\n\
             -name \"f\" -ext_motion_level 1.5\n\
             -name \"g\" -do_not_restart_after_motors_off 1\n\
             -name \"abcdefghijklmnopqrstuvwxyz0123456\"\n\
             -ext_motion_level 2\n\
             -name \"ok\" -ext_motion_Kp 0 -ext_motion_filter_bandwidth 100 -ramp_time 0.005 -colour 3\n\
             -name \"OK\"\n",
        );
        let text = diags.render_plain(&map, 100);
        assert_eq!(diags.error_count(), 10, "{text}");
        assert_eq!(diags.warning_count(), 1, "{text}");
        assert!(text.contains("`-ext_motion_level` takes 0 (raw), 1 (filtering) or 2"));
        assert!(text.contains("`-ramp_time` takes a time 0.005 to 10 (seconds)"));
        assert!(text.contains("0.001 is out of range"));
        assert!(text.contains("a name of 1 to 32 characters"));
        assert!(text.contains("profile `OK` is defined twice"));
        let names: Vec<&str> = moc.profiles().iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["default", "ok"]);
    }
}
