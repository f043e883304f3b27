//! Kinematic errors and their ABB event numbers and RAPID error names.

use crate::events::EventKind;

use super::JointsDeg;
use super::conf::ConfData;
use super::singularity::SingularityKind;

/// Why a pose or a joint vector is not acceptable for the robot.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum KinError {
    /// No arm configuration reaches the pose at all.
    #[error(
        "position outside reach: flange at [{}, {}, {}] mm (world) cannot be reached",
        msg_num(position[0], Some(2)), msg_num(position[1], Some(2)), msg_num(position[2], Some(2))
    )]
    OutsideReach {
        /// The flange (tool0) position asked for, mm in world coordinates.
        position: [f64; 3],
    },
    /// An axis value lies outside its working range.
    #[error(
        "joint {joint} out of range: {}° is outside {}°…{}°",
        msg_num(*value, Some(3)), msg_num(*min, None), msg_num(*max, None)
    )]
    JointOutOfRange {
        /// Axis number, 1-based as ABB counts them.
        joint: usize,
        /// The offending value (deg).
        value: f64,
        /// Lower limit (deg).
        min: f64,
        /// Upper limit (deg).
        max: f64,
    },
    /// The pose is reachable, but not in the programmed configuration (ConfJ\On / ConfL\On).
    #[error(
        "configuration {wanted} cannot reach the position{}",
        available_text(available)
    )]
    ConfigurationUnreachable {
        /// The programmed confdata.
        wanted: ConfData,
        /// The configurations that do reach it within the axis limits.
        available: Vec<ConfData>,
    },
    /// The joints are too close to a singularity.
    #[error("close to {kind} at [{}]", joints_text(joints))]
    Singularity {
        /// Which singularity.
        kind: SingularityKind,
        /// Where (deg).
        joints: JointsDeg,
    },
    /// A pose or joint value is NaN or infinite.
    #[error("position, orientation or axis value is not a finite number")]
    NotFinite,
}

fn available_text(available: &[ConfData]) -> String {
    if available.is_empty() {
        String::new()
    } else {
        let list: Vec<String> = available.iter().map(ToString::to_string).collect();
        format!(" (reachable configurations: {})", list.join(", "))
    }
}

fn joints_text(j: &JointsDeg) -> String {
    let parts: Vec<String> = j.iter().map(|v| msg_num(*v, Some(2))).collect();
    parts.join(", ")
}

/// Magnitude from which a message writes a number in exponent notation.
const EXP_FROM: f64 = 1e9;
/// Magnitude below which a number without fixed decimals is written in exponent notation.
const EXP_BELOW: f64 = 1e-4;

/// A number for an event or error message: with `decimals` digits after the point (Rust's
/// shortest form for `None`), except that a magnitude of 1e9 or more (and, for `None`, one
/// below 1e-4) is written in exponent notation with at most that many digits after the
/// point (at least 2, 6 for `None`; trailing zeros dropped): `9e9`, `1e308`, `-2.5e-7`. A
/// fixed form of those would be hundreds of digits long (1e308 has 309). NaN and infinity
/// are written as `NaN`, `inf`, `-inf`.
pub fn msg_num(x: f64, decimals: Option<usize>) -> String {
    let a = x.abs();
    let exponent =
        x.is_finite() && (a >= EXP_FROM || (decimals.is_none() && a != 0.0 && a < EXP_BELOW));
    if !exponent {
        return match decimals {
            Some(d) => format!("{x:.d$}"),
            None => format!("{x}"),
        };
    }
    let d = decimals.unwrap_or(6).max(2);
    let text = format!("{x:.d$e}");
    match text.split_once('e') {
        Some((mantissa, exp)) if mantissa.contains('.') => {
            let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
            format!("{mantissa}e{exp}")
        }
        _ => text,
    }
}

impl KinError {
    /// The ABB event log number and title (docs/robot.md, "Errors and events"):
    /// outside reach, configuration unreachable and non-finite input → 50050 "Position outside
    /// reach"; joint out of range → 50027 "Joint out of range"; singularity → 50026 "Close to
    /// singularity". The mapping of an unreachable *configuration* to 50050 is one of the two
    /// candidates (docs/robot.md, "Errors and events"; ABB's exact event is unverified).
    pub fn event(&self) -> (u32, &'static str) {
        let kind = self.event_kind();
        (kind.number(), kind.title())
    }

