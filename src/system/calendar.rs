//! The controller's calendar: the date and time `CDate`, `CTime` and `GetTime` read.
//!
//! A controller's clock is a wall clock; rapidvc's runs on robot time, so a virtual run reads
//! the same dates every time. The calendar is a start date plus the host's seconds since the
//! program started: in virtual time that is virtual seconds, in real time elapsed wall
//! seconds. The start date is [`DEFAULT_START`] (2025-01-01 00:00:00) unless `rapidvc run
//! --date` sets another one (`--date now` takes the host's local time when the run starts).
//!
//! The clock has no time zone, as a controller's has none that RAPID sees; where a service
//! needs an absolute time ([`Calendar::unix_seconds`]) the calendar is read as UTC. Start
//! dates are limited to the years [`FIRST_YEAR`]–[`LAST_YEAR`], so that `CDate` keeps its
//! four-digit year for as long as any run can last.

use chrono::{Datelike, NaiveDateTime, TimeDelta, Timelike};

/// The start date of a run without `--date`.
pub const DEFAULT_START: &str = "2025-01-01 00:00:00";

/// How a start date is written: `YYYY-MM-DD HH:MM:SS`.
pub const FORMAT: &str = "%Y-%m-%d %H:%M:%S";

/// The earliest year a start date may have.
pub const FIRST_YEAR: i32 = 1970;

/// The latest year a start date may have.
pub const LAST_YEAR: i32 = 9000;

/// One part of the calendar time, as `GetTime` reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimePart {
    /// `\WDay`: the day of the week, 1 (Monday) to 7 (Sunday).
    WeekDay,
    /// `\Hour`: 0–23.
    Hour,
    /// `\Min`: 0–59.
    Minute,
    /// `\Sec`: 0–59.
    Second,
}

/// The controller's calendar (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Calendar {
    start: NaiveDateTime,
}

impl Default for Calendar {
    fn default() -> Self {
        Calendar::parse(DEFAULT_START).unwrap_or_else(|_| Calendar {
            start: chrono::DateTime::UNIX_EPOCH.naive_utc(),
        })
    }
}

impl Calendar {
    /// A calendar that starts at `start` (the time when the program starts), or a message
    /// when its year is outside [`FIRST_YEAR`]–[`LAST_YEAR`].
    pub fn starting_at(start: NaiveDateTime) -> Result<Calendar, String> {
        if !(FIRST_YEAR..=LAST_YEAR).contains(&start.year()) {
            return Err(format!(
                "{} is outside the years {FIRST_YEAR} to {LAST_YEAR}",
                start.format(FORMAT)
            ));
        }
        // Whole seconds: a controller's calendar (and `CTime`) counts in seconds.
        Ok(Calendar {
            start: start.with_nanosecond(0).unwrap_or(start),
        })
    }

    /// A calendar starting at `text`, written `YYYY-MM-DD HH:MM:SS` (a valid date and time
    /// of the years [`FIRST_YEAR`]–[`LAST_YEAR`]; a `T` may stand for the space, as in ISO
    /// 8601); the message names what is wrong.
    pub fn parse(text: &str) -> Result<Calendar, String> {
        let t = text.trim();
        let shape_ok = t.len() == 19
            && t.bytes().enumerate().all(|(i, b)| match i {
                4 | 7 => b == b'-',
                10 => b == b' ' || b == b'T',
                13 | 16 => b == b':',
                _ => b.is_ascii_digit(),
            });
        if !shape_ok {
            return Err(format!(
                "`{text}` is not a date and time: expected YYYY-MM-DD HH:MM:SS, e.g. `{DEFAULT_START}`"
            ));
        }
        let start = NaiveDateTime::parse_from_str(&t.replace('T', " "), FORMAT)
            .map_err(|e| format!("`{text}` is not a valid date and time ({e})"))?;
        if start.nanosecond() >= 1_000_000_000 {
            return Err(format!(
                "`{text}` is not a valid date and time (a controller's clock has no leap second)"
            ));
        }
        Calendar::starting_at(start)
    }

    /// When the program started.
    pub fn start(&self) -> NaiveDateTime {
        self.start
    }

    /// The calendar time `seconds` after the start (robot time; negative or NaN counts as
    /// 0), to the millisecond.
    pub fn at(&self, seconds: f64) -> NaiveDateTime {
        let ms = if seconds.is_finite() && seconds > 0.0 {
            // At most about 292 million years: far beyond any run, never an overflow.
            (seconds * 1e3).floor().min(9.2e18) as i64
        } else {
            0
        };
        self.start
            .checked_add_signed(TimeDelta::milliseconds(ms))
            .unwrap_or(NaiveDateTime::MAX)
    }

