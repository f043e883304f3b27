//! Unit tests of the EGM identity registry: reservations, the state machine, setups, activations and the checks of run, stream and move requests.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

use super::*;
use crate::egm::sensor::SensorPattern;
use crate::egm::servo::StopMode;
use crate::egm::test_support::{level_2, registry, registry_with};
use crate::signals::SignalKind;

fn uc(mode: EgmMode) -> SetupUc {
    SetupUc {
        mecunit: "ROB_1".into(),
        profile: "default".into(),
        device: "EGMsensor:".into(),
        mode,
        tracker: None,
        comm_timeout: None,
    }
}

fn run() -> RunArgs {
    RunArgs::new(StopMode::Hold)
}

const ALL_J: [bool; 7] = [true, true, true, true, true, true, false];

#[test]
fn get_id_is_idempotent_per_name_and_a_fifth_is_refused() {
    let mut r = registry();
    let a = r.get_id("egmID1").unwrap();
    assert_eq!(r.get_id("EGMID1").unwrap(), a, "names are case-insensitive");
    assert_eq!(r.state(a), (EgmState::Disconnected, CorrState::Stopped));
    for n in ["b", "c", "d"] {
        r.get_id(n).unwrap();
    }
    let err = r.get_id("e").unwrap_err();
    assert!(
        matches!(err, EgmError::TooManyIdentities { max: 4, .. }),
        "{err}"
    );
    assert_eq!(err.event().number, 90120);
    assert!(err.is_fatal());
    assert!(err.to_string().contains("egmID1, b, c, d"), "{err}");
    // Releasing one makes room; the old id is stale.
    assert_eq!(r.reset(a), StopTarget::Nothing);
    assert_eq!(r.state(a), (EgmState::Disconnected, CorrState::Undefined));
    assert_eq!(
        r.reset(a),
        StopTarget::Nothing,
        "resetting twice is harmless"
    );
    let e = r.get_id("e").unwrap();
    assert_ne!(e, a);
    assert_eq!(EgmId::from_raw(e.to_raw()), e);
    assert!(matches!(
        r.setup_uc(a, &uc(EgmMode::Joint)),
        Err(EgmError::NotReserved { .. })
    ));
    assert_eq!(r.names().len(), 4);
    assert_eq!(r.name_of(e), Some("e"));
    assert_eq!(r.lookup("B"), r.lookup("b"));
}

#[test]
fn state_numbers_match_egm_sys() {
    let sys = include_str!("../../../stdlib/egm.sys");
    for (name, v) in [
        ("EGM_STATE_DISCONNECTED", EgmState::Disconnected.value()),
        ("EGM_STATE_CONNECTED", EgmState::Connected.value()),
        ("EGM_STATE_RUNNING", EgmState::Running.value()),
    ] {
        assert!(
            sys.contains(&format!("CONST egmstate {name} := {v};")),
            "{name}"
        );
    }
    for (name, v) in [
        ("EGM_CORR_UNDEFINED", CorrState::Undefined.value()),
        ("EGM_CORR_ERROR", CorrState::Error.value()),
        ("EGM_CORR_STOPPED", CorrState::Stopped.value()),
        ("EGM_CORR_RUNNING", CorrState::Running.value()),
    ] {
        assert!(
            sys.contains(&format!("CONST egmcorrstate {name} := {v};")),
            "{name}"
        );
    }
    for (name, mode) in [
        ("EGM_STOP_HOLD", StopMode::Hold),
        ("EGM_STOP_RAMP_DOWN", StopMode::RampDown),
    ] {
        let v = stop_mode_value(mode);
        assert!(
            sys.contains(&format!("CONST egmstopmode {name} := {v};")),
            "{name}"
        );
        assert_eq!(stop_mode_from_value("EGMStop", v).unwrap(), mode);
    }
    assert!(stop_mode_from_value("EGMStop", 3.0).is_err());
    assert_eq!(
        frame_type_from_value("EGMActPose", "CorrFrType", 4.0).unwrap(),
        EgmFrameType::World
    );
    assert!(frame_type_from_value("EGMActPose", "CorrFrType", 0.5).is_err());
}

