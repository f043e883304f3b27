//! Motion instructions and functions: their signatures and implementations over the
//! [`crate::interp::Host`] motion methods (the interpreter only builds
//! [`crate::robot::command`] values; the host plans, moves and does the kinematics).
//!
//! Moves only queue commands: RAPID runs ahead of the robot up to the next stop point
//! (`fine` without `\Conc`), where it waits until the robot is there. Waits keep running
//! traps. On a host without a robot every motion native fails with a clear error.

pub(super) mod data;
mod moves;
pub(super) mod position;
mod settings;

use super::{Ctx, NativeFn, Registry};
use crate::interp::error::Exec;
use crate::interp::host::MotionWait;

/// The motion signatures (also used by the controller when it replaces the implementations).
pub const SIGNATURES: &[&str] = &[
    r"PROC MoveAbsJ(\switch Conc, jointtarget ToJointPos, \identno ID, \switch NoEOffs, speeddata Speed, \num V | num T, zonedata Zone, \num Z, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad)",
    r"PROC MoveJ(\switch Conc, robtarget ToPoint, \identno ID, speeddata Speed, \num V | num T, zonedata Zone, \num Z, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad)",
    r"PROC MoveL(\switch Conc, robtarget ToPoint, \identno ID, speeddata Speed, \num V | num T, zonedata Zone, \num Z, PERS tooldata Tool, \PERS wobjdata WObj, \switch Corr, \PERS loaddata TLoad)",
    r"PROC MoveC(\switch Conc, robtarget CirPoint, robtarget ToPoint, \identno ID, speeddata Speed, \num V | num T, zonedata Zone, \num Z, PERS tooldata Tool, \PERS wobjdata WObj, \switch Corr, \PERS loaddata TLoad)",
    r"PROC ConfJ(\switch On | switch Off)",
    r"PROC ConfL(\switch On | switch Off)",
    r"PROC SingArea(\switch Wrist | switch LockAxis4 | switch Off)",
    r"PROC VelSet(num Override, num Max)",
    r"PROC AccSet(num Acc, num Ramp, \num FinePointRamp)",
    r"FUNC robtarget CRobT(\string TaskName, \PERS tooldata Tool, \PERS wobjdata WObj)",
    r"FUNC jointtarget CJointT(\string TaskName)",
    r"FUNC pos CPos(\PERS tooldata Tool, \PERS wobjdata WObj)",
    r"FUNC jointtarget CalcJointT(\switch UseCurWObjPos, robtarget Rob_target, PERS tooldata Tool, \PERS wobjdata WObj, \VAR errnum ErrorNumber)",
    r"FUNC robtarget CalcRobT(jointtarget Joint_target, PERS tooldata Tool, \PERS wobjdata WObj)",
    r"PROC WaitRob(\switch InPos | switch ZeroSpeed)",
    r"PROC PDispSet(pose DispFrame)",
    r"PROC PDispOff()",
    r"PROC PDispOn(\switch Rot, \robtarget ExeP, robtarget ProgPoint, PERS tooldata Tool, \PERS wobjdata WObj)",
];

/// The implementation of each entry of [`SIGNATURES`], in the same order.
const IMPLS: [NativeFn; 18] = [
    moves::move_abs_j,
    moves::move_j,
    moves::move_l,
    moves::move_c,
    settings::conf_j,
    settings::conf_l,
    settings::sing_area,
    settings::vel_set,
    settings::acc_set,
    position::c_rob_t,
    position::c_joint_t,
    position::c_pos,
    position::calc_joint_t,
    position::calc_rob_t,
    position::wait_rob,
    settings::pdisp_set,
    settings::pdisp_off,
    settings::pdisp_on,
];

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    for (s, f) in SIGNATURES.iter().zip(IMPLS) {
        r.add(s, f);
    }
}

/// How long (robot time) a motion wait may go without looking at the condition. A host with
/// a robot ends each wait early whenever the motion state changes, so this only bounds waits
/// on a host that cannot tell.
const MOTION_POLL_S: f64 = 1.0;

/// Wait until `w` holds, running traps meanwhile (a fine point, `WaitRob`, `WaitTime \InPos`).
pub(crate) fn wait_for(cx: &mut Ctx<'_>, w: MotionWait) -> Exec<()> {
    cx.wait_host(None, MOTION_POLL_S, |h| h.motion_reached(w))?;
    Ok(())
}
