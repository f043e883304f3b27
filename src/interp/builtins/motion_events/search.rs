//! `SearchL`, `SearchC`, `SearchExtJ`: move towards the ToPoint and watch a digital signal
//! once per motion cycle; where it changes, remember the position (`SearchPoint`) and, with
//! `\Stop`, `\PStop` or `\SStop`, stop the robot (it brakes within the axis limits and ends
//! a little past that position, as ABB's robot does). Without a stop switch (or with
//! `\Sup`) the robot goes on to the ToPoint (a flying search).
//!
//! Errors: `ERR_SIGSUPSEARCH` when a flank search starts with the signal already at the
//! level it looks for (before the robot moves); `ERR_WHLSEARCH` when the robot reached the
//! ToPoint without a hit, or, with `\Sup`, with more than one.

use super::{At, Kind, command, submit, with_events};
use crate::interp::builtins::Ctx;
use crate::interp::builtins::motion::{data, wait_for};
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::host::{MotionWait, SearchStop};
use crate::interp::value::Value;

/// What counts as a hit (`\Flanks`, `\PosFlank` (the default), `\NegFlank`, `\HighLevel`,
/// `\LowLevel`).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Detect {
    Flanks,
    PosFlank,
    NegFlank,
    HighLevel,
    LowLevel,
}

impl Detect {
    /// From the switches at `first`…`first + 4`.
    fn of(cx: &Ctx<'_>, first: usize) -> Detect {
        [
            Detect::Flanks,
            Detect::PosFlank,
            Detect::NegFlank,
            Detect::HighLevel,
            Detect::LowLevel,
        ]
        .into_iter()
        .zip(first..)
        .find(|(_, i)| cx.present(*i))
        .map_or(Detect::PosFlank, |(d, _)| d)
    }

    /// A change from `was` to `now` is a hit.
    fn hit(self, was: bool, now: bool) -> bool {
        match self {
            Detect::Flanks => was != now,
            Detect::PosFlank | Detect::HighLevel => !was && now,
            Detect::NegFlank | Detect::LowLevel => was && !now,
        }
    }

    /// At the start: `Err(())` when a flank search finds the signal already at its level,
    /// `Ok(true)` when a level search is already satisfied.
    fn at_start(self, high: bool) -> Result<bool, ()> {
        match self {
            Detect::PosFlank if high => Err(()),
            Detect::NegFlank if !high => Err(()),
            Detect::HighLevel => Ok(high),
            Detect::LowLevel => Ok(!high),
            _ => Ok(false),
        }
    }
}

/// `\Stop | \PStop | \SStop | \Sup` at 0…3: the stop (`None`: go on to the ToPoint) and
/// whether more than one hit is an error.
fn stop_mode(cx: &Ctx<'_>) -> (Option<SearchStop>, bool) {
    if cx.present(0) {
        (Some(SearchStop::Stop), false)
    } else if cx.present(1) {
        (Some(SearchStop::PStop), false)
    } else if cx.present(2) {
        (Some(SearchStop::SStop), false)
    } else {
        (None, cx.present(3))
    }
}

/// The digital signal of argument 4 (`VAR anysignal`: a `signaldi`, or in rapidvc also a
/// `signaldo`, so that the program itself can drive a search).
fn search_signal(cx: &mut Ctx<'_>) -> Exec<String> {
    let is_signal = matches!(cx.value(4)?.fields(), Some([Value::Str(_)]));
    let name = if is_signal {
        crate::interp::builtins::io::signal_name(cx, 4)?
    } else {
        String::new()
    };
    let digital = cx.host().signal_kind(&name).is_some_and(|k| k.is_digital());
    if !digital {
        return Err(cx.error(
            errnum::ERR_ALIASIO_TYPE,
            format!(
                "{} searches a digital signal (signaldi or signaldo)",
                cx.name()
            ),
        ));
    }
    Ok(name)
}

fn high(cx: &mut Ctx<'_>, signal: &str) -> Exec<bool> {
    let v = cx.host().read_signal(signal).map_err(|e| cx.host_err(e))?;
    Ok(v >= 0.5)
}

fn sigsup(cx: &Ctx<'_>, signal: &str) -> crate::interp::error::Unwind {
    cx.error(
        errnum::ERR_SIGSUPSEARCH,
        format!("signal `{signal}` is already at the level the search looks for when it starts"),
    )
}

