//! What the view keeps of a run: the motion cycles thinned to what the page can draw within
//! a tolerance (see [`super::decimate`]), the instructions, the TP output and events with
//! their robot time, the EGM samples and states, and the path-correction samples with the
//! programmed and corrected paths in world coordinates.

use std::collections::HashMap;

use crate::interp::Output;
use crate::motion::Setpoint;
use crate::output::{EgmAxes, EgmSample, EgmTraceState, FeedItem, PathCorrSample};
use crate::source::SourceMap;

use super::decimate::Thinner;

/// Tolerance of the drawn axis values (deg).
pub const JOINT_TOL_DEG: f64 = 0.01;
/// Tolerance of the drawn TCP position (mm).
pub const TCP_TOL_MM: f64 = 0.1;
/// Tolerance of the drawn TCP orientation (quaternion components).
pub const QUAT_TOL: f64 = 5e-4;
/// Tolerance of the EGM curves (deg or mm) and of the path-correction curves (mm).
pub const CURVE_TOL: f64 = 0.01;
/// The longest time between two kept rows (s): speed colours and flags are sampled at least
/// this often.
pub const MAX_GAP_S: f64 = 0.5;

/// Robot time in µs (the page's time unit).
pub type Micros = i64;

fn micros(sp_time: crate::time::RobotTime) -> Micros {
    i64::try_from(sp_time.as_nanos() / 1000).unwrap_or(i64::MAX)
}

/// One motion cycle as the page draws it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row {
    /// Robot time (µs).
    pub t: Micros,
    /// Axis values (deg).
    pub joints: [f64; 6],
    /// TCP of the active tool in world (mm).
    pub tcp: [f64; 3],
    /// Its orientation `[w, x, y, z]`, continuous from row to row (no sign flips).
    pub quat: [f64; 4],
    /// TCP speed (mm/s).
    pub speed: f64,
    /// Index into [`Recording::instrs`], `-1` when idle.
    pub instr: i32,
}

/// A move (or EGM) instruction the robot executed.
#[derive(Clone, Debug, PartialEq)]
pub struct InstrInfo {
    /// The controller's number of the instruction in the run.
    pub id: u64,
    /// `MoveL`, `EGMMoveL`, …
    pub name: &'static str,
    /// Index into the page's files; `-1` when unknown.
    pub file: i32,
    /// Source line (1-based); 0 when unknown.
    pub line: u32,
}

/// What a log entry is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LogKind {
    /// A `TPWrite` line.
    Tp,
    /// `TPErase`.
    TpErase,
    /// An event (motion, EGM, interrupt queue …).
    Event,
    /// An `ErrWrite` entry (error).
    ErrWrite,
    /// An `ErrWrite \W` entry (warning).
    ErrWriteWarning,
    /// How the program ended.
    End,
}

impl LogKind {
    /// The page's name for the kind.
    pub fn as_str(self) -> &'static str {
        match self {
            LogKind::Tp => "tp",
            LogKind::TpErase => "erase",
            LogKind::Event => "event",
            LogKind::ErrWrite => "error",
            LogKind::ErrWriteWarning => "warning",
            LogKind::End => "end",
        }
    }
}

/// One line of TP output or of the event log, with the robot time it appeared at.
#[derive(Clone, Debug, PartialEq)]
pub struct LogEntry {
    /// Robot time (µs).
    pub t: Micros,
    /// What it is.
    pub kind: LogKind,
    /// The text.
    pub text: String,
}

impl LogEntry {
    /// The entry for a program output at `t`.
    pub fn from_output(t: Micros, o: &Output) -> LogEntry {
        let (kind, text) = match o {
            Output::TpWrite(s) => (LogKind::Tp, s.clone()),
            Output::TpErase => (LogKind::TpErase, String::new()),
            Output::ErrWrite {
                warning,
                header,
                reason,
            } => (
                if *warning {
                    LogKind::ErrWriteWarning
                } else {
                    LogKind::ErrWrite
                },
                format!("{header}: {}", reason.join(" ")),
            ),
            Output::Event(e) => (LogKind::Event, e.clone()),
        };
        LogEntry { t, kind, text }
    }
}

/// One EGM cycle as the page draws it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EgmRow {
    /// Robot time (µs).
    pub t: Micros,
    /// Joint or pose values.
    pub axes: EgmAxes,
    /// The sensor's reference (`None` before the first).
    pub reference: Option<[f64; 6]>,
    /// The feedback.
    pub feedback: [f64; 6],
    /// The identity's state.
    pub state: EgmTraceState,
    /// `MaxSpeedDeviation` limited the speed.
    pub limited: bool,
}

