//! The numeric command-line options and their ranges: every real-valued option is parsed by
//! one of the value parsers here, so an absurd value (`--max-time 1e20`, `nan`, `-3`) is a
//! clap usage error (exit 2) naming the option and its range before anything runs, and
//! every accepted value converts to a `Duration` (or whatever the option feeds) without
//! overflow. Integer options use clap's own ranged parsers at their definitions.
//!
//! The ranges are documented in the README ("Option ranges"); change both together.

use crate::motion::settings::PERIOD_RANGE;

/// A closed interval of accepted values and the unit it is written in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    /// Smallest value (included).
    pub lo: f64,
    /// Largest value (included).
    pub hi: f64,
    /// What the number counts (`seconds`, `ms`, …).
    pub unit: &'static str,
}

impl Range {
    /// Whether `x` lies in the range (never true for NaN).
    pub fn contains(&self, x: f64) -> bool {
        x >= self.lo && x <= self.hi
    }

    /// `s` as a number in this range, or a message naming the range.
    pub fn parse(&self, s: &str) -> Result<f64, String> {
        let x: f64 = s
            .trim()
            .parse()
            .map_err(|_| format!("`{s}` is not a number ({})", self.describe()))?;
        if self.contains(x) {
            Ok(x)
        } else {
            Err(format!("{s} is out of range: {}", self.describe()))
        }
    }

    /// "expected seconds from 0.001 to 1000000000".
    pub fn describe(&self) -> String {
        format!("expected {} from {} to {}", self.unit, self.lo, self.hi)
    }
}

/// The shortest time an option takes: one millisecond (a shorter one would round to no time
/// at all in some of the durations it feeds).
pub const MIN_SECONDS: f64 = 0.001;

/// The longest time limit: about 31.7 years (`--max-time`, `sensor --duration`).
pub const MAX_SECONDS: f64 = 1e9;

/// `run --max-time S`: how far a wait may reach (robot time, or wall time with `--realtime`).
pub const MAX_TIME: Range = Range {
    lo: MIN_SECONDS,
    hi: MAX_SECONDS,
    unit: "seconds",
};

/// `run --period MS`: the motion cycle.
pub const PERIOD_MS: Range = Range {
    lo: PERIOD_RANGE.0.as_micros() as f64 / 1e3,
    hi: PERIOD_RANGE.1.as_micros() as f64 / 1e3,
    unit: "milliseconds",
};

/// `run --lockstep-timeout MS`: the longest wait for one sensor reply (10 minutes).
pub const LOCKSTEP_TIMEOUT_MS: std::ops::RangeInclusive<u64> = 1..=600_000;

/// `bench virtual --seconds S`: simulated time (about 11.6 days).
pub const BENCH_VIRTUAL_SECONDS: Range = Range {
    lo: MIN_SECONDS,
    hi: 1e6,
    unit: "seconds",
};

/// `bench realtime|egm --seconds S`: wall time (one day).
pub const BENCH_WALL_SECONDS: Range = Range {
    lo: MIN_SECONDS,
    hi: 86_400.0,
    unit: "seconds",
};

/// `bench realtime --load N`: busy-loop processes.
pub const BENCH_LOAD: std::ops::RangeInclusive<i64> = 0..=256;

/// `bench realtime --spin-us US`: at most one 4 ms motion cycle.
pub const BENCH_SPIN_US: std::ops::RangeInclusive<u64> = 0..=4_000;

/// `sensor --duration S`.
pub const SENSOR_DURATION: Range = Range {
    lo: MIN_SECONDS,
    hi: MAX_SECONDS,
    unit: "seconds",
};

/// `sensor --amplitude`, `--y`, `--z`: degrees or millimetres, either sign (1 km at most).
pub const SENSOR_OFFSET: Range = Range {
    lo: -1e6,
    hi: 1e6,
    unit: "a number (degrees or mm)",
};

/// `sensor --radius MM`.
pub const SENSOR_RADIUS: Range = Range {
    lo: 0.0,
    hi: 1e6,
    unit: "millimetres",
};

