//! `--trace FILE.csv`: one row per motion cycle with time, joints, the TCP of the active tool in
//! world coordinates, TCP speed and the instruction being executed, optionally followed by EGM
//! and path-correction columns fed through a [`Feed`](crate::controller::sample_feed::Feed). Deterministic text:
//! the same run always gives the same bytes.
//!
//! # Columns
//!
//! [`TRACE_HEADER`] always comes first. [`TraceColumns`] chosen when the trace is created adds
//! groups after it (the header never changes during a run):
//!
//! | group | columns | value |
//! |---|---|---|
//! | `egm` | `egm_state` | `DISCONNECTED`, `CONNECTED` or `RUNNING`: the last state fed (it holds until the next); empty before any |
//! | `egm` | `egm_limited` | `1` when `MaxSpeedDeviation` limited the EGM speed in this cycle, `0` when not, empty without an EGM sample in this cycle |
//! | `egm_ref` | `egm_ref_1` … `egm_ref_6` | the sensor's reference in this cycle: joints (deg) in joint mode, x, y, z (mm) and rx, ry, rz (deg, Euler ZYX) in pose mode; empty without one |
//! | `pathcorr` | `path_s` | arc length along the programmed path (mm) |
//! | `pathcorr` | `corr_y`, `corr_z` | the correction applied, path frame (mm); all three empty without a path-correction sample in this cycle |
//!
//! A cycle's samples are those fed with a time after the previous row's and at or before this
//! row's; when there are several, the last counts.

use std::fmt::Write as _;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;
use std::sync::Arc;

use crate::controller::TickSink;
use crate::motion::Setpoint;
use crate::robot::units::quat_to_wxyz;
use crate::source::SourceMap;
use crate::time::RobotTime;

use super::number_format::{canonical_quat, push_fixed, push_time};
use crate::controller::sample_feed::{
    EgmAxes, EgmSample, EgmTraceState, FeedItem, FeedRx, PathCorrSample,
};

/// The header of every trace.
pub const TRACE_HEADER: [&str; 18] = [
    "time_s",
    "j1",
    "j2",
    "j3",
    "j4",
    "j5",
    "j6",
    "x",
    "y",
    "z",
    "q1",
    "q2",
    "q3",
    "q4",
    "speed_mm_s",
    "instr",
    "id",
    "line",
];

/// The `egm` column group.
const EGM_COLUMNS: [&str; 2] = ["egm_state", "egm_limited"];
/// The `egm_ref` column group.
const EGM_REF_COLUMNS: [&str; 6] = [
    "egm_ref_1",
    "egm_ref_2",
    "egm_ref_3",
    "egm_ref_4",
    "egm_ref_5",
    "egm_ref_6",
];
/// The `pathcorr` column group.
const PATHCORR_COLUMNS: [&str; 3] = ["path_s", "corr_y", "corr_z"];

/// Decimals: joints (deg), positions (mm), quaternion components, speed (mm/s).
const JOINT_DECIMALS: usize = 6;
const POS_DECIMALS: usize = 4;
const QUAT_DECIMALS: usize = 8;
const SPEED_DECIMALS: usize = 3;

/// Which column groups follow [`TRACE_HEADER`] (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct TraceColumns {
    /// `egm_state`, `egm_limited`.
    pub egm: bool,
    /// `egm_ref_1` … `egm_ref_6`.
    pub egm_ref: bool,
    /// `path_s`, `corr_y`, `corr_z`.
    pub pathcorr: bool,
}

impl TraceColumns {
    /// Only [`TRACE_HEADER`].
    pub const BASE: TraceColumns = TraceColumns {
        egm: false,
        egm_ref: false,
        pathcorr: false,
    };
    /// The EGM state and the path correction: what a run of a program using EGM shows.
    pub const EGM_AND_PATHCORR: TraceColumns = TraceColumns {
        egm: true,
        egm_ref: false,
        pathcorr: true,
    };
    /// Every group.
    pub const ALL: TraceColumns = TraceColumns {
        egm: true,
        egm_ref: true,
        pathcorr: true,
    };

