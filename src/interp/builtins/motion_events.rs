//! Moves with position events and searches: `MoveLDO`/`MoveJDO`/`MoveCDO` and their `AO`,
//! `GO` and `Sync` variants, `TriggIO`/`TriggEquip`/`TriggInt`/`TriggSpeed` with
//! `TriggL`/`TriggJ`/`TriggC`, `SearchL`/`SearchC`/`SearchExtJ` and `MoveExtJ`.
//!
//! The natives build a [`MotionCommand`] and a list of [`TriggEvent`]s (place on the path,
//! action) and hand both to the host's [`crate::interp::host::PositionEventHost`]; the
//! planner turns each place into the motion cycle where the TCP gets there, and the
//! controller writes the signal in that cycle. Interrupts (`TriggInt`) and procedures
//! (`MoveLSync`) come back to the interpreter, which runs them at its next check, as traps.
//! The virtual robot's choices are in docs/rapid.md, "Position events and searches".

mod search;
mod trigg;

use super::motion::{data, wait_for};
use super::{Ctx, NativeFn, Registry};
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::host::{HostError, MotionWait, PositionEventHost, TriggAction, TriggEvent};
use crate::interp::value::Value;
use crate::robot::command::{MotionCommand, MoveArgs, MoveC, MoveJ, MoveL, SpeedOverride};
use crate::robot::trigger::TriggPlace;

/// The signatures of this domain.
const SIGNATURES: &[&str] = &[
    r"PROC MoveLDO(robtarget ToPoint, \identno ID, speeddata Speed, \num T, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, VAR signaldo Signal, dionum Value)",
    r"PROC MoveJDO(robtarget ToPoint, \identno ID, speeddata Speed, \num T, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, VAR signaldo Signal, dionum Value)",
    r"PROC MoveCDO(robtarget CirPoint, robtarget ToPoint, \identno ID, speeddata Speed, \num T, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, VAR signaldo Signal, dionum Value)",
    r"PROC MoveLAO(robtarget ToPoint, \identno ID, speeddata Speed, \num T, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, VAR signalao Signal, num Value)",
    r"PROC MoveJAO(robtarget ToPoint, \identno ID, speeddata Speed, \num T, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, VAR signalao Signal, num Value)",
    r"PROC MoveCAO(robtarget CirPoint, robtarget ToPoint, \identno ID, speeddata Speed, \num T, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, VAR signalao Signal, num Value)",
    r"PROC MoveLGO(robtarget ToPoint, \identno ID, speeddata Speed, \num T, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, VAR signalgo Signal, anynum Value)",
    r"PROC MoveJGO(robtarget ToPoint, \identno ID, speeddata Speed, \num T, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, VAR signalgo Signal, anynum Value)",
    r"PROC MoveCGO(robtarget CirPoint, robtarget ToPoint, \identno ID, speeddata Speed, \num T, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, VAR signalgo Signal, anynum Value)",
    r"PROC MoveLSync(robtarget ToPoint, \identno ID, speeddata Speed, \num T, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, string ProcName)",
    r"PROC MoveJSync(robtarget ToPoint, \identno ID, speeddata Speed, \num T, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, string ProcName)",
    r"PROC MoveCSync(robtarget CirPoint, robtarget ToPoint, \identno ID, speeddata Speed, \num T, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, string ProcName)",
    r"PROC TriggIO(VAR triggdata TriggData, num Distance, \switch Start | switch Time, \VAR signaldo DOp | VAR signalgo GOp | VAR signalao AOp | num ProcID, anynum SetValue, \num DODelay)",
    r"PROC TriggEquip(VAR triggdata TriggData, num Distance, \switch Start, num EquipLag, \VAR signaldo DOp | VAR signalgo GOp | VAR signalao AOp | num ProcID, anynum SetValue, \PERS bool Inhib, \anynum InhibSetValue)",
    r"PROC TriggInt(VAR triggdata TriggData, num Distance, \switch Start | switch Time, VAR intnum Interrupt, \switch Inpos)",
    r"PROC TriggSpeed(VAR triggdata TriggData, num Distance, \switch Start, num ScaleLag, VAR signalao AOp, num ScaleValue, \num DipLag, \VAR signaldo ErrDO, \PERS bool Inhib)",
    r"PROC TriggL(\switch Conc, robtarget ToPoint, \identno ID, speeddata Speed, \num T, VAR triggdata Trigg_1, \VAR triggdata T2, \VAR triggdata T3, \VAR triggdata T4, \VAR triggdata T5, \VAR triggdata T6, \VAR triggdata T7, \VAR triggdata T8, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \switch Corr, \PERS loaddata TLoad)",
    r"PROC TriggJ(\switch Conc, robtarget ToPoint, \identno ID, speeddata Speed, \num T, VAR triggdata Trigg_1, \VAR triggdata T2, \VAR triggdata T3, \VAR triggdata T4, \VAR triggdata T5, \VAR triggdata T6, \VAR triggdata T7, \VAR triggdata T8, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad)",
    r"PROC TriggC(\switch Conc, robtarget CirPoint, robtarget ToPoint, \identno ID, speeddata Speed, \num T, VAR triggdata Trigg_1, \VAR triggdata T2, \VAR triggdata T3, \VAR triggdata T4, \VAR triggdata T5, \VAR triggdata T6, \VAR triggdata T7, \VAR triggdata T8, zonedata Zone, PERS tooldata Tool, \PERS wobjdata WObj, \switch Corr, \PERS loaddata TLoad)",
    r"PROC SearchL(\switch Stop | switch PStop | switch SStop | switch Sup, VAR anysignal Signal, \switch Flanks | switch PosFlank | switch NegFlank | switch HighLevel | switch LowLevel, VAR robtarget SearchPoint, robtarget ToPoint, \identno ID, speeddata Speed, \num V | num T, PERS tooldata Tool, \PERS wobjdata WObj, \switch Corr, \PERS loaddata TLoad)",
    r"PROC SearchC(\switch Stop | switch PStop | switch SStop | switch Sup, VAR anysignal Signal, \switch Flanks | switch PosFlank | switch NegFlank | switch HighLevel | switch LowLevel, VAR robtarget SearchPoint, robtarget CirPoint, robtarget ToPoint, \identno ID, speeddata Speed, \num V | num T, PERS tooldata Tool, \PERS wobjdata WObj, \switch Corr, \PERS loaddata TLoad)",
    r"PROC SearchExtJ(\switch Stop | switch PStop | switch SStop | switch Sup, VAR anysignal Signal, \switch Flanks | switch PosFlank | switch NegFlank | switch HighLevel | switch LowLevel, VAR jointtarget SearchJointPos, jointtarget ToJointPos, \identno ID, \switch UseEOffs, speeddata Speed, \num T, \PERS loaddata TLoad)",
    r"PROC MoveExtJ(\switch Conc, jointtarget ToJointPos, \identno ID, \switch UseEOffs, speeddata Speed, \num T, zonedata Zone)",
];

