//! Target patterns of the built-in sensor and their text form (`joint:…`, `pose:…`, `sine:…`, `circle:…`, `pathcorr:…`).
//!
//! Text form (used by `--device NAME=builtin:PATTERN`; `rapidvc sensor` has flags for the
//! same things):
//!
//! | Pattern | Mode | Meaning |
//! |---|---|---|
//! | `hold` | joint | keep the joints the session started at |
//! | `hold-pose` | pose | keep the pose the session started at |
//! | `joint:J1,J2,J3,J4,J5,J6` | joint | constant joint target, degrees |
//! | `pose:X,Y,Z,RX,RY,RZ` | pose | constant pose target, mm and ZYX Euler degrees |
//! | `sine[:axis=A,amplitude=M,frequency=F]` | joint for `axis=1..6`, pose for `axis=x\|y\|z` | start value + M·sin(2π·F·t) on one axis; defaults axis 1, M = 10 (degrees or mm), F = 0.1 Hz |
//! | `circle[:radius=R,frequency=F]` | pose | circle in the x-y plane that starts at the start position: start + R·(cos(2πFt) − 1, sin(2πFt), 0); defaults R = 50 mm, F = 0.1 Hz |
//! | `pathcorr[:kind=K,y=Y,z=Z,time=T,frequency=F]` | path correction | correction (0, y, z) in mm: `constant` (default), `ramp` (linear from 0 over T s, default 1) or `sine` (Y, Z are amplitudes, F Hz, default 0.5) |
//!
//! Moving patterns also send the analytic speed as `speedRef` (feed-forward), unless the
//! sensor is configured not to. Time t starts when the controller starts a session (seqno 0).

use std::f64::consts::TAU;
use std::str::FromStr;

use crate::egm::convert::quaternion_from_euler_zyx;
use crate::egm::types::{EgmMode, Joints, Pose, ROBOT_AXES};

/// Default sine amplitude (degrees or mm).
pub const DEFAULT_AMPLITUDE: f64 = 10.0;
/// Default frequency of moving patterns, Hz.
pub const DEFAULT_FREQUENCY: f64 = 0.1;
/// Default circle radius, mm.
pub const DEFAULT_RADIUS: f64 = 50.0;
/// Default path-correction ramp time, s.
pub const DEFAULT_RAMP_TIME: f64 = 1.0;
/// Default path-correction sine frequency, Hz.
pub const DEFAULT_PATHCORR_FREQUENCY: f64 = 0.5;

/// The axis a sine moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SineAxis {
    /// Robot joint, 0-based (joint mode).
    Joint(usize),
    /// Cartesian direction 0 = x, 1 = y, 2 = z (pose mode).
    Cartesian(usize),
}

/// Path-correction profile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PathCorrProfile {
    /// Constant (0, y, z).
    Constant,
    /// Linear ramp from 0 to (0, y, z) over `time_s`.
    Ramp {
        /// Ramp duration, s.
        time_s: f64,
    },
    /// (0, y, z)·sin(2π·f·t).
    Sine {
        /// Frequency, Hz.
        frequency_hz: f64,
    },
}

/// What the built-in sensor asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SensorPattern {
    /// Keep the start position: joint mode (`hold`) or pose mode (`hold-pose`).
    Hold(EgmMode),
    /// Constant joint target, degrees.
    Joint(Joints),
    /// Constant pose target: position mm, ZYX Euler angles degrees.
    Pose {
        /// x, y, z in mm.
        pos: [f64; 3],
        /// rx, ry, rz in degrees (ZYX).
        euler: [f64; 3],
    },
    /// Sine on one axis around the start position.
    Sine {
        /// Which axis.
        axis: SineAxis,
        /// Amplitude, degrees or mm.
        amplitude: f64,
        /// Frequency, Hz.
        frequency_hz: f64,
    },
    /// Circle in the x-y plane through the start position (pose mode).
    Circle {
        /// Radius, mm.
        radius_mm: f64,
        /// Frequency, Hz.
        frequency_hz: f64,
    },
    /// Path correction in y and z.
    PathCorr {
        /// Profile.
        profile: PathCorrProfile,
        /// y, mm.
        y_mm: f64,
        /// z, mm.
        z_mm: f64,
    },
}

/// The robot's position when the session started (the pattern's origin).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Origin {
    /// Joints, degrees, if the robot reported them.
    pub joints: Option<Joints>,
    /// TCP pose, if the robot reported it.
    pub pose: Option<Pose>,
}

