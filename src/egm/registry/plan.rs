//! What the registry hands to the controller: the resolved setup of an identity (its data source), its activation, and the plans of one EGM run, stream or corrected movement with every default applied.

use std::net::SocketAddr;
use std::time::Duration;

use super::configuration::MotionProfile;
use crate::egm::geometry::{Convergence, PoseSetup, SignalSource};
use crate::egm::path_correction::SeamProfile;
use crate::egm::sensor::SensorPattern;
use crate::egm::servo::{MinMax, ServoParams, StopMode};
use crate::egm::types::{EgmMode, ROBOT_AXES};
use crate::robot::{LoadData, Pose, Robot, ToolData, WobjData};
use crate::signals::{SignalId, SignalKind};

use super::{EgmId, TrackerKind};

/// Where an identity's data come from, resolved at setup.
#[derive(Clone, Debug, PartialEq)]
pub enum SourceSpec {
    /// An external sensor over UdpUc.
    Udp {
        /// The device name as the program wrote it (without a trailing `:`).
        device: String,
        /// The sensor's address (Remote Address, Remote Port Number).
        remote: SocketAddr,
        /// Local Port Number (0: any free port).
        local_port: u16,
    },
    /// The in-process built-in sensor behind a UdpUc device name.
    Builtin {
        /// The device name.
        device: String,
        /// The sensor's pattern (the mode's default when the device gave none: `hold`,
        /// `hold-pose` — holding the start in the sensor frame — or a zero path correction).
        pattern: SensorPattern,
    },
    /// I/O signals (EGMSetupAI/AO/GI).
    Signals {
        /// `Ai`, `Ao` or `Gi`.
        kind: SignalKind,
        /// The signals.
        source: SignalSource,
    },
    /// A simulated LTAPP seam sensor (EGMSetupLTAPP; path correction only).
    Ltapp {
        /// The device name.
        device: String,
        /// `JointType`.
        joint_type: f64,
        /// The seam it reports.
        seam: SeamProfile,
    },
}

impl SourceSpec {
    /// The device name (`None` for signals).
    pub fn device(&self) -> Option<&str> {
        match self {
            SourceSpec::Udp { device, .. }
            | SourceSpec::Builtin { device, .. }
            | SourceSpec::Ltapp { device, .. } => Some(device),
            SourceSpec::Signals { .. } => None,
        }
    }

    /// True for a UdpUc device, external or built-in (what streams and RAPID data need).
    pub fn is_udpuc(&self) -> bool {
        matches!(self, SourceSpec::Udp { .. } | SourceSpec::Builtin { .. })
    }

    /// True when the sensor is outside rapidvc (the clock must run in real time or
    /// lockstep).
    pub fn is_external(&self) -> bool {
        matches!(self, SourceSpec::Udp { .. })
    }
}

/// The setup of an identity (EGMSetupUC/AI/AO/GI/LTAPP), resolved.
#[derive(Clone, Debug, PartialEq)]
pub struct Setup {
    /// The instruction that made it.
    pub instruction: &'static str,
    /// `MecUnit`.
    pub mecunit: String,
    /// The External Motion Interface Data profile.
    pub profile: MotionProfile,
    /// Guidance in joints, pose, or path correction.
    pub mode: EgmMode,
    /// `\APTR` / `\LATR` (path correction).
    pub tracker: Option<TrackerKind>,
    /// `\CommTimeout` (UdpUc; the default elsewhere, where it is not used).
    pub comm_timeout: Duration,
    /// The data source.
    pub source: SourceSpec,
}

/// Joint or pose specifics of an activation.
#[derive(Clone, Debug, PartialEq)]
pub enum ActivationKind {
    /// EGMActJoint.
    Joint {
        /// Convergence windows `\J1`…`\J6`, degrees.
        windows: [MinMax; ROBOT_AXES],
    },
    /// EGMActPose.
    Pose {
        /// The frames (with the tool and work object; offset and selection are set by
        /// EGMRunPose).
        frames: Box<PoseSetup>,
        /// Convergence windows `\x`…`\rz`.
        windows: Convergence,
    },
}

/// The activation of an identity (EGMActJoint/EGMActPose), resolved.
#[derive(Clone, Debug, PartialEq)]
pub struct Activation {
    /// The instruction that made it.
    pub instruction: &'static str,
    /// Joint or pose data.
    pub kind: ActivationKind,
    /// `\Tool`.
    pub tool: ToolData,
    /// `\WObj`.
    pub wobj: WobjData,
    /// `\TLoad` (`None`: the tool's load).
    pub tload: Option<LoadData>,
    /// `\DOToSensor`.
    pub do_to_sensor: Option<SignalId>,
    /// `\DIFromSensor`.
    pub di_from_sensor: Option<SignalId>,
    /// `\LpFilter`, Hz (`None`: the profile's bandwidth).
    pub lp_filter_hz: Option<f64>,
    /// `\SampleRate`.
    pub sample_period: Duration,
    /// `\MaxPosDeviation`, degrees.
    pub max_pos_deviation: f64,
    /// `\MaxSpeedDeviation`, degrees/s.
    pub max_speed_deviation: f64,
}

/// The activation of path correction (EGMActMove).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoveActivation {
    /// The sensor frame relative to the flange.
    pub sensor_frame: Pose,
    /// The correction sample period (a multiple of 24 ms).
    pub sample_period: Duration,
}

