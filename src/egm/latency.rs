//! Latency statistics without per-sample allocation: a log-linear histogram with exact min/max/mean.
//!
//! Buckets cover 0 ns to about 18 minutes with 32 sub-buckets per power of two, so a reported
//! percentile is within about 3 % of the true value (min and max are exact).

use std::time::Duration;

/// Sub-bucket bits: 2^5 = 32 sub-buckets per power of two.
const SUB_BITS: u32 = 5;
const SUB: u64 = 1 << SUB_BITS;
/// Highest power of two tracked (2^40 ns ≈ 18 min); larger values land in the last bucket.
const MAX_EXP: u32 = 40;
const BUCKETS: usize = ((MAX_EXP - SUB_BITS + 2) as usize) * (SUB as usize);

/// Histogram of durations with percentiles.
#[derive(Clone, Debug, PartialEq)]
pub struct LatencyHistogram {
    counts: Vec<u32>,
    count: u64,
    sum_ns: u128,
    min_ns: u64,
    max_ns: u64,
}

impl Default for LatencyHistogram {
    fn default() -> Self {
        LatencyHistogram::new()
    }
}

impl LatencyHistogram {
    /// An empty histogram (allocates its buckets once, here).
    pub fn new() -> Self {
        LatencyHistogram {
            counts: vec![0; BUCKETS],
            count: 0,
            sum_ns: 0,
            min_ns: u64::MAX,
            max_ns: 0,
        }
    }

    /// Adds one sample.
    pub fn record(&mut self, d: Duration) {
        let ns = u64::try_from(d.as_nanos()).unwrap_or(u64::MAX);
        if let Some(c) = self.counts.get_mut(bucket_of(ns)) {
            *c = c.saturating_add(1);
        }
        self.count += 1;
        self.sum_ns += u128::from(ns);
        self.min_ns = self.min_ns.min(ns);
        self.max_ns = self.max_ns.max(ns);
    }

    /// Number of samples.
    pub fn count(&self) -> u64 {
        self.count
    }

    /// Smallest sample.
    pub fn min(&self) -> Option<Duration> {
        (self.count > 0).then(|| Duration::from_nanos(self.min_ns))
    }

    /// Largest sample.
    pub fn max(&self) -> Option<Duration> {
        (self.count > 0).then(|| Duration::from_nanos(self.max_ns))
    }

    /// Arithmetic mean.
    pub fn mean(&self) -> Option<Duration> {
        let n = u128::from(self.count);
        (n > 0).then(|| Duration::from_nanos(u64::try_from(self.sum_ns / n).unwrap_or(u64::MAX)))
    }

    /// The `p`-th percentile (`p` in 0..=100), clamped to the exact min and max.
    pub fn percentile(&self, p: f64) -> Option<Duration> {
        if self.count == 0 || !p.is_finite() {
            return None;
        }
        let rank = ((p.clamp(0.0, 100.0) / 100.0) * self.count as f64).ceil() as u64;
        let rank = rank.max(1);
        let mut seen = 0u64;
        for (index, &c) in self.counts.iter().enumerate() {
            seen += u64::from(c);
            if seen >= rank {
                let ns = bucket_mid(index).clamp(self.min_ns, self.max_ns);
                return Some(Duration::from_nanos(ns));
            }
        }
        self.max()
    }

    /// Adds all samples of `other`.
    pub fn merge(&mut self, other: &LatencyHistogram) {
        for (a, b) in self.counts.iter_mut().zip(&other.counts) {
            *a = a.saturating_add(*b);
        }
        self.count += other.count;
        self.sum_ns += other.sum_ns;
        self.min_ns = self.min_ns.min(other.min_ns);
        self.max_ns = self.max_ns.max(other.max_ns);
    }

    /// One-line summary: `n=… p50=… p99=… max=…` (or `n=0`).
    pub fn summary(&self) -> String {
        match (self.percentile(50.0), self.percentile(99.0), self.max()) {
            (Some(p50), Some(p99), Some(max)) => format!(
                "n={} p50={} p99={} max={}",
                self.count,
                fmt_duration(p50),
                fmt_duration(p99),
                fmt_duration(max)
            ),
            _ => "n=0".to_string(),
        }
    }
}

