//! The controller's system side as RAPID reaches it (`crate::system`, through
//! `Host::system`): the calendar (`CDate`, `CTime`, `GetTime`), the system's identity and
//! modes (`GetSysInfo`, `IsSysId`, `RobOS`, `OpMode`, `RunMode`, `NonMotionMode`,
//! `PPMovedInManMode`), the task and its mechanical units (`GetTaskName`, `RobName`,
//! `GetMecUnitName`, `GetNextMechUnit`, `IsMechUnitActive`, `MaxRobSpeed`), the active system
//! data (`GetSysData`, `SetSysData`), the configuration database (`ReadCfgData`,
//! `WriteCfgData`, `SaveCfgData`), text tables (`TextTabGet`, `TextGet`,
//! `TextTabFreeToUse`), the event log (`ErrLog`, `SkipWarn`), the interpreter's own state
//! (`ExecLevel`, `ExecHandler`, `EventType`, `ProgMemFree`), `WarmStart` (not possible from inside a run)
//! and `Linked_m_exe` (declared for backups' LINKEDM module; not supported when called).

use super::{Ctx, Registry};
use crate::interp::NArg;
use crate::interp::errnum;
use crate::interp::error::{ErrorKind, Exec, Unwind};
use crate::interp::host::{Output, no_robot};
use crate::interp::place::AbsRoot;
use crate::interp::value::Value;
use crate::ir::{Storage, Ty};
use crate::system::Services;
use crate::system::calendar::TimePart;
use crate::system::cfg_data::{CfgError, RapidKind, RapidValue};
use crate::system::info::{RUN_CONT_CYCLE, SysDataKind};

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    // Calendar.
    r.add("FUNC string CDate()", |cx| {
        let text = with_system(cx, |s, now| s.calendar.date_text(now))?;
        cx.string(text)
    });
    r.add("FUNC string CTime()", |cx| {
        let text = with_system(cx, |s, now| s.calendar.time_text(now))?;
        cx.string(text)
    });
    r.add(
        r"FUNC num GetTime(\switch WDay | switch Hour | switch Min | switch Sec)",
        get_time,
    );
    // Identity and modes.
    r.add(
        r"FUNC string GetSysInfo(\switch SerialNo | switch SWVersion | switch RobotType | switch CtrlId | switch LanIp | switch CtrlLang | switch SystemName | switch SWVersionName)",
        get_sys_info,
    );
    r.add("FUNC bool IsSysId(string SystemId)", |cx| {
        let id = cx.str(0)?.to_string();
        with_system(cx, |s, _| Value::Bool(s.info.is_sys_id(&id)))
    });
    // rapidvc is a virtual controller: never the robot controller's operating system.
    r.add("FUNC bool RobOS()", |_| Ok(Value::Bool(false)));
    r.add("FUNC symnum OpMode()", |cx| {
        with_system(cx, |s, _| Value::Num(s.info.op_mode.symnum()))
    });
    r.add(r"FUNC symnum RunMode(\switch Main)", |_| {
        Ok(Value::Num(RUN_CONT_CYCLE))
    });
    // Moves always move the robot (there is no non-motion execution), and nobody can move
    // the program pointer by hand.
    r.add(r"FUNC bool NonMotionMode(\switch Main)", |_| {
        Ok(Value::Bool(false))
    });
    r.add("FUNC bool PPMovedInManMode()", |_| Ok(Value::Bool(false)));
    // Task and mechanical units.
    r.add(
        r"FUNC string GetTaskName(\VAR num TaskNo | VAR num MecTaskNo)",
        |cx| {
            // Among several tasks the scheduler knows the name and numbers; alone, the
            // task is number 1 and moves its own robot.
            let (task, numbers) = match cx.host().tasks() {
                Some(t) => (t.task_name(), [t.task_number(), t.mec_task_number()]),
                None => (with_system(cx, |s, _| s.info.task.clone())?, [1, 1]),
            };
            for (i, n) in numbers.into_iter().enumerate() {
                if cx.present(i) {
                    cx.set(i, Value::Num(n as f32))?;
                }
            }
            cx.string(task)
        },
    );
    r.add("FUNC string RobName()", |cx| {
        let name = with_system(cx, |s, _| s.info.robot.map(|r| r.unit()))?;
        cx.string(name.unwrap_or_default().to_string())
    });
    r.add("FUNC string GetMecUnitName(mecunit MechUnit)", |cx| {
        let name = mecunit_name(cx, 0)?;
        cx.string(name)
    });
    r.add(
        r"FUNC bool GetNextMechUnit(INOUT num ListNumber, INOUT string UnitName, \VAR mecunit MecRef, \VAR bool TCPRob, \VAR num NoOfAxes, \VAR num MecTaskNo, \VAR num MotPlanNo, \VAR bool Active, \VAR num DriveModule, \VAR bool OKToDeact)",
        get_next_mech_unit,
    );
    r.add("FUNC bool IsMechUnitActive(mecunit MechUnit)", |cx| {
        let name = mecunit_name(cx, 0)?;
        with_system(cx, |s, _| {
            Value::Bool(
                s.info
                    .mech_units()
                    .iter()
                    .any(|u| u.unit().eq_ignore_ascii_case(&name)),
            )
        })
    });
    r.add("FUNC num MaxRobSpeed()", |cx| {
        match with_system(cx, |s, _| s.info.robot.map(|r| r.max_tcp_speed()))? {
            Some(v) => cx.num_result(v),
            None => Err(cx.host_err(no_robot())),
        }
    });
    // The interpreter's own state.
    r.add("FUNC exec_level ExecLevel()", |cx| {
        Ok(Value::Num(if cx.it.ints.in_trap() { 1.0 } else { 0.0 }))
    });
    r.add("FUNC handler_type ExecHandler()", |cx| {
        Ok(Value::Num(f32::from(exec_handler(cx))))
    });
    // rapidvc runs no event routines (POWER_ON, START, STOP, …), so no code ever runs as
    // one: EVENT_NONE.
    r.add("FUNC event_type EventType()", |_| Ok(Value::Num(0.0)));
    r.add("FUNC num ProgMemFree()", |cx| {
        let free = crate::ir::limits::MAX_TASK_VALUES.saturating_sub(cx.it.data_values);
        let bytes = free.saturating_mul(std::mem::size_of::<Value>() as u64);
        cx.num_result(bytes as f64)
    });
    // Active system data.
    r.add(
        r"PROC GetSysData(PERS anytype DestObject, \INOUT string ObjectName)",
        get_sys_data,
    );
    r.add(
        r"PROC SetSysData(PERS anytype SourceObject, \string ObjectName)",
        set_sys_data,
    );
    // Configuration database.
    r.add(
        r"PROC ReadCfgData(string InstancePath, string Attribute, INOUT anytype CfgData, \INOUT num ListNo)",
        read_cfg_data,
    );
    r.add(
        r"PROC WriteCfgData(string InstancePath, string Attribute, anytype CfgData, \INOUT num ListNo)",
        write_cfg_data,
    );
    r.add(
        r"PROC SaveCfgData(string FilePath, \string File, cfgdomain Domain)",
        save_cfg_data,
    );
    // Text tables.
    r.add("FUNC num TextTabGet(string TableName)", |cx| {
        let name = cx.str(0)?.to_string();
        match with_system(cx, |s, _| s.texts.number(&name))? {
            Some(n) => Ok(Value::Num(n as f32)),
            None => Err(cx.error(
                errnum::ERR_TXTNOEXIST,
                format!("no text table `{name}` is installed"),
            )),
        }
    });
    r.add("FUNC string TextGet(num Table, num Index)", |cx| {
        let (table, index) = (cx.int(0, "Table")?, cx.int(1, "Index")?);
        let text = with_system(cx, |s, _| {
            let t = u32::try_from(table).ok()?;
            let i = u32::try_from(index).ok()?;
            s.texts.text(t, i).map(str::to_string)
        })?;
        match text {
            Some(t) => cx.string(t),
            None => Err(cx.error(
                errnum::ERR_TXTNOEXIST,
                format!("text table {table} has no text {index}"),
            )),
        }
    });
    r.add("FUNC bool TextTabFreeToUse(string TableName)", |cx| {
        let name = cx.str(0)?.to_string();
        with_system(cx, |s, _| Value::Bool(s.texts.number(&name).is_none()))
    });
    // Event log.
    r.add(
        r"PROC ErrLog(num ErrorId, \switch W | switch I, errstr Argument1, errstr Argument2, errstr Argument3, errstr Argument4, errstr Argument5)",
        err_log,
    );
    // rapidvc writes no warning for an error an ERROR handler takes, so there is never one
    // for SkipWarn to keep out of the event log.
    r.add("PROC SkipWarn()", |_| Ok(Value::Absent));
    r.add("PROC WarmStart()", |cx| {
        Err(cx.it.fatal(
            ErrorKind::Unsupported,
            cx.span,
            "`WarmStart` is not supported by rapidvc: a warm start restarts the controller, \
             which a run cannot do from inside its program (start the run again instead)",
        ))
    });
    // The service routine `Linked_m` of every controller's LINKEDM system module calls
    // `Linked_m_exe`, which RobotWare installs in an encrypted module for electronically
    // linked motors. Declared so that a backup's SYSMOD checks and its programs run; calling
    // it stops the program with the reason (rapidvc has no linked motors).
    r.add("PROC Linked_m_exe()", |cx| {
        Err(cx.it.fatal(
            ErrorKind::Unsupported,
            cx.span,
            "`Linked_m_exe` is not supported by rapidvc: it is ABB's service routine for \
             electronically linked motors (a master and a follower axis), and the virtual \
             robot has no linked motors",
        ))
    });
}

