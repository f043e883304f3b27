//! I/O signal instructions and functions (`SetDO`, `SetAO`, `SetGO`, `Set`, `Reset`,
//! `PulseDO`, `WaitDI`, `WaitDO`, `DInput`, `DOutput`, `AInput`, `AOutput`, `GInput`,
//! `GOutput`, `TestDI`) on the host's signal table. A signal value is a record holding the
//! signal's configured name.

use super::{Ctx, Registry};
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::value::Value;

/// Default pulse length of `PulseDO` (seconds).
const PULSE_LENGTH: f64 = 0.2;

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add(
        r"PROC SetDO(\num SDelay | switch Sync, VAR signaldo Signal, dionum Value)",
        |cx| set_digital(cx, 3, 2),
    );
    r.add(r"PROC Set(VAR signaldo Signal, \switch Sync)", |cx| {
        write(cx, 0, 1.0)
    });
    r.add(r"PROC Reset(VAR signaldo Signal, \switch Sync)", |cx| {
        write(cx, 0, 0.0)
    });
    r.add(r"PROC SetAO(VAR signalao Signal, num Value)", |cx| {
        let v = cx.f64(1)?;
        write(cx, 0, v)
    });
    r.add(
        r"PROC SetGO(\num SDelay, VAR signalgo Signal, num Value)",
        |cx| {
            let v = cx.f64(2)?;
            if v < 0.0 || v.fract() != 0.0 {
                return Err(cx.error(
                    errnum::ERR_GO_LIM,
                    format!("{v} is not a valid group output value"),
                ));
            }
            delayed_write(cx, 1, 0, v)
        },
    );
    r.add(
        r"PROC PulseDO(\switch High, \num PLength, VAR signaldo Signal)",
        pulse_do,
    );
    r.add(
        &format!(
            r"PROC WaitDI(VAR signaldi Signal, dionum Value, \num MaxTime, \VAR bool TimeFlag, {VISUAL})"
        ),
        wait_signal,
    );
    r.add(
        &format!(
            r"PROC WaitDO(VAR signaldo Signal, dionum Value, \num MaxTime, \VAR bool TimeFlag, {VISUAL})"
        ),
        wait_signal,
    );
    r.add("FUNC dionum DInput(VAR signaldi Signal)", read);
    r.add("FUNC dionum DOutput(VAR signaldo Signal)", read);
    r.add("FUNC num AInput(VAR signalai Signal)", read);
    r.add("FUNC num AOutput(VAR signalao Signal)", read);
    r.add("FUNC num GInput(VAR signalgi Signal)", read);
    r.add("FUNC num GOutput(VAR signalgo Signal)", read);
    r.add("FUNC bool TestDI(VAR signaldi Signal)", |cx| {
        let v = read_value(cx, 0)?;
        Ok(Value::Bool(v >= 0.5))
    });
}

/// The configured name behind a signal argument.
pub(crate) fn signal_name(cx: &Ctx<'_>, i: usize) -> Exec<String> {
    let v = cx.value(i)?;
    match v.fields() {
        Some([Value::Str(s)]) if !s.is_empty() => Ok(s.to_string()),
        Some([Value::Str(_)]) => Err(cx.error(
            errnum::ERR_NO_ALIASIO_DEF,
            "the signal variable is not connected to a configured signal",
        )),
        _ => Err(cx.it.type_bug(cx.span, "signal", v)),
    }
}

fn read_value(cx: &mut Ctx<'_>, i: usize) -> Exec<f64> {
    let name = signal_name(cx, i)?;
    cx.host().read_signal(&name).map_err(|e| cx.host_err(e))
}

fn read(cx: &mut Ctx<'_>) -> Exec<Value> {
    Ok(Value::Num(read_value(cx, 0)? as f32))
}

fn write(cx: &mut Ctx<'_>, sig: usize, v: f64) -> Exec<Value> {
    let name = signal_name(cx, sig)?;
    cx.host()
        .write_signal(&name, v)
        .map_err(|e| cx.host_err(e))?;
    Ok(Value::Absent)
}

fn dio(cx: &Ctx<'_>, i: usize) -> Exec<f64> {
    let v = cx.f64(i)?;
    if v != 0.0 && v != 1.0 {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("a digital signal value must be 0 or 1, not {v}"),
        ));
    }
    Ok(v)
}

fn set_digital(cx: &mut Ctx<'_>, val: usize, sig: usize) -> Exec<Value> {
    let v = dio(cx, val)?;
    delayed_write(cx, sig, 0, v)
}

/// Write now, or after `\SDelay` (argument `delay`) seconds of (virtual) time.
fn delayed_write(cx: &mut Ctx<'_>, sig: usize, delay: usize, v: f64) -> Exec<Value> {
    match cx.opt_f64(delay)? {
        Some(d) if d > 0.0 => {
            let name = signal_name(cx, sig)?;
            let at = cx.now().after_secs(d);
            cx.it.schedule_write(at, name, v);
            Ok(Value::Absent)
        }
        _ => write(cx, sig, v),
    }
}

