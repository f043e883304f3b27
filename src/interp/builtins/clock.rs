//! Clocks (`ClkReset`, `ClkStart`, `ClkStop`, `ClkRead`) on the host's time, so they read
//! virtual seconds in a virtual run. A `clock` is a semi-value record
//! `[running, started_at, accumulated]`.

use super::{Ctx, Registry};
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::value::Value;

/// Longest time a clock can measure (seconds), as on a controller.
const CLOCK_MAX: f64 = 4_294_967.0;

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add("PROC ClkReset(VAR clock Clock)", |cx| {
        let now = cx.now_secs();
        let running = state(cx)?.0;
        cx.set(0, clock(running, now, 0.0))?;
        Ok(Value::Absent)
    });
    r.add("PROC ClkStart(VAR clock Clock)", |cx| {
        let (running, start, acc) = state(cx)?;
        if !running {
            let now = cx.now_secs();
            cx.set(0, clock(true, now, acc))?;
        } else {
            cx.set(0, clock(true, start, acc))?;
        }
        Ok(Value::Absent)
    });
    r.add("PROC ClkStop(VAR clock Clock)", |cx| {
        let (running, start, acc) = state(cx)?;
        if running {
            let now = cx.now_secs();
            cx.set(0, clock(false, now, acc + (now - start)))?;
        }
        Ok(Value::Absent)
    });
    r.add(
        r"FUNC num ClkRead(VAR clock Clock, \switch HighRes)",
        |cx| {
            let (running, start, acc) = state(cx)?;
            let t = if running {
                acc + (cx.now_secs() - start)
            } else {
                acc
            };
            if t > CLOCK_MAX {
                return Err(cx.error(
                    errnum::ERR_OVERFLOW,
                    format!("the clock ran longer than {CLOCK_MAX} s"),
                ));
            }
            let t = if cx.present(1) {
                t
            } else {
                (t * 1000.0).round() / 1000.0
            };
            Ok(Value::Num(t as f32))
        },
    );
}

fn clock(running: bool, start: f64, acc: f64) -> Value {
    Value::Record(Box::new([
        Value::Bool(running),
        Value::Dnum(start),
        Value::Dnum(acc),
    ]))
}

fn state(cx: &Ctx<'_>) -> Exec<(bool, f64, f64)> {
    let v = cx.value(0)?;
    match v.fields() {
        Some([Value::Bool(r), Value::Dnum(s), Value::Dnum(a)]) => Ok((*r, *s, *a)),
        _ => Err(cx.it.type_bug(cx.span, "clock", v)),
    }
}
