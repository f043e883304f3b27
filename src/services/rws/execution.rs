//! `rw/rapid/execution` (state, start, stop, reset of the program pointer), `rw/rapid/tasks`
//! (list, one task, activate, deactivate) and `rw/rapid/modules?task=`.

use std::sync::Arc;

use axum::http::Method;

use super::repr::{Item, RwsError, State};
use super::{Answer, Outcome, Rq, Shared};
use crate::controller::service::{
    CycleMode, ExecState, Request, TaskExecState, TaskInfo, TaskType,
};

/// `ctrlexecstate` text.
pub(super) fn exec_text(s: ExecState) -> &'static str {
    match s {
        ExecState::Running => "running",
        ExecState::Stopped => "stopped",
    }
}

/// `cycle` text.
pub(super) fn cycle_text(c: CycleMode) -> &'static str {
    match c {
        CycleMode::Once => "once",
        CycleMode::Forever => "forever",
        CycleMode::AsIs => "asis",
    }
}

/// One allowed value of a start/stop form field, or a clear 400.
fn one_of<'a>(
    rq: &'a Rq,
    key: &str,
    default: &'a str,
    allowed: &[&str],
) -> Result<&'a str, RwsError> {
    let v = rq.form(key).unwrap_or(default);
    if allowed.iter().any(|a| a.eq_ignore_ascii_case(v)) {
        Ok(v)
    } else {
        Err(RwsError::bad(format!(
            "`{key}={v}`: expected one of {}",
            allowed.join(", ")
        )))
    }
}

pub(super) async fn execution(shared: &Arc<Shared>, rq: &Rq) -> Outcome {
    match (&rq.method, rq.action()) {
        (&Method::GET, None) => {
            let (state, cycle) = shared.ask(Request::Execution).await?;
            Ok(Answer::Ok(
                State::new("rapid", "rw/rapid/", "execution").item(
                    Item::new("rap-execution", "execution")
                        .field("ctrlexecstate", exec_text(state))
                        .field("cycle", cycle_text(cycle)),
                ),
            ))
        }
        (&Method::POST, Some("start")) => {
            one_of(
                rq,
                "regain",
                "continue",
                &["continue", "regain", "clear", "enter_consume"],
            )?;
            let mode = one_of(
                rq,
                "execmode",
                "continue",
                &[
                    "continue",
                    "stepin",
                    "stepover",
                    "stepout",
                    "stepback",
                    "steplast",
                    "stepmotion",
                ],
            )?;
            if !mode.eq_ignore_ascii_case("continue") {
                return Err(RwsError::unsupported(format!(
                    "execmode={mode} (stepwise execution)"
                )));
            }
            let cycle = match one_of(
                rq,
                "cycle",
                "asis",
                &["once", "forever", "asis", "oncedone"],
            )? {
                c if c.eq_ignore_ascii_case("once") => CycleMode::Once,
                c if c.eq_ignore_ascii_case("forever") => CycleMode::Forever,
                c if c.eq_ignore_ascii_case("asis") => CycleMode::AsIs,
                c => return Err(RwsError::unsupported(format!("cycle={c}"))),
            };
            let cond = one_of(rq, "condition", "none", &["none", "callchain"])?;
            if !cond.eq_ignore_ascii_case("none") {
                return Err(RwsError::unsupported(format!("condition={cond}")));
            }
            // rapidvc has no breakpoints, so stopping at them changes nothing; all normal tasks
            // that are active start (the task selection panel is the activation state).
            one_of(rq, "stopatbp", "disabled", &["disabled", "enabled"])?;
            one_of(rq, "alltaskbytsp", "false", &["true", "false"])?;
            shared.ask(|reply| Request::Start { cycle, reply }).await?;
            Ok(Answer::NoContent)
        }
        (&Method::POST, Some("stop")) => {
            let mode = one_of(rq, "stopmode", "stop", &["stop", "qstop", "cycle", "instr"])?;
            if !(mode.eq_ignore_ascii_case("stop") || mode.eq_ignore_ascii_case("qstop")) {
                return Err(RwsError::unsupported(format!("stopmode={mode}")));
            }
            one_of(rq, "usetsp", "normal", &["normal", "alltsk"])?;
            shared.ask(Request::Stop).await?;
            Ok(Answer::NoContent)
        }
        (&Method::POST, Some("resetpp")) => {
            shared.ask(Request::ResetPp).await?;
            Ok(Answer::NoContent)
        }
        _ => Err(rq.unknown_action()),
    }
}