/// Run `f` on the host's system side (with the host's time in seconds), or fail with "… is not
/// supported by this controller".
fn with_system<T>(cx: &mut Ctx<'_>, f: impl FnOnce(&mut Services, f64) -> T) -> Exec<T> {
    let now = cx.now_secs();
    match cx.host().system().map(|s| f(s, now)) {
        Some(v) => Ok(v),
        None => Err(cx.it.fatal(
            ErrorKind::Unsupported,
            cx.span,
            format!(
                "`{}` is not supported by this controller (it has no system side; \
                 `rapidvc run` and `rapidvc test` have)",
                cx.name()
            ),
        )),
    }
}

/// `ExecHandler`: the handler the calling routine is executing: `HANDLER_ERR` (2) in its
/// ERROR handler, `HANDLER_UNDO` (3) in its UNDO handler, `HANDLER_NONE` (0) elsewhere
/// (rapidvc has no backward execution, so never `HANDLER_BWD`).
fn exec_handler(cx: &Ctx<'_>) -> u8 {
    let Some(frame) = cx.it.frames.last() else {
        return 0;
    };
    let Some(r) = cx.p.routines.get(frame.routine.0 as usize) else {
        return 0;
    };
    let within = |b: &crate::ir::Block| match (b.stmts.first(), b.stmts.last()) {
        (Some(first), Some(last)) => {
            first.span.source == frame.at.source
                && first.span.start <= frame.at.start
                && frame.at.end <= last.span.end
        }
        _ => false,
    };
    if r.error.as_ref().is_some_and(|h| within(&h.body)) {
        2
    } else if r.undo.as_ref().is_some_and(within) {
        3
    } else {
        0
    }
}

