//! The arguments of the EGM setup, activation and movement instructions as the interpreter passes them: optional arguments stay `None` here, defaults are applied by the registry.

use crate::egm::geometry::EgmFrameType;
use crate::egm::servo::{MinMax, StopMode};
use crate::egm::types::EgmMode;
use crate::robot::{LoadData, Pose, ToolData, WobjData};
use crate::signals::{SignalId, SignalKind};

use super::EgmError;

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

/// The `egmstopmode` of a RAPID value (`EGM_STOP_HOLD` = 1, `EGM_STOP_RAMP_DOWN` = 2 in
/// `stdlib/egm.sys`).
pub fn stop_mode_from_value(instruction: &'static str, value: f64) -> Result<StopMode, EgmError> {
    if value == 1.0 {
        Ok(StopMode::Hold)
    } else if value == 2.0 {
        Ok(StopMode::RampDown)
    } else {
        Err(EgmError::Argument {
            instruction,
            argument: "Mode",
            value,
            range: "EGM_STOP_HOLD or EGM_STOP_RAMP_DOWN",
        })
    }
}

/// The RAPID value of a stop mode.
pub fn stop_mode_value(mode: StopMode) -> f64 {
    match mode {
        StopMode::Hold => 1.0,
        StopMode::RampDown => 2.0,
    }
}

/// The `egmframetype` of a RAPID value (`EGM_FRAME_BASE` = 1 … `EGM_FRAME_JOINT` = 5).
pub fn frame_type_from_value(
    instruction: &'static str,
    argument: &'static str,
    value: f64,
) -> Result<EgmFrameType, EgmError> {
    EgmFrameType::from_value(value).ok_or(EgmError::Argument {
        instruction,
        argument,
        value,
        range: "an egmframetype (EGM_FRAME_BASE, EGM_FRAME_TOOL, EGM_FRAME_WOBJ, EGM_FRAME_WORLD, EGM_FRAME_JOINT)",
    })
}
