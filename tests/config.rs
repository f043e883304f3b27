//! Reading configuration directories: EIO.cfg fixtures under `tests/fixtures/cfg/`, valid and
//! malformed, with the rendered diagnostics snapshotted (colour off, 80 columns).

use std::path::Path;

use rapidvc::config::{self, ConfigError};
use rapidvc::diag::Diagnostics;
use rapidvc::io::SignalKind;
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