/// Which of the mutually exclusive switches `first..first + n` was given.
fn which_switch(cx: &Ctx<'_>, n: usize, names: &str) -> Exec<usize> {
    (0..n).find(|&i| cx.present(i)).ok_or_else(|| {
        cx.error(
            errnum::ERR_ARGVALERR,
            format!("`{}` needs one of {names}", cx.name()),
        )
    })
}

fn get_time(cx: &mut Ctx<'_>) -> Exec<Value> {
    let part = match which_switch(cx, 4, r"\WDay, \Hour, \Min or \Sec")? {
        0 => TimePart::WeekDay,
        1 => TimePart::Hour,
        2 => TimePart::Minute,
        _ => TimePart::Second,
    };
    with_system(cx, |s, now| Value::Num(s.calendar.part(now, part) as f32))
}

fn get_sys_info(cx: &mut Ctx<'_>) -> Exec<Value> {
    let which = which_switch(
        cx,
        8,
        r"\SerialNo, \SWVersion, \RobotType, \CtrlId, \LanIp, \CtrlLang, \SystemName or \SWVersionName",
    )?;
    let text = with_system(cx, |s, _| {
        let i = &s.info;
        match which {
            0 => i.serial.clone(),
            1 => i.sw_version.clone(),
            2 => i
                .robot
                .map(|r| r.robot_type().to_string())
                .unwrap_or_default(),
            3 => i.ctrl_id.clone(),
            4 => i.lan_ip.clone(),
            5 => i.language.clone(),
            6 => i.system_name.clone(),
            // The version as RWS's `rwversionname` gives it.
            _ => crate::system::info::ROBOTWARE_VERSION.to_string(),
        }
    })?;
    cx.string(text)
}

