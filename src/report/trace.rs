//! `--trace FILE.csv`: one row per motion cycle with time, joints, the TCP of the active tool in
//! world coordinates, TCP speed and the instruction being executed. Deterministic text: the
//! same run always gives the same bytes.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;
use std::sync::Arc;

use crate::controller::TickSink;
use crate::motion::Setpoint;
use crate::robot::units::quat_to_wxyz;
use crate::source::SourceMap;

use super::num::{canonical_quat, push_fixed, push_time};

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

/// Decimals: joints (deg), positions (mm), quaternion components, speed (mm/s).
const JOINT_DECIMALS: usize = 6;
const POS_DECIMALS: usize = 4;
const QUAT_DECIMALS: usize = 8;
const SPEED_DECIMALS: usize = 3;

/// Writes a CSV trace (see the module docs).
pub struct TraceWriter<W: Write + Send> {
    out: csv::Writer<W>,
    lines: Option<Arc<SourceMap>>,
    fields: Vec<String>,
    error: Option<String>,
}

impl TraceWriter<BufWriter<File>> {
    /// Create (truncate) `path`. `lines` resolves instruction spans to line numbers.
    pub fn create(path: &Path, lines: Option<Arc<SourceMap>>) -> Result<Self, String> {
        let file = File::create(path)
            .map_err(|e| format!("cannot create trace {}: {e}", path.display()))?;
        Ok(TraceWriter::new(BufWriter::new(file), lines))
    }
}

impl<W: Write + Send> TraceWriter<W> {
    /// A trace written to `w` (the header is written at once).
    pub fn new(w: W, lines: Option<Arc<SourceMap>>) -> Self {
        let mut out = csv::WriterBuilder::new()
            .terminator(csv::Terminator::Any(b'\n'))
            .from_writer(w);
        let error = out.write_record(TRACE_HEADER).err().map(|e| e.to_string());
        TraceWriter {
            out,
            lines,
            fields: vec![String::new(); TRACE_HEADER.len()],
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
            f.push_str(&i.id.to_string());
        }
        if let Some(f) = it.next()
            && let (Some(map), Some(span)) = (&self.lines, instr.and_then(|i| i.source))
        {
            f.push_str(&map.get(span.source).line_col(span.start).0.to_string());
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
