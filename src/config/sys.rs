//! `SYS.cfg`: the controller's RAPID tasks (`CAB_TASKS`).
//!
//! Each `CAB_TASKS` instance is one task: `-Name`, `-Type` (`NORMAL`, `STATIC` or
//! `SEMISTATIC`; `NORMAL` when absent, as on a controller), `-MotionTask` (a flag, or a
//! `TRUE`/`FALSE` value), `-UseMechanicalUnitGroup`, `-Entry` (the procedure to start,
//! `main` when absent), `-TrustLevel`, and the RAPID message queue of the task
//! (`-RmqType`, `-RmqMaxMsgSize`, `-RmqMaxNoOfMsg`). The many other attributes of a real
//! backup's `CAB_TASKS` (`-TaskInForeground`, `-Hidden`, `-BindRef`, …) are accepted and
//! ignored without a warning, so a backup loads as it is. The tasks keep the file's order:
//! the first is `TASK1` of the backup, and task number 1 of `GetTaskName(\TaskNo)`.
//!
//! Without `CAB_TASKS` (or without SYS.cfg) the system has one task, [`SysConfig::single`]:
//! `T_ROB1`, NORMAL, the motion task.

use crate::diag::Diagnostics;
use crate::source::{SourceId, Span};

use super::ConfigError;
use super::attr::{int_attr, keep, missing_attr, text_attr};
use super::cfg::{CfgFile, CfgInstance, CfgValue};

/// The name of the one task of a system without SYS.cfg.
pub const DEFAULT_TASK: &str = "T_ROB1";

/// Largest RAPID message a queue may be configured for (bytes), as on a controller.
pub const RMQ_MAX_MSG_SIZE: i64 = 3000;

/// Default RAPID message size (bytes) and queue length.
pub const RMQ_DEFAULT_MSG_SIZE: i64 = 400;
/// Default number of messages a task's queue holds.
pub const RMQ_DEFAULT_NO_OF_MSG: i64 = 5;

/// How a task starts and stops (`-Type`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TaskType {
    /// Started and stopped with the program (the default).
    Normal,
    /// Started at boot, restarted from the beginning at a restart; keeps running.
    Static,
    /// Started at boot, restarted from the beginning at a restart; keeps running.
    SemiStatic,
}

impl TaskType {
    /// The `-Type` text.
    pub fn name(self) -> &'static str {
        match self {
            TaskType::Normal => "NORMAL",
            TaskType::Static => "STATIC",
            TaskType::SemiStatic => "SEMISTATIC",
        }
    }
}

/// The RAPID message queue of a task (`-RmqType`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RmqType {
    /// No queue: messages to the task are refused.
    None,
    /// Messages from the controller's own tasks.
    Internal,
    /// Messages from the tasks and from outside (treated as `Internal` by rapidvc).
    Remote,
}

/// One task of `CAB_TASKS`.
#[derive(Clone, Debug, PartialEq)]
pub struct TaskConfig {
    /// `-Name`.
    pub name: String,
    /// `-Type`.
    pub kind: TaskType,
    /// `-MotionTask`: the task that moves the robot.
    pub motion: bool,
    /// `-UseMechanicalUnitGroup` (empty when absent).
    pub mech_group: String,
    /// `-Entry`: the procedure to start.
    pub entry: String,
    /// `-TrustLevel` (empty when absent; rapidvc does not act on it).
    pub trust_level: String,
    /// `-RmqType`.
    pub rmq_type: RmqType,
    /// `-RmqMaxMsgSize` (bytes).
    pub rmq_max_msg_size: usize,
    /// `-RmqMaxNoOfMsg`.
    pub rmq_max_no_of_msg: usize,
    /// Where the instance is written (none for the default task).
    pub span: Option<Span>,
}

impl TaskConfig {
    /// A task with the controller's defaults.
    pub fn new(name: impl Into<String>, kind: TaskType, motion: bool) -> TaskConfig {
        TaskConfig {
            name: name.into(),
            kind,
            motion,
            mech_group: if motion { "rob1".into() } else { String::new() },
            entry: "main".into(),
            trust_level: String::new(),
            rmq_type: RmqType::Internal,
            rmq_max_msg_size: RMQ_DEFAULT_MSG_SIZE as usize,
            rmq_max_no_of_msg: RMQ_DEFAULT_NO_OF_MSG as usize,
            span: None,
        }
    }
}

/// The tasks of a system.
#[derive(Clone, Debug, PartialEq)]
pub struct SysConfig {
    /// The tasks in file order (never empty).
    pub tasks: Vec<TaskConfig>,
}

impl Default for SysConfig {
    fn default() -> Self {
        Self::single()
    }
}

impl SysConfig {
    /// One NORMAL motion task, [`DEFAULT_TASK`].
    pub fn single() -> SysConfig {
        SysConfig {
            tasks: vec![TaskConfig::new(DEFAULT_TASK, TaskType::Normal, true)],
        }
    }

