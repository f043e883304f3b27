//! Progress numbers for a front end to draw (e.g. a bar on a terminal): a [`ProgressSink`]
//! among the controller's sinks updates a [`Progress`] that any thread can read while the
//! run goes on. The library draws nothing.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::controller::TickSink;
use crate::motion::Setpoint;
use crate::source::SourceMap;
use crate::time::RobotTime;

#[derive(Debug, Default)]
struct Counters {
    time_ns: AtomicU64,
    ticks: AtomicU64,
    /// Line of the instruction being executed, 0 when none or unknown.
    line: AtomicU64,
    finished: AtomicU64,
}

/// A reader of the run's progress: cheap to clone, readable from any thread.
#[derive(Clone, Debug, Default)]
pub struct Progress {
    counters: Arc<Counters>,
}

impl Progress {
    /// A reader and the sink that updates it (put the sink among the controller's sinks).
    /// `lines` resolves instruction spans to line numbers.
    pub fn new(lines: Option<Arc<SourceMap>>) -> (Progress, ProgressSink) {
        let progress = Progress::default();
        let sink = ProgressSink {
            counters: Arc::clone(&progress.counters),
            lines,
            last_instr: None,
        };
        (progress, sink)
    }

    /// Robot time of the last recorded cycle.
    pub fn robot_time(&self) -> RobotTime {
        RobotTime::from_nanos(self.counters.time_ns.load(Ordering::Relaxed))
    }

    /// Cycles recorded so far.
    pub fn ticks(&self) -> u64 {
        self.counters.ticks.load(Ordering::Relaxed)
    }

    /// Source line of the instruction being executed, if known.
    pub fn line(&self) -> Option<u64> {
        match self.counters.line.load(Ordering::Relaxed) {
            0 => None,
            n => Some(n),
        }
    }

    /// The run is over (the sink's `finish` ran).
    pub fn is_finished(&self) -> bool {
        self.counters.finished.load(Ordering::Relaxed) != 0
    }
}

/// The [`TickSink`] behind a [`Progress`].
#[derive(Debug)]
pub struct ProgressSink {
    counters: Arc<Counters>,
    lines: Option<Arc<SourceMap>>,
    last_instr: Option<u64>,
}

impl TickSink for ProgressSink {
    fn record(&mut self, sp: &Setpoint) {
        let c = &self.counters;
        c.time_ns.store(sp.time.as_nanos(), Ordering::Relaxed);
        c.ticks.fetch_add(1, Ordering::Relaxed);
        let id = sp.instr.map(|i| i.id);
        if id != self.last_instr {
            self.last_instr = id;
            let line = match (&self.lines, sp.instr.and_then(|i| i.source)) {
                (Some(map), Some(span)) => {
                    u64::try_from(map.get(span.source).line_col(span.start).0).unwrap_or(0)
                }
                _ => 0,
            };
            c.line.store(line, Ordering::Relaxed);
        }
    }

    fn finish(&mut self) -> Result<(), String> {
        self.counters.finished.store(1, Ordering::Relaxed);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::InstrRef;
    use crate::robot::Pose;

    #[test]
    fn the_reader_follows_the_sink() {
        let (progress, mut sink) = Progress::new(None);
        let reader = progress.clone();
        assert_eq!(reader.ticks(), 0);
        assert!(!reader.is_finished());
        let sp = Setpoint {
            time: RobotTime::from_nanos(12_000_000),
            tick: 3,
            joints: [0.0; 6],
            tcp: Pose::identity(),
            speed: 0.0,
            standstill: true,
            instr: Some(InstrRef {
                id: 1,
                name: "MoveL",
                source: None,
            }),
        };
        sink.record(&sp);
        sink.record(&sp);
        assert_eq!(reader.ticks(), 2);
        assert_eq!(reader.robot_time(), RobotTime::from_nanos(12_000_000));
        assert_eq!(reader.line(), None, "no source map");
        sink.finish().unwrap();
        assert!(reader.is_finished());

        let mut map = SourceMap::new();
        let source = map.add(
            "a.mod",
            "MODULE m\n  PROC main()\n    MoveL p, v10, fine, tool0;\n",
        );
        let (progress, mut sink) = Progress::new(Some(Arc::new(map)));
        let span = crate::source::Span {
            source,
            start: 27,
            end: 32,
        };
        let mut moving = sp;
        moving.instr = Some(InstrRef {
            id: 2,
            name: "MoveL",
            source: Some(span),
        });
        sink.record(&moving);
        assert_eq!(progress.line(), Some(3));
        moving.instr = None;
        sink.record(&moving);
        assert_eq!(progress.line(), None);
    }
}
