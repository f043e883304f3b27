//! Where the robot is as a robtarget, for services (Robot Web Services'
//! `rw/motionsystem/mechunits/ROB_1/robtarget?tool=&wobj=&coordinate=`): the tool and work
//! object are looked up by name in the motion task's RAPID data, as a controller does, and
//! the position is the motion thread's latest cycle.
//!
//! The coordinate systems (docs/rws.md):
//!
//! * **Base**: the TCP of the tool in the robot's base frame;
//! * **World**: the same as Base, since rapidvc's robot stands at the world origin (it has no
//!   configured base frame);
//! * **Wobj**: the TCP of the tool in the work object, with the active program displacement
//!   removed: exactly what `CRobT(\Tool:=tool \WObj:=wobj)` returns;
//! * **Tool**: the TCP in its own frame: the origin with a unit orientation (only the
//!   configuration and external axes carry information).

use crate::controller::service::{Coordinate, ServiceError};
use crate::interp::Interp;
use crate::interp::value::Value;
use crate::robot::command::RobTarget;
use crate::robot::{JointsDeg, LoadData, Pose, ToolData, WobjData, pose_from_pos_quat};

/// How far a stored quaternion's length may be from 1 (as RAPID's motion instructions check).
const QUAT_TOLERANCE: f64 = 1e-3;

/// A malformed value of `name`, for the error text.
fn malformed(name: &str, ty: &str) -> ServiceError {
    ServiceError::BadValue(format!("{ty} {name} does not hold a usable {ty} value"))
}

fn pose_of(v: &Value, name: &str, ty: &str) -> Result<Pose, ServiceError> {
    let f = v.fields().ok_or_else(|| malformed(name, ty))?;
    let trans = f
        .first()
        .and_then(Value::num_fields::<3>)
        .ok_or_else(|| malformed(name, ty))?;
    let rot = f
        .get(1)
        .and_then(Value::num_fields::<4>)
        .ok_or_else(|| malformed(name, ty))?;
    let norm = rot.iter().map(|c| c * c).sum::<f64>().sqrt();
    if !norm.is_finite() || (norm - 1.0).abs() > QUAT_TOLERANCE {
        return Err(ServiceError::BadValue(format!(
            "the orientation in {ty} {name} is not normalised (length {norm:.5})"
        )));
    }
    Ok(pose_from_pos_quat(trans, rot))
}

fn tool_of(v: &Value, name: &str) -> Result<ToolData, ServiceError> {
    let f = v.fields().ok_or_else(|| malformed(name, "tooldata"))?;
    Ok(ToolData {
        robhold: f
            .first()
            .and_then(Value::as_bool)
            .ok_or_else(|| malformed(name, "tooldata"))?,
        tframe: pose_of(
            f.get(1).ok_or_else(|| malformed(name, "tooldata"))?,
            name,
            "tooldata",
        )?,
        // The load does not move the TCP.
        load: LoadData::default(),
    })
}

fn wobj_of(v: &Value, name: &str) -> Result<WobjData, ServiceError> {
    let f = v.fields().ok_or_else(|| malformed(name, "wobjdata"))?;
    let flag = |i: usize| {
        f.get(i)
            .and_then(Value::as_bool)
            .ok_or_else(|| malformed(name, "wobjdata"))
    };
    let pose = |i: usize| {
        f.get(i)
            .ok_or_else(|| malformed(name, "wobjdata"))
            .and_then(|v| pose_of(v, name, "wobjdata"))
    };
    Ok(WobjData {
        robhold: flag(0)?,
        ufprog: flag(1)?,
        ufmec: f
            .get(2)
            .and_then(Value::as_str)
            .ok_or_else(|| malformed(name, "wobjdata"))?
            .to_string(),
        uframe: pose(3)?,
        oframe: pose(4)?,
    })
}

/// The value of the motion task's data `name` of type `ty` (`tooldata`, `wobjdata`);
/// `builtin` is the system's own instance (`tool0`, `wobj0`), which lives outside the
/// program's modules.
fn named<'i>(
    it: &'i Interp,
    name: &str,
    ty: &str,
    builtin: &str,
) -> Result<Option<&'i Value>, ServiceError> {
    let found = it.data_symbols(None, Some(name));
    match found.first() {
        Some(d) if d.data_type.eq_ignore_ascii_case(ty) && d.dims.is_empty() => {
            Ok(it.data_value(d.index))
        }
        Some(d) => Err(ServiceError::BadValue(format!(
            "{name} is a {}{}, not a {ty}",
            d.data_type,
            if d.dims.is_empty() { "" } else { " array" }
        ))),
        None if name.eq_ignore_ascii_case(builtin) => Ok(None),
        None => Err(ServiceError::NotFound(format!(
            "no {ty} {name} in the motion task's data"
        ))),
    }
}