/// The implementation of each entry of [`SIGNATURES`], in the same order.
const IMPLS: [NativeFn; 23] = [
    |cx| move_with_signal(cx, Kind::L, "MoveLDO"),
    |cx| move_with_signal(cx, Kind::J, "MoveJDO"),
    |cx| move_with_signal(cx, Kind::C, "MoveCDO"),
    |cx| move_with_signal(cx, Kind::L, "MoveLAO"),
    |cx| move_with_signal(cx, Kind::J, "MoveJAO"),
    |cx| move_with_signal(cx, Kind::C, "MoveCAO"),
    |cx| move_with_signal(cx, Kind::L, "MoveLGO"),
    |cx| move_with_signal(cx, Kind::J, "MoveJGO"),
    |cx| move_with_signal(cx, Kind::C, "MoveCGO"),
    |cx| move_sync(cx, Kind::L, "MoveLSync"),
    |cx| move_sync(cx, Kind::J, "MoveJSync"),
    |cx| move_sync(cx, Kind::C, "MoveCSync"),
    trigg::trigg_io,
    trigg::trigg_equip,
    trigg::trigg_int,
    trigg::trigg_speed,
    |cx| trigg::trigg_move(cx, Kind::L, "TriggL"),
    |cx| trigg::trigg_move(cx, Kind::J, "TriggJ"),
    |cx| trigg::trigg_move(cx, Kind::C, "TriggC"),
    |cx| search::search(cx, Kind::L),
    |cx| search::search(cx, Kind::C),
    search::search_ext_j,
    move_ext_j,
];

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    for (s, f) in SIGNATURES.iter().zip(IMPLS) {
        r.add(s, f);
    }
}

