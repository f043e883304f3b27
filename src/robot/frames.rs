//! The frame chain (docs/robot.md, "Frame chain"): world, base, `tooldata` (tframe, robot-held or stationary),
//! `wobjdata` (uframe · oframe, robot-held or fixed) and program displacement.
//!
//! Robot-held tool: `base · FK(q) · tframe = uframe · oframe · pdisp · target`, so the flange in
//! world is `uframe · oframe · pdisp · target · tframe⁻¹`.
//! Stationary tool with a robot-held work object (uframe defined in the flange frame, tframe in
//! world): `base · FK(q) · uframe · oframe · pdisp · target = tframe`, so the flange in world is
//! `tframe · (uframe · oframe · pdisp · target)⁻¹`.

use super::kinematics::Robot;
use super::{JointsDeg, Pose};

/// `loaddata`: payload mass, centre of gravity and inertia (carried along, not simulated).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoadData {
    /// Mass (kg).
    pub mass: f64,
    /// Centre of gravity (mm) in the tool (or flange) frame.
    pub cog: [f64; 3],
    /// Orientation of the axes of moment `[w, x, y, z]`.
    pub aom: [f64; 4],
    /// Moment of inertia about x (kg·m²).
    pub ix: f64,
    /// Moment of inertia about y (kg·m²).
    pub iy: f64,
    /// Moment of inertia about z (kg·m²).
    pub iz: f64,
}

impl LoadData {
    /// RAPID `load0`: `[0.001, [0,0,0.001], [1,0,0,0], 0, 0, 0]`.
    pub const LOAD0: LoadData = LoadData {
        mass: 0.001,
        cog: [0.0, 0.0, 0.001],
        aom: [1.0, 0.0, 0.0, 0.0],
        ix: 0.0,
        iy: 0.0,
        iz: 0.0,
    };
}

impl Default for LoadData {
    fn default() -> Self {
        LoadData::LOAD0
    }
}

/// `tooldata [robhold, tframe, tload]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToolData {
    /// TRUE: the robot holds the tool (tframe in the flange frame). FALSE: stationary tool
    /// (tframe in world).
    pub robhold: bool,
    /// The tool frame (TCP), mm.
    pub tframe: Pose,
    /// The tool's load.
    pub load: LoadData,
}

impl ToolData {
    /// RAPID `tool0`: robot-held, TCP at the flange, `load0`.
    pub fn tool0() -> ToolData {
        ToolData {
            robhold: true,
            tframe: Pose::identity(),
            load: LoadData::LOAD0,
        }
    }
}

impl Default for ToolData {
    fn default() -> Self {
        ToolData::tool0()
    }
}

/// `wobjdata [robhold, ufprog, ufmec, uframe, oframe]`.
#[derive(Clone, Debug, PartialEq)]
pub struct WobjData {
    /// TRUE: the robot holds the work object (used with a stationary tool).
    pub robhold: bool,
    /// TRUE: fixed user frame. FALSE (moved by a mechanical unit) is not supported by rapidvc.
    pub ufprog: bool,
    /// Mechanical unit moving the user frame (only with `ufprog = FALSE`).
    pub ufmec: String,
    /// User frame: in world, or in the flange frame when the robot holds the work object.
    pub uframe: Pose,
    /// Object frame, in the user frame.
    pub oframe: Pose,
}

impl WobjData {
    /// RAPID `wobj0`: `[FALSE, TRUE, "", [[0,0,0],[1,0,0,0]], [[0,0,0],[1,0,0,0]]]` = world.
    pub fn wobj0() -> WobjData {
        WobjData {
            robhold: false,
            ufprog: true,
            ufmec: String::new(),
            uframe: Pose::identity(),
            oframe: Pose::identity(),
        }
    }

    /// uframe · oframe.
    pub fn object_frame(&self) -> Pose {
        self.uframe * self.oframe
    }
}

impl Default for WobjData {
    fn default() -> Self {
        WobjData::wobj0()
    }
}

/// Whether a tool and a work object can be used together: exactly one of them is held by the
/// robot (robot-held tool with a fixed work object, or stationary tool with a robot-held work
/// object). The other two combinations have no meaning on a controller; the functions below
/// then follow `tool.robhold` alone.
pub fn frames_consistent(tool: &ToolData, wobj: &WobjData) -> bool {
    tool.robhold != wobj.robhold
}

/// The flange (tool0) pose in **world** that puts the TCP of `tool` at `target_in_obj`
/// (a robtarget in the object frame of `wobj`, displaced by `pdisp`). This is the input of
/// [`Robot::ik_conf`] / [`Robot::ik_nearest`]. Handles a stationary tool with a robot-held
/// work object. Non-finite frames give non-finite poses, which IK rejects.
pub fn flange_target(target_in_obj: &Pose, tool: &ToolData, wobj: &WobjData, pdisp: &Pose) -> Pose {
    let target = wobj.object_frame() * pdisp * target_in_obj;
    if tool.robhold {
        target * tool.tframe.inverse()
    } else {
        tool.tframe * target.inverse()
    }
}