/// The tool named `name` (`tool0` when `None`).
pub fn tool(it: &Interp, name: Option<&str>) -> Result<ToolData, ServiceError> {
    let name = name.unwrap_or("tool0");
    match named(it, name, "tooldata", "tool0")? {
        Some(v) => tool_of(v, name),
        None => Ok(ToolData::tool0()),
    }
}

/// The work object named `name` (`wobj0` when `None`).
pub fn wobj(it: &Interp, name: Option<&str>) -> Result<WobjData, ServiceError> {
    let name = name.unwrap_or("wobj0");
    match named(it, name, "wobjdata", "wobj0")? {
        Some(v) => wobj_of(v, name),
        None => Ok(WobjData::wobj0()),
    }
}

/// The robtarget of `joints` for `tool` and `wobj` in `coordinate` (see the module doc);
/// `kinematics` is the host's `robot_target_of` (tool, wobj, program displacement).
pub fn in_coordinate(
    joints: &JointsDeg,
    tool: &ToolData,
    wobj: &WobjData,
    pdisp: &Pose,
    coordinate: Coordinate,
    kinematics: impl Fn(&JointsDeg, &ToolData, &WobjData, &Pose) -> Result<RobTarget, String>,
) -> Result<RobTarget, ServiceError> {
    let err = ServiceError::NotAllowed;
    match coordinate {
        Coordinate::Base | Coordinate::World => {
            kinematics(joints, tool, &WobjData::wobj0(), &Pose::identity()).map_err(err)
        }
        Coordinate::Wobj => kinematics(joints, tool, wobj, pdisp).map_err(err),
        Coordinate::Tool => {
            let t = kinematics(joints, tool, &WobjData::wobj0(), &Pose::identity()).map_err(err)?;
            Ok(RobTarget {
                trans: [0.0; 3],
                rot: [1.0, 0.0, 0.0, 0.0],
                ..t
            })
        }
    }
}

/// A robtarget as RAPID text (numbers as RAPID writes a `num`).
pub fn text(t: &RobTarget) -> String {
    let n = |v: f64| crate::functions::format::format_num(v as f32);
    let list = |v: &[f64]| v.iter().map(|x| n(*x)).collect::<Vec<_>>().join(",");
    format!(
        "[[{}],[{}],[{}],[{}]]",
        list(&t.trans),
        list(&t.rot),
        t.robconf
            .to_array()
            .iter()
            .map(|c| c.to_string())
            .collect::<Vec<_>>()
            .join(","),
        list(&t.extax)
    )
}

#[cfg(test)]
#[allow(clippy::expect_used)]
mod tests {
    use super::*;

    fn fake(
        _: &JointsDeg,
        tool: &ToolData,
        wobj: &WobjData,
        _: &Pose,
    ) -> Result<RobTarget, String> {
        let (trans, _) = crate::robot::pose_to_pos_quat(&tool.tframe);
        let (w, _) = crate::robot::pose_to_pos_quat(&wobj.uframe);
        Ok(RobTarget {
            trans: [trans[0] - w[0], trans[1] - w[1], trans[2] - w[2]],
            rot: [0.0, 1.0, 0.0, 0.0],
            robconf: crate::robot::ConfData::default(),
            extax: crate::robot::command::EXTAX_NONE,
        })
    }

    #[test]
    fn coordinates_pick_the_frames() {
        let tool = ToolData {
            tframe: pose_from_pos_quat([0.0, 0.0, 100.0], [1.0, 0.0, 0.0, 0.0]),
            ..ToolData::tool0()
        };
        let wobj = WobjData {
            uframe: pose_from_pos_quat([0.0, 0.0, 30.0], [1.0, 0.0, 0.0, 0.0]),
            ..WobjData::wobj0()
        };
        let at = |c| in_coordinate(&[0.0; 6], &tool, &wobj, &Pose::identity(), c, fake);
        assert_eq!(at(Coordinate::Base).map(|t| t.trans[2]), Ok(100.0));
        assert_eq!(at(Coordinate::World).map(|t| t.trans[2]), Ok(100.0));
        assert_eq!(at(Coordinate::Wobj).map(|t| t.trans[2]), Ok(70.0));
        let t = at(Coordinate::Tool).expect("tool");
        assert_eq!((t.trans, t.rot), ([0.0; 3], [1.0, 0.0, 0.0, 0.0]));
    }
}