/// The path of a move.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// Linear.
    L,
    /// Axis-wise.
    J,
    /// Circular.
    C,
}

/// Where a move's arguments sit in its signature.
#[derive(Clone, Copy)]
struct At {
    /// `CirPoint` (circular moves only).
    cir: Option<usize>,
    to: usize,
    speed: usize,
    v: Option<usize>,
    t: usize,
    /// `Zone` (`None`: a stop point, for searches).
    zone: Option<usize>,
    tool: usize,
    wobj: usize,
    tload: usize,
}

impl At {
    /// `[CirPoint,] ToPoint [\ID], Speed [\T], Zone, Tool [\WObj] [\TLoad]` from index
    /// `first` (the layout of `MoveLDO`, `MoveLSync`, …).
    fn plain(kind: Kind, first: usize) -> At {
        let c = usize::from(kind == Kind::C);
        let to = first + c;
        At {
            cir: (kind == Kind::C).then_some(first),
            to,
            speed: to + 2,
            v: None,
            t: to + 3,
            zone: Some(to + 4),
            tool: to + 5,
            wobj: to + 6,
            tload: to + 7,
        }
    }
}

/// The fine zone of a search.
const FINE: crate::robot::command::ZoneData = crate::robot::command::ZoneData::FINE;

/// The command of a move from its arguments and the modal settings.
fn command(cx: &Ctx<'_>, kind: Kind, at: At) -> Exec<MotionCommand> {
    let speed_override = match at.v {
        Some(v) if cx.present(v) => Some(SpeedOverride::V(cx.f64(v)?)),
        _ if cx.present(at.t) => Some(SpeedOverride::T(cx.f64(at.t)?)),
        _ => None,
    };
    let zone = match at.zone {
        Some(z) => data::zonedata(cx, cx.value(z)?)?,
        None => FINE,
    };
    let modes = cx.it.host.motion_modes();
    let args = MoveArgs {
        id: 0,
        source: Some(cx.span),
        speed: data::speeddata(cx, cx.value(at.speed)?)?,
        speed_override,
        zone,
        tool: data::tooldata(cx, cx.value(at.tool)?)?,
        wobj: data::opt_wobj(cx, at.wobj)?,
        tload: if cx.present(at.tload) {
            Some(data::loaddata(cx, cx.value(at.tload)?)?)
        } else {
            None
        },
        pdisp: modes.pdisp,
    };
    let target = data::robtarget(cx, cx.value(at.to)?)?;
    Ok(match (kind, at.cir) {
        (Kind::C, Some(c)) => MotionCommand::MoveC(MoveC {
            args,
            cir_point: data::robtarget(cx, cx.value(c)?)?,
            to_point: target,
            conf_check: modes.conf_l,
        }),
        (Kind::J, _) => MotionCommand::MoveJ(MoveJ {
            args,
            target,
            conf_check: modes.conf_j,
        }),
        _ => MotionCommand::MoveL(MoveL {
            args,
            target,
            conf_check: modes.conf_l,
        }),
    })
}

/// Calls the host's position-event capability; a host without one stops the program.
fn with_events<T>(
    cx: &mut Ctx<'_>,
    f: impl FnOnce(&mut dyn PositionEventHost) -> Result<T, HostError>,
) -> Exec<T> {
    let r = cx.host().position_events().map(f);
    match r {
        Some(Ok(v)) => Ok(v),
        Some(Err(e)) => Err(cx.host_err(e)),
        None => {
            let msg = format!(
                "`{}` is not supported by this controller (it has no robot; `rapidvc run` has)",
                cx.name()
            );
            Err(cx.host_err(HostError::fatal(msg)))
        }
    }
}