#[test]
fn the_state_machine_of_a_joint_run() {
    let mut r = registry();
    let id = r.get_id("egmID1").unwrap();
    r.setup_uc(id, &uc(EgmMode::Joint)).unwrap();
    assert_eq!(r.state(id), (EgmState::Connected, CorrState::Stopped));
    let setup = r.setup(id).unwrap();
    assert_eq!(setup.comm_timeout, Duration::from_secs(1));
    assert!(matches!(
        &setup.source,
        SourceSpec::Builtin { device, pattern: SensorPattern::Hold(EgmMode::Joint) } if device == "EGMsensor"
    ));
    let err = r.run_joint(id, &run(), ALL_J).unwrap_err();
    assert!(
        matches!(
            err,
            EgmError::NotActivated {
                needs: "EGMActJoint",
                ..
            }
        ),
        "{err}"
    );
    r.act_joint(id, &ActJoint::default()).unwrap();
    assert_eq!(r.state(id), (EgmState::Connected, CorrState::Stopped));
    let plan = r.run_joint(id, &run(), ALL_J).unwrap();
    assert_eq!(r.state(id), (EgmState::Running, CorrState::Running));
    assert!(r.is_running(id));
    // The documented defaults.
    assert_eq!(plan.cond_time, Duration::from_secs(1));
    assert_eq!(plan.ramp_in_time, Duration::from_millis(500));
    assert_eq!(plan.ramp_out_time, Duration::from_millis(500));
    assert_eq!(plan.pos_corr_gain, 1.0);
    assert_eq!(plan.max_speed_deviation, 1.0);
    assert_eq!(plan.max_pos_deviation, 1000.0);
    assert_eq!(plan.sample_period, Duration::from_millis(4));
    assert_eq!(plan.lp_filter_hz, 20.0);
    assert_eq!(plan.windows, [MinMax::JOINT_DEFAULT; 6]);
    assert_eq!(plan.profile.kp, 5.0);
    assert!(plan.moves() && !plan.stops_stream);
    // Busy while running.
    let err = r.act_joint(id, &ActJoint::default()).unwrap_err();
    assert!(matches!(err, EgmError::Busy { .. }), "{err}");
    assert_eq!(r.stop(id).unwrap(), StopTarget::Run);
    assert_eq!(
        r.state(id).0,
        EgmState::Running,
        "until the driver finishes"
    );
    r.run_finished(id, false);
    assert_eq!(r.state(id), (EgmState::Connected, CorrState::Error));
    r.run_joint(id, &run(), ALL_J).unwrap();
    r.run_finished(id, true);
    assert_eq!(r.state(id), (EgmState::Connected, CorrState::Stopped));
    assert_eq!(r.stop(id).unwrap(), StopTarget::Nothing);
    r.run_joint(id, &run(), [false; 7])
        .map(|p| assert!(!p.moves()))
        .unwrap();
    r.abandon_all();
    assert_eq!(r.state(id), (EgmState::Connected, CorrState::Stopped));
    assert_eq!(r.reset(id), StopTarget::Nothing);
    assert_eq!(r.state(id), (EgmState::Disconnected, CorrState::Undefined));
}

#[test]
fn mode_mismatch_is_fatal_41826() {
    let mut r = registry();
    let id = r.get_id("egmID1").unwrap();
    r.setup_uc(id, &uc(EgmMode::Pose)).unwrap();
    r.act_pose(id, &ActPose::world()).unwrap();
    let err = r.run_joint(id, &run(), ALL_J).unwrap_err();
    assert_eq!(err.event().number, 41826);
    assert_eq!(err.event().title, "EGM mode mismatch");
    assert!(err.is_fatal() && err.rapid_error().is_none());
    assert!(err.to_string().contains("EGMRunJoint egmID1"), "{err}");
    assert_eq!(r.state(id).0, EgmState::Connected, "nothing started");
    // Joint setup, pose activation, joint run: the activation does not fit.
    let id2 = r.get_id("egmID2").unwrap();
    r.setup_uc(id2, &uc(EgmMode::Joint)).unwrap();
    r.act_pose(id2, &ActPose::world()).unwrap();
    let err = r.run_joint(id2, &run(), ALL_J).unwrap_err();
    assert_eq!(err.event().number, 41826);
    assert!(err.to_string().contains("activated by EGMActPose"), "{err}");
    // And the reverse.
    r.act_joint(id2, &ActJoint::default()).unwrap();
    let err = r.run_pose(id2, &run(), [true; 6], None).unwrap_err();
    assert_eq!(err.event().number, 41826);
}

