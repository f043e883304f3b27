//! The effective device table: SIO.cfg devices, `--device` overrides, the simulated LTAPP seam sensors and the built-in sensor, and which one a device name resolves to.
//!
//! [`DeviceTable::resolve_device`] decides, for the device name a program passes to
//! EGMSetupUC or EGMSetupLTAPP (case-insensitive, one trailing `:` ignored), in this order:
//!
//! 1. a command-line override `--device NAME=HOST:PORT` → [`DeviceTarget::Udp`] (the local
//!    port comes from SIO.cfg if it defines the device, else 0), or `--device
//!    NAME=builtin[:PATTERN]` → [`DeviceTarget::Builtin`];
//! 2. a UDPUC device of SIO.cfg → [`DeviceTarget::Udp`];
//! 3. a simulated LTAPP device name ([`SIMULATED_LTAPP`]: `OptSim`, `wg1sim`, the names of the
//!    manual's path-correction example) → [`DeviceTarget::Ltapp`] with that device's seam
//!    pattern — also when SIO.cfg lists the name with another type such as LTAPPTCP;
//! 4. a device of SIO.cfg with another type → [`DeviceError::Unsupported`] (the LTAPP
//!    protocol is not public, and rapidvc implements no other transmission protocol);
//! 5. no SIO.cfg at all → [`DeviceTarget::Builtin`] without a pattern: with no
//!    configuration, every device is the built-in sensor, so the manual's programs run with
//!    one command and nothing else running;
//! 6. otherwise (SIO.cfg exists but does not define the name) → [`DeviceError::NotConfigured`],
//!    which names the devices that exist, as a real controller would refuse it.
//!
//! Patterns are kept as text here: the built-in sensor (guidance patterns) and the path
//! correction's seam profiles parse them, each for its own mode.

use std::fmt;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::str::FromStr;

use crate::diag::RapidDiagnostic;
use crate::source::SourceId;

use super::sio::{MAX_UDPUC_DEVICES, SioConfig, SioDeviceKind, device_key};

/// The simulated LTAPP seam sensors: device name and the seam pattern it reports (a seam
/// offset profile in the path frame, mm; see the path-correction module's `SeamProfile`).
/// Override one with `--device OptSim=builtin:PATTERN`.
pub const SIMULATED_LTAPP: &[(&str, &str)] = &[
    // A look-ahead laser tracker following a gently waving seam.
    ("OptSim", "sine:y=2,z=0.5,period=200"),
    // An at-point weld-guide sensor finding a seam that drifts off to one side.
    ("wg1sim", "ramp:y=3,z=-1,len=150"),
];

/// What a device name resolves to.
#[derive(Clone, Debug, PartialEq, Eq)]
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
    /// A simulated LTAPP seam sensor (rapidvc does not speak the LTAPP protocol).
    Ltapp {
        /// The device name as the table spells it (`OptSim`).
        name: String,
        /// The seam pattern it reports.
        seam: String,
    },
}

impl DeviceTarget {
    /// Whether the target is outside rapidvc (the clock must then run in real time).
    pub fn is_external(&self) -> bool {
        matches!(self, DeviceTarget::Udp { .. })
    }
}

/// A device that cannot be used.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error, miette::Diagnostic)]
pub enum DeviceError {
    /// The device has a transmission protocol type rapidvc does not implement.
    #[error("device \"{name}\" has type {kind}, which is not supported by rapidvc")]
    #[diagnostic(
        code(rapidvc::config::unusable_device),
        help(
            "only UDPUC devices can be used; `--device {name}=builtin[:PATTERN]` puts the built-in sensor in its place"
        )
    )]
    Unsupported {
        /// The device name.
        name: String,
        /// Its `-Type`.
        kind: String,
    },
    /// SIO.cfg exists and does not define the device.
    #[error("device \"{name}\" is not configured (SIO.cfg defines: {known})")]
    #[diagnostic(
        code(rapidvc::config::unknown_device),
        help(
            "add it to SIO.cfg (type COM_TRP, -Type \"UDPUC\"), or use `--device {name}=HOST:PORT` or `--device {name}=builtin`"
        )
    )]
    NotConfigured {
        /// The name asked for.
        name: String,
        /// The defined names, quoted and comma-separated (or "no devices").
        known: String,
    },
}