fn pulse_do(cx: &mut Ctx<'_>) -> Exec<Value> {
    let len = cx.opt_f64(1)?.unwrap_or(PULSE_LENGTH);
    if !(0.001..=2000.0).contains(&len) {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("PLength {len} s is outside 0.001–2000 s"),
        ));
    }
    let name = signal_name(cx, 2)?;
    let cur = cx.host().read_signal(&name).map_err(|e| cx.host_err(e))?;
    // \High: always a positive pulse; otherwise the signal is inverted for the pulse.
    let (on, after) = if cx.present(0) || cur < 0.5 {
        (1.0, 0.0)
    } else {
        (0.0, 1.0)
    };
    cx.host()
        .write_signal(&name, on)
        .map_err(|e| cx.host_err(e))?;
    let at = cx.now().after_secs(len);
    cx.it.schedule_write(at, name, after);
    Ok(Value::Absent)
}

/// Wait (running traps) until signal `name`'s value passes `test`, or for at most `max`
/// seconds; true when it passed.
pub(super) fn wait_for_signal(
    cx: &mut Ctx<'_>,
    name: &str,
    max: Option<f64>,
    visual: Option<usize>,
    test: impl Fn(f64) -> bool,
) -> Exec<bool> {
    let deadline = max.map(|m| cx.now().after_secs(m));
    let span = cx.span;
    let mut f = |it: &mut crate::interp::Interp, _: &crate::ir::Program| {
        let v = it
            .host
            .read_signal(name)
            .map_err(|e| it.host_error(e, span))?;
        Ok(test(v))
    };
    wait_shown(cx, visual, deadline, 0.1, &mut f)
}

/// The FlexPendant message of a waiting instruction (`WaitUntil`, `WaitDI`, `WaitDO`),
/// appended to its parameters: the box is shown once the wait has lasted `\VisualizeTime`
/// seconds (at once without it) and closes when the wait ends; `\UIActiveSignal` is 1 while
/// it is shown. rapidvc's FlexPendant is the `TPWrite` output, as for the UI dialogs.
pub(super) const VISUAL: &str = r"\switch Visualize, \string Header, \string Message | string MsgArray{*}, \switch Wrap, \icondata Icon, \string Image, \num VisualizeTime, \VAR signaldo UIActiveSignal";

/// Wait until `cond` holds (true) or `deadline` passes (false), polling every `poll` s;
/// with `\Visualize` (argument `visual`, the first of [`VISUAL`]) present, the message is
/// shown while the wait goes on.
pub(super) fn wait_shown(
    cx: &mut Ctx<'_>,
    visual: Option<usize>,
    deadline: Option<crate::time::RobotTime>,
    poll: f64,
    cond: &mut crate::interp::interrupts::WaitCond<'_>,
) -> Exec<bool> {
    let (p, span) = (cx.p, cx.span);
    let Some(v) = visual.filter(|&v| cx.present(v)) else {
        return cx.it.wait(p, span, deadline, Some(cond), poll);
    };
    let after = cx.opt_f64(v + 7)?.unwrap_or(0.0);
    if !(after >= 0.0 && after.is_finite()) {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("VisualizeTime {after} s is not a time (0 s or more)"),
        ));
    }
    // Until the message is due, a plain wait (a condition true at once shows nothing).
    let due = cx.now().after_secs(after);
    let first = deadline.map_or(due, |d| d.min(due));
    if cx.it.wait(p, span, Some(first), Some(cond), poll)? {
        return Ok(true);
    }
    if deadline.is_some_and(|d| cx.now() >= d) {
        return Ok(false);
    }
    let mut lines = super::dialogs::ui_text(cx, Some(v + 1), &[v + 2], Some(v + 3), Some(v + 4))?;
    if lines.is_empty() {
        lines.push(format!("== {} ==", cx.name()));
    }
    for line in lines {
        cx.host().output(crate::interp::host::Output::TpWrite(line));
    }
    let active = cx.present(v + 8);
    if active {
        write(cx, v + 8, 1.0)?;
    }
    let r = cx.it.wait(p, span, deadline, Some(cond), poll);
    if active {
        write(cx, v + 8, 0.0)?;
    }
    r
}

/// Optional `\MaxTime` argument `i`: a time of 0 s or more, else `ERR_ARGVALERR`.
pub(super) fn max_time(cx: &Ctx<'_>, i: usize) -> Exec<Option<f64>> {
    let max = cx.opt_f64(i)?;
    if let Some(m) = max
        && !(m >= 0.0 && m.is_finite())
    {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("MaxTime {m} s is not a time (0 s or more)"),
        ));
    }
    Ok(max)
}

fn wait_signal(cx: &mut Ctx<'_>) -> Exec<Value> {
    let name = signal_name(cx, 0)?;
    let want = dio(cx, 1)?;
    let max = cx.opt_f64(2)?;
    let done = wait_for_signal(cx, &name, max, Some(4), |v| (v >= 0.5) == (want >= 0.5))?;
    if !done {
        if cx.present(3) {
            cx.set(3, Value::Bool(true))?;
        } else {
            return Err(cx.error(
                errnum::ERR_WAIT_MAXTIME,
                format!(
                    "the signal did not get the value {want} within {} s",
                    max.unwrap_or(0.0)
                ),
            ));
        }
    } else if cx.present(3) {
        cx.set(3, Value::Bool(false))?;
    }
    Ok(Value::Absent)
}