/// A pattern's target at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PatternOutput {
    /// Joint target and optional feed-forward speed (degrees/s).
    Joint {
        /// Target joints.
        joints: Joints,
        /// Feed-forward speed.
        speed: Option<Joints>,
    },
    /// Pose target and optional feed-forward speed (mm/s, degrees/s).
    Pose {
        /// Target pose.
        pose: Pose,
        /// Feed-forward speed.
        speed: Option<[f64; 6]>,
    },
    /// Path correction, mm.
    PathCorr {
        /// Correction (x is always 0).
        pos: [f64; 3],
    },
}

/// A pattern that cannot be used.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PatternError {
    /// Unknown pattern name.
    #[error(
        "unknown sensor pattern `{0}`; use hold, hold-pose, joint:…, pose:…, sine, circle or pathcorr"
    )]
    UnknownPattern(String),
    /// A value is missing, not a number, or out of range.
    #[error("sensor pattern: {0}")]
    BadValue(String),
    /// The origin lacks the part the pattern needs.
    #[error("the robot's first message has no {0}; the pattern needs it")]
    NoOrigin(&'static str),
}

impl SensorPattern {
    /// The EGM mode the pattern talks in.
    pub fn mode(&self) -> EgmMode {
        match self {
            SensorPattern::Hold(mode) => *mode,
            SensorPattern::Joint(_) => EgmMode::Joint,
            SensorPattern::Pose { .. } | SensorPattern::Circle { .. } => EgmMode::Pose,
            SensorPattern::Sine {
                axis: SineAxis::Joint(_),
                ..
            } => EgmMode::Joint,
            SensorPattern::Sine {
                axis: SineAxis::Cartesian(_),
                ..
            } => EgmMode::Pose,
            SensorPattern::PathCorr { .. } => EgmMode::PathCorr,
        }
    }

    /// Checks that every number is finite and in range.
    pub fn validate(&self) -> Result<(), PatternError> {
        let bad = |what: &str| Err(PatternError::BadValue(what.to_string()));
        match *self {
            SensorPattern::Hold(EgmMode::PathCorr) => bad("hold has no path-correction form"),
            SensorPattern::Hold(_) => Ok(()),
            SensorPattern::Joint(j) if j.iter().all(|v| v.is_finite()) => Ok(()),
            SensorPattern::Joint(_) => bad("joint values must be finite numbers"),
            SensorPattern::Pose { pos, euler }
                if pos.iter().chain(&euler).all(|v| v.is_finite()) =>
            {
                Ok(())
            }
            SensorPattern::Pose { .. } => bad("pose values must be finite numbers"),
            SensorPattern::Sine {
                axis,
                amplitude,
                frequency_hz,
            } => {
                let axis_ok = match axis {
                    SineAxis::Joint(i) => i < ROBOT_AXES,
                    SineAxis::Cartesian(i) => i < 3,
                };
                if !axis_ok {
                    bad("sine axis must be 1..6, x, y or z")
                } else if !amplitude.is_finite() || !valid_frequency(frequency_hz) {
                    bad("sine amplitude must be finite and frequency finite and >= 0")
                } else {
                    Ok(())
                }
            }
            SensorPattern::Circle {
                radius_mm,
                frequency_hz,
            } => {
                if radius_mm.is_finite() && radius_mm >= 0.0 && valid_frequency(frequency_hz) {
                    Ok(())
                } else {
                    bad("circle radius must be finite and >= 0, frequency finite and >= 0")
                }
            }
            SensorPattern::PathCorr {
                profile,
                y_mm,
                z_mm,
            } => {
                let profile_ok = match profile {
                    PathCorrProfile::Constant => true,
                    PathCorrProfile::Ramp { time_s } => time_s.is_finite() && time_s > 0.0,
                    PathCorrProfile::Sine { frequency_hz } => valid_frequency(frequency_hz),
                };
                if profile_ok && y_mm.is_finite() && z_mm.is_finite() {
                    Ok(())
                } else {
                    bad("path correction needs finite y, z, ramp time > 0 and frequency >= 0")
                }
            }
        }
    }

