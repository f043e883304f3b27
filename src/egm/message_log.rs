//! The EGM message log behind `--egm-log FILE.csv`: one [`LogRow`] per message, kept in a bounded [`LogRing`] by the driver and written by [`EgmLogWriter`] outside the real-time tick.
//!
//! # Rows
//!
//! One row per `EgmRobot` sent (UdpUc and built-in devices) or per signal sample (signal
//! sources), completed with the sensor's reply when one arrives before the next message:
//!
//! | column | meaning |
//! |---|---|
//! | `identity` | the EGM identity's variable name |
//! | `kind` | `joint`, `pose`, `stream` or `pathcorr` |
//! | `send_time_s` | controller time the message was sent (the signals read), s |
//! | `recv_time_s` | when the reply arrived (empty: no reply before the next message; for signals the read time) |
//! | `seqno` | `header.seqno` of the message (the sample number for signals) |
//! | `ref_1` … `ref_6` | the reference of the reply: joints in degrees (`joint`), the sensor pose x, y, z in mm and rx, ry, rz in degrees, Euler ZYX (`pose`), or the correction x, y, z in mm and its age in ms, then two zeros (`pathcorr`); empty without a reply |
//! | `fb_1` … `fb_6` | the feedback sent: measured joints in degrees (`joint`, `stream`, `pathcorr`), or the measured TCP in the correction frame, x, y, z mm and rx, ry, rz degrees ZYX (`pose`) |
//! | `state` | the run's phase: `running`, `holding`, `ramping_down`, `halting`, `done`; `streaming`; `correcting` |
//! | `utilization_pct` | `utilizationRate` sent |
//!
//! # Real-time use
//!
//! The driver pushes rows into its [`LogRing`] (preallocated, no allocation per row; when
//! full the oldest row is dropped and counted). The controller's shell takes them with
//! `pop_log()` after a tick and hands them to an [`EgmLogWriter`] on a thread that may
//! block on the file (or writes them directly when it runs in virtual time).

use crate::time::RobotTime;
use std::collections::VecDeque;
use std::io::Write;

/// The CSV header.
pub const LOG_COLUMNS: [&str; 19] = [
    "identity",
    "kind",
    "send_time_s",
    "recv_time_s",
    "seqno",
    "ref_1",
    "ref_2",
    "ref_3",
    "ref_4",
    "ref_5",
    "ref_6",
    "fb_1",
    "fb_2",
    "fb_3",
    "fb_4",
    "fb_5",
    "fb_6",
    "state",
    "utilization_pct",
];

/// Default capacity of a driver's ring (about 4 s of messages at 4 ms).
pub const DEFAULT_LOG_CAPACITY: usize = 1024;

/// What produced a row.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LogKind {
    /// Joint-mode guidance.
    Joint,
    /// Pose-mode guidance.
    Pose,
    /// A position stream.
    Stream,
    /// Path correction (EGMMoveL/EGMMoveC).
    PathCorr,
}

impl LogKind {
    /// The `kind` column's text.
    pub fn as_str(self) -> &'static str {
        match self {
            LogKind::Joint => "joint",
            LogKind::Pose => "pose",
            LogKind::Stream => "stream",
            LogKind::PathCorr => "pathcorr",
        }
    }
}

/// One logged message (plain data, `Copy`; the identity name lives in the ring).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LogRow {
    /// What produced it.
    pub kind: LogKind,
    /// When the message was sent.
    pub send_time: RobotTime,
    /// When its reply arrived.
    pub recv_time: Option<RobotTime>,
    /// `header.seqno` (or sample number).
    pub seqno: u32,
    /// The reply's reference (see the module docs for units).
    pub reference: Option<[f64; 6]>,
    /// The feedback sent.
    pub feedback: [f64; 6],
    /// The run's phase (`running`, …).
    pub state: &'static str,
    /// `utilizationRate`, percent.
    pub utilization: f64,
}

/// A bounded queue of rows; the oldest row is dropped (and counted) when it is full.
#[derive(Clone, Debug)]
pub struct LogRing {
    identity: String,
    rows: VecDeque<LogRow>,
    capacity: usize,
    dropped: u64,
}

impl LogRing {
    /// A ring for identity `identity` holding at most `capacity` rows (0: logging off).
    pub fn new(identity: &str, capacity: usize) -> LogRing {
        LogRing {
            identity: identity.to_string(),
            rows: VecDeque::with_capacity(capacity),
            capacity,
            dropped: 0,
        }
    }

    /// The identity's name (the `identity` column).
    pub fn identity(&self) -> &str {
        &self.identity
    }

    /// Appends a row, dropping the oldest when full.
    pub fn push(&mut self, row: LogRow) {
        if self.capacity == 0 {
            return;
        }
        if self.rows.len() >= self.capacity {
            self.rows.pop_front();
            self.dropped += 1;
        }
        self.rows.push_back(row);
    }