/// One EGMRunJoint/EGMRunPose, everything resolved: what [`crate::egm::EgmDriver::start`]
/// needs.
#[derive(Clone, Debug, PartialEq)]
pub struct RunPlan {
    /// The identity.
    pub id: EgmId,
    /// Its variable name.
    pub name: String,
    /// `EGMRunJoint` or `EGMRunPose`.
    pub instruction: &'static str,
    /// `Joint` or `Pose`.
    pub mode: EgmMode,
    /// The data source.
    pub source: SourceSpec,
    /// The motion profile.
    pub profile: MotionProfile,
    /// `\CommTimeout`.
    pub comm_timeout: Duration,
    /// `\SampleRate` of the activation.
    pub sample_period: Duration,
    /// `\Tool`.
    pub tool: ToolData,
    /// `\WObj`.
    pub wobj: WobjData,
    /// `\TLoad`.
    pub tload: Option<LoadData>,
    /// Pose mode: frames, `\Offset` and direction switches.
    pub pose: Option<PoseSetup>,
    /// Convergence windows (joints in degrees; pose: x, y, z mm then rx, ry, rz degrees).
    pub windows: [MinMax; ROBOT_AXES],
    /// `\J1`…`\J6` (joint mode) or `\x`…`\rz` (pose mode).
    pub selection: [bool; ROBOT_AXES],
    /// `Mode`.
    pub stop_mode: StopMode,
    /// `\NoWaitCond`.
    pub no_wait_cond: bool,
    /// `\CondTime`.
    pub cond_time: Duration,
    /// `\RampInTime`.
    pub ramp_in_time: Duration,
    /// `\RampOutTime`.
    pub ramp_out_time: Duration,
    /// `\PosCorrGain`.
    pub pos_corr_gain: f64,
    /// `\LpFilter`, Hz (≤ 0 or absent: the profile's bandwidth).
    pub lp_filter_hz: f64,
    /// `\MaxSpeedDeviation`, degrees/s.
    pub max_speed_deviation: f64,
    /// `\MaxPosDeviation`, degrees.
    pub max_pos_deviation: f64,
    /// `\DOToSensor`.
    pub do_to_sensor: Option<SignalId>,
    /// `\DIFromSensor`.
    pub di_from_sensor: Option<SignalId>,
    /// The identity was streaming: the controller must end that stream (and hand its
    /// socket over) before starting the run; the run's end ends the stream's RUNNING state
    /// too.
    pub stops_stream: bool,
}

impl RunPlan {
    /// True when at least one axis or direction is selected; with none "there is no
    /// movement and RAPID continues" (the driver then finishes at its first tick).
    pub fn moves(&self) -> bool {
        self.selection.iter().any(|s| *s)
    }

    /// The servo parameters of this run, stepped every `tick`, with `servo_delay` from
    /// commanded to measured position and the robot's axis ranges as hard limits.
    pub fn servo_params(
        &self,
        tick: Duration,
        servo_delay: Duration,
        robot: &Robot,
    ) -> ServoParams {
        let limits = robot.model().joint_limits;
        let mut axis_limits = [MinMax::JOINT_DEFAULT; ROBOT_AXES];
        for (slot, l) in axis_limits.iter_mut().zip(&limits) {
            *slot = MinMax {
                min: l.min,
                max: l.max,
            };
        }
        let pose = self.mode == EgmMode::Pose;
        ServoParams {
            period: tick,
            kp: self.profile.kp,
            pos_corr_gain: self.pos_corr_gain,
            lp_filter_hz: self.lp_filter_hz,
            default_lp_filter_hz: self.profile.filter_bandwidth,
            ramp_in_time: self.ramp_in_time,
            ramp_out_time: self.ramp_out_time,
            max_speed_deviation: self.max_speed_deviation,
            max_pos_deviation: self.max_pos_deviation,
            servo_delay,
            cond_time: self.cond_time,
            windows: self.windows,
            // Pose mode moves every joint (the IK honours the direction switches) and checks
            // convergence on the selected directions.
            selected: if pose {
                [self.moves(); ROBOT_AXES]
            } else {
                self.selection
            },
            convergence_axes: pose.then_some(self.selection),
            axis_limits: Some(axis_limits),
            axis_accel: Some(robot.model().max_accel),
            stop_mode: self.stop_mode,
        }
    }
}

/// One position stream (EGMStreamStart or `\StreamStart`).
#[derive(Clone, Debug, PartialEq)]
pub struct StreamPlan {
    /// The identity.
    pub id: EgmId,
    /// Its variable name.
    pub name: String,
    /// The setup's mode (`Joint` or `Pose`; only decides how replies would be read).
    pub mode: EgmMode,
    /// The device (UdpUc or built-in).
    pub source: SourceSpec,
    /// The sample period.
    pub sample_period: Duration,
    /// `\Tool` of the activation (tool0 without one): the TCP of the feedback.
    pub tool: ToolData,
    /// `\WObj` of the activation (wobj0 without one): the frame of the feedback.
    pub wobj: WobjData,
}

/// One corrected sequence of EGMMoveL/EGMMoveC (path correction).
#[derive(Clone, Debug, PartialEq)]
pub struct MovePlan {
    /// The identity.
    pub id: EgmId,
    /// Its variable name.
    pub name: String,
    /// `\APTR` or `\LATR`.
    pub tracker: TrackerKind,
    /// EGMActMove's sensor frame (relative to the flange).
    pub sensor_frame: Pose,
    /// EGMActMove's sample period.
    pub sample_period: Duration,
    /// The data source.
    pub source: SourceSpec,
    /// `\CommTimeout` (UdpUc).
    pub comm_timeout: Duration,
    /// The Level 2 profile.
    pub profile: MotionProfile,
}
