//! Position events on the controller's side: what each event of a queued move does when the
//! motion core reports it fired ([`crate::motion::MotionError::Trigger`]). Output signals are
//! written here, in the motion cycle of the event (virtual time) or as soon as the program's
//! thread sees it (real time); `TriggSpeed` drives its analog output with the TCP speed of
//! every cycle from then on; interrupts and procedure calls go to the program.

use std::collections::HashMap;
use std::sync::Arc;

use crate::interp::host::{ProgramAction, TriggAction};
use crate::motion::{MotionError, MotionEvent};
use crate::signals::{IoError, SignalId, SignalTable};

/// An action with its signal looked up.
#[derive(Debug)]
enum Resolved {
    Signal(SignalId, f64),
    Speed(SignalId, f64),
    Program(ProgramAction),
}

/// The position events of the queued moves (see the module docs).
#[derive(Debug, Default)]
pub struct PositionEvents {
    signals: Option<Arc<SignalTable>>,
    next_key: u64,
    actions: HashMap<u64, Resolved>,
    /// Program actions fired and not yet taken.
    fired: Vec<ProgramAction>,
    /// Program actions still to fire.
    program_pending: usize,
    /// `TriggSpeed`'s output and scale, while it runs.
    speed: Option<(SignalId, f64)>,
    /// Signal writes that failed when an event fired (reported to the program).
    failures: Vec<IoError>,
}

impl PositionEvents {
    /// Write signals to `table`.
    pub fn set_signals(&mut self, table: Arc<SignalTable>) {
        self.signals = Some(table);
    }

    /// Register an action; returns its key for the motion core. A signal must exist.
    pub fn register(&mut self, action: TriggAction) -> Result<u64, IoError> {
        let lookup = |name: &str| match &self.signals {
            Some(t) => t.lookup_or_err(name),
            None => Err(IoError::UnknownSignal {
                name: name.to_string(),
            }),
        };
        let resolved = match action {
            TriggAction::Signal { name, value } => {
                let id = lookup(&name)?;
                // The value is checked now, when the move is queued, as SetDO/SetAO/SetGO
                // would check it.
                if let Some(def) = self.signals.as_ref().and_then(|t| t.def(id)) {
                    def.check_value(value)?;
                }
                Resolved::Signal(id, value)
            }
            TriggAction::Speed { name, scale } => Resolved::Speed(lookup(&name)?, scale),
            TriggAction::Program(p) => {
                self.program_pending += 1;
                Resolved::Program(p)
            }
        };
        self.next_key += 1;
        self.actions.insert(self.next_key, resolved);
        Ok(self.next_key)
    }

    /// Forget an action whose move was not queued.
    pub fn unregister(&mut self, key: u64) {
        if let Some(Resolved::Program(_)) = self.actions.remove(&key) {
            self.program_pending = self.program_pending.saturating_sub(1);
        }
    }

    /// The moves were dropped (a stop, an error, a search that found its signal): their
    /// events never fire. `TriggSpeed` stops driving its output.
    pub fn drop_pending(&mut self) {
        self.actions.clear();
        self.program_pending = 0;
        self.speed = None;
    }

    /// Take the position events out of `events` (from index `from`) and do them; `speed` is
    /// the TCP speed (mm/s) of the newest cycle, for `TriggSpeed`.
    pub fn route(&mut self, events: &mut Vec<MotionEvent>, from: usize, speed: f64) {
        if events.len() > from {
            let mut k = from;
            while k < events.len() {
                let key = match events.get(k).map(|e| &e.error) {
                    Some(MotionError::Trigger { key }) => *key,
                    _ => {
                        k += 1;
                        continue;
                    }
                };
                events.remove(k);
                self.fire(key);
            }
        }
        self.drive_speed(speed);
    }

    fn fire(&mut self, key: u64) {
        match self.actions.remove(&key) {
            Some(Resolved::Signal(id, value)) => self.write(id, value),
            Some(Resolved::Speed(id, scale)) => {
                self.speed = (scale != 0.0).then_some((id, scale));
                if scale == 0.0 {
                    self.write(id, 0.0);
                }
            }
            Some(Resolved::Program(p)) => {
                self.program_pending = self.program_pending.saturating_sub(1);
                self.fired.push(p);
            }
            None => {}
        }
    }

    fn write(&mut self, id: SignalId, value: f64) {
        if let Some(t) = &self.signals
            && let Err(e) = t.set(id, value)
        {
            self.failures.push(e);
        }
    }

    /// `TriggSpeed`: the output follows the TCP speed, clamped to the signal's range.
    fn drive_speed(&mut self, speed: f64) {
        let (Some((id, scale)), Some(t)) = (self.speed, &self.signals) else {
            return;
        };
        let Some(def) = t.def(id) else {
            return;
        };
        let v = scale * speed;
        let v = if v.is_finite() { v } else { 0.0 };
        let (lo, hi) = (def.min_log.min(def.max_log), def.max_log.max(def.min_log));
        let _ = t.set(id, v.clamp(lo, hi));
    }

    /// The program's events that fired, oldest first.
    pub fn take_fired(&mut self) -> Vec<ProgramAction> {
        std::mem::take(&mut self.fired)
    }

    /// Signal writes that failed when their event fired.
    pub fn take_failures(&mut self) -> Vec<IoError> {
        std::mem::take(&mut self.failures)
    }

    /// True while program events are queued or fired and not taken.
    pub fn program_pending(&self) -> bool {
        self.program_pending > 0 || !self.fired.is_empty()
    }
}
