//! The interpreter's [`EgmHost`] for any host that can lend its [`EgmController`] and [`ControllerHandle`] ([`EgmParts`]): failures become RAPID errors (`ERR_UDPUC_COMM`) or fatal errors, EGM events become program output.
//!
//! A controller-backed host implements [`EgmParts`] (four small methods) and returns itself
//! from [`crate::interp::Host::egm`]; the blanket implementation below does the rest.

use std::time::Duration;

use crate::egm::registry::{
    ActJoint, ActMove, ActPose, CorrState, EgmState, SetupLtapp, SetupSignals, SetupUc,
};
use crate::egm::servo::StopMode;
use crate::interp::host::{EgmHost, EgmRun, HostError};
use crate::ir::errnum;
use crate::motion::InstrRef;
use crate::robot::command::MotionCommand;
use crate::signals::SignalId;
use crate::source::Span;

use super::{EgmController, EgmFailure, LastMove};
use crate::controller::ControllerHandle;

/// What a host lends to run EGM.
pub trait EgmParts {
    /// The EGM controller and the controller handle (`None`: this host has no EGM).
    fn egm_parts(&mut self) -> Option<(&mut EgmController, &mut ControllerHandle)>;
    /// What the program's last movement was.
    fn last_move(&self) -> LastMove;
    /// The trace's reference for the EGM movement `name` at `span` (a fresh command id).
    fn egm_instr(&mut self, name: &'static str, span: Span) -> Option<InstrRef>;
    /// One EGM event line for the event log (stderr).
    fn egm_event(&mut self, text: String);
    /// A corrected move (EGMMoveL/EGMMoveC, id `id`) was queued: a host that continues
    /// stopped moves keeps it too.
    fn keep_move(&mut self, _id: u64, _cmd: &MotionCommand) {}
}

/// An [`EgmFailure`] as the interpreter's error: catchable with its RAPID error number
/// (`ERR_UDPUC_COMM`), else fatal.
pub fn host_error(f: &EgmFailure) -> HostError {
    match f.rapid_error().and_then(errnum::by_name) {
        Some(d) => HostError::rapid(d.num, f.to_string()),
        None => HostError::fatal(f.to_string()),
    }
}

fn no_egm() -> HostError {
    HostError::fatal("this controller has no EGM")
}

/// Runs `f` on the parts and reports the events it produced.
fn call<H: EgmParts + ?Sized, T>(
    host: &mut H,
    f: impl FnOnce(&mut EgmController, &mut ControllerHandle) -> Result<T, EgmFailure>,
) -> Result<T, HostError> {
    let (r, events) = match host.egm_parts() {
        Some((egm, handle)) => {
            let r = f(egm, handle);
            (r, egm.take_events())
        }
        None => return Err(no_egm()),
    };
    for (name, e) in events {
        if e.number == 0 {
            host.egm_event(format!("EGM {name}: {}", e.detail));
        } else {
            host.egm_event(format!("EGM {name}: {e}"));
        }
    }
    r.map_err(|e| host_error(&e))
}

fn seconds(s: Option<f64>) -> Option<Duration> {
    s.and_then(|s| Duration::try_from_secs_f64(s).ok())
}

impl<H: EgmParts> EgmHost for H {
    fn egm_get_id(&mut self, ident: &str) -> Result<(), HostError> {
        call(self, |e, h| e.get_id(h, ident))
    }

    fn egm_reset(&mut self, ident: &str) -> Result<(), HostError> {
        call(self, |e, h| e.reset(h, ident))
    }

    fn egm_get_state(&mut self, ident: &str) -> Result<(EgmState, CorrState), HostError> {
        call(self, |e, _| e.state(ident))
    }

    fn egm_signal(&mut self, name: &str) -> Result<SignalId, HostError> {
        call(self, |e, _| {
            e.signals()
                .lookup_or_err(name)
                .map_err(|err| EgmFailure::Fatal(err.to_string()))
        })
    }

    fn egm_setup_uc(&mut self, ident: &str, args: &SetupUc) -> Result<(), HostError> {
        call(self, |e, h| e.setup_uc(h, ident, args))
    }

    fn egm_setup_signals(&mut self, ident: &str, args: &SetupSignals) -> Result<(), HostError> {
        call(self, |e, h| e.setup_signals(h, ident, args))
    }

    fn egm_setup_ltapp(&mut self, ident: &str, args: &SetupLtapp) -> Result<(), HostError> {
        call(self, |e, h| e.setup_ltapp(h, ident, args))
    }

    fn egm_act_joint(&mut self, ident: &str, args: &ActJoint) -> Result<(), HostError> {
        call(self, |e, h| e.act_joint(h, ident, args))
    }

    fn egm_act_pose(&mut self, ident: &str, args: &ActPose) -> Result<(), HostError> {
        call(self, |e, h| e.act_pose(h, ident, args))
    }

    fn egm_act_move(&mut self, ident: &str, args: &ActMove) -> Result<(), HostError> {
        call(self, |e, _| e.act_move(ident, args))
    }

    fn egm_run(&mut self, ident: &str, run: &EgmRun, span: Span) -> Result<(), HostError> {
        let last = self.last_move();
        let name = match run {
            EgmRun::Joint { .. } => "EGMRunJoint",
            EgmRun::Pose { .. } => "EGMRunPose",
        };
        let instr = self.egm_instr(name, span);
        call(self, |e, h| match run {
            EgmRun::Joint { args, axes } => e.run_joint(h, ident, args, *axes, last, instr),
            EgmRun::Pose {
                args,
                directions,
                offset,
            } => e.run_pose(h, ident, args, *directions, *offset, last, instr),
        })
    }

    fn egm_run_done(&mut self, ident: &str, fatal: bool) -> Result<bool, HostError> {
        call(self, |e, _| e.run_done(ident, fatal))
    }

    fn egm_run_active(&mut self, ident: &str) -> Result<bool, HostError> {
        call(self, |e, _| e.run_active(ident))
    }

    fn egm_stop(
        &mut self,
        ident: &str,
        mode: StopMode,
        ramp_out: Option<f64>,
    ) -> Result<(), HostError> {
        if let Some(s) = ramp_out
            && !(s.is_finite() && s >= 0.0)
        {
            return Err(HostError::fatal(format!(
                "EGMStop: \\RampOutTime = {s} is not allowed; it must be a number of seconds ≥ 0"
            )));
        }
        call(self, |e, h| e.stop(h, ident, mode, seconds(ramp_out)))
    }

    fn egm_stop_done(&mut self, ident: &str) -> Result<(), HostError> {
        call(self, |e, _| e.stop_done(ident))
    }

    fn egm_stream_start(&mut self, ident: &str, sample_rate: Option<f64>) -> Result<(), HostError> {
        call(self, |e, h| e.stream_start(h, ident, sample_rate))
    }

    fn egm_stream_stop(&mut self, ident: &str) -> Result<(), HostError> {
        call(self, |e, h| e.stream_stop(h, ident))
    }

    fn egm_program_stopped(&mut self) -> Result<(), HostError> {
        call(self, |e, h| e.program_stopped(h))
    }
}
