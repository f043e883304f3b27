//! The interpreter's [`EgmPathHost`] for any controller-backed host with EGM ([`EgmParts`] plus [`Host`]): EGMMoveL/EGMMoveC go to the [`super::PathCorr`] of its EGM controller; failures become RAPID errors (`ERR_UDPUC_COMM`) or fatal errors, path-correction events become program output.

use crate::controller::ControllerError;
use crate::controller::egm_controller::{EgmFailure, EgmParts, host_error};
use crate::controller::program_host::motion_error;
use crate::egm::EgmError;
use crate::interp::Host;
use crate::interp::host::{EgmPathHost, HostError, MotionWait};
use crate::motion::MotionError;
use crate::robot::command::MotionCommand;

use super::PathCorrError;

fn no_egm() -> HostError {
    HostError::fatal("this controller has no EGM")
}

/// The instruction name of a corrected move.
fn instruction(cmd: &MotionCommand) -> &'static str {
    match cmd {
        MotionCommand::MoveC(_) => "EGMMoveC",
        _ => "EGMMoveL",
    }
}

/// Give `cmd` the host's next command id (the host numbers every move).
fn renumber<H: EgmParts + ?Sized>(host: &mut H, cmd: &mut MotionCommand) -> Option<u64> {
    let span = cmd.source()?;
    let id = host.egm_instr(instruction(cmd), span)?.id;
    match cmd {
        MotionCommand::MoveAbsJ(m) => m.args.id = id,
        MotionCommand::MoveJ(m) => m.args.id = id,
        MotionCommand::MoveL(m) => m.args.id = id,
        MotionCommand::MoveC(m) => m.args.id = id,
    }
    Some(id)
}

/// Hand the path-correction events to the event log.
fn report_events<H: EgmParts + ?Sized>(host: &mut H) {
    let events = match host.egm_parts() {
        Some((egm, _)) => egm.path_corr().0.take_events(),
        None => return,
    };
    for (name, e) in events {
        host.egm_event(format!("EGM {name}: {e}"));
    }
}

/// The program's error for a path-correction failure. A robot that stopped is handled as
/// the host handles every motion stop ([`Host::motion_reached`] gives the stop's error and
/// recovers the robot).
fn program_error<H: EgmParts + Host + ?Sized>(host: &mut H, e: PathCorrError) -> HostError {
    match e {
        PathCorrError::Egm(e) => host_error(&EgmFailure::Egm(e)),
        PathCorrError::Controller(ControllerError::Rejected(MotionError::Halted))
        | PathCorrError::Controller(ControllerError::Stopped(_)) => {
            match Host::motion_reached(host, MotionWait::InPos) {
                Err(e) => e,
                Ok(_) => HostError::fatal("the robot stopped after a motion error"),
            }
        }
        PathCorrError::Controller(ControllerError::Rejected(e)) => motion_error(&e, None, None),
        PathCorrError::Controller(e) => HostError::fatal(e.to_string()),
    }
}

impl<H: EgmParts + Host> EgmPathHost for H {
    fn egm_move(
        &mut self,
        ident: &str,
        mut cmd: MotionCommand,
        no_corr: bool,
    ) -> Result<u64, HostError> {
        let instruction = instruction(&cmd);
        renumber(self, &mut cmd).ok_or_else(no_egm)?;
        let last = self.last_move();
        let kept = cmd.clone();
        let result = match self.egm_parts() {
            Some((egm, handle)) => {
                let (pc, registry) = egm.path_corr();
                match registry.lookup(ident) {
                    Some(id) => pc.submit(handle, registry, id, cmd, no_corr, last),
                    None => Err(EgmError::NotReserved { instruction }.into()),
                }
            }
            None => return Err(no_egm()),
        };
        report_events(self);
        match result {
            Ok(ticket) => {
                // A program stop brakes it; the start continues it like any move.
                self.keep_move(ticket.cmd_id, &kept);
                Ok(ticket.cmd_id)
            }
            Err(e) => Err(program_error(self, e)),
        }
    }

    fn egm_move_end(&mut self, _ident: &str, ok: bool) -> Result<(), HostError> {
        let result = match self.egm_parts() {
            Some((egm, handle)) => {
                let (pc, registry) = egm.path_corr();
                pc.finish_sequence(handle, registry, ok)
            }
            None => return Err(no_egm()),
        };
        report_events(self);
        result.map_err(|e| program_error(self, e))
    }
}
