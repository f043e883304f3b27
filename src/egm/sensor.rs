//! The built-in EGM sensor, sans-IO: decodes `EgmRobot`, answers with the pattern's target, keeps statistics.
//!
//! Used in-process for `builtin` devices and over UDP by `rapidvc sensor`. It behaves like the
//! public clients: it replies once per received message, to the sender, with `header.seqno`
//! counting from 0 per controller session, `tm` = its own clock in ms and `mtype`
//! `CORRECTION` (or `PATH_CORRECTION`). A controller session starts when the robot's seqno is
//! 0 (or with the first message seen); the pattern's origin is that message's feedback and
//! its time origin is the arrival time.

use std::time::Duration;

use prost::Message;

use super::convert::clock_to_duration;
use super::latency::LatencyHistogram;
use super::proto::{
    EgmCartesian, EgmCartesianSpeed, EgmHeader, EgmJoints, EgmPathCorr, EgmPlanned, EgmPose,
    EgmQuaternion, EgmRobot, EgmSensor, EgmSensorPathCorr, EgmSpeedRef, egm_header::MessageType,
    egm_mci_state::MciStateType, egm_motor_state::MotorStateType,
    egm_rapid_ctrl_exec_state::RapidCtrlExecStateType,
};
use super::types::{EgmMode, Joints, MciState, MotorState, Pose, ROBOT_AXES, RapidExecState};

mod pattern;

pub use pattern::{
    Origin, PathCorrProfile, PatternError, PatternOutput, SensorPattern, SineAxis, parse_axis,
    parse_profile,
};

/// Built-in sensor configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorConfig {
    /// What to ask for.
    pub pattern: SensorPattern,
    /// Send the pattern's analytic speed as `speedRef` (moving patterns only).
    pub speed_feedforward: bool,
}

impl SensorConfig {
    /// `pattern` with speed feed-forward on.
    pub fn new(pattern: SensorPattern) -> Self {
        SensorConfig {
            pattern,
            speed_feedforward: true,
        }
    }
}

