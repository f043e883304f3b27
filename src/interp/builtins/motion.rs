//! Motion instructions and functions: their signatures and implementations over the
//! [`crate::interp::Host`] motion methods (the interpreter only builds
//! [`crate::robot::command`] values; the host plans, moves and does the kinematics).
//!
//! Moves only queue commands: RAPID runs ahead of the robot up to the next stop point
//! (`fine` without `\Conc`), where it waits until the robot is there. Waits keep running
//! traps. On a host without a robot every motion native fails with a clear error.

mod data;
mod moves;
mod position;
mod settings;

use super::{Ctx, NativeFn, Registry};
use crate::interp::error::Exec;
use crate::interp::host::MotionWait;
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

/// The EGM signatures (egm-rapid.md §3).
pub const EGM_SIGNATURES: &[&str] = &[
    r"PROC EGMGetId(VAR egmident EGMid)",
    r"PROC EGMReset(VAR egmident EGMid)",
    r"FUNC egmstate EGMGetState(VAR egmident EGMid, \VAR egmcorrstate CorrectionState)",
    r"PROC EGMSetupUC(VAR mecunit MecUnit, VAR egmident EGMid, string ExtConfigName, string UCDevice, \switch Joint | switch Pose | switch PathCorr, \switch APTR | switch LATR, \num CommTimeout)",
    r"PROC EGMSetupAI(VAR mecunit MecUnit, VAR egmident EGMid, string ExtConfigName, \switch Joint | switch Pose | switch PathCorr, \switch APTR, \VAR signalai aiR1x, \VAR signalai aiR2y, \VAR signalai aiR3z, \VAR signalai aiR4rx, \VAR signalai aiR5ry, \VAR signalai aiR6rz, \VAR signalai aiE1, \VAR signalai aiE2, \VAR signalai aiE3, \VAR signalai aiE4, \VAR signalai aiE5, \VAR signalai aiE6)",
    r"PROC EGMSetupAO(VAR mecunit MecUnit, VAR egmident EGMid, string ExtConfigName, \switch Joint | switch Pose | switch PathCorr, \switch APTR, \VAR signalao aoR1x, \VAR signalao aoR2y, \VAR signalao aoR3z, \VAR signalao aoR4rx, \VAR signalao aoR5ry, \VAR signalao aoR6rz, \VAR signalao aoE1, \VAR signalao aoE2, \VAR signalao aoE3, \VAR signalao aoE4, \VAR signalao aoE5, \VAR signalao aoE6)",
    r"PROC EGMSetupGI(VAR mecunit MecUnit, VAR egmident EGMid, string ExtConfigName, \switch Joint | switch Pose | switch PathCorr, \switch APTR, \VAR signalgi giR1x, \VAR signalgi giR2y, \VAR signalgi giR3z, \VAR signalgi giR4rx, \VAR signalgi giR5ry, \VAR signalgi giR6rz, \VAR signalgi giE1, \VAR signalgi giE2, \VAR signalgi giE3, \VAR signalgi giE4, \VAR signalgi giE5, \VAR signalgi giE6)",
    r"PROC EGMSetupLTAPP(VAR mecunit MecUnit, VAR egmident EGMid, string ExtConfigName, string Device, num JointType, \switch APTR | switch LATR)",
    r"PROC EGMActJoint(VAR egmident EGMid, \switch StreamStart, \PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, \VAR signaldo DOToSensor, \PERS dnum DataToSensor{*}, \VAR signaldi DIFromSensor, \PERS dnum DataFromSensor{*}, \egm_minmax J1, \egm_minmax J2, \egm_minmax J3, \egm_minmax J4, \egm_minmax J5, \egm_minmax J6, \egm_minmax J7, \num LpFilter, \num SampleRate, \num MaxPosDeviation, \num MaxSpeedDeviation)",
    r"PROC EGMActPose(VAR egmident EGMid, \switch StreamStart, \PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, \VAR signaldo DOToSensor, \PERS dnum DataToSensor{*}, \VAR signaldi DIFromSensor, \PERS dnum DataFromSensor{*}, pose CorrFrame, egmframetype CorrFrType, pose SensorFrame, egmframetype SensFrType, \egm_minmax x, \egm_minmax y, \egm_minmax z, \egm_minmax rx, \egm_minmax ry, \egm_minmax rz, \num LpFilter, \num SampleRate, \num MaxPosDeviation, \num MaxSpeedDeviation)",
    r"PROC EGMActMove(VAR egmident EGMid, pose SensorFrame, \num SampleRate)",
    r"PROC EGMRunJoint(VAR egmident EGMid, egmstopmode Mode, \switch NoWaitCond, \switch J1, \switch J2, \switch J3, \switch J4, \switch J5, \switch J6, \switch J7, \num CondTime, \num RampInTime, \num RampOutTime, \num PosCorrGain)",
    r"PROC EGMRunPose(VAR egmident EGMid, egmstopmode Mode, \switch NoWaitCond, \switch x, \switch y, \switch z, \switch rx, \switch ry, \switch rz, \num CondTime, \num RampInTime, \num RampOutTime, \pose Offset, \num PosCorrGain)",
    r"PROC EGMStop(VAR egmident EGMid, egmstopmode Mode, \num RampOutTime)",
    r"PROC EGMWaitCond(VAR egmident EGMid)",
    r"PROC EGMStreamStart(VAR egmident EGMid, \num SampleRate)",
    r"PROC EGMStreamStop(VAR egmident EGMid)",
    r"PROC EGMMoveL(VAR egmident EGMid, robtarget ToPoint, speeddata Speed, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, \switch NoCorr)",
    r"PROC EGMMoveC(VAR egmident EGMid, robtarget CirPoint, robtarget ToPoint, speeddata Speed, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, \switch NoCorr)",
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
    for s in EGM_SIGNATURES {
        r.add(s, egm_pending);
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

fn egm_pending(cx: &mut Ctx<'_>) -> Exec<Value> {
    Err(cx.unsupported("EGM: issue 5"))
}
