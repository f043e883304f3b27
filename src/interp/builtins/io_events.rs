//! Signal waits, aliases and the interrupts beyond timers and digital edges:
//! `InvertDO`, `WaitAI`, `WaitAO`, `WaitGI`, `WaitGO`, `AliasIO`, `ValidIO`, `ISignalAI`,
//! `ISignalAO`, `ISignalGI`, `ISignalGO`, `IPers`, `IError`, `GetTrapData`, `ReadErrData`,
//! `IVarValue`.

use super::interrupts::intno;
use super::io::{max_time, signal_name, wait_for_signal};
use super::{Ctx, Registry};
use crate::interp::errnum;
use crate::interp::error::{ErrorKind, Exec};
use crate::interp::host::Output;
use crate::interp::interrupts::{ErrorOrder, Trigger};
use crate::interp::value::Value;

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add("PROC InvertDO(VAR signaldo Signal)", |cx| {
        let name = signal_name(cx, 0)?;
        let v = cx.host().read_signal(&name).map_err(|e| cx.host_err(e))?;
        let inv = if v >= 0.5 { 0.0 } else { 1.0 };
        cx.host()
            .write_signal(&name, inv)
            .map_err(|e| cx.host_err(e))?;
        Ok(Value::Absent)
    });
    r.add(
        r"PROC WaitAI(VAR signalai Signal, \switch LT | switch GT, num Value, \num MaxTime, \VAR num ValueAtTimeout)",
        |cx| wait_level(cx, None),
    );
    r.add(
        r"PROC WaitAO(VAR signalao Signal, \switch LT | switch GT, num Value, \num MaxTime, \VAR num ValueAtTimeout)",
        |cx| wait_level(cx, None),
    );
    r.add(
        r"PROC WaitGI(VAR signalgi Signal, \switch NOTEQ | switch LT | switch GT, anynum Value, \num MaxTime, \VAR num ValueAtTimeout | VAR dnum DvalueAtTimeout)",
        |cx| wait_level(cx, Some(1)),
    );
    r.add(
        r"PROC WaitGO(VAR signalgo Signal, \switch NOTEQ | switch LT | switch GT, anynum Value, \num MaxTime, \VAR num ValueAtTimeout | VAR dnum DvalueAtTimeout)",
        |cx| wait_level(cx, Some(1)),
    );
    r.add(
        "PROC AliasIO(anysignal FromSignal, VAR anysignal ToSignal)",
        alias_io,
    );
    r.add("FUNC bool ValidIO(anysignal Signal)", |cx| {
        let name = match cx.value(0)? {
            Value::Str(s) => s.to_string(),
            v => match v.fields() {
                Some([Value::Str(s)]) => s.to_string(),
                _ => return Err(cx.it.type_bug(cx.span, "signal", v)),
            },
        };
        Ok(Value::Bool(
            !name.is_empty() && cx.host().signal_kind(&name).is_some(),
        ))
    });
    r.add(
        r"PROC ISignalAI(\switch Single | switch SingleSafe, VAR signalai Signal, aiotrigg Condition, num HighValue, num LowValue, num DeltaValue, \switch DPos | switch DNeg, intnum Interrupt)",
        signal_analog,
    );
    r.add(
        r"PROC ISignalAO(\switch Single | switch SingleSafe, VAR signalao Signal, aiotrigg Condition, num HighValue, num LowValue, num DeltaValue, \switch DPos | switch DNeg, intnum Interrupt)",
        signal_analog,
    );
    r.add(
        r"PROC ISignalGI(\switch Single | switch SingleSafe, VAR signalgi Signal, intnum Interrupt)",
        signal_group,
    );
    r.add(
        r"PROC ISignalGO(\switch Single | switch SingleSafe, VAR signalgo Signal, intnum Interrupt)",
        signal_group,
    );
    r.add("PROC IPers(PERS anytype Name, intnum Interrupt)", |cx| {
        let no = intno(cx, 1)?;
        let place = match cx.it.nargs.get(cx.base) {
            Some(crate::interp::NArg::Ref(r)) => r.clone(),
            _ => {
                return Err(cx.it.fatal(
                    ErrorKind::Host,
                    cx.span,
                    "internal error: IPers without a persistent",
                ));
            }
        };
        let span = cx.span;
        cx.it.order_pers(no, place, span)?;
        Ok(Value::Absent)
    });
    r.add(
        r"PROC IError(errdomain ErrorDomain, \num ErrorId, errtype ErrorType, intnum Interrupt)",
        |cx| {
            let domain = cx.int(0, "ErrorDomain")?;
            if !(0..=12).contains(&domain) {
                return Err(cx.error(
                    errnum::ERR_ARGVALERR,
                    format!("{domain} is not an errdomain (COMMON_ERR … CFG_ERR)"),
                ));
            }
            let number = match cx.present(1) {
                true => Some(cx.int(1, "ErrorId")? as i32),
                false => None,
            };
            let etype = cx.int(2, "ErrorType")?;
            if !(0..=3).contains(&etype) {
                return Err(cx.error(
                    errnum::ERR_ARGVALERR,
                    format!(
                        "{etype} is not an errtype (TYPE_ALL, TYPE_STATE, TYPE_WARN, TYPE_ERR)"
                    ),
                ));
            }
            let intno = intno(cx, 3)?;
            let span = cx.span;
            cx.it.order_error(
                ErrorOrder {
                    intno,
                    domain: domain as i32,
                    number,
                    etype: etype as i32,
                },
                span,
            )?;
            Ok(Value::Absent)
        },
    );
    r.add("PROC GetTrapData(VAR trapdata TrapEvent)", |cx| {
        let Some(ev) = cx.it.ints.trap_event.clone() else {
            return Err(cx.it.fatal(
                ErrorKind::Host,
                cx.span,
                "GetTrapData can only be used in a TRAP that an IError interrupt started",
            ));
        };
        let mut fields = vec![
            Value::Num(ev.domain as f32),
            Value::Num(ev.number as f32),
            Value::Num(ev.etype as f32),
            Value::str(&ev.title),
        ];
        for i in 0..5 {
            fields.push(Value::str(ev.strs.get(i).map_or("", String::as_str)));
        }
        cx.set(0, Value::Record(fields.into()))?;
        Ok(Value::Absent)
    });
    r.add(
        r"PROC ReadErrData(trapdata TrapEvent, VAR errdomain ErrorDomain, VAR num ErrorId, VAR errtype ErrorType, \VAR string Title, \VAR string Str1, \VAR string Str2, \VAR string Str3, \VAR string Str4, \VAR string Str5)",
        |cx| {
            let fields: Vec<Value> = match cx.value(0)?.fields() {
                Some(f) if f.len() == 9 => f.to_vec(),
                _ => {
                    let v = cx.value(0)?;
                    return Err(cx.it.type_bug(cx.span, "trapdata", v));
                }
            };
            for (i, f) in fields.into_iter().enumerate() {
                let arg = i + 1;
                if arg <= 3 || cx.present(arg) {
                    cx.set(arg, f)?;
                }
            }
            Ok(Value::Absent)
        },
    );
    r.add(
        r"PROC IVarValue(string device, num VarNo, INOUT num Value, intnum Interrupt, \num Unit, \num DeadBand, \switch ReportAtTool, \switch SpeedAdapt, \switch APTR)",
        |cx| {
            let no = intno(cx, 3)?;
            let device = cx.str(0)?.to_string();
            cx.host().output(Output::Event(format!(
                "IVarValue: rapidvc has no sensor interface, so device `{device}` never sends \
                 a value and interrupt {no} never occurs"
            )));
            Ok(Value::Absent)
        },
    );
}

