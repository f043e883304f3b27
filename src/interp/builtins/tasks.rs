//! Several RAPID tasks: `WaitSyncTask`, `WaitTestAndSet`, `TaskRunMec`, `TaskRunRob`,
//! `TasksInSync`, and the RAPID message queue (`RMQFindSlot`, `RMQSendMessage`,
//! `RMQSendWait`, `RMQGetMessage`, `RMQGetMsgHeader`, `RMQGetMsgData`, `IRMQMessage`,
//! `RMQReadWait`, `RMQEmptyQueue`, `RMQGetSlotName`).
//!
//! They reach the other tasks through the host's task capability
//! ([`crate::interp::host::TaskHost`]); a host without one is a system of one task,
//! `T_ROB1`, the motion task: `WaitSyncTask` with only that task passes at once, the message
//! queue has only that task's slot.
//!
//! Waits (`WaitSyncTask`, `WaitTestAndSet`, `RMQSendWait`, `RMQReadWait`) poll every
//! [`POLL`] seconds of robot time, running traps meanwhile; each poll hands the processor to
//! the other tasks. A message travels as the RAPID literal text of its data (its size is
//! that text's length in bytes, checked against the receiver's `-RmqMaxMsgSize`).

use super::{Ctx, Registry};
use crate::interp::errnum;
use crate::interp::error::{ErrorKind, Exec};
use crate::interp::host::{HostError, RmqMessage};
use crate::interp::value::Value;
use crate::ir::Ty;

/// How often the inter-task waits look again (seconds of robot time).
pub const POLL: f64 = 0.004;

/// The task name of a system without the task capability.
const SINGLE_TASK: &str = "T_ROB1";

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add(
        r"PROC WaitSyncTask(\switch InPos, VAR syncident SyncID, PERS tasks TaskList{*}, \num TimeOut)",
        wait_sync_task,
    );
    r.add("PROC WaitTestAndSet(PERS bool Object)", wait_test_and_set);
    r.add("FUNC bool TaskRunMec()", |cx| {
        Ok(Value::Bool(is_motion(cx)))
    });
    r.add("FUNC bool TaskRunRob()", |cx| {
        Ok(Value::Bool(is_motion(cx)))
    });
    // rapidvc has one robot and no synchronized (MultiMove) movements: no task is ever in
    // synchronized mode.
    r.add(r"FUNC num TasksInSync(\INOUT tasks TaskList{*})", |_| {
        Ok(Value::Num(0.0))
    });
    r.add(
        "PROC RMQFindSlot(INOUT rmqslot Slot, string Name)",
        rmq_find_slot,
    );
    r.add(
        r"PROC RMQSendMessage(VAR rmqslot Slot, anydata SendData, \num UserDef)",
        rmq_send_message,
    );
    r.add(
        r"PROC RMQSendWait(VAR rmqslot Slot, anydata SendData, VAR rmqmessage Message, REF anydata ReceiveDataType, \num UserDef, \num TimeOut)",
        rmq_send_wait,
    );
    r.add(
        "PROC RMQGetMessage(VAR rmqmessage Message)",
        rmq_get_message,
    );
    r.add(
        r"PROC RMQGetMsgHeader(VAR rmqmessage Message, \VAR rmqheader Header, \VAR rmqslot SenderId, \VAR num UserDef)",
        rmq_get_msg_header,
    );
    r.add(
        "PROC RMQGetMsgData(VAR rmqmessage Message, VAR anydata Data)",
        rmq_get_msg_data,
    );
    r.add(
        "PROC IRMQMessage(REF anydata InterruptDataType, VAR intnum Interrupt)",
        irmq_message,
    );
    r.add(
        r"PROC RMQReadWait(VAR rmqmessage Message, \num TimeOut)",
        rmq_read_wait,
    );
    r.add("PROC RMQEmptyQueue()", |cx| {
        if let Some(t) = cx.host().tasks() {
            t.rmq_empty();
        }
        Ok(Value::Absent)
    });
    r.add("FUNC string RMQGetSlotName(rmqslot Slot)", |cx| {
        let slot = slot_of(cx, 0)?;
        let name = match cx.host().tasks() {
            Some(t) => t.rmq_slot_name(slot),
            None => (slot == 1).then(|| SINGLE_TASK.to_string()),
        };
        match name {
            Some(n) => cx.string(n),
            None => Err(cx.error(
                errnum::ERR_RMQ_INVALID,
                format!("slot {slot} is not an RMQ client of this system"),
            )),
        }
    });
}

fn is_motion(cx: &mut Ctx<'_>) -> bool {
    cx.host().tasks().is_none_or(|t| t.is_motion_task())
}

