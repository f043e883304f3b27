//! Conversion between the EGM protobuf messages and rapidvc's domain data (mm, degrees, `[w,x,y,z]`).
//!
//! Decoding rules (docs/egm.md, "Messages accepted"): the message type comes from the mode, never from the
//! bytes; NaN and infinity are rejected; a missing `required` leaf is rejected (as Google's
//! parser would); Euler angles (ZYX, degrees) win over the quaternion when both are sent; the
//! quaternion is normalised; joint vectors need at least 6 values (extras ignored); parts of a
//! pose the sensor leaves out keep the previous reference. `header.mtype` is only a
//! cross-check: a `CORRECTION`/`PATH_CORRECTION` that contradicts the mode, or a controller
//! `DATA`/`COMMAND` message, is rejected; a missing or undefined type is accepted.

use std::time::Duration;

use nalgebra::{Quaternion, UnitQuaternion};
use prost::Message;

use super::presence::{fields_at, has_all};
use super::proto::{
    EgmCartesian, EgmClock, EgmFeedBack, EgmHeader, EgmJoints, EgmMciState, EgmMotorState,
    EgmPlanned, EgmPose, EgmQuaternion, EgmRapidCtrlExecState, EgmRapidData, EgmRobot, EgmSensor,
    EgmSensorPathCorr, egm_header::MessageType, egm_mci_state::MciStateType,
    egm_motor_state::MotorStateType, egm_rapid_ctrl_exec_state::RapidCtrlExecStateType,
};
use super::types::{
    EgmMode, ExternalAxes, JointReference, Joints, MciState, MotorState, PathCorrection, Pose,
    PoseReference, ROBOT_AXES, RapidData, RapidExecState, RobotFeedback, SensorHeader,
    SensorReference, Target,
};
use crate::robot::units::{quat_from_euler_zyx_deg, quat_to_euler_zyx_deg, quat_to_wxyz};
use crate::time::RobotTime;

/// Sanity bound for angles (degrees) when no robot limits are configured.
pub const SANITY_ABS_DEGREES: f64 = 1.0e5;
/// Sanity bound for positions (mm) when no robot limits are configured: 1 km.
pub const SANITY_ABS_MM: f64 = 1.0e6;
/// Sanity bound for speeds (mm/s or degrees/s).
pub const SANITY_ABS_SPEED: f64 = 1.0e6;
/// Smallest quaternion norm accepted before normalising.
const MIN_QUATERNION_NORM: f64 = 1.0e-9;

/// Bounds a reference must respect to be accepted ("input out of bounds" otherwise).
///
/// The defaults are sanity bounds that reject garbage such as `1e300`; the controller narrows
/// them to the robot's axis limits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceLimits {
    /// Lower joint bounds, degrees.
    pub joint_min: Joints,
    /// Upper joint bounds, degrees.
    pub joint_max: Joints,
    /// Bound on |additional axis| values (degrees or mm).
    pub max_abs_external: f64,
    /// Bound on |x|, |y|, |z| of poses and path corrections, mm.
    pub max_abs_position_mm: f64,
    /// Bound on |speed reference| values, mm/s or degrees/s.
    pub max_abs_speed: f64,
}

impl Default for ReferenceLimits {
    fn default() -> Self {
        ReferenceLimits {
            joint_min: [-SANITY_ABS_DEGREES; ROBOT_AXES],
            joint_max: [SANITY_ABS_DEGREES; ROBOT_AXES],
            max_abs_external: SANITY_ABS_MM,
            max_abs_position_mm: SANITY_ABS_MM,
            max_abs_speed: SANITY_ABS_SPEED,
        }
    }
}

