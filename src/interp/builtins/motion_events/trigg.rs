//! `triggdata` and the instructions that define it (`TriggIO`, `TriggEquip`, `TriggInt`,
//! `TriggSpeed`), and the moves that carry it (`TriggL`, `TriggJ`, `TriggC`).
//!
//! A `triggdata` is a record with hidden components (`sema::predef`): what to do
//! (`kind`: 1 write a signal, 2 an interrupt, 3 `TriggSpeed`, 4 nothing), where (`distance`, `start`,
//! `time`), how much earlier (`lead`, seconds), the signal, its value and the interrupt.

use super::{At, Kind, command, submit};
use crate::interp::builtins::Ctx;
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::host::{ProgramAction, TriggAction, TriggEvent};
use crate::interp::value::Value;
use crate::robot::trigger::TriggPlace;

/// `kind` of a `triggdata`.
const SIGNAL: f32 = 1.0;
const INTERRUPT: f32 = 2.0;
const SPEED: f32 = 3.0;
/// A `TriggEquip` inhibited without `\InhibSetValue`: the event does nothing.
const NOTHING: f32 = 4.0;

/// A position event as a `triggdata` holds it.
struct Def {
    kind: f32,
    distance: f64,
    start: bool,
    time: bool,
    lead: f64,
    signal: String,
    value: f64,
    intno: i32,
}

impl Def {
    fn value(&self) -> Value {
        Value::Record(Box::new([
            Value::Num(self.kind),
            Value::Num(self.distance as f32),
            Value::Bool(self.start),
            Value::Bool(self.time),
            Value::Num(self.lead as f32),
            Value::Str(self.signal.as_str().into()),
            Value::Dnum(self.value),
            Value::Num(self.intno as f32),
        ]))
    }

    /// The definition in a `triggdata` value; `None` when no `Trigg…` instruction set it.
    fn read(v: &Value) -> Option<Def> {
        let f = v.fields()?;
        let num = |i: usize| -> Option<f64> { f.get(i)?.as_f64() };
        let kind = num(0)? as f32;
        if ![SIGNAL, INTERRUPT, SPEED, NOTHING].contains(&kind) {
            return None;
        }
        Some(Def {
            kind,
            distance: num(1)?,
            start: f.get(2)?.as_bool()?,
            time: f.get(3)?.as_bool()?,
            lead: num(4)?,
            signal: f.get(5)?.as_str()?.to_string(),
            value: num(6)?,
            intno: num(7)? as i32,
        })
    }

    fn event(&self) -> TriggEvent {
        let place = if self.start {
            TriggPlace::AfterStart(self.distance)
        } else if self.time {
            TriggPlace::BeforeEndTime(self.distance)
        } else {
            TriggPlace::BeforeEnd(self.distance)
        };
        let action = if self.kind == INTERRUPT {
            TriggAction::Program(ProgramAction::Interrupt(self.intno))
        } else if self.kind == SPEED {
            TriggAction::Speed {
                name: self.signal.clone(),
                scale: self.value,
            }
        } else {
            TriggAction::Signal {
                name: self.signal.clone(),
                value: self.value,
            }
        };
        TriggEvent {
            place,
            lead_s: self.lead,
            action,
        }
    }
}

/// A distance (mm) or time (s) that is a finite number.
fn distance(cx: &Ctx<'_>, i: usize) -> Exec<f64> {
    let d = cx.f64(i)?;
    if !d.is_finite() {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("Distance {d} is not a number"),
        ));
    }
    Ok(d)
}

/// The output of `\DOp | \GOp | \AOp | \ProcID` at `first`…`first + 3`.
fn output(cx: &Ctx<'_>, first: usize) -> Exec<String> {
    if cx.present(first + 3) {
        return Err(cx.unsupported(
            "\\ProcID addresses a process of the IPM option; use \\DOp, \\GOp or \\AOp",
        ));
    }
    match (first..first + 3).find(|&i| cx.present(i)) {
        Some(i) => crate::interp::builtins::io::signal_name(cx, i),
        None => Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!(
                "{} needs the signal to set: \\DOp, \\GOp or \\AOp",
                cx.name()
            ),
        )),
    }
}

/// `TriggIO TriggData, Distance [\Start] | [\Time] [\DOp] | [\GOp] | [\AOp] | [\ProcID],
/// SetValue [\DODelay]`: set an output at `Distance` mm before the ToPoint (`\Start`: after
/// the start point; `\Time`: seconds before the ToPoint). `\DODelay` sets it that many
/// seconds later (up to the end of the move).
pub(super) fn trigg_io(cx: &mut Ctx<'_>) -> Exec<Value> {
    let d = distance(cx, 1)?;
    let signal = output(cx, 4)?;
    let value = cx.f64(8)?;
    let delay = cx.opt_f64(9)?.unwrap_or(0.0);
    if !(delay >= 0.0 && delay.is_finite()) {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("DODelay {delay} s is not a time"),
        ));
    }
    let def = Def {
        kind: SIGNAL,
        distance: d,
        start: cx.present(2),
        time: cx.present(3),
        lead: -delay,
        signal,
        value,
        intno: 0,
    };
    cx.set(0, def.value())?;
    Ok(Value::Absent)
}

