//! Path recovery: `StopMove`, `StartMove`, `StartMoveRetry`, `StopMoveReset`,
//! `IsStopMoveAct`, `StorePath`, `RestoPath`, `ClearPath`, `SpeedRefresh`, `CSpeedOverride`,
//! over [`crate::interp::Host::motion_path`].
//!
//! `StopMove` decelerates the robot on its path and returns when it stands still; the path
//! stays held (new moves queue behind it) until `StartMove`. `StorePath` puts the held path
//! aside so the program can move the robot elsewhere (in a TRAP or an ERROR handler);
//! `RestoPath` brings it back once those moves are done, and `StartMove` continues it from
//! where the robot is (within 10 mm and 20° of where it was interrupted, else
//! `ERR_PATHDIST`). `ClearPath` drops the moves of the current path. rapidvc runs one motion
//! task: `\AllMotionTasks` and `\KeepSync` change nothing, and no other task sets a stop-move
//! state (`IsStopMoveAct \FromNonMoveTask` is FALSE).

use super::motion::wait_for;
use super::{Ctx, Registry};
use crate::interp::errnum;
use crate::interp::error::{ErrorKind, Exec, Unwind};
use crate::interp::host::{CorrAnswer, CorrRequest, MotionWait, PathCommand};
use crate::interp::value::Value;

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add(
        r"PROC StopMove(\switch Quick, \switch AllMotionTasks)",
        |cx| {
            let quick = cx.present(0);
            path(cx, PathCommand::Stop { quick })?;
            wait_for(cx, MotionWait::ZeroSpeed)?;
            Ok(Value::Absent)
        },
    );
    r.add(r"PROC StartMove(\switch AllMotionTasks)", |cx| {
        path(cx, PathCommand::Start)?;
        Ok(Value::Absent)
    });
    r.add("PROC StartMoveRetry()", |cx| {
        let in_handler = cx.it.frames.last().is_some_and(|f| f.handling.is_some());
        if !in_handler {
            return Err(cx.it.fatal(
                ErrorKind::Host,
                cx.span,
                "`StartMoveRetry` can only be used in an ERROR handler",
            ));
        }
        path(cx, PathCommand::Start)?;
        Err(Unwind::Retry)
    });
    r.add(r"PROC StopMoveReset(\switch AllMotionTasks)", |cx| {
        path(cx, PathCommand::Reset)?;
        Ok(Value::Absent)
    });
    r.add(
        r"FUNC bool IsStopMoveAct(\switch FromMoveTask | switch FromNonMoveTask)",
        |cx| {
            // No other task exists to set the state.
            let from_non_move = cx.present(1);
            let active = !from_non_move && cx.it.host.motion_modes().stop_move;
            Ok(Value::Bool(active))
        },
    );
    r.add(r"PROC StorePath(\switch KeepSync)", |cx| {
        // The path is stored where the robot holds on it: a moving robot stops on the path
        // first (as with StopMove; StartMove resumes it after RestoPath).
        let still = cx
            .host()
            .motion_reached(MotionWait::ZeroSpeed)
            .map_err(|e| cx.host_err(e))?;
        if !still {
            path(cx, PathCommand::Stop { quick: false })?;
            wait_for(cx, MotionWait::ZeroSpeed)?;
        }
        path(cx, PathCommand::Store)?;
        Ok(Value::Absent)
    });
    r.add("PROC RestoPath()", |cx| {
        // The moves made since StorePath end first.
        wait_for(cx, MotionWait::InPos)?;
        path(cx, PathCommand::Restore)?;
        Ok(Value::Absent)
    });
    r.add("PROC ClearPath()", |cx| {
        path(cx, PathCommand::Clear)?;
        Ok(Value::Absent)
    });
    r.add("PROC SpeedRefresh(num Override)", |cx| {
        let pct = cx.f64(0)?;
        if !(0.0..=100.0).contains(&pct) {
            return Err(cx.error(
                errnum::ERR_SPEED_REFRESH_LIM,
                format!("the SpeedRefresh override must be 0 to 100 %, not {pct}"),
            ));
        }
        path(cx, PathCommand::Speed(pct))?;
        Ok(Value::Absent)
    });
    r.add(r"FUNC num CSpeedOverride(\switch CTask)", |cx| {
        // No FlexPendant override exists (it is 100 %): the override is SpeedRefresh's.
        let pct = cx.it.host.motion_modes().speed_refresh;
        cx.num_result(pct)
    });
}

/// The correction generators (`CorrCon`, …), driving `\Corr` on `MoveL`/`MoveC`: the
/// descriptor holds the generator's number (0 when not connected); offsets are in the path
/// frame (x along the path, z the tool's z made perpendicular to it, y = z × x).
pub(super) fn register_corr(r: &mut Registry) {
    r.add("PROC CorrCon(VAR corrdescr Descr)", |cx| {
        let n = match corr(cx, CorrRequest::Connect)? {
            CorrAnswer::Connected(n) => n,
            _ => 0,
        };
        cx.set(0, Value::Record(Box::new([Value::Num(n as f32)])))?;
        Ok(Value::Absent)
    });
    r.add("PROC CorrWrite(VAR corrdescr Descr, pos Data)", |cx| {
        let n = descr(cx, 0)?;
        let data = cx.nums::<3>(1)?;
        if !data.iter().all(|c| c.is_finite()) {
            return Err(cx.error(errnum::ERR_ARGVALERR, "the correction must be finite"));
        }
        corr(cx, CorrRequest::Write(n, data))?;
        Ok(Value::Absent)
    });
    r.add("PROC CorrDiscon(VAR corrdescr Descr)", |cx| {
        let n = descr(cx, 0)?;
        corr(cx, CorrRequest::Disconnect(n))?;
        cx.set(0, Value::Record(Box::new([Value::Num(0.0)])))?;
        Ok(Value::Absent)
    });
    r.add("PROC CorrClear()", |cx| {
        corr(cx, CorrRequest::Clear)?;
        Ok(Value::Absent)
    });
    r.add("FUNC pos CorrRead()", |cx| {
        match corr(cx, CorrRequest::Read)? {
            CorrAnswer::Offset(o) => Ok(Value::num_record(&o)),
            _ => Ok(Value::num_record(&[0.0; 3])),
        }
    });
}

/// Mark the move `id` as a `\Corr` move.
pub(crate) fn mark_corr(cx: &mut Ctx<'_>, id: u64) -> Exec<()> {
    corr(cx, CorrRequest::Mark(id)).map(drop)
}

fn corr(cx: &mut Ctx<'_>, req: CorrRequest) -> Exec<CorrAnswer> {
    cx.host().motion_corr(req).map_err(|e| cx.host_err(e))
}

/// The generator number in descriptor argument `i` (connected: at least 1).
fn descr(cx: &Ctx<'_>, i: usize) -> Exec<u32> {
    let n = cx
        .value(i)?
        .fields()
        .and_then(|f| f.first())
        .and_then(|v| v.as_f64())
        .unwrap_or(0.0);
    if n >= 1.0 && n.fract() == 0.0 && n <= f64::from(u32::MAX) {
        Ok(n as u32)
    } else {
        Err(cx.it.fatal(
            ErrorKind::Host,
            cx.span,
            format!(
                "`{}`: the correction descriptor is not connected (CorrCon first)",
                cx.name()
            ),
        ))
    }
}

fn path(cx: &mut Ctx<'_>, cmd: PathCommand) -> Exec<()> {
    cx.host().motion_path(cmd).map_err(|e| cx.host_err(e))
}
