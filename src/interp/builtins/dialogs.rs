//! Operator dialogs: `TPReadFK`, `TPReadNum`, `TPReadDnum`, `UIMsgBox`, `UIMessageBox`,
//! `UINumEntry`, `UINumTune`, `UIAlphaEntry`, `UIListView`, `UIClientExist`, `TPShow`.
//!
//! A dialog prints its text on the TP output as it appears, then takes the next answer of
//! the interpreter's [`crate::interp::operator::Operator`] (an answers file, the terminal,
//! or nobody). Without an answer it ends the way ABB documents: after `\MaxTime` seconds
//! (`ERR_TP_MAXTIME`), when `\DIBreak`/`\DOBreak` get their value or `\PersBoolBreak`
//! turns TRUE (`ERR_TP_DIBREAK`, `ERR_TP_DOBREAK`, `ERR_TP_PERSBOOLBREAK`) — the reason
//! goes to `\BreakFlag` when given, else the error is raised. A dialog that nothing can end
//! raises `ERR_TP_NO_CLIENT` (no answer source) or stops the program (an answers file said
//! `!noanswer`).

use std::cell::Cell;

use super::io::{max_time, signal_name};
use super::{Ctx, Registry};
use crate::interp::errnum;
use crate::interp::error::{ErrorKind, Exec};
use crate::interp::host::Output;
use crate::interp::operator::Reply;
use crate::interp::value::{MAX_STRING, Value};

/// The optional parameters that end a dialog without an answer, in this order after the
/// dialog's own parameters.
const BREAKS: &str = r"\num MaxTime, \VAR signaldi DIBreak, \switch DIPassive, \VAR signaldo DOBreak, \switch DOPassive, \PERS bool PersBoolBreak, \switch PersBoolPassive, \VAR errnum BreakFlag";

/// `btnres` values (`stdlib/ui.sys`).
const RES_UNKWN: f64 = 0.0;
/// Button names by `btnres` (1 = `resOK` … 7 = `resNo`).
const BUTTONS: [&str; 7] = ["OK", "Abort", "Retry", "Ignore", "Cancel", "Yes", "No"];
/// The buttons of each `buttondata` (0 = `btnOK` … 5 = `btnYesNoCancel`), as `btnres`.
const BUTTON_SETS: [&[usize]; 6] = [&[1], &[2, 3, 4], &[1, 5], &[3, 5], &[6, 7], &[6, 7, 5]];

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add(
        &format!(
            "PROC TPReadFK(INOUT num TPAnswer, string TPText, string TPFK1, string TPFK2, \
             string TPFK3, string TPFK4, string TPFK5, {BREAKS})"
        ),
        tp_read_fk,
    );
    r.add(
        &format!("PROC TPReadNum(INOUT num TPAnswer, string TPText, {BREAKS})"),
        |cx| tp_read_number(cx, "TPReadNum", false),
    );
    r.add(
        &format!("PROC TPReadDnum(INOUT dnum TPAnswer, string TPText, {BREAKS})"),
        |cx| tp_read_number(cx, "TPReadDnum", true),
    );
    r.add(
        &format!(
            r"PROC UIMsgBox(\string Header, string MsgLine1, \string MsgLine2, \string MsgLine3, \string MsgLine4, \string MsgLine5, \switch Wrap, \buttondata Buttons, \icondata Icon, \string Image, \VAR btnres Result, {BREAKS}, \VAR signaldo UIActiveSignal)"
        ),
        ui_msg_box,
    );
    r.add(
        &format!(
            r"FUNC btnres UIMessageBox(\string Header, \string Message | string MsgArray{{*}}, \switch Wrap, \buttondata Buttons | string BtnArray{{*}}, \btnres DefaultBtn, \icondata Icon, \string Image, {BREAKS}, \VAR signaldo UIActiveSignal)"
        ),
        ui_message_box,
    );
    r.add(
        &format!(
            r"FUNC num UINumEntry(\string Header, \string Message | string MsgArray{{*}}, \switch Wrap, \icondata Icon, \num InitValue, \num MinValue, \num MaxValue, \switch AsInteger, {BREAKS}, \VAR signaldo UIActiveSignal)"
        ),
        ui_num_entry,
    );
    r.add(
        &format!(
            r"FUNC num UINumTune(\string Header, \string Message | string MsgArray{{*}}, \switch Wrap, \icondata Icon, num InitValue, num Increment, \num MinValue, \num MaxValue, {BREAKS}, \VAR signaldo UIActiveSignal)"
        ),
        ui_num_tune,
    );
    r.add(
        &format!(
            r"FUNC string UIAlphaEntry(\string Header, \string Message | string MsgArray{{*}}, \switch Wrap, \icondata Icon, \string InitString, {BREAKS}, \VAR signaldo UIActiveSignal)"
        ),
        ui_alpha_entry,
    );
    r.add(
        &format!(
            r"FUNC num UIListView(\VAR btnres Result, \string Header, listitem ListItems{{*}}, \buttondata Buttons | string BtnArray{{*}}, \icondata Icon, \num DefaultIndex, {BREAKS}, \VAR signaldo UIActiveSignal)"
        ),
        ui_list_view,
    );
    r.add("FUNC bool UIClientExist()", |cx| {
        Ok(Value::Bool(cx.it.operator.present()))
    });
    r.add("PROC TPShow(tpnum Window)", |cx| {
        let w = cx.int(0, "Window")?;
        if !(1..=3).contains(&w) {
            return Err(cx.error(
                errnum::ERR_ARGVALERR,
                format!("{w} is not a TP window (TP_PROGRAM, TP_LATEST, TP_SCREENVIEWER)"),
            ));
        }
        // A virtual controller has one TP output: there is no window to bring forward.
        Ok(Value::Absent)
    });
}