/// `sensor --frequency HZ` (the EGM cycle is at most 250 Hz; 1 kHz leaves room).
pub const SENSOR_FREQUENCY: Range = Range {
    lo: 0.0,
    hi: 1_000.0,
    unit: "hertz",
};

/// `sensor --ramp-time S`.
pub const SENSOR_RAMP_TIME: Range = Range {
    lo: MIN_SECONDS,
    hi: 1e6,
    unit: "seconds",
};

/// Value parser of `--max-time`.
pub fn max_time(s: &str) -> Result<f64, String> {
    MAX_TIME.parse(s)
}

/// Value parser of `--period`.
pub fn period_ms(s: &str) -> Result<f64, String> {
    PERIOD_MS.parse(s)
}

/// Value parser of `bench virtual --seconds`.
pub fn bench_virtual_seconds(s: &str) -> Result<f64, String> {
    BENCH_VIRTUAL_SECONDS.parse(s)
}

/// Value parser of `bench realtime|egm --seconds`.
pub fn bench_wall_seconds(s: &str) -> Result<f64, String> {
    BENCH_WALL_SECONDS.parse(s)
}

/// Value parser of `sensor --duration`.
pub fn sensor_duration(s: &str) -> Result<f64, String> {
    SENSOR_DURATION.parse(s)
}

/// Value parser of `sensor --amplitude`, `--y`, `--z`.
pub fn sensor_offset(s: &str) -> Result<f64, String> {
    SENSOR_OFFSET.parse(s)
}

/// Value parser of `sensor --radius`.
pub fn sensor_radius(s: &str) -> Result<f64, String> {
    SENSOR_RADIUS.parse(s)
}

/// Value parser of `sensor --frequency`.
pub fn sensor_frequency(s: &str) -> Result<f64, String> {
    SENSOR_FREQUENCY.parse(s)
}

/// Value parser of `sensor --ramp-time`.
pub fn sensor_ramp_time(s: &str) -> Result<f64, String> {
    SENSOR_RAMP_TIME.parse(s)
}

/// Value parser of `run --date`: the controller's calendar at the start of the run, written
/// `YYYY-MM-DD HH:MM:SS` (years 1970 to 9000), or `now`: the host's local time when the
/// command line is read. This is the only place rapidvc reads the host's calendar.
pub fn start_date(s: &str) -> Result<crate::system::calendar::Calendar, String> {
    use crate::system::calendar::Calendar;
    if s.trim().eq_ignore_ascii_case("now") {
        return Calendar::starting_at(chrono::Local::now().naive_local());
    }
    Calendar::parse(s).map_err(|e| format!("{e}, or `now`"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_accept_their_bounds_and_refuse_the_rest() {
        assert_eq!(max_time("86400"), Ok(86_400.0));
        assert_eq!(max_time("1e9"), Ok(1e9));
        for bad in ["0", "1e-300", "-1", "1e20", "1e30", "nan", "inf", "", "5s"] {
            let e = max_time(bad).expect_err(bad);
            assert!(e.contains("seconds"), "{bad}: {e}");
        }
        assert_eq!(period_ms("0.1"), Ok(0.1));
        assert_eq!(period_ms("100"), Ok(100.0));
        assert!(period_ms("0.09").is_err() && period_ms("101").is_err());
        assert!(sensor_frequency("0").is_ok() && sensor_frequency("-1").is_err());
        assert!(sensor_offset("-20").is_ok() && sensor_offset("1e7").is_err());
    }

    #[test]
    fn start_dates() {
        let c = start_date("2030-06-15 12:30:00").unwrap();
        assert_eq!(c.date_text(0.0), "2030-06-15");
        assert!(start_date(" NOW ").is_ok());
        for bad in [
            "",
            "tomorrow",
            "2030-06-15",
            "2030-02-30 00:00:00",
            "1900-01-01 00:00:00",
        ] {
            let e = start_date(bad).expect_err(bad);
            assert!(e.ends_with("or `now`"), "{bad}: {e}");
        }
    }
}