    /// The task called `name` (case-insensitive).
    pub fn task(&self, name: &str) -> Option<&TaskConfig> {
        self.tasks
            .iter()
            .find(|t| t.name.eq_ignore_ascii_case(name))
    }
}

/// Read the tasks of `file` (SYS.cfg). Invalid instances are reported and left out; without
/// any valid task the single default task is used.
pub fn read(file: &CfgFile, diags: &mut Diagnostics) -> SysConfig {
    let src = file.source;
    let mut tasks: Vec<TaskConfig> = Vec::new();
    let mut motion_span: Option<Span> = None;
    for section in file.sections_named("CAB_TASKS") {
        for inst in &section.instances {
            let Some(mut task) = task(src, inst, diags) else {
                continue;
            };
            let span = task.span.unwrap_or_default();
            if let Some(first) = tasks
                .iter()
                .find(|t| t.name.eq_ignore_ascii_case(&task.name))
            {
                diags.push(ConfigError::DuplicateTask {
                    src,
                    span,
                    first: first.span.unwrap_or_default(),
                    name: task.name.clone(),
                });
                continue;
            }
            if task.motion {
                let here = inst.get("MotionTask").map_or(span, |a| a.name_span);
                match motion_span {
                    Some(first) => {
                        diags.push(ConfigError::SeveralMotionTasks {
                            src,
                            span: here,
                            first,
                            name: task.name.clone(),
                        });
                        task.motion = false;
                    }
                    None => motion_span = Some(here),
                }
            }
            tasks.push(task);
        }
    }
    if tasks.is_empty() {
        return SysConfig::single();
    }
    SysConfig { tasks }
}