/// How a dialog ended.
enum Ending<T> {
    /// The operator's answer.
    Answer(T),
    /// No answer: the error number of the reason (`ERR_TP_MAXTIME`, …).
    Broken(i32),
}

/// One dialog call: its name, where its break parameters start, the `UIActiveSignal`.
struct Dialog {
    name: &'static str,
    breaks: usize,
    active: Option<usize>,
}

impl Dialog {
    /// Show `lines`, then get an answer through `parse` (or end by the break conditions).
    fn run<T>(
        &self,
        cx: &mut Ctx<'_>,
        lines: Vec<String>,
        parse: impl Fn(&str) -> Result<T, String>,
    ) -> Exec<Ending<T>> {
        self.check_max_time(cx)?;
        self.set_active(cx, 1.0)?;
        let r = self.exchange(cx, lines, parse);
        self.set_active(cx, 0.0)?;
        let end = r?;
        let flag = self.breaks + 7;
        match &end {
            Ending::Answer(_) if cx.present(flag) => cx.set(flag, Value::Num(0.0))?,
            Ending::Answer(_) => {}
            Ending::Broken(errno) => {
                tp(cx, format!("  > no answer ({})", errname(*errno)));
                if cx.present(flag) {
                    cx.set(flag, Value::Num(*errno as f32))?;
                }
            }
        }
        Ok(end)
    }

    /// After a broken dialog has set its default results: raise the reason unless
    /// `\BreakFlag` took it.
    fn finish(&self, cx: &Ctx<'_>, errno: i32) -> Exec<()> {
        if cx.present(self.breaks + 7) {
            return Ok(());
        }
        let why = match errno {
            errnum::ERR_TP_MAXTIME => "nobody answered within \\MaxTime".to_string(),
            errnum::ERR_TP_DIBREAK => "\\DIBreak ended it".to_string(),
            errnum::ERR_TP_DOBREAK => "\\DOBreak ended it".to_string(),
            _ => "\\PersBoolBreak ended it".to_string(),
        };
        Err(cx.error(errno, format!("{}: {why}", self.name)))
    }

    fn check_max_time(&self, cx: &Ctx<'_>) -> Exec<()> {
        max_time(cx, self.breaks).map(drop)
    }

    fn set_active(&self, cx: &mut Ctx<'_>, v: f64) -> Exec<()> {
        if let Some(i) = self.active
            && cx.present(i)
        {
            let name = signal_name(cx, i)?;
            cx.host()
                .write_signal(&name, v)
                .map_err(|e| cx.host_err(e))?;
        }
        Ok(())
    }

