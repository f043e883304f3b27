//! Reading configuration directories: EIO.cfg fixtures under `tests/fixtures/cfg/`, valid and
//! malformed, with the rendered diagnostics snapshotted (colour off, 80 columns).

use std::path::Path;

use rapidvc::config::{self, ConfigError};
use rapidvc::diag::Diagnostics;
use rapidvc::signals::SignalKind;
use rapidvc::source::SourceMap;

/// Load a fixture directory by its relative path (stable file names in the snapshots).
fn load(dir: &str) -> (SourceMap, config::Config, Diagnostics) {
    let mut map = SourceMap::new();
    let mut diags = Diagnostics::new();
    let cfg = config::load_dir(
        Path::new(&format!("tests/fixtures/cfg/{dir}")),
        &mut map,
        &mut diags,
    );
    (map, cfg, diags)
}

#[test]
fn valid_file() {
    let (map, cfg, diags) = load("valid");
    assert!(diags.is_empty(), "{}", diags.render_plain(&map, 80));
    let eio = cfg.eio.as_ref().unwrap();
    assert_eq!(eio.signals.len(), 7);
    let table = cfg.signal_table().unwrap();
    // 6 built-ins (ao_MoveX replaced by the file's definition) + 6 more from the file.
    assert_eq!(table.len(), 12);

    let id = table.lookup("AO_MOVEX").unwrap();
    let d = table.def(id).unwrap();
    assert_eq!((d.min_log, d.max_log), (-2500.0, 2500.0));
    assert_eq!((d.min_phys, d.max_phys), (-10.0, 10.0));
    assert_eq!(d.physical(1250.0), 5.0);
    table.set(id, 2500.0).unwrap();
    assert_eq!(
        table.set(id, 2501.0).unwrap_err().err_name(),
        Some("ERR_AO_LIM")
    );

    let di = table.lookup("di_partpresent").unwrap();
    assert_eq!(table.value(di), Some(1.0));
    assert_eq!(table.def(di).unwrap().device.as_deref(), Some("d652"));

    let ai = table.def(table.lookup("ai_Pressure").unwrap()).unwrap();
    assert_eq!(
        (ai.min_log, ai.max_log, ai.min_phys, ai.max_phys),
        (0.0, 6.0, 4.0, 20.0)
    );

    let go = table.lookup("go_Program").unwrap();
    assert_eq!(table.def(go).unwrap().bits, 8);
    table.set(go, 255.0).unwrap();
    assert_eq!(
        table.set(go, 256.0).unwrap_err().err_name(),
        Some("ERR_GO_LIM")
    );
    let gi = table.def(table.lookup("gi_Status").unwrap()).unwrap();
    assert_eq!((gi.kind, gi.bits), (SignalKind::Gi, 8));
    assert_eq!(gi.device_map.as_deref(), Some("0-3,8-11"));

    let low = table
        .def(table.lookup("DO_LOWERCASE_ATTRS").unwrap())
        .unwrap();
    assert_eq!(low.kind, SignalKind::Do);

    // The file is in the source map under the path it was read from.
    let (_, f) = map.iter().next().unwrap();
    assert_eq!(f.name, "tests/fixtures/cfg/valid/EIO.cfg");
}

#[test]
fn file_name_is_case_insensitive() {
    let (map, cfg, diags) = load("lowercase");
    assert!(diags.is_empty(), "{}", diags.render_plain(&map, 80));
    assert!(cfg.signal_table().unwrap().lookup("do_Lamp").is_some());
}

#[test]
fn backup_layout_with_crlf() {
    let (map, cfg, diags) = load("backup");
    assert!(diags.is_empty(), "{}", diags.render_plain(&map, 80));
    let table = cfg.signal_table().unwrap();
    assert!(table.lookup("doGripper").is_some());
}

#[test]
fn latin1_file() {
    let (map, cfg, diags) = load("latin1");
    assert!(diags.is_empty(), "{}", diags.render_plain(&map, 80));
    assert!(cfg.signal_table().unwrap().lookup("do_Présence").is_some());
}