    /// `CDate`: `YYYY-MM-DD`.
    pub fn date_text(&self, seconds: f64) -> String {
        self.at(seconds).format("%Y-%m-%d").to_string()
    }

    /// `CTime`: `HH:MM:SS`.
    pub fn time_text(&self, seconds: f64) -> String {
        self.at(seconds).format("%H:%M:%S").to_string()
    }

    /// `GetTime`: one part of the calendar time.
    pub fn part(&self, seconds: f64, part: TimePart) -> u32 {
        let t = self.at(seconds);
        match part {
            TimePart::WeekDay => t.weekday().number_from_monday(),
            TimePart::Hour => t.hour(),
            TimePart::Minute => t.minute(),
            TimePart::Second => t.second(),
        }
    }

    /// The calendar time as seconds since 1970-01-01 00:00:00 UTC (the calendar read as UTC),
    /// for services that stamp events with an absolute time.
    pub fn unix_seconds(&self, seconds: f64) -> f64 {
        let t = self.at(seconds).and_utc();
        t.timestamp() as f64 + f64::from(t.timestamp_subsec_millis()) / 1e3
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_start_and_the_texts() {
        let c = Calendar::default();
        assert_eq!(c.start().format(FORMAT).to_string(), DEFAULT_START);
        assert_eq!(c.date_text(0.0), "2025-01-01");
        assert_eq!(c.time_text(0.0), "00:00:00");
        // 2025-01-01 was a Wednesday.
        assert_eq!(c.part(0.0, TimePart::WeekDay), 3);
        let t = 86_400.0 * 4.0 + 13.0 * 3600.0 + 7.0 * 60.0 + 9.999;
        assert_eq!(c.date_text(t), "2025-01-05");
        assert_eq!(c.time_text(t), "13:07:09");
        assert_eq!(c.part(t, TimePart::WeekDay), 7);
        assert_eq!(c.part(t, TimePart::Hour), 13);
        assert_eq!(c.part(t, TimePart::Minute), 7);
        assert_eq!(c.part(t, TimePart::Second), 9);
        assert_eq!(c.unix_seconds(0.0), 1_735_689_600.0);
        assert_eq!(c.unix_seconds(1.5), 1_735_689_601.5);
    }

    #[test]
    fn leap_year_and_year_end() {
        let c = Calendar::parse("2024-02-28 23:59:59").unwrap();
        assert_eq!(c.date_text(1.0), "2024-02-29");
        assert_eq!(c.date_text(86_401.0), "2024-03-01");
        let c = Calendar::parse("1999-12-31 23:59:58").unwrap();
        assert_eq!(c.date_text(2.0), "2000-01-01");
        assert_eq!(c.time_text(2.0), "00:00:00");
    }

    #[test]
    fn odd_times_count_as_the_start() {
        let c = Calendar::default();
        assert_eq!(c.at(-5.0), c.start());
        assert_eq!(c.at(f64::NAN), c.start());
        assert_eq!(c.at(f64::INFINITY), c.start());
        // The longest run any option allows still has a four-digit year.
        let late = Calendar::parse("9000-12-31 23:59:59").unwrap();
        assert_eq!(late.date_text(1e9).len(), 10);
    }

    #[test]
    fn start_dates_are_validated() {
        for bad in [
            "",
            "now",
            "2025-01-01",
            "2025-1-01 00:00:00",
            "2025-01-01t00:00:00",
            "2025-01-01 00:00:00 ",
            "2025-02-30 00:00:00",
            "2025-13-01 00:00:00",
            "2025-01-01 24:00:00",
            "2025-01-01 23:60:00",
            "2016-12-31 23:59:60",
            "+025-01-01 00:00:00",
            "1969-12-31 23:59:59",
            "9001-01-01 00:00:00",
            "２025-01-01 00:00:00",
        ] {
            let t = bad.trim_end();
            if t != bad {
                // Surrounding spaces are allowed.
                assert!(Calendar::parse(bad).is_ok(), "{bad:?}");
                continue;
            }
            assert!(Calendar::parse(bad).is_err(), "{bad:?}");
        }
        assert!(Calendar::parse("1970-01-01 00:00:00").is_ok());
        assert_eq!(
            Calendar::parse("2030-06-15T12:30:00"),
            Calendar::parse("2030-06-15 12:30:00")
        );
        assert!(Calendar::parse("2024-02-29 12:00:00").is_ok());
        let e = Calendar::parse("2025-02-30 00:00:00").unwrap_err();
        assert!(e.contains("not a valid date"), "{e}");
        let e = Calendar::parse("1900-01-01 00:00:00").unwrap_err();
        assert!(e.contains("1970 to 9000"), "{e}");
    }
}