    fn exchange<T>(
        &self,
        cx: &mut Ctx<'_>,
        lines: Vec<String>,
        parse: impl Fn(&str) -> Result<T, String>,
    ) -> Exec<Ending<T>> {
        for l in lines {
            tp(cx, l);
        }
        loop {
            let reply = match cx.it.operator.next(self.name) {
                Ok(r) => r,
                Err(e) => return Err(cx.it.fatal(ErrorKind::Host, cx.span, e.0)),
            };
            match reply {
                Reply::Text { text, origin } => match parse(&text) {
                    Ok(v) => {
                        if !cx.it.operator.interactive() {
                            tp(cx, format!("  > {text} ({origin})"));
                        }
                        return Ok(Ending::Answer(v));
                    }
                    Err(why) if cx.it.operator.interactive() => {
                        tp(cx, format!("  ! {why}; answer again"));
                    }
                    Err(why) => {
                        return Err(cx.it.fatal(
                            ErrorKind::Host,
                            cx.span,
                            format!(
                                "{origin}: `{text}` is not an answer to {}: {why}",
                                self.name
                            ),
                        ));
                    }
                },
                Reply::Silent(origin) => return self.without_answer(cx, Some(origin)),
                Reply::Nobody => return self.without_answer(cx, None),
            }
        }
    }

    /// Wait for `\MaxTime` or a break condition.
    fn without_answer<T>(&self, cx: &mut Ctx<'_>, origin: Option<String>) -> Exec<Ending<T>> {
        let b = self.breaks;
        let max = cx.opt_f64(b)?;
        let di = match cx.present(b + 1) {
            true => Some((signal_name(cx, b + 1)?, !cx.present(b + 2))),
            false => None,
        };
        let dout = match cx.present(b + 3) {
            true => Some((signal_name(cx, b + 3)?, !cx.present(b + 4))),
            false => None,
        };
        let pers = match (cx.present(b + 5), cx.it.nargs.get(cx.base + b + 5)) {
            (true, Some(crate::interp::NArg::Ref(r))) => Some((r.clone(), !cx.present(b + 6))),
            _ => None,
        };
        if max.is_none() && di.is_none() && dout.is_none() && pers.is_none() {
            return Err(match origin {
                None => cx.error(
                    errnum::ERR_TP_NO_CLIENT,
                    format!(
                        "{} needs an operator's answer, but nobody can give one: pass \
                         --answers FILE (or run from a terminal), or give the dialog \\MaxTime",
                        self.name
                    ),
                ),
                Some(o) => cx.it.fatal(
                    ErrorKind::Host,
                    cx.span,
                    format!(
                        "{o}: no answer to {}, and it has no \\MaxTime, \\DIBreak, \\DOBreak or \
                         \\PersBoolBreak to end it: it would wait forever",
                        self.name
                    ),
                ),
            });
        }
        let deadline = max.map(|m| cx.now().after_secs(m));
        let reason = Cell::new(errnum::ERR_TP_MAXTIME);
        let (p, span) = (cx.p, cx.span);
        let mut cond = |it: &mut crate::interp::Interp, _: &crate::ir::Program| {
            for (sig, errno) in [
                (&di, errnum::ERR_TP_DIBREAK),
                (&dout, errnum::ERR_TP_DOBREAK),
            ] {
                if let Some((name, high)) = sig {
                    let v = it
                        .host
                        .read_signal(name)
                        .map_err(|e| it.host_error(e, span))?;
                    if (v >= 0.5) == *high {
                        reason.set(errno);
                        return Ok(true);
                    }
                }
            }
            if let Some((place, want)) = &pers {
                let v = it.abs_get(place).map_err(|e| it.walk_err(e, span))?;
                if v.as_bool() == Some(*want) {
                    reason.set(errnum::ERR_TP_PERSBOOLBREAK);
                    return Ok(true);
                }
            }
            Ok(false)
        };
        let broke = if di.is_some() || dout.is_some() || pers.is_some() {
            cx.it.wait(p, span, deadline, Some(&mut cond), 0.1)?
        } else {
            cx.it.wait(p, span, deadline, None, 0.1)?
        };
        let errno = if broke {
            reason.get()
        } else {
            errnum::ERR_TP_MAXTIME
        };
        Ok(Ending::Broken(errno))
    }
}

fn errname(errno: i32) -> &'static str {
    errnum::by_num(errno).map_or("ERR_TP_MAXTIME", |d| d.name)
}