/// Queue `cmd` with `events` as instruction `name`; its tool and work object become the
/// active ones; at a stop point without `\Conc` wait until the robot is there. Returns the
/// move's id.
fn submit(
    cx: &mut Ctx<'_>,
    cmd: MotionCommand,
    name: &'static str,
    events: Vec<TriggEvent>,
    conc: bool,
    at: At,
) -> Exec<u64> {
    let stop_point = cmd.args().zone.finep && !conc;
    let program = events
        .iter()
        .any(|e| matches!(e.action, TriggAction::Program(_)));
    let id = with_events(cx, |h| h.submit_with_events(cmd, name, events))?;
    if program {
        cx.it.ints.position = true;
    }
    super::system::note_move_data(cx, at.tool, at.wobj);
    if stop_point {
        wait_for(cx, MotionWait::Done(id))?;
    }
    Ok(id)
}

/// The place of the `Move…DO/AO/GO/Sync` events: the ToPoint (the middle of the corner path
/// for a fly-by point).
const AT_TO_POINT: TriggPlace = TriggPlace::BeforeEnd(0.0);

/// `MoveLDO`, `MoveLAO`, `MoveLGO` and their `J`/`C` variants: `Signal` and `Value` follow
/// `\TLoad`. The value is checked against the signal when the move is queued (`ERR_AO_LIM`,
/// `ERR_GO_LIM`, `ERR_ARGVALERR`, as `SetAO`, `SetGO`, `SetDO` would).
fn move_with_signal(cx: &mut Ctx<'_>, kind: Kind, name: &'static str) -> Exec<Value> {
    let at = At::plain(kind, 0);
    let (sig, val) = (at.tload + 1, at.tload + 2);
    let signal = super::io::signal_name(cx, sig)?;
    let value = cx.f64(val)?;
    let cmd = command(cx, kind, at)?;
    let events = vec![TriggEvent {
        place: AT_TO_POINT,
        lead_s: 0.0,
        action: TriggAction::Signal {
            name: signal,
            value,
        },
    }];
    submit(cx, cmd, name, events, false, at)?;
    Ok(Value::Absent)
}

/// `MoveLSync`, `MoveJSync`, `MoveCSync`: `ProcName` follows `\TLoad`; the procedure must
/// exist (`ERR_REFUNKPRC` at the instruction, not later at the point).
fn move_sync(cx: &mut Ctx<'_>, kind: Kind, name: &'static str) -> Exec<Value> {
    let at = At::plain(kind, 0);
    let proc_name = cx.str(at.tload + 1)?.to_string();
    let known = cx.p.find_proc(&proc_name).is_some_and(|r| {
        let r = cx.p.routine(r);
        r.kind == crate::ir::RoutineKind::Proc && r.params.is_empty()
    });
    if !known {
        return Err(cx.error(
            errnum::ERR_REFUNKPRC,
            format!(
                "there is no procedure `{proc_name}` without parameters to call at the ToPoint"
            ),
        ));
    }
    let cmd = command(cx, kind, at)?;
    let events = vec![TriggEvent {
        place: AT_TO_POINT,
        lead_s: 0.0,
        action: TriggAction::Program(crate::interp::host::ProgramAction::Call(proc_name)),
    }];
    submit(cx, cmd, name, events, false, at)?;
    Ok(Value::Absent)
}

/// `MoveExtJ [\Conc,] ToJointPos [\ID] [\UseEOffs], Speed [\T], Zone`: moves only external
/// axes. The virtual robot has none: nothing moves, the robot's own axes stay where they are
/// (docs/rapid.md); at a stop point the instruction waits, as any stop point, until the moves
/// before it are done.
fn move_ext_j(cx: &mut Ctx<'_>) -> Exec<Value> {
    let target = data::jointtarget(cx, cx.value(1)?)?;
    let speed = data::speeddata(cx, cx.value(4)?)?;
    if let Some(t) = cx.opt_f64(5)?
        && !(t > 0.0 && t.is_finite())
    {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("\\T {t} s is not a time above 0"),
        ));
    }
    if !(speed.v_reax > 0.0 && speed.v_leax > 0.0) {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            "the speeddata of MoveExtJ needs v_leax and v_reax above 0",
        ));
    }
    let zone = data::zonedata(cx, cx.value(6)?)?;
    let _ = target;
    if zone.finep && !cx.present(0) {
        wait_for(cx, MotionWait::InPos)?;
    }
    Ok(Value::Absent)
}
