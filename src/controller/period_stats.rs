//! Cycle timing statistics of the real-time loop: a fixed-size histogram of the tick-period
//! error (recorded without allocation) with percentiles and a printable rendering.

use std::fmt::Write as _;
use std::time::Duration;

/// Histogram resolution (µs per bin).
const BIN_US: u64 = 1;
/// Bins: errors from 0 to 5 ms in 1 µs steps; larger ones go to the last bin (and `max`).
const BINS: usize = 5001;

/// Distribution of |actual period − nominal period| over the cycles of a run.
#[derive(Clone, Debug)]
pub struct PeriodStats {
    bins: Box<[u64]>,
    count: u64,
    max_ns: u64,
    sum_ns: u128,
    overruns: u64,
}

impl Default for PeriodStats {
    fn default() -> Self {
        PeriodStats::new()
    }
}

impl PeriodStats {
    /// Empty statistics (allocates the histogram once).
    pub fn new() -> PeriodStats {
        PeriodStats {
            bins: vec![0; BINS].into_boxed_slice(),
            count: 0,
            max_ns: 0,
            sum_ns: 0,
            overruns: 0,
        }
    }

    /// Record one period error (no allocation).
    pub fn record(&mut self, error: Duration) {
        let ns = u64::try_from(error.as_nanos()).unwrap_or(u64::MAX);
        let bin = usize::try_from(ns / 1000 / BIN_US)
            .unwrap_or(usize::MAX)
            .min(BINS - 1);
        if let Some(b) = self.bins.get_mut(bin) {
            *b += 1;
        }
        self.count += 1;
        self.max_ns = self.max_ns.max(ns);
        self.sum_ns += u128::from(ns);
    }

    /// Count a cycle that started more than one period late (ticks were skipped).
    pub fn record_overrun(&mut self) {
        self.overruns += 1;
    }

    /// Cycles recorded.
    pub fn count(&self) -> u64 {
        self.count
    }

    /// Cycles that overran a whole period.
    pub fn overruns(&self) -> u64 {
        self.overruns
    }

    /// Largest error.
    pub fn max(&self) -> Duration {
        Duration::from_nanos(self.max_ns)
    }

    /// Mean error.
    pub fn mean(&self) -> Duration {
        if self.count == 0 {
            Duration::ZERO
        } else {
            Duration::from_nanos(
                u64::try_from(self.sum_ns / u128::from(self.count)).unwrap_or(u64::MAX),
            )
        }
    }

    /// The error below which `p` (0…1) of the cycles lie (upper edge of the bin, µs steps).
    pub fn percentile(&self, p: f64) -> Duration {
        if self.count == 0 {
            return Duration::ZERO;
        }
        let want = ((self.count as f64) * p.clamp(0.0, 1.0)).ceil().max(1.0) as u64;
        let mut seen = 0;
        for (i, n) in self.bins.iter().enumerate() {
            seen += n;
            if seen >= want {
                let upper_us = (i as u64 + 1) * BIN_US;
                return Duration::from_micros(upper_us)
                    .min(self.max().max(Duration::from_micros(i as u64 * BIN_US)));
            }
        }
        self.max()
    }

    /// One line: `n=15000 mean=12µs p50=8µs p99=95µs p99.9=180µs max=410µs overruns=0`.
    pub fn summary_line(&self) -> String {
        format!(
            "n={} mean={}µs p50={}µs p99={}µs p99.9={}µs max={}µs overruns={}",
            self.count,
            self.mean().as_micros(),
            self.percentile(0.5).as_micros(),
            self.percentile(0.99).as_micros(),
            self.percentile(0.999).as_micros(),
            self.max().as_micros(),
            self.overruns
        )
    }

    /// A text histogram with logarithmic buckets (0–10 µs, 10–20, 20–50, 50–100, …), one
    /// line per bucket with a bar scaled to `width` characters.
    pub fn histogram(&self, width: usize) -> String {
        let edges_us: [u64; 13] = [
            0,
            10,
            20,
            50,
            100,
            200,
            500,
            1000,
            2000,
            5000,
            10_000,
            100_000,
            u64::MAX,
        ];
        let mut counts = [0u64; 12];
        for (i, n) in self.bins.iter().enumerate() {
            let us = i as u64 * BIN_US;
            if let Some(k) = edges_us
                .windows(2)
                .position(|w| matches!(w, [lo, hi] if us >= *lo && us < *hi))
                && let Some(c) = counts.get_mut(k)
            {
                *c += n;
            }
        }
        // Errors beyond the histogram range sit in the last bin; place them by `max`.
        let top = counts.iter().copied().max().unwrap_or(0).max(1);
        let mut out = String::new();
        for (k, n) in counts.iter().enumerate() {
            let (Some(lo), Some(hi)) = (edges_us.get(k), edges_us.get(k + 1)) else {
                continue;
            };
            if *n == 0 && *lo > self.max().as_micros() as u64 {
                continue;
            }
            let bar = "#".repeat(((*n as f64 / top as f64) * width as f64).ceil() as usize);
            let hi_text = if *hi == u64::MAX {
                "∞".to_string()
            } else {
                hi.to_string()
            };
            let _ = writeln!(out, "{lo:>6}–{hi_text:<6} µs {n:>9}  {bar}");
        }
        out
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::*;

    #[test]
    fn percentiles() {
        let mut s = PeriodStats::new();
        for i in 0..100 {
            s.record(Duration::from_micros(i));
        }
        assert_eq!(s.count(), 100);
        assert_eq!(s.max(), Duration::from_micros(99));
        assert_eq!(s.percentile(0.5), Duration::from_micros(50));
        assert_eq!(s.percentile(0.99), Duration::from_micros(99));
        s.record(Duration::from_secs(1));
        assert_eq!(s.max(), Duration::from_secs(1));
        assert!(s.histogram(20).contains("#"));
        assert!(s.summary_line().starts_with("n=101"));
    }
}