/// A `num` as the TP shows it (single precision: 0.1, not 0.10000000149011612).
fn shown(x: f64) -> String {
    format!("{}", x as f32)
}

fn tp(cx: &mut Ctx<'_>, line: String) {
    cx.host().output(Output::TpWrite(line));
}

/// A number answer.
fn number(text: &str) -> Result<f64, String> {
    let t = text.trim();
    match t.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err("a number is needed".into()),
    }
}

fn tp_read_fk(cx: &mut Ctx<'_>) -> Exec<Value> {
    let text = cx.str(1)?.to_string();
    let keys: Vec<String> = (2..7)
        .map(|i| cx.str(i).map(str::to_string))
        .collect::<Exec<_>>()?;
    let shown: Vec<String> = keys
        .iter()
        .enumerate()
        .filter(|(_, k)| !k.is_empty())
        .map(|(i, k)| format!("[F{} {k}]", i + 1))
        .collect();
    let d = Dialog {
        name: "TPReadFK",
        breaks: 7,
        active: None,
    };
    let lines = vec![text, format!("  {}", shown.join(" "))];
    let parse = |a: &str| {
        let a = a.trim();
        let by_number = a
            .strip_prefix(['F', 'f'])
            .unwrap_or(a)
            .parse::<usize>()
            .ok()
            .filter(|n| (1..=5).contains(n) && !keys[n - 1].is_empty());
        by_number
            .or_else(|| {
                keys.iter()
                    .position(|k| !k.is_empty() && k.eq_ignore_ascii_case(a))
                    .map(|i| i + 1)
            })
            .ok_or_else(|| {
                format!(
                    "a function key is needed: {}",
                    if shown.is_empty() {
                        "none is shown (all five texts are empty)".to_string()
                    } else {
                        shown.join(" ")
                    }
                )
            })
    };
    match d.run(cx, lines, parse)? {
        Ending::Answer(k) => cx.set(0, Value::Num(k as f32))?,
        Ending::Broken(e) => d.finish(cx, e)?,
    }
    Ok(Value::Absent)
}

fn tp_read_number(cx: &mut Ctx<'_>, name: &'static str, dnum: bool) -> Exec<Value> {
    let text = cx.str(1)?.to_string();
    let d = Dialog {
        name,
        breaks: 2,
        active: None,
    };
    let parse = |a: &str| {
        let x = number(a)?;
        if !dnum && crate::functions::math::num_from_f64(x).is_err() {
            return Err(format!("{x} is outside the range of num"));
        }
        Ok(x)
    };
    match d.run(cx, vec![text], parse)? {
        Ending::Answer(x) => {
            let v = if dnum {
                Value::Dnum(x)
            } else {
                Value::Num(x as f32)
            };
            cx.set(0, v)?
        }
        Ending::Broken(e) => d.finish(cx, e)?,
    }
    Ok(Value::Absent)
}

/// The header and message lines of a UI dialog: `\Header`, then `\Message` (index `msg`)
/// or `\MsgArray` (index `msg + 1`), joined into one line with `\Wrap` (index `wrap`).
pub(super) fn ui_text(
    cx: &Ctx<'_>,
    header: Option<usize>,
    msgs: &[usize],
    array: Option<usize>,
    wrap: Option<usize>,
) -> Exec<Vec<String>> {
    let mut body = Vec::new();
    for &i in msgs {
        if cx.present(i) {
            body.push(cx.str(i)?.to_string());
        }
    }
    if let Some(a) = array
        && cx.present(a)
    {
        body.extend(strings(cx, a)?);
    }
    if wrap.is_some_and(|w| cx.present(w)) {
        body = vec![body.join(" ")];
    }
    let mut lines = Vec::new();
    if let Some(h) = header
        && cx.present(h)
    {
        lines.push(format!("== {} ==", cx.str(h)?));
    }
    lines.extend(body);
    Ok(lines)
}

/// The strings of an array argument.
fn strings(cx: &Ctx<'_>, i: usize) -> Exec<Vec<String>> {
    match cx.value(i)? {
        Value::Array(a) => Ok(a
            .data
            .iter()
            .map(|v| v.as_str().unwrap_or("").to_string())
            .collect()),
        other => Err(cx.it.type_bug(cx.span, "string array", other)),
    }
}

