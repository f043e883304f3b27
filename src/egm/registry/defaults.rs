//! Every default of the EGM instructions in one place (docs/egm.md, "Activations and defaults"), with where each comes from.
//!
//! | Argument | Default | Source |
//! |---|---|---|
//! | EGMSetupUC `\CommTimeout` | 1 s | Unknown in ABB's manuals; an ABB maintainer recalled 1 s (libegm#104) |
//! | EGMActJoint/EGMActPose `\Tool`, `\WObj` | `tool0`, `wobj0` | ABB |
//! | `\TLoad` | the tool's load | ABB |
//! | EGMActJoint `\J1`…`\J6` | ±0.5° | ABB (`egm_minmax` record default) |
//! | EGMActPose `\x \y \z` / `\rx \ry \rz` | ±1 mm / ±0.5° | ABB |
//! | `\LpFilter` | the profile's Default Low Pass Filter Bandwidth (20 Hz in "default") | ABB (stated for EGMActPose; the same for EGMActJoint by inference) |
//! | `\SampleRate` (EGMActJoint/EGMActPose/EGMStreamStart) | 4 ms, multiples of 4 | ABB |
//! | EGMActMove `\SampleRate` | 48 ms, multiples of 24 | Unknown; the manual speaks of "about 48 ms" |
//! | `\MaxPosDeviation` | 1000° | ABB |
//! | `\MaxSpeedDeviation` | 1 °/s | ABB — users trip on it; rapidvc keeps it and logs event 90110 while it limits |
//! | EGMRun… `\CondTime` | 1 s | ABB |
//! | `\RampInTime` | the profile's Default Ramp Time (0.5 s in "default") | Unknown; rapidvc's choice (docs/egm.md, "Stop modes and ramps") |
//! | `\RampOutTime` | the profile's Default Ramp Time | ABB (when the stop is not from RAPID); rapidvc also uses it when EGMRun/EGMStop omit it |
//! | `\PosCorrGain` | 1 (k = 1 × the profile's Default Proportional Position Gain, 5 in "default") | ABB |
//! | EGMStop `\RampOutTime` | the EGMRun's ramp-out time | rapidvc's choice |
//!
//! Profile values themselves ("default": Level 1, ramp 0.5 s, Kp 5, 20 Hz) live in
//! the controller's configuration (MOC.cfg).

use std::time::Duration;

use crate::egm::geometry::Convergence;
use crate::egm::servo::{self, MinMax};
use crate::egm::session;

/// `\CommTimeout` default.
pub const COMM_TIMEOUT: Duration = session::DEFAULT_COMM_TIMEOUT;
/// `\CondTime` default.
pub const COND_TIME: Duration = servo::DEFAULT_COND_TIME;
/// `\PosCorrGain` default.
pub const POS_CORR_GAIN: f64 = 1.0;
/// `\MaxSpeedDeviation` default, degrees/s.
pub const MAX_SPEED_DEVIATION: f64 = servo::DEFAULT_MAX_SPEED_DEVIATION;
/// `\MaxPosDeviation` default, degrees.
pub const MAX_POS_DEVIATION: f64 = servo::DEFAULT_MAX_POS_DEVIATION;
/// `\J1`…`\J6` window default, degrees.
pub const JOINT_WINDOW: MinMax = MinMax::JOINT_DEFAULT;
/// `\x`…`\rz` window defaults (mm, degrees).
pub const POSE_WINDOWS: Convergence = Convergence::POSE_DEFAULT;
/// `\SampleRate` default of EGMActJoint, EGMActPose and EGMStreamStart, ms.
pub const SAMPLE_RATE_MS: u64 = 4;
/// `\SampleRate` of EGMActJoint, EGMActPose and EGMStreamStart must be a multiple of this, ms.
pub const SAMPLE_RATE_MULTIPLE_MS: u64 = 4;
/// `\SampleRate` default of EGMActMove, ms.
pub const MOVE_SAMPLE_RATE_MS: u64 = 48;
/// `\SampleRate` of EGMActMove must be a multiple of this, ms.
pub const MOVE_SAMPLE_RATE_MULTIPLE_MS: u64 = 24;
/// Largest `\SampleRate` accepted, ms (a rapidvc bound that keeps times representable).
pub const MAX_SAMPLE_RATE_MS: u64 = 60_000;
