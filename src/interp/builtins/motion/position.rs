//! Where the robot is and the kinematics of RAPID: `CRobT`, `CJointT`, `CPos`, `CalcRobT`,
//! `CalcJointT`, and `WaitRob`. The host does the math (the interpreter knows no kinematics).

use super::{data, wait_for};
use crate::interp::builtins::Ctx;
use crate::interp::error::{ErrorKind, Exec};
use crate::interp::host::MotionWait;
use crate::interp::value::Value;
use crate::robot::command::RobTarget;
use crate::robot::{Pose, ToolData, WobjData};

/// The one task of a rapidvc program.
pub const TASK_NAME: &str = "T_ROB1";

/// `\TaskName` argument `i`: only the program's own task exists.
fn check_task(cx: &Ctx<'_>, i: usize) -> Exec<()> {
    if cx.present(i) {
        let name = cx.str(i)?;
        if !name.eq_ignore_ascii_case(TASK_NAME) {
            return Err(cx.it.fatal(
                ErrorKind::Unsupported,
                cx.span,
                format!(
                    "task `{name}` does not exist: rapidvc runs one motion task, `{TASK_NAME}`"
                ),
            ));
        }
    }
    Ok(())
}

/// The TCP of `tool` now, as a robtarget in `wobj` with the active program displacement
/// removed.
pub(crate) fn current_target(
    cx: &mut Ctx<'_>,
    tool: &ToolData,
    wobj: &WobjData,
) -> Exec<RobTarget> {
    let joints = cx.host().motion_joints().map_err(|e| cx.host_err(e))?;
    let pdisp = cx.it.host.motion_modes().pdisp;
    cx.it
        .host
        .robot_target_of(&joints, tool, wobj, &pdisp)
        .map_err(|e| cx.host_err(e))
}

/// `CRobT([\TaskName] [\Tool] [\WObj])`: tool0 and wobj0 when not given.
pub(super) fn c_rob_t(cx: &mut Ctx<'_>) -> Exec<Value> {
    check_task(cx, 0)?;
    let tool = data::opt_tool(cx, 1)?;
    let wobj = data::opt_wobj(cx, 2)?;
    let t = current_target(cx, &tool, &wobj)?;
    Ok(data::robtarget_value(&t))
}

/// `CPos([\Tool] [\WObj])`.
pub(super) fn c_pos(cx: &mut Ctx<'_>) -> Exec<Value> {
    let tool = data::opt_tool(cx, 0)?;
    let wobj = data::opt_wobj(cx, 1)?;
    let t = current_target(cx, &tool, &wobj)?;
    Ok(Value::num_record(&t.trans))
}

/// `CJointT([\TaskName])`.
pub(super) fn c_joint_t(cx: &mut Ctx<'_>) -> Exec<Value> {
    check_task(cx, 0)?;
    let joints = cx.host().motion_joints().map_err(|e| cx.host_err(e))?;
    Ok(data::jointtarget_value(&joints))
}

/// `CalcRobT(Joint_target, Tool [\WObj])`, with the active program displacement removed as in
/// `CRobT`.
pub(super) fn calc_rob_t(cx: &mut Ctx<'_>) -> Exec<Value> {
    let jt = data::jointtarget(cx, cx.value(0)?)?;
    let tool = data::tooldata(cx, cx.value(1)?)?;
    let wobj = data::opt_wobj(cx, 2)?;
    let pdisp = cx.it.host.motion_modes().pdisp;
    let t = cx
        .it
        .host
        .robot_target_of(&jt.robax, &tool, &wobj, &pdisp)
        .map_err(|e| cx.host_err(e))?;
    Ok(data::robtarget_value(&RobTarget {
        extax: jt.extax,
        ..t
    }))
}

/// `CalcJointT([\UseCurWObjPos,] Rob_target, Tool [\WObj] [\ErrorNumber])`: the axis values in
/// the robtarget's configuration (whatever `ConfJ`/`ConfL` say), with the active program
/// displacement. With `\ErrorNumber` a failure stores the error number there (0 on success)
/// and returns axis values of 9E9, which no move accepts. `\UseCurWObjPos` only matters for
/// work objects moved by a mechanical unit, which rapidvc does not support (it is accepted
/// and changes nothing).
pub(super) fn calc_joint_t(cx: &mut Ctx<'_>) -> Exec<Value> {
    let target = data::robtarget(cx, cx.value(1)?)?;
    let tool = data::tooldata(cx, cx.value(2)?)?;
    let wobj = data::opt_wobj(cx, 3)?;
    let pdisp = cx.it.host.motion_modes().pdisp;
    let result = cx.it.host.robot_joints_of(&target, &tool, &wobj, &pdisp);
    let report = cx.present(4);
    match result {
        Ok(j) => {
            if report {
                cx.set(4, Value::Num(0.0))?;
            }
            Ok(Value::Record(Box::new([
                Value::num_record(&j),
                Value::num_record(&target.extax),
            ])))
        }
        Err(e) => match e.errno {
            Some(n) if report => {
                cx.set(4, Value::Num(n as f32))?;
                Ok(data::jointtarget_value(
                    &[crate::robot::command::EXTAX_UNUSED; 6],
                ))
            }
            _ => Err(cx.host_err(e)),
        },
    }
}

/// `WaitRob [\InPos] | [\ZeroSpeed]` (`\InPos` when neither is given).
pub(super) fn wait_rob(cx: &mut Ctx<'_>) -> Exec<Value> {
    let w = if cx.present(1) {
        MotionWait::ZeroSpeed
    } else {
        MotionWait::InPos
    };
    wait_for(cx, w)?;
    Ok(Value::Absent)
}

/// The current position for `PDispOn` without `\ExeP`: the robot must stand still, so this
/// waits until it is in position (as at a fine point).
pub(super) fn position_in_wobj(
    cx: &mut Ctx<'_>,
    tool: &ToolData,
    wobj: &WobjData,
) -> Exec<RobTarget> {
    wait_for(cx, MotionWait::InPos)?;
    let joints = cx.host().motion_joints().map_err(|e| cx.host_err(e))?;
    cx.it
        .host
        .robot_target_of(&joints, tool, wobj, &Pose::identity())
        .map_err(|e| cx.host_err(e))
}
