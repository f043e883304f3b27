//! Plain domain data exchanged over EGM: joints, poses, references and robot feedback (mm, degrees).

use crate::time::RobotTime;

/// Number of robot axes rapidvc's EGM layer handles (a 6-axis TCP robot).
pub const ROBOT_AXES: usize = 6;
/// Most additional (external) axes an EGM message carries.
pub const MAX_EXTERNAL_AXES: usize = 6;
/// Most `dnum` values in `EgmRAPIDdata` (ABB's `EGM_MAX_RAPID_DNUM`, presumably 40).
pub const MAX_RAPID_DNUM: usize = 40;

/// Robot joint values, degrees (or degrees per second for speeds), axis 1 first; the same
/// type as [`crate::robot::JointsDeg`].
pub type Joints = crate::robot::JointsDeg;

pub use crate::egm_args::EgmMode;

/// A Cartesian pose: position in mm and a unit quaternion `[w, x, y, z]` (w is the scalar).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Position x, y, z in mm.
    pub pos: [f64; 3],
    /// Orientation as a unit quaternion `[w, x, y, z]`.
    pub orient: [f64; 4],
}

impl Pose {
    /// The origin with no rotation.
    pub const IDENTITY: Pose = Pose {
        pos: [0.0; 3],
        orient: [1.0, 0.0, 0.0, 0.0],
    };
}

impl Default for Pose {
    fn default() -> Self {
        Pose::IDENTITY
    }
}

impl Pose {
    /// The same pose as the robot module's isometry (mm, normalised rotation).
    pub fn to_robot(&self) -> crate::robot::Pose {
        crate::robot::pose_from_pos_quat(self.pos, self.orient)
    }
}

impl From<&crate::robot::Pose> for Pose {
    fn from(p: &crate::robot::Pose) -> Self {
        let (pos, orient) = crate::robot::pose_to_pos_quat(p);
        Pose { pos, orient }
    }
}

/// A short list of additional-axis values (0 to [`MAX_EXTERNAL_AXES`]), without allocation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ExternalAxes {
    values: [f64; MAX_EXTERNAL_AXES],
    len: u8,
}

impl ExternalAxes {
    /// No additional axes.
    pub const NONE: ExternalAxes = ExternalAxes {
        values: [0.0; MAX_EXTERNAL_AXES],
        len: 0,
    };

    /// Takes up to [`MAX_EXTERNAL_AXES`] values; extra values are ignored.
    pub fn from_slice(values: &[f64]) -> Self {
        let mut out = ExternalAxes::NONE;
        for (slot, value) in out.values.iter_mut().zip(values) {
            *slot = *value;
            out.len += 1;
        }
        out
    }

    /// The values, in axis order.
    pub fn as_slice(&self) -> &[f64] {
        self.values.get(..usize::from(self.len)).unwrap_or(&[])
    }

    /// True when there are no additional axes.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// `EgmRAPIDdata`: one digital value and up to [`MAX_RAPID_DNUM`] numbers, without allocation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RapidData {
    /// `digVal`: the digital signal value, if sent.
    pub dig_val: Option<bool>,
    values: [f64; MAX_RAPID_DNUM],
    len: u8,
}

impl Default for RapidData {
    fn default() -> Self {
        RapidData {
            dig_val: None,
            values: [0.0; MAX_RAPID_DNUM],
            len: 0,
        }
    }
}

impl RapidData {
    /// Builds the data from a digital value and up to 40 numbers (extra values are ignored).
    pub fn new(dig_val: Option<bool>, dnum: &[f64]) -> Self {
        let mut out = RapidData {
            dig_val,
            ..RapidData::default()
        };
        for (slot, value) in out.values.iter_mut().zip(dnum) {
            *slot = *value;
            out.len += 1;
        }
        out
    }

    /// The `dnum` values.
    pub fn dnum(&self) -> &[f64] {
        self.values.get(..usize::from(self.len)).unwrap_or(&[])
    }
}

/// Header fields a sensor sent; logged for latency analysis, never required (clients differ).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SensorHeader {
    /// `header.seqno`, if present.
    pub seqno: Option<u32>,
    /// `header.tm`, if present (its meaning differs between clients).
    pub tm: Option<u32>,
    /// `header.mtype` as its raw number, if present.
    pub mtype: Option<i32>,
}

