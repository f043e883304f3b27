//! The configuration as the EGM registry takes it: the MOC.cfg profiles and the device table (SIO.cfg, `--device`, the simulated LTAPP devices) converted into egm's plain values, so egm reads no configuration.

use crate::config::devices::{self, DeviceTable};
use crate::config::moc::{self, MocConfig};
use crate::egm::registry::{
    DeviceError, DeviceTarget, Devices, MotionLevel, MotionProfile, Profiles, RegistryConfig,
    Unlisted,
};

/// The registry configuration of `moc` and `devices` for the unit `ROB_1`.
pub fn registry_config(moc: &MocConfig, devices: &DeviceTable) -> RegistryConfig {
    RegistryConfig::new(profiles(moc), device_values(devices))
}

/// The profiles of MOC.cfg (with the built-in or redefined `"default"` first).
pub fn profiles(moc: &MocConfig) -> Profiles {
    Profiles::new(moc.profiles().iter().map(profile).collect())
}

fn profile(p: &moc::ExtMotionProfile) -> MotionProfile {
    MotionProfile {
        name: p.name.clone(),
        level: match p.level {
            moc::MotionLevel::Raw => MotionLevel::Raw,
            moc::MotionLevel::Filtering => MotionLevel::Filtering,
            moc::MotionLevel::Path => MotionLevel::Path,
        },
        ramp_time: p.ramp_time,
        kp: p.kp,
        filter_bandwidth: p.filter_bandwidth,
    }
}

/// Every name of the device table resolved, and what any other name leads to.
pub fn device_values(table: &DeviceTable) -> Devices {
    let named = table
        .names()
        .into_iter()
        .map(|name| {
            let target = table.resolve_device(&name).map(target).map_err(error);
            (name, target)
        })
        .collect();
    let unlisted = match table.unlisted_known() {
        None => Unlisted::Builtin,
        Some(known) => Unlisted::NotConfigured { known },
    };
    Devices::new(named, unlisted)
}

fn target(t: devices::DeviceTarget) -> DeviceTarget {
    match t {
        devices::DeviceTarget::Udp { remote, local_port } => {
            DeviceTarget::Udp { remote, local_port }
        }
        devices::DeviceTarget::Builtin { pattern } => DeviceTarget::Builtin { pattern },
        devices::DeviceTarget::Ltapp { name, seam } => DeviceTarget::Ltapp { name, seam },
    }
}

fn error(e: devices::DeviceError) -> DeviceError {
    match e {
        devices::DeviceError::Unsupported { name, kind } => DeviceError::Unsupported { name, kind },
        devices::DeviceError::NotConfigured { name, known } => {
            DeviceError::NotConfigured { name, known }
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::*;
    use crate::config::devices::{DeviceOverride, SIMULATED_LTAPP};
    use crate::egm::path_correction::SeamProfile;

    /// The domain `read` makes of the CFG file `name` with `text`.
    fn read_cfg<T>(
        name: &str,
        text: &str,
        read: fn(&crate::config::cfg::CfgFile, &mut crate::diag::Diagnostics) -> T,
    ) -> T {
        let mut sources = crate::source::SourceMap::new();
        let mut diags = crate::diag::Diagnostics::new();
        let id = sources.add(name.to_string(), text);
        let file = crate::config::cfg::parse(id, text, &mut diags).unwrap();
        read(&file, &mut diags)
    }

    /// Every name resolves through the plain values exactly as through the configuration.
    #[test]
    fn devices_resolve_as_the_configuration_does() {
        let sio_text = "SIO:CFG_1.0:6:0::\n#\nCOM_TRP:\n\n      -Name \"UCdevice\" -Type \"UDPUC\" -RemoteAdress \"127.0.0.1\" -RemotePortNumber 6510 -LocalPortNumber 6599\n\n      -Name \"laser\" -Type \"LTAPPTCP\"\n";
        let sio = read_cfg("SIO.cfg", sio_text, crate::config::sio::read);
        let overrides: Vec<DeviceOverride> =
            ["pat=builtin:joint:1,2,3,4,5,6", "ext=127.0.0.1:7000"]
                .iter()
                .map(|o| o.parse().unwrap())
                .collect();
        for table in [
            DeviceTable::new(Some(&sio), &overrides).unwrap(),
            DeviceTable::new(None, &overrides).unwrap(),
            DeviceTable::new(None, &[]).unwrap(),
        ] {
            let plain = device_values(&table);
            for name in [
                "UCdevice",
                "ucdevice:",
                "laser",
                "pat",
                "ext",
                "OptSim",
                "wg1sim",
                "nowhere",
            ] {
                assert_eq!(
                    plain.resolve_device(name),
                    table.resolve_device(name).map(target).map_err(error),
                    "{name}"
                );
            }
        }
        // The simulated LTAPP devices' seams are valid seam profiles.
        for (_, pattern) in SIMULATED_LTAPP {
            assert!(SeamProfile::parse(pattern).is_ok(), "{pattern}");
        }
    }

    #[test]
    fn profiles_keep_their_values_and_order() {
        let text = "MOC:CFG_1.0:6:0::\n#\nEXT_MOTION_DATA:\n\n      -name \"pathCorr\" -ext_motion_level 2\n";
        let moc = read_cfg("MOC.cfg", text, crate::config::moc::read);
        let plain = profiles(&moc);
        let p = plain.profile("PATHCORR").unwrap();
        assert_eq!((p.name.as_str(), p.level), ("pathCorr", MotionLevel::Path));
        let want = moc.profile("pathCorr").unwrap();
        assert_eq!((p.kp, p.ramp_time), (want.kp, want.ramp_time));
        let err = plain.profile("nope").unwrap_err();
        assert_eq!(
            err.to_string(),
            moc.profile("nope").unwrap_err().to_string()
        );
    }
}