impl RapidDiagnostic for DeviceError {
    fn source_id(&self) -> Option<SourceId> {
        None
    }
}

/// Where a `--device` override points.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum OverrideTarget {
    /// `NAME=HOST:PORT`.
    Udp(SocketAddr),
    /// `NAME=builtin[:PATTERN]`.
    Builtin {
        /// The pattern text after `builtin:`.
        pattern: Option<String>,
    },
}

/// A parsed `--device NAME=HOST:PORT` or `--device NAME=builtin[:PATTERN]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DeviceOverride {
    /// The device name (one trailing `:` removed).
    pub name: String,
    /// Where it points.
    pub target: OverrideTarget,
}

/// A `--device` value or a set of them that cannot be used.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error, miette::Diagnostic)]
#[diagnostic(
    code(rapidvc::config::bad_device_override),
    help(
        "write `--device NAME=HOST:PORT` (e.g. `EGMsensor=127.0.0.1:6510`, `UCdevice=[::1]:6511`) or `--device NAME=builtin[:PATTERN]`"
    )
)]
pub enum DeviceOverrideError {
    /// No `=`.
    #[error("`{input}`: expected NAME=HOST:PORT or NAME=builtin[:PATTERN]")]
    NoEquals {
        /// The argument.
        input: String,
    },
    /// Nothing before `=`.
    #[error("`{input}`: the device name before `=` is missing")]
    NoName {
        /// The argument.
        input: String,
    },
    /// `builtin:` with nothing after it.
    #[error("`{input}`: the pattern after `builtin:` is missing")]
    EmptyPattern {
        /// The argument.
        input: String,
    },
    /// No `:PORT`.
    #[error("`{input}`: the port is missing (HOST:PORT)")]
    NoPort {
        /// The argument.
        input: String,
    },
    /// A port that is not 1..65535.
    #[error("`{input}`: `{port}` is not a port number 1 to 65535")]
    BadPort {
        /// The argument.
        input: String,
        /// The port text.
        port: String,
    },
    /// A host that is not an IP address (or `localhost`).
    #[error(
        "`{input}`: `{host}` is not an IP address; rapidvc does not look up host names (use an address or `localhost`)"
    )]
    BadHost {
        /// The argument.
        input: String,
        /// The host text.
        host: String,
    },
    /// An IPv6 address without brackets.
    #[error("`{input}`: write IPv6 addresses in brackets, e.g. `[::1]:6510`")]
    UnbracketedIpv6 {
        /// The argument.
        input: String,
    },
    /// 0.0.0.0 or `::`.
    #[error("`{input}`: cannot send to the unspecified address {host}")]
    Unspecified {
        /// The argument.
        input: String,
        /// The address.
        host: String,
    },
    /// The same device overridden twice.
    #[error("--device {name} is given twice")]
    Duplicate {
        /// The device name.
        name: String,
    },
    /// More UdpUc devices than a controller supports (SIO.cfg plus overrides).
    #[error(
        "{count} UdpUc devices with the --device overrides; a controller supports at most {max}"
    )]
    TooManyDevices {
        /// The number of UdpUc devices.
        count: usize,
        /// The limit.
        max: usize,
    },
}

impl RapidDiagnostic for DeviceOverrideError {
    fn source_id(&self) -> Option<SourceId> {
        None
    }
}

impl FromStr for DeviceOverride {
    type Err = DeviceOverrideError;

    fn from_str(input: &str) -> Result<Self, Self::Err> {
        let owned = || input.to_string();
        let (name, value) = input
            .split_once('=')
            .ok_or_else(|| DeviceOverrideError::NoEquals { input: owned() })?;
        let name = device_key(name.trim());
        if name.is_empty() {
            return Err(DeviceOverrideError::NoName { input: owned() });
        }
        let value = value.trim();
        let target = match split_builtin(value) {
            Some(None) => OverrideTarget::Builtin { pattern: None },
            Some(Some(pattern)) if pattern.trim().is_empty() => {
                return Err(DeviceOverrideError::EmptyPattern { input: owned() });
            }
            Some(Some(pattern)) => OverrideTarget::Builtin {
                pattern: Some(pattern.trim().to_string()),
            },
            None => OverrideTarget::Udp(parse_host_port(input, value)?),
        };
        Ok(DeviceOverride {
            name: name.to_string(),
            target,
        })
    }
}

