//! The EGM vocabulary the interpreter and the EGM layer share: the arguments of the EGM instructions as RAPID passes them (optional arguments stay `None`; the registry applies the defaults), the modes, frame types, stop modes and convergence windows, and the RAPID values of the states.
//!
//! Plain data with no behaviour beyond reading RAPID values: the interpreter fills these
//! from RAPID arguments and hands them to its host (`interp::host::EgmHost`); the controller
//! passes them to `egm::registry`. Neither side needs the other to name them, so both may
//! use this module (`docs/architecture.md`, "Layers"). The numbers of the RAPID constants
//! are those of `stdlib/egm.sys` (`docs/egm.md`, "Identities and states").

use std::fmt;

pub mod event;

use crate::robot::{LoadData, Pose, ToolData, WobjData};
use crate::signals::{SignalId, SignalKind};

/// Which message the sensor sends, chosen by the EGM setup (`\Joint`, `\Pose`, `\PathCorr`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EgmMode {
    /// Position guidance in joint space: `EgmSensor.planned.joints`.
    Joint,
    /// Position guidance in Cartesian space: `EgmSensor.planned.cartesian`.
    Pose,
    /// Path correction: `EgmSensorPathCorr.pathCorr`.
    PathCorr,
}

impl std::fmt::Display for EgmMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            EgmMode::Joint => "joint",
            EgmMode::Pose => "pose",
            EgmMode::PathCorr => "path correction",
        })
    }
}

/// `egmframetype`: what a correction or sensor frame is relative to. The numbers are those of
/// rapidvc's `stdlib/egm.sys` (`EGM_FRAME_BASE` = 1 … `EGM_FRAME_JOINT` = 5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum EgmFrameType {
    /// `EGM_FRAME_BASE`: relative to the robot base frame.
    Base = 1,
    /// `EGM_FRAME_TOOL`: relative to tool0 (the flange) at the start of the EGM movement.
    Tool = 2,
    /// `EGM_FRAME_WOBJ`: relative to the active work object (`\WObj`).
    Wobj = 3,
    /// `EGM_FRAME_WORLD`: relative to the world frame.
    World = 4,
    /// `EGM_FRAME_JOINT`: joint values (joint mode only; not a pose frame).
    Joint = 5,
}

impl EgmFrameType {
    /// The RAPID value (`stdlib/egm.sys`).
    pub const fn value(self) -> u8 {
        self as u8
    }

    /// The frame type of a RAPID `egmframetype` value; `None` unless it is exactly 1…5.
    pub fn from_value(v: f64) -> Option<EgmFrameType> {
        const ALL: [EgmFrameType; 5] = [
            EgmFrameType::Base,
            EgmFrameType::Tool,
            EgmFrameType::Wobj,
            EgmFrameType::World,
            EgmFrameType::Joint,
        ];
        ALL.into_iter().find(|t| f64::from(t.value()) == v)
    }

    /// The RAPID constant's name, e.g. `EGM_FRAME_WORLD`.
    pub const fn rapid_name(self) -> &'static str {
        match self {
            EgmFrameType::Base => "EGM_FRAME_BASE",
            EgmFrameType::Tool => "EGM_FRAME_TOOL",
            EgmFrameType::Wobj => "EGM_FRAME_WOBJ",
            EgmFrameType::World => "EGM_FRAME_WORLD",
            EgmFrameType::Joint => "EGM_FRAME_JOINT",
        }
    }
}

impl fmt::Display for EgmFrameType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.rapid_name())
    }
}

/// An `egm_minmax` convergence window: converged when min ≤ ordered − actual ≤ max.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MinMax {
    /// Lower bound.
    pub min: f64,
    /// Upper bound.
    pub max: f64,
}

impl MinMax {
    /// The default joint window, ±0.5 degrees.
    pub const JOINT_DEFAULT: MinMax = MinMax {
        min: -0.5,
        max: 0.5,
    };

    /// True when `error` lies inside the window.
    pub fn contains(&self, error: f64) -> bool {
        error >= self.min && error <= self.max
    }
}

/// How an EGM run ends (`egmstopmode`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopMode {
    /// `EGM_STOP_HOLD`: stay at the end position.
    Hold,
    /// `EGM_STOP_RAMP_DOWN`: return to the start position within the ramp-out time.
    RampDown,
}

/// `egmstate`, with the numbers of `stdlib/egm.sys`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum EgmState {
    /// `EGM_STATE_DISCONNECTED` (1): no setup.
    Disconnected = 1,
    /// `EGM_STATE_CONNECTED` (2): set up, no EGM movement.
    Connected = 2,
    /// `EGM_STATE_RUNNING` (3): an EGM movement or stream is active.
    Running = 3,
}

impl EgmState {
    /// The RAPID value.
    pub fn value(self) -> f64 {
        f64::from(self as u8)
    }
}

