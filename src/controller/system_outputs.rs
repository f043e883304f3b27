//! The controller's system outputs (`SYSSIG_OUT` in EIO.cfg): digital outputs that follow
//! the controller's state, as a PLC or a PC interface reads them (`DOutput(doMotorOn)`).
//!
//! | status | the signal is 1 while |
//! |---|---|
//! | `MotOnState` (`MotorOnState`), `MotorOn` | the motors are on (always in `rapidvc run`) |
//! | `MotOffState` (`MotorOffState`), `MotorOff` | the motors are off |
//! | `AutoOn` | the operating mode is automatic |
//! | `CycleOn` | the program runs |
//! | `TaskExecuting` (`-Arg2` task) | that task runs (without `-Arg2`: any task) |
//! | `Error`, `ProdExecError` (`-Arg2` task) | the program stopped on an error, until the next start |
//! | `MechUnitNotMoving` (`-Arg1` unit) | the robot stands still (set every motion cycle) |
//! | `RunchOk`, `MotSupOn` | always (a virtual controller's run chain is closed) |
//! | `EmStop`, `SmbBatteryChargeLow` | never |
//!
//! ABB documents what each status means, not when within a cycle it changes: rapidvc sets
//! them when the program starts and ends (and, in `rapidvc serve`, at the 20 ms panel poll)
//! and `MechUnitNotMoving` in the motion cycle.

use std::sync::Arc;

use crate::config::eio::SystemOutput;
use crate::controller::TickSink;
use crate::motion::Setpoint;
use crate::signals::{SignalId, SignalTable};

/// What the state-driven outputs show.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct OutputState {
    /// The motors are on.
    pub motors_on: bool,
    /// The operating mode is automatic.
    pub auto: bool,
    /// The tasks whose programs run now (names as in SYS.cfg).
    pub running: Vec<String>,
    /// The program stopped on an error (until the next start).
    pub error: bool,
}

#[derive(Clone, Debug)]
enum Drive {
    MotorsOn,
    MotorsOff,
    Auto,
    Cycle,
    Task(Option<String>),
    Error,
    Always(bool),
}

/// The system outputs of one system, resolved against its signal table.
#[derive(Debug)]
pub struct SystemOutputs {
    signals: Arc<SignalTable>,
    driven: Vec<(SignalId, Drive)>,
    not_moving: Vec<SignalId>,
}

impl SystemOutputs {
    /// The outputs of `config` (EIO.cfg's `SYSSIG_OUT`) on `signals`; `None` when there are
    /// none.
    pub fn new(config: &[SystemOutput], signals: &Arc<SignalTable>) -> Option<SystemOutputs> {
        let mut driven = Vec::new();
        let mut not_moving = Vec::new();
        for out in config {
            let Some(id) = signals.lookup(&out.signal) else {
                continue;
            };
            let drive = match out.status {
                "MotOnState" | "MotorOnState" | "MotorOn" => Drive::MotorsOn,
                "MotOffState" | "MotorOffState" | "MotorOff" => Drive::MotorsOff,
                "AutoOn" => Drive::Auto,
                "CycleOn" => Drive::Cycle,
                "TaskExecuting" => Drive::Task(out.arg2.clone()),
                "Error" | "ProdExecError" => Drive::Error,
                "RunchOk" | "MotSupOn" => Drive::Always(true),
                "MechUnitNotMoving" => {
                    not_moving.push(id);
                    continue;
                }
                // EmStop, SmbBatteryChargeLow, and what the configuration reader did not
                // accept.
                _ => Drive::Always(false),
            };
            driven.push((id, drive));
        }
        (!driven.is_empty() || !not_moving.is_empty()).then(|| SystemOutputs {
            signals: Arc::clone(signals),
            driven,
            not_moving,
        })
    }

    /// Set the state-driven outputs to `st`.
    pub fn show(&self, st: &OutputState) {
        for (id, drive) in &self.driven {
            let on = match drive {
                Drive::MotorsOn => st.motors_on,
                Drive::MotorsOff => !st.motors_on,
                Drive::Auto => st.auto,
                Drive::Cycle => !st.running.is_empty(),
                Drive::Task(None) => !st.running.is_empty(),
                Drive::Task(Some(task)) => st.running.iter().any(|t| t.eq_ignore_ascii_case(task)),
                Drive::Error => st.error,
                Drive::Always(v) => *v,
            };
            // A DO takes 0 and 1; the table refuses nothing else.
            let _ = self.signals.set(*id, if on { 1.0 } else { 0.0 });
        }
    }

    /// The motion cycle's sink for `MechUnitNotMoving` (`None` when no output asks for it).
    pub fn motion_sink(&self) -> Option<Box<dyn TickSink>> {
        (!self.not_moving.is_empty()).then(|| {
            Box::new(NotMoving {
                signals: Arc::clone(&self.signals),
                ids: self.not_moving.clone(),
                last: None,
            }) as Box<dyn TickSink>
        })
    }
}

/// Sets `MechUnitNotMoving` outputs every motion cycle.
struct NotMoving {
    signals: Arc<SignalTable>,
    ids: Vec<SignalId>,
    last: Option<bool>,
}

impl TickSink for NotMoving {
    fn record(&mut self, sp: &Setpoint) {
        let still = sp.standstill || sp.speed == 0.0;
        if self.last != Some(still) {
            self.last = Some(still);
            for id in &self.ids {
                let _ = self.signals.set(*id, if still { 1.0 } else { 0.0 });
            }
        }
    }
}

#[cfg(test)]
#[allow(clippy::expect_used)]
mod tests {
    use super::*;
    use crate::signals::{SignalDef, SignalKind};

    fn table(names: &[&str]) -> Arc<SignalTable> {
        let defs: Vec<SignalDef> = names
            .iter()
            .map(|n| SignalDef::digital(*n, SignalKind::Do))
            .collect();
        Arc::new(SignalTable::new(defs).expect("signals"))
    }

    fn out(status: &'static str, signal: &str, arg2: Option<&str>) -> SystemOutput {
        SystemOutput {
            status,
            signal: signal.into(),
            arg1: None,
            arg2: arg2.map(String::from),
        }
    }

    #[test]
    fn outputs_follow_the_state() {
        let t = table(&["mon", "moff", "cyc", "t1", "t2", "err", "ok", "estop"]);
        let outs = SystemOutputs::new(
            &[
                out("MotOnState", "mon", None),
                out("MotOffState", "moff", None),
                out("CycleOn", "cyc", None),
                out("TaskExecuting", "t1", Some("T_ROB1")),
                out("TaskExecuting", "t2", Some("T_LOG")),
                out("Error", "err", None),
                out("RunchOk", "ok", None),
                out("EmStop", "estop", None),
            ],
            &t,
        )
        .expect("outputs");
        let value = |n: &str| t.value(t.lookup(n).expect("signal")).expect("value");
        outs.show(&OutputState {
            motors_on: true,
            auto: true,
            running: vec!["T_ROB1".into()],
            error: false,
        });
        assert_eq!(
            ["mon", "moff", "cyc", "t1", "t2", "err", "ok", "estop"].map(value),
            [1.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0]
        );
        outs.show(&OutputState {
            motors_on: true,
            auto: true,
            running: vec![],
            error: true,
        });
        assert_eq!(["cyc", "t1", "err"].map(value), [0.0, 0.0, 1.0]);
    }
}