#[test]
fn no_eio_file_means_builtins_only() {
    let (_, cfg, diags) = load("empty");
    assert!(diags.is_empty());
    assert_eq!(cfg.eio, None);
    let table = cfg.signal_table().unwrap();
    assert_eq!(table.len(), 6);
    assert!(table.lookup("ao_RotZ").is_some());
}

#[test]
fn missing_directory() {
    let (_, cfg, diags) = load("does-not-exist");
    assert_eq!(diags.error_count(), 1);
    assert_eq!(cfg.eio, None);
    let d = diags.iter().next().unwrap();
    assert_eq!(d.code().unwrap().to_string(), "rapidvc::config::io");
    assert!(
        d.to_string()
            .starts_with("cannot read tests/fixtures/cfg/does-not-exist: ")
    );
}

#[test]
fn bad_header() {
    let (map, cfg, diags) = load("bad_header");
    assert_eq!(cfg.eio, None);
    insta::assert_snapshot!(diags.render_plain(&map, 80));
}

#[test]
fn wrong_domain() {
    let (map, cfg, diags) = load("wrong_domain");
    assert_eq!(cfg.eio, None);
    assert!(matches!(
        diags.iter().next().and_then(|d| d.code()).map(|c| c.to_string()),
        Some(c) if c == "rapidvc::config::wrong_domain"
    ));
    insta::assert_snapshot!(diags.render_plain(&map, 80));
}

#[test]
fn malformed_signals() {
    let (map, cfg, diags) = load("malformed");
    // Every instance with a problem is reported; the good ones are kept.
    assert_eq!(diags.error_count(), 10, "{}", diags.render_plain(&map, 80));
    assert_eq!(diags.warning_count(), 3);
    let names: Vec<String> = cfg
        .eio
        .as_ref()
        .unwrap()
        .signals
        .iter()
        .map(|s| s.def.name.clone())
        .collect();
    assert_eq!(names, ["do_a", "ao_unscaled"]);
    let table = cfg.signal_table().unwrap();
    let ao = table.lookup("ao_unscaled").unwrap();
    assert_eq!(table.set(ao, 0.0), Ok(false));
    assert!(table.set(ao, 1.0).is_err());
    insta::assert_snapshot!(diags.render_plain(&map, 80));
}

#[test]
fn json_diagnostics_point_into_the_file() {
    let (map, _, diags) = load("malformed");
    let json = diags.to_json(&map);
    assert!(json.contains("\"code\":\"rapidvc::config::duplicate_signal\""));
    assert!(json.contains("\"file\":\"tests/fixtures/cfg/malformed/EIO.cfg\""));
    assert!(json.contains("\"severity\":\"warning\""));
}

/// A scratch directory of its own for one test.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rapidvc-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// An `EIO.cfg` that is a directory is an error naming it, not silently skipped (also in
/// the `SYSPAR` layout, and not hidden by a file of the same name in `SYSPAR`).
#[test]
fn eio_cfg_that_is_a_directory_is_an_error() {
    for layout in ["", "SYSPAR"] {
        let dir = scratch(&format!("eio-dir{layout}"));
        let eio = dir.join(layout).join("EIO.cfg");
        std::fs::create_dir_all(&eio).unwrap();
        if layout.is_empty() {
            // A real file further down must not hide the directory.
            std::fs::create_dir_all(dir.join("SYSPAR")).unwrap();
            std::fs::write(
                dir.join("SYSPAR/EIO.cfg"),
                "EIO:CFG_1.0:6:1::\n#\nEIO_SIGNAL:\n  -Name \"do1\" -SignalType \"DO\"\n",
            )
            .unwrap();
        }
        let mut map = SourceMap::new();
        let mut diags = Diagnostics::new();
        let cfg = config::load_dir(&dir, &mut map, &mut diags);
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(cfg.eio, None);
        assert_eq!(diags.error_count(), 1, "{}", diags.render_plain(&map, 80));
        let d = diags.iter().next().unwrap();
        assert_eq!(d.code().unwrap().to_string(), "rapidvc::config::io");
        assert_eq!(
            d.to_string(),
            format!(
                "cannot read {}: it is a directory, not a configuration file",
                eio.display()
            )
        );
    }
}