    /// The target `t` seconds after the session started.
    pub fn output(&self, origin: &Origin, t: f64) -> Result<PatternOutput, PatternError> {
        let joints = || {
            origin
                .joints
                .ok_or(PatternError::NoOrigin("feedBack.joints"))
        };
        let pose = || {
            origin
                .pose
                .ok_or(PatternError::NoOrigin("feedBack.cartesian"))
        };
        Ok(match *self {
            SensorPattern::Hold(EgmMode::Pose) => PatternOutput::Pose {
                pose: pose()?,
                speed: None,
            },
            SensorPattern::Hold(EgmMode::PathCorr) => PatternOutput::PathCorr { pos: [0.0; 3] },
            SensorPattern::Hold(EgmMode::Joint) => PatternOutput::Joint {
                joints: joints()?,
                speed: None,
            },
            SensorPattern::Joint(j) => PatternOutput::Joint {
                joints: j,
                speed: None,
            },
            SensorPattern::Pose { pos, euler } => PatternOutput::Pose {
                pose: Pose {
                    pos,
                    orient: quaternion_from_euler_zyx(euler),
                },
                speed: None,
            },
            SensorPattern::Sine {
                axis,
                amplitude,
                frequency_hz,
            } => {
                let w = TAU * frequency_hz;
                let offset = amplitude * (w * t).sin();
                let rate = amplitude * w * (w * t).cos();
                match axis {
                    SineAxis::Joint(i) => {
                        let mut target = joints()?;
                        let mut speed = [0.0; ROBOT_AXES];
                        if let (Some(j), Some(s)) = (target.get_mut(i), speed.get_mut(i)) {
                            *j += offset;
                            *s = rate;
                        }
                        PatternOutput::Joint {
                            joints: target,
                            speed: Some(speed),
                        }
                    }
                    SineAxis::Cartesian(i) => {
                        let mut target = pose()?;
                        let mut speed = [0.0; 6];
                        if let (Some(p), Some(s)) = (target.pos.get_mut(i), speed.get_mut(i)) {
                            *p += offset;
                            *s = rate;
                        }
                        PatternOutput::Pose {
                            pose: target,
                            speed: Some(speed),
                        }
                    }
                }
            }
            SensorPattern::Circle {
                radius_mm,
                frequency_hz,
            } => {
                let w = TAU * frequency_hz;
                let (s, c) = (w * t).sin_cos();
                let mut target = pose()?;
                let [x, y, z] = target.pos;
                target.pos = [x + radius_mm * (c - 1.0), y + radius_mm * s, z];
                PatternOutput::Pose {
                    pose: target,
                    speed: Some([-radius_mm * w * s, radius_mm * w * c, 0.0, 0.0, 0.0, 0.0]),
                }
            }
            SensorPattern::PathCorr {
                profile,
                y_mm,
                z_mm,
            } => {
                let scale = match profile {
                    PathCorrProfile::Constant => 1.0,
                    PathCorrProfile::Ramp { time_s } => (t / time_s).clamp(0.0, 1.0),
                    PathCorrProfile::Sine { frequency_hz } => (TAU * frequency_hz * t).sin(),
                };
                PatternOutput::PathCorr {
                    pos: [0.0, y_mm * scale, z_mm * scale],
                }
            }
        })
    }
}

fn valid_frequency(f: f64) -> bool {
    f.is_finite() && f >= 0.0
}

impl FromStr for SensorPattern {
    type Err = PatternError;

