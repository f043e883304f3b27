//! Argument checks and small resolutions shared by the registry's instructions: trackers, sample rates, seconds, windows, the activation's common arguments and the built-in sensor's pattern.

use std::net::SocketAddr;
use std::time::Duration;

use super::configuration::MotionProfile;
use crate::egm::sensor::{PathCorrProfile, PatternError, SensorPattern};
use crate::egm::servo::MinMax;
use crate::egm::types::EgmMode;

use super::{
    ActCommon, Activation, ActivationKind, EgmError, Setup, SourceSpec, TrackerKind, defaults,
};

pub(super) fn bad(instruction: &'static str, detail: &str) -> EgmError {
    EgmError::BadSetup {
        instruction,
        detail: detail.to_string(),
    }
}

pub(super) fn describe_mode(mode: EgmMode) -> &'static str {
    match mode {
        EgmMode::Joint => "joint guidance (\\Joint)",
        EgmMode::Pose => "pose guidance (\\Pose)",
        EgmMode::PathCorr => "path correction (\\PathCorr)",
    }
}

pub(super) fn udp_spec(device: String, remote: SocketAddr, local_port: u16) -> SourceSpec {
    SourceSpec::Udp {
        device,
        remote,
        local_port,
    }
}

pub(super) fn check_tracker_uc(
    instruction: &'static str,
    mode: EgmMode,
    tracker: Option<TrackerKind>,
) -> Result<(), EgmError> {
    match (mode, tracker) {
        (EgmMode::PathCorr, Some(_)) | (EgmMode::Joint | EgmMode::Pose, None) => Ok(()),
        (EgmMode::PathCorr, None) => Err(bad(instruction, "\\PathCorr needs \\APTR or \\LATR")),
        (_, Some(_)) => Err(bad(
            instruction,
            "\\APTR and \\LATR are only allowed with \\PathCorr",
        )),
    }
}

pub(super) fn check_streamable(instruction: &'static str, setup: &Setup) -> Result<(), EgmError> {
    if !setup.source.is_udpuc() {
        return Err(bad(
            instruction,
            "a position stream needs a UdpUc setup (EGMSetupUC); signal and LTAPP sources cannot stream",
        ));
    }
    if setup.mode == EgmMode::PathCorr {
        return Err(bad(
            instruction,
            "a position stream cannot be combined with path correction (\\PathCorr)",
        ));
    }
    Ok(())
}

/// The built-in sensor's pattern for a UdpUc setup in `mode`.
pub(super) fn builtin_pattern(
    instruction: &'static str,
    device: &str,
    text: Option<&str>,
    mode: EgmMode,
) -> Result<SensorPattern, EgmError> {
    let Some(text) = text else {
        return Ok(match mode {
            EgmMode::Joint | EgmMode::Pose => SensorPattern::Hold(mode),
            EgmMode::PathCorr => SensorPattern::PathCorr {
                profile: PathCorrProfile::Constant,
                y_mm: 0.0,
                z_mm: 0.0,
            },
        });
    };
    let pattern: SensorPattern = text
        .parse()
        .map_err(|e: PatternError| EgmError::BadDevice {
            instruction,
            device: device.to_string(),
            detail: e.to_string(),
        })?;
    if pattern.mode() != mode {
        return Err(EgmError::BadDevice {
            instruction,
            device: device.to_string(),
            detail: format!(
                "the built-in sensor pattern `{text}` talks {} mode, but the setup asks for {}",
                pattern.mode(),
                describe_mode(mode)
            ),
        });
    }
    Ok(pattern)
}

