//! The SIO domain: UdpUc devices (transmission protocols, type `COM_TRP`) of a `SIO.cfg` file, the targets of EGMSetupUC.
//!
//! ```text
//! SIO:CFG_1.0:6:1::
//! #
//! COM_TRP:
//!
//!       -Name "UCdevice" -Type "UDPUC" -PhyChannel ""\
//!       -RemoteAdress "192.168.10.20" -RemotePortNumber 6510 -LocalPortNumber 0
//! ```
//!
//! | attribute | meaning | rapidvc |
//! |---|---|---|
//! | `-Name` | device name used in EGMSetupUC (required) | compared case-insensitively, one trailing `:` ignored ([`device_key`]) |
//! | `-Type` | transmission protocol type (required) | only `UDPUC` is usable; other types (`LTAPPTCP`, `SOCKDEV`, `TCP/IP`, …) are recorded with an "is not supported" warning |
//! | `-PhyChannel` | serial port; not used for IP types (`""` or `N/A`) | kept, informational |
//! | `-RemoteAdress` (one "d", as ABB writes it; `-RemoteAddress` accepted) | IPv4 or IPv6 address of the sensor (required for UDPUC) | not the unspecified address |
//! | `-RemotePortNumber` | port the sensor listens on (required for UDPUC) | 1 to 65535 |
//! | `-LocalPortNumber` | local port of the controller's socket | 0 to 65535, default 0 (an ephemeral port) |
//!
//! At most [`MAX_UDPUC_DEVICES`] UdpUc devices: later ones are errors and left out, as are
//! duplicated names and invalid instances. Other sections of SIO.cfg (serial ports,
//! `COM_APP`, …) are skipped.
//!
//! The section name is `COM_TRP` in RobotWare 6 backups; the RobotWare 7 name was not found in
//! any public file, so [`SioOptions::device_sections`] lists the section names read (an alias
//! can be added there).

use std::net::{IpAddr, SocketAddr};

use crate::diag::Diagnostics;
use crate::source::{SourceId, Span};

use super::ConfigError;
use super::attr::{int_attr, keep, missing_attr, text_attr, warn_unknown};
use super::cfg::{CfgFile, CfgInstance};

/// The RobotWare 6 section of transmission protocols.
pub const DEVICE_SECTION: &str = "COM_TRP";

/// The most UdpUc devices a controller supports.
pub const MAX_UDPUC_DEVICES: usize = 8;

/// The `-Type` of a UdpUc device.
pub const UDPUC_TYPE: &str = "UDPUC";

/// Attributes of a UDPUC instance that rapidvc reads.
const UDPUC_ATTRS: &[&str] = &[
    "Name",
    "Type",
    "PhyChannel",
    "RemoteAdress",
    "RemoteAddress",
    "RemotePortNumber",
    "LocalPortNumber",
];

/// How SIO.cfg is read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SioOptions {
    /// The section names holding devices (case-insensitive). Default: `COM_TRP`.
    pub device_sections: Vec<String>,
}

impl Default for SioOptions {
    fn default() -> Self {
        SioOptions {
            device_sections: vec![DEVICE_SECTION.to_string()],
        }
    }
}

/// The name under which a device is looked up: one trailing `:` removed (the manual writes
/// `"EGMsensor:"` in EGMSetupUC). Compare keys with `eq_ignore_ascii_case`.
pub fn device_key(name: &str) -> &str {
    name.strip_suffix(':').unwrap_or(name)
}

/// A device of SIO.cfg.
#[derive(Clone, Debug, PartialEq)]
pub struct SioDevice {
    /// The name as written (without a trailing `:`).
    pub name: String,
    /// Where its `-Name` value is written.
    pub span: Span,
    /// What it is.
    pub kind: SioDeviceKind,
}

/// The kind of a device.
#[derive(Clone, Debug, PartialEq)]
pub enum SioDeviceKind {
    /// A usable UdpUc device.
    UdpUc(UdpUcDevice),
    /// A transmission protocol rapidvc does not implement.
    Unsupported {
        /// The `-Type` as written (`LTAPPTCP`, `SOCKDEV`, …).
        type_name: String,
    },
}

/// The addresses of a UdpUc device.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UdpUcDevice {
    /// Remote Address and Remote Port Number: where the controller sends.
    pub remote: SocketAddr,
    /// Local Port Number (0: an ephemeral port).
    pub local_port: u16,
    /// `-PhyChannel` as written (informational).
    pub phy_channel: Option<String>,
}

/// The devices of one SIO.cfg, distinct by [`device_key`], in file order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SioConfig {
    /// The devices (UdpUc and unsupported ones).
    pub devices: Vec<SioDevice>,
}

