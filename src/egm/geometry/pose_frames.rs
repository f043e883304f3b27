//! Correction and sensor frames, the sensor-pose → TCP → joints pipeline of `EGMRunPose`, and the Cartesian feedback frames.

use nalgebra::{Translation3, UnitQuaternion, Vector3};

use super::convergence::pose_error;
use super::speed_refs::{SpeedRef, joint_speed_ref};
use super::{DIRECTIONS, EgmFrameType, GuidanceError};
use crate::robot::units::{pose_is_finite, quat_from_euler_zyx_deg, quat_to_euler_zyx_deg};
use crate::robot::{JointsDeg, Pose, Robot, ToolData, WobjData, flange_target};

/// The frame a frame type refers to, in world coordinates (see the module docs of
/// `egm::geometry`): WORLD → identity, BASE → the robot base, WOBJ → user frame · object frame
/// of `wobj` (for a robot-held work object: `flange_at_start` · that, frozen like TOOL), TOOL →
/// `flange_at_start`, the tool0 pose when the EGM movement started.
///
/// Errors: [`GuidanceError::JointFrameInPoseMode`] for `EGM_FRAME_JOINT`;
/// [`GuidanceError::NotFinite`] when the resulting frame is not finite.
pub fn base_of(
    frame_type: EgmFrameType,
    robot: &Robot,
    flange_at_start: &Pose,
    wobj: &WobjData,
) -> Result<Pose, GuidanceError> {
    let base = match frame_type {
        EgmFrameType::World => Pose::identity(),
        EgmFrameType::Base => *robot.base(),
        EgmFrameType::Tool => *flange_at_start,
        EgmFrameType::Wobj if wobj.robhold => flange_at_start * wobj.object_frame(),
        EgmFrameType::Wobj => wobj.object_frame(),
        EgmFrameType::Joint => return Err(GuidanceError::JointFrameInPoseMode { which: "the" }),
    };
    finite(base, "frame")
}

/// The static data of one pose-mode EGM movement: `EGMActPose`'s tool, work object, frames,
/// and `EGMRunPose`'s `\Offset` and direction switches.
#[derive(Clone, Debug, PartialEq)]
pub struct PoseSetup {
    /// `\Tool` (default tool0).
    pub tool: ToolData,
    /// `\WObj` (default wobj0).
    pub wobj: WobjData,
    /// `CorrFrame`.
    pub corr_frame: Pose,
    /// `CorrFrType`.
    pub corr_type: EgmFrameType,
    /// `SensorFrame`.
    pub sensor_frame: Pose,
    /// `SensFrType`.
    pub sens_type: EgmFrameType,
    /// `\Offset` of `EGMRunPose` (`None`: no offset).
    pub offset: Option<Pose>,
    /// Direction switches `\x \y \z \rx \ry \rz` of `EGMRunPose`, in that order.
    pub selection: [bool; DIRECTIONS],
}

impl PoseSetup {
    /// `tool` with wobj0, identity correction and sensor frames of type WORLD, no offset, all
    /// six directions selected: the sensor pose is the TCP target in world.
    pub fn world(tool: ToolData) -> PoseSetup {
        PoseSetup {
            tool,
            wobj: WobjData::wobj0(),
            corr_frame: Pose::identity(),
            corr_type: EgmFrameType::World,
            sensor_frame: Pose::identity(),
            sens_type: EgmFrameType::World,
            offset: None,
            selection: [true; DIRECTIONS],
        }
    }
}

/// Which frame `feedBack.cartesian` / `planned.cartesian` are reported in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FeedbackMode {
    /// Pose-mode guidance: the TCP of `\Tool` relative to the correction frame `F_c`.
    Pose,
    /// Joint-mode guidance: the TCP of `\Tool` relative to `\WObj`.
    Joint,
    /// Position streaming: the TCP of `\Tool` relative to `\WObj`.
    Stream,
}

