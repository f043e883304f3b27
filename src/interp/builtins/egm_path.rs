//! EGM path correction in RAPID: `EGMMoveL` and `EGMMoveC` (docs/egm.md, "Path correction") build a `MoveL` / `MoveC` from their arguments and the active program displacement and hand it to the host's [`EgmPathHost`], which corrects it with the sensor data while it runs; at the fine point that ends a corrected sequence they wait (traps keep running) and end the sequence.
//!
//! `EGMActMove`, the setups and `PDispSet`/`PDispOff` are the EGM and motion domains'
//! natives; the signatures here replace the EGM domain's placeholders of the same names.

use super::egm::ident;
use super::motion::{data, wait_for};
use super::{Ctx, NativeFn, Registry};
use crate::interp::error::Exec;
use crate::interp::host::{EgmPathHost, HostError, MotionWait};
use crate::interp::value::Value;
use crate::robot::command::{MotionCommand, MoveArgs, MoveC, MoveL};

/// The signatures with their implementations.
const NATIVES: &[(&str, NativeFn)] = &[
    (
        r"PROC EGMMoveL(VAR egmident EGMid, robtarget ToPoint, speeddata Speed, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, \switch NoCorr)",
        egm_move_l,
    ),
    (
        r"PROC EGMMoveC(VAR egmident EGMid, robtarget CirPoint, robtarget ToPoint, speeddata Speed, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, \switch NoCorr)",
        egm_move_c,
    ),
];

/// Register this domain (after the EGM domain: these replace its placeholders).
pub(super) fn register(r: &mut Registry) {
    for (sig, f) in NATIVES {
        r.add(sig, *f);
    }
}

/// Calls the host's path-correction capability; a host without one stops the program.
fn with_path<T>(
    cx: &mut Ctx<'_>,
    f: impl FnOnce(&mut dyn EgmPathHost) -> Result<T, HostError>,
) -> Exec<T> {
    let r = cx.host().egm_path().map(f);
    match r {
        Some(Ok(v)) => Ok(v),
        Some(Err(e)) => Err(cx.host_err(e)),
        None => {
            let msg = format!(
                "`{}` is not supported by this controller (it has no EGM path correction; \
                 `rapidvc run` has)",
                cx.name()
            );
            Err(cx.host_err(HostError::fatal(msg)))
        }
    }
}

/// Speed at `speed`, then Zone, Tool, `\WObj`, `\TLoad` (the id is given by the host).
fn move_args(cx: &mut Ctx<'_>, speed: usize) -> Exec<MoveArgs> {
    let tload = speed + 4;
    Ok(MoveArgs {
        id: 0,
        source: Some(cx.span),
        speed: data::speeddata(cx, cx.value(speed)?)?,
        speed_override: None,
        zone: data::zonedata(cx, cx.value(speed + 1)?)?,
        tool: data::tooldata(cx, cx.value(speed + 2)?)?,
        wobj: data::opt_wobj(cx, speed + 3)?,
        tload: if cx.present(tload) {
            Some(data::loaddata(cx, cx.value(tload)?)?)
        } else {
            None
        },
        pdisp: cx.it.host.motion_modes().pdisp,
    })
}

/// Queue the corrected move; at a fine point wait for it and end the sequence.
fn run(cx: &mut Ctx<'_>, cmd: MotionCommand, no_corr: bool) -> Exec<Value> {
    let id = ident(cx, 0)?;
    let fine = cmd.args().zone.finep;
    let move_id = with_path(cx, |h| h.egm_move(&id, cmd, no_corr))?;
    if fine {
        if let Err(e) = wait_for(cx, MotionWait::Done(move_id)) {
            // The robot stopped (e.g. ERR_UDPUC_COMM): the sequence is over; the wait's
            // error is the one the program sees.
            let _ = with_path(cx, |h| h.egm_move_end(&id, false));
            return Err(e);
        }
        with_path(cx, |h| h.egm_move_end(&id, true))?;
    }
    Ok(Value::Absent)
}

/// `EGMMoveL EGMid, ToPoint, Speed, Zone, Tool [\WObj] [\TLoad] [\NoCorr]`.
fn egm_move_l(cx: &mut Ctx<'_>) -> Exec<Value> {
    let cmd = MotionCommand::MoveL(MoveL {
        args: move_args(cx, 2)?,
        target: data::robtarget(cx, cx.value(1)?)?,
        conf_check: cx.it.host.motion_modes().conf_l,
    });
    let no_corr = cx.present(7);
    run(cx, cmd, no_corr)
}

/// `EGMMoveC EGMid, CirPoint, ToPoint, Speed, Zone, Tool [\WObj] [\TLoad] [\NoCorr]`.
fn egm_move_c(cx: &mut Ctx<'_>) -> Exec<Value> {
    let cmd = MotionCommand::MoveC(MoveC {
        args: move_args(cx, 3)?,
        cir_point: data::robtarget(cx, cx.value(1)?)?,
        to_point: data::robtarget(cx, cx.value(2)?)?,
        conf_check: cx.it.host.motion_modes().conf_l,
    });
    let no_corr = cx.present(8);
    run(cx, cmd, no_corr)
}
