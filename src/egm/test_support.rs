//! What the egm unit tests (and the controller's EGM unit tests) share: registries over plain device tables and profiles, and the context of the drivers.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::sync::Arc;

use crate::egm::registry::{
    DeviceTarget, Devices, EgmRegistry, MotionLevel, MotionProfile, Profiles, RegistryConfig,
    Unlisted,
};
use crate::egm::{DriverContext, DriverOptions};
use crate::robot::Robot;
use crate::signals::SignalTable;

/// Devices written as `--device` values: `NAME=HOST:PORT`, `NAME=builtin[:PATTERN]`, or
/// `NAME=ltapp:SEAM` (a simulated seam sensor); any other name is the built-in sensor, as
/// without SIO.cfg.
pub(crate) fn devices(entries: &[&str]) -> Devices {
    let named = entries
        .iter()
        .map(|e| {
            let (name, value) = e.split_once('=').expect("NAME=VALUE");
            let target = if let Some(seam) = value.strip_prefix("ltapp:") {
                DeviceTarget::Ltapp {
                    name: name.to_string(),
                    seam: seam.to_string(),
                }
            } else if let Some(rest) = value.strip_prefix("builtin") {
                DeviceTarget::Builtin {
                    pattern: rest.strip_prefix(':').map(str::to_string),
                }
            } else {
                DeviceTarget::Udp {
                    remote: value.parse().expect("HOST:PORT"),
                    local_port: 0,
                }
            };
            (name.to_string(), Ok(target))
        })
        .collect();
    Devices::new(named, Unlisted::Builtin)
}

/// A registry with the devices `entries` (see [`devices`]) and the built-in profile.
pub(crate) fn registry_with(entries: &[&str]) -> EgmRegistry {
    EgmRegistry::new(RegistryConfig::new(Profiles::default(), devices(entries)))
}

/// A registry where every device is the built-in sensor.
pub(crate) fn registry() -> EgmRegistry {
    registry_with(&[])
}

/// A Level 2 profile called `name` with the default values otherwise.
pub(crate) fn level_2(name: &str) -> MotionProfile {
    MotionProfile {
        name: name.to_string(),
        level: MotionLevel::Path,
        ..MotionProfile::builtin_default()
    }
}

/// The drivers' context: the default robot, `signals`, default options.
pub(crate) fn ctx(signals: Arc<SignalTable>) -> DriverContext {
    DriverContext {
        robot: Robot::default(),
        signals,
        options: DriverOptions::default(),
        drops: Default::default(),
    }
}