/// The task names of a `tasks` array argument.
fn task_names(cx: &Ctx<'_>, i: usize) -> Exec<Vec<String>> {
    let v = cx.value(i)?;
    let items: Vec<&Value> = match v {
        Value::Array(a) => a.data.iter().collect(),
        other => vec![other],
    };
    Ok(items
        .into_iter()
        .filter_map(|item| match item {
            Value::Record(fs) => match fs.first() {
                Some(Value::Str(s)) => Some(s.trim().to_string()),
                _ => None,
            },
            _ => None,
        })
        .collect())
}

fn wait_sync_task(cx: &mut Ctx<'_>) -> Exec<Value> {
    let ident = super::egm::ident(cx, 1)?;
    let names = task_names(cx, 2)?;
    let timeout = cx.opt_f64(3)?;
    if let Some(t) = timeout
        && !(t.is_finite() && t >= 0.0)
    {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("\\TimeOut must be a time in seconds, not {t}"),
        ));
    }
    let ticket = match cx.host().tasks() {
        Some(t) => t.sync_arrive(&ident, &names),
        None => match names.iter().find(|n| !n.eq_ignore_ascii_case(SINGLE_TASK)) {
            None => Ok(0),
            Some(other) => Err(HostError::fatal(format!(
                "WaitSyncTask: `{other}` is not a task of this system (it runs one task, {SINGLE_TASK})"
            ))),
        },
    }
    .map_err(|e| cx.host_err(e))?;
    let deadline = timeout.map(|t| cx.now().after_secs(t));
    let passed = cx.wait_host(deadline, POLL, |h| {
        Ok(h.tasks().is_none_or(|t| t.sync_passed(&ident, ticket)))
    })?;
    if !passed {
        if let Some(t) = cx.host().tasks() {
            t.sync_leave(&ident, ticket);
        }
        return Err(cx.error(
            errnum::ERR_WAITSYNCTASK,
            format!(
                "WaitSyncTask {ident}: not every task arrived within {} s",
                timeout.unwrap_or_default()
            ),
        ));
    }
    if cx.present(0) {
        // \InPos: the robot of this task stands still in position before the wait ends.
        cx.wait_host(None, POLL, |h| {
            h.motion_reached(crate::interp::host::MotionWait::InPos)
        })?;
    }
    Ok(Value::Absent)
}

fn wait_test_and_set(cx: &mut Ctx<'_>) -> Exec<Value> {
    loop {
        if !cx.bool(0)? {
            cx.set(0, Value::Bool(true))?;
            return Ok(Value::Absent);
        }
        // Wait for one poll (the other tasks run meanwhile), then test again.
        let until = cx.now().after_secs(POLL);
        cx.wait_host(Some(until), POLL, |_| Ok(false))?;
    }
}

// ----- the RAPID message queue -----

/// The name of the type of argument `i` (a data object).
fn type_name_of(cx: &Ctx<'_>, i: usize) -> Exec<String> {
    match super::data_by_name::arg_type(cx, i) {
        Some(ty) => Ok(cx.p.types.name(ty.base).to_string()),
        None => Err(cx.it.fatal(
            ErrorKind::Host,
            cx.span,
            format!(
                "internal error: the type of {}'s argument {} is not known",
                cx.name(),
                i + 1
            ),
        )),
    }
}

/// The slot number held by an `rmqslot` argument.
fn slot_of(cx: &Ctx<'_>, i: usize) -> Exec<i32> {
    match cx.value(i)? {
        Value::Record(fs) => match fs.first() {
            Some(Value::Num(n)) if *n >= 1.0 => Ok(*n as i32),
            _ => Err(cx.error(
                errnum::ERR_RMQ_INVALID,
                "the rmqslot was never set by RMQFindSlot",
            )),
        },
        _ => Err(cx.error(errnum::ERR_RMQ_INVALID, "not an rmqslot")),
    }
}

fn rmq_find_slot(cx: &mut Ctx<'_>) -> Exec<Value> {
    let name = cx.str(1)?.trim().to_string();
    let slot = match cx.host().tasks() {
        Some(t) => t.rmq_find_slot(&name),
        None => name.eq_ignore_ascii_case(SINGLE_TASK).then_some(1),
    };
    match slot {
        Some(n) => {
            cx.set(0, Value::Record(Box::new([Value::Num(n as f32)])))?;
            Ok(Value::Absent)
        }
        None => Err(cx.error(
            errnum::ERR_RMQ_NAME,
            format!("`{name}` is not the name of a task with a RAPID message queue"),
        )),
    }
}