/// One `CAB_TASKS` instance.
fn task(src: SourceId, inst: &CfgInstance, diags: &mut Diagnostics) -> Option<TaskConfig> {
    let mut failed = false;
    let f = &mut failed;
    let name = keep(text_attr(src, inst, &["Name"], diags), f);
    let kind = keep(text_attr(src, inst, &["Type"], diags), f);
    let group = keep(text_attr(src, inst, &["UseMechanicalUnitGroup"], diags), f);
    let entry = keep(text_attr(src, inst, &["Entry"], diags), f);
    let trust = keep(text_attr(src, inst, &["TrustLevel"], diags), f);
    let rmq = keep(text_attr(src, inst, &["RmqType"], diags), f);
    let size = keep(
        int_attr(
            src,
            inst,
            &["RmqMaxMsgSize"],
            (1, RMQ_MAX_MSG_SIZE),
            "a whole number of bytes, 1 to 3000",
            diags,
        ),
        f,
    );
    let count = keep(
        int_attr(
            src,
            inst,
            &["RmqMaxNoOfMsg"],
            (1, 1000),
            "a whole number of messages, 1 to 1000",
            diags,
        ),
        f,
    );
    let motion = match inst.get("MotionTask") {
        None => false,
        Some(a) => match &a.value {
            CfgValue::Flag => true,
            CfgValue::Str(s) | CfgValue::Word(s) if s.eq_ignore_ascii_case("TRUE") => true,
            CfgValue::Str(s) | CfgValue::Word(s) if s.eq_ignore_ascii_case("FALSE") => false,
            other => {
                bad(
                    src,
                    a.value_or_name_span(),
                    "MotionTask",
                    "no value, TRUE or FALSE",
                    other,
                    diags,
                );
                failed = true;
                false
            }
        },
    };
    let Some((name, name_span)) = name else {
        if !failed {
            missing_attr(src, "CAB_TASKS", inst, "Name", diags);
        }
        return None;
    };
    let valid_name = !name.is_empty()
        && name.len() <= 30
        && name.starts_with(|c: char| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if !valid_name {
        bad(
            src,
            name_span,
            "Name",
            "a RAPID name of at most 30 characters",
            &CfgValue::Str(name),
            diags,
        );
        return None;
    }
    let kind = match kind {
        None => TaskType::Normal,
        Some((k, span)) => match k.trim().to_ascii_uppercase().as_str() {
            "NORMAL" => TaskType::Normal,
            "STATIC" => TaskType::Static,
            "SEMISTATIC" => TaskType::SemiStatic,
            _ => {
                bad(
                    src,
                    span,
                    "Type",
                    "NORMAL, STATIC or SEMISTATIC",
                    &CfgValue::Str(k),
                    diags,
                );
                return None;
            }
        },
    };
    let rmq_type = match rmq {
        None => RmqType::Internal,
        Some((r, span)) => match r.trim().to_ascii_uppercase().as_str() {
            "NONE" => RmqType::None,
            "INTERNAL" => RmqType::Internal,
            "REMOTE" => RmqType::Remote,
            _ => {
                bad(
                    src,
                    span,
                    "RmqType",
                    "None, Internal or Remote",
                    &CfgValue::Str(r),
                    diags,
                );
                return None;
            }
        },
    };
    if failed {
        return None;
    }
    let mut t = TaskConfig::new(name, kind, motion);
    t.mech_group = group.map(|g| g.0).unwrap_or_default();
    if let Some((e, _)) = entry.filter(|e| !e.0.trim().is_empty()) {
        t.entry = e;
    }
    t.trust_level = trust.map(|t| t.0).unwrap_or_default();
    t.rmq_type = rmq_type;
    if let Some((s, _)) = size {
        t.rmq_max_msg_size = s as usize;
    }
    if let Some((n, _)) = count {
        t.rmq_max_no_of_msg = n as usize;
    }
    t.span = Some(inst.span);
    Some(t)
}

fn bad(
    src: SourceId,
    span: Span,
    name: &str,
    expected: &str,
    found: &CfgValue,
    diags: &mut Diagnostics,
) {
    diags.push(ConfigError::BadValue {
        src,
        span,
        name: name.into(),
        expected: expected.into(),
        found: super::attr::found_text(found),
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::SourceMap;

    fn read_text(text: &str) -> (SysConfig, Diagnostics) {
        let mut map = SourceMap::new();
        let id = map.add("SYS.cfg", text);
        let mut diags = Diagnostics::new();
        let file = crate::config::cfg::parse(id, text, &mut diags).expect("parses");
        (read(&file, &mut diags), diags)
    }

    #[test]
    fn reads_three_tasks_in_order() {
        let (sys, diags) = read_text(
            "SYS:CFG_1.0:6:0::\n#\nCAB_TASKS:\n\n\
             -Name \"T_ROB1\" -Type \"NORMAL\" -UseMechanicalUnitGroup \"rob1\" -MotionTask\n\n\
             -Name \"T_LOG\" -Type \"STATIC\" -Entry \"logger\" -TrustLevel \"NoSafety\" \\\n\
             -RmqType \"Internal\" -RmqMaxMsgSize 200 -RmqMaxNoOfMsg 10 -Hidden\n\n\
             -Name \"T_CELL\" -Type \"SEMISTATIC\" -TaskInForeground \"T_ROB1\"\n",
        );
        assert!(!diags.has_errors(), "{diags:?}");
        let names: Vec<_> = sys.tasks.iter().map(|t| t.name.as_str()).collect();
        assert_eq!(names, ["T_ROB1", "T_LOG", "T_CELL"]);
        assert!(sys.tasks[0].motion && !sys.tasks[1].motion && !sys.tasks[2].motion);
        assert_eq!(sys.tasks[0].mech_group, "rob1");
        assert_eq!(sys.tasks[1].kind, TaskType::Static);
        assert_eq!(sys.tasks[1].entry, "logger");
        assert_eq!(sys.tasks[1].rmq_max_msg_size, 200);
        assert_eq!(sys.tasks[1].rmq_max_no_of_msg, 10);
        assert_eq!(sys.tasks[1].trust_level, "NoSafety");
        assert_eq!(sys.tasks[2].kind, TaskType::SemiStatic);
        assert_eq!(sys.tasks[2].entry, "main");
    }

    #[test]
    fn bad_tasks_are_reported() {
        let (sys, diags) = read_text(
            "SYS:CFG_1.0:6:0::\n#\nCAB_TASKS:\n\n\
             -Name \"A\" -MotionTask\n\n-Name \"a\"\n\n-Name \"B\" -MotionTask\n\n\
             -Name \"C\" -Type \"SOMETIMES\"\n\n-Type \"NORMAL\"\n\n-Name \"D\" -RmqMaxMsgSize 5000\n",
        );
        let codes: Vec<String> = diags
            .iter()
            .filter_map(|d| d.code().map(|c| c.to_string()))
            .collect();
        assert_eq!(
            codes,
            [
                "rapidvc::config::duplicate_task",
                "rapidvc::config::several_motion_tasks",
                "rapidvc::config::bad_value",
                "rapidvc::config::missing_attribute",
                "rapidvc::config::bad_value",
            ]
        );
        let names: Vec<_> = sys
            .tasks
            .iter()
            .map(|t| (t.name.as_str(), t.motion))
            .collect();
        assert_eq!(names, [("A", true), ("B", false)]);
    }

    #[test]
    fn without_tasks_one_motion_task() {
        let (sys, _) = read_text("SYS:CFG_1.0:6:0::\n#\nCAB_APP:\n\n-Name \"x\"\n");
        assert_eq!(sys, SysConfig::single());
        assert_eq!(sys.tasks[0].name, DEFAULT_TASK);
        assert!(sys.tasks[0].motion);
    }
}