/// 200,000 signals load (the duplicate check and the merge with the built-in signals are
/// hash look-ups; they were a linear search per signal, which took minutes for this file).
/// Timing is measured by `cargo bench --bench config`, not here.
#[test]
fn eio_with_200k_signals_loads_every_signal() {
    const N: usize = 200_000;
    let dir = scratch("eio-200k");
    let mut text = String::from("EIO:CFG_1.0:6:1::\n#\nEIO_SIGNAL:\n");
    for i in 0..N {
        text.push_str(&format!("  -Name \"sig_{i}\" -SignalType \"DO\"\n"));
    }
    // One duplicate (other case) at the end, and one that replaces a built-in signal.
    text.push_str("  -Name \"SIG_0\" -SignalType \"DI\"\n");
    text.push_str("  -Name \"AO_MOVEX\" -SignalType \"AO\" -MinLog -1 -MaxLog 1\n");
    std::fs::write(dir.join("EIO.cfg"), text).unwrap();
    let mut map = SourceMap::new();
    let mut diags = Diagnostics::new();
    let cfg = config::load_dir(&dir, &mut map, &mut diags);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(diags.len(), 1);
    let dup = diags.iter().next().unwrap();
    assert_eq!(
        dup.code().unwrap().to_string(),
        "rapidvc::config::duplicate_signal"
    );
    assert_eq!(cfg.eio.as_ref().unwrap().signals.len(), N + 1);
    let table = cfg.signal_table().unwrap();
    // The built-ins, one of them replaced, plus the file's signals.
    assert_eq!(table.len(), 6 + N);
    let first = table.lookup("sig_0").unwrap();
    assert_eq!(table.def(first).unwrap().kind, SignalKind::Do);
    let last = table.lookup("SIG_199999").unwrap();
    assert_eq!(last.index(), 6 + N - 1);
    let ao = table.def(table.lookup("ao_movex").unwrap()).unwrap();
    assert_eq!((ao.min_log, ao.max_log), (-1.0, 1.0));
}

#[test]
fn config_error_is_a_rapid_diagnostic() {
    use rapidvc::diag::RapidDiagnostic;
    let e = ConfigError::Io {
        path: "x".into(),
        message: "gone".into(),
    };
    assert_eq!(e.source_id(), None);
    assert_eq!(e.to_string(), "cannot read x: gone");
}

/// SIO.cfg (UdpUc devices), MOC.cfg (External Motion Interface Data), the device table with
/// `--device` overrides, and the configuration shipped with the manual's programs.
mod egm {
    use std::path::Path;

    use rapidvc::config::devices::{DeviceOverride, DeviceTarget};
    use rapidvc::config::moc::MotionLevel;
    use rapidvc::config::sio::SioDeviceKind;
    use rapidvc::config::{self, LoadOptions};
    use rapidvc::diag::Diagnostics;
    use rapidvc::source::SourceMap;

    use super::load;

    fn load_path(dir: &str) -> (SourceMap, config::Config, Diagnostics) {
        let mut map = SourceMap::new();
        let mut diags = Diagnostics::new();
        let cfg = config::load_dir(Path::new(dir), &mut map, &mut diags);
        (map, cfg, diags)
    }