/// `WaitAI`/`WaitAO` (`noteq` = None) and `WaitGI`/`WaitGO` (`\NOTEQ` at index 1): wait
/// until the signal equals (or is not equal to, below, above) the value.
fn wait_level(cx: &mut Ctx<'_>, noteq: Option<usize>) -> Exec<Value> {
    let name = signal_name(cx, 0)?;
    let first = noteq.map_or(1, |_| 2);
    let (lt, gt) = (cx.present(first), cx.present(first + 1));
    let ne = noteq.is_some_and(|i| cx.present(i));
    let want = cx.f64(first + 2)?;
    let max = max_time(cx, first + 3)?;
    let reached = wait_for_signal(cx, &name, max, None, |v| {
        if lt {
            v < want
        } else if gt {
            v > want
        } else if ne {
            v != want
        } else {
            v == want
        }
    })?;
    if reached {
        return Ok(Value::Absent);
    }
    let now = cx.host().read_signal(&name).map_err(|e| cx.host_err(e))?;
    let at = first + 4;
    if cx.present(at) {
        cx.set(at, Value::Num(now as f32))?;
    } else if noteq.is_some() && cx.present(at + 1) {
        cx.set(at + 1, Value::Dnum(now))?;
    }
    let rel = if lt {
        "below"
    } else if gt {
        "above"
    } else if ne {
        "other than"
    } else {
        "equal to"
    };
    Err(cx.error(
        errnum::ERR_WAIT_MAXTIME,
        format!(
            "{} did not get a value {rel} {want} within {} s (it is {now})",
            name,
            max.unwrap_or(0.0)
        ),
    ))
}