/// The inverse of [`flange_target`]: where the TCP of `tool` is, expressed in the object
/// frame of `wobj` after removing `pdisp`, when the flange is at `flange_world`. This is what
/// `CRobT(\Tool \WObj)` reports.
pub fn target_from_flange(
    flange_world: &Pose,
    tool: &ToolData,
    wobj: &WobjData,
    pdisp: &Pose,
) -> Pose {
    let obj_pdisp = wobj.object_frame() * pdisp;
    if tool.robhold {
        obj_pdisp.inverse() * flange_world * tool.tframe
    } else {
        (flange_world * obj_pdisp).inverse() * tool.tframe
    }
}

impl Robot {
    /// The TCP of `tool` at joints `q`, expressed in the object frame of `wobj` (world for
    /// `wobj0`), without program displacement. Non-finite joints give NaNs.
    pub fn tcp_pose(&self, q: &JointsDeg, tool: &ToolData, wobj: &WobjData) -> Pose {
        target_from_flange(&self.fk(q), tool, wobj, &Pose::identity())
    }

    /// The TCP of `tool` at joints `q` in **world** coordinates (for a stationary tool, its
    /// fixed tframe). This is the trace's `x, y, z, q1…q4`.
    pub fn tcp_world(&self, q: &JointsDeg, tool: &ToolData) -> Pose {
        if tool.robhold {
            self.fk(q) * tool.tframe
        } else {
            tool.tframe
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::units::pose_from_pos_quat;
    use super::*;

    fn close(a: &Pose, b: &Pose) -> bool {
        (a.translation.vector - b.translation.vector).norm() < 1e-9
            && a.rotation.angle_to(&b.rotation) < 1e-9
    }

    #[test]
    fn defaults_are_identity() {
        let t = pose_from_pos_quat([100.0, 200.0, 300.0], [0.5, 0.5, 0.5, 0.5]);
        let f = flange_target(
            &t,
            &ToolData::tool0(),
            &WobjData::wobj0(),
            &Pose::identity(),
        );
        assert!(close(&f, &t));
        assert!(frames_consistent(&ToolData::tool0(), &WobjData::wobj0()));
    }

    #[test]
    fn robot_held_tool_round_trip() {
        let tool = ToolData {
            tframe: pose_from_pos_quat([12.0, -3.0, 400.0], [0.9, 0.0, 0.43, 0.0]),
            ..ToolData::tool0()
        };
        let wobj = WobjData {
            uframe: pose_from_pos_quat([800.0, 100.0, 50.0], [0.7, 0.0, 0.0, 0.7]),
            oframe: pose_from_pos_quat([10.0, 20.0, 0.0], [1.0, 0.0, 0.0, 0.0]),
            ..WobjData::wobj0()
        };
        let pdisp = pose_from_pos_quat([5.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]);
        let target = pose_from_pos_quat([30.0, 40.0, 10.0], [0.0, 0.0, 1.0, 0.0]);
        let f = flange_target(&target, &tool, &wobj, &pdisp);
        // The chain holds: flange · tframe = uframe · oframe · pdisp · target.
        assert!(close(
            &(f * tool.tframe),
            &(wobj.uframe * wobj.oframe * pdisp * target)
        ));
        assert!(close(
            &target_from_flange(&f, &tool, &wobj, &pdisp),
            &target
        ));
    }

    #[test]
    fn stationary_tool_round_trip() {
        let tool = ToolData {
            robhold: false,
            tframe: pose_from_pos_quat([1200.0, 0.0, 900.0], [0.0, 0.0, 1.0, 0.0]),
            load: LoadData::LOAD0,
        };
        let wobj = WobjData {
            robhold: true,
            uframe: pose_from_pos_quat([0.0, 0.0, 150.0], [1.0, 0.0, 0.0, 0.0]),
            ..WobjData::wobj0()
        };
        assert!(frames_consistent(&tool, &wobj));
        let target = pose_from_pos_quat([10.0, 5.0, 0.0], [0.0, 1.0, 0.0, 0.0]);
        let pdisp = Pose::identity();
        let f = flange_target(&target, &tool, &wobj, &pdisp);
        // flange · uframe · oframe · target = tframe.
        assert!(close(
            &(f * wobj.uframe * wobj.oframe * target),
            &tool.tframe
        ));
        assert!(close(
            &target_from_flange(&f, &tool, &wobj, &pdisp),
            &target
        ));
    }
}