    #[test]
    fn valid_sio_and_moc() {
        let (map, cfg, diags) = load("egm");
        // One warning: the LTAPPTCP device is recorded but not usable.
        assert_eq!(diags.error_count(), 0, "{}", diags.render_plain(&map, 80));
        assert_eq!(diags.warning_count(), 1);
        insta::assert_snapshot!(diags.render_plain(&map, 80));

        let sio = cfg.sio.as_ref().unwrap();
        assert_eq!(sio.devices.len(), 4);
        assert_eq!(sio.udpuc_devices().count(), 3);
        assert!(matches!(
            &sio.device("lasertrack").unwrap().kind,
            SioDeviceKind::Unsupported { type_name } if type_name == "LTAPPTCP"
        ));

        let names: Vec<&str> = cfg.moc.profiles().iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["default", "pathCorr", "ROB_1", "ROB_1_RAW"]);
        assert_eq!(
            cfg.moc.profile("pathCorr").unwrap().level,
            MotionLevel::Path
        );
        let raw = cfg.moc.profile("rob_1_raw").unwrap();
        assert_eq!(raw.level, MotionLevel::Raw);
        assert_eq!(
            (raw.ramp_time, raw.kp, raw.filter_bandwidth),
            (0.1, 10.0, 40.0)
        );
        assert!(raw.do_not_restart_after_motors_off);

        let table = cfg.device_table(&[]).unwrap();
        assert_eq!(
            table.resolve_device("EGMsensor:"),
            Ok(DeviceTarget::Udp {
                remote: "127.0.0.1:6510".parse().unwrap(),
                local_port: 0
            })
        );
        assert_eq!(
            table.resolve_device("rob_1_v6"),
            Ok(DeviceTarget::Udp {
                remote: "[::1]:6511".parse().unwrap(),
                local_port: 6599
            })
        );
        let e = table.resolve_device("LaserTrack").unwrap_err();
        assert_eq!(
            e.to_string(),
            "device \"LaserTrack\" has type LTAPPTCP, which is not supported by rapidvc"
        );
        assert!(matches!(
            table.resolve_device("OptSim"),
            Ok(DeviceTarget::Ltapp { .. })
        ));
        assert!(table.resolve_device("nothere").is_err());