    /// The full header: [`TRACE_HEADER`] followed by the chosen groups.
    pub fn header(self) -> Vec<&'static str> {
        let mut h = TRACE_HEADER.to_vec();
        if self.egm {
            h.extend(EGM_COLUMNS);
        }
        if self.egm_ref {
            h.extend(EGM_REF_COLUMNS);
        }
        if self.pathcorr {
            h.extend(PATHCORR_COLUMNS);
        }
        h
    }
}

/// The feed-driven part of a row.
struct Extras {
    columns: TraceColumns,
    feed: FeedRx,
    /// The last EGM state fed (it holds until the next).
    state: Option<EgmTraceState>,
    /// This cycle's samples.
    egm: Option<EgmSample>,
    pathcorr: Option<PathCorrSample>,
}

impl Extras {
    fn take(&mut self, now: RobotTime) {
        self.egm = None;
        self.pathcorr = None;
        let Extras {
            feed,
            state,
            egm,
            pathcorr,
            ..
        } = self;
        feed.drain_until(now, |item| match item {
            FeedItem::Egm(s) => {
                *state = Some(s.state);
                *egm = Some(s);
            }
            FeedItem::EgmState(_, s) => *state = Some(s),
            FeedItem::PathCorr(s) => *pathcorr = Some(s),
        });
    }

    fn fill<'a>(&self, it: &mut impl Iterator<Item = &'a mut String>) {
        if self.columns.egm {
            if let Some(f) = it.next()
                && let Some(s) = self.state
            {
                f.push_str(s.as_str());
            }
            if let Some(f) = it.next()
                && let Some(s) = &self.egm
            {
                f.push(if s.speed_limited { '1' } else { '0' });
            }
        }
        if self.columns.egm_ref {
            let reference = self.egm.and_then(|s| s.reference.map(|r| (s.axes, r)));
            for k in 0..6 {
                let Some(f) = it.next() else { break };
                if let Some((axes, r)) = reference
                    && let Some(v) = r.get(k).filter(|v| v.is_finite())
                {
                    let decimals = match axes {
                        EgmAxes::Joint => JOINT_DECIMALS,
                        EgmAxes::Pose => POS_DECIMALS,
                    };
                    push_fixed(f, *v, decimals);
                }
            }
        }
        if self.columns.pathcorr {
            let values = self.pathcorr.map(|s| {
                let [y, z] = s.correction();
                [s.s_mm, y, z]
            });
            for k in 0..3 {
                let Some(f) = it.next() else { break };
                if let Some(v) = values.as_ref().and_then(|v| v.get(k)) {
                    push_fixed(f, *v, POS_DECIMALS);
                }
            }
        }
    }
}

/// Writes a CSV trace (see the module docs).
pub struct TraceWriter<W: Write + Send> {
    out: csv::Writer<W>,
    lines: Option<Arc<SourceMap>>,
    fields: Vec<String>,
    extras: Option<Extras>,
    error: Option<String>,
}

impl TraceWriter<BufWriter<File>> {
    /// Create (truncate) `path`. `lines` resolves instruction spans to line numbers.
    pub fn create(path: &Path, lines: Option<Arc<SourceMap>>) -> Result<Self, String> {
        Ok(TraceWriter::new(create_file(path)?, lines))
    }

    /// [`TraceWriter::create`] with extra column groups filled from `feed`.
    pub fn create_with_feed(
        path: &Path,
        lines: Option<Arc<SourceMap>>,
        columns: TraceColumns,
        feed: FeedRx,
    ) -> Result<Self, String> {
        Ok(TraceWriter::with_feed(
            create_file(path)?,
            lines,
            columns,
            feed,
        ))
    }
}

fn create_file(path: &Path) -> Result<BufWriter<File>, String> {
    File::create(path)
        .map(BufWriter::new)
        .map_err(|e| format!("cannot create trace {}: {e}", path.display()))
}

impl<W: Write + Send> TraceWriter<W> {
    /// A trace written to `w` with the [`TRACE_HEADER`] columns (the header is written at
    /// once).
    pub fn new(w: W, lines: Option<Arc<SourceMap>>) -> Self {
        TraceWriter::build(w, lines, None)
    }

