//! The page's data as JSON: the scene (robot model, base, source files, work objects) and the
//! recording in columns of quantised integers, each column stored as differences from the
//! previous value (small numbers, short text). `view.js` (`decodeColumns`) reverses it.
//! Live messages carry the same fields as plain numbers, one row at a time.

use serde_json::{Value, json};

use crate::output::{EgmAxes, EgmTraceState};
use crate::robot::units::m_to_mm;

use super::Scene;
use super::record::{EgmRow, InstrInfo, LogEntry, PathRow, Recording, Row};

/// Format version of the embedded data (the page checks it).
pub const DATA_VERSION: u32 = 1;

/// Scales of the quantised columns: value × scale, rounded.
pub const SCALE_JOINT: f64 = 1e3;
/// TCP and path positions: 0.01 mm.
pub const SCALE_POS: f64 = 1e2;
/// Quaternion components.
pub const SCALE_QUAT: f64 = 1e4;
/// TCP speed: 0.1 mm/s.
pub const SCALE_SPEED: f64 = 1e1;
/// EGM values and path corrections: 0.001 deg or mm.
pub const SCALE_CURVE: f64 = 1e3;

/// A column of quantised values stored as differences.
#[derive(Default)]
struct Column {
    last: i64,
    out: Vec<Value>,
}

impl Column {
    fn push_int(&mut self, q: i64) {
        self.out.push(Value::from(q - self.last));
        self.last = q;
    }

    fn push(&mut self, v: f64, scale: f64) {
        // Non-finite values are stored as 0 (the page never receives NaN).
        let q = if v.is_finite() {
            (v * scale).round() as i64
        } else {
            0
        };
        self.push_int(q);
    }

    fn done(self) -> Value {
        Value::Array(self.out)
    }
}

/// A time column in units of `unit` µs (the motion cycle when every time is a multiple of
/// it, else 1): `{"unit": …, "d": […]}`.
fn time_column(times: impl Iterator<Item = i64> + Clone, cycle_us: i64) -> Value {
    let unit = if cycle_us > 1 && times.clone().all(|t| t % cycle_us == 0) {
        cycle_us
    } else {
        1
    };
    let mut c = Column::default();
    for t in times {
        c.push_int(t / unit);
    }
    json!({"unit": unit, "d": c.done()})
}

fn columns<const N: usize>() -> [Column; N] {
    std::array::from_fn(|_| Column::default())
}

fn done<const N: usize>(c: [Column; N]) -> Value {
    Value::Array(c.into_iter().map(Column::done).collect())
}

/// The EGM state as the page's number: 0 disconnected, 1 connected, 2 running.
pub fn state_code(s: EgmTraceState) -> u8 {
    match s {
        EgmTraceState::Disconnected => 0,
        EgmTraceState::Connected => 1,
        EgmTraceState::Running => 2,
    }
}

fn axes_code(a: EgmAxes) -> u8 {
    match a {
        EgmAxes::Joint => 0,
        EgmAxes::Pose => 1,
    }
}

/// The scene: robot, base, source files and work objects.
pub fn scene(scene: &Scene) -> Value {
    let model = scene.robot.model();
    let p = &model.opw;
    let base = scene.robot.base();
    let bt = base.translation.vector;
    let br = base.rotation;
    let files: Vec<Value> = scene
        .files
        .iter()
        .map(|&id| {
            let f = scene.sources.get(id);
            json!({"name": f.name, "text": &*f.text})
        })
        .collect();
    let frames: Vec<Value> = scene
        .frames
        .iter()
        .map(|f| {
            let t = f.pose.translation.vector;
            let r = f.pose.rotation;
            json!({"name": f.name, "pose": [t.x, t.y, t.z, r.w, r.i, r.j, r.k]})
        })
        .collect();
    json!({
        "title": scene.title,
        "robot": {
            "name": model.name,
            "opw": {
                "a1": m_to_mm(p.a1), "a2": m_to_mm(p.a2), "b": m_to_mm(p.b),
                "c1": m_to_mm(p.c1), "c2": m_to_mm(p.c2), "c3": m_to_mm(p.c3),
                "c4": m_to_mm(p.c4),
            },
            "base": [bt.x, bt.y, bt.z, br.w, br.i, br.j, br.k],
            "limits": model.joint_limits.iter().map(|l| [l.min, l.max]).collect::<Vec<_>>(),
            "reach": model.reach_mm(),
        },
        "periodUs": u64::try_from(scene.period.as_micros()).unwrap_or(u64::MAX),
        "files": files,
        "frames": frames,
    })
}

fn instr(i: &InstrInfo) -> Value {
    json!([i.id, i.name, i.file, i.line])
}

fn log_entry(e: &LogEntry) -> Value {
    json!([e.t, e.kind.as_str(), e.text])
}

fn rows(rows: &[Row], cycle_us: i64) -> Value {
    let mut j = columns::<6>();
    let mut p = columns::<3>();
    let mut q = columns::<4>();
    let mut v = Column::default();
    let mut i = Column::default();
    for r in rows {
        for (c, x) in j.iter_mut().zip(r.joints) {
            c.push(x, SCALE_JOINT);
        }
        for (c, x) in p.iter_mut().zip(r.tcp) {
            c.push(x, SCALE_POS);
        }
        for (c, x) in q.iter_mut().zip(r.quat) {
            c.push(x, SCALE_QUAT);
        }
        v.push(r.speed, SCALE_SPEED);
        i.push_int(i64::from(r.instr));
    }
    json!({
        "n": rows.len(), "t": time_column(rows.iter().map(|r| r.t), cycle_us), "j": done(j), "p": done(p), "q": done(q),
        "v": v.done(), "i": i.done(),
    })
}