/// Why the sensor did not reply to a message.
#[derive(Debug, thiserror::Error)]
pub enum SensorError {
    /// The bytes are not an `EgmRobot`.
    #[error("not an EgmRobot: {0}")]
    Decode(#[from] prost::DecodeError),
    /// The pattern cannot be computed (bad configuration or missing feedback).
    #[error(transparent)]
    Pattern(#[from] PatternError),
}

/// What the sensor learned from one `EgmRobot` (for printing and tests).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RobotSnapshot {
    /// `header.seqno`.
    pub seqno: Option<u32>,
    /// `header.tm`, ms.
    pub tm: Option<u32>,
    /// `feedBack.joints` (first six), degrees.
    pub joints: Option<Joints>,
    /// `feedBack.cartesian` (pos + orient).
    pub pose: Option<Pose>,
    /// `feedBack.time`.
    pub feedback_time: Option<Duration>,
    /// `planned.joints` (first six).
    pub planned_joints: Option<Joints>,
    /// `motorState`.
    pub motor_state: Option<MotorState>,
    /// `rapidExecState`.
    pub exec_state: Option<RapidExecState>,
    /// `mciState`.
    pub mci_state: Option<MciState>,
    /// `mciConvergenceMet`.
    pub convergence_met: Option<bool>,
    /// `utilizationRate`, percent.
    pub utilization: Option<f64>,
}

impl RobotSnapshot {
    /// Extracts the fields rapidvc's tools look at.
    pub fn from_robot(robot: &EgmRobot) -> Self {
        let header = robot.header.as_ref();
        let feedback = robot.feedback();
        RobotSnapshot {
            seqno: header.and_then(|h| h.seqno),
            tm: header.and_then(|h| h.tm),
            joints: feedback.and_then(|f| f.joints.as_ref()).and_then(first_six),
            pose: feedback
                .and_then(|f| f.cartesian.as_ref())
                .and_then(pose_of),
            feedback_time: feedback
                .and_then(|f| f.time.as_ref())
                .map(clock_to_duration),
            planned_joints: robot
                .planned
                .as_ref()
                .and_then(|p| p.joints.as_ref())
                .and_then(first_six),
            motor_state: robot
                .motor_state
                .and_then(|m| match MotorStateType::try_from(m.state) {
                    Ok(MotorStateType::MotorsOn) => Some(MotorState::On),
                    Ok(MotorStateType::MotorsOff) => Some(MotorState::Off),
                    _ => None,
                }),
            exec_state: robot.rapid_exec_state.and_then(
                |r| match RapidCtrlExecStateType::try_from(r.state) {
                    Ok(RapidCtrlExecStateType::RapidRunning) => Some(RapidExecState::Running),
                    Ok(RapidCtrlExecStateType::RapidStopped) => Some(RapidExecState::Stopped),
                    _ => None,
                },
            ),
            mci_state: robot
                .mci_state
                .and_then(|m| match MciStateType::try_from(m.state) {
                    Ok(MciStateType::MciRunning) => Some(MciState::Running),
                    Ok(MciStateType::MciStopped) => Some(MciState::Stopped),
                    Ok(MciStateType::MciError) => Some(MciState::Error),
                    _ => None,
                }),
            convergence_met: robot.mci_convergence_met,
            utilization: robot.utilization_rate,
        }
    }
}

fn first_six(j: &EgmJoints) -> Option<Joints> {
    let mut out = [0.0; ROBOT_AXES];
    if j.joints.len() < ROBOT_AXES {
        return None;
    }
    for (slot, v) in out.iter_mut().zip(&j.joints) {
        *slot = *v;
    }
    Some(out)
}

fn pose_of(p: &EgmPose) -> Option<Pose> {
    let pos = p.pos.as_ref()?;
    let q = p.orient.as_ref()?;
    Some(Pose {
        pos: [pos.x, pos.y, pos.z],
        orient: [q.u0, q.u1, q.u2, q.u3],
    })
}

/// The mandatory items of docs/egm.md, "Messages sent", that `robot` lacks (empty when complete).
/// This is what the strictest client (libegm) checks before it replies.
pub fn missing_mandatory(robot: &EgmRobot) -> Vec<&'static str> {
    let mut missing = Vec::new();
    let mut need = |ok: bool, name: &'static str| {
        if !ok {
            missing.push(name);
        }
    };
    let header = robot.header.as_ref();
    need(header.and_then(|h| h.seqno).is_some(), "header.seqno");
    need(header.and_then(|h| h.tm).is_some(), "header.tm");
    need(
        header.and_then(|h| h.mtype) == Some(MessageType::MsgtypeData as i32),
        "header.mtype = DATA",
    );
    let feedback = robot.feedback();
    let six = |j: Option<&EgmJoints>| j.is_some_and(|j| j.joints.len() == ROBOT_AXES);
    let full_pose = |p: Option<&EgmPose>| p.is_some_and(|p| p.pos.is_some() && p.orient.is_some());
    need(
        six(feedback.and_then(|f| f.joints.as_ref())),
        "feedBack.joints (6)",
    );
    need(
        full_pose(feedback.and_then(|f| f.cartesian.as_ref())),
        "feedBack.cartesian (pos + orient)",
    );
    need(feedback.and_then(|f| f.time).is_some(), "feedBack.time");
    let planned = robot.planned.as_ref();
    need(
        six(planned.and_then(|p| p.joints.as_ref())),
        "planned.joints (6)",
    );
    need(
        full_pose(planned.and_then(|p| p.cartesian.as_ref())),
        "planned.cartesian (pos + orient)",
    );
    need(planned.and_then(|p| p.time).is_some(), "planned.time");
    need(robot.motor_state.is_some(), "motorState");
    need(robot.mci_state.is_some(), "mciState");
    need(robot.rapid_exec_state.is_some(), "rapidExecState");
    need(robot.mci_convergence_met.is_some(), "mciConvergenceMet");
    need(robot.utilization_rate.is_some(), "utilizationRate");
    need(robot.measured_force.is_none(), "no measuredForce (field 9)");
    missing
}