/// The name of the `mecunit` argument `i`.
fn mecunit_name(cx: &Ctx<'_>, i: usize) -> Exec<String> {
    let v = cx.value(i)?;
    match v.fields() {
        Some([Value::Str(name)]) => Ok(name.to_string()),
        _ => Err(cx.it.type_bug(cx.span, "mecunit", v)),
    }
}

fn get_next_mech_unit(cx: &mut Ctx<'_>) -> Exec<Value> {
    let n = cx.f64(0)?;
    let units = with_system(cx, |s, _| s.info.mech_units())?;
    let unit = (n >= 0.0 && n.fract() == 0.0)
        .then(|| units.get(n as usize))
        .flatten();
    let Some(unit) = unit else {
        return Ok(Value::Bool(false));
    };
    cx.set(0, Value::Num((n + 1.0) as f32))?;
    cx.set(1, Value::str(unit.unit()))?;
    let outputs = [
        (2, Value::Record(Box::new([Value::str(unit.unit())]))),
        (3, Value::Bool(true)),
        (4, Value::Num(unit.axes() as f32)),
        (5, Value::Num(1.0)),
        (6, Value::Num(1.0)),
        (7, Value::Bool(true)),
        (8, Value::Num(1.0)),
        // A TCP robot cannot be deactivated.
        (9, Value::Bool(false)),
    ];
    for (i, v) in outputs {
        if cx.present(i) {
            cx.set(i, v)?;
        }
    }
    Ok(Value::Bool(true))
}

// ----- active system data -----

/// The persistent passed as argument `i`: its global index.
fn pers_arg(cx: &Ctx<'_>, i: usize) -> Option<usize> {
    match cx.arg(i) {
        Some(NArg::Ref(place)) if place.path.is_empty() => match place.root {
            AbsRoot::Global(g) => Some(g as usize),
            _ => None,
        },
        _ => None,
    }
}

/// The global of argument `i` and the kind of system data its type designates.
fn sys_data_arg(cx: &Ctx<'_>, i: usize) -> Exec<(usize, SysDataKind)> {
    let g = pers_arg(cx, i).ok_or_else(|| {
        cx.error(
            errnum::ERR_ARGVALERR,
            format!("`{}` needs an entire persistent", cx.name()),
        )
    })?;
    let glob = &cx.p.globals[g];
    let type_name = cx.p.types.name(glob.ty.base);
    match SysDataKind::of_type(type_name) {
        Some(kind) if glob.ty.rank == 0 => Ok((g, kind)),
        _ => Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!(
                "`{}` takes a tooldata, wobjdata or loaddata persistent, not `{}` of type {type_name}",
                cx.name(),
                glob.name
            ),
        )),
    }
}

/// The persistent called `name` of type `ty`.
fn find_pers(cx: &Ctx<'_>, name: &str, ty: Ty) -> Option<usize> {
    cx.p.globals
        .iter()
        .position(|g| g.storage == Storage::Pers && g.ty == ty && g.name.eq_ignore_ascii_case(name))
}

fn is_read_only(cx: &Ctx<'_>, g: usize) -> bool {
    match cx.p.globals[g].origin {
        crate::ir::GlobalOrigin::Module(m) => cx.p.modules[m.0 as usize].stdlib,
        _ => true,
    }
}