fn egm(rows: &[EgmRow], cycle_us: i64) -> Value {
    let mut axes = Column::default();
    let mut state = Column::default();
    let mut lim = Column::default();
    let mut has_ref = Column::default();
    let mut reference = columns::<6>();
    let mut feedback = columns::<6>();
    for r in rows {
        axes.push_int(i64::from(axes_code(r.axes)));
        state.push_int(i64::from(state_code(r.state)));
        lim.push_int(i64::from(r.limited));
        has_ref.push_int(i64::from(r.reference.is_some()));
        let rv = r.reference.unwrap_or([0.0; 6]);
        for (c, x) in reference.iter_mut().zip(rv) {
            c.push(x, SCALE_CURVE);
        }
        for (c, x) in feedback.iter_mut().zip(r.feedback) {
            c.push(x, SCALE_CURVE);
        }
    }
    json!({
        "n": rows.len(), "t": time_column(rows.iter().map(|r| r.t), cycle_us),
        "axes": axes.done(), "state": state.done(),
        "lim": lim.done(), "hasRef": has_ref.done(), "ref": done(reference),
        "fb": done(feedback),
    })
}

fn path(rows: &[PathRow], cycle_us: i64) -> Value {
    let mut s = Column::default();
    let mut corr = columns::<2>();
    let mut start = Column::default();
    let mut has_meas = Column::default();
    let mut meas = columns::<2>();
    let mut prog = columns::<3>();
    let mut cor = columns::<3>();
    for r in rows {
        s.push(r.s, SCALE_POS);
        start.push_int(i64::from(r.start));
        for (c, x) in corr.iter_mut().zip(r.corr) {
            c.push(x, SCALE_CURVE);
        }
        has_meas.push_int(i64::from(r.measured.is_some()));
        for (c, x) in meas.iter_mut().zip(r.measured.unwrap_or([0.0; 2])) {
            c.push(x, SCALE_CURVE);
        }
        for (c, x) in prog.iter_mut().zip(r.programmed) {
            c.push(x, SCALE_POS);
        }
        for (c, x) in cor.iter_mut().zip(r.corrected) {
            c.push(x, SCALE_POS);
        }
    }
    json!({
        "n": rows.len(), "t": time_column(rows.iter().map(|r| r.t), cycle_us), "s": s.done(), "start": start.done(), "corr": done(corr),
        "hasMeas": has_meas.done(), "meas": done(meas), "prog": done(prog), "cor": done(cor),
    })
}

/// Everything the page needs: the scene and the recording. `live` tells the page to connect
/// to the server's stream for what follows.
pub fn page_data(sc: &Scene, rec: &Recording, live: bool) -> Value {
    let cycle = i64::try_from(sc.period.as_micros()).unwrap_or(1);
    json!({
        "version": DATA_VERSION,
        "live": live,
        "scene": scene(sc),
        "instrs": rec.instrs.iter().map(instr).collect::<Vec<_>>(),
        "rows": rows(&rec.rows, cycle),
        "log": rec.log.iter().map(log_entry).collect::<Vec<_>>(),
        "egm": egm(&rec.egm, cycle),
        "egmStates": rec.egm_states.iter().map(|(t, s)| json!([t, state_code(*s)])).collect::<Vec<_>>(),
        "path": path(&rec.pathcorr, cycle),
        "endUs": rec.now,
        "finished": rec.finished,
    })
}

/// Live: one motion row (plain numbers).
pub fn live_row(r: &Row) -> Value {
    json!({"type": "row", "t": r.t, "j": r.joints, "p": r.tcp, "q": r.quat, "v": r.speed, "i": r.instr})
}

/// Live: a new instruction at `index` of the table.
pub fn live_instr(index: usize, i: &InstrInfo) -> Value {
    json!({"type": "instr", "index": index, "instr": instr(i)})
}

/// Live: the log entry at `index` of the log.
pub fn live_log(index: usize, e: &LogEntry) -> Value {
    json!({"type": "log", "index": index, "entry": log_entry(e)})
}

/// Live: an EGM sample.
pub fn live_egm(r: &EgmRow) -> Value {
    json!({
        "type": "egm", "t": r.t, "axes": axes_code(r.axes), "state": state_code(r.state),
        "lim": r.limited, "ref": r.reference, "fb": r.feedback,
    })
}

/// Live: an EGM state change.
pub fn live_egm_state(t: i64, s: EgmTraceState) -> Value {
    json!({"type": "egmState", "t": t, "state": state_code(s)})
}

/// Live: a path-correction sample.
pub fn live_path(r: &PathRow) -> Value {
    json!({
        "type": "path", "t": r.t, "s": r.s, "start": r.start, "corr": r.corr, "meas": r.measured,
        "prog": r.programmed, "cor": r.corrected,
    })
}

/// Live: the run is over.
pub fn live_end(t: i64) -> Value {
    json!({"type": "end", "t": t})
}
