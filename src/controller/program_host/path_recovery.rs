//! The controller's side of `StopMove`, `StartMove`, `StopMoveReset`, `SpeedRefresh`,
//! `StorePath`, `RestoPath` and `ClearPath`: the stop-move state and the speed override the
//! program reads back, and the executor's path operations (`motion::PathOp`).

use std::sync::Arc;

use super::ControllerHost;
use super::corr_generators::{CorrPath, CorrShared};
use crate::interp::HostError;
use crate::interp::errnum;
use crate::interp::host::{CorrAnswer, CorrRequest, PathCommand};
use crate::motion::{PathOp, PathOpError};

/// The correction generators: their offsets, and what the cycle reads.
#[derive(Debug, Default)]
pub(super) struct Corr {
    shared: Arc<CorrShared>,
    /// Connected generators and their offsets (path frame, mm).
    gens: Vec<(u32, [f64; 3])>,
    last_id: u32,
    installed: bool,
}

impl Corr {
    fn sum(&self) -> [f64; 3] {
        let mut s = [0.0; 3];
        for (_, o) in &self.gens {
            for (a, b) in s.iter_mut().zip(o) {
                *a += b;
            }
        }
        s
    }
}

/// Carry out a correction generator request (`corr_generators`).
pub(super) fn corr(h: &mut ControllerHost, req: CorrRequest) -> Result<CorrAnswer, HostError> {
    let c = h.corr.get_or_insert_with(Corr::default);
    let answer = match req {
        CorrRequest::Mark(id) => {
            c.shared.mark(id);
            return Ok(CorrAnswer::Done);
        }
        CorrRequest::Read => return Ok(CorrAnswer::Offset(c.sum())),
        CorrRequest::Connect => {
            c.last_id += 1;
            let id = c.last_id;
            c.gens.push((id, [0.0; 3]));
            CorrAnswer::Connected(id)
        }
        CorrRequest::Write(id, o) => match c.gens.iter_mut().find(|(g, _)| *g == id) {
            Some((_, slot)) => {
                *slot = o;
                CorrAnswer::Done
            }
            None => {
                return Err(HostError::fatal(
                    "CorrWrite: the correction descriptor is not connected (CorrCon first)",
                ));
            }
        },
        CorrRequest::Disconnect(id) => {
            c.gens.retain(|(g, _)| *g != id);
            CorrAnswer::Done
        }
        CorrRequest::Clear => {
            c.gens.clear();
            CorrAnswer::Done
        }
    };
    c.shared.set_offset(c.sum());
    if !c.installed && matches!(req, CorrRequest::Connect) {
        let correction = Box::new(CorrPath::new(Arc::clone(&c.shared)));
        let installed = h
            .ctl()?
            .install_path_correction(correction)
            .map_err(|e| HostError::fatal(format!("CorrCon: {e}")))?;
        if !installed {
            return Err(HostError::fatal(
                "CorrCon: another path correction (EGM path correction) is active",
            ));
        }
        if let Some(c) = h.corr.as_mut() {
            c.installed = true;
        }
    }
    Ok(answer)
}

/// Carry out `cmd` (see the module docs).
pub(super) fn run(h: &mut ControllerHost, cmd: PathCommand) -> Result<(), HostError> {
    h.state_checked()?;
    let before = h.modes;
    let op = match cmd {
        PathCommand::Stop { quick } => {
            h.modes.stop_move = true;
            PathOp::Hold { quick }
        }
        PathCommand::Start => {
            h.modes.stop_move = false;
            PathOp::Release
        }
        PathCommand::Reset => {
            // The state ends; the held path stays held until StartMove (or ClearPath).
            h.modes.stop_move = false;
            return Ok(());
        }
        PathCommand::Speed(pct) => {
            h.modes.speed_refresh = pct;
            PathOp::Speed(pct / 100.0)
        }
        PathCommand::Store => PathOp::Store,
        PathCommand::Restore => PathOp::Restore,
        PathCommand::Clear => {
            // Waits for the cleared moves are over.
            h.void_up_to = h.last_id;
            PathOp::Clear
        }
    };
    let result = h.ctl()?.path_op(op);
    h.pump_events();
    if let Err(e) = result {
        h.modes = before;
        return Err(path_error(cmd, e));
    }
    match cmd {
        PathCommand::Store => h.stored_accepted = Some(h.last_accepted),
        PathCommand::Restore => {
            if let Some(a) = h.stored_accepted.take() {
                h.last_accepted = a;
            }
        }
        _ => {}
    }
    if cmd == PathCommand::Clear && !h.modes.stop_move {
        // Without a stop-move state nothing holds the new moves.
        h.ctl()?
            .path_op(PathOp::Release)
            .map_err(|e| path_error(cmd, e))?;
    }
    Ok(())
}

/// The program's error for a refused path operation.
fn path_error(cmd: PathCommand, e: PathOpError) -> HostError {
    let what = match cmd {
        PathCommand::Stop { .. } => "StopMove",
        PathCommand::Start => "StartMove",
        PathCommand::Reset => "StopMoveReset",
        PathCommand::Speed(_) => "SpeedRefresh",
        PathCommand::Store => "StorePath",
        PathCommand::Restore => "RestoPath",
        PathCommand::Clear => "ClearPath",
    };
    match e {
        PathOpError::TooFar => HostError::rapid(
            errnum::ERR_PATHDIST,
            format!(
                "{what}: {e} (the robot must be within {} mm and {}° of the place where the \
                 path was interrupted)",
                crate::motion::executor::path_hold_limits::REGAIN_MAX_MM,
                crate::motion::executor::path_hold_limits::REGAIN_MAX_DEG
            ),
        ),
        _ => HostError::fatal(format!("{what}: {e}")),
    }
}
