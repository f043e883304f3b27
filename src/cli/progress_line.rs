//! The progress line of `rapidvc run` on a terminal: robot time and the line being executed,
//! redrawn in place at most four times a second once a run has taken a second of wall time.
//! Anything else written to stderr calls [`clear`] first, so lines never mix.

use std::io::Write;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crate::controller::TickSink;
use crate::motion::Setpoint;
use crate::output::{Progress, ProgressSink};
use crate::source::SourceMap;

/// True while a progress line is on the screen.
static SHOWN: AtomicBool = AtomicBool::new(false);

/// Wall time before the first line is drawn, and between redraws.
const FIRST: Duration = Duration::from_secs(1);
const EVERY: Duration = Duration::from_millis(250);
/// Cycles between looks at the wall clock.
const CHECK_EVERY: u64 = 256;

/// Erase the progress line if one is shown.
pub fn clear() {
    if SHOWN.swap(false, Ordering::Relaxed) {
        let mut err = std::io::stderr().lock();
        let _ = write!(err, "\r\x1b[K");
        let _ = err.flush();
    }
}

/// A [`TickSink`] that draws the progress line.
pub struct ProgressLine {
    progress: Progress,
    sink: ProgressSink,
    started: Instant,
    next: Instant,
    count: u64,
}

impl ProgressLine {
    /// A progress line; `lines` resolves instructions to line numbers.
    pub fn new(lines: Arc<SourceMap>) -> ProgressLine {
        let (progress, sink) = Progress::new(Some(lines));
        let now = Instant::now();
        ProgressLine {
            progress,
            sink,
            started: now,
            next: now + FIRST,
            count: 0,
        }
    }
}

impl TickSink for ProgressLine {
    fn record(&mut self, sp: &Setpoint) {
        self.sink.record(sp);
        self.count += 1;
        if !self.count.is_multiple_of(CHECK_EVERY) {
            return;
        }
        let now = Instant::now();
        if now < self.next {
            return;
        }
        self.next = now + EVERY;
        let t = self.progress.robot_time().as_secs_f64();
        let wall = now.duration_since(self.started).as_secs_f64();
        let line = self
            .progress
            .line()
            .map_or_else(String::new, |l| format!(", line {l}"));
        let mut err = std::io::stderr().lock();
        let _ = write!(
            err,
            "\r\x1b[Krobot time {t:.1} s ({:.0}× real time){line}",
            t / wall.max(1e-9)
        );
        let _ = err.flush();
        SHOWN.store(true, Ordering::Relaxed);
    }

    fn finish(&mut self) -> Result<(), String> {
        clear();
        self.sink.finish()
    }
}