    /// A trace with [`TRACE_HEADER`] followed by the `columns` groups, whose values come from
    /// `feed` (see the module docs; the header is written at once).
    pub fn with_feed(
        w: W,
        lines: Option<Arc<SourceMap>>,
        columns: TraceColumns,
        feed: FeedRx,
    ) -> Self {
        let extras = Extras {
            columns,
            feed,
            state: None,
            egm: None,
            pathcorr: None,
        };
        TraceWriter::build(w, lines, Some(extras))
    }

    fn build(w: W, lines: Option<Arc<SourceMap>>, extras: Option<Extras>) -> Self {
        let mut out = csv::WriterBuilder::new()
            .terminator(csv::Terminator::Any(b'\n'))
            .from_writer(w);
        let header = extras
            .as_ref()
            .map_or(TraceColumns::BASE, |e| e.columns)
            .header();
        let error = out.write_record(&header).err().map(|e| e.to_string());
        TraceWriter {
            out,
            lines,
            fields: vec![String::new(); header.len()],
            extras,
            error,
        }
    }

    /// Finish and return the writer (for in-memory traces).
    pub fn into_inner(mut self) -> Result<W, String> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        self.out.into_inner().map_err(|e| e.to_string())
    }

    fn fill(&mut self, sp: &Setpoint) {
        for f in &mut self.fields {
            f.clear();
        }
        let mut it = self.fields.iter_mut();
        if let Some(f) = it.next() {
            push_time(f, sp.time);
        }
        for q in sp.joints {
            if let Some(f) = it.next() {
                push_fixed(f, q, JOINT_DECIMALS);
            }
        }
        let t = sp.tcp.translation.vector;
        for v in [t.x, t.y, t.z] {
            if let Some(f) = it.next() {
                push_fixed(f, v, POS_DECIMALS);
            }
        }
        for c in canonical_quat(quat_to_wxyz(&sp.tcp.rotation)) {
            if let Some(f) = it.next() {
                push_fixed(f, c, QUAT_DECIMALS);
            }
        }
        if let Some(f) = it.next() {
            push_fixed(f, sp.speed, SPEED_DECIMALS);
        }
        let instr = sp.instr;
        if let Some(f) = it.next() {
            f.push_str(instr.map_or("", |i| i.name));
        }
        if let Some(f) = it.next()
            && let Some(i) = instr
        {
            let _ = write!(f, "{}", i.id);
        }
        if let Some(f) = it.next()
            && let (Some(map), Some(span)) = (&self.lines, instr.and_then(|i| i.source))
        {
            let _ = write!(f, "{}", map.get(span.source).line_col(span.start).0);
        }
        if let Some(extras) = &mut self.extras {
            extras.take(sp.time);
            extras.fill(&mut it);
        }
    }
}

impl<W: Write + Send> TickSink for TraceWriter<W> {
    fn record(&mut self, sp: &Setpoint) {
        if self.error.is_some() {
            return;
        }
        self.fill(sp);
        if let Err(e) = self.out.write_record(&self.fields) {
            self.error = Some(format!("cannot write the trace: {e}"));
        }
    }