/// Pose-mode guidance for one EGM movement: the frames frozen at its start and every
/// per-cycle computation on them. Build it when `EGMRunPose` starts.
#[derive(Clone, Debug)]
pub struct PoseGuidance {
    robot: Robot,
    tool: ToolData,
    /// wobj0, for [`flange_target`] of a TCP target already in world.
    world: WobjData,
    /// uframe · oframe of `\WObj` (fixed work object).
    object: Pose,
    object_inv: Pose,
    f_s: Pose,
    f_c: Pose,
    f_c_inv: Pose,
    offset: Option<Pose>,
    selection: [bool; DIRECTIONS],
    start_joints: JointsDeg,
    start_tcp_world: Pose,
    start_in_corr: Pose,
    start_euler_corr: [f64; 3],
    start_in_sensor: Pose,
}

impl PoseGuidance {
    /// Computes `F_s` and `F_c` once, with the TOOL frame type taken at `start_joints` (the
    /// fine point the movement starts in).
    ///
    /// Errors: non-finite frames, offset or start joints ([`GuidanceError::NotFinite`]); start
    /// joints outside the axis limits ([`GuidanceError::Kinematics`]); `EGM_FRAME_JOINT`;
    /// a stationary tool or a work object moved by a mechanical unit
    /// ([`GuidanceError::Unsupported`]); a robot-held work object with a robot-held tool
    /// ([`GuidanceError::InconsistentFrames`]).
    pub fn new(
        robot: &Robot,
        setup: &PoseSetup,
        start_joints: &JointsDeg,
    ) -> Result<PoseGuidance, GuidanceError> {
        if !start_joints.iter().all(|v| v.is_finite()) {
            return Err(GuidanceError::NotFinite {
                what: "start position",
            });
        }
        robot.check_limits(start_joints)?;
        if !setup.tool.robhold {
            return Err(GuidanceError::Unsupported(
                "EGM pose guidance with a stationary tool (\\Tool with robhold FALSE)",
            ));
        }
        if setup.wobj.robhold {
            return Err(GuidanceError::InconsistentFrames);
        }
        if !setup.wobj.ufprog {
            return Err(GuidanceError::Unsupported(
                "EGM with a work object moved by a mechanical unit (ufprog FALSE)",
            ));
        }
        let tframe = finite(setup.tool.tframe, "tool frame")?;
        let object = finite(setup.wobj.object_frame(), "work object")?;
        let corr_frame = finite(setup.corr_frame, "correction frame")?;
        let sensor_frame = finite(setup.sensor_frame, "sensor frame")?;
        let offset = match setup.offset {
            Some(o) => Some(finite(o, "\\Offset")?),
            None => None,
        };
        if setup.corr_type == EgmFrameType::Joint {
            return Err(GuidanceError::JointFrameInPoseMode {
                which: "correction",
            });
        }
        if setup.sens_type == EgmFrameType::Joint {
            return Err(GuidanceError::JointFrameInPoseMode { which: "sensor" });
        }
        let flange_start = robot.try_fk(start_joints)?;
        let f_s = base_of(setup.sens_type, robot, &flange_start, &setup.wobj)? * sensor_frame;
        let f_c = base_of(setup.corr_type, robot, &flange_start, &setup.wobj)? * corr_frame;
        let f_c_inv = f_c.inverse();
        let start_tcp_world = flange_start * tframe;
        let start_in_corr = f_c_inv * start_tcp_world;
        Ok(PoseGuidance {
            robot: robot.clone(),
            tool: setup.tool,
            world: WobjData::wobj0(),
            object,
            object_inv: object.inverse(),
            f_s,
            f_c,
            f_c_inv,
            offset,
            selection: setup.selection,
            start_joints: *start_joints,
            start_tcp_world,
            start_in_corr,
            start_euler_corr: quat_to_euler_zyx_deg(&start_in_corr.rotation),
            start_in_sensor: f_s.inverse() * start_tcp_world,
        })
    }

    /// The robot.
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// The sensor frame `F_s` in world.
    pub fn sensor_frame(&self) -> &Pose {
        &self.f_s
    }

    /// The correction frame `F_c` in world.
    pub fn correction_frame(&self) -> &Pose {
        &self.f_c
    }

    /// The object frame (user frame · object frame) of `\WObj` in world.
    pub fn work_object_frame(&self) -> &Pose {
        &self.object
    }

    /// The direction switches (x, y, z, rx, ry, rz).
    pub fn selection(&self) -> &[bool; DIRECTIONS] {
        &self.selection
    }

