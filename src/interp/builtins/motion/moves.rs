//! `MoveAbsJ`, `MoveJ`, `MoveL`, `MoveC`: build a [`MotionCommand`] from the arguments and the
//! modal settings, queue it through the host, and at a stop point (`fine` without `\Conc`)
//! wait until the robot is there.

use super::data;
use super::wait_for;
use crate::interp::builtins::Ctx;
use crate::interp::error::Exec;
use crate::interp::host::MotionWait;
use crate::interp::value::Value;
use crate::robot::command::{
    MotionCommand, MoveAbsJ, MoveArgs, MoveC, MoveJ, MoveL, SpeedOverride,
};

/// Where the arguments every move has sit in a signature: `Speed` at `speed`, then `\V`,
/// `\T`, `Zone`, `\Z`, `Tool`, `\WObj`; `\TLoad` at `tload`.
#[derive(Clone, Copy)]
struct Layout {
    speed: usize,
    tload: usize,
}

impl Layout {
    fn v(self) -> usize {
        self.speed + 1
    }
    fn t(self) -> usize {
        self.speed + 2
    }
    fn zone(self) -> usize {
        self.speed + 3
    }
    fn z(self) -> usize {
        self.speed + 4
    }
    fn tool(self) -> usize {
        self.speed + 5
    }
    fn wobj(self) -> usize {
        self.speed + 6
    }
}

/// `\Conc` is the first argument of every move.
const CONC: usize = 0;

/// The arguments common to every move (the id is given by the host).
fn move_args(cx: &Ctx<'_>, l: Layout) -> Exec<MoveArgs> {
    let speed = data::speeddata(cx, cx.value(l.speed)?)?;
    let speed_override = if cx.present(l.v()) {
        Some(SpeedOverride::V(cx.f64(l.v())?))
    } else if cx.present(l.t()) {
        Some(SpeedOverride::T(cx.f64(l.t())?))
    } else {
        None
    };
    let mut zone = data::zonedata(cx, cx.value(l.zone())?)?;
    if let Some(z) = cx.opt_f64(l.z())? {
        zone.pzone_tcp = z;
    }
    let tool = data::tooldata(cx, cx.value(l.tool())?)?;
    let wobj = data::opt_wobj(cx, l.wobj())?;
    let tload = if cx.present(l.tload) {
        Some(data::loaddata(cx, cx.value(l.tload)?)?)
    } else {
        None
    };
    let pdisp = cx.it.host.motion_modes().pdisp;
    Ok(MoveArgs {
        id: 0,
        source: Some(cx.span),
        speed,
        speed_override,
        zone,
        tool,
        wobj,
        tload,
        pdisp,
    })
}

/// Queue the move; at a stop point without `\Conc`, wait until the robot is there. Its tool
/// and work object become the active ones (`GetSysData`).
fn submit(cx: &mut Ctx<'_>, cmd: MotionCommand, l: Layout) -> Exec<Value> {
    submit_corr(cx, cmd, l, None)
}

/// [`submit`], marking the move for the correction generators when argument `corr`
/// (`\Corr`) is present.
fn submit_corr(
    cx: &mut Ctx<'_>,
    cmd: MotionCommand,
    l: Layout,
    corr: Option<usize>,
) -> Exec<Value> {
    let stop_point = cmd.args().zone.finep && !cx.present(CONC);
    // Among several tasks in real time the host may let the other tasks run while the move
    // waits for room in the motion queue: the shared persistents go with the baton.
    cx.it.publish_shared();
    let submitted = cx.host().motion_submit(cmd);
    cx.it.fetch_shared();
    let id = submitted.map_err(|e| cx.host_err(e))?;
    if corr.is_some_and(|i| cx.present(i)) {
        crate::interp::builtins::path_recovery::mark_corr(cx, id)?;
    }
    crate::interp::builtins::system::note_move_data(cx, l.tool(), l.wobj());
    if stop_point {
        wait_for(cx, MotionWait::Done(id))?;
    }
    Ok(Value::Absent)
}

/// `MoveAbsJ [\Conc,] ToJointPos [\ID] [\NoEOffs], Speed [\V]|[\T], Zone [\Z], Tool [\WObj]
/// [\TLoad]`.
pub(super) fn move_abs_j(cx: &mut Ctx<'_>) -> Exec<Value> {
    let l = Layout {
        speed: 4,
        tload: 11,
    };
    let cmd = MotionCommand::MoveAbsJ(MoveAbsJ {
        args: move_args(cx, l)?,
        target: data::jointtarget(cx, cx.value(1)?)?,
        no_eoffs: cx.present(3),
    });
    submit(cx, cmd, l)
}

/// `MoveJ [\Conc,] ToPoint [\ID], Speed [\V]|[\T], Zone [\Z], Tool [\WObj] [\TLoad]`.
pub(super) fn move_j(cx: &mut Ctx<'_>) -> Exec<Value> {
    let l = Layout {
        speed: 3,
        tload: 10,
    };
    let cmd = MotionCommand::MoveJ(MoveJ {
        args: move_args(cx, l)?,
        target: data::robtarget(cx, cx.value(1)?)?,
        conf_check: cx.it.host.motion_modes().conf_j,
    });
    submit(cx, cmd, l)
}

/// `MoveL [\Conc,] ToPoint [\ID], Speed [\V]|[\T], Zone [\Z], Tool [\WObj] [\Corr] [\TLoad]`.
/// `\Corr`: the offset of the connected correction generators is added (`CorrWrite`);
/// without one it adds nothing.
pub(super) fn move_l(cx: &mut Ctx<'_>) -> Exec<Value> {
    let l = Layout {
        speed: 3,
        tload: 11,
    };
    let cmd = MotionCommand::MoveL(MoveL {
        args: move_args(cx, l)?,
        target: data::robtarget(cx, cx.value(1)?)?,
        conf_check: cx.it.host.motion_modes().conf_l,
    });
    submit_corr(cx, cmd, l, Some(10))
}

/// `MoveC [\Conc,] CirPoint, ToPoint [\ID], Speed [\V]|[\T], Zone [\Z], Tool [\WObj] [\Corr]
/// [\TLoad]`.
pub(super) fn move_c(cx: &mut Ctx<'_>) -> Exec<Value> {
    let l = Layout {
        speed: 4,
        tload: 12,
    };
    let cmd = MotionCommand::MoveC(MoveC {
        args: move_args(cx, l)?,
        cir_point: data::robtarget(cx, cx.value(1)?)?,
        to_point: data::robtarget(cx, cx.value(2)?)?,
        conf_check: cx.it.host.motion_modes().conf_l,
    });
    submit_corr(cx, cmd, l, Some(11))
}
