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
use crate::interp::host::{MotionWait, PathCommand};
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

fn path(cx: &mut Ctx<'_>, cmd: PathCommand) -> Exec<()> {
    cx.host().motion_path(cmd).map_err(|e| cx.host_err(e))
}