/// What the sensor counted.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SensorStats {
    /// Datagrams handed to the sensor.
    pub received: u64,
    /// Replies produced.
    pub replied: u64,
    /// Datagrams that were not an `EgmRobot`.
    pub decode_errors: u64,
    /// `EgmRobot`s lacking a mandatory item (see [`missing_mandatory`]).
    pub incomplete: u64,
    /// Controller sessions seen (seqno 0).
    pub sessions: u64,
    /// Non-consecutive seqno within a session.
    pub seqno_gaps: u64,
    /// Time between consecutive `EgmRobot` arrivals within a session.
    pub interval: LatencyHistogram,
    /// Time from arrival to the reply being handed to the socket (recorded by the I/O shell).
    pub turnaround: LatencyHistogram,
}

/// The built-in sensor.
#[derive(Debug)]
pub struct BuiltinSensor {
    config: SensorConfig,
    pose_origin: Option<Pose>,
    origin: Option<Origin>,
    session_start: Duration,
    seqno: u32,
    last_arrival: Option<Duration>,
    last_robot_seqno: Option<u32>,
    last: Option<RobotSnapshot>,
    last_missing: Vec<&'static str>,
    stats: SensorStats,
}

impl BuiltinSensor {
    /// A sensor for a validated configuration.
    pub fn new(config: SensorConfig) -> Result<Self, PatternError> {
        config.pattern.validate()?;
        Ok(BuiltinSensor {
            config,
            pose_origin: None,
            origin: None,
            session_start: Duration::ZERO,
            seqno: 0,
            last_arrival: None,
            last_robot_seqno: None,
            last: None,
            last_missing: Vec::new(),
            stats: SensorStats::default(),
        })
    }

    /// Fixes the pose origin of every following session to `pose` instead of the robot's
    /// `feedBack.cartesian` (`None`: back to the feedback). The in-process sensor of a
    /// pose-mode run uses this with the TCP in the sensor frame at the start, because
    /// feedback is reported in the correction frame while the sensor's poses are read in the
    /// sensor frame: `hold-pose`, `sine` and `circle` then start exactly where the robot is
    /// even when the two frames differ.
    pub fn set_pose_origin(&mut self, pose: Option<Pose>) {
        self.pose_origin = pose;
    }

    /// The mode the sensor talks in (the controller's setup must match).
    pub fn mode(&self) -> EgmMode {
        self.config.pattern.mode()
    }

    /// The configuration.
    pub fn config(&self) -> &SensorConfig {
        &self.config
    }

    /// Counters.
    pub fn stats(&self) -> &SensorStats {
        &self.stats
    }

    /// Records the I/O shell's arrival-to-send time of one reply.
    pub fn record_turnaround(&mut self, d: Duration) {
        self.stats.turnaround.record(d);
    }

    /// The last robot message seen.
    pub fn last_robot(&self) -> Option<&RobotSnapshot> {
        self.last.as_ref()
    }

    /// Mandatory items the last robot message lacked.
    pub fn last_missing(&self) -> &[&'static str] {
        &self.last_missing
    }

    /// The origin of the current session, once a message arrived.
    pub fn origin(&self) -> Option<&Origin> {
        self.origin.as_ref()
    }

    /// The pattern's output at `now` (after the first message).
    pub fn target(&self, now: Duration) -> Option<Result<PatternOutput, PatternError>> {
        let origin = self.origin.as_ref()?;
        let t = now.saturating_sub(self.session_start).as_secs_f64();
        Some(self.config.pattern.output(origin, t))
    }

    /// Decodes one datagram from the controller and returns the reply to send back.
    pub fn handle_datagram(&mut self, now: Duration, bytes: &[u8]) -> Result<Vec<u8>, SensorError> {
        self.stats.received += 1;
        let robot = match EgmRobot::decode(bytes) {
            Ok(robot) => robot,
            Err(e) => {
                self.stats.decode_errors += 1;
                return Err(e.into());
            }
        };
        self.respond_counted(now, &robot)
    }