fn type_short(t: TaskType) -> &'static str {
    match t {
        TaskType::Normal => "norm",
        TaskType::Static => "stat",
        TaskType::SemiStatic => "semi",
    }
}

fn type_long(t: TaskType) -> &'static str {
    match t {
        TaskType::Normal => "Normal",
        TaskType::Static => "Static",
        TaskType::SemiStatic => "SemiStatic",
    }
}

/// The list's four-letter execution states (abb_librws compares `read`, `stop`, `star`,
/// `unin`), and the single task's words.
fn exc_short(s: TaskExecState) -> &'static str {
    match s {
        TaskExecState::Ready => "read",
        TaskExecState::Started => "star",
        TaskExecState::Stopped => "stop",
        TaskExecState::Uninitialized => "unin",
    }
}

pub(super) fn exc_long(s: TaskExecState) -> &'static str {
    match s {
        TaskExecState::Ready => "ready",
        TaskExecState::Started => "started",
        TaskExecState::Stopped => "stopped",
        TaskExecState::Uninitialized => "uninitialized",
    }
}

fn task_item(t: &TaskInfo, list: bool) -> Item {
    let (class, exc) = if list {
        ("rap-task-li", exc_short(t.exec_state))
    } else {
        ("rap-task", exc_long(t.exec_state))
    };
    Item::new(class, t.name.clone())
        .link("self", format!("tasks/{}", t.name))
        .link("modules", format!("modules?task={}", t.name))
        .field("name", &t.name)
        .field("type", type_short(t.task_type))
        .field(
            "taskstate",
            if t.exec_state == TaskExecState::Uninitialized {
                "init"
            } else {
                "linked"
            },
        )
        .field("excstate", exc)
        .field("active", if t.active { "On" } else { "Off" })
        .field("motiontask", if t.motion_task { "TRUE" } else { "FALSE" })
        .field("tasktype", type_long(t.task_type))
}

pub(super) async fn tasks(shared: &Arc<Shared>, rq: &Rq, rest: &[&str]) -> Outcome {
    match (rest, &rq.method, rq.action()) {
        ([], &Method::GET, None) => {
            let tasks = shared.ask(Request::Tasks).await?;
            let mut s = State::new("rapid", "rw/rapid/", "tasks");
            for t in &tasks {
                s = s.item(task_item(t, true));
            }
            Ok(Answer::Ok(s))
        }
        ([name], &Method::GET, None) => {
            let tasks = shared.ask(Request::Tasks).await?;
            let t = super::find_ci(&tasks, name, |t| &t.name)
                .ok_or_else(|| RwsError::not_found(format!("no task `{name}`")))?;
            Ok(Answer::Ok(
                State::new("rapid", "rw/rapid/", format!("tasks/{}", t.name))
                    .item(task_item(t, false)),
            ))
        }
        ([name], &Method::POST, Some(a @ ("activate" | "deactivate"))) => {
            let task = name.to_string();
            let active = a == "activate";
            shared
                .ask(|reply| Request::SetTaskActive {
                    task,
                    active,
                    reply,
                })
                .await?;
            Ok(Answer::NoContent)
        }
        ([_], _, _) => Err(rq.unknown_action()),
        _ => Err(RwsError::not_found(format!("no resource {}", rq.path))),
    }
}

pub(super) async fn modules(shared: &Arc<Shared>, rq: &Rq) -> Outcome {
    if rq.method != Method::GET || rq.action().is_some() {
        return Err(rq.unknown_action());
    }
    let task = rq
        .query("task")
        .ok_or_else(|| RwsError::bad("`task=` is required: rw/rapid/modules?task=T_ROB1"))?
        .to_string();
    let list = shared
        .ask(|reply| Request::Modules {
            task: task.clone(),
            reply,
        })
        .await?;
    let mut s = State::new("rapid", "rw/rapid/", format!("modules?task={task}"));
    for m in &list {
        s = s.item(
            Item::new("rap-module-info-li", format!("{task}/{}", m.name))
                .link("self", format!("modules/{}?task={task}", m.name))
                .field("name", &m.name)
                .field("type", if m.system { "SysMod" } else { "ProgMod" }),
        );
    }
    Ok(Answer::Ok(s))
}