    fn finish(&mut self) -> Result<(), String> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        self.out
            .flush()
            .map_err(|e| format!("cannot write the trace: {e}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::controller::sample_feed::Feed;
    use crate::motion::InstrRef;
    use crate::robot::Pose;

    fn sp(tick: u64) -> Setpoint {
        Setpoint {
            time: RobotTime::from_nanos(tick * 4_000_000),
            tick,
            joints: [0.0, 10.0, -5.0, 0.0, 30.0, 0.0],
            tcp: Pose::identity(),
            speed: 0.0,
            standstill: false,
            instr: Some(InstrRef {
                id: 7,
                name: "EGMMoveL",
                source: None,
            }),
        }
    }

    fn text(w: TraceWriter<Vec<u8>>) -> String {
        String::from_utf8(w.into_inner().unwrap()).unwrap()
    }

    #[test]
    fn base_trace_is_unchanged() {
        let mut w = TraceWriter::new(Vec::new(), None);
        w.record(&sp(1));
        let t = text(w);
        let mut lines = t.lines();
        assert_eq!(lines.next().unwrap(), TRACE_HEADER.join(","));
        assert_eq!(
            lines.next().unwrap(),
            "0.004000,0.000000,10.000000,-5.000000,0.000000,30.000000,0.000000,\
             0.0000,0.0000,0.0000,1.00000000,0.00000000,0.00000000,0.00000000,0.000,EGMMoveL,7,"
        );
    }

    #[test]
    fn extra_columns_follow_the_feed_row_by_row() {
        let mut feed = Feed::new();
        let mut w = TraceWriter::with_feed(Vec::new(), None, TraceColumns::ALL, feed.subscribe());
        let at = |tick: u64| RobotTime::from_nanos(tick * 4_000_000);
        // Tick 1: nothing fed. Tick 2: CONNECTED. Ticks 3–4: EGM cycles (one limited, the
        // first without a reference yet), an off-grid sample belongs to the next row. Tick 5:
        // path correction only, the state holds. Tick 6: EGMReset.
        w.record(&sp(1));
        feed.push_egm_state(at(2), EgmTraceState::Connected);
        w.record(&sp(2));
        feed.push_egm_sample(
            at(3),
            EgmAxes::Joint,
            None,
            [0.0; 6],
            EgmTraceState::Running,
            false,
        );
        w.record(&sp(3));
        feed.push_egm_sample(
            RobotTime::from_nanos(at(3).as_nanos() + 1),
            EgmAxes::Pose,
            Some([1.0, -2.0, 3.0, f64::NAN, -0.0, 180.0]),
            [0.0; 6],
            EgmTraceState::Running,
            true,
        );
        feed.push_pathcorr_sample(at(5), 12.5, [0.0, 1.0], [3.0, -1.0], Some([3.0, -2.0]));
        w.record(&sp(4));
        w.record(&sp(5));
        feed.push_egm_state(at(6), EgmTraceState::Disconnected);
        w.record(&sp(6));
        let t = text(w);
        let rows: Vec<Vec<&str>> = t.lines().map(|l| l.split(',').collect()).collect();
        let header = rows.first().unwrap();
        assert_eq!(header.get(..18).unwrap(), TRACE_HEADER);
        assert_eq!(
            header.get(18..).unwrap(),
            [
                "egm_state",
                "egm_limited",
                "egm_ref_1",
                "egm_ref_2",
                "egm_ref_3",
                "egm_ref_4",
                "egm_ref_5",
                "egm_ref_6",
                "path_s",
                "corr_y",
                "corr_z"
            ]
        );
        let extra = |row: usize| rows.get(row).unwrap().get(18..).unwrap().join(",");
        assert!(rows.iter().all(|r| r.len() == 29));
        assert_eq!(extra(1), ",,,,,,,,,,");
        assert_eq!(extra(2), "CONNECTED,,,,,,,,,,");
        assert_eq!(extra(3), "RUNNING,0,,,,,,,,,");
        assert_eq!(
            extra(4),
            "RUNNING,1,1.0000,-2.0000,3.0000,,0.0000,180.0000,,,"
        );
        assert_eq!(extra(5), "RUNNING,,,,,,,,12.5000,3.0000,-2.0000");
        assert_eq!(extra(6), "DISCONNECTED,,,,,,,,,,");
    }

    #[test]
    fn groups_can_be_chosen() {
        let mut feed = Feed::new();
        let columns = TraceColumns {
            egm: false,
            egm_ref: false,
            pathcorr: true,
        };
        let mut w = TraceWriter::with_feed(Vec::new(), None, columns, feed.subscribe());
        feed.push_pathcorr_sample(RobotTime::ZERO, 0.0, [0.0; 2], [0.25, 0.5], None);
        w.record(&sp(0));
        let t = text(w);
        let mut lines = t.lines();
        assert!(
            lines
                .next()
                .unwrap()
                .ends_with(",line,path_s,corr_y,corr_z")
        );
        assert!(
            lines
                .next()
                .unwrap()
                .ends_with(",EGMMoveL,7,,0.0000,0.2500,0.5000")
        );
        assert_eq!(
            TraceColumns::EGM_AND_PATHCORR.header().len(),
            TRACE_HEADER.len() + 5
        );
    }
}