/// Why a decoded sensor message was not accepted as a reference.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ReferenceError {
    /// A value was NaN or infinite.
    #[error("`{field}` is not a finite number")]
    NotFinite {
        /// Field path, e.g. `planned.joints`.
        field: &'static str,
    },
    /// Fewer values than the robot has axes.
    #[error("`{field}` has {got} values; {need} are needed")]
    TooFewValues {
        /// Field path.
        field: &'static str,
        /// Values received.
        got: usize,
        /// Values needed.
        need: usize,
    },
    /// The part the mode needs is absent.
    #[error("no `{field}` in the message; {mode} mode needs it")]
    MissingTarget {
        /// Field path.
        field: &'static str,
        /// The configured mode.
        mode: EgmMode,
    },
    /// A proto2 `required` leaf is absent.
    #[error("`{field}` lacks a required value")]
    MissingRequired {
        /// Field path of the incomplete sub-message.
        field: &'static str,
    },
    /// The quaternion has (almost) zero length.
    #[error("`planned.cartesian.orient` has zero length")]
    ZeroQuaternion,
    /// A value is outside the configured bounds.
    #[error("`{field}` = {value} is outside [{min}, {max}]")]
    OutOfRange {
        /// Field path.
        field: &'static str,
        /// Offending value.
        value: f64,
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
    },
    /// `header.mtype` contradicts the mode.
    #[error("header.mtype {mtype} does not fit {mode} mode")]
    WrongMessageType {
        /// The raw `mtype`.
        mtype: i32,
        /// The configured mode.
        mode: EgmMode,
    },
}

