//! What the registry needs from the controller's configuration, as plain values: the External Motion Interface Data profiles (MOC.cfg) and where each device name leads (SIO.cfg, `--device`, the simulated LTAPP devices). The controller converts its configuration into these; egm reads no configuration.

use std::net::SocketAddr;

/// An External Motion Interface Data profile (MOC.cfg `EXT_MOTION_DATA`).
#[derive(Clone, Debug, PartialEq)]
pub struct MotionProfile {
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
}

impl MotionProfile {
    /// The built-in profile `"default"` with RobotWare's default values (Level 1).
    pub fn builtin_default() -> MotionProfile {
        MotionProfile {
            name: "default".to_string(),
            level: MotionLevel::Filtering,
            ramp_time: 0.5,
            kp: 5.0,
            filter_bandwidth: 20.0,
        }
    }
}

/// `-ext_motion_level` of a profile.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MotionLevel {
    /// 0: raw corrections added just before the servos.
    Raw,
    /// 1: extra filtering, extra latency (the default).
    Filtering,
    /// 2: path correction (required by EGMMoveL/EGMMoveC).
    Path,
}

impl MotionLevel {
    /// The number written in MOC.cfg.
    pub fn number(self) -> u8 {
        match self {
            MotionLevel::Raw => 0,
            MotionLevel::Filtering => 1,
            MotionLevel::Path => 2,
        }
    }
}

/// An ExtConfigName that names no profile.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("External Motion Interface Data \"{name}\" is not defined (defined: {known})")]
pub struct UnknownProfile {
    /// The name asked for.
    pub name: String,
    /// The defined names, quoted and comma-separated.
    pub known: String,
}

/// Where a device name leads.
#[derive(Clone, Debug, PartialEq)]
pub enum DeviceTarget {
    /// An external sensor over UdpUc: the controller sends to `remote` from a socket bound
    /// to `local_port` (0: any free port).
    Udp {
        /// The sensor's address.
        remote: SocketAddr,
        /// The controller's local port.
        local_port: u16,
    },
    /// rapidvc's in-process built-in sensor; `pattern` as written after `builtin:` (`None`:
    /// the sensor's default for the mode).
    Builtin {
        /// The pattern text.
        pattern: Option<String>,
    },
    /// A simulated LTAPP seam sensor.
    Ltapp {
        /// The device name as the table spells it (`OptSim`).
        name: String,
        /// The seam pattern it reports.
        seam: String,
    },
}

/// Why a device name cannot be used.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum DeviceError {
    /// The device has a transmission protocol type rapidvc does not implement.
    #[error("device \"{name}\" has type {kind}, which is not supported by rapidvc")]
    Unsupported {
        /// The device name.
        name: String,
        /// Its `-Type`.
        kind: String,
    },
    /// The configuration does not define the device.
    #[error("device \"{name}\" is not configured (SIO.cfg defines: {known})")]
    NotConfigured {
        /// The name asked for.
        name: String,
        /// The defined names, quoted and comma-separated (or "no devices").
        known: String,
    },
}

/// What a name the configuration does not list leads to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Unlisted {
    /// No SIO.cfg: every device is the built-in sensor.
    Builtin,
    /// SIO.cfg defines only `known` (quoted, comma-separated, or "no devices").
    NotConfigured {
        /// The defined names.
        known: String,
    },
}

/// Every device name of the configuration and where it leads, plus what any other name
/// leads to.
#[derive(Clone, Debug, PartialEq)]
pub struct Devices {
    named: Vec<(String, Result<DeviceTarget, DeviceError>)>,
    unlisted: Unlisted,
}

impl Default for Devices {
    /// No configuration: every name is the built-in sensor.
    fn default() -> Self {
        Devices {
            named: Vec::new(),
            unlisted: Unlisted::Builtin,
        }
    }
}

impl Devices {
    /// The devices `named` (compared case-insensitively, the first of a name wins) and what
    /// any other name leads to.
    pub fn new(
        named: Vec<(String, Result<DeviceTarget, DeviceError>)>,
        unlisted: Unlisted,
    ) -> Self {
        Devices { named, unlisted }
    }

    /// Where the device `name` leads (one trailing `:` ignored, see [`device_key`]).
    pub fn resolve_device(&self, name: &str) -> Result<DeviceTarget, DeviceError> {
        let key = device_key(name);
        if let Some((_, target)) = self.named.iter().find(|(n, _)| n.eq_ignore_ascii_case(key)) {
            return target.clone();
        }
        match &self.unlisted {
            Unlisted::Builtin => Ok(DeviceTarget::Builtin { pattern: None }),
            Unlisted::NotConfigured { known } => Err(DeviceError::NotConfigured {
                name: key.to_string(),
                known: known.clone(),
            }),
        }
    }
}

/// The name under which a device is looked up: one trailing `:` removed (the manual writes
/// `"EGMsensor:"` in EGMSetupUC).
pub fn device_key(name: &str) -> &str {
    name.strip_suffix(':').unwrap_or(name)
}

/// The profiles of a registry: `"default"` always among them.
#[derive(Clone, Debug, PartialEq)]
pub struct Profiles(Vec<MotionProfile>);

impl Default for Profiles {
    fn default() -> Self {
        Profiles(vec![MotionProfile::builtin_default()])
    }
}

impl Profiles {
    /// `profiles`, with the built-in `"default"` first unless one of them is called so.
    pub fn new(profiles: Vec<MotionProfile>) -> Profiles {
        let mut all = Profiles::default().0;
        for p in profiles {
            match all
                .iter_mut()
                .find(|q| q.name.eq_ignore_ascii_case(&p.name))
            {
                Some(q) => *q = p,
                None => all.push(p),
            }
        }
        Profiles(all)
    }

    /// The profile called `name` (case-insensitive), or an error naming the profiles that
    /// exist.
    pub fn profile(&self, name: &str) -> Result<&MotionProfile, UnknownProfile> {
        self.0
            .iter()
            .find(|p| p.name.eq_ignore_ascii_case(name))
            .ok_or_else(|| UnknownProfile {
                name: name.to_string(),
                known: self
                    .0
                    .iter()
                    .map(|p| format!("\"{}\"", p.name))
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }
}