/// `egmcorrstate` (RW7.15), with the numbers of `stdlib/egm.sys`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CorrState {
    /// `EGM_CORR_UNDEFINED` (0): not reserved.
    Undefined = 0,
    /// `EGM_CORR_ERROR` (1): the last EGM movement ended with an error.
    Error = 1,
    /// `EGM_CORR_STOPPED` (2): no EGM movement moves the robot.
    Stopped = 2,
    /// `EGM_CORR_RUNNING` (3): EGM moves the robot.
    Running = 3,
}

impl CorrState {
    /// The RAPID value.
    pub fn value(self) -> f64 {
        f64::from(self as u8)
    }
}

/// `\APTR` or `\LATR` (path correction).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TrackerKind {
    /// `\APTR`: at-point tracker (the sensor measures at the TCP).
    Aptr,
    /// `\LATR`: look-ahead tracker (the sensor measures ahead of the TCP).
    Latr,
}

/// `EGMSetupUC MecUnit, EGMid, ExtConfigName, UCDevice [\Joint|\Pose|\PathCorr]
/// [\APTR|\LATR] [\CommTimeout]`.
#[derive(Clone, Debug, PartialEq)]
pub struct SetupUc {
    /// `MecUnit` (e.g. `ROB_1`).
    pub mecunit: String,
    /// `ExtConfigName`: the External Motion Interface Data profile.
    pub profile: String,
    /// `UCDevice` (a trailing `:` is ignored).
    pub device: String,
    /// `\Joint`, `\Pose` or `\PathCorr`.
    pub mode: EgmMode,
    /// `\APTR` / `\LATR` (only with `\PathCorr`, where one is required).
    pub tracker: Option<TrackerKind>,
    /// `\CommTimeout`, seconds.
    pub comm_timeout: Option<f64>,
}

/// `EGMSetupAI`, `EGMSetupAO` or `EGMSetupGI` (by `kind`): `MecUnit, EGMid, ExtConfigName
/// [\Joint|\Pose|\PathCorr] [\APTR] [\<p>R1x] … [\<p>R6rz] [\<p>E1] … [\<p>E6]`.
#[derive(Clone, Debug, PartialEq)]
pub struct SetupSignals {
    /// `MecUnit`.
    pub mecunit: String,
    /// `ExtConfigName`.
    pub profile: String,
    /// `Ai`, `Ao` or `Gi` (which instruction).
    pub kind: SignalKind,
    /// `\Joint`, `\Pose` or `\PathCorr`.
    pub mode: EgmMode,
    /// `\APTR` (required with `\PathCorr`; `\LATR` does not exist for signals since RW 7.1).
    pub tracker: Option<TrackerKind>,
    /// `R1x, R2y, R3z, R4rx, R5ry, R6rz`.
    pub mapping: [Option<SignalId>; 6],
    /// `E1` … `E6`.
    pub ext: [Option<SignalId>; 6],
}

impl SetupSignals {
    /// The RAPID instruction name for `kind`.
    pub fn instruction(&self) -> &'static str {
        match self.kind {
            SignalKind::Ai => "EGMSetupAI",
            SignalKind::Gi => "EGMSetupGI",
            _ => "EGMSetupAO",
        }
    }
}

/// `EGMSetupLTAPP MecUnit, EGMid, ExtConfigName, Device, JointType [\APTR|\LATR]`.
#[derive(Clone, Debug, PartialEq)]
pub struct SetupLtapp {
    /// `MecUnit`.
    pub mecunit: String,
    /// `ExtConfigName`.
    pub profile: String,
    /// `Device`.
    pub device: String,
    /// `JointType`: the seam type number the sensor shall use.
    pub joint_type: f64,
    /// `\APTR` or `\LATR` (exactly one).
    pub tracker: TrackerKind,
}

/// The optional arguments EGMActJoint and EGMActPose share.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ActCommon {
    /// `\StreamStart` (RW7): start a position stream at once.
    pub stream_start: bool,
    /// `\Tool` (default tool0).
    pub tool: Option<ToolData>,
    /// `\WObj` (default wobj0).
    pub wobj: Option<WobjData>,
    /// `\TLoad` (default: the tool's load; `load0` also means the tool's load).
    pub tload: Option<LoadData>,
    /// `\DOToSensor` (RW7.7): a digital output sent as `RAPIDfromRobot.digVal`.
    pub do_to_sensor: Option<SignalId>,
    /// `\DataToSensor` given (RW7.7; not supported by rapidvc).
    pub data_to_sensor: bool,
    /// `\DIFromSensor` (RW7.7): a digital input set from `RAPIDtoRobot.digVal`.
    pub di_from_sensor: Option<SignalId>,
    /// `\DataFromSensor` given (RW7.7; not supported by rapidvc).
    pub data_from_sensor: bool,
    /// `\LpFilter`, Hz.
    pub lp_filter: Option<f64>,
    /// `\SampleRate`, ms.
    pub sample_rate: Option<f64>,
    /// `\MaxPosDeviation`, degrees.
    pub max_pos_deviation: Option<f64>,
    /// `\MaxSpeedDeviation`, degrees/s.
    pub max_speed_deviation: Option<f64>,
}

