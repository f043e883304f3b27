//! Motion instructions and functions: their signatures, so programs check today, and
//! implementations that fail clearly until the virtual robot (issue 4) plugs in through
//! [`super::Registry::replace`].

use super::{Ctx, Registry};
use crate::interp::error::Exec;
use crate::interp::value::Value;

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

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    for s in SIGNATURES {
        r.add(s, motion_pending);
    }
}

fn motion_pending(cx: &mut Ctx<'_>) -> Exec<Value> {
    Err(cx.unsupported("virtual robot: issue 4"))
}