pub(super) fn resolve_common(
    instruction: &'static str,
    args: &ActCommon,
    setup: &Setup,
    kind: ActivationKind,
) -> Result<Activation, EgmError> {
    if args.data_to_sensor || args.data_from_sensor {
        return Err(EgmError::Unsupported {
            instruction,
            what: "\\DataToSensor and \\DataFromSensor (RAPID data exchange with the sensor)",
        });
    }
    let udp_only = [
        (args.do_to_sensor.is_some(), "\\DOToSensor"),
        (args.di_from_sensor.is_some(), "\\DIFromSensor"),
        (args.stream_start, "\\StreamStart"),
    ];
    for (given, name) in udp_only {
        if given && !setup.source.is_udpuc() {
            return Err(EgmError::BadSetup {
                instruction,
                detail: format!("{name} needs a UdpUc setup (EGMSetupUC)"),
            });
        }
    }
    if let Some(lp) = args.lp_filter
        && !lp.is_finite()
    {
        return Err(EgmError::Argument {
            instruction,
            argument: "\\LpFilter",
            value: lp,
            range: "a number of Hz (≤ 0 uses the profile's bandwidth)",
        });
    }
    let sample_period = sample_rate(
        instruction,
        args.sample_rate,
        defaults::SAMPLE_RATE_MS,
        defaults::SAMPLE_RATE_MULTIPLE_MS,
    )?;
    let non_negative =
        |argument: &'static str, v: Option<f64>, default: f64, range: &'static str| {
            let v = v.unwrap_or(default);
            if v.is_finite() && v >= 0.0 {
                Ok(v)
            } else {
                Err(EgmError::Argument {
                    instruction,
                    argument,
                    value: v,
                    range,
                })
            }
        };
    let max_pos_deviation = non_negative(
        "\\MaxPosDeviation",
        args.max_pos_deviation,
        defaults::MAX_POS_DEVIATION,
        "a number of degrees ≥ 0",
    )?;
    let max_speed_deviation = non_negative(
        "\\MaxSpeedDeviation",
        args.max_speed_deviation,
        defaults::MAX_SPEED_DEVIATION,
        "a number of degrees/s ≥ 0",
    )?;
    Ok(Activation {
        instruction,
        kind,
        tool: args.tool.unwrap_or_default(),
        wobj: args.wobj.clone().unwrap_or_default(),
        tload: args.tload,
        do_to_sensor: args.do_to_sensor,
        di_from_sensor: args.di_from_sensor,
        lp_filter_hz: args.lp_filter.filter(|lp| *lp > 0.0),
        sample_period,
        max_pos_deviation,
        max_speed_deviation,
    })
}

pub(super) fn check_window(
    instruction: &'static str,
    argument: &'static str,
    w: &MinMax,
) -> Result<(), EgmError> {
    if !(w.min.is_finite() && w.max.is_finite()) {
        let value = if w.min.is_finite() { w.max } else { w.min };
        return Err(EgmError::Argument {
            instruction,
            argument,
            value,
            range: "an egm_minmax of finite numbers",
        });
    }
    if w.min > w.max {
        return Err(EgmError::Argument {
            instruction,
            argument,
            value: w.min,
            range: "an egm_minmax with min ≤ max",
        });
    }
    Ok(())
}

/// A `\SampleRate` in ms: a positive multiple of `multiple` (default `default`).
pub(super) fn sample_rate(
    instruction: &'static str,
    value: Option<f64>,
    default: u64,
    multiple: u64,
) -> Result<Duration, EgmError> {
    let Some(v) = value else {
        return Ok(Duration::from_millis(default));
    };
    let err = EgmError::SampleRate {
        instruction,
        value: v,
        multiple,
    };
    if !(v.is_finite() && v > 0.0 && v <= defaults::MAX_SAMPLE_RATE_MS as f64 && v.fract() == 0.0) {
        return Err(err);
    }
    // Exact: an integer in 1..=60000.
    let ms = v as u64;
    if !ms.is_multiple_of(multiple) {
        return Err(err);
    }
    Ok(Duration::from_millis(ms))
}

pub(super) fn seconds(
    instruction: &'static str,
    argument: &'static str,
    v: f64,
    zero_ok: bool,
) -> Result<Duration, EgmError> {
    let ok = v.is_finite() && (v > 0.0 || (zero_ok && v == 0.0));
    if !ok {
        return Err(EgmError::Argument {
            instruction,
            argument,
            value: v,
            range: if zero_ok {
                "a number of seconds ≥ 0"
            } else {
                "a number of seconds > 0"
            },
        });
    }
    // Huge values (users pass 9e9 s to keep a session open) saturate.
    Ok(Duration::try_from_secs_f64(v).unwrap_or(Duration::MAX))
}

pub(super) fn opt_seconds(
    instruction: &'static str,
    argument: &'static str,
    v: Option<f64>,
    default: Duration,
) -> Result<Duration, EgmError> {
    match v {
        Some(v) => seconds(instruction, argument, v, true),
        None => Ok(default),
    }
}

/// The profile's Default Ramp Time.
pub(super) fn profile_ramp(p: &MotionProfile) -> Duration {
    Duration::try_from_secs_f64(p.ramp_time).unwrap_or(crate::egm::servo::DEFAULT_RAMP_TIME)
}