    /// The joints the movement started at.
    pub fn start_joints(&self) -> &JointsDeg {
        &self.start_joints
    }

    /// The TCP in world at the start.
    pub fn start_tcp_world(&self) -> &Pose {
        &self.start_tcp_world
    }

    /// The TCP in `F_c` at the start (the value of every unselected direction).
    pub fn start_in_corr(&self) -> &Pose {
        &self.start_in_corr
    }

    /// The TCP in `F_s` at the start: the sensor pose that keeps the robot where it is, and
    /// the value of every component a signal source does not map.
    pub fn start_sensor_pose(&self) -> &Pose {
        &self.start_in_sensor
    }

    /// The sensor's target before offset and selection: `F_s · S`, in world.
    pub fn sensor_target_world(&self, sensor_pose: &Pose) -> Result<Pose, GuidanceError> {
        let s = finite(*sensor_pose, "sensor pose")?;
        Ok(self.f_s * s)
    }

    /// The ordered TCP in `F_c`: `F_c⁻¹ · F_s · S`, then `\Offset` added in `F_c`, then every
    /// unselected direction replaced by its start value.
    pub fn ordered_in_corr(&self, sensor_pose: &Pose) -> Result<Pose, GuidanceError> {
        let target = self.f_c_inv * self.sensor_target_world(sensor_pose)?;
        let target = match &self.offset {
            Some(o) => apply_offset(&target, o),
            None => target,
        };
        Ok(self.select(&target))
    }

    /// The ordered TCP in world: `F_c ·` [`PoseGuidance::ordered_in_corr`]. This is the
    /// "ordered" pose of the convergence check.
    pub fn target_tcp_world(&self, sensor_pose: &Pose) -> Result<Pose, GuidanceError> {
        Ok(self.f_c * self.ordered_in_corr(sensor_pose)?)
    }

    /// The joint reference for a sensor pose: [`PoseGuidance::target_tcp_world`], then
    /// [`PoseGuidance::joints_for_tcp`]. `current` should be the joints commanded last (the
    /// servo's position), so consecutive references stay on one configuration branch.
    pub fn joint_target(
        &self,
        sensor_pose: &Pose,
        current: &JointsDeg,
    ) -> Result<JointsDeg, GuidanceError> {
        let tcp = self.target_tcp_world(sensor_pose)?;
        self.joints_for_tcp(&tcp, current)
    }

    /// The joints that put the TCP at `tcp_world`, closest to `current` (IK nearest, one small
    /// allocation inside rs-opw), supervised: [`crate::robot::KinError::OutsideReach`],
    /// [`crate::robot::KinError::JointOutOfRange`] when every solution needs an axis beyond
    /// its limit, [`crate::robot::KinError::Singularity`] when the solution is close to a
    /// singularity (default thresholds). Only the target is checked: the servo moves towards
    /// it in joint space.
    pub fn joints_for_tcp(
        &self,
        tcp_world: &Pose,
        current: &JointsDeg,
    ) -> Result<JointsDeg, GuidanceError> {
        let tcp = finite(*tcp_world, "TCP target")?;
        if !current.iter().all(|v| v.is_finite()) {
            return Err(GuidanceError::NotFinite {
                what: "current position",
            });
        }
        let flange = flange_target(&tcp, &self.tool, &self.world, &Pose::identity());
        let q = self.robot.ik_nearest(&flange, current)?;
        self.robot.check_limits(&q)?;
        self.robot.check_singularity(&q)?;
        Ok(q)
    }

    /// The TCP of `\Tool` in world at joints `q`.
    pub fn tcp_world(&self, q: &JointsDeg) -> Result<Pose, GuidanceError> {
        Ok(self.robot.try_fk(q)? * self.tool.tframe)
    }

    /// The pose-mode convergence errors "ordered minus actual" in `F_c` (see
    /// [`pose_error`]) between the ordered TCP (world) and the TCP at `actual`.
    pub fn convergence_errors(
        &self,
        ordered_world: &Pose,
        actual: &JointsDeg,
    ) -> Result<[f64; DIRECTIONS], GuidanceError> {
        let actual_tcp = self.tcp_world(actual)?;
        pose_error(&self.f_c, ordered_world, &actual_tcp)
    }