/// `SearchL`/`SearchC [\Stop] | [\PStop] | [\SStop] | [\Sup], Signal [\Flanks] |
/// [\PosFlank] | [\NegFlank] | [\HighLevel] | [\LowLevel], SearchPoint, [CirPoint,] ToPoint
/// [\ID], Speed [\V] | [\T], Tool [\WObj] [\Corr] [\TLoad]`.
pub(super) fn search(cx: &mut Ctx<'_>, kind: Kind) -> Exec<Value> {
    let name = if kind == Kind::C {
        "SearchC"
    } else {
        "SearchL"
    };
    let c = usize::from(kind == Kind::C);
    let at = At {
        cir: (kind == Kind::C).then_some(11),
        to: 11 + c,
        speed: 13 + c,
        v: Some(14 + c),
        t: 15 + c,
        zone: None,
        tool: 16 + c,
        wobj: 17 + c,
        tload: 19 + c,
    };
    let signal = search_signal(cx)?;
    let detect = Detect::of(cx, 5);
    let (stop, sup) = stop_mode(cx);
    let tool = data::tooldata(cx, cx.value(at.tool)?)?;
    let wobj = data::opt_wobj(cx, at.wobj)?;
    let cmd = command(cx, kind, at)?;
    let period = with_events(cx, |h| Ok(h.motion_period()))?;
    // The search watches the signal from the start of its own movement: the moves before it
    // end first (ABB's search instructions follow a stop point or a corner path).
    wait_for(cx, MotionWait::InPos)?;
    let mut was = high(cx, &signal)?;
    let start_hit = detect.at_start(was).map_err(|()| sigsup(cx, &signal))?;
    let mut found = None;
    let mut hits = 0u32;
    if start_hit {
        hits = 1;
        found = Some(super::super::motion::position::current_target(
            cx, &tool, &wobj,
        )?);
        if stop.is_some() {
            // A level search already satisfied: the robot does not move.
            let t = found
                .as_ref()
                .map(data::robtarget_value)
                .unwrap_or(Value::Absent);
            cx.set(10, t)?;
            return Ok(Value::Absent);
        }
    }
    let id = submit(cx, cmd, name, Vec::new(), true, at)?;
    loop {
        if cx
            .host()
            .motion_reached(MotionWait::Done(id))
            .map_err(|e| cx.host_err(e))?
        {
            break;
        }
        let deadline = cx.now().saturating_add(period);
        let (p, span) = (cx.p, cx.span);
        cx.it
            .wait(p, span, Some(deadline), None, period.as_secs_f64())?;
        let now = high(cx, &signal)?;
        if detect.hit(was, now) {
            hits += 1;
            if hits == 1 {
                found = Some(super::super::motion::position::current_target(
                    cx, &tool, &wobj,
                )?);
                if let Some(how) = stop {
                    with_events(cx, |h| h.search_stop(how))?;
                    break;
                }
            }
        }
        was = now;
    }
    let Some(point) = found else {
        return Err(cx.error(
            errnum::ERR_WHLSEARCH,
            format!("{name}: signal `{signal}` did not change as searched before the ToPoint"),
        ));
    };
    if sup && hits > 1 {
        return Err(cx.error(
            errnum::ERR_WHLSEARCH,
            format!("{name}\\Sup: signal `{signal}` changed as searched {hits} times, not once"),
        ));
    }
    cx.set(10, data::robtarget_value(&point))?;
    Ok(Value::Absent)
}

/// `SearchExtJ … SearchJointPos, ToJointPos [\ID] [\UseEOffs], Speed [\T] [\TLoad]`: a
/// search with the external axes. The virtual robot has none, so nothing moves: a level
/// search already satisfied is a hit at the current position, a flank search already at its
/// level is `ERR_SIGSUPSEARCH`, anything else ends without a hit (`ERR_WHLSEARCH`).
pub(super) fn search_ext_j(cx: &mut Ctx<'_>) -> Exec<Value> {
    let signal = search_signal(cx)?;
    let detect = Detect::of(cx, 5);
    let _ = data::jointtarget(cx, cx.value(11)?)?;
    let _ = data::speeddata(cx, cx.value(14)?)?;
    wait_for(cx, MotionWait::InPos)?;
    let was = high(cx, &signal)?;
    match detect.at_start(was) {
        Err(()) => Err(sigsup(cx, &signal)),
        Ok(true) => {
            let q = cx.host().motion_joints().map_err(|e| cx.host_err(e))?;
            cx.set(10, data::jointtarget_value(&q))?;
            Ok(Value::Absent)
        }
        Ok(false) => Err(cx.error(
            errnum::ERR_WHLSEARCH,
            format!(
                "SearchExtJ: the robot has no external axes to move, so signal `{signal}` cannot change during the search"
            ),
        )),
    }
}