/// One path-correction cycle with the paths in world coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathRow {
    /// Robot time (µs).
    pub t: Micros,
    /// Arc length along the programmed path (mm).
    pub s: f64,
    /// The correction applied in the path frame: y, z (mm).
    pub corr: [f64; 2],
    /// The seam as measured at `s`, path frame y, z (mm).
    pub measured: Option<[f64; 2]>,
    /// The programmed TCP in world (mm): the corrected one less the correction.
    pub programmed: [f64; 3],
    /// The corrected TCP in world (mm).
    pub corrected: [f64; 3],
    /// The first cycle of a corrected sequence.
    pub start: bool,
}

/// Everything the page shows, as recorded so far.
#[derive(Clone, Debug)]
pub struct Recording {
    /// Kept motion cycles, in time order.
    pub rows: Vec<Row>,
    /// The instructions the rows point at.
    pub instrs: Vec<InstrInfo>,
    /// TP output and events, in the order they appeared.
    pub log: Vec<LogEntry>,
    /// Kept EGM cycles.
    pub egm: Vec<EgmRow>,
    /// EGM state changes (µs, state).
    pub egm_states: Vec<(Micros, EgmTraceState)>,
    /// Kept path-correction cycles; a new corrected sequence starts where the time between
    /// two rows exceeds two motion cycles.
    pub pathcorr: Vec<PathRow>,
    /// Robot time of the last cycle seen (µs).
    pub now: Micros,
    /// The run is over.
    pub finished: bool,
    thin: Thinner<Row, 13>,
    egm_thin: Thinner<EgmRow, 12>,
    path_thin: Thinner<PathRow, 8>,
    instr_index: HashMap<u64, i32>,
    last_row: Option<Row>,
    last_egm: Option<EgmRow>,
    last_path: Option<PathRow>,
    period_us: Micros,
}

impl Recording {
    /// An empty recording for a controller with motion cycle `period_us`.
    pub fn new(period_us: Micros) -> Recording {
        let j = JOINT_TOL_DEG;
        let p = TCP_TOL_MM;
        let q = QUAT_TOL;
        let c = CURVE_TOL;
        Recording {
            rows: Vec::new(),
            instrs: Vec::new(),
            log: Vec::new(),
            egm: Vec::new(),
            egm_states: Vec::new(),
            pathcorr: Vec::new(),
            now: 0,
            finished: false,
            thin: Thinner::new([j, j, j, j, j, j, p, p, p, q, q, q, q], MAX_GAP_S),
            egm_thin: Thinner::new([c; 12], MAX_GAP_S),
            path_thin: Thinner::new([p, p, p, p, p, p, c, c], MAX_GAP_S),
            instr_index: HashMap::new(),
            last_row: None,
            last_egm: None,
            last_path: None,
            period_us: period_us.max(1),
        }
    }

    /// The index of the instruction of `sp` (registered on first sight).
    fn instr(&mut self, sp: &Setpoint, lines: Option<&SourceMap>, files: &[u32]) -> i32 {
        let Some(i) = sp.instr else {
            return -1;
        };
        if let Some(&k) = self.instr_index.get(&i.id) {
            return k;
        }
        let (file, line) = match (lines, i.source) {
            (Some(map), Some(span)) => (
                files
                    .iter()
                    .position(|&f| f == span.source.0)
                    .and_then(|k| i32::try_from(k).ok())
                    .unwrap_or(-1),
                u32::try_from(map.get(span.source).line_col(span.start).0).unwrap_or(0),
            ),
            _ => (-1, 0),
        };
        let k = i32::try_from(self.instrs.len()).unwrap_or(i32::MAX);
        self.instrs.push(InstrInfo {
            id: i.id,
            name: i.name,
            file,
            line,
        });
        self.instr_index.insert(i.id, k);
        k
    }

    /// One motion cycle. `lines` and `files` (the source ids of the page's files) place the
    /// instruction in the source. Returns the row.
    pub fn record(&mut self, sp: &Setpoint, lines: Option<&SourceMap>, files: &[u32]) -> Row {
        let instr = self.instr(sp, lines, files);
        let t = micros(sp.time);
        let p = sp.tcp.translation.vector;
        let r = &sp.tcp.rotation;
        let mut quat = [r.w, r.i, r.j, r.k];
        if let Some(prev) = &self.last_row {
            let dot: f64 = quat.iter().zip(&prev.quat).map(|(a, b)| a * b).sum();
            if dot < 0.0 {
                quat = quat.map(|c| -c);
            }
        }
        let row = Row {
            t,
            joints: sp.joints,
            tcp: [p.x, p.y, p.z],
            quat,
            speed: sp.speed,
            instr,
        };
        let force = self.last_row.is_none_or(|prev| {
            prev.instr != row.instr || (prev.speed == 0.0) != (row.speed == 0.0)
        });
        let [j1, j2, j3, j4, j5, j6] = row.joints;
        let [x, y, z] = row.tcp;
        let [qw, qx, qy, qz] = row.quat;
        let values = [j1, j2, j3, j4, j5, j6, x, y, z, qw, qx, qy, qz];
        self.thin
            .offer(row, t as f64 * 1e-6, values, force, &mut self.rows);
        self.last_row = Some(row);
        self.now = t;
        row
    }