    /// `feedBack.cartesian` at joints `q`: position (mm) and quaternion `[w, x, y, z]` (w ≥ 0)
    /// of the TCP of `\Tool`, relative to `F_c` in [`FeedbackMode::Pose`] and relative to
    /// `\WObj` in [`FeedbackMode::Joint`] and [`FeedbackMode::Stream`].
    pub fn feedback_cartesian(
        &self,
        q: &JointsDeg,
        mode: FeedbackMode,
    ) -> Result<([f64; 3], [f64; 4]), GuidanceError> {
        let tcp = self.tcp_world(q)?;
        let rel = match mode {
            FeedbackMode::Pose => self.f_c_inv * tcp,
            FeedbackMode::Joint | FeedbackMode::Stream => self.object_inv * tcp,
        };
        Ok(pos_quat(&rel))
    }

    /// The feed-forward joint speeds (deg/s) for a Cartesian speed reference
    /// (`EgmSensor.speedRef.cartesians`: mm/s along, then deg/s about, the axes of `F_c`) at
    /// joints `q`; unselected directions get zero speed. See [`SpeedRef`].
    pub fn joint_speed_ref(
        &self,
        q: &JointsDeg,
        cartesian: &[f64; DIRECTIONS],
    ) -> Result<SpeedRef, GuidanceError> {
        let mut v = *cartesian;
        for (c, sel) in v.iter_mut().zip(&self.selection) {
            if !sel {
                *c = 0.0;
            }
        }
        joint_speed_ref(&self.robot, q, &self.tool.tframe, &self.f_c.rotation, &v)
    }

    /// Replace every unselected direction of `target` (in `F_c`) by its start value.
    fn select(&self, target: &Pose) -> Pose {
        let [sx, sy, sz, srx, sry, srz] = self.selection;
        let t = target.translation.vector;
        let s = self.start_in_corr.translation.vector;
        let pick = |sel: bool, a: f64, b: f64| if sel { a } else { b };
        let pos = Vector3::new(pick(sx, t.x, s.x), pick(sy, t.y, s.y), pick(sz, t.z, s.z));
        let rot = match (srx, sry, srz) {
            (true, true, true) => target.rotation,
            (false, false, false) => self.start_in_corr.rotation,
            _ => {
                let [tx, ty, tz] = quat_to_euler_zyx_deg(&target.rotation);
                let [ax, ay, az] = self.start_euler_corr;
                quat_from_euler_zyx_deg(pick(srx, tx, ax), pick(sry, ty, ay), pick(srz, tz, az))
            }
        };
        Pose::from_parts(Translation3::from(pos), rot)
    }
}

/// `feedBack.cartesian` for a setup without correction frame (joint mode, streaming): the TCP
/// of `tool` at `q` relative to `wobj` (any tool/work-object combination, as `CRobT`), with a
/// quaternion `[w, x, y, z]` with w ≥ 0.
pub fn feedback_in_wobj(
    robot: &Robot,
    q: &JointsDeg,
    tool: &ToolData,
    wobj: &WobjData,
) -> Result<([f64; 3], [f64; 4]), GuidanceError> {
    let p = finite(robot.tcp_pose(q, tool, wobj), "feedback pose")?;
    Ok(pos_quat(&p))
}

/// `\Offset` on a target in `F_c`: translation added along the `F_c` axes, rotation applied
/// about the `F_c` axes around the TCP point.
fn apply_offset(target: &Pose, offset: &Pose) -> Pose {
    Pose::from_parts(
        Translation3::from(target.translation.vector + offset.translation.vector),
        offset.rotation * target.rotation,
    )
}

/// Position and quaternion `[w, x, y, z]` with w ≥ 0 (q and −q are the same rotation).
fn pos_quat(p: &Pose) -> ([f64; 3], [f64; 4]) {
    let t = p.translation.vector;
    let q: &UnitQuaternion<f64> = &p.rotation;
    let s = if q.w < 0.0 { -1.0 } else { 1.0 };
    ([t.x, t.y, t.z], [s * q.w, s * q.i, s * q.j, s * q.k])
}