/// A joint-mode reference from `EgmSensor`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointReference {
    /// `planned.joints`, degrees (the first six values).
    pub joints: Joints,
    /// `speedRef.joints`, degrees/s; zero when the sensor sent none.
    pub speed: Joints,
    /// `planned.externalJoints` (degrees or mm).
    pub external: ExternalAxes,
    /// `speedRef.externalJoints`.
    pub external_speed: ExternalAxes,
}

/// A pose-mode reference from `EgmSensor`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PoseReference {
    /// `planned.cartesian`: position in mm and normalised orientation; parts the sensor left
    /// out keep the previous reference.
    pub pose: Pose,
    /// `speedRef.cartesians`: mm/s for x, y, z then degrees/s for rx, ry, rz; zero when absent.
    pub speed: [f64; 6],
    /// `planned.externalJoints` (degrees or mm).
    pub external: ExternalAxes,
    /// `speedRef.externalJoints`.
    pub external_speed: ExternalAxes,
}

/// A path correction from `EgmSensorPathCorr`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathCorrection {
    /// `pathCorr.pos`, mm in the sensor frame (only y and z are used by path correction).
    pub pos: [f64; 3],
    /// `pathCorr.age`, ms.
    pub age_ms: u32,
}

/// What the sensor asks for, by mode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    /// Joint-mode position guidance.
    Joint(JointReference),
    /// Pose-mode position guidance.
    Pose(PoseReference),
    /// Path correction.
    PathCorr(PathCorrection),
}

/// One accepted, validated sensor message.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorReference {
    /// When the datagram arrived (robot time).
    pub received_at: RobotTime,
    /// The sensor's header fields.
    pub header: SensorHeader,
    /// The reference itself.
    pub target: Target,
    /// `RAPIDtoRobot` (RobotWare 7.7), for `\DIFromSensor` and `\DataFromSensor`.
    pub rapid: Option<RapidData>,
}

/// `EgmMotorState`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MotorState {
    /// Motors on.
    On,
    /// Motors off.
    Off,
}

/// `EgmRapidCtrlExecState`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RapidExecState {
    /// The RAPID program is running.
    Running,
    /// The RAPID program is stopped.
    Stopped,
}

/// `EgmMCIState`: the EGM correction state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MciState {
    /// EGMRun is moving the robot.
    Running,
    /// No correction active (for example a pure position stream).
    Stopped,
    /// After a guidance or path-correction error.
    Error,
}

/// What the controller reports to the sensor each cycle; plain data filled by the motion core.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RobotFeedback {
    /// Measured joints, degrees.
    pub joints: Joints,
    /// Measured additional axes.
    pub external: ExternalAxes,
    /// Measured TCP pose (mm, quaternion) in the frame the EGM setup reports in.
    pub pose: Pose,
    /// When the axes were at `joints` (sent as `feedBack.time`).
    pub time: RobotTime,
    /// Planned (commanded) joints, degrees.
    pub planned_joints: Joints,
    /// Planned additional axes.
    pub planned_external: ExternalAxes,
    /// Planned TCP pose.
    pub planned_pose: Pose,
    /// When the axes will be at the planned position (sent as `planned.time`).
    pub planned_time: RobotTime,
    /// Drive state.
    pub motor_state: MotorState,
    /// Program state.
    pub exec_state: RapidExecState,
    /// EGM correction state.
    pub mci_state: MciState,
    /// Whether the active EGM instruction's convergence criteria are met right now.
    pub convergence_met: bool,
    /// `utilizationRate`, percent.
    pub utilization: f64,
    /// `moveIndex` (RobotWare 7.6), sent only when set.
    pub move_index: Option<u32>,
    /// `RAPIDfromRobot` (`\DOToSensor`, `\DataToSensor`), sent only when set.
    pub rapid_to_sensor: Option<RapidData>,
}

impl RobotFeedback {
    /// A robot standing still at `joints`/`pose`: planned equals measured, motors on, program
    /// running, EGM running, convergence not met, zero utilisation, time zero.
    pub fn standing(joints: Joints, pose: Pose) -> Self {
        RobotFeedback {
            joints,
            external: ExternalAxes::NONE,
            pose,
            time: RobotTime::ZERO,
            planned_joints: joints,
            planned_external: ExternalAxes::NONE,
            planned_pose: pose,
            planned_time: RobotTime::ZERO,
            motor_state: MotorState::On,
            exec_state: RapidExecState::Running,
            mci_state: MciState::Running,
            convergence_met: false,
            utilization: 0.0,
            move_index: None,
            rapid_to_sensor: None,
        }
    }
}