/// Why a datagram produced no reference.
#[derive(Debug, thiserror::Error)]
pub enum DecodeError {
    /// The bytes are not a valid protobuf message of the mode's type.
    #[error("does not decode as {expected}: {source}")]
    Malformed {
        /// `EgmSensor` or `EgmSensorPathCorr`.
        expected: &'static str,
        /// prost's reason.
        source: prost::DecodeError,
    },
    /// The message decoded but its content was rejected.
    #[error(transparent)]
    Rejected(#[from] ReferenceError),
}

/// Decodes one sensor datagram as the message `mode` calls for and validates it.
///
/// `previous` supplies the pose parts a pose-mode message leaves out.
pub fn decode_reference(
    bytes: &[u8],
    mode: EgmMode,
    previous: &Pose,
    limits: &ReferenceLimits,
    received_at: RobotTime,
) -> Result<SensorReference, DecodeError> {
    match mode {
        EgmMode::Joint | EgmMode::Pose => {
            let msg = EgmSensor::decode(bytes).map_err(|source| DecodeError::Malformed {
                expected: "EgmSensor",
                source,
            })?;
            let header = sensor_header(msg.header.as_ref());
            check_mtype(header.mtype, mode)?;
            let target = if mode == EgmMode::Joint {
                Target::Joint(joint_reference(&msg, limits)?)
            } else {
                Target::Pose(pose_reference(&msg, bytes, previous, limits)?)
            };
            let rapid = msg.rapid_to_robot().map(rapid_data).transpose()?;
            Ok(SensorReference {
                received_at,
                header,
                target,
                rapid,
            })
        }
        EgmMode::PathCorr => {
            let msg =
                EgmSensorPathCorr::decode(bytes).map_err(|source| DecodeError::Malformed {
                    expected: "EgmSensorPathCorr",
                    source,
                })?;
            let header = sensor_header(msg.header.as_ref());
            check_mtype(header.mtype, mode)?;
            let target = Target::PathCorr(path_correction(&msg, bytes, limits)?);
            Ok(SensorReference {
                received_at,
                header,
                target,
                rapid: None,
            })
        }
    }
}

/// True when `bytes` is a protobuf message cut short: its top-level fields read well up to
/// the end of the datagram, where the last one needs more bytes than are left (a varint,
/// a fixed-size value or a length-delimited field that runs past the end). A message that
/// breaks the wire format anywhere else is merely malformed.
pub fn is_truncated(bytes: &[u8]) -> bool {
    let mut rest = bytes;
    while !rest.is_empty() {
        // A key cut in the middle is noise, not a cut message: the keys of the EGM
        // messages are one byte long.
        let Varint::Value(key, n) = varint(rest) else {
            return false;
        };
        rest = rest.get(n..).unwrap_or(&[]);
        if key >> 3 == 0 {
            return false;
        }
        let need = match key & 7 {
            0 => match varint(rest) {
                Varint::Value(_, n) => n,
                Varint::CutShort => return true,
                Varint::Invalid => return false,
            },
            1 => 8,
            2 => match varint(rest) {
                Varint::Value(len, n) => {
                    rest = rest.get(n..).unwrap_or(&[]);
                    match usize::try_from(len) {
                        Ok(len) => len,
                        Err(_) => return true,
                    }
                }
                Varint::CutShort => return true,
                Varint::Invalid => return false,
            },
            5 => 4,
            // Groups (3, 4) and the unused wire types 6 and 7: not a cut, a broken message.
            _ => return false,
        };
        match rest.get(need..) {
            Some(r) => rest = r,
            None => return true,
        }
    }
    false
}

/// A varint at the start of a buffer.
enum Varint {
    /// The value and its length in bytes.
    Value(u64, usize),
    /// The buffer ends inside it.
    CutShort,
    /// Longer than ten bytes.
    Invalid,
}

fn varint(bytes: &[u8]) -> Varint {
    let mut value = 0u64;
    for (i, b) in bytes.iter().enumerate().take(10) {
        value |= u64::from(b & 0x7f) << (7 * i);
        if b & 0x80 == 0 {
            return Varint::Value(value, i + 1);
        }
    }
    if bytes.len() < 10 {
        Varint::CutShort
    } else {
        Varint::Invalid
    }
}

fn sensor_header(header: Option<&EgmHeader>) -> SensorHeader {
    header
        .map(|h| SensorHeader {
            seqno: h.seqno,
            tm: h.tm,
            mtype: h.mtype,
        })
        .unwrap_or_default()
}

fn check_mtype(mtype: Option<i32>, mode: EgmMode) -> Result<(), ReferenceError> {
    let Some(raw) = mtype else { return Ok(()) };
    let expected = match mode {
        EgmMode::Joint | EgmMode::Pose => MessageType::MsgtypeCorrection,
        EgmMode::PathCorr => MessageType::MsgtypePathCorrection,
    };
    if raw == MessageType::MsgtypeUndefined as i32 || raw == expected as i32 {
        Ok(())
    } else {
        Err(ReferenceError::WrongMessageType { mtype: raw, mode })
    }
}

fn joint_reference(
    msg: &EgmSensor,
    limits: &ReferenceLimits,
) -> Result<JointReference, ReferenceError> {
    let planned_joints = msg.planned.as_ref().and_then(|p| p.joints.as_ref()).ok_or(
        ReferenceError::MissingTarget {
            field: "planned.joints",
            mode: EgmMode::Joint,
        },
    )?;
    let joints = six(&planned_joints.joints, "planned.joints")?;
    for ((value, min), max) in joints.iter().zip(&limits.joint_min).zip(&limits.joint_max) {
        in_range(*value, *min, *max, "planned.joints")?;
    }
    let speed_ref = msg.speed_ref.as_ref();
    let speed = match speed_ref.and_then(|s| s.joints.as_ref()) {
        Some(j) => six(&j.joints, "speedRef.joints")?,
        None => [0.0; ROBOT_AXES],
    };
    for v in &speed {
        in_range(
            *v,
            -limits.max_abs_speed,
            limits.max_abs_speed,
            "speedRef.joints",
        )?;
    }
    let external = external_axes(
        msg.planned
            .as_ref()
            .and_then(|p| p.external_joints.as_ref()),
        limits.max_abs_external,
        "planned.externalJoints",
    )?;
    let external_speed = external_axes(
        speed_ref.and_then(|s| s.external_joints.as_ref()),
        limits.max_abs_speed,
        "speedRef.externalJoints",
    )?;
    Ok(JointReference {
        joints,
        speed,
        external,
        external_speed,
    })
}

fn pose_reference(
    msg: &EgmSensor,
    bytes: &[u8],
    previous: &Pose,
    limits: &ReferenceLimits,
) -> Result<PoseReference, ReferenceError> {
    let missing = ReferenceError::MissingTarget {
        field: "planned.cartesian",
        mode: EgmMode::Pose,
    };
    let cart = msg
        .planned
        .as_ref()
        .and_then(|p| p.cartesian.as_ref())
        .ok_or(missing.clone())?;
    if cart.pos.is_none() && cart.orient.is_none() && cart.euler.is_none() {
        return Err(missing);
    }
    // planned = EgmSensor field 2, cartesian = EgmPlanned field 2.
    let mut pose = *previous;
    if let Some(pos) = &cart.pos {
        require(bytes, &[2, 2, 1], &[1, 2, 3], "planned.cartesian.pos")?;
        pose.pos = position(pos, limits, "planned.cartesian.pos")?;
    }
    if let Some(euler) = &cart.euler {
        require(bytes, &[2, 2, 3], &[1, 2, 3], "planned.cartesian.euler")?;
        let angles = [euler.x, euler.y, euler.z];
        finite(&angles, "planned.cartesian.euler")?;
        for a in &angles {
            in_range(
                *a,
                -SANITY_ABS_DEGREES,
                SANITY_ABS_DEGREES,
                "planned.cartesian.euler",
            )?;
        }
        pose.orient = quaternion_from_euler_zyx(angles);
    } else if let Some(q) = &cart.orient {
        require(bytes, &[2, 2, 2], &[1, 2, 3, 4], "planned.cartesian.orient")?;
        let raw = [q.u0, q.u1, q.u2, q.u3];
        finite(&raw, "planned.cartesian.orient")?;
        pose.orient = normalize_quaternion(raw).ok_or(ReferenceError::ZeroQuaternion)?;
    }
    let speed_ref = msg.speed_ref.as_ref();
    let speed = match speed_ref.and_then(|s| s.cartesians.as_ref()) {
        Some(s) => cartesian_speed(&s.value, limits.max_abs_speed)?,
        None => [0.0; 6],
    };
    let external = external_axes(
        msg.planned
            .as_ref()
            .and_then(|p| p.external_joints.as_ref()),
        limits.max_abs_external,
        "planned.externalJoints",
    )?;
    let external_speed = external_axes(
        speed_ref.and_then(|s| s.external_joints.as_ref()),
        limits.max_abs_speed,
        "speedRef.externalJoints",
    )?;
    Ok(PoseReference {
        pose,
        speed,
        external,
        external_speed,
    })
}

fn path_correction(
    msg: &EgmSensorPathCorr,
    bytes: &[u8],
    limits: &ReferenceLimits,
) -> Result<PathCorrection, ReferenceError> {
    let corr = msg
        .path_corr
        .as_ref()
        .ok_or(ReferenceError::MissingTarget {
            field: "pathCorr",
            mode: EgmMode::PathCorr,
        })?;
    // pathCorr = EgmSensorPathCorr field 2; pos = 1, age = 2; pos.x/y/z = 1..3.
    require(bytes, &[2], &[1, 2], "pathCorr")?;
    require(bytes, &[2, 1], &[1, 2, 3], "pathCorr.pos")?;
    Ok(PathCorrection {
        pos: position(&corr.pos, limits, "pathCorr.pos")?,
        age_ms: corr.age,
    })
}

fn rapid_data(data: &EgmRapidData) -> Result<RapidData, ReferenceError> {
    finite(&data.dnum, "RAPIDtoRobot.dnum")?;
    Ok(RapidData::new(data.dig_val, &data.dnum))
}

fn require(
    bytes: &[u8],
    path: &[u32],
    fields: &[u32],
    name: &'static str,
) -> Result<(), ReferenceError> {
    match fields_at(bytes, path) {
        Some(mask) if has_all(mask, fields) => Ok(()),
        _ => Err(ReferenceError::MissingRequired { field: name }),
    }
}

fn six(values: &[f64], field: &'static str) -> Result<Joints, ReferenceError> {
    let mut out = [0.0; ROBOT_AXES];
    if values.len() < ROBOT_AXES {
        return Err(ReferenceError::TooFewValues {
            field,
            got: values.len(),
            need: ROBOT_AXES,
        });
    }
    for (slot, v) in out.iter_mut().zip(values) {
        *slot = *v;
    }
    finite(&out, field)?;
    Ok(out)
}

/// Cartesian speed: 6 values (mm/s ×3, degrees/s ×3); 3 values are read as a linear speed
/// with no rotation (ABBRobotEGM documents a 3-value form); other counts are rejected.
fn cartesian_speed(values: &[f64], bound: f64) -> Result<[f64; 6], ReferenceError> {
    const FIELD: &str = "speedRef.cartesians";
    if values.len() != 3 && values.len() < 6 {
        return Err(ReferenceError::TooFewValues {
            field: FIELD,
            got: values.len(),
            need: 6,
        });
    }
    let mut out = [0.0; 6];
    for (slot, v) in out.iter_mut().zip(values) {
        *slot = *v;
    }
    finite(&out, FIELD)?;
    for v in &out {
        in_range(*v, -bound, bound, FIELD)?;
    }
    Ok(out)
}

fn external_axes(
    joints: Option<&EgmJoints>,
    bound: f64,
    field: &'static str,
) -> Result<ExternalAxes, ReferenceError> {
    let Some(j) = joints else {
        return Ok(ExternalAxes::NONE);
    };
    let axes = ExternalAxes::from_slice(&j.joints);
    finite(axes.as_slice(), field)?;
    for v in axes.as_slice() {
        in_range(*v, -bound, bound, field)?;
    }
    Ok(axes)
}

fn position(
    pos: &EgmCartesian,
    limits: &ReferenceLimits,
    field: &'static str,
) -> Result<[f64; 3], ReferenceError> {
    let p = [pos.x, pos.y, pos.z];
    finite(&p, field)?;
    for v in &p {
        in_range(
            *v,
            -limits.max_abs_position_mm,
            limits.max_abs_position_mm,
            field,
        )?;
    }
    Ok(p)
}

fn finite(values: &[f64], field: &'static str) -> Result<(), ReferenceError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(ReferenceError::NotFinite { field })
    }
}