/// Human-readable duration with a unit that fits (ns, µs, ms or s).
pub fn fmt_duration(d: Duration) -> String {
    let ns = d.as_nanos();
    if ns < 1_000 {
        format!("{ns}ns")
    } else if ns < 1_000_000 {
        format!("{:.1}µs", ns as f64 / 1e3)
    } else if ns < 1_000_000_000 {
        format!("{:.2}ms", ns as f64 / 1e6)
    } else {
        format!("{:.3}s", ns as f64 / 1e9)
    }
}

fn bucket_of(ns: u64) -> usize {
    if ns < SUB {
        return ns as usize;
    }
    let exp = (63 - ns.leading_zeros()).min(MAX_EXP);
    let ns = if exp == MAX_EXP && ns >= (1u64 << (MAX_EXP + 1)) {
        (1u64 << (MAX_EXP + 1)) - 1
    } else {
        ns
    };
    let sub = (ns >> (exp - SUB_BITS)) & (SUB - 1);
    ((exp - SUB_BITS + 1) as usize) * (SUB as usize) + sub as usize
}

/// Middle of a bucket's range, in ns.
fn bucket_mid(index: usize) -> u64 {
    let index = index as u64;
    if index < SUB {
        return index;
    }
    let exp = index / SUB + u64::from(SUB_BITS) - 1;
    let sub = index % SUB;
    let width = 1u64 << (exp - u64::from(SUB_BITS));
    (1u64 << exp) + sub * width + width / 2
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_are_within_three_percent() {
        let mut h = LatencyHistogram::new();
        for us in 1..=1000u64 {
            h.record(Duration::from_micros(us));
        }
        assert_eq!(h.count(), 1000);
        assert_eq!(h.min(), Some(Duration::from_micros(1)));
        assert_eq!(h.max(), Some(Duration::from_micros(1000)));
        let p50 = h.percentile(50.0).unwrap().as_secs_f64() * 1e6;
        let p99 = h.percentile(99.0).unwrap().as_secs_f64() * 1e6;
        assert!((p50 - 500.0).abs() / 500.0 < 0.03, "p50 {p50}");
        assert!((p99 - 990.0).abs() / 990.0 < 0.03, "p99 {p99}");
        assert_eq!(h.percentile(100.0), h.max());
        assert!((h.mean().unwrap().as_secs_f64() * 1e6 - 500.5).abs() < 1e-6);
    }

    #[test]
    fn empty_small_huge_and_merge() {
        let mut h = LatencyHistogram::default();
        assert_eq!(h.percentile(50.0), None);
        assert_eq!(h.summary(), "n=0");
        h.record(Duration::ZERO);
        h.record(Duration::from_nanos(7));
        h.record(Duration::from_secs(100_000));
        assert_eq!(h.percentile(0.0), Some(Duration::ZERO));
        assert_eq!(h.max(), Some(Duration::from_secs(100_000)));
        let mut g = LatencyHistogram::new();
        g.record(Duration::from_millis(4));
        g.merge(&h);
        assert_eq!(g.count(), 4);
        assert_eq!(g.min(), Some(Duration::ZERO));
        assert!(g.summary().starts_with("n=4 p50="));
        assert_eq!(h.percentile(f64::NAN), None);
    }

    #[test]
    fn buckets_are_monotonic_and_in_range() {
        let mut last = 0;
        let mut ns = 1u64;
        while ns < u64::MAX / 3 {
            let b = bucket_of(ns);
            assert!(b >= last && b < BUCKETS, "{ns} -> {b}");
            last = b;
            ns = ns * 3 / 2 + 1;
        }
        assert!(bucket_of(u64::MAX) < BUCKETS);
    }

    #[test]
    fn formats_durations() {
        assert_eq!(fmt_duration(Duration::from_nanos(12)), "12ns");
        assert_eq!(fmt_duration(Duration::from_micros(12)), "12.0µs");
        assert_eq!(fmt_duration(Duration::from_millis(4)), "4.00ms");
        assert_eq!(fmt_duration(Duration::from_secs(2)), "2.000s");
    }
}