#[test]
fn not_set_up_and_not_reserved() {
    let mut r = registry();
    let id = r.get_id("egmID1").unwrap();
    let err = r.act_joint(id, &ActJoint::default()).unwrap_err();
    assert!(matches!(err, EgmError::NotSetUp { .. }));
    assert_eq!(err.event().number, 90122);
    let err = r.run_pose(id, &run(), [true; 6], None).unwrap_err();
    assert!(matches!(err, EgmError::NotSetUp { .. }));
    assert!(matches!(
        r.stream_start(id, None),
        Err(EgmError::NotSetUp { .. })
    ));
    let stale = EgmId::from_raw(0xdead_0003);
    assert!(matches!(r.stop(stale), Err(EgmError::NotReserved { .. })));
    assert!(matches!(
        r.stream_stop(stale),
        Err(EgmError::NotReserved { .. })
    ));
    assert_eq!(
        r.state(stale),
        (EgmState::Disconnected, CorrState::Undefined)
    );
}

#[test]
fn sample_rates_are_multiples_of_4_and_24() {
    let mut r = registry();
    let id = r.get_id("egmID1").unwrap();
    r.setup_uc(id, &uc(EgmMode::Joint)).unwrap();
    for bad in [6.0, 0.0, -4.0, 4.5, f64::NAN, 1e12] {
        let mut a = ActJoint::default();
        a.common.sample_rate = Some(bad);
        let err = r.act_joint(id, &a).unwrap_err();
        assert!(
            matches!(err, EgmError::SampleRate { multiple: 4, .. }),
            "{bad}: {err}"
        );
        assert_eq!(err.event().number, 90124);
    }
    let mut a = ActJoint::default();
    a.common.sample_rate = Some(8.0);
    r.act_joint(id, &a).unwrap();
    assert_eq!(
        r.activation(id).unwrap().sample_period,
        Duration::from_millis(8)
    );
    let err = r
        .act_move(
            id,
            &ActMove {
                sensor_frame: Pose::identity(),
                sample_rate: Some(50.0),
            },
        )
        .unwrap_err();
    assert!(
        err.to_string().contains("multiple of 24 ms (24, 48, 72"),
        "{err}"
    );
    r.act_move(
        id,
        &ActMove {
            sensor_frame: Pose::identity(),
            sample_rate: None,
        },
    )
    .unwrap();
    assert_eq!(
        r.move_activation(id).unwrap().sample_period,
        Duration::from_millis(48)
    );
}