fn in_range(value: f64, min: f64, max: f64, field: &'static str) -> Result<(), ReferenceError> {
    if value >= min && value <= max {
        Ok(())
    } else {
        Err(ReferenceError::OutOfRange {
            field,
            value,
            min,
            max,
        })
    }
}

/// Normalises `[w, x, y, z]`; `None` for non-finite or (almost) zero-length input.
pub fn normalize_quaternion(q: [f64; 4]) -> Option<[f64; 4]> {
    let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    if !norm.is_finite() || norm < MIN_QUATERNION_NORM {
        return None;
    }
    let [w, x, y, z] = q;
    Some([w / norm, x / norm, y / norm, z / norm])
}

/// Quaternion `[w, x, y, z]` of the ZYX Euler angles `[x, y, z]` in degrees:
/// R = Rz(z)·Ry(y)·Rx(x), as RAPID's `OrientZYX` and libegm use.
pub fn quaternion_from_euler_zyx(deg: [f64; 3]) -> [f64; 4] {
    let [x, y, z] = deg;
    quat_to_wxyz(&quat_from_euler_zyx_deg(x, y, z))
}

/// ZYX Euler angles `[x, y, z]` in degrees of a quaternion `[w, x, y, z]` (inverse of
/// [`quaternion_from_euler_zyx`]; y in [-90, 90]).
pub fn euler_zyx_from_quaternion(q: [f64; 4]) -> [f64; 3] {
    let [w, i, j, k] = q;
    quat_to_euler_zyx_deg(&UnitQuaternion::from_quaternion(Quaternion::new(
        w, i, j, k,
    )))
}