impl fmt::Display for DeviceOverride {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.target {
            OverrideTarget::Udp(addr) => write!(f, "{}={addr}", self.name),
            OverrideTarget::Builtin { pattern: None } => write!(f, "{}=builtin", self.name),
            OverrideTarget::Builtin { pattern: Some(p) } => {
                write!(f, "{}=builtin:{p}", self.name)
            }
        }
    }
}

/// `builtin` → `Some(None)`, `builtin:REST` → `Some(Some(REST))`, else `None`.
fn split_builtin(value: &str) -> Option<Option<&str>> {
    let head = value.get(..7)?;
    if !head.eq_ignore_ascii_case("builtin") {
        return None;
    }
    match value.get(7..)? {
        "" => Some(None),
        rest => rest.strip_prefix(':').map(Some),
    }
}

fn parse_host_port(input: &str, value: &str) -> Result<SocketAddr, DeviceOverrideError> {
    let owned = || input.to_string();
    let check = |addr: SocketAddr| {
        if addr.port() == 0 {
            Err(DeviceOverrideError::BadPort {
                input: owned(),
                port: "0".into(),
            })
        } else if addr.ip().is_unspecified() {
            Err(DeviceOverrideError::Unspecified {
                input: owned(),
                host: addr.ip().to_string(),
            })
        } else {
            Ok(addr)
        }
    };
    if let Ok(addr) = value.parse::<SocketAddr>() {
        return check(addr);
    }
    let Some((host, port)) = value.rsplit_once(':') else {
        return Err(DeviceOverrideError::NoPort { input: owned() });
    };
    let ip = if host.eq_ignore_ascii_case("localhost") {
        IpAddr::V4(Ipv4Addr::LOCALHOST)
    } else if let Some(inner) = host.strip_prefix('[').and_then(|h| h.strip_suffix(']')) {
        inner
            .parse::<IpAddr>()
            .map_err(|_| DeviceOverrideError::BadHost {
                input: owned(),
                host: host.to_string(),
            })?
    } else if host.contains(':') {
        return Err(DeviceOverrideError::UnbracketedIpv6 { input: owned() });
    } else {
        host.parse::<IpAddr>()
            .map_err(|_| DeviceOverrideError::BadHost {
                input: owned(),
                host: host.to_string(),
            })?
    };
    let port = port
        .parse::<u16>()
        .map_err(|_| DeviceOverrideError::BadPort {
            input: owned(),
            port: port.to_string(),
        })?;
    check(SocketAddr::new(ip, port))
}

/// The devices a program can name (see the module doc for the rules).
#[derive(Clone, Debug, PartialEq)]
pub struct DeviceTable {
    sio: Option<SioConfig>,
    overrides: Vec<DeviceOverride>,
}

impl DeviceTable {
    /// The table of `sio` (`None`: no SIO.cfg was read) with the `--device` overrides.
    /// Errors: a device overridden twice; more than [`MAX_UDPUC_DEVICES`] UdpUc devices in
    /// all.
    pub fn new(
        sio: Option<&SioConfig>,
        overrides: &[DeviceOverride],
    ) -> Result<Self, DeviceOverrideError> {
        for (i, o) in overrides.iter().enumerate() {
            if overrides
                .iter()
                .take(i)
                .any(|p| p.name.eq_ignore_ascii_case(&o.name))
            {
                return Err(DeviceOverrideError::Duplicate {
                    name: o.name.clone(),
                });
            }
        }
        let table = DeviceTable {
            sio: sio.cloned(),
            overrides: overrides.to_vec(),
        };
        let count = table.udp_device_names().len();
        if count > MAX_UDPUC_DEVICES {
            return Err(DeviceOverrideError::TooManyDevices {
                count,
                max: MAX_UDPUC_DEVICES,
            });
        }
        Ok(table)
    }

    fn override_for(&self, key: &str) -> Option<&DeviceOverride> {
        self.overrides
            .iter()
            .find(|o| o.name.eq_ignore_ascii_case(key))
    }

