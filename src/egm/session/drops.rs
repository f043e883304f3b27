//! Why a datagram was not used ([`DropReason`]) and the run-wide totals by cause ([`DropTally`], shared by every session of a controller; [`DropCounts`], a snapshot for the end-of-run summary).

use std::fmt;
use std::sync::atomic::{AtomicU64, Ordering};

/// Why a datagram was not used.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DropReason {
    /// Not from the device's remote address and port.
    WrongSource,
    /// Longer than the limit.
    Oversized,
    /// A protobuf message cut short (its last field runs past the end of the datagram).
    Truncated,
    /// Not a valid protobuf message of the mode's type.
    Malformed,
    /// A NaN or infinite value.
    NotFinite,
    /// The mode's target or a required value is missing.
    Incomplete,
    /// Outside the configured bounds.
    OutOfRange,
    /// `header.mtype` contradicts the mode.
    WrongType,
    /// Arrived while no session was running (a late reply).
    Late,
    /// A valid reference dropped because the one-per-cycle queue was full.
    QueueOverflow,
    /// A valid reference replaced by a newer one in the same cycle (newest policy): not an
    /// error, counted apart from the drops.
    Superseded,
}

impl DropReason {
    /// Every reason, in the order of the summary.
    pub const ALL: [DropReason; 11] = [
        DropReason::WrongSource,
        DropReason::Malformed,
        DropReason::Truncated,
        DropReason::Oversized,
        DropReason::NotFinite,
        DropReason::OutOfRange,
        DropReason::Incomplete,
        DropReason::WrongType,
        DropReason::Late,
        DropReason::QueueOverflow,
        DropReason::Superseded,
    ];

    fn index(self) -> usize {
        DropReason::ALL.iter().position(|r| *r == self).unwrap_or(0)
    }

    /// How the summary names datagrams dropped for this reason.
    pub fn describe(self) -> &'static str {
        match self {
            DropReason::WrongSource => "from another sender than the device's address and port",
            DropReason::Malformed => "malformed",
            DropReason::Truncated => "truncated",
            DropReason::Oversized => "oversized",
            DropReason::NotFinite => "with NaN or infinite values",
            DropReason::OutOfRange => "out of range",
            DropReason::Incomplete => "incomplete",
            DropReason::WrongType => "of the wrong message type",
            DropReason::Late => "late (no session running)",
            DropReason::QueueOverflow => "overflowing the receive queue",
            DropReason::Superseded => "superseded by a newer one in the same cycle",
        }
    }
}

/// Datagrams not used, by cause, of every session that shares it (lock-free: sessions on
/// the motion thread count, the program side reads).
#[derive(Debug, Default)]
pub struct DropTally {
    counts: [AtomicU64; DropReason::ALL.len()],
}

impl DropTally {
    /// Counts one datagram dropped for `reason`.
    pub fn add(&self, reason: DropReason) {
        if let Some(c) = self.counts.get(reason.index()) {
            c.fetch_add(1, Ordering::Relaxed);
        }
    }

    /// The counts so far.
    pub fn snapshot(&self) -> DropCounts {
        let mut counts = DropCounts::default();
        for (slot, c) in counts.0.iter_mut().zip(&self.counts) {
            *slot = c.load(Ordering::Relaxed);
        }
        counts
    }
}

/// Datagrams not used, by cause.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DropCounts([u64; DropReason::ALL.len()]);

impl DropCounts {
    /// The count of `reason`.
    pub fn get(&self, reason: DropReason) -> u64 {
        self.0.get(reason.index()).copied().unwrap_or(0)
    }

    /// Counts one more for `reason`.
    pub fn add(&mut self, reason: DropReason) {
        if let Some(c) = self.0.get_mut(reason.index()) {
            *c = c.saturating_add(1);
        }
    }

    /// Every datagram dropped, superseded references not included (they were valid).
    pub fn dropped(&self) -> u64 {
        DropReason::ALL
            .iter()
            .filter(|r| **r != DropReason::Superseded)
            .map(|r| self.get(*r))
            .fold(0u64, u64::saturating_add)
    }
}

impl fmt::Display for DropCounts {
    /// `N datagrams dropped: a from another sender …, b malformed; c superseded …`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let total = self.dropped();
        let plural = if total == 1 { "" } else { "s" };
        write!(f, "{total} datagram{plural} dropped")?;
        let mut sep = ": ";
        for r in DropReason::ALL {
            let n = self.get(r);
            if n == 0 || r == DropReason::Superseded {
                continue;
            }
            write!(f, "{sep}{n} {}", r.describe())?;
            sep = ", ";
        }
        let superseded = self.get(DropReason::Superseded);
        if superseded > 0 {
            write!(
                f,
                "; {superseded} valid {} {}",
                if superseded == 1 {
                    "reference"
                } else {
                    "references"
                },
                DropReason::Superseded.describe()
            )?;
        }
        Ok(())
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn counts_by_cause_and_describes_them() {
        let tally = DropTally::default();
        for _ in 0..3 {
            tally.add(DropReason::WrongSource);
        }
        tally.add(DropReason::Truncated);
        tally.add(DropReason::Superseded);
        let c = tally.snapshot();
        assert_eq!(c.get(DropReason::WrongSource), 3);
        assert_eq!(c.dropped(), 4);
        assert_eq!(
            c.to_string(),
            "4 datagrams dropped: 3 from another sender than the device's address and port, \
             1 truncated; 1 valid reference superseded by a newer one in the same cycle"
        );
        assert_eq!(DropCounts::default().to_string(), "0 datagrams dropped");
    }
}