/// The buttons of a UI dialog: (label, result) pairs, from `\Buttons` (`btnres` results)
/// or `\BtnArray` (index results); `default` when neither is given.
fn buttons(
    cx: &Ctx<'_>,
    set: usize,
    array: Option<usize>,
    default: Option<i64>,
) -> Exec<Vec<(String, f64)>> {
    if let Some(a) = array
        && cx.present(a)
    {
        return Ok(strings(cx, a)?
            .into_iter()
            .enumerate()
            .map(|(i, s)| (s, (i + 1) as f64))
            .collect());
    }
    let b = match cx.present(set) {
        true => Some(cx.int(set, "Buttons")?),
        false => default,
    };
    let Some(b) = b else { return Ok(Vec::new()) };
    if b == -1 {
        return Ok(Vec::new());
    }
    let Some(list) = usize::try_from(b).ok().and_then(|i| BUTTON_SETS.get(i)) else {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("{b} is not a buttondata (btnNone, btnOK … btnYesNoCancel)"),
        ));
    };
    Ok(list
        .iter()
        .map(|&r| (BUTTONS[r - 1].to_string(), r as f64))
        .collect())
}

fn button_line(buttons: &[(String, f64)]) -> String {
    let b: Vec<String> = buttons.iter().map(|(l, _)| format!("[{l}]")).collect();
    format!("  {}", b.join(" "))
}

/// A button answer: its label (case-insensitive) or its position (1-based).
fn pick_button(buttons: &[(String, f64)], a: &str) -> Result<f64, String> {
    let a = a.trim();
    if buttons.is_empty() {
        return Err(
            "the dialog shows no button (btnNone): only `!noanswer` with \\MaxTime or a break \
             condition ends it"
                .into(),
        );
    }
    if let Some((_, r)) = buttons.iter().find(|(l, _)| l.eq_ignore_ascii_case(a)) {
        return Ok(*r);
    }
    if let Some(r) = a
        .parse::<usize>()
        .ok()
        .and_then(|n| n.checked_sub(1))
        .and_then(|i| buttons.get(i))
    {
        return Ok(r.1);
    }
    let names: Vec<&str> = buttons.iter().map(|(l, _)| l.as_str()).collect();
    Err(format!("a button is needed: {}", names.join(", ")))
}

fn ui_msg_box(cx: &mut Ctx<'_>) -> Exec<Value> {
    let mut lines = ui_text(cx, Some(0), &[1, 2, 3, 4, 5], None, Some(6))?;
    let btns = buttons(cx, 7, None, Some(0))?;
    lines.push(button_line(&btns));
    let d = Dialog {
        name: "UIMsgBox",
        breaks: 11,
        active: Some(19),
    };
    let end = d.run(cx, lines, |a| pick_button(&btns, a))?;
    let (res, broken) = match end {
        Ending::Answer(r) => (r, None),
        Ending::Broken(e) => (RES_UNKWN, Some(e)),
    };
    if cx.present(10) {
        cx.set(10, Value::Num(res as f32))?;
    }
    if let Some(e) = broken {
        d.finish(cx, e)?;
    }
    Ok(Value::Absent)
}

fn ui_message_box(cx: &mut Ctx<'_>) -> Exec<Value> {
    let mut lines = ui_text(cx, Some(0), &[1], Some(2), Some(3))?;
    let btns = buttons(cx, 4, Some(5), Some(0))?;
    lines.push(button_line(&btns));
    let default = cx.opt_f64(6)?.unwrap_or(RES_UNKWN);
    let d = Dialog {
        name: "UIMessageBox",
        breaks: 9,
        active: Some(17),
    };
    match d.run(cx, lines, |a| pick_button(&btns, a))? {
        Ending::Answer(r) => Ok(Value::Num(r as f32)),
        Ending::Broken(e) => {
            d.finish(cx, e)?;
            Ok(Value::Num(default as f32))
        }
    }
}

/// Check the limits of UINumEntry and UINumTune.
fn check_limits(cx: &Ctx<'_>, init: Option<f64>, min: Option<f64>, max: Option<f64>) -> Exec<()> {
    if let (Some(lo), Some(hi)) = (min, max)
        && lo > hi
    {
        return Err(cx.error(
            errnum::ERR_UI_MAXMIN,
            format!("MinValue {lo} is greater than MaxValue {hi}"),
        ));
    }
    if let Some(v) = init
        && (min.is_some_and(|lo| v < lo) || max.is_some_and(|hi| v > hi))
    {
        return Err(cx.error(
            errnum::ERR_UI_INITVALUE,
            format!("InitValue {v} is outside MinValue–MaxValue"),
        ));
    }
    Ok(())
}