#[test]
fn argument_values_are_checked_at_the_activation() {
    let mut r = registry();
    let id = r.get_id("egmID1").unwrap();
    r.setup_uc(id, &uc(EgmMode::Joint)).unwrap();
    let mut a = ActJoint::default();
    a.windows[1] = Some(MinMax {
        min: 1.0,
        max: -1.0,
    });
    let err = r.act_joint(id, &a).unwrap_err();
    assert!(err.to_string().contains("\\J2"), "{err}");
    let mut a = ActJoint::default();
    a.windows[6] = Some(MinMax::JOINT_DEFAULT);
    assert!(matches!(
        r.act_joint(id, &a),
        Err(EgmError::Unsupported { .. })
    ));
    let mut a = ActJoint::default();
    a.common.max_speed_deviation = Some(-1.0);
    assert!(
        r.act_joint(id, &a)
            .unwrap_err()
            .to_string()
            .contains("\\MaxSpeedDeviation")
    );
    let mut a = ActJoint::default();
    a.common.data_to_sensor = true;
    assert!(matches!(
        r.act_joint(id, &a),
        Err(EgmError::Unsupported { .. })
    ));
    let mut a = ActJoint::default();
    a.common.lp_filter = Some(0.0);
    a.common.max_speed_deviation = Some(20.0);
    a.windows[0] = Some(MinMax {
        min: -0.1,
        max: 0.2,
    });
    r.act_joint(id, &a).unwrap();
    assert!(matches!(
        r.run_joint(
            id,
            &RunArgs {
                cond_time: Some(-1.0),
                ..run()
            },
            ALL_J
        ),
        Err(EgmError::Argument {
            argument: "\\CondTime",
            ..
        })
    ));
    assert!(matches!(
        r.run_joint(
            id,
            &RunArgs {
                pos_corr_gain: Some(f64::NAN),
                ..run()
            },
            ALL_J
        ),
        Err(EgmError::Argument {
            argument: "\\PosCorrGain",
            ..
        })
    ));
    assert!(matches!(
        r.run_joint(id, &run(), [false, false, false, false, false, false, true]),
        Err(EgmError::Unsupported { .. })
    ));
    let args = RunArgs {
        cond_time: Some(9e9),
        ramp_in_time: Some(0.05),
        pos_corr_gain: Some(0.0),
        ..run()
    };
    let plan = r.run_joint(id, &args, ALL_J).unwrap();
    assert_eq!(
        plan.lp_filter_hz, 20.0,
        "LpFilter 0 uses the profile's bandwidth"
    );
    assert_eq!(plan.max_speed_deviation, 20.0);
    assert_eq!(
        plan.windows[0],
        MinMax {
            min: -0.1,
            max: 0.2
        }
    );
    assert_eq!(plan.cond_time, Duration::from_secs(9_000_000_000));
    assert_eq!(plan.ramp_in_time, Duration::from_millis(50));
    assert_eq!(plan.pos_corr_gain, 0.0);
    // Pose activation checks.
    r.run_finished(id, true);
    let mut p = ActPose::world();
    p.sens_type = EgmFrameType::Joint;
    assert!(matches!(r.act_pose(id, &p), Err(EgmError::Guidance { .. })));
    let mut p = ActPose::world();
    p.windows[3] = Some(MinMax {
        min: f64::NAN,
        max: 1.0,
    });
    assert!(r.act_pose(id, &p).unwrap_err().to_string().contains("\\rx"));
}

#[test]
fn profiles_devices_and_trackers_at_setup() {
    let mut r = registry_with(&["ext=127.0.0.1:6510", "pat=builtin:joint:1,2,3,4,5,6"]);
    let id = r.get_id("egmID1").unwrap();
    let mut s = uc(EgmMode::Joint);
    s.profile = "pathCorr".into();
    let err = r.setup_uc(id, &s).unwrap_err();
    assert!(matches!(err, EgmError::UnknownProfile { .. }), "{err}");
    assert_eq!(err.event().number, 90125);
    assert_eq!(r.state(id).0, EgmState::Disconnected);
    let mut s = uc(EgmMode::Joint);
    s.mecunit = "ROB_2".into();
    assert!(
        r.setup_uc(id, &s)
            .unwrap_err()
            .to_string()
            .contains("ROB_2")
    );
    let mut s = uc(EgmMode::Joint);
    s.tracker = Some(TrackerKind::Aptr);
    assert!(r.setup_uc(id, &s).is_err());
    let s = uc(EgmMode::PathCorr);
    assert!(
        r.setup_uc(id, &s)
            .unwrap_err()
            .to_string()
            .contains("\\APTR or \\LATR")
    );
    let mut s = uc(EgmMode::Joint);
    s.comm_timeout = Some(0.0);
    assert!(matches!(
        r.setup_uc(id, &s),
        Err(EgmError::Argument {
            argument: "\\CommTimeout",
            ..
        })
    ));
    // An external device.
    let mut s = uc(EgmMode::Pose);
    s.device = "EXT:".into();
    s.comm_timeout = Some(2.5);
    r.setup_uc(id, &s).unwrap();
    let setup = r.setup(id).unwrap();
    assert_eq!(setup.comm_timeout, Duration::from_millis(2500));
    assert!(setup.source.is_external());
    assert_eq!(setup.source.device(), Some("EXT"));
    // A built-in pattern of the wrong mode.
    let mut s = uc(EgmMode::Pose);
    s.device = "pat".into();
    let err = r.setup_uc(id, &s).unwrap_err();
    assert!(err.to_string().contains("talks joint mode"), "{err}");
    s.mode = EgmMode::Joint;
    r.setup_uc(id, &s).unwrap();
    assert!(matches!(
        r.setup(id).unwrap().source,
        SourceSpec::Builtin {
            pattern: SensorPattern::Joint(_),
            ..
        }
    ));
}