/// Options for building `EgmRobot`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EncodeOptions {
    /// Also fill `euler` in feedback and planned poses (consistent with `orient`). Off by
    /// default: no tested client needs it and whether a real controller fills it is unknown.
    pub send_euler: bool,
}

/// The first non-finite value in the feedback, named by its field, if any.
pub fn feedback_non_finite(fb: &RobotFeedback) -> Option<&'static str> {
    let checks: [(&'static str, &[f64]); 9] = [
        ("feedBack.joints", &fb.joints),
        ("feedBack.externalJoints", fb.external.as_slice()),
        ("feedBack.cartesian.pos", &fb.pose.pos),
        ("feedBack.cartesian.orient", &fb.pose.orient),
        ("planned.joints", &fb.planned_joints),
        ("planned.externalJoints", fb.planned_external.as_slice()),
        ("planned.cartesian.pos", &fb.planned_pose.pos),
        ("planned.cartesian.orient", &fb.planned_pose.orient),
        ("utilizationRate", std::slice::from_ref(&fb.utilization)),
    ];
    if let Some((name, _)) = checks
        .iter()
        .find(|(_, values)| !values.iter().all(|v| v.is_finite()))
    {
        return Some(name);
    }
    match &fb.rapid_to_sensor {
        Some(data) if !data.dnum().iter().all(|v| v.is_finite()) => Some("RAPIDfromRobot.dnum"),
        _ => None,
    }
}