    /// Parses the text form described in the module docs.
    fn from_str(text: &str) -> Result<Self, PatternError> {
        let text = text.trim();
        let (name, args) = text.split_once(':').unwrap_or((text, ""));
        let pattern = match name.trim().to_ascii_lowercase().as_str() {
            "hold" => no_args(args, SensorPattern::Hold(EgmMode::Joint))?,
            "hold-pose" => no_args(args, SensorPattern::Hold(EgmMode::Pose))?,
            "joint" => {
                let v = numbers::<6>(args, "joint needs 6 values J1..J6 in degrees")?;
                SensorPattern::Joint(v)
            }
            "pose" => {
                let [x, y, z, rx, ry, rz] =
                    numbers::<6>(args, "pose needs 6 values X,Y,Z (mm),RX,RY,RZ (degrees)")?;
                SensorPattern::Pose {
                    pos: [x, y, z],
                    euler: [rx, ry, rz],
                }
            }
            "sine" => {
                let mut axis = SineAxis::Joint(0);
                let mut amplitude = DEFAULT_AMPLITUDE;
                let mut frequency_hz = DEFAULT_FREQUENCY;
                for (key, value) in pairs(args)? {
                    match key.as_str() {
                        "axis" => axis = parse_axis(&value)?,
                        "amplitude" => amplitude = number(&value, "amplitude")?,
                        "frequency" => frequency_hz = number(&value, "frequency")?,
                        _ => return Err(unknown_key("sine", &key)),
                    }
                }
                SensorPattern::Sine {
                    axis,
                    amplitude,
                    frequency_hz,
                }
            }
            "circle" => {
                let mut radius_mm = DEFAULT_RADIUS;
                let mut frequency_hz = DEFAULT_FREQUENCY;
                for (key, value) in pairs(args)? {
                    match key.as_str() {
                        "radius" => radius_mm = number(&value, "radius")?,
                        "frequency" => frequency_hz = number(&value, "frequency")?,
                        _ => return Err(unknown_key("circle", &key)),
                    }
                }
                SensorPattern::Circle {
                    radius_mm,
                    frequency_hz,
                }
            }
            "pathcorr" => {
                let mut kind = "constant".to_string();
                let (mut y_mm, mut z_mm) = (0.0, 0.0);
                let mut time_s = DEFAULT_RAMP_TIME;
                let mut frequency_hz = DEFAULT_PATHCORR_FREQUENCY;
                for (key, value) in pairs(args)? {
                    match key.as_str() {
                        "kind" => kind = value.to_ascii_lowercase(),
                        "y" => y_mm = number(&value, "y")?,
                        "z" => z_mm = number(&value, "z")?,
                        "time" => time_s = number(&value, "time")?,
                        "frequency" => frequency_hz = number(&value, "frequency")?,
                        _ => return Err(unknown_key("pathcorr", &key)),
                    }
                }
                let profile = parse_profile(&kind, time_s, frequency_hz)?;
                SensorPattern::PathCorr {
                    profile,
                    y_mm,
                    z_mm,
                }
            }
            other => return Err(PatternError::UnknownPattern(other.to_string())),
        };
        pattern.validate()?;
        Ok(pattern)
    }
}

/// `constant`, `ramp` or `sine` with its parameter.
pub fn parse_profile(
    kind: &str,
    time_s: f64,
    frequency_hz: f64,
) -> Result<PathCorrProfile, PatternError> {
    match kind {
        "constant" => Ok(PathCorrProfile::Constant),
        "ramp" => Ok(PathCorrProfile::Ramp { time_s }),
        "sine" => Ok(PathCorrProfile::Sine { frequency_hz }),
        other => Err(PatternError::BadValue(format!(
            "path-correction kind `{other}`; use constant, ramp or sine"
        ))),
    }
}

/// `1`..`6` (joint) or `x`, `y`, `z` (pose).
pub fn parse_axis(text: &str) -> Result<SineAxis, PatternError> {
    match text.trim().to_ascii_lowercase().as_str() {
        "x" => Ok(SineAxis::Cartesian(0)),
        "y" => Ok(SineAxis::Cartesian(1)),
        "z" => Ok(SineAxis::Cartesian(2)),
        n => match n.parse::<usize>() {
            Ok(i @ 1..=ROBOT_AXES) => Ok(SineAxis::Joint(i - 1)),
            _ => Err(PatternError::BadValue(format!(
                "axis `{text}`; use 1..6, x, y or z"
            ))),
        },
    }
}

fn no_args(args: &str, pattern: SensorPattern) -> Result<SensorPattern, PatternError> {
    if args.trim().is_empty() {
        Ok(pattern)
    } else {
        Err(PatternError::BadValue(format!(
            "`{args}`: this pattern takes no values"
        )))
    }
}

/// Exactly `N` comma-separated numbers.
pub fn numbers<const N: usize>(text: &str, what: &str) -> Result<[f64; N], PatternError> {
    let mut out = [0.0; N];
    let mut count = 0;
    for part in text.split(',') {
        let slot = out
            .get_mut(count)
            .ok_or_else(|| PatternError::BadValue(what.to_string()))?;
        *slot = number(part, what)?;
        count += 1;
    }
    if count == N {
        Ok(out)
    } else {
        Err(PatternError::BadValue(what.to_string()))
    }
}

fn number(text: &str, what: &str) -> Result<f64, PatternError> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(PatternError::BadValue(format!(
            "`{}` is not a finite number ({what})",
            text.trim()
        ))),
    }
}

fn pairs(args: &str) -> Result<Vec<(String, String)>, PatternError> {
    if args.trim().is_empty() {
        return Ok(Vec::new());
    }
    args.split(',')
        .map(|part| {
            part.split_once('=')
                .map(|(k, v)| (k.trim().to_ascii_lowercase(), v.trim().to_string()))
                .ok_or_else(|| PatternError::BadValue(format!("`{part}` is not key=value")))
        })
        .collect()
}

fn unknown_key(pattern: &str, key: &str) -> PatternError {
    PatternError::BadValue(format!("{pattern} has no parameter `{key}`"))
}
