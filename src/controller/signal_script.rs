//! `--signal-script FILE`: signal values that change at given robot times, for tests and
//! demonstrations of programs that wait for inputs (`SearchL` on a `signaldi`, `WaitDI`,
//! `ISignalDI`). One change per line, `TIME SIGNAL VALUE`: the time in seconds of robot
//! time from the start of the run, a configured signal (inputs and outputs alike) and its
//! new logical value; blank lines and lines starting with `#` are skipped. Times must not go
//! backwards. The controller's host applies each change at its time: a wait of the program
//! ends there, so interrupts and searches see it in that motion cycle.

use std::collections::VecDeque;

use crate::signals::SignalTable;
use crate::time::RobotTime;

/// The changes of a signal script, in time order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SignalScript {
    changes: VecDeque<(RobotTime, String, f64)>,
}

impl SignalScript {
    /// Parse a script's text against the run's signals. Errors name the line.
    pub fn parse(text: &str, signals: &SignalTable) -> Result<SignalScript, String> {
        let mut changes = VecDeque::new();
        let mut last = RobotTime::ZERO;
        for (n, line) in text.lines().enumerate() {
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let at = |what: String| format!("line {}: {what}", n + 1);
            let fields: Vec<&str> = line.split_whitespace().collect();
            let [time, name, value] = fields.as_slice() else {
                return Err(at(format!("expected `TIME SIGNAL VALUE`, found `{line}`")));
            };
            let t: f64 = time
                .parse()
                .map_err(|_| at(format!("`{time}` is not a time in seconds")))?;
            if !(t.is_finite() && (0.0..=1e9).contains(&t)) {
                return Err(at(format!("the time {t} s is outside 0…1e9 s")));
            }
            let t = RobotTime::from_secs_f64(t);
            if t < last {
                return Err(at("the times must not go backwards".to_string()));
            }
            last = t;
            let v: f64 = value
                .parse()
                .map_err(|_| at(format!("`{value}` is not a number")))?;
            let id = signals.lookup_or_err(name).map_err(|e| at(e.to_string()))?;
            if let Some(def) = signals.def(id) {
                def.check_value(v).map_err(|e| at(e.to_string()))?;
            }
            changes.push_back((t, (*name).to_string(), v));
        }
        Ok(SignalScript { changes })
    }

    /// The time of the next change.
    pub fn next_time(&self) -> Option<RobotTime> {
        self.changes.front().map(|c| c.0)
    }

    /// Take the changes due at `now`, in order.
    pub fn take_due(&mut self, now: RobotTime) -> Vec<(String, f64)> {
        let mut due = Vec::new();
        while let Some((t, _, _)) = self.changes.front() {
            if *t > now {
                break;
            }
            if let Some((_, name, v)) = self.changes.pop_front() {
                due.push((name, v));
            }
        }
        due
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::signals::{SignalDef, SignalKind};

    fn table() -> SignalTable {
        SignalTable::new(vec![SignalDef::digital("di1", SignalKind::Di)]).unwrap_or_else(|e| {
            panic!("{e}");
        })
    }

    #[test]
    fn changes_come_due_in_order() {
        let mut s = SignalScript::parse("# probe\n0.5 di1 1\n\n1.25 DI1 0\n", &table())
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(s.next_time(), Some(RobotTime::from_secs_f64(0.5)));
        assert!(s.take_due(RobotTime::from_secs_f64(0.4)).is_empty());
        assert_eq!(
            s.take_due(RobotTime::from_secs_f64(2.0)),
            vec![("di1".to_string(), 1.0), ("DI1".to_string(), 0.0)]
        );
        assert_eq!(s.next_time(), None);
    }

    #[test]
    fn bad_lines_are_named() {
        for (text, want) in [
            ("1 di1", "line 1: expected `TIME SIGNAL VALUE`"),
            ("x di1 1", "line 1: `x` is not a time"),
            ("-1 di1 1", "line 1: the time -1 s"),
            (
                "1 di1 1\n0.5 di1 0",
                "line 2: the times must not go backwards",
            ),
            ("1 nosuch 1", "line 1: I/O signal `nosuch` is not defined"),
            ("1 di1 2", "line 1: value 2 is not allowed"),
            ("1 di1 NaN", "line 1: value NaN is not allowed"),
        ] {
            let e = SignalScript::parse(text, &table())
                .err()
                .unwrap_or_default();
            assert!(e.starts_with(want), "{text:?}: {e}");
        }
    }
}