    /// The oldest row.
    pub fn pop(&mut self) -> Option<LogRow> {
        self.rows.pop_front()
    }

    /// Rows waiting.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// True when no row waits.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// Rows dropped because the ring was full (the shell did not drain it in time).
    pub fn dropped(&self) -> u64 {
        self.dropped
    }
}

/// Writes rows as CSV with the header of [`LOG_COLUMNS`].
pub struct EgmLogWriter<W: Write> {
    csv: csv::Writer<W>,
}

impl<W: Write> std::fmt::Debug for EgmLogWriter<W> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("EgmLogWriter")
    }
}

impl<W: Write> EgmLogWriter<W> {
    /// A writer on `out`; writes the header line.
    pub fn new(out: W) -> csv::Result<Self> {
        let mut csv = csv::Writer::from_writer(out);
        csv.write_record(LOG_COLUMNS)?;
        Ok(EgmLogWriter { csv })
    }

    /// Writes one row of identity `identity`.
    pub fn write_row(&mut self, identity: &str, row: &LogRow) -> csv::Result<()> {
        let mut record: Vec<String> = Vec::with_capacity(LOG_COLUMNS.len());
        record.push(identity.to_string());
        record.push(row.kind.as_str().to_string());
        record.push(secs(row.send_time));
        record.push(row.recv_time.map(secs).unwrap_or_default());
        record.push(row.seqno.to_string());
        match &row.reference {
            Some(r) => record.extend(r.iter().map(|v| num(*v))),
            None => record.extend(std::iter::repeat_n(String::new(), 6)),
        }
        record.extend(row.feedback.iter().map(|v| num(*v)));
        record.push(row.state.to_string());
        record.push(num(row.utilization));
        self.csv.write_record(&record)
    }

    /// Writes and removes every row waiting in `ring`; returns how many.
    pub fn drain(&mut self, ring: &mut LogRing) -> csv::Result<usize> {
        let mut n = 0;
        while let Some(row) = ring.pop() {
            let identity = ring.identity.clone();
            self.write_row(&identity, &row)?;
            n += 1;
        }
        Ok(n)
    }

    /// Flushes the underlying writer.
    pub fn flush(&mut self) -> std::io::Result<()> {
        self.csv.flush()
    }

    /// Flushes and returns the underlying writer.
    pub fn into_inner(self) -> Result<W, std::io::Error> {
        self.csv.into_inner().map_err(|e| e.into_error())
    }
}

/// Seconds with microsecond resolution.
fn secs(t: RobotTime) -> String {
    let d = t.since_start();
    format!("{}.{:06}", d.as_secs(), d.subsec_micros())
}

/// A value with 6 decimals (mm, degrees, percent); NaN never occurs in sent data.
fn num(v: f64) -> String {
    format!("{v:.6}")
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing)]

    use super::*;

    fn row(seqno: u32) -> LogRow {
        LogRow {
            kind: LogKind::Joint,
            send_time: RobotTime::from_nanos(1_000 * (4_000 * u64::from(seqno) + 1)),
            recv_time: seqno
                .is_multiple_of(2)
                .then(|| RobotTime::from_millis(4 * u64::from(seqno) + 1)),
            seqno,
            reference: seqno
                .is_multiple_of(2)
                .then_some([1.0, 2.0, 3.0, 4.0, 5.0, 6.5]),
            feedback: [0.0, -1.25, 0.0, 0.0, 30.0, 0.0],
            state: "running",
            utilization: 12.5,
        }
    }

    #[test]
    fn ring_is_bounded_and_counts_drops() {
        let mut ring = LogRing::new("egmID1", 3);
        for i in 0..5 {
            ring.push(row(i));
        }
        assert_eq!(ring.len(), 3);
        assert_eq!(ring.dropped(), 2);
        assert_eq!(ring.pop().unwrap().seqno, 2, "the oldest were dropped");
        let mut off = LogRing::new("x", 0);
        off.push(row(0));
        assert!(off.is_empty());
    }

    #[test]
    fn csv_has_one_line_per_row_with_empty_reply_columns() {
        let mut ring = LogRing::new("egmID1", 8);
        ring.push(row(0));
        ring.push(row(1));
        let mut w = EgmLogWriter::new(Vec::new()).unwrap();
        assert_eq!(w.drain(&mut ring).unwrap(), 2);
        let text = String::from_utf8(w.into_inner().unwrap()).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3);
        assert_eq!(lines[0], LOG_COLUMNS.join(","));
        assert_eq!(
            lines[1],
            "egmID1,joint,0.000001,0.001000,0,1.000000,2.000000,3.000000,4.000000,5.000000,6.500000,0.000000,-1.250000,0.000000,0.000000,30.000000,0.000000,running,12.500000"
        );
        assert!(
            lines[2].starts_with("egmID1,joint,0.004001,,1,,,,,,,0.000000"),
            "{}",
            lines[2]
        );
    }
}