fn get_sys_data(cx: &mut Ctx<'_>) -> Exec<Value> {
    let (dest, kind) = sys_data_arg(cx, 0)?;
    if is_read_only(cx, dest) {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!(
                "`{}` is predefined read-only data; it cannot receive the active value",
                cx.p.globals[dest].name
            ),
        ));
    }
    let active = with_system(cx, |s, _| s.info.active.get(kind).to_string())?;
    let ty = cx.p.globals[dest].ty;
    let Some(src) = find_pers(cx, &active, ty) else {
        return Err(cx.error(
            errnum::ERR_REFUNKDAT,
            format!("the active data `{active}` is not a persistent of this program"),
        ));
    };
    let value = cx.it.globals[src].clone();
    let name = cx.p.globals[src].name.clone();
    cx.set(0, value)?;
    if cx.present(1) {
        cx.set(1, Value::str(&name))?;
    }
    Ok(Value::Absent)
}

fn set_sys_data(cx: &mut Ctx<'_>) -> Exec<Value> {
    let (src, kind) = sys_data_arg(cx, 0)?;
    let name = if cx.present(1) {
        let wanted = cx.str(1)?.to_string();
        let ty = cx.p.globals[src].ty;
        let Some(g) = find_pers(cx, &wanted, ty) else {
            return Err(cx.error(
                errnum::ERR_REFUNKDAT,
                format!(
                    "there is no {} persistent called `{wanted}`",
                    cx.p.types.name(ty.base)
                ),
            ));
        };
        cx.p.globals[g].name.clone()
    } else {
        cx.p.globals[src].name.clone()
    };
    with_system(cx, |s, _| s.info.active.set(kind, &name))?;
    Ok(Value::Absent)
}

/// A move's tool (argument `tool`) and work object (`wobj`, `wobj0` when left out) become
/// the active ones. Nothing happens on a host without a system side.
pub(crate) fn note_move_data(cx: &mut Ctx<'_>, tool: usize, wobj: usize) {
    let tool = pers_arg(cx, tool).map(|g| cx.p.globals[g].name.clone());
    let wobj = if cx.present(wobj) {
        pers_arg(cx, wobj).map(|g| cx.p.globals[g].name.clone())
    } else {
        Some("wobj0".to_string())
    };
    if let Some(s) = cx.host().system() {
        if let Some(t) = tool {
            s.info.active.set(SysDataKind::Tool, &t);
        }
        if let Some(w) = wobj {
            s.info.active.set(SysDataKind::Wobj, &w);
        }
    }
}

/// Make the persistent of argument `arg` the active data of `kind` (`GripLoad`).
pub(crate) fn note_active(cx: &mut Ctx<'_>, kind: SysDataKind, arg: usize) {
    let name = pers_arg(cx, arg).map(|g| cx.p.globals[g].name.clone());
    if let (Some(n), Some(s)) = (name, cx.host().system()) {
        s.info.active.set(kind, &n);
    }
}

/// The value of the active data of `kind` (`CTool`, `CWObj`): the persistent of that name.
pub(crate) fn active_value(cx: &mut Ctx<'_>, kind: SysDataKind) -> Exec<Value> {
    let active = with_system(cx, |s, _| s.info.active.get(kind).to_string())?;
    let type_name = match kind {
        SysDataKind::Tool => "tooldata",
        SysDataKind::Wobj => "wobjdata",
        SysDataKind::Load => "loaddata",
    };
    let ty = cx.p.types.lookup(type_name).map(crate::ir::Ty::scalar);
    match ty.and_then(|ty| find_pers(cx, &active, ty)) {
        Some(g) => Ok(cx.it.globals[g].clone()),
        None => Err(cx.error(
            errnum::ERR_REFUNKDAT,
            format!("the active {type_name} `{active}` is not a persistent of this program"),
        )),
    }
}

// ----- configuration database -----

fn cfg_error(cx: &Ctx<'_>, e: CfgError) -> Unwind {
    match errnum::by_name(e.err_name()) {
        Some(d) => cx.error(d.num, e.to_string()),
        None => cx.it.fatal(ErrorKind::Host, cx.span, e.to_string()),
    }
}

fn ill_type(cx: &Ctx<'_>) -> Unwind {
    cx.error(
        errnum::ERR_CFG_ILLTYPE,
        "CfgData must be a bool, num, dnum or string",
    )
}

fn list_no(cx: &Ctx<'_>, i: usize) -> Exec<Option<f64>> {
    cx.opt_f64(i)
}