fn signal_analog(cx: &mut Ctx<'_>) -> Exec<Value> {
    let single = cx.present(0) || cx.present(1);
    let name = signal_name(cx, 2)?;
    let cond = cx.int(3, "Condition")?;
    if !(1..=7).contains(&cond) {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("{cond} is not an aiotrigg condition (AIO_ABOVE_HIGH … AIO_ALWAYS)"),
        ));
    }
    let (high, low, delta) = (cx.f64(4)?, cx.f64(5)?, cx.f64(6)?);
    if (cond == 5 || cond == 6) && low > high {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("LowValue {low} is above HighValue {high}"),
        ));
    }
    if !(delta >= 0.0 && delta.is_finite()) {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("DeltaValue {delta} must be 0 or positive"),
        ));
    }
    let dir = if cx.present(7) {
        1
    } else if cx.present(8) {
        -1
    } else {
        0
    };
    let no = intno(cx, 9)?;
    let span = cx.span;
    let trig = Trigger::Analog {
        cond: cond as u8,
        high,
        low,
        delta,
        dir,
    };
    cx.it.order_watch(no, &name, trig, single, span)?;
    Ok(Value::Absent)
}

fn signal_group(cx: &mut Ctx<'_>) -> Exec<Value> {
    let single = cx.present(0) || cx.present(1);
    let name = signal_name(cx, 2)?;
    let no = intno(cx, 3)?;
    let span = cx.span;
    cx.it
        .order_watch(no, &name, Trigger::Change, single, span)?;
    Ok(Value::Absent)
}

/// `AliasIO FromSignal, ToSignal`: connect a signal variable to a configured signal, named
/// by a signal or a string.
fn alias_io(cx: &mut Ctx<'_>) -> Exec<Value> {
    let from = match cx.value(0)? {
        Value::Str(s) => s.to_string(),
        v => match v.fields() {
            Some([Value::Str(s)]) => s.to_string(),
            _ => return Err(cx.it.type_bug(cx.span, "signal or string", v)),
        },
    };
    let Some(kind) = cx.host().signal_kind(&from) else {
        return Err(cx.error(
            errnum::ERR_ALIASIO_DEF,
            format!("there is no signal `{from}` in the I/O configuration"),
        ));
    };
    match target_type(cx, 1) {
        Some(ty) if !ty.starts_with("signal") => {
            return Err(cx.error(
                errnum::ERR_ALIASIO_TYPE,
                format!("ToSignal must be a signal variable, not a {ty}"),
            ));
        }
        Some(ty) if !ty.eq_ignore_ascii_case(kind.rapid_type()) => {
            return Err(cx.error(
                errnum::ERR_ALIASIO_TYPE,
                format!(
                    "`{from}` is a {} signal, the variable a {ty}",
                    kind.as_str()
                ),
            ));
        }
        _ => {}
    }
    cx.set(1, Value::Record(vec![Value::str(&from)].into()))?;
    Ok(Value::Absent)
}

/// The declared type of reference argument `i` when it is a whole module or routine data
/// object (`None` when rapidvc cannot tell, e.g. an array element).
fn target_type(cx: &Ctx<'_>, i: usize) -> Option<String> {
    let Some(crate::ir::Arg::Ref(place)) = cx.args.get(i) else {
        return None;
    };
    if !place.path.is_empty() {
        return None;
    }
    let ty = match place.root {
        crate::ir::Root::Global(g) => cx.p.globals.get(g as usize)?.ty,
        crate::ir::Root::Local(slot) => {
            let rid = cx.it.frames.last()?.routine;
            cx.p.routine(rid).locals.iter().find(|l| l.slot == slot)?.ty
        }
        crate::ir::Root::Ref(_) => return None,
    };
    Some(cx.p.types.name(ty.base).to_string())
}