fn in_limits(x: f64, min: Option<f64>, max: Option<f64>) -> Result<f64, String> {
    if min.is_some_and(|lo| x < lo) || max.is_some_and(|hi| x > hi) {
        return Err(format!("{x} is outside {}", range_text(min, max)));
    }
    if crate::functions::math::num_from_f64(x).is_err() {
        return Err(format!("{x} is outside the range of num"));
    }
    Ok(x)
}

fn ui_num_entry(cx: &mut Ctx<'_>) -> Exec<Value> {
    let mut lines = ui_text(cx, Some(0), &[1], Some(2), Some(3))?;
    let (init, min, max) = (cx.opt_f64(5)?, cx.opt_f64(6)?, cx.opt_f64(7)?);
    let as_int = cx.present(8);
    check_limits(cx, init, min, max)?;
    if as_int && init.is_some_and(|v| v.fract() != 0.0) {
        return Err(cx.error(
            errnum::ERR_UI_NOTINT,
            format!(
                "InitValue {} is not an integer (\\AsInteger)",
                init.unwrap_or(0.0)
            ),
        ));
    }
    let mut spec = vec![format!("value {}", shown(init.unwrap_or(0.0)))];
    if min.is_some() || max.is_some() {
        spec.push(range_text(min, max));
    }
    if as_int {
        spec.push("integer".into());
    }
    lines.push(format!("  ({})", spec.join(", ")));
    let d = Dialog {
        name: "UINumEntry",
        breaks: 9,
        active: Some(17),
    };
    let parse = |a: &str| {
        let x = in_limits(number(a)?, min, max)?;
        if as_int && x.fract() != 0.0 {
            return Err(format!("{x} is not an integer (\\AsInteger)"));
        }
        Ok(x)
    };
    let end = d.run(cx, lines, parse)?;
    number_result(cx, &d, end, init.unwrap_or(0.0))
}

fn ui_num_tune(cx: &mut Ctx<'_>) -> Exec<Value> {
    let mut lines = ui_text(cx, Some(0), &[1], Some(2), Some(3))?;
    let (init, inc) = (cx.f64(5)?, cx.f64(6)?);
    let (min, max) = (cx.opt_f64(7)?, cx.opt_f64(8)?);
    check_limits(cx, Some(init), min, max)?;
    if !(inc.is_finite() && inc != 0.0) {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("Increment {inc} cannot tune a value"),
        ));
    }
    lines.push(format!(
        "  (value {}, steps of {}{})",
        shown(init),
        shown(inc),
        match (min, max) {
            (None, None) => String::new(),
            (lo, hi) => format!(", {}", range_text(lo, hi)),
        }
    ));
    let d = Dialog {
        name: "UINumTune",
        breaks: 9,
        active: Some(17),
    };
    let parse = |a: &str| {
        let x = in_limits(number(a)?, min, max)?;
        let steps = (x - init) / inc;
        if (steps - steps.round()).abs() > 1e-4 {
            return Err(format!(
                "{x} cannot be reached from {} in steps of {}",
                shown(init),
                shown(inc)
            ));
        }
        Ok(x)
    };
    let end = d.run(cx, lines, parse)?;
    number_result(cx, &d, end, init)
}

/// The result of a number dialog: the answer, or `default` after the break reason.
fn number_result(cx: &Ctx<'_>, d: &Dialog, end: Ending<f64>, default: f64) -> Exec<Value> {
    match end {
        Ending::Answer(x) => Ok(Value::Num(x as f32)),
        Ending::Broken(e) => {
            d.finish(cx, e)?;
            Ok(Value::Num(default as f32))
        }
    }
}

/// `lo to hi` of optional limits.
fn range_text(min: Option<f64>, max: Option<f64>) -> String {
    format!(
        "{} to {}",
        min.map_or("-∞".into(), shown),
        max.map_or("∞".into(), shown)
    )
}