    /// The entry of the event table ([`crate::events`]) that [`KinError::event`] reports.
    pub fn event_kind(&self) -> EventKind {
        match self {
            KinError::OutsideReach { .. }
            | KinError::ConfigurationUnreachable { .. }
            | KinError::NotFinite => EventKind::OutsideReach,
            KinError::JointOutOfRange { .. } => EventKind::JointOutOfRange,
            KinError::Singularity { .. } => EventKind::Singularity,
        }
    }

    /// The RAPID error a program can catch in an `ERROR` handler: `ERR_OUTSIDE_REACH` for an
    /// unreachable position (and non-finite input), `ERR_ROBLIMIT` for axis limits, the
    /// programmed configuration and singularities.
    pub fn rapid_error_name(&self) -> &'static str {
        match self {
            KinError::OutsideReach { .. } | KinError::NotFinite => "ERR_OUTSIDE_REACH",
            KinError::JointOutOfRange { .. }
            | KinError::ConfigurationUnreachable { .. }
            | KinError::Singularity { .. } => "ERR_ROBLIMIT",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn message_numbers_never_run_to_hundreds_of_digits() {
        assert_eq!(msg_num(1e308, Some(2)), "1e308");
        assert_eq!(msg_num(-1e308, None), "-1e308");
        assert_eq!(msg_num(9e9, Some(2)), "9e9");
        assert_eq!(msg_num(3e38_f32 as f64, Some(2)), "3e38");
        assert_eq!(msg_num(1.25e30, Some(3)), "1.25e30");
        assert_eq!(msg_num(1e-300, None), "1e-300");
        assert_eq!(msg_num(2.5e-7, None), "2.5e-7");
        // Ordinary magnitudes keep the fixed form they always had.
        assert_eq!(msg_num(1705.776, Some(2)), "1705.78");
        assert_eq!(msg_num(-180.0, None), "-180");
        assert_eq!(msg_num(0.0, None), "0");
        assert_eq!(msg_num(1e-300, Some(2)), "0.00");
        assert_eq!(msg_num(f64::NAN, Some(2)), "NaN");
        assert_eq!(msg_num(f64::NEG_INFINITY, None), "-inf");
        for x in [
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            5e-324,
            123456789012.0,
        ] {
            for d in [None, Some(0), Some(1), Some(3)] {
                assert!(msg_num(x, d).len() <= 24, "{x} {d:?}: {}", msg_num(x, d));
            }
        }
        let e = KinError::OutsideReach {
            position: [1e308, 0.0, -9e9],
        };
        assert_eq!(
            e.to_string(),
            "position outside reach: flange at [1e308, 0.00, -9e9] mm (world) cannot be reached"
        );
        let e = KinError::JointOutOfRange {
            joint: 1,
            value: 1e308,
            min: -180.0,
            max: 180.0,
        };
        assert_eq!(
            e.to_string(),
            "joint 1 out of range: 1e308° is outside -180°…180°"
        );
    }

    #[test]
    fn events_and_names() {
        let e = KinError::JointOutOfRange {
            joint: 3,
            value: 80.0,
            min: -180.0,
            max: 75.0,
        };
        assert_eq!(e.event(), (50027, "Joint out of range"));
        assert_eq!(e.rapid_error_name(), "ERR_ROBLIMIT");
        assert_eq!(
            e.to_string(),
            "joint 3 out of range: 80.000° is outside -180°…75°"
        );
        let e = KinError::OutsideReach {
            position: [1.0, 2.0, 3000.0],
        };
        assert_eq!(e.event().0, 50050);
        assert_eq!(e.rapid_error_name(), "ERR_OUTSIDE_REACH");
        let e = KinError::ConfigurationUnreachable {
            wanted: ConfData::new(0, 0, -1, 0),
            available: vec![ConfData::new(0, -1, -1, 1)],
        };
        assert!(e.to_string().contains("[0,0,-1,0]"), "{e}");
        assert!(e.to_string().contains("[0,-1,-1,1]"), "{e}");
        let e = KinError::Singularity {
            kind: SingularityKind::Wrist,
            joints: [0.0; 6],
        };
        assert_eq!(e.event(), (50026, "Close to singularity"));
        assert_eq!(KinError::NotFinite.rapid_error_name(), "ERR_OUTSIDE_REACH");
    }
}