        // --device overrides the file; builtin stands in for the LTAPP device.
        let overrides: Vec<DeviceOverride> = [
            "UCdevice=127.0.0.1:6600",
            "LaserTrack=builtin:const:y=1,z=0",
        ]
        .iter()
        .map(|s| s.parse().unwrap())
        .collect();
        let table = cfg.device_table(&overrides).unwrap();
        assert_eq!(
            table.resolve_device("ucdevice"),
            Ok(DeviceTarget::Udp {
                remote: "127.0.0.1:6600".parse().unwrap(),
                local_port: 0
            })
        );
        assert_eq!(
            table.resolve_device("LaserTrack"),
            Ok(DeviceTarget::Builtin {
                pattern: Some("const:y=1,z=0".into())
            })
        );
    }

    #[test]
    fn malformed_sio_and_moc() {
        let (map, cfg, diags) = load("egm_bad");
        assert_eq!(diags.error_count(), 10, "{}", diags.render_plain(&map, 80));
        assert_eq!(diags.warning_count(), 3);
        let devices: Vec<&str> = cfg
            .sio
            .as_ref()
            .unwrap()
            .devices
            .iter()
            .map(|d| d.name.as_str())
            .collect();
        assert_eq!(devices, ["good", "sock"]);
        let names: Vec<&str> = cfg.moc.profiles().iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["default", "ok"]);
        // Diagnostics point into the files.
        let json = diags.to_json(&map);
        assert!(json.contains("\"file\":\"tests/fixtures/cfg/egm_bad/SIO.cfg\""));
        assert!(json.contains("\"file\":\"tests/fixtures/cfg/egm_bad/MOC.cfg\""));
        assert!(json.contains("\"code\":\"rapidvc::config::duplicate_device\""));
        insta::assert_snapshot!(diags.render_plain(&map, 80));
    }

    #[test]
    fn backup_layout_lowercase_names_crlf() {
        let (map, cfg, diags) = load("egm_backup");
        assert!(diags.is_empty(), "{}", diags.render_plain(&map, 80));
        assert!(cfg.sio.unwrap().device("egmsensor").is_some());
        assert_eq!(
            cfg.moc.profile("pathcorr").unwrap().level,
            MotionLevel::Path
        );
    }

    #[test]
    fn no_files_means_default_profile_and_builtin_devices() {
        let (_, cfg, diags) = load("empty");
        assert!(diags.is_empty());
        assert_eq!(cfg.sio, None);
        assert_eq!(cfg.moc.profiles().len(), 1);
        assert_eq!(
            cfg.moc.profile("default").unwrap().level,
            MotionLevel::Filtering
        );
        let e = cfg.moc.profile("pathCorr").unwrap_err();
        assert!(e.to_string().contains("\"pathCorr\" is not defined"));
        let table = cfg.device_table(&[]).unwrap();
        assert_eq!(
            table.resolve_device("EGMsensor:"),
            Ok(DeviceTarget::Builtin { pattern: None })
        );
    }

    #[test]
    fn section_alias_option() {
        let dir = std::env::temp_dir().join(format!("rapidvc-sio-alias-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(
            dir.join("SIO.cfg"),
            "SIO:CFG_1.0:7:0::\n#\nUDP_UC_DEV:\n  -Name \"s\" -Type \"UDPUC\" -RemoteAdress \"10.0.0.1\" -RemotePortNumber 6510\n",
        )
        .unwrap();
        let mut map = SourceMap::new();
        let mut diags = Diagnostics::new();
        let mut options = LoadOptions::default();
        options.sio.device_sections.push("udp_uc_dev".into());
        let cfg = config::load_dir_with(&dir, &options, &mut map, &mut diags);
        let plain = config::load_dir(&dir, &mut map, &mut diags);
        std::fs::remove_dir_all(&dir).unwrap();
        assert!(diags.is_empty());
        assert!(cfg.sio.unwrap().device("s").is_some());
        assert!(plain.sio.unwrap().devices.is_empty());
    }

    /// The manual's programs run with `--config programs/manual` (the default: the program's
    /// directory): pathCorr exists, every UdpUc device is the built-in sensor, OptSim and
    /// wg1sim are simulated seam sensors.
    #[test]
    fn manual_programs_config_loads_clean() {
        let (map, cfg, diags) = load_path("programs/manual");
        assert!(diags.is_empty(), "{}", diags.render_plain(&map, 80));
        assert_eq!(cfg.sio, None);
        assert_eq!(
            cfg.moc.profile("pathCorr").unwrap().level,
            MotionLevel::Path
        );
        assert!(cfg.moc.profile("default").is_ok());
        let table = cfg.device_table(&[]).unwrap();
        for name in ["EGMsensor:", "UCdevice"] {
            assert_eq!(
                table.resolve_device(name),
                Ok(DeviceTarget::Builtin { pattern: None })
            );
        }
        for name in ["OptSim", "wg1sim"] {
            assert!(matches!(
                table.resolve_device(name),
                Ok(DeviceTarget::Ltapp { .. })
            ));
        }
    }

    #[test]
    fn manual_programs_external_config_loads_clean() {
        let (map, cfg, diags) = load_path("programs/manual/external");
        assert!(diags.is_empty(), "{}", diags.render_plain(&map, 80));
        let (_, default_dir, _) = load_path("programs/manual");
        assert_eq!(
            cfg.moc
                .profiles()
                .iter()
                .map(|p| (&p.name, p.level, p.ramp_time, p.kp, p.filter_bandwidth))
                .collect::<Vec<_>>(),
            default_dir
                .moc
                .profiles()
                .iter()
                .map(|p| (&p.name, p.level, p.ramp_time, p.kp, p.filter_bandwidth))
                .collect::<Vec<_>>(),
            "programs/manual/external/MOC.cfg must stay a copy of programs/manual/MOC.cfg"
        );
        let table = cfg.device_table(&[]).unwrap();
        for name in ["EGMsensor:", "UCdevice"] {
            let target = table.resolve_device(name).unwrap();
            assert!(target.is_external());
            assert_eq!(
                target,
                DeviceTarget::Udp {
                    remote: "127.0.0.1:6510".parse().unwrap(),
                    local_port: 0
                }
            );
        }
        assert!(matches!(
            table.resolve_device("wg1sim"),
            Ok(DeviceTarget::Ltapp { .. })
        ));
    }
}