/// The message of sending argument `i` (type, sizes, literal text).
fn message_of(cx: &mut Ctx<'_>, i: usize, userdef: i32) -> Exec<RmqMessage> {
    let v = cx.value(i)?.clone();
    let ty = super::data_by_name::arg_type(cx, i).or(match &v {
        Value::Num(_) => Some(Ty::NUM),
        Value::Dnum(_) => Some(Ty::DNUM),
        Value::Bool(_) => Some(Ty::BOOL),
        Value::Str(_) => Some(Ty::STRING),
        _ => None,
    });
    let Some(ty) = ty else {
        return Err(cx.it.fatal(
            ErrorKind::Unsupported,
            cx.span,
            "sending a computed record value is not supported by rapidvc (its type is not \
             known here): send a data object",
        ));
    };
    let dims = match &v {
        Value::Array(a) => a.dims[..a.rank as usize].to_vec(),
        _ => Vec::new(),
    };
    let sender = match cx.host().tasks() {
        Some(t) => t.task_number(),
        None => 1,
    };
    Ok(RmqMessage {
        datatype: cx.p.types.name(ty.base).to_string(),
        dims,
        data: crate::interp::pers::to_text(&v),
        sender,
        userdef,
        seq: 0,
    })
}

fn userdef(cx: &Ctx<'_>, i: usize) -> Exec<i32> {
    match cx.opt_f64(i)? {
        None => Ok(-1),
        Some(x) if x.fract() == 0.0 && x.abs() <= i32::MAX as f64 => Ok(x as i32),
        Some(x) => Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("\\UserDef must be a whole number, not {x}"),
        )),
    }
}

fn send(cx: &mut Ctx<'_>, slot: i32, msg: RmqMessage) -> Exec<()> {
    let r = match cx.host().tasks() {
        Some(t) => t.rmq_send(slot, msg),
        None => Err(HostError::rapid(
            errnum::ERR_RMQ_INVALID,
            format!("slot {slot}: this system runs one task, which cannot send to itself"),
        )),
    };
    r.map_err(|e| cx.host_err(e))
}

fn rmq_send_message(cx: &mut Ctx<'_>) -> Exec<Value> {
    let slot = slot_of(cx, 0)?;
    let ud = userdef(cx, 2)?;
    let msg = message_of(cx, 1, ud)?;
    send(cx, slot, msg)?;
    Ok(Value::Absent)
}

/// An `rmqmessage` value holding `m`.
fn message_value(m: &RmqMessage) -> Value {
    let dim = |k: usize| Value::Num(m.dims.get(k).copied().unwrap_or(0) as f32);
    Value::Record(Box::new([
        Value::str(&m.datatype),
        Value::Num(m.dims.len() as f32),
        dim(0),
        dim(1),
        dim(2),
        Value::str(&m.data),
        Value::Num(m.sender as f32),
        Value::Num(m.userdef as f32),
        Value::Bool(true),
    ]))
}

/// The message an `rmqmessage` argument holds.
fn message_in(cx: &Ctx<'_>, i: usize) -> Exec<RmqMessage> {
    let invalid = || cx.error(errnum::ERR_RMQ_INVMSG, "the rmqmessage holds no message");
    let Value::Record(fs) = cx.value(i)? else {
        return Err(invalid());
    };
    let num = |k: usize| match fs.get(k) {
        Some(Value::Num(n)) => Some(*n),
        _ => None,
    };
    let text = |k: usize| match fs.get(k) {
        Some(Value::Str(s)) => Some(s.to_string()),
        _ => None,
    };
    if !matches!(fs.get(8), Some(Value::Bool(true))) {
        return Err(invalid());
    }
    let ndim = num(1).unwrap_or(0.0) as usize;
    Ok(RmqMessage {
        datatype: text(0).unwrap_or_default(),
        dims: (0..ndim.min(3))
            .map(|k| num(2 + k).unwrap_or(0.0) as u32)
            .collect(),
        data: text(5).unwrap_or_default(),
        sender: num(6).unwrap_or(0.0) as i32,
        userdef: num(7).unwrap_or(-1.0) as i32,
        seq: 0,
    })
}

fn rmq_get_message(cx: &mut Ctx<'_>) -> Exec<Value> {
    let m = cx.host().tasks().and_then(|t| t.rmq_take());
    match m {
        Some(m) => {
            cx.set(0, message_value(&m))?;
            Ok(Value::Absent)
        }
        None => Err(cx.error(
            errnum::ERR_RMQ_NOMSG,
            "the task's RAPID message queue is empty",
        )),
    }
}

