//! The EGM capability of [`ControllerHost`]: it lends its [`EgmController`] and controller to [`crate::controller::egm_controller`]'s blanket [`crate::interp::host::EgmHost`] implementation.

use crate::controller::ControllerHandle;
use crate::controller::egm_controller::{EgmController, EgmParts, LastMove};
use crate::interp::Host;
use crate::interp::host::Output;
use crate::motion::InstrRef;
use crate::robot::command::MotionCommand;
use crate::source::Span;

use super::ControllerHost;

impl EgmParts for ControllerHost {
    fn egm_parts(&mut self) -> Option<(&mut EgmController, &mut ControllerHandle)> {
        match (self.egm.as_mut(), self.ctl.as_mut()) {
            (Some(e), Some(c)) => Some((e, c)),
            _ => None,
        }
    }

    fn last_move(&self) -> LastMove {
        self.last_move
    }

    fn egm_instr(&mut self, name: &'static str, span: Span) -> Option<InstrRef> {
        self.last_id += 1;
        Some(InstrRef {
            id: self.last_id,
            name,
            source: Some(span),
        })
    }

    fn egm_event(&mut self, text: String) {
        self.output(Output::Event(text));
    }

    fn keep_move(&mut self, id: u64, cmd: &MotionCommand) {
        if let Some(p) = self.panel.as_mut() {
            p.unfinished.push_back((id, cmd.clone()));
        }
    }
}