impl SioConfig {
    /// The device called `name` (case-insensitive, one trailing `:` ignored).
    pub fn device(&self, name: &str) -> Option<&SioDevice> {
        let key = device_key(name);
        self.devices
            .iter()
            .find(|d| d.name.eq_ignore_ascii_case(key))
    }

    /// The UdpUc devices with their names.
    pub fn udpuc_devices(&self) -> impl Iterator<Item = (&str, &UdpUcDevice)> {
        self.devices.iter().filter_map(|d| match &d.kind {
            SioDeviceKind::UdpUc(u) => Some((d.name.as_str(), u)),
            SioDeviceKind::Unsupported { .. } => None,
        })
    }
}

/// Read the devices of `file` with the default options.
pub fn read(file: &CfgFile, diags: &mut Diagnostics) -> SioConfig {
    read_with(file, &SioOptions::default(), diags)
}

/// Read the devices of `file`. Invalid instances are reported and left out.
pub fn read_with(file: &CfgFile, options: &SioOptions, diags: &mut Diagnostics) -> SioConfig {
    let src = file.source;
    let mut out = SioConfig::default();
    let mut udpuc_count = 0;
    let sections = file.sections.iter().filter(|s| {
        options
            .device_sections
            .iter()
            .any(|n| n.eq_ignore_ascii_case(&s.name))
    });
    for section in sections {
        for inst in &section.instances {
            let Some(dev) = device(src, &section.name, inst, diags) else {
                continue;
            };
            if let Some(first) = out
                .devices
                .iter()
                .find(|d| d.name.eq_ignore_ascii_case(&dev.name))
            {
                diags.push(ConfigError::DuplicateDevice {
                    src,
                    span: dev.span,
                    first: first.span,
                    name: dev.name.clone(),
                });
                continue;
            }
            if matches!(dev.kind, SioDeviceKind::UdpUc(_)) {
                udpuc_count += 1;
                if udpuc_count > MAX_UDPUC_DEVICES {
                    diags.push(ConfigError::TooManyDevices {
                        src,
                        span: dev.span,
                        name: dev.name.clone(),
                        number: udpuc_count,
                        max: MAX_UDPUC_DEVICES,
                    });
                    continue;
                }
            }
            out.devices.push(dev);
        }
    }
    out
}

/// An IP address as written in `-RemoteAdress` (IPv6 optionally in brackets).
fn parse_ip(text: &str) -> Option<IpAddr> {
    let t = text.trim();
    let t = t
        .strip_prefix('[')
        .and_then(|r| r.strip_suffix(']'))
        .unwrap_or(t);
    t.parse().ok()
}