fn rmq_get_msg_header(cx: &mut Ctx<'_>) -> Exec<Value> {
    let m = message_in(cx, 0)?;
    if cx.present(1) {
        let dim = |k: usize| Value::Num(m.dims.get(k).copied().unwrap_or(0) as f32);
        cx.set(
            1,
            Value::Record(Box::new([
                Value::str(&m.datatype),
                Value::Num(m.dims.len() as f32),
                dim(0),
                dim(1),
                dim(2),
            ])),
        )?;
    }
    if cx.present(2) {
        cx.set(2, Value::Record(Box::new([Value::Num(m.sender as f32)])))?;
    }
    if cx.present(3) {
        cx.set(3, Value::Num(m.userdef as f32))?;
    }
    Ok(Value::Absent)
}

fn rmq_get_msg_data(cx: &mut Ctx<'_>) -> Exec<Value> {
    let m = message_in(cx, 0)?;
    let target_ty = type_name_of(cx, 1)?;
    if !target_ty.eq_ignore_ascii_case(&m.datatype) {
        return Err(cx.error(
            errnum::ERR_RMQ_VALUE,
            format!(
                "the message holds a `{}`, the data is a `{target_ty}`",
                m.datatype
            ),
        ));
    }
    let mut target = cx.value(1)?.clone();
    let dims = match &target {
        Value::Array(a) => a.dims[..a.rank as usize].to_vec(),
        _ => Vec::new(),
    };
    if dims != m.dims {
        return Err(cx.error(
            errnum::ERR_RMQ_DIM,
            format!(
                "the message holds data of sizes {:?}, the data has {:?}",
                m.dims, dims
            ),
        ));
    }
    let lit = crate::functions::format::parse_value(&m.data);
    match lit {
        Some(l) if crate::interp::pers::fill(&mut target, &l) => {
            cx.set(1, target)?;
            Ok(Value::Absent)
        }
        _ => Err(cx.error(
            errnum::ERR_RMQ_INVMSG,
            "the message's data cannot be read back",
        )),
    }
}

fn irmq_message(cx: &mut Ctx<'_>) -> Exec<Value> {
    let datatype = type_name_of(cx, 0)?;
    let no = cx.int(1, "interrupt number")? as i32;
    let span = cx.span;
    cx.it.order_rmq(no, datatype, span)?;
    Ok(Value::Absent)
}

/// Wait until the queue holds a message (of `datatype`, when given): true when one came.
fn wait_message(cx: &mut Ctx<'_>, timeout: Option<f64>, datatype: Option<&str>) -> Exec<bool> {
    let deadline = timeout.map(|t| cx.now().after_secs(t));
    cx.wait_host(deadline, POLL, |h| {
        Ok(h.tasks()
            .and_then(|t| t.rmq_peek())
            .is_some_and(|m| datatype.is_none_or(|d| m.datatype.eq_ignore_ascii_case(d))))
    })
}

fn timeout_arg(cx: &Ctx<'_>, i: usize) -> Exec<Option<f64>> {
    match cx.opt_f64(i)? {
        Some(t) if !(t.is_finite() && t >= 0.0) => Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("\\TimeOut must be a time in seconds, not {t}"),
        )),
        other => Ok(other),
    }
}

fn rmq_read_wait(cx: &mut Ctx<'_>) -> Exec<Value> {
    let timeout = timeout_arg(cx, 1)?;
    if !wait_message(cx, timeout, None)? {
        return Err(cx.error(
            errnum::ERR_RMQ_TIMEOUT,
            format!(
                "no RAPID message arrived within {} s",
                timeout.unwrap_or_default()
            ),
        ));
    }
    rmq_get_message(cx)
}

fn rmq_send_wait(cx: &mut Ctx<'_>) -> Exec<Value> {
    let slot = slot_of(cx, 0)?;
    let ud = userdef(cx, 4)?;
    let timeout = timeout_arg(cx, 5)?;
    let answer = type_name_of(cx, 3)?;
    let msg = message_of(cx, 1, ud)?;
    send(cx, slot, msg)?;
    if !wait_message(cx, timeout, Some(&answer))? {
        return Err(cx.error(
            errnum::ERR_RMQ_TIMEOUT,
            format!(
                "no answer of type `{answer}` arrived within {} s",
                timeout.unwrap_or_default()
            ),
        ));
    }
    let m = cx.host().tasks().and_then(|t| t.rmq_take());
    match m {
        Some(m) => {
            cx.set(2, message_value(&m))?;
            Ok(Value::Absent)
        }
        None => Err(cx.error(errnum::ERR_RMQ_NOMSG, "the answer disappeared")),
    }
}