    /// The names that resolve to UdpUc devices (SIO.cfg's, then overrides').
    fn udp_device_names(&self) -> Vec<String> {
        let mut names: Vec<String> = Vec::new();
        let from_sio = self
            .sio
            .iter()
            .flat_map(|s| s.udpuc_devices().map(|(n, _)| n.to_string()));
        let from_overrides = self
            .overrides
            .iter()
            .filter(|o| matches!(o.target, OverrideTarget::Udp(_)))
            .map(|o| o.name.clone());
        for name in from_sio.chain(from_overrides) {
            let is_udp = matches!(self.resolve_device(&name), Ok(DeviceTarget::Udp { .. }));
            if is_udp && !names.iter().any(|n| n.eq_ignore_ascii_case(&name)) {
                names.push(name);
            }
        }
        names
    }

    /// The devices that resolve to an external sensor (SIO.cfg's UdpUc devices and
    /// `--device NAME=HOST:PORT`): with any, the controller's clock runs in real time (or
    /// lockstep), because a sensor outside rapidvc lives in real time.
    pub fn external_devices(&self) -> Vec<String> {
        self.udp_device_names()
    }

    /// What the device `name` is (module doc: precedence).
    pub fn resolve_device(&self, name: &str) -> Result<DeviceTarget, DeviceError> {
        let key = device_key(name);
        let sio_device = self.sio.as_ref().and_then(|s| s.device(key));
        if let Some(o) = self.override_for(key) {
            return Ok(match &o.target {
                OverrideTarget::Udp(remote) => DeviceTarget::Udp {
                    remote: *remote,
                    local_port: match sio_device.map(|d| &d.kind) {
                        Some(SioDeviceKind::UdpUc(u)) => u.local_port,
                        _ => 0,
                    },
                },
                OverrideTarget::Builtin { pattern } => DeviceTarget::Builtin {
                    pattern: pattern.clone(),
                },
            });
        }
        if let Some(d) = sio_device
            && let SioDeviceKind::UdpUc(u) = &d.kind
        {
            return Ok(DeviceTarget::Udp {
                remote: u.remote,
                local_port: u.local_port,
            });
        }
        if let Some((sim, seam)) = SIMULATED_LTAPP
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(key))
        {
            return Ok(DeviceTarget::Ltapp {
                name: (*sim).to_string(),
                seam: (*seam).to_string(),
            });
        }
        if let Some(d) = sio_device {
            return Err(DeviceError::Unsupported {
                name: d.name.clone(),
                kind: match &d.kind {
                    SioDeviceKind::Unsupported { type_name } => type_name.clone(),
                    SioDeviceKind::UdpUc(_) => super::sio::UDPUC_TYPE.to_string(),
                },
            });
        }
        match self.unlisted_known() {
            None => Ok(DeviceTarget::Builtin { pattern: None }),
            Some(known) => Err(DeviceError::NotConfigured {
                name: key.to_string(),
                known,
            }),
        }
    }

    /// Every name the table defines, once each (case-insensitive): the overrides', SIO.cfg's
    /// devices' and the simulated LTAPP devices'. Any other name resolves as
    /// [`DeviceTable::unlisted_known`] says.
    pub fn names(&self) -> Vec<String> {
        let overrides = self.overrides.iter().map(|o| o.name.clone());
        let sio = self
            .sio
            .iter()
            .flat_map(|s| s.devices.iter().map(|d| d.name.clone()));
        let simulated = SIMULATED_LTAPP.iter().map(|(n, _)| (*n).to_string());
        let mut names: Vec<String> = Vec::new();
        for name in overrides.chain(sio).chain(simulated) {
            if !names.iter().any(|n| n.eq_ignore_ascii_case(&name)) {
                names.push(name);
            }
        }
        names
    }

    /// What a name the table does not define resolves to: `None` — the built-in sensor (no
    /// SIO.cfg was read); `Some(known)` — not configured, SIO.cfg defines `known` (quoted and
    /// comma-separated, or "no devices").
    pub fn unlisted_known(&self) -> Option<String> {
        let sio = self.sio.as_ref()?;
        let known: Vec<String> = sio
            .devices
            .iter()
            .map(|d| format!("\"{}\"", d.name))
            .collect();
        Some(if known.is_empty() {
            "no devices".to_string()
        } else {
            known.join(", ")
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::sio::{SioDevice, UdpUcDevice};
    use crate::source::Span;

    fn parse(s: &str) -> Result<DeviceOverride, DeviceOverrideError> {
        s.parse()
    }

    fn udp(s: &str) -> OverrideTarget {
        OverrideTarget::Udp(s.parse().unwrap())
    }

    #[test]
    fn override_syntax() {
        let o = parse("EGMsensor=127.0.0.1:6510").unwrap();
        assert_eq!(o.name, "EGMsensor");
        assert_eq!(o.target, udp("127.0.0.1:6510"));
        assert_eq!(parse("UCdevice:=[::1]:6511").unwrap().name, "UCdevice");
        assert_eq!(
            parse("UCdevice:=[::1]:6511").unwrap().target,
            udp("[::1]:6511")
        );
        assert_eq!(parse("a=localhost:7").unwrap().target, udp("127.0.0.1:7"));
        assert_eq!(
            parse(" a = 10.1.2.3:80 ").unwrap().target,
            udp("10.1.2.3:80")
        );
        assert_eq!(
            parse("a=builtin").unwrap().target,
            OverrideTarget::Builtin { pattern: None }
        );
        assert_eq!(
            parse("OptSim=BuiltIn:sine:y=2,z=0,period=100")
                .unwrap()
                .target,
            OverrideTarget::Builtin {
                pattern: Some("sine:y=2,z=0,period=100".into())
            }
        );
        for s in [
            "EGMsensor=127.0.0.1:6510",
            "a=builtin",
            "a=builtin:const:y=3,z=-2",
            "v6=[::1]:6510",
        ] {
            assert_eq!(parse(s).unwrap().to_string(), s);
        }
    }

    #[test]
    fn override_errors() {
        let msg = |s: &str| parse(s).unwrap_err().to_string();
        assert_eq!(
            msg("EGMsensor"),
            "`EGMsensor`: expected NAME=HOST:PORT or NAME=builtin[:PATTERN]"
        );
        assert_eq!(
            msg("=1.2.3.4:5"),
            "`=1.2.3.4:5`: the device name before `=` is missing"
        );
        assert_eq!(
            msg(":=builtin"),
            "`:=builtin`: the device name before `=` is missing"
        );
        assert_eq!(
            msg("a=builtin:"),
            "`a=builtin:`: the pattern after `builtin:` is missing"
        );
        assert_eq!(
            msg("a=1.2.3.4"),
            "`a=1.2.3.4`: the port is missing (HOST:PORT)"
        );
        assert_eq!(
            msg("a=1.2.3.4:70000"),
            "`a=1.2.3.4:70000`: `70000` is not a port number 1 to 65535"
        );
        assert_eq!(
            msg("a=1.2.3.4:0"),
            "`a=1.2.3.4:0`: `0` is not a port number 1 to 65535"
        );
        assert_eq!(
            msg("a=1.2.3.4:"),
            "`a=1.2.3.4:`: `` is not a port number 1 to 65535"
        );
        assert!(msg("a=sensor.lan:6510").contains("`sensor.lan` is not an IP address"));
        assert!(msg("a=builtinx:1").contains("`builtinx` is not an IP address"));
        assert!(msg("a=[nope]:1").contains("`[nope]` is not an IP address"));
        assert_eq!(
            msg("a=::1:6510"),
            "`a=::1:6510`: write IPv6 addresses in brackets, e.g. `[::1]:6510`"
        );
        assert_eq!(
            msg("a=0.0.0.0:6510"),
            "`a=0.0.0.0:6510`: cannot send to the unspecified address 0.0.0.0"
        );
        assert!(msg("a=[::]:6510").contains("unspecified address ::"));
    }

    fn sio(devices: &[(&str, Option<&str>)]) -> SioConfig {
        SioConfig {
            devices: devices
                .iter()
                .map(|(name, addr)| SioDevice {
                    name: name.to_string(),
                    span: Span::default(),
                    kind: match addr {
                        Some(a) => SioDeviceKind::UdpUc(UdpUcDevice {
                            remote: a.parse().unwrap(),
                            local_port: 6600,
                            phy_channel: None,
                        }),
                        None => SioDeviceKind::Unsupported {
                            type_name: "LTAPPTCP".into(),
                        },
                    },
                })
                .collect(),
        }
    }

    #[test]
    fn no_configuration_means_builtin() {
        let t = DeviceTable::new(None, &[]).unwrap();
        let b = DeviceTarget::Builtin { pattern: None };
        assert_eq!(t.resolve_device("EGMsensor:"), Ok(b.clone()));
        assert_eq!(t.resolve_device("UCdevice"), Ok(b));
        assert_eq!(
            t.resolve_device("optsim"),
            Ok(DeviceTarget::Ltapp {
                name: "OptSim".into(),
                seam: "sine:y=2,z=0.5,period=200".into()
            })
        );
        assert!(matches!(
            t.resolve_device("WG1SIM"),
            Ok(DeviceTarget::Ltapp { name, .. }) if name == "wg1sim"
        ));
        assert!(!t.resolve_device("x").unwrap().is_external());
    }

    #[test]
    fn precedence() {
        let s = sio(&[
            ("EGMsensor", Some("10.0.0.1:6510")),
            ("laser", None),
            ("OptSim", None),
        ]);
        let t = DeviceTable::new(
            Some(&s),
            &[
                parse("egmsensor:=127.0.0.1:7000").unwrap(),
                parse("other=127.0.0.1:7001").unwrap(),
                parse("laser=builtin:const:y=1").unwrap(),
            ],
        )
        .unwrap();
        // 1. override, keeping SIO.cfg's local port.
        assert_eq!(
            t.resolve_device("EGMsensor:"),
            Ok(DeviceTarget::Udp {
                remote: "127.0.0.1:7000".parse().unwrap(),
                local_port: 6600
            })
        );
        assert!(t.resolve_device("EGMsensor").unwrap().is_external());
        assert_eq!(
            t.resolve_device("OTHER"),
            Ok(DeviceTarget::Udp {
                remote: "127.0.0.1:7001".parse().unwrap(),
                local_port: 0
            })
        );
        assert_eq!(
            t.resolve_device("laser"),
            Ok(DeviceTarget::Builtin {
                pattern: Some("const:y=1".into())
            })
        );
        // 3. a simulated LTAPP name wins over an LTAPPTCP entry.
        assert!(matches!(
            t.resolve_device("OptSim"),
            Ok(DeviceTarget::Ltapp { .. })
        ));
        // 6. SIO.cfg exists: unknown names are errors.
        let e = t.resolve_device("UCdevice:").unwrap_err();
        assert_eq!(
            e.to_string(),
            "device \"UCdevice\" is not configured (SIO.cfg defines: \"EGMsensor\", \"laser\", \"OptSim\")"
        );

        // 2. and 4. without overrides.
        let t = DeviceTable::new(Some(&s), &[]).unwrap();
        assert_eq!(
            t.resolve_device("egmsensor"),
            Ok(DeviceTarget::Udp {
                remote: "10.0.0.1:6510".parse().unwrap(),
                local_port: 6600
            })
        );
        assert_eq!(
            t.resolve_device("laser").unwrap_err().to_string(),
            "device \"laser\" has type LTAPPTCP, which is not supported by rapidvc"
        );
        let empty = DeviceTable::new(Some(&SioConfig::default()), &[]).unwrap();
        assert!(
            empty
                .resolve_device("a")
                .unwrap_err()
                .to_string()
                .ends_with("(SIO.cfg defines: no devices)")
        );
    }

    #[test]
    fn table_errors() {
        let twice = [parse("a=builtin").unwrap(), parse("A:=1.2.3.4:5").unwrap()];
        assert_eq!(
            DeviceTable::new(None, &twice).unwrap_err().to_string(),
            "--device A is given twice"
        );
        let devices: Vec<(String, Option<String>)> = (0..8)
            .map(|i| (format!("d{i}"), Some(format!("10.0.0.1:{}", 6500 + i))))
            .collect();
        let refs: Vec<(&str, Option<&str>)> = devices
            .iter()
            .map(|(n, a)| (n.as_str(), a.as_deref()))
            .collect();
        let s = sio(&refs);
        // Eight in SIO.cfg; re-pointing one or making one builtin is fine, a ninth is not.
        assert!(DeviceTable::new(Some(&s), &[parse("d0=1.2.3.4:5").unwrap()]).is_ok());
        assert!(DeviceTable::new(Some(&s), &[parse("x=builtin").unwrap()]).is_ok());
        assert_eq!(
            DeviceTable::new(Some(&s), &[parse("d8=1.2.3.4:5").unwrap()])
                .unwrap_err()
                .to_string(),
            "9 UdpUc devices with the --device overrides; a controller supports at most 8"
        );
    }
}
