//! Kinematic errors and their ABB event numbers and RAPID error names.

use super::JointsDeg;
use super::conf::ConfData;
use super::singularity::SingularityKind;

/// Why a pose or a joint vector is not acceptable for the robot.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum KinError {
    /// No arm configuration reaches the pose at all.
    #[error(
        "position outside reach: flange at [{:.2}, {:.2}, {:.2}] mm (world) cannot be reached",
        position[0], position[1], position[2]
    )]
    OutsideReach {
        /// The flange (tool0) position asked for, mm in world coordinates.
        position: [f64; 3],
    },
    /// An axis value lies outside its working range.
    #[error("joint {joint} out of range: {value:.3}° is outside {min}°…{max}°")]
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
    let parts: Vec<String> = j.iter().map(|v| format!("{v:.2}")).collect();
    parts.join(", ")
}

impl KinError {
    /// The ABB event log number and title (docs/robot.md, "Errors and events"):
    /// outside reach, configuration unreachable and non-finite input → 50050 "Position outside
    /// reach"; joint out of range → 50027 "Joint out of range"; singularity → 50026 "Close to
    /// singularity". The mapping of an unreachable *configuration* to 50050 is one of the two
    /// candidates (docs/robot.md, "Errors and events"; ABB's exact event is unverified).
    pub fn event(&self) -> (u32, &'static str) {
        match self {
            KinError::OutsideReach { .. }
            | KinError::ConfigurationUnreachable { .. }
            | KinError::NotFinite => (50050, "Position outside reach"),
            KinError::JointOutOfRange { .. } => (50027, "Joint out of range"),
            KinError::Singularity { .. } => (50026, "Close to singularity"),
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