#[test]
fn a_new_setup_clears_the_activation() {
    let mut r = registry();
    let id = r.get_id("egmID1").unwrap();
    r.setup_uc(id, &uc(EgmMode::Joint)).unwrap();
    r.act_joint(id, &ActJoint::default()).unwrap();
    r.setup_uc(id, &uc(EgmMode::Joint)).unwrap();
    assert!(r.activation(id).is_none());
    assert!(matches!(
        r.run_joint(id, &run(), ALL_J),
        Err(EgmError::NotActivated { .. })
    ));
}

#[test]
fn path_correction_needs_a_level_2_profile_50452() {
    let mut r = registry();
    let id = r.get_id("egmId1").unwrap();
    let mut s = uc(EgmMode::PathCorr);
    s.tracker = Some(TrackerKind::Aptr);
    r.setup_uc(id, &s).unwrap();
    assert!(matches!(
        r.move_start(id, "EGMMoveL"),
        Err(EgmError::NotActivated {
            needs: "EGMActMove",
            ..
        })
    ));
    r.act_move(
        id,
        &ActMove {
            sensor_frame: Pose::identity(),
            sample_rate: Some(48.0),
        },
    )
    .unwrap();
    let err = r.move_start(id, "EGMMoveL").unwrap_err();
    assert_eq!(err.event().number, 50452);
    assert_eq!(err.event().title, "External Interface Cyclic Error");
    assert!(err.to_string().contains("\"default\" has Level 1"), "{err}");
}

#[test]
fn level_2_profile_runs_a_corrected_sequence() {
    let profiles = Profiles::new(vec![level_2("pathCorr")]);
    let devices = crate::egm::test_support::devices(&["OptSim=ltapp:sine:y=2,z=0.5,period=200"]);
    let mut r = EgmRegistry::new(RegistryConfig::new(profiles, devices));
    let id = r.get_id("egmId1").unwrap();
    r.setup_ltapp(
        id,
        &SetupLtapp {
            mecunit: "ROB_1".into(),
            profile: "pathCorr".into(),
            device: "OptSim".into(),
            joint_type: 1.0,
            tracker: TrackerKind::Latr,
        },
    )
    .unwrap();
    assert!(matches!(
        r.setup(id).unwrap().source,
        SourceSpec::Ltapp { .. }
    ));
    r.act_move(
        id,
        &ActMove {
            sensor_frame: Pose::identity(),
            sample_rate: None,
        },
    )
    .unwrap();
    let plan = r.move_start(id, "EGMMoveL").unwrap();
    assert_eq!(plan.tracker, TrackerKind::Latr);
    assert_eq!(r.state(id), (EgmState::Running, CorrState::Running));
    r.move_start(id, "EGMMoveC").unwrap();
    assert!(matches!(
        r.stream_start(id, None),
        Err(EgmError::BadSetup { .. })
    ));
    r.move_finished(id, true);
    assert_eq!(r.state(id), (EgmState::Connected, CorrState::Stopped));
    // EGMRunJoint on a path-correction setup is a mode mismatch.
    assert_eq!(
        r.run_joint(id, &run(), ALL_J).unwrap_err().event().number,
        41826
    );
    // EGMSetupLTAPP on a UdpUc device is not supported.
    let mut r = registry_with(&["ext=127.0.0.1:6510"]);
    let id = r.get_id("x").unwrap();
    let err = r
        .setup_ltapp(
            id,
            &SetupLtapp {
                mecunit: "ROB_1".into(),
                profile: "default".into(),
                device: "ext".into(),
                joint_type: 1.0,
                tracker: TrackerKind::Aptr,
            },
        )
        .unwrap_err();
    assert_eq!(err.event().number, 90127);
}

