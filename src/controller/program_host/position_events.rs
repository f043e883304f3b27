//! The position-event capability of the controller's host: moves with events
//! (`controller::position_events` does them when they fire), the program's events handed
//! back to the interpreter, and the stop of a search.

use std::sync::Arc;
use std::time::Duration;

use crate::interp::host::{
    Output, PositionEventHost, ProgramAction, SearchStop, TriggEvent, io_error,
};
use crate::interp::{Host, HostError};
use crate::robot::command::MotionCommand;
use crate::robot::trigger::PathTrigger;

use super::ControllerHost;
use crate::controller::signal_script::SignalScript;

impl ControllerHost {
    /// Change signals at the times of `script` (`--signal-script`).
    pub fn with_signal_script(mut self, script: SignalScript) -> Self {
        self.script = script;
        self
    }

    /// Make the script's changes that are due.
    pub(super) fn apply_script(&mut self) -> Result<(), HostError> {
        if self.script.next_time().is_none_or(|t| t > self.now()) {
            return Ok(());
        }
        for (name, value) in self.script.take_due(self.now()) {
            self.io.write_signal(&name, value)?;
        }
        Ok(())
    }
}

impl PositionEventHost for ControllerHost {
    fn submit_with_events(
        &mut self,
        cmd: MotionCommand,
        name: &'static str,
        events: Vec<TriggEvent>,
    ) -> Result<u64, HostError> {
        let signals = Arc::clone(self.io.signals());
        let pos = self.ctl()?.position_events();
        pos.set_signals(signals);
        let mut triggers = Vec::with_capacity(events.len());
        for e in events {
            match pos.register(e.action) {
                Ok(key) => triggers.push(PathTrigger {
                    key,
                    place: e.place,
                    lead_s: e.lead_s,
                }),
                Err(err) => {
                    for t in &triggers {
                        pos.unregister(t.key);
                    }
                    return Err(io_error(err));
                }
            }
        }
        let result = self.submit_with(cmd, &triggers, Some(name));
        if result.is_err()
            && let Some(ctl) = self.ctl.as_mut()
        {
            for t in &triggers {
                ctl.position_events().unregister(t.key);
            }
        }
        result
    }

    fn take_program_events(&mut self) -> Vec<ProgramAction> {
        let Some(ctl) = self.ctl.as_mut() else {
            return Vec::new();
        };
        // Events fired while the handle ran cycles are routed already; look at new ones.
        let _ = ctl.state();
        let failures = ctl.position_events().take_failures();
        let fired = ctl.position_events().take_fired();
        for f in failures {
            self.io.output(Output::Event(format!(
                "position event: the signal could not be set: {f}"
            )));
        }
        fired
    }

    fn program_events_pending(&self) -> bool {
        self.ctl
            .as_ref()
            .is_some_and(|c| c.position_events_ref().program_pending())
    }

    fn search_stop(&mut self, _how: SearchStop) -> Result<(), HostError> {
        // \Stop, \PStop and \SStop all brake along the axes as quickly as their
        // accelerations allow (docs/rapid.md, "Position events and searches").
        let ctl = self.ctl()?;
        ctl.stop_motion();
        self.void_up_to = self.last_id;
        self.pump_events();
        Ok(())
    }

    fn motion_period(&self) -> Duration {
        self.ctl
            .as_ref()
            .map_or(Duration::from_millis(4), |c| c.period())
    }
}