    /// One item of the EGM/path-correction feed, taken when the row of its time is recorded
    /// (`row` is that row: it gives the corrected TCP and the tool's orientation).
    pub fn absorb(&mut self, item: FeedItem, row: Option<&Row>) {
        match item {
            FeedItem::Egm(s) => self.egm_sample(&s),
            FeedItem::EgmState(t, state) => self.egm_state(micros(t), state),
            FeedItem::PathCorr(s) => {
                if let Some(row) = row.filter(|r| r.t == micros(s.t)) {
                    self.path_sample(&s, row);
                }
            }
        }
    }

    fn egm_state(&mut self, t: Micros, state: EgmTraceState) {
        if self.egm_states.last().map(|(_, s)| *s) != Some(state) {
            self.egm_states.push((t, state));
        }
    }

    fn egm_sample(&mut self, s: &EgmSample) {
        let t = micros(s.t);
        self.egm_state(t, s.state);
        let row = EgmRow {
            t,
            axes: s.axes,
            reference: s.reference,
            feedback: s.feedback,
            state: s.state,
            limited: s.speed_limited,
        };
        let force = self.last_egm.is_none_or(|p| {
            p.axes != row.axes
                || p.state != row.state
                || p.limited != row.limited
                || p.reference.is_some() != row.reference.is_some()
                || row.t - p.t > 2 * self.period_us.max(4000)
        });
        let r = row.reference.unwrap_or([0.0; 6]);
        let f = row.feedback;
        let values = [
            r[0], r[1], r[2], r[3], r[4], r[5], f[0], f[1], f[2], f[3], f[4], f[5],
        ];
        self.egm_thin
            .offer(row, t as f64 * 1e-6, values, force, &mut self.egm);
        self.last_egm = Some(row);
    }

    /// A path-correction sample: the corrected TCP is the row's, the programmed one that
    /// less the correction in world coordinates. Samples without the world offset (from a
    /// producer that does not know it) are not drawn.
    fn path_sample(&mut self, s: &PathCorrSample, row: &Row) {
        let Some(offset) = s.offset_world else {
            return;
        };
        let t = micros(s.t);
        let new_sequence = self.last_path.is_none_or(|p| t - p.t > 2 * self.period_us);
        let corr = s.correction();
        let [cx, cy, cz] = row.tcp;
        let programmed = [cx - offset[0], cy - offset[1], cz - offset[2]];
        let path_row = PathRow {
            t,
            s: s.s_mm,
            corr,
            measured: s.measured_yz,
            programmed,
            corrected: row.tcp,
            start: new_sequence,
        };
        let [px, py, pz] = programmed;
        let values = [px, py, pz, cx, cy, cz, corr[0], corr[1]];
        self.path_thin.offer(
            path_row,
            t as f64 * 1e-6,
            values,
            new_sequence,
            &mut self.pathcorr,
        );
        self.last_path = Some(path_row);
    }

    /// The last EGM sample offered.
    pub fn egm_last(&self) -> Option<EgmRow> {
        self.last_egm
    }

    /// The last path-correction sample offered.
    pub fn path_last(&self) -> Option<PathRow> {
        self.last_path
    }

    /// A program output at the current robot time.
    pub fn output(&mut self, o: &Output) {
        let entry = LogEntry::from_output(self.now, o);
        self.log.push(entry);
    }

    /// How the program ended (shown as the last log entry).
    pub fn end(&mut self, text: String) {
        self.log.push(LogEntry {
            t: self.now,
            kind: LogKind::End,
            text,
        });
    }

    /// The run is over: keep the pending rows.
    pub fn finish(&mut self) {
        if self.finished {
            return;
        }
        self.thin.flush(&mut self.rows);
        self.egm_thin.flush(&mut self.egm);
        self.path_thin.flush(&mut self.pathcorr);
        self.finished = true;
    }

    /// A copy with the pending rows kept (what a viewer joining now gets).
    pub fn snapshot(&self) -> Recording {
        let mut copy = self.clone();
        copy.finish();
        copy.finished = self.finished;
        copy
    }
}