#[test]
fn signal_setups() {
    let table = SignalTable::with_builtins();
    let mut r = registry();
    let id = r.get_id("egmID1").unwrap();
    let x = table.lookup("ao_MoveX").unwrap();
    let mut args = SetupSignals {
        mecunit: "ROB_1".into(),
        profile: "default".into(),
        kind: SignalKind::Ao,
        mode: EgmMode::Pose,
        tracker: None,
        mapping: [Some(x), None, None, None, None, None],
        ext: [None; 6],
    };
    r.setup_signals(id, &args, &table).unwrap();
    assert_eq!(r.state(id).0, EgmState::Connected);
    assert!(matches!(
        r.setup(id).unwrap().source,
        SourceSpec::Signals { .. }
    ));
    // Streams and RAPID-data arguments need UdpUc.
    assert!(matches!(
        r.stream_start(id, None),
        Err(EgmError::BadSetup { .. })
    ));
    let mut p = ActPose::world();
    p.common.stream_start = true;
    assert!(matches!(r.act_pose(id, &p), Err(EgmError::BadSetup { .. })));
    // No signal at all: an error that stops the program.
    args.mapping = [None; 6];
    let err = r.setup_signals(id, &args, &table).unwrap_err();
    assert!(
        err.to_string().contains("needs at least one signal"),
        "{err}"
    );
    assert!(err.is_fatal());
    args.mapping[0] = Some(x);
    args.kind = SignalKind::Ai;
    let err = r.setup_signals(id, &args, &table).unwrap_err();
    assert!(
        err.to_string().contains("EGMSetupAI takes AI signals"),
        "{err}"
    );
    args.kind = SignalKind::Ao;
    args.mode = EgmMode::PathCorr;
    args.tracker = Some(TrackerKind::Latr);
    assert!(
        r.setup_signals(id, &args, &table)
            .unwrap_err()
            .to_string()
            .contains("\\LATR")
    );
    args.tracker = Some(TrackerKind::Aptr);
    r.setup_signals(id, &args, &table).unwrap();
}

#[test]
fn streams() {
    let mut r = registry();
    let id = r.get_id("egmID1").unwrap();
    r.setup_uc(id, &uc(EgmMode::Joint)).unwrap();
    let plan = r.stream_start(id, Some(8.0)).unwrap();
    assert_eq!(plan.sample_period, Duration::from_millis(8));
    assert_eq!(r.state(id), (EgmState::Running, CorrState::Stopped));
    assert!(r.is_streaming(id));
    assert!(matches!(
        r.stream_start(id, None),
        Err(EgmError::Busy { .. })
    ));
    assert!(r.stream_stop(id).unwrap());
    assert!(!r.stream_stop(id).unwrap());
    assert_eq!(r.state(id), (EgmState::Connected, CorrState::Stopped));
    // \StreamStart on the activation, then a run takes over.
    let mut a = ActJoint::default();
    a.common.stream_start = true;
    a.common.sample_rate = Some(12.0);
    let plan = r.act_joint(id, &a).unwrap().unwrap();
    assert_eq!(plan.sample_period, Duration::from_millis(12));
    assert_eq!(r.state(id), (EgmState::Running, CorrState::Stopped));
    let run_plan = r.run_joint(id, &run(), ALL_J).unwrap();
    assert!(run_plan.stops_stream);
    assert_eq!(r.state(id), (EgmState::Running, CorrState::Running));
    r.run_finished(id, true);
    assert_eq!(r.state(id), (EgmState::Connected, CorrState::Stopped));
    // EGMStop ends a stream at once.
    r.stream_start(id, None).unwrap();
    assert_eq!(r.stop(id).unwrap(), StopTarget::Stream);
    assert_eq!(r.state(id).0, EgmState::Connected);
    r.stream_start(id, None).unwrap();
    assert_eq!(r.reset(id), StopTarget::Stream);
}