fn read_cfg_data(cx: &mut Ctx<'_>) -> Exec<Value> {
    let path = cx.str(0)?.to_string();
    let attr = cx.str(1)?.to_string();
    let kind = match cx.value(2)? {
        Value::Num(_) | Value::Dnum(_) => RapidKind::Number,
        Value::Bool(_) => RapidKind::Bool,
        Value::Str(_) => RapidKind::Text,
        _ => return Err(ill_type(cx)),
    };
    let list = list_no(cx, 3)?;
    let (value, next) = with_system(cx, |s, _| s.cfg.read(&path, &attr, kind, list))?
        .map_err(|e| cfg_error(cx, e))?;
    let value = match (value, cx.value(2)?) {
        (RapidValue::Number(x), Value::Dnum(_)) => Value::Dnum(x),
        (RapidValue::Number(x), _) => cx.num_result(x)?,
        (RapidValue::Bool(b), _) => Value::Bool(b),
        (RapidValue::Text(t), _) => cx.string(t)?,
    };
    cx.set(2, value)?;
    if let Some(n) = next {
        cx.set(3, Value::Num(n as f32))?;
    }
    Ok(Value::Absent)
}

fn write_cfg_data(cx: &mut Ctx<'_>) -> Exec<Value> {
    let path = cx.str(0)?.to_string();
    let attr = cx.str(1)?.to_string();
    let value = match cx.value(2)? {
        Value::Num(x) => RapidValue::Number(f64::from(*x)),
        Value::Dnum(x) => RapidValue::Number(*x),
        Value::Bool(b) => RapidValue::Bool(*b),
        Value::Str(s) => RapidValue::Text(s.to_string()),
        _ => return Err(ill_type(cx)),
    };
    let list = list_no(cx, 3)?;
    let next = with_system(cx, |s, _| s.cfg.write(&path, &attr, &value, list))?
        .map_err(|e| cfg_error(cx, e))?;
    if let Some(n) = next {
        cx.set(3, Value::Num(n as f32))?;
    }
    Ok(Value::Absent)
}

/// The `cfgdomain` constants of `stdlib/system.sys`: `None` for `ALL_DOMAINS`.
fn domain_name(n: f64) -> Option<Option<&'static str>> {
    const DOMAINS: [Option<&str>; 7] = [
        None,
        Some("EIO"),
        Some("MMC"),
        Some("MOC"),
        Some("PROC"),
        Some("SIO"),
        Some("SYS"),
    ];
    if n.fract() != 0.0 || !(1.0..=7.0).contains(&n) {
        return None;
    }
    DOMAINS.get(n as usize - 1).copied()
}

fn save_cfg_data(cx: &mut Ctx<'_>) -> Exec<Value> {
    let dir = cx.str(0)?.to_string();
    let file = if cx.present(1) {
        Some(cx.str(1)?.to_string())
    } else {
        None
    };
    let n = cx.f64(2)?;
    let Some(domain) = domain_name(n) else {
        return Err(cx.error(
            errnum::ERR_CFG_ILL_DOMAIN,
            format!("{n} is not a configuration domain (EIO_DOMAIN, MOC_DOMAIN, …)"),
        ));
    };
    with_system(cx, |s, _| s.cfg.save(&dir, file.as_deref(), domain))?
        .map_err(|e| cfg_error(cx, e))?;
    Ok(Value::Absent)
}

// ----- event log -----

fn err_log(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = cx.int(0, "ErrorId")?;
    if !(4800..=9999).contains(&id) {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!(
                "ErrorId {id} is outside 4800–4999 (texts of an installed message file) and 5000–9999 (the arguments are the text)"
            ),
        ));
    }
    let warning = cx.present(1) || cx.present(2);
    let mut args = Vec::with_capacity(5);
    for i in 3..8 {
        args.push(cx.str(i)?.to_string());
    }
    // 5000–9999: Argument1 is the title and the others the description. 4800–4999 take their
    // text from a message file rapidvc does not have: all five are shown.
    let (header, rest) = if id >= 5000 {
        (
            format!("{id} {}", args[0]).trim_end().to_string(),
            &args[1..],
        )
    } else {
        (id.to_string(), &args[..])
    };
    let reason = rest.iter().filter(|a| !a.is_empty()).cloned().collect();
    cx.host().output(Output::ErrWrite {
        warning,
        header,
        reason,
    });
    Ok(Value::Absent)
}