/// `p` when finite, else [`GuidanceError::NotFinite`] naming `what`.
fn finite(p: Pose, what: &'static str) -> Result<Pose, GuidanceError> {
    if pose_is_finite(&p) {
        Ok(p)
    } else {
        Err(GuidanceError::NotFinite { what })
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::panic)]

    use super::*;
    use crate::robot::units::pose_from_pos_quat;
    use crate::robot::{KinError, SingularityKind};

    const START: JointsDeg = [10.0, 5.0, 10.0, 20.0, 45.0, -30.0];

    fn robot() -> Robot {
        Robot::default()
    }

    fn tool() -> ToolData {
        ToolData {
            tframe: pose_from_pos_quat([10.0, 0.0, 200.0], [0.9238795, 0.0, 0.3826834, 0.0]),
            ..ToolData::tool0()
        }
    }

    fn close(a: &Pose, b: &Pose, tol: f64) -> bool {
        (a.translation.vector - b.translation.vector).norm() < tol
            && a.rotation.angle_to(&b.rotation) < tol
    }

    #[test]
    fn base_of_every_type() {
        let r = robot().with_base(pose_from_pos_quat([0.0, 0.0, 100.0], [1.0, 0.0, 0.0, 0.0]));
        let flange = r.fk(&START);
        let wobj = WobjData {
            uframe: pose_from_pos_quat([500.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]),
            oframe: pose_from_pos_quat([0.0, 10.0, 0.0], [1.0, 0.0, 0.0, 0.0]),
            ..WobjData::wobj0()
        };
        let id = Pose::identity();
        assert!(close(
            &base_of(EgmFrameType::World, &r, &flange, &wobj).unwrap(),
            &id,
            1e-12
        ));
        assert!(close(
            &base_of(EgmFrameType::Base, &r, &flange, &wobj).unwrap(),
            r.base(),
            1e-12
        ));
        assert!(close(
            &base_of(EgmFrameType::Tool, &r, &flange, &wobj).unwrap(),
            &flange,
            1e-12
        ));
        assert!(close(
            &base_of(EgmFrameType::Wobj, &r, &flange, &wobj).unwrap(),
            &wobj.object_frame(),
            1e-12
        ));
        let held = WobjData {
            robhold: true,
            ..wobj.clone()
        };
        assert!(close(
            &base_of(EgmFrameType::Wobj, &r, &flange, &held).unwrap(),
            &(flange * wobj.object_frame()),
            1e-9
        ));
        assert!(matches!(
            base_of(EgmFrameType::Joint, &r, &flange, &wobj),
            Err(GuidanceError::JointFrameInPoseMode { .. })
        ));
        let nan = crate::robot::units::nan_pose();
        assert!(matches!(
            base_of(EgmFrameType::Tool, &r, &nan, &wobj),
            Err(GuidanceError::NotFinite { .. })
        ));
    }

    #[test]
    fn start_sensor_pose_keeps_the_robot_still() {
        let setup = PoseSetup {
            corr_frame: pose_from_pos_quat([100.0, 200.0, 0.0], [0.0, 0.0, 0.0, 1.0]),
            corr_type: EgmFrameType::Base,
            sensor_frame: pose_from_pos_quat([1.0, 2.0, 3.0], [0.5, 0.5, 0.5, 0.5]),
            sens_type: EgmFrameType::Tool,
            ..PoseSetup::world(tool())
        };
        let g = PoseGuidance::new(&robot(), &setup, &START).unwrap();
        let s = *g.start_sensor_pose();
        assert!(close(
            &g.target_tcp_world(&s).unwrap(),
            g.start_tcp_world(),
            1e-9
        ));
        let q = g.joint_target(&s, &START).unwrap();
        for (a, b) in q.iter().zip(&START) {
            assert!((a - b).abs() < 1e-6, "{q:?}");
        }
        let e = g
            .convergence_errors(&g.target_tcp_world(&s).unwrap(), &q)
            .unwrap();
        assert!(e.iter().all(|v| v.abs() < 1e-6), "{e:?}");
    }

    #[test]
    fn offset_is_added_in_the_correction_frame() {
        // F_c rotated 90° about z: its x axis is world y.
        let offset = pose_from_pos_quat([10.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]);
        let setup = PoseSetup {
            corr_frame: pose_from_pos_quat([0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 1.0]),
            offset: Some(offset),
            ..PoseSetup::world(tool())
        };
        let g = PoseGuidance::new(&robot(), &setup, &START).unwrap();
        let s = pose_from_pos_quat([1000.0, 100.0, 1200.0], [0.0, 0.0, 1.0, 0.0]);
        let t = g.target_tcp_world(&s).unwrap();
        let d = t.translation.vector - s.translation.vector;
        assert!((d - Vector3::new(0.0, 10.0, 0.0)).norm() < 1e-9, "{d}");
        assert!(t.rotation.angle_to(&s.rotation) < 1e-12);
        // A pure rotation offset turns the tool about the F_c axes around the TCP point.
        let rot = pose_from_pos_quat([0.0; 3], [0.9961947, 0.0871557, 0.0, 0.0]); // 10° about x
        let g = PoseGuidance::new(
            &robot(),
            &PoseSetup {
                offset: Some(rot),
                ..setup
            },
            &START,
        )
        .unwrap();
        let t = g.target_tcp_world(&s).unwrap();
        assert!((t.translation.vector - s.translation.vector).norm() < 1e-9);
        // About F_c's x axis = world y.
        let expected =
            UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 10f64.to_radians()) * s.rotation;
        assert!(t.rotation.angle_to(&expected) < 1e-6);
    }

    #[test]
    fn selection_keeps_unselected_directions() {
        let setup = PoseSetup {
            selection: [false, false, true, false, false, false],
            ..PoseSetup::world(tool())
        };
        let g = PoseGuidance::new(&robot(), &setup, &START).unwrap();
        let start = *g.start_tcp_world();
        let s = pose_from_pos_quat([0.0, 0.0, 777.0], [0.0, 1.0, 0.0, 0.0]);
        let t = g.target_tcp_world(&s).unwrap();
        let (sp, tp) = (start.translation.vector, t.translation.vector);
        assert!((tp.x - sp.x).abs() < 1e-9 && (tp.y - sp.y).abs() < 1e-9);
        assert!((tp.z - 777.0).abs() < 1e-9);
        assert!(t.rotation.angle_to(&start.rotation) < 1e-12);
        // Only rz selected: rx, ry of the start (ZYX Euler in F_c), rz of the target.
        let g = PoseGuidance::new(
            &robot(),
            &PoseSetup {
                selection: [true, true, true, false, false, true],
                ..setup
            },
            &START,
        )
        .unwrap();
        let s = pose_from_pos_quat([900.0, 0.0, 1000.0], quat_wxyz_from_euler(5.0, 6.0, 33.0));
        let t = g.target_tcp_world(&s).unwrap();
        let e_t = quat_to_euler_zyx_deg(&t.rotation);
        let e_s = quat_to_euler_zyx_deg(&start.rotation);
        assert!((e_t[0] - e_s[0]).abs() < 1e-9 && (e_t[1] - e_s[1]).abs() < 1e-9);
        assert!((e_t[2] - 33.0).abs() < 1e-9);
    }

    fn quat_wxyz_from_euler(x: f64, y: f64, z: f64) -> [f64; 4] {
        let q = quat_from_euler_zyx_deg(x, y, z);
        [q.w, q.i, q.j, q.k]
    }

    #[test]
    fn feedback_frames() {
        let wobj = WobjData {
            uframe: pose_from_pos_quat([500.0, -100.0, 20.0], [0.0, 0.0, 0.0, 1.0]),
            ..WobjData::wobj0()
        };
        let corr = pose_from_pos_quat([10.0, 20.0, 30.0], [0.5, 0.5, 0.5, 0.5]);
        let setup = PoseSetup {
            wobj: wobj.clone(),
            corr_frame: corr,
            ..PoseSetup::world(tool())
        };
        let r = robot();
        let g = PoseGuidance::new(&r, &setup, &START).unwrap();
        let tcp = r.fk(&START) * tool().tframe;
        let (p, q) = g.feedback_cartesian(&START, FeedbackMode::Pose).unwrap();
        let expect = corr.inverse() * tcp;
        assert!(close(&pose_from_pos_quat(p, q), &expect, 1e-9));
        assert!(q[0] >= 0.0);
        for mode in [FeedbackMode::Joint, FeedbackMode::Stream] {
            let (p, q) = g.feedback_cartesian(&START, mode).unwrap();
            let expect = wobj.object_frame().inverse() * tcp;
            assert!(close(&pose_from_pos_quat(p, q), &expect, 1e-9));
            let free = feedback_in_wobj(&r, &START, &tool(), &wobj).unwrap();
            assert!(close(&pose_from_pos_quat(free.0, free.1), &expect, 1e-9));
        }
        assert!(
            g.feedback_cartesian(&[f64::NAN; 6], FeedbackMode::Pose)
                .is_err()
        );
        assert!(feedback_in_wobj(&r, &[f64::NAN; 6], &tool(), &wobj).is_err());
    }

    #[test]
    fn setup_errors() {
        let r = robot();
        let stationary = ToolData {
            robhold: false,
            ..tool()
        };
        assert!(matches!(
            PoseGuidance::new(&r, &PoseSetup::world(stationary), &START),
            Err(GuidanceError::Unsupported(_))
        ));
        let held = PoseSetup {
            wobj: WobjData {
                robhold: true,
                ..WobjData::wobj0()
            },
            ..PoseSetup::world(tool())
        };
        assert_eq!(
            PoseGuidance::new(&r, &held, &START).err(),
            Some(GuidanceError::InconsistentFrames)
        );
        let moving = PoseSetup {
            wobj: WobjData {
                ufprog: false,
                ..WobjData::wobj0()
            },
            ..PoseSetup::world(tool())
        };
        assert!(matches!(
            PoseGuidance::new(&r, &moving, &START),
            Err(GuidanceError::Unsupported(_))
        ));
        let joint = PoseSetup {
            sens_type: EgmFrameType::Joint,
            ..PoseSetup::world(tool())
        };
        assert_eq!(
            PoseGuidance::new(&r, &joint, &START).err(),
            Some(GuidanceError::JointFrameInPoseMode { which: "sensor" })
        );
        let joint = PoseSetup {
            corr_type: EgmFrameType::Joint,
            ..PoseSetup::world(tool())
        };
        assert_eq!(
            PoseGuidance::new(&r, &joint, &START).err(),
            Some(GuidanceError::JointFrameInPoseMode {
                which: "correction"
            })
        );
        let nan = crate::robot::units::nan_pose();
        for setup in [
            PoseSetup {
                corr_frame: nan,
                ..PoseSetup::world(tool())
            },
            PoseSetup {
                sensor_frame: nan,
                ..PoseSetup::world(tool())
            },
            PoseSetup {
                offset: Some(nan),
                ..PoseSetup::world(tool())
            },
            PoseSetup::world(ToolData {
                tframe: nan,
                ..tool()
            }),
        ] {
            assert!(matches!(
                PoseGuidance::new(&r, &setup, &START),
                Err(GuidanceError::NotFinite { .. })
            ));
        }
        let mut bad = START;
        bad[2] = f64::INFINITY;
        assert!(matches!(
            PoseGuidance::new(&r, &PoseSetup::world(tool()), &bad),
            Err(GuidanceError::NotFinite { .. })
        ));
        bad[2] = 100.0; // axis 3 limit is 75°
        assert!(matches!(
            PoseGuidance::new(&r, &PoseSetup::world(tool()), &bad),
            Err(GuidanceError::Kinematics(KinError::JointOutOfRange {
                joint: 3,
                ..
            }))
        ));
    }

    #[test]
    fn wrist_singular_target_is_refused() {
        let r = robot();
        let g = PoseGuidance::new(&r, &PoseSetup::world(ToolData::tool0()), &START).unwrap();
        let singular = r.fk(&[10.0, 5.0, 10.0, 0.0, 1.0, 0.0]);
        let e = g.joint_target(&singular, &START).unwrap_err();
        assert_eq!(
            e,
            GuidanceError::Kinematics(KinError::Singularity {
                kind: SingularityKind::Wrist,
                joints: match e.kin_error() {
                    Some(KinError::Singularity { joints, .. }) => *joints,
                    _ => panic!("{e:?}"),
                }
            })
        );
        assert_eq!(e.event(), Some((50026, "Close to singularity")));
    }
}