    /// Answers an already decoded `EgmRobot`.
    pub fn respond(&mut self, now: Duration, robot: &EgmRobot) -> Result<Vec<u8>, SensorError> {
        self.stats.received += 1;
        self.respond_counted(now, robot)
    }

    fn respond_counted(&mut self, now: Duration, robot: &EgmRobot) -> Result<Vec<u8>, SensorError> {
        let snap = RobotSnapshot::from_robot(robot);
        self.last_missing = missing_mandatory(robot);
        if !self.last_missing.is_empty() {
            self.stats.incomplete += 1;
        }
        let new_session = snap.seqno == Some(0) || self.origin.is_none();
        if new_session {
            self.stats.sessions += 1;
            self.session_start = now;
            self.seqno = 0;
            self.origin = Some(Origin {
                joints: snap.joints.or(snap.planned_joints),
                pose: self.pose_origin.or(snap.pose),
            });
        } else {
            if let Some(last) = self.last_arrival {
                self.stats.interval.record(now.saturating_sub(last));
            }
            if let (Some(prev), Some(cur)) = (self.last_robot_seqno, snap.seqno)
                && cur != prev.wrapping_add(1)
            {
                self.stats.seqno_gaps += 1;
            }
        }
        self.last_arrival = Some(now);
        self.last_robot_seqno = snap.seqno;
        self.last = Some(snap);
        let output = match self.target(now) {
            Some(result) => result?,
            None => return Err(PatternError::NoOrigin("feedback").into()),
        };
        let bytes = self.encode(now, &output);
        self.seqno = self.seqno.wrapping_add(1);
        self.stats.replied += 1;
        Ok(bytes)
    }

    fn encode(&self, now: Duration, output: &PatternOutput) -> Vec<u8> {
        let header = |mtype: MessageType| {
            Some(EgmHeader {
                seqno: Some(self.seqno),
                tm: Some(crate::time::wire_ms(now)),
                mtype: Some(mtype as i32),
            })
        };
        let ff = self.config.speed_feedforward;
        match *output {
            PatternOutput::Joint { joints, speed } => EgmSensor {
                header: header(MessageType::MsgtypeCorrection),
                planned: Some(EgmPlanned {
                    joints: Some(EgmJoints {
                        joints: joints.to_vec(),
                    }),
                    ..EgmPlanned::default()
                }),
                speed_ref: speed.filter(|_| ff).map(|s| EgmSpeedRef {
                    joints: Some(EgmJoints { joints: s.to_vec() }),
                    ..EgmSpeedRef::default()
                }),
                ..EgmSensor::default()
            }
            .encode_to_vec(),
            PatternOutput::Pose { pose, speed } => {
                let [x, y, z] = pose.pos;
                let [u0, u1, u2, u3] = pose.orient;
                EgmSensor {
                    header: header(MessageType::MsgtypeCorrection),
                    planned: Some(EgmPlanned {
                        cartesian: Some(EgmPose {
                            pos: Some(EgmCartesian { x, y, z }),
                            orient: Some(EgmQuaternion { u0, u1, u2, u3 }),
                            euler: None,
                        }),
                        ..EgmPlanned::default()
                    }),
                    speed_ref: speed.filter(|_| ff).map(|s| EgmSpeedRef {
                        cartesians: Some(EgmCartesianSpeed { value: s.to_vec() }),
                        ..EgmSpeedRef::default()
                    }),
                    ..EgmSensor::default()
                }
                .encode_to_vec()
            }
            PatternOutput::PathCorr { pos } => {
                let [x, y, z] = pos;
                EgmSensorPathCorr {
                    header: header(MessageType::MsgtypePathCorrection),
                    path_corr: Some(EgmPathCorr {
                        pos: EgmCartesian { x, y, z },
                        age: 1,
                    }),
                }
                .encode_to_vec()
            }
        }
    }
}

#[cfg(test)]
mod tests;
