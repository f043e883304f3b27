//! Interrupt instructions: `IDelete`, `IDisable`, `IEnable`, `ISleep`, `IWatch`, `ITimer`,
//! `ISignalDI`, `ISignalDO` (CONNECT is a statement; the analog and group signal
//! interrupts, `IPers` and `IError` are in `io_events.rs`).

use super::io::signal_name;
use super::{Ctx, Registry};
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::interrupts::Trigger;
use crate::interp::value::Value;

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add("PROC IDelete(intnum Interrupt)", |cx| {
        let no = cx.int(0, "Interrupt")? as i32;
        cx.it.delete_interrupt(no);
        Ok(Value::Absent)
    });
    r.add("PROC IDisable()", |cx| {
        cx.it.ints.disabled = true;
        Ok(Value::Absent)
    });
    r.add("PROC IEnable()", |cx| {
        cx.it.ints.disabled = false;
        cx.it.update_poll();
        Ok(Value::Absent)
    });
    r.add("PROC ISleep(intnum Interrupt)", |cx| {
        let no = intno(cx, 0)?;
        cx.it.ints.asleep.insert(no);
        Ok(Value::Absent)
    });
    r.add("PROC IWatch(intnum Interrupt)", |cx| {
        let no = intno(cx, 0)?;
        cx.it.ints.asleep.remove(&no);
        Ok(Value::Absent)
    });
    r.add(
        r"PROC ITimer(\switch Single | switch SingleSafe, num Time, intnum Interrupt)",
        |cx| {
            let single = cx.present(0) || cx.present(1);
            let t = cx.f64(2)?;
            if t.is_nan() || t < 0.01 {
                return Err(cx.error(
                    errnum::ERR_ARGVALERR,
                    format!("ITimer time {t} s is below the minimum of 0.01 s"),
                ));
            }
            let no = intno(cx, 3)?;
            let span = cx.span;
            cx.it.order_timer(no, t, single, span)?;
            Ok(Value::Absent)
        },
    );
    r.add(
        r"PROC ISignalDI(\switch Single | switch SingleSafe, VAR signaldi Signal, dionum TriggValue, intnum Interrupt)",
        signal_digital,
    );
    r.add(
        r"PROC ISignalDO(\switch Single | switch SingleSafe, VAR signaldo Signal, dionum TriggValue, intnum Interrupt)",
        signal_digital,
    );
}

/// Interrupt-number argument `i`, checked to be connected.
pub(super) fn intno(cx: &Ctx<'_>, i: usize) -> Exec<i32> {
    let no = cx.int(i, "Interrupt")? as i32;
    cx.it.check_intno(no, cx.span)?;
    Ok(no)
}

fn signal_digital(cx: &mut Ctx<'_>) -> Exec<Value> {
    let single = cx.present(0) || cx.present(1);
    let name = signal_name(cx, 2)?;
    let t = cx.int(3, "TriggValue")?;
    if !(0..=2).contains(&t) {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("TriggValue must be 0, 1 or 2 (edge), not {t}"),
        ));
    }
    let no = intno(cx, 4)?;
    let span = cx.span;
    cx.it
        .order_watch(no, &name, Trigger::Edge(t as u8), single, span)?;
    Ok(Value::Absent)
}