/// `TriggEquip TriggData, Distance [\Start], EquipLag, [\DOp] | [\GOp] | [\AOp] |
/// [\ProcID], SetValue [\Inhib] [\InhibSetValue]`: as `TriggIO`, set `EquipLag` seconds
/// earlier than the place (negative: later) so that equipment with that lag acts there.
/// `\Inhib` is read when `TriggEquip` runs: when TRUE, the event sets `InhibSetValue`, or
/// nothing without it.
pub(super) fn trigg_equip(cx: &mut Ctx<'_>) -> Exec<Value> {
    let d = distance(cx, 1)?;
    let lag = cx.f64(3)?;
    if !lag.is_finite() {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("EquipLag {lag} is not a time"),
        ));
    }
    let signal = output(cx, 4)?;
    let mut value = cx.f64(8)?;
    let mut kind = SIGNAL;
    if cx.present(9) && cx.bool(9)? {
        match cx.opt_f64(10)? {
            Some(v) => value = v,
            None => kind = NOTHING,
        }
    }
    let def = Def {
        kind,
        distance: d,
        start: cx.present(2),
        time: false,
        lead: lag,
        signal,
        value,
        intno: 0,
    };
    cx.set(0, def.value())?;
    Ok(Value::Absent)
}

/// `TriggInt TriggData, Distance [\Start] | [\Time], Interrupt [\Inpos]`: order the
/// interrupt there. The interrupt must be connected (`ERR_UNKINO`). `\Inpos` is accepted:
/// the virtual robot is in position when it reaches the point.
pub(super) fn trigg_int(cx: &mut Ctx<'_>) -> Exec<Value> {
    let d = distance(cx, 1)?;
    let no = cx.f64(4)? as i32;
    cx.it.check_intno(no, cx.span)?;
    let def = Def {
        kind: INTERRUPT,
        distance: d,
        start: cx.present(2),
        time: cx.present(3),
        lead: 0.0,
        signal: String::new(),
        value: 0.0,
        intno: no,
    };
    cx.set(0, def.value())?;
    Ok(Value::Absent)
}

/// `TriggSpeed TriggData, Distance [\Start], ScaleLag, AOp, ScaleValue [\DipLag] [\ErrDO]
/// [\Inhib]`: from the place on (`ScaleLag` seconds earlier), the analog output follows the
/// TCP speed: `ScaleValue × speed` (mm/s), clamped to the signal's range, until the next
/// `TriggSpeed` event; `ScaleValue` 0 sets it to 0. `\Inhib` TRUE (read when `TriggSpeed`
/// runs) makes the value 0. `\DipLag` and `\ErrDO` are accepted: the virtual robot's speed
/// never dips below the programmed speed unannounced, so `\ErrDO` is never set.
pub(super) fn trigg_speed(cx: &mut Ctx<'_>) -> Exec<Value> {
    let d = distance(cx, 1)?;
    let lag = cx.f64(3)?;
    if !(lag.is_finite() && lag >= 0.0) {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("ScaleLag {lag} s is not a time"),
        ));
    }
    let signal = crate::interp::builtins::io::signal_name(cx, 4)?;
    let mut scale = cx.f64(5)?;
    if !scale.is_finite() {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("ScaleValue {scale} is not a number"),
        ));
    }
    if cx.present(8) && cx.bool(8)? {
        scale = 0.0;
    }
    let def = Def {
        kind: SPEED,
        distance: d,
        start: cx.present(2),
        time: false,
        lead: lag,
        signal,
        value: scale,
        intno: 0,
    };
    cx.set(0, def.value())?;
    Ok(Value::Absent)
}

/// `TriggL`/`TriggJ`/`TriggC [\Conc,] [CirPoint,] ToPoint [\ID], Speed [\T], Trigg_1 [\T2]
/// … [\T8], Zone, Tool [\WObj] [\Corr] [\TLoad]`.
pub(super) fn trigg_move(cx: &mut Ctx<'_>, kind: Kind, name: &'static str) -> Exec<Value> {
    let c = usize::from(kind == Kind::C);
    let first_trigg = 5 + c;
    let zone = first_trigg + 8;
    let at = At {
        cir: (kind == Kind::C).then_some(1),
        to: 1 + c,
        speed: 3 + c,
        v: None,
        t: 4 + c,
        zone: Some(zone),
        tool: zone + 1,
        wobj: zone + 2,
        // TriggJ has no \Corr.
        tload: if kind == Kind::J { zone + 3 } else { zone + 4 },
    };
    let mut events = Vec::with_capacity(8);
    for i in first_trigg..first_trigg + 8 {
        if !cx.present(i) {
            continue;
        }
        let Some(def) = Def::read(cx.value(i)?) else {
            return Err(cx.error(
                errnum::ERR_ARGVALERR,
                format!(
                    "argument {} of {name} is a triggdata no TriggIO, TriggEquip, TriggInt or TriggSpeed defined",
                    i - first_trigg + 1
                ),
            ));
        };
        if def.kind == NOTHING {
            continue;
        }
        if def.kind == INTERRUPT {
            cx.it.check_intno(def.intno, cx.span)?;
        }
        events.push(def.event());
    }
    let cmd = command(cx, kind, at)?;
    submit(cx, cmd, name, events, cx.present(0), at)?;
    Ok(Value::Absent)
}