fn device(
    src: SourceId,
    section: &str,
    inst: &CfgInstance,
    diags: &mut Diagnostics,
) -> Option<SioDevice> {
    let missing =
        |name: &str, diags: &mut Diagnostics| missing_attr(src, section, inst, name, diags);
    let mut failed = false;
    let f = &mut failed;
    let name = keep(text_attr(src, inst, &["Name"], diags), f);
    let kind = keep(text_attr(src, inst, &["Type"], diags), f);
    let Some((name, name_span)) = name else {
        if !failed {
            missing("Name", diags);
        }
        return None;
    };
    let name = device_key(&name).to_string();
    if name.trim().is_empty() {
        diags.push(ConfigError::BadValue {
            src,
            span: name_span,
            name: "Name".into(),
            expected: "a non-empty device name".into(),
            found: "an empty text".into(),
        });
        return None;
    }
    let Some((kind, kind_span)) = kind else {
        if !failed {
            missing("Type", diags);
        }
        return None;
    };
    if !kind.trim().eq_ignore_ascii_case(UDPUC_TYPE) {
        let help = if kind.trim().to_ascii_uppercase().starts_with("LTAPP") {
            "the LTAPP sensor protocol is not public; for a simulated seam sensor use \
             `--device NAME=builtin:PATTERN`, or the simulated device names OptSim and wg1sim"
        } else {
            "rapidvc implements only the UdpUc transmission protocol (EGMSetupUC)"
        };
        diags.push(ConfigError::UnsupportedDevice {
            src,
            span: kind_span,
            name: name.clone(),
            kind: kind.clone(),
            help: help.to_string(),
        });
        return Some(SioDevice {
            name,
            span: name_span,
            kind: SioDeviceKind::Unsupported { type_name: kind },
        });
    }

    warn_unknown(src, section, inst, &[UDPUC_ATTRS], diags);
    let phy = keep(text_attr(src, inst, &["PhyChannel"], diags), f);
    let address = keep(
        text_attr(src, inst, &["RemoteAdress", "RemoteAddress"], diags),
        f,
    );
    let port_text = "a port number 1 to 65535";
    let remote_port = keep(
        int_attr(
            src,
            inst,
            &["RemotePortNumber"],
            (1, 65535),
            port_text,
            diags,
        ),
        f,
    );
    let local_text = "a port number 0 to 65535 (0: any free port)";
    let local_port = keep(
        int_attr(
            src,
            inst,
            &["LocalPortNumber"],
            (0, 65535),
            local_text,
            diags,
        ),
        f,
    );
    let ip = match &address {
        Some((text, span)) => match parse_ip(text) {
            Some(ip) if !ip.is_unspecified() => Some(ip),
            parsed => {
                let found = match parsed {
                    Some(_) => format!("\"{text}\" is the unspecified address"),
                    None => format!("\"{text}\""),
                };
                diags.push(ConfigError::BadValue {
                    src,
                    span: *span,
                    name: "RemoteAdress".into(),
                    expected: "the IPv4 or IPv6 address of the sensor, such as \"192.168.10.20\""
                        .into(),
                    found,
                });
                failed = true;
                None
            }
        },
        None => {
            if !failed {
                missing("RemoteAdress", diags);
            }
            failed = true;
            None
        }
    };
    if remote_port.is_none() && !failed {
        missing("RemotePortNumber", diags);
        failed = true;
    }
    let (Some(ip), Some((port, _)), false) = (ip, remote_port, failed) else {
        return None;
    };
    // int_attr checked the ranges, so the conversions cannot fail.
    let port = u16::try_from(port).ok()?;
    let local_port = match local_port {
        Some((p, _)) => u16::try_from(p).ok()?,
        None => 0,
    };
    Some(SioDevice {
        name,
        span: name_span,
        kind: SioDeviceKind::UdpUc(UdpUcDevice {
            remote: SocketAddr::new(ip, port),
            local_port,
            phy_channel: phy.map(|p| p.0),
        }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::SourceMap;

    fn read_text(text: &str, options: &SioOptions) -> (SourceMap, SioConfig, Diagnostics) {
        let mut map = SourceMap::new();
        let id = map.add("SIO.cfg", text);
        let mut diags = Diagnostics::new();
        let file = super::super::cfg::parse(id, text, &mut diags).unwrap();
        let sio = read_with(&file, options, &mut diags);
        (map, sio, diags)
    }

    #[test]
    fn device_keys() {
        assert_eq!(device_key("EGMsensor:"), "EGMsensor");
        assert_eq!(device_key("EGMsensor"), "EGMsensor");
        assert_eq!(device_key("x::"), "x:");
        assert_eq!(device_key(":"), "");
    }

    #[test]
    fn udpuc_device_and_lookup() {
        let (map, sio, diags) = read_text(
            "SIO:CFG_1.0:6:1::\n#\nCOM_TRP:\n\n  -Name \"EGMsensor\" -Type \"UDPUC\" -PhyChannel \"\"\\\n  -RemoteAdress \"127.0.0.1\" -RemotePortNumber 6510 -LocalPortNumber 6599\n\n  -Name \"v6:\" -Type udpuc -RemoteAddress \"[::1]\" -RemotePortNumber \"6511\"\n",
            &SioOptions::default(),
        );
        assert!(diags.is_empty(), "{}", diags.render_plain(&map, 80));
        let d = sio.device("egmsensor:").unwrap();
        let SioDeviceKind::UdpUc(u) = &d.kind else {
            panic!("{d:?}")
        };
        assert_eq!(u.remote, "127.0.0.1:6510".parse().unwrap());
        assert_eq!(u.local_port, 6599);
        assert_eq!(u.phy_channel.as_deref(), Some(""));
        assert_eq!(map.snippet(d.span), "\"EGMsensor\"");
        let v6 = sio.device("V6").unwrap();
        assert_eq!(v6.name, "v6");
        let SioDeviceKind::UdpUc(u) = &v6.kind else {
            panic!()
        };
        assert_eq!(u.remote, "[::1]:6511".parse().unwrap());
        assert_eq!(u.local_port, 0);
        assert_eq!(sio.udpuc_devices().count(), 2);
        assert!(sio.device("other").is_none());
    }

    #[test]
    fn section_alias() {
        let text = "SIO:CFG_7.0:7:0::\n#\nUDP_UNICAST_DEVICE:\n  -Name \"d\" -Type \"UDPUC\" -RemoteAdress \"10.0.0.2\" -RemotePortNumber 6510\n";
        let (_, sio, diags) = read_text(text, &SioOptions::default());
        assert!(diags.is_empty() && sio.devices.is_empty());
        let options = SioOptions {
            device_sections: vec!["COM_TRP".into(), "udp_unicast_device".into()],
        };
        let (_, sio, diags) = read_text(text, &options);
        assert!(diags.is_empty());
        assert_eq!(sio.udpuc_devices().count(), 1);
    }

    #[test]
    fn unsupported_types_are_recorded_with_a_warning() {
        let (map, sio, diags) = read_text(
            "SIO:CFG_1.0:6:1::\n#\nCOM_TRP:\n  -Name \"laser\" -Type \"LTAPPTCP\" -RemoteAdress \"10.0.0.5\" -RemotePortNumber 5000 -Whatever 1\n  -Name \"sock\" -Type \"SOCKDEV\"\n",
            &SioOptions::default(),
        );
        assert_eq!(diags.error_count(), 0);
        assert_eq!(diags.warning_count(), 2);
        let text = diags.render_plain(&map, 200);
        assert!(
            text.contains("LTAPP sensor protocol is not public"),
            "{text}"
        );
        assert!(
            text.contains("only the UdpUc transmission protocol"),
            "{text}"
        );
        assert_eq!(
            sio.device("LASER").unwrap().kind,
            SioDeviceKind::Unsupported {
                type_name: "LTAPPTCP".into()
            }
        );
        assert_eq!(sio.udpuc_devices().count(), 0);
    }

    #[test]
    fn at_most_eight_udpuc_devices() {
        let mut text = String::from("SIO:CFG_1.0:6:1::\n#\nCOM_TRP:\n");
        for i in 0..10 {
            text.push_str(&format!(
                "  -Name \"d{i}\" -Type \"UDPUC\" -RemoteAdress \"127.0.0.1\" -RemotePortNumber {}\n",
                6510 + i
            ));
        }
        // Unsupported devices do not count.
        text.push_str("  -Name \"l\" -Type \"LTAPPTCP\"\n");
        let (map, sio, diags) = read_text(&text, &SioOptions::default());
        assert_eq!(diags.error_count(), 2, "{}", diags.render_plain(&map, 80));
        assert!(
            diags
                .render_plain(&map, 80)
                .contains("more than 8 UdpUc devices; device `d8` is ignored")
        );
        assert_eq!(sio.udpuc_devices().count(), 8);
        assert!(sio.device("d9").is_none() && sio.device("l").is_some());
    }

    #[test]
    fn bad_addresses_and_ports() {
        let (map, sio, diags) = read_text(
            "SIO:CFG_1.0:6:1::\n#\nCOM_TRP:\n\
             -Name \"a\" -Type \"UDPUC\" -RemoteAdress \"192.168.1.300\" -RemotePortNumber 6510\n\
             -Name \"b\" -Type \"UDPUC\" -RemoteAdress \"10.0.0.1\" -RemotePortNumber 70000\n\
             -Name \"c\" -Type \"UDPUC\" -RemoteAdress \"10.0.0.1\" -RemotePortNumber 0\n\
             -Name \"d\" -Type \"UDPUC\" -RemoteAdress \"0.0.0.0\" -RemotePortNumber 6510\n\
             -Name \"e\" -Type \"UDPUC\" -RemotePortNumber 6510\n\
             -Name \"f\" -Type \"UDPUC\" -RemoteAdress \"10.0.0.1\"\n\
             -Name \"g\" -Type \"UDPUC\" -RemoteAdress \"10.0.0.1\" -RemotePortNumber 6510.5 -LocalPortNumber -1\n\
             -Name \"EGMsensor\" -Type \"UDPUC\" -RemoteAdress \"10.0.0.1\" -RemotePortNumber 6510\n\
             -Name \"egmsensor:\" -Type \"UDPUC\" -RemoteAdress \"10.0.0.2\" -RemotePortNumber 6510\n\
             -Type \"UDPUC\"\n\
             -Name \"\" -Type \"UDPUC\"\n\
             -Name \"h\" -RemoteAdress \"10.0.0.1\"\n",
            &SioOptions::default(),
        );
        let text = diags.render_plain(&map, 100);
        assert_eq!(diags.error_count(), 12, "{text}");
        assert!(text.contains("\"192.168.1.300\""), "{text}");
        assert!(text.contains("70000 is out of range"), "{text}");
        assert!(text.contains("6510.5 is not a whole number"), "{text}");
        assert!(text.contains("the unspecified address"), "{text}");
        assert!(text.contains("without `-RemoteAdress`"), "{text}");
        assert!(text.contains("without `-RemotePortNumber`"), "{text}");
        assert!(
            text.contains("device `egmsensor` is defined twice"),
            "{text}"
        );
        assert!(text.contains("without `-Type`"), "{text}");
        assert!(text.contains("without `-Name`"), "{text}");
        let names: Vec<&str> = sio.devices.iter().map(|d| d.name.as_str()).collect();
        assert_eq!(names, ["EGMsensor"]);
    }
}