fn ui_alpha_entry(cx: &mut Ctx<'_>) -> Exec<Value> {
    let lines = ui_text(cx, Some(0), &[1], Some(2), Some(3))?;
    let init = match cx.present(5) {
        true => cx.str(5)?.to_string(),
        false => String::new(),
    };
    let d = Dialog {
        name: "UIAlphaEntry",
        breaks: 6,
        active: Some(14),
    };
    let parse = |a: &str| {
        let n = a.chars().count();
        if n > MAX_STRING {
            return Err(format!(
                "{n} characters, a string holds at most {MAX_STRING}"
            ));
        }
        Ok(a.to_string())
    };
    match d.run(cx, lines, parse)? {
        Ending::Answer(s) => Ok(Value::Str(s.into())),
        Ending::Broken(e) => {
            d.finish(cx, e)?;
            Ok(Value::Str(init.into()))
        }
    }
}

fn ui_list_view(cx: &mut Ctx<'_>) -> Exec<Value> {
    let mut lines = ui_text(cx, Some(1), &[], None, None)?;
    let items: Vec<String> = match cx.value(2)? {
        Value::Array(a) => a
            .data
            .iter()
            .map(|v| match v.fields() {
                Some([_, Value::Str(t)]) => t.to_string(),
                _ => String::new(),
            })
            .collect(),
        other => return Err(cx.it.type_bug(cx.span, "listitem array", other)),
    };
    for (i, t) in items.iter().enumerate() {
        lines.push(format!("  {}: {t}", i + 1));
    }
    let btns = buttons(cx, 3, Some(4), None)?;
    if !btns.is_empty() {
        lines.push(button_line(&btns));
    }
    let default = cx.opt_f64(6)?;
    let d = Dialog {
        name: "UIListView",
        breaks: 7,
        active: Some(15),
    };
    let n = items.len();
    let parse = |a: &str| {
        let mut words = a.split_whitespace();
        let idx = words
            .next()
            .and_then(|w| w.parse::<usize>().ok())
            .filter(|i| (1..=n).contains(i))
            .ok_or_else(|| format!("a list index 1 to {n} is needed (then a button)"))?;
        let rest: Vec<&str> = words.collect();
        let res = match (rest.is_empty(), btns.first()) {
            (true, Some((_, r))) => *r,
            (true, None) => RES_UNKWN,
            (false, _) => pick_button(&btns, &rest.join(" "))?,
        };
        Ok((idx, res))
    };
    let (idx, res, broken) = match d.run(cx, lines, parse)? {
        Ending::Answer((i, r)) => (i as f64, r, None),
        Ending::Broken(e) => (default.unwrap_or(0.0), RES_UNKWN, Some(e)),
    };
    if cx.present(0) {
        cx.set(0, Value::Num(res as f32))?;
    }
    if let Some(e) = broken {
        d.finish(cx, e)?;
    }
    Ok(Value::Num(idx as f32))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The numbers in `stdlib/ui.sys` are the ones the natives use.
    #[test]
    fn ui_sys_matches_the_natives() {
        let sys = include_str!("../../../stdlib/ui.sys");
        let value = |name: &str| -> f64 {
            let line = sys
                .lines()
                .find(|l| l.split_whitespace().nth(2) == Some(name))
                .unwrap_or_else(|| panic!("{name} missing"));
            line.split(":=")
                .nth(1)
                .unwrap()
                .trim()
                .trim_end_matches(';')
                .parse()
                .unwrap()
        };
        assert_eq!(value("resUnkwn"), RES_UNKWN);
        for (i, b) in [
            "resOK",
            "resAbort",
            "resRetry",
            "resIgnore",
            "resCancel",
            "resYes",
            "resNo",
        ]
        .iter()
        .enumerate()
        {
            assert_eq!(value(b), (i + 1) as f64);
            assert!(b[3..].eq_ignore_ascii_case(BUTTONS[i]));
        }
        for (i, b) in [
            "btnOK",
            "btnAbrtRtryIgn",
            "btnOKCancel",
            "btnRetryCancel",
            "btnYesNo",
            "btnYesNoCancel",
        ]
        .iter()
        .enumerate()
        {
            assert_eq!(value(b), i as f64);
        }
        assert_eq!(value("btnNone"), -1.0);
        assert_eq!(value("TP_SCREENVIEWER"), 3.0);
    }
}