/// `EGMActJoint EGMid [\StreamStart] [\Tool] … [\J1] … [\J7] [\LpFilter] [\SampleRate]
/// [\MaxPosDeviation] [\MaxSpeedDeviation]`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ActJoint {
    /// The shared optional arguments.
    pub common: ActCommon,
    /// `\J1` … `\J7` convergence windows, degrees (`\J7` only on 7-axis robots).
    pub windows: [Option<MinMax>; 7],
}

/// `EGMActPose EGMid [\StreamStart] [\Tool] …, CorrFrame, CorrFrType, SensorFrame,
/// SensFrType [\x] … [\rz] [\LpFilter] [\SampleRate] [\MaxPosDeviation]
/// [\MaxSpeedDeviation]`.
#[derive(Clone, Debug, PartialEq)]
pub struct ActPose {
    /// The shared optional arguments.
    pub common: ActCommon,
    /// `CorrFrame`.
    pub corr_frame: Pose,
    /// `CorrFrType`.
    pub corr_type: EgmFrameType,
    /// `SensorFrame`.
    pub sensor_frame: Pose,
    /// `SensFrType`.
    pub sens_type: EgmFrameType,
    /// `\x \y \z \rx \ry \rz` windows (mm, degrees).
    pub windows: [Option<MinMax>; 6],
}

impl ActPose {
    /// Identity frames of type WORLD, no optional argument.
    pub fn world() -> ActPose {
        ActPose {
            common: ActCommon::default(),
            corr_frame: Pose::identity(),
            corr_type: EgmFrameType::World,
            sensor_frame: Pose::identity(),
            sens_type: EgmFrameType::World,
            windows: [None; 6],
        }
    }
}

/// `EGMActMove EGMid, SensorFrame [\SampleRate]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ActMove {
    /// `SensorFrame`: the sensor frame relative to the flange.
    pub sensor_frame: Pose,
    /// `\SampleRate`, ms (multiples of 24).
    pub sample_rate: Option<f64>,
}

/// The arguments EGMRunJoint and EGMRunPose share.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunArgs {
    /// `Mode`: how the movement ends.
    pub stop_mode: StopMode,
    /// `\NoWaitCond` (RW7): the program continues at once; finish with EGMWaitCond.
    pub no_wait_cond: bool,
    /// `\CondTime`, seconds.
    pub cond_time: Option<f64>,
    /// `\RampInTime`, seconds.
    pub ramp_in_time: Option<f64>,
    /// `\RampOutTime`, seconds.
    pub ramp_out_time: Option<f64>,
    /// `\PosCorrGain` (0 = pure velocity control).
    pub pos_corr_gain: Option<f64>,
}

impl RunArgs {
    /// `stop_mode` with every optional argument left out.
    pub fn new(stop_mode: StopMode) -> RunArgs {
        RunArgs {
            stop_mode,
            no_wait_cond: false,
            cond_time: None,
            ramp_in_time: None,
            ramp_out_time: None,
            pos_corr_gain: None,
        }
    }
}

/// A RAPID value an EGM argument does not allow (the controller reports it as event 90124,
/// "EGM argument value error").
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{instruction}: {argument} = {value} is not allowed; it must be {range}")]
pub struct ArgumentError {
    /// The instruction.
    pub instruction: &'static str,
    /// The argument, as written in RAPID (`Mode`).
    pub argument: &'static str,
    /// The value.
    pub value: f64,
    /// The allowed values, in words.
    pub range: &'static str,
}

impl ArgumentError {
    /// The event-log entry (90124, "EGM argument value error", this error's text as detail),
    /// as the controller reports it.
    pub fn event(&self) -> event::EgmEvent {
        event::EgmEvent::new(event::EventKind::ArgumentValue, self.to_string())
    }
}

impl StopMode {
    /// The stop mode of an `egmstopmode` value (`EGM_STOP_HOLD` = 1, `EGM_STOP_RAMP_DOWN` =
    /// 2 in `stdlib/egm.sys`), the argument `Mode` of `instruction`.
    pub fn from_value(instruction: &'static str, value: f64) -> Result<StopMode, ArgumentError> {
        if value == 1.0 {
            Ok(StopMode::Hold)
        } else if value == 2.0 {
            Ok(StopMode::RampDown)
        } else {
            Err(ArgumentError {
                instruction,
                argument: "Mode",
                value,
                range: "EGM_STOP_HOLD or EGM_STOP_RAMP_DOWN",
            })
        }
    }

    /// The RAPID value.
    pub fn value(self) -> f64 {
        match self {
            StopMode::Hold => 1.0,
            StopMode::RampDown => 2.0,
        }
    }
}

impl EgmFrameType {
    /// The frame type of an `egmframetype` value given as `argument` of `instruction`.
    pub fn from_argument(
        instruction: &'static str,
        argument: &'static str,
        value: f64,
    ) -> Result<EgmFrameType, ArgumentError> {
        EgmFrameType::from_value(value).ok_or(ArgumentError {
            instruction,
            argument,
            value,
            range: "an egmframetype (EGM_FRAME_BASE, EGM_FRAME_TOOL, EGM_FRAME_WOBJ, EGM_FRAME_WORLD, EGM_FRAME_JOINT)",
        })
    }
}