/// Fills `msg` in place (reusing its buffers) with everything the strictest client needs:
/// header (seqno, tm, `DATA`), feedback and planned joints + pose + clock, motor, MCI and
/// RAPID states, `mciConvergenceMet` (always) and `utilizationRate`. Never fills field 9.
pub fn fill_robot(
    msg: &mut EgmRobot,
    seqno: u32,
    tm: u32,
    fb: &RobotFeedback,
    opts: &EncodeOptions,
) {
    msg.header = Some(EgmHeader {
        seqno: Some(seqno),
        tm: Some(tm),
        mtype: Some(MessageType::MsgtypeData as i32),
    });
    let feed = msg.feed_back.get_or_insert_with(EgmFeedBack::default);
    fill_joints(&mut feed.joints, &fb.joints);
    fill_external(&mut feed.external_joints, &fb.external);
    fill_pose(&mut feed.cartesian, &fb.pose, opts);
    feed.time = Some(clock(fb.time));
    feed.time_stamp = None;
    let planned = msg.planned.get_or_insert_with(EgmPlanned::default);
    fill_joints(&mut planned.joints, &fb.planned_joints);
    fill_external(&mut planned.external_joints, &fb.planned_external);
    fill_pose(&mut planned.cartesian, &fb.planned_pose, opts);
    planned.time = Some(clock(fb.planned_time));
    planned.time_stamp = None;
    msg.motor_state = Some(EgmMotorState {
        state: match fb.motor_state {
            MotorState::On => MotorStateType::MotorsOn,
            MotorState::Off => MotorStateType::MotorsOff,
        } as i32,
    });
    msg.mci_state = Some(EgmMciState {
        state: match fb.mci_state {
            MciState::Running => MciStateType::MciRunning,
            MciState::Stopped => MciStateType::MciStopped,
            MciState::Error => MciStateType::MciError,
        } as i32,
    });
    msg.rapid_exec_state = Some(EgmRapidCtrlExecState {
        state: match fb.exec_state {
            RapidExecState::Running => RapidCtrlExecStateType::RapidRunning,
            RapidExecState::Stopped => RapidCtrlExecStateType::RapidStopped,
        } as i32,
    });
    msg.mci_convergence_met = Some(fb.convergence_met);
    msg.utilization_rate = Some(fb.utilization);
    msg.test_signals = None;
    msg.measured_force = None;
    msg.move_index = fb.move_index;
    msg.collision_info = None;
    msg.torque_ref = None;
    match &fb.rapid_to_sensor {
        Some(data) => {
            let out = msg
                .rapi_dfrom_robot
                .get_or_insert_with(EgmRapidData::default);
            out.dig_val = data.dig_val;
            out.dnum.clear();
            out.dnum.extend_from_slice(data.dnum());
        }
        None => msg.rapi_dfrom_robot = None,
    }
}

fn fill_joints(slot: &mut Option<EgmJoints>, values: &[f64]) {
    let joints = slot.get_or_insert_with(EgmJoints::default);
    joints.joints.clear();
    joints.joints.extend_from_slice(values);
}

fn fill_external(slot: &mut Option<EgmJoints>, axes: &ExternalAxes) {
    if axes.is_empty() {
        *slot = None;
    } else {
        fill_joints(slot, axes.as_slice());
    }
}

fn fill_pose(slot: &mut Option<EgmPose>, pose: &Pose, opts: &EncodeOptions) {
    let [x, y, z] = pose.pos;
    let [u0, u1, u2, u3] = pose.orient;
    let out = slot.get_or_insert_with(EgmPose::default);
    out.pos = Some(EgmCartesian { x, y, z });
    out.orient = Some(EgmQuaternion { u0, u1, u2, u3 });
    out.euler = opts.send_euler.then(|| {
        let [x, y, z] = euler_zyx_from_quaternion(pose.orient);
        super::proto::EgmEuler { x, y, z }
    });
}

/// `EgmClock` of a robot time (the conversion is [`RobotTime::egm_clock`]).
pub fn clock(t: RobotTime) -> EgmClock {
    let (sec, usec) = t.egm_clock();
    EgmClock { sec, usec }
}

/// The time an `EgmClock` stands for, since the clock's epoch (saturating).
pub fn clock_to_duration(c: &EgmClock) -> Duration {
    crate::time::duration_from_egm_clock(c.sec, c.usec)
}

/// `header.tm` of a controller message (the conversion is [`RobotTime::wire_ms`]).
pub fn header_tm(now: RobotTime) -> u32 {
    now.wire_ms()
}

#[cfg(test)]
mod tests;
