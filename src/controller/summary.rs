//! The end-of-run summary: simulated time, wall time, real-time factor, final joints, and the
//! cycle timing of real-time runs.

use std::fmt;
use std::time::Duration;

use crate::robot::JointsDeg;

use super::period_stats::PeriodStats;

/// What a run did, for the one-line summary the CLI prints at the end.
#[derive(Clone, Debug)]
pub struct RunSummary {
    /// Robot time at the end.
    pub simulated: Duration,
    /// Wall-clock time of the run.
    pub wall: Duration,
    /// Motion cycles executed.
    pub ticks: u64,
    /// Axis values at the end (deg).
    pub final_joints: JointsDeg,
    /// True for a real-time run.
    pub realtime: bool,
    /// Cycle-period statistics of a real-time run.
    pub period_stats: Option<PeriodStats>,
    /// Setpoints the recorder thread could not take in time (real time only).
    pub dropped_records: u64,
}

impl RunSummary {
    /// Simulated seconds per wall second.
    pub fn realtime_factor(&self) -> f64 {
        let wall = self.wall.as_secs_f64();
        if wall > 0.0 {
            self.simulated.as_secs_f64() / wall
        } else {
            f64::INFINITY
        }
    }
}

impl fmt::Display for RunSummary {
    /// `simulated 12.344 s in 0.011 s wall (1122× real time), 3086 cycles; final joints [83.50, 0.08, -0.34, 0.10, 39.07, -0.14]`
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let factor = self.realtime_factor();
        let factor_text = if factor.is_finite() {
            if factor >= 10.0 {
                format!("{factor:.0}")
            } else {
                format!("{factor:.2}")
            }
        } else {
            "∞".to_string()
        };
        write!(
            f,
            "simulated {:.3} s in {:.3} s wall ({factor_text}× real time), {} cycles; final joints [",
            self.simulated.as_secs_f64(),
            self.wall.as_secs_f64(),
            self.ticks
        )?;
        for (i, q) in self.final_joints.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            let text = format!("{q:.2}");
            // Never print "-0.00".
            f.write_str(
                text.strip_prefix('-')
                    .filter(|t| *t == "0.00")
                    .unwrap_or(&text),
            )?;
        }
        f.write_str("]")?;
        if let Some(s) = &self.period_stats {
            write!(f, "; period error {}", s.summary_line())?;
        }
        if self.dropped_records > 0 {
            write!(f, "; {} trace rows dropped", self.dropped_records)?;
        }
        Ok(())
    }
}
