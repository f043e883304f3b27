//! Core instructions and functions: data manipulation (`Incr`, `Add`, `Clear`, `Dim`),
//! error numbers (`BookErrNo`), program control (`Stop`, `ExitCycle`), waiting (`WaitTime`,
//! `WaitUntil`), the event log (`ErrWrite`) and the test assertion (`Assert`).

use super::{Ctx, Registry};
use crate::interp::errnum;
use crate::interp::error::{Exec, Unwind};
use crate::interp::host::{MotionWait, Output};
use crate::interp::value::Value;

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add("PROC Incr(INOUT anynum Name)", |cx| add_to(cx, 1.0));
    r.add("PROC Decr(INOUT anynum Name)", |cx| add_to(cx, -1.0));
    r.add("PROC Add(INOUT anynum Name, anynum AddValue)", |cx| {
        let d = cx.f64(1)?;
        add_to(cx, d)
    });
    r.add("PROC Clear(INOUT anynum Name)", |cx| {
        let v = match cx.value(0)? {
            Value::Dnum(_) => Value::Dnum(0.0),
            _ => Value::Num(0.0),
        };
        cx.set(0, v)?;
        Ok(Value::Absent)
    });
    r.add("FUNC num Dim(REF anytype ArrPar{*}, num DimNo)", dim);
    r.add("PROC BookErrNo(VAR errnum ErrorName)", book_err_no);
    r.add(r"PROC Stop(\switch NoRegain | switch AllMoveTasks)", |_| {
        Err(Unwind::Stop)
    });
    r.add("PROC ExitCycle()", |_| Err(Unwind::ExitCycle));
    r.add(r"PROC WaitTime(\switch InPos, num Time)", wait_time);
    r.add(
        &format!(
            r"PROC WaitUntil(\switch InPos, bool Cond, \num MaxTime, \VAR bool TimeFlag, \num PollRate, {})",
            super::io::VISUAL
        ),
        wait_until,
    );
    r.add(
        r"PROC ErrWrite(\switch W | switch I, string Header, string Reason, \string RL2, \string RL3, \string RL4)",
        err_write,
    );
    r.add(r"PROC Assert(bool Condition, \string Msg)", assert);
}

fn add_to(cx: &mut Ctx<'_>, d: f64) -> Exec<Value> {
    let v = match cx.value(0)? {
        Value::Num(x) => {
            let r = *x + d as f32;
            if !r.is_finite() {
                return Err(cx.error(
                    errnum::ERR_NUM_LIMIT,
                    "the result is outside the range of num",
                ));
            }
            Value::Num(r)
        }
        Value::Dnum(x) => Value::Dnum(*x + d),
        other => return Err(cx.it.type_bug(cx.span, "num", other)),
    };
    cx.set(0, v)?;
    Ok(Value::Absent)
}

fn dim(cx: &mut Ctx<'_>) -> Exec<Value> {
    let n = cx.int(1, "DimNo")?;
    let Value::Array(a) = cx.value(0)? else {
        return Err(cx.error(errnum::ERR_NOTARR, "the argument is not an array"));
    };
    if n < 1 || n > a.rank as i64 {
        return Err(cx.error(
            errnum::ERR_ILLDIM,
            format!("dimension {n} does not exist (the array has {})", a.rank),
        ));
    }
    Ok(Value::Num(a.dims[(n - 1) as usize] as f32))
}

fn book_err_no(cx: &mut Ctx<'_>) -> Exec<Value> {
    let cur = cx.f64(0)? as i32;
    if (errnum::BOOK_FIRST..cx.it.next_booked).contains(&cur) {
        // Already booked: booking the same variable again keeps its number.
        return Ok(Value::Absent);
    }
    if cx.it.next_booked > errnum::BOOK_LAST {
        return Err(cx.error(errnum::ERR_ARGVALERR, "no more error numbers can be booked"));
    }
    let n = cx.it.next_booked;
    cx.it.next_booked += 1;
    cx.set(0, Value::Num(n as f32))?;
    Ok(Value::Absent)
}

fn wait_time(cx: &mut Ctx<'_>) -> Exec<Value> {
    let t = cx.f64(1)?;
    if t.is_nan() || t < 0.0 || !t.is_finite() {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("WaitTime {t}: the time must be 0 or more"),
        ));
    }
    if cx.present(0) {
        // `\InPos`: the robot must stand still before the time starts.
        super::motion::wait_for(cx, MotionWait::InPos)?;
    }
    let deadline = cx.now().after_secs(t);
    let (p, span) = (cx.p, cx.span);
    cx.it.wait(p, span, Some(deadline), None, 0.0)?;
    Ok(Value::Absent)
}

fn wait_until(cx: &mut Ctx<'_>) -> Exec<Value> {
    // The condition was evaluated once as an argument; re-evaluate it through the call's
    // IR expression on every poll.
    if cx.present(0) {
        // `\InPos`: the robot must stand still before the condition is looked at.
        super::motion::wait_for(cx, MotionWait::InPos)?;
    }
    let max = cx.opt_f64(2)?;
    let poll = cx.opt_f64(4)?.unwrap_or(0.1).max(0.004);
    let deadline = max.map(|m| cx.now().after_secs(m));
    let cond_expr = cx.arg_expr(1);
    let p = cx.p;
    let first = match cond_expr {
        // After waiting for the robot the condition is looked at again.
        Some(e) if cx.present(0) => cx.it.eval_bool(p, e)?,
        _ => cx.bool(1)?,
    };
    let done = if first {
        true
    } else {
        match cond_expr {
            Some(e) => {
                let mut f =
                    |it: &mut crate::interp::Interp, p: &crate::ir::Program| it.eval_bool(p, e);
                super::io::wait_shown(cx, Some(5), deadline, poll, &mut f)?
            }
            None => false,
        }
    };
    if !done {
        if cx.present(3) {
            cx.set(3, Value::Bool(true))?;
        } else {
            return Err(cx.error(
                errnum::ERR_WAIT_MAXTIME,
                format!(
                    "the condition did not become true within {} s",
                    max.unwrap_or(0.0)
                ),
            ));
        }
    } else if cx.present(3) {
        cx.set(3, Value::Bool(false))?;
    }
    Ok(Value::Absent)
}

fn err_write(cx: &mut Ctx<'_>) -> Exec<Value> {
    let warning = cx.present(0) || cx.present(1);
    let header = cx.str(2)?.to_string();
    let mut reason = vec![cx.str(3)?.to_string()];
    for i in 4..7 {
        if cx.present(i) {
            reason.push(cx.str(i)?.to_string());
        }
    }
    // The user domain of the event log (USER_DEF_ERR): 80001 an error, 80002 a warning
    // (`\W`), 80003 information (`\I`); `IError` traps see it.
    let (number, etype) = match (cx.present(0), cx.present(1)) {
        (true, _) => (2, 2),
        (_, true) => (3, 1),
        _ => (1, 3),
    };
    cx.it.log_event(crate::interp::interrupts::LogEvent {
        domain: 8,
        number,
        etype,
        title: header.clone(),
        strs: reason.clone(),
    });
    cx.host().output(Output::ErrWrite {
        warning,
        header,
        reason,
    });
    Ok(Value::Absent)
}

fn assert(cx: &mut Ctx<'_>) -> Exec<Value> {
    if cx.bool(0)? {
        return Ok(Value::Absent);
    }
    let msg = if cx.present(1) {
        cx.str(1)?.to_string()
    } else {
        "assertion failed".to_string()
    };
    Err(cx
        .it
        .fatal(crate::interp::ErrorKind::Assertion, cx.span, msg))
}
