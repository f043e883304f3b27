//! Several RAPID tasks on one controller: the scheduler that passes one baton between them,
//! the host each task's interpreter runs on ([`TaskedHost`]), synchronisation points
//! (`WaitSyncTask`) and the RAPID message queues.
//!
//! In real time ([`Scheduler::use_real_time`], for a controller that stays up) the same
//! rule holds, except that waiting takes real time: the motion task's controller runs on
//! its real-time clock, and when the motion task does not wait the task with the earliest
//! deadline sleeps until it.
//!
//! # The scheduling rule (virtual time)
//!
//! Every task has its own interpreter on its own thread, but only the task holding the
//! baton runs; the others are blocked. So a run is one sequence of steps, the same every
//! time:
//!
//! 1. At the start the tasks get the baton in SYS.cfg order (each initialises its data and
//!    starts its entry routine when it first gets it).
//! 2. A task keeps the baton until it waits (`WaitTime`, `WaitUntil`, `WaitDI`, a stop
//!    point, `WaitSyncTask`, an RMQ or socket wait, …: every wait goes through
//!    `Host::wait_until`), ends, or has run [`DEFAULT_SLICE`] statements since it got the
//!    baton (its time slice). It then hands the baton to the next task in SYS.cfg order,
//!    round robin, that can run: one that does not wait, or whose wait's deadline has come.
//!    All tasks have the same priority, as on a controller where no task is set to run in
//!    the foreground of another (`-TaskInForeground` is read but not acted on).
//! 3. When every task waits, virtual time advances to the earliest deadline. The motion
//!    task advances it (its robot moves meanwhile, cycle by cycle; the wait ends early
//!    when a move ends), then the baton goes to the motion task first, then round robin.
//!    Without a running motion task the time jumps.
//! 4. Time advances only then: a task that computes never lets time pass.
//!
//! A task that waits for something another task does (a shared `PERS`, a message) looks
//! again at least every 4 ms of robot time (the inter-task waits' poll).
//!
//! # Task types in `rapidvc run`
//!
//! NORMAL, STATIC and SEMISTATIC tasks all start when the run starts (on a controller the
//! STATIC and SEMISTATIC ones start at boot, which is the same moment here). The run ends
//! when every NORMAL task has ended: the STATIC and SEMISTATIC tasks are then stopped where
//! they are (as the controller's power-off would). An unhandled error in any task stops
//! every task.
//!
//! # The motion task
//!
//! One task (`-MotionTask`) moves the robot; in the others every move instruction, and
//! every function that needs the robot's position, fails with a fatal error naming the
//! task ("… is not a motion task"); ABB refuses motion instructions in a task without a
//! mechanical unit group, and its error number is not published, so rapidvc names none.

use std::collections::{BTreeSet, HashMap, VecDeque};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};

use crate::config::sys::{RmqType, TaskConfig, TaskType};
use crate::interp::errnum;
use crate::interp::host::{
    CorrAnswer, CorrRequest, EgmHost, EgmPathHost, MotionModes, MotionSetting, MotionWait, Output,
    PathCommand, RmqMessage, TaskHost,
};
use crate::interp::{Host, HostError};
use crate::robot::command::{MotionCommand, RobTarget};
use crate::robot::{JointsDeg, Pose, ToolData, WobjData};
use crate::time::{Clock, RobotTime};

/// Statements a task runs before it hands the baton over (when it does not wait earlier).
pub const DEFAULT_SLICE: u64 = 1000;

/// What the scheduler knows of a task.
#[derive(Clone, Debug, PartialEq)]
pub struct TaskSpec {
    /// The task's configuration (name, type, motion task, message queue).
    pub config: TaskConfig,
    /// Its task number (1-based, SYS.cfg order; idle tasks keep their numbers).
    pub number: i32,
}

/// Where a task is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Run {
    /// Not started yet, or running or ready to run.
    Ready,
    /// Waiting until this robot time.
    Waiting(RobotTime),
    /// Real time: blocked outside the scheduler without the baton (the motion task waits
    /// for room in the motion queue); it becomes ready again by itself.
    Blocked,
    /// Its program has ended.
    Done,
}

#[derive(Debug)]
struct Slot {
    spec: TaskSpec,
    run: Run,
    queue: VecDeque<RmqMessage>,
}

#[derive(Debug, Default)]
struct SyncPoint {
    arrived: BTreeSet<usize>,
    generation: u64,
}

struct State {
    slots: Vec<Slot>,
    /// The task that may run.
    baton: Option<usize>,
    /// The motion task is to advance the time to here before anything else.
    advance: Option<RobotTime>,
    now: RobotTime,
    /// Every NORMAL task has ended (or the run was stopped): the rest stop.
    finished: bool,
    /// Every NORMAL task has ended: the others may go on at this instant (no more time
    /// passes); `last_call` once every one of them waits.
    ending: bool,
    /// The tasks still waiting at the end had their last look.
    last_call: bool,
    /// Why the run was stopped from inside (`None`: it was not, or only from outside).
    halted_because: Option<String>,
    sync: HashMap<String, SyncPoint>,
    next_seq: u64,
    /// The tasks that do not run (idle) but have numbers.
    idle: Vec<TaskSpec>,
    /// Real time: the clock the tasks without a robot read and sleep on.
    real: Option<Arc<dyn Clock>>,
    /// Message queues outside the tasks (`rw/dipc` queues of a controller that stays up).
    external: Option<Arc<dyn ExternalQueues>>,
    /// The robot's axes as the motion task last handed the baton over (what the tasks
    /// sharing its mechanical unit group read in virtual time).
    robot: Option<JointsDeg>,
    /// Real time: the motion thread's latest cycle, read instead of `robot`.
    position: Option<Arc<super::position_cell::PositionCell>>,
}

/// Slot numbers of queues outside the tasks start here (task slots are task numbers).
pub const EXTERNAL_SLOT_BASE: i32 = 100;

/// Message queues outside the RAPID tasks that `RMQFindSlot` finds by name and
/// `RMQSendMessage` sends to (a controller's external clients, over `rw/dipc`).
pub trait ExternalQueues: Send + Sync {
    /// The slot of the queue called `name`, if there is one.
    fn slot(&self, name: &str) -> Option<i32>;
    /// The queue behind `slot`.
    fn name(&self, slot: i32) -> Option<String>;
    /// Put a message from task `from` (its queue's name, `RMQ_T_ROB1`) in the queue of
    /// `slot`; the error says why not.
    fn send(&self, slot: i32, from: &str, msg: &RmqMessage) -> Result<(), String>;
}

/// The scheduler of one system's tasks (see the module docs).
pub struct Scheduler {
    state: Mutex<State>,
    turn: Condvar,
    halt: Arc<AtomicBool>,
    /// A stop request from outside (Ctrl-C), turned into `halt` at the next wait or slice.
    outside: Option<Arc<AtomicBool>>,
}

impl std::fmt::Debug for Scheduler {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let st = self.lock();
        f.debug_struct("Scheduler")
            .field("tasks", &st.slots.len())
            .field("baton", &st.baton)
            .field("now", &st.now)
            .finish_non_exhaustive()
    }
}

impl Scheduler {
    /// A scheduler for `tasks` (in SYS.cfg order; the first gets the baton first); `idle`:
    /// tasks of the system that have no program (they keep their names and numbers).
    /// `halt` is the stop flag every task's interpreter and host watch: the scheduler sets
    /// it when the run ends or fails; `outside` (Ctrl-C) stops the run too, seen at the next
    /// wait or time slice of the running task.
    pub fn new(
        tasks: Vec<TaskSpec>,
        idle: Vec<TaskSpec>,
        halt: Arc<AtomicBool>,
        outside: Option<Arc<AtomicBool>>,
    ) -> Arc<Self> {
        let slots: Vec<Slot> = tasks
            .into_iter()
            .map(|spec| Slot {
                spec,
                run: Run::Ready,
                queue: VecDeque::new(),
            })
            .collect();
        let baton = (!slots.is_empty()).then_some(0);
        Arc::new(Scheduler {
            state: Mutex::new(State {
                slots,
                baton,
                advance: None,
                now: RobotTime::ZERO,
                finished: false,
                ending: false,
                last_call: false,
                halted_because: None,
                sync: HashMap::new(),
                next_seq: 0,
                idle,
                real: None,
                external: None,
                robot: None,
                position: None,
            }),
            turn: Condvar::new(),
            halt,
            outside,
        })
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        match self.state.lock() {
            Ok(g) => g,
            // A task thread that panicked holds no invariant the others need.
            Err(poisoned) => poisoned.into_inner(),
        }
    }

    /// Every task of the system in task-number order: its spec, and whether it runs (has a
    /// program) and has ended (for a controller's task list).
    pub fn task_list(&self) -> Vec<(TaskSpec, bool, bool)> {
        let st = self.lock();
        let mut v: Vec<(TaskSpec, bool, bool)> = st
            .slots
            .iter()
            .map(|s| (s.spec.clone(), true, s.run == Run::Done))
            .chain(st.idle.iter().map(|s| (s.clone(), false, false)))
            .collect();
        v.sort_by_key(|t| t.0.number);
        v
    }

    /// Number of tasks that run.
    pub fn len(&self) -> usize {
        self.lock().slots.len()
    }

    /// True when no task runs.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The stop flag.
    pub fn halt_flag(&self) -> &Arc<AtomicBool> {
        &self.halt
    }

    /// Stop every task (an unhandled error in one of them); `why` is kept for the report.
    pub fn halt_all(&self, why: impl Into<String>) {
        let mut st = self.lock();
        if st.halted_because.is_none() {
            st.halted_because = Some(why.into());
        }
        st.finished = true;
        self.halt.store(true, Ordering::SeqCst);
        if st.baton.is_none() {
            Self::handover(&mut st, 0);
        }
        self.turn.notify_all();
    }

    /// Stop every task when the outside asked for it (Ctrl-C); true when stopping.
    fn check_outside(&self) -> bool {
        if self.halt.load(Ordering::Relaxed) {
            return true;
        }
        if self
            .outside
            .as_ref()
            .is_some_and(|f| f.load(Ordering::Relaxed))
        {
            let mut st = self.lock();
            st.finished = true;
            self.halt.store(true, Ordering::SeqCst);
            return true;
        }
        false
    }

    /// Why the run was stopped from inside, if it was.
    pub fn halted_because(&self) -> Option<String> {
        self.lock().halted_because.clone()
    }

    /// Run in real time on `clock` (the motion task's controller runs in real time too):
    /// when every task waits and the motion task does not, the task with the earliest
    /// deadline sleeps until it instead of the time jumping.
    pub fn use_real_time(&self, clock: Arc<dyn Clock>) {
        self.lock().real = Some(clock);
    }

    /// The motion task's robot and where it starts: the tasks that share its mechanical unit
    /// group read its position (in real time from the motion thread's `cell`).
    pub fn use_robot(
        &self,
        start: JointsDeg,
        cell: Option<Arc<super::position_cell::PositionCell>>,
    ) {
        let mut st = self.lock();
        st.robot = Some(start);
        st.position = cell;
    }

    /// The motion task has ended: its robot rests at `joints` from now on.
    pub fn robot_rests_at(&self, joints: JointsDeg) {
        let mut st = self.lock();
        st.robot = Some(joints);
        st.position = None;
    }

    /// Where the robot is, for a task that shares the motion task's mechanical unit group:
    /// the motion thread's latest cycle in real time, else the motion task's last hand-over
    /// (virtual time passes only while the motion task has the baton). `None` before the
    /// motion task first handed over.
    fn robot_joints(&self) -> Option<JointsDeg> {
        let st = self.lock();
        match &st.position {
            Some(cell) => Some(cell.load().joints),
            None => st.robot,
        }
    }

    /// Queues outside the tasks that the tasks may send to (see [`ExternalQueues`]).
    pub fn use_external_queues(&self, queues: Arc<dyn ExternalQueues>) {
        self.lock().external = Some(queues);
    }

    /// A message from outside (`rw/dipc`) to the queue `target` of a task (`RMQ_T_ROB1`,
    /// or the task's name): `data` is `type;value` as on a controller (`num;42`,
    /// `string;"go"`), `from` the sender's queue. `None` when `target` names no task.
    pub fn deliver(
        &self,
        target: &str,
        from: &str,
        data: &str,
        userdef: i64,
    ) -> Option<Result<(), String>> {
        let mut st = self.lock();
        let i = Self::index_of(&st, target)?;
        let slot = st.slots.get(i)?.spec.number;
        let Some((datatype, value)) = data.split_once(';') else {
            return Some(Err(format!(
                "the data of a message to a RAPID task's queue is `type;value` (`num;42`,                  `string;\"text\"`), not `{data}`"
            )));
        };
        let datatype = datatype.trim();
        let value = value.trim();
        let Some(lit) = crate::functions::format::parse_value(value) else {
            return Some(Err(format!(
                "`{value}` is not the RAPID text of one {datatype} value"
            )));
        };
        let sender = st.external.as_ref().and_then(|e| e.slot(from)).unwrap_or(0);
        let msg = RmqMessage {
            datatype: datatype.to_string(),
            dims: atomic_dims(datatype, &lit),
            data: value.to_string(),
            sender,
            userdef: i32::try_from(userdef).unwrap_or(-1),
            seq: 0,
        };
        let r = Self::enqueue(&mut st, slot, msg).map_err(|e| e.message);
        drop(st);
        self.turn.notify_all();
        Some(r)
    }

    /// Put `msg` in the queue of the task with number `slot` (see [`TaskHost::rmq_send`]).
    fn enqueue(st: &mut State, slot: i32, mut msg: RmqMessage) -> Result<(), HostError> {
        st.next_seq += 1;
        let seq = st.next_seq;
        let Some(s) = st.slots.iter_mut().find(|s| s.spec.number == slot) else {
            return Err(HostError::rapid(
                errnum::ERR_RMQ_INVALID,
                format!("slot {slot} is not a running task of this system"),
            ));
        };
        let cfg = &s.spec.config;
        if cfg.rmq_type == RmqType::None {
            return Err(HostError::rapid(
                errnum::ERR_RMQ_INVALID,
                format!(
                    "task {} has no RAPID message queue (-RmqType None)",
                    cfg.name
                ),
            ));
        }
        if msg.data.len() > cfg.rmq_max_msg_size {
            return Err(HostError::rapid(
                errnum::ERR_RMQ_MSGSIZE,
                format!(
                    "the message has {} bytes; task {} takes at most {} (-RmqMaxMsgSize)",
                    msg.data.len(),
                    cfg.name,
                    cfg.rmq_max_msg_size
                ),
            ));
        }
        if s.queue.len() >= cfg.rmq_max_no_of_msg {
            return Err(HostError::rapid(
                errnum::ERR_RMQ_FULL,
                format!(
                    "the message queue of task {} is full ({} messages, -RmqMaxNoOfMsg)",
                    cfg.name, cfg.rmq_max_no_of_msg
                ),
            ));
        }
        msg.seq = seq;
        s.queue.push_back(msg);
        Ok(())
    }

    /// The real-time clock's time (`None` in virtual time).
    fn clock_now(&self) -> Option<RobotTime> {
        let clock = self.lock().real.clone()?;
        Some(clock.now())
    }

    /// The robot time the tasks share.
    pub fn now(&self) -> RobotTime {
        self.lock().now
    }

    /// Block until task `me` holds the baton; returns the guard.
    fn wait_turn<'a>(&'a self, mut st: MutexGuard<'a, State>, me: usize) -> MutexGuard<'a, State> {
        while st.baton != Some(me) {
            st = match self.turn.wait(st) {
                Ok(g) => g,
                Err(p) => p.into_inner(),
            };
        }
        st
    }

    /// Before task `me` starts: wait for its first turn.
    pub fn start(&self, me: usize) {
        let st = self.lock();
        drop(self.wait_turn(st, me));
    }

    /// Task `me` has ended: hand the baton on.
    pub fn done(&self, me: usize) {
        let mut st = self.lock();
        if let Some(s) = st.slots.get_mut(me) {
            s.run = Run::Done;
        }
        let normal_left = st
            .slots
            .iter()
            .any(|s| s.spec.config.kind == TaskType::Normal && s.run != Run::Done);
        if !normal_left {
            st.ending = true;
        }
        Self::handover(&mut st, me);
        if st.finished {
            self.halt.store(true, Ordering::SeqCst);
        }
        self.turn.notify_all();
    }

    /// Can task `i` run now?
    fn runnable(st: &State, i: usize) -> bool {
        match st.slots.get(i).map(|s| s.run) {
            Some(Run::Ready) => true,
            Some(Run::Waiting(d)) => st.finished || d <= st.now,
            Some(Run::Done | Run::Blocked) | None => false,
        }
    }

    /// Give the baton to the next task after `from` that can run, advancing the time when
    /// none can (see the module docs).
    fn handover(st: &mut State, from: usize) {
        let n = st.slots.len();
        st.advance = None;
        if let Some(clock) = &st.real {
            // Real time: deadlines that have passed are due whoever advanced the time.
            st.now = st.now.max(clock.now());
        }
        if n == 0 {
            st.baton = None;
            return;
        }
        let mut start = from;
        loop {
            if let Some(i) = (1..=n)
                .map(|k| (start + k) % n)
                .find(|&i| Self::runnable(st, i))
            {
                st.baton = Some(i);
                return;
            }
            // Nobody can run: every task waits (or has ended).
            if st.ending && !st.finished {
                if st.last_call {
                    // They had their last look and wait again: the run is over.
                    st.finished = true;
                } else {
                    // The NORMAL tasks have ended: no more time passes. Each waiting task
                    // looks once more at what it waits for (another task may have done it
                    // just before ending), then the run is over.
                    st.last_call = true;
                    for s in st.slots.iter_mut() {
                        if matches!(s.run, Run::Waiting(_)) {
                            s.run = Run::Ready;
                        }
                    }
                }
                continue;
            }
            let Some(target) = st
                .slots
                .iter()
                .filter_map(|s| match s.run {
                    Run::Waiting(d) => Some(d),
                    _ => None,
                })
                .min()
            else {
                st.baton = None;
                return;
            };
            let motion = st
                .slots
                .iter()
                .position(|s| s.spec.config.motion && matches!(s.run, Run::Waiting(_)));
            if let Some(m) = motion {
                st.baton = Some(m);
                st.advance = Some(target);
                return;
            }
            if st.real.is_some()
                && let Some(first) = st.slots.iter().position(|s| s.run == Run::Waiting(target))
            {
                st.baton = Some(first);
                st.advance = Some(target);
                return;
            }
            st.now = st.now.max(target);
            // After a time step the motion task comes first, then round robin: start the
            // search just before it.
            start = st
                .slots
                .iter()
                .position(|s| s.spec.config.motion)
                .map_or(n - 1, |m| (m + n - 1) % n);
        }
    }

    /// The task called `name`, or whose message queue is called `name` (`RMQ_` and the
    /// task's name, as on a controller).
    fn index_of(st: &State, name: &str) -> Option<usize> {
        let name = name.trim();
        let find = |n: &str| {
            st.slots
                .iter()
                .position(|s| s.spec.config.name.eq_ignore_ascii_case(n))
        };
        find(name).or_else(|| {
            name.get(..4)
                .filter(|p| p.eq_ignore_ascii_case("RMQ_"))
                .and_then(|_| name.get(4..))
                .and_then(find)
        })
    }
}

/// A task's view of the scheduler: the inter-task capability of its host.
#[derive(Debug, Clone)]
pub struct TaskHandle {
    sched: Arc<Scheduler>,
    me: usize,
}

impl TaskHandle {
    /// The handle of task `me` (index in the scheduler's tasks).
    pub fn new(sched: Arc<Scheduler>, me: usize) -> Self {
        TaskHandle { sched, me }
    }

    fn spec(&self) -> Option<TaskSpec> {
        self.sched.lock().slots.get(self.me).map(|s| s.spec.clone())
    }
}

impl TaskHost for TaskHandle {
    fn task_name(&self) -> String {
        self.spec().map(|s| s.config.name).unwrap_or_default()
    }

    fn task_number(&self) -> i32 {
        self.spec().map_or(0, |s| s.number)
    }

    fn mec_task_number(&self) -> i32 {
        let st = self.sched.lock();
        st.slots
            .iter()
            .find(|s| s.spec.config.motion)
            .map_or(0, |s| s.spec.number)
    }

    fn is_motion_task(&self) -> bool {
        self.spec().is_some_and(|s| s.config.motion)
    }

    fn sync_arrive(&mut self, ident: &str, tasks: &[String]) -> Result<u64, HostError> {
        let mut st = self.sched.lock();
        let mut members = BTreeSet::new();
        for t in tasks {
            match Scheduler::index_of(&st, t) {
                Some(i) => {
                    members.insert(i);
                }
                None => {
                    return Err(HostError::fatal(format!(
                        "WaitSyncTask {ident}: `{t}` is not a running task of this system"
                    )));
                }
            }
        }
        if !members.contains(&self.me) {
            return Err(HostError::fatal(format!(
                "WaitSyncTask {ident}: the task list does not hold this task"
            )));
        }
        let point = st.sync.entry(ident.to_ascii_uppercase()).or_default();
        point.arrived.insert(self.me);
        let ticket = point.generation;
        if members.is_subset(&point.arrived) {
            point.generation += 1;
            point.arrived.clear();
        }
        Ok(ticket)
    }

    fn sync_passed(&mut self, ident: &str, ticket: u64) -> bool {
        let st = self.sched.lock();
        st.sync
            .get(&ident.to_ascii_uppercase())
            .is_some_and(|p| p.generation > ticket)
    }

    fn sync_leave(&mut self, ident: &str, ticket: u64) {
        let mut st = self.sched.lock();
        if let Some(p) = st.sync.get_mut(&ident.to_ascii_uppercase())
            && p.generation == ticket
        {
            p.arrived.remove(&self.me);
        }
    }

    fn rmq_find_slot(&self, name: &str) -> Option<i32> {
        let st = self.sched.lock();
        let Some(i) = Scheduler::index_of(&st, name) else {
            return st.external.as_ref().and_then(|e| e.slot(name.trim()));
        };
        let s = st.slots.get(i)?;
        (s.spec.config.rmq_type != RmqType::None).then_some(s.spec.number)
    }

    fn rmq_slot_name(&self, slot: i32) -> Option<String> {
        let st = self.sched.lock();
        st.slots
            .iter()
            .find(|s| s.spec.number == slot)
            .map(|s| s.spec.config.name.clone())
            .or_else(|| st.external.as_ref().and_then(|e| e.name(slot)))
    }

    fn rmq_send(&mut self, slot: i32, msg: RmqMessage) -> Result<(), HostError> {
        let mut st = self.sched.lock();
        let outside = !st.slots.iter().any(|s| s.spec.number == slot);
        if outside && let Some(ext) = st.external.clone() {
            let from = format!(
                "RMQ_{}",
                st.slots
                    .get(self.me)
                    .map(|s| s.spec.config.name.as_str())
                    .unwrap_or_default()
            );
            drop(st);
            if ext.name(slot).is_some() {
                return ext
                    .send(slot, &from, &msg)
                    .map_err(|m| HostError::rapid(errnum::ERR_RMQ_FULL, m));
            }
            st = self.sched.lock();
        }
        Scheduler::enqueue(&mut st, slot, msg)
    }

    fn rmq_take(&mut self) -> Option<RmqMessage> {
        let mut st = self.sched.lock();
        st.slots.get_mut(self.me)?.queue.pop_front()
    }

    fn rmq_peek(&self) -> Option<RmqMessage> {
        let st = self.sched.lock();
        st.slots.get(self.me)?.queue.front().cloned()
    }

    fn rmq_empty(&mut self) {
        let mut st = self.sched.lock();
        if let Some(s) = st.slots.get_mut(self.me) {
            s.queue.clear();
        }
    }
}

/// The host of one task: the task's own host (the controller's for the motion task, a
/// plain one for the others) with the scheduler around its waits (see the module docs).
pub struct TaskedHost {
    inner: Box<dyn Host + Send>,
    task: TaskHandle,
    motion: bool,
    name: String,
    /// The task's mechanical unit group (`-UseMechanicalUnitGroup`; empty: none).
    mech_group: String,
    /// Prefix output with the task's name (when there are several tasks).
    label: bool,
    max_time: Option<f64>,
}

impl std::fmt::Debug for TaskedHost {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TaskedHost")
            .field("task", &self.name)
            .field("motion", &self.motion)
            .finish_non_exhaustive()
    }
}

impl TaskedHost {
    /// Task `me` of `sched` on `inner`; `label`: prefix TP lines and events with
    /// `[TASK] ` (several tasks); `max_time`: fail waits beyond this robot time (the motion
    /// task's own host checks its waits itself).
    pub fn new(
        sched: Arc<Scheduler>,
        me: usize,
        inner: Box<dyn Host + Send>,
        label: bool,
        max_time: Option<f64>,
    ) -> TaskedHost {
        let task = TaskHandle::new(sched, me);
        let spec = task.spec();
        TaskedHost {
            inner,
            motion: spec.as_ref().is_some_and(|s| s.config.motion),
            mech_group: spec
                .as_ref()
                .map(|s| s.config.mech_group.clone())
                .unwrap_or_default(),
            name: spec.map(|s| s.config.name).unwrap_or_default(),
            task,
            label,
            max_time,
        }
    }

    /// The task's own host.
    pub fn inner_mut(&mut self) -> &mut (dyn Host + Send) {
        self.inner.as_mut()
    }

    /// Real time: sleep until `until` on the scheduler's clock, in short slices so that a
    /// stop request ends the sleep.
    fn sleep_until(&self, until: RobotTime) -> Result<RobotTime, HostError> {
        let sched = &self.task.sched;
        while let Some(now) = sched.clock_now() {
            if now >= until || sched.check_outside() || self.others_ready() {
                return Ok(now);
            }
            let left = until.saturating_since(now);
            std::thread::sleep(left.min(std::time::Duration::from_millis(10)));
        }
        Ok(until)
    }

    /// True when another task is ready to run (one that was blocked outside the scheduler).
    fn others_ready(&self) -> bool {
        let st = self.task.sched.lock();
        st.slots
            .iter()
            .enumerate()
            .any(|(i, s)| i != self.task.me && s.run == Run::Ready)
    }

    /// Real time: run `f` without the baton (the other tasks run meanwhile), then take the
    /// baton back. For what blocks on something outside the tasks (room in the motion
    /// queue), so that it blocks only this task. In virtual time `f` runs with the baton.
    fn unscheduled<T>(&mut self, f: impl FnOnce(&mut Self) -> T) -> T {
        let sched = Arc::clone(&self.task.sched);
        let me = self.task.me;
        if sched.clock_now().is_none() {
            return f(self);
        }
        {
            let mut st = sched.lock();
            if let Some(s) = st.slots.get_mut(me) {
                s.run = Run::Blocked;
            }
            Scheduler::handover(&mut st, me);
            sched.turn.notify_all();
        }
        let r = f(self);
        let mut st = sched.lock();
        if let Some(s) = st.slots.get_mut(me) {
            s.run = Run::Ready;
        }
        if st.baton.is_none() {
            st.baton = Some(me);
        }
        drop(sched.wait_turn(st, me));
        r
    }

    fn not_motion(&self, what: &str) -> HostError {
        HostError::fatal(format!(
            "{what}: task {} is not a motion task: only the motion task (-MotionTask in SYS.cfg) moves the robot",
            self.name
        ))
    }

    /// Hand the baton over with this task in state `run`, and take it back; returns the
    /// time to advance to when the motion task is to advance it.
    fn switch(&mut self, run: Run) -> Option<RobotTime> {
        let sched = Arc::clone(&self.task.sched);
        let me = self.task.me;
        // What the other tasks of the robot's group read until the next hand-over.
        let robot = if self.motion {
            self.inner.motion_joints().ok()
        } else {
            None
        };
        let mut st = sched.lock();
        if self.motion {
            let t = self.inner.now();
            st.now = st.now.max(t);
            if robot.is_some() {
                st.robot = robot;
            }
        }
        if let Some(s) = st.slots.get_mut(me) {
            s.run = run;
        }
        Scheduler::handover(&mut st, me);
        if st.finished {
            sched.halt.store(true, Ordering::SeqCst);
        }
        sched.turn.notify_all();
        let mut st = sched.wait_turn(st, me);
        let advance = st.advance.take();
        if advance.is_none()
            && let Some(s) = st.slots.get_mut(me)
        {
            s.run = Run::Ready;
        }
        advance
    }
}

impl Host for TaskedHost {
    fn now(&self) -> RobotTime {
        if self.motion {
            self.inner.now()
        } else {
            let sched = &self.task.sched;
            sched.clock_now().unwrap_or_else(|| sched.now())
        }
    }

    fn wait_until(&mut self, deadline: RobotTime) -> Result<RobotTime, HostError> {
        if self.task.sched.check_outside() {
            return Ok(self.now());
        }
        if !self.motion
            && let Some(max) = self.max_time
            && deadline > RobotTime::from_secs_f64(max)
        {
            return Err(HostError::fatal(format!(
                "task {}: the program waits beyond the virtual time limit of {max} s \
                 (use --max-time to raise it)",
                self.name
            )));
        }
        loop {
            match self.switch(Run::Waiting(deadline)) {
                None => return Ok(self.now()),
                Some(target) => {
                    // The motion task moves the robot up to the next deadline of any task;
                    // in real time without a waiting motion task, the task with the
                    // earliest deadline sleeps until it.
                    let until = target.min(deadline);
                    let t = if self.motion {
                        self.inner.wait_until(until)
                    } else {
                        self.sleep_until(until)
                    };
                    let sched = Arc::clone(&self.task.sched);
                    let now = if self.motion {
                        self.inner.now()
                    } else {
                        sched.clock_now().unwrap_or(until)
                    };
                    let mut st = sched.lock();
                    st.now = st.now.max(now);
                    let ended_early = now < until;
                    if t.is_err() || now >= deadline || ended_early {
                        if let Some(s) = st.slots.get_mut(self.task.me) {
                            s.run = Run::Ready;
                        }
                        drop(st);
                        return t;
                    }
                    drop(st);
                    // Another task's deadline came first: let it run.
                }
            }
        }
    }

    fn check_time_limit(&mut self) -> Result<(), HostError> {
        if self.motion {
            return self.inner.check_time_limit();
        }
        match self.max_time {
            Some(max) if self.now() >= RobotTime::from_secs_f64(max) => {
                Err(HostError::fatal(format!(
                    "task {}: the program waits beyond the time limit of {max} s \
                     (use --max-time to raise it)",
                    self.name
                )))
            }
            _ => Ok(()),
        }
    }

    fn yield_now(&mut self) -> Result<(), HostError> {
        if self.task.sched.check_outside() {
            return Ok(());
        }
        // A yield never advances time: this task stays ready.
        if self.switch(Run::Ready).is_some() {
            return Err(HostError::fatal(
                "internal error: a ready task was asked to advance the time",
            ));
        }
        Ok(())
    }

    fn output(&mut self, out: Output) {
        if !self.label {
            self.inner.output(out);
            return;
        }
        let tag = |s: &str| format!("[{}] {s}", self.name);
        let out = match out {
            Output::TpWrite(s) => Output::TpWrite(tag(&s)),
            Output::Event(s) => Output::Event(tag(&s)),
            Output::ErrWrite {
                warning,
                header,
                reason,
            } => Output::ErrWrite {
                warning,
                header: tag(&header),
                reason,
            },
            Output::TpErase => Output::TpErase,
        };
        self.inner.output(out);
    }

    fn read_signal(&mut self, name: &str) -> Result<f64, HostError> {
        self.inner.read_signal(name)
    }

    fn write_signal(&mut self, name: &str, value: f64) -> Result<(), HostError> {
        self.inner.write_signal(name, value)
    }

    fn signal_kind(&self, name: &str) -> Option<crate::signals::SignalKind> {
        self.inner.signal_kind(name)
    }

    fn motion_submit(&mut self, cmd: MotionCommand) -> Result<u64, HostError> {
        if !self.motion {
            return Err(self.not_motion("a move instruction"));
        }
        // In real time the move may wait for room in the motion queue: only this task waits.
        self.unscheduled(|h| h.inner.motion_submit(cmd))
    }

    fn motion_reached(&mut self, wait: MotionWait) -> Result<bool, HostError> {
        if self.motion {
            return self.inner.motion_reached(wait);
        }
        match wait {
            MotionWait::Done(_) => Err(self.not_motion("waiting for a move")),
            MotionWait::InPos | MotionWait::ZeroSpeed => Ok(true),
        }
    }

    fn motion_joints(&mut self) -> Result<JointsDeg, HostError> {
        if self.motion {
            return self.inner.motion_joints();
        }
        // A task connected to the robot's mechanical unit group (-UseMechanicalUnitGroup)
        // reads where the motion task's robot is, as a state server task does.
        if self.mech_group.is_empty() {
            return Err(HostError::fatal(format!(
                "reading the robot's position: task {} is not a motion task and has no mechanical unit group (-UseMechanicalUnitGroup in SYS.cfg)",
                self.name
            )));
        }
        self.task.sched.robot_joints().ok_or_else(|| {
            HostError::fatal(format!(
                "reading the robot's position: no motion task moves the robot of task {}'s mechanical unit group {}",
                self.name, self.mech_group
            ))
        })
    }

    fn motion_modes(&self) -> MotionModes {
        self.inner.motion_modes()
    }

    fn motion_set(&mut self, setting: MotionSetting) -> Result<(), HostError> {
        if !self.motion {
            return Err(self.not_motion("a motion setting"));
        }
        self.inner.motion_set(setting)
    }

    fn motion_path(&mut self, cmd: PathCommand) -> Result<(), HostError> {
        if !self.motion {
            return Err(self.not_motion("a path instruction (StopMove, StartMove, StorePath, …)"));
        }
        self.inner.motion_path(cmd)
    }

    fn motion_corr(&mut self, req: CorrRequest) -> Result<CorrAnswer, HostError> {
        if !self.motion {
            return Err(self.not_motion("a path correction instruction"));
        }
        self.inner.motion_corr(req)
    }

    fn robot_target_of(
        &self,
        joints: &JointsDeg,
        tool: &ToolData,
        wobj: &WobjData,
        pdisp: &Pose,
    ) -> Result<RobTarget, HostError> {
        self.inner.robot_target_of(joints, tool, wobj, pdisp)
    }

    fn robot_joints_of(
        &self,
        target: &RobTarget,
        tool: &ToolData,
        wobj: &WobjData,
        pdisp: &Pose,
    ) -> Result<JointsDeg, HostError> {
        self.inner.robot_joints_of(target, tool, wobj, pdisp)
    }

    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        self.inner.as_any_mut()
    }

    fn egm(&mut self) -> Option<&mut dyn EgmHost> {
        if self.motion { self.inner.egm() } else { None }
    }

    fn egm_path(&mut self) -> Option<&mut dyn EgmPathHost> {
        if self.motion {
            self.inner.egm_path()
        } else {
            None
        }
    }

    fn system(&mut self) -> Option<&mut crate::system::Services> {
        self.inner.system()
    }

    fn system_blocking(&mut self, f: &mut dyn FnMut(&mut crate::system::Services)) -> bool {
        // Blocked outside the scheduler (real time): the other tasks run meanwhile.
        let done = self.unscheduled(|h| h.inner.system_blocking(f));
        // A Ctrl-C is seen here too (a socket wait never waits on the scheduler's clock).
        self.task.sched.check_outside();
        done
    }

    fn position_events(&mut self) -> Option<&mut dyn crate::interp::host::PositionEventHost> {
        if self.motion {
            self.inner.position_events()
        } else {
            None
        }
    }

    fn tasks(&mut self) -> Option<&mut dyn TaskHost> {
        Some(&mut self.task)
    }
}

/// Run one body per task of `sched`, each on its own thread (8 MiB of stack), in turn as
/// the scheduler says: a body runs once its task first gets the baton, and its task ends
/// when the body returns. Returns the bodies' results in task order (`None` for a body that
/// panicked; the run is then stopped).
pub fn run_tasks<R: Send>(
    sched: &Arc<Scheduler>,
    bodies: Vec<Box<dyn FnOnce() -> R + Send + '_>>,
) -> Vec<Option<R>> {
    std::thread::scope(|scope| {
        let handles: Vec<_> = bodies
            .into_iter()
            .enumerate()
            .map(|(me, body)| {
                let sched = Arc::clone(sched);
                std::thread::Builder::new()
                    .name(format!("rapid-task-{me}"))
                    .stack_size(8 << 20)
                    .spawn_scoped(scope, move || {
                        sched.start(me);
                        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(body));
                        if r.is_err() {
                            sched.halt_all("a task's thread failed");
                        }
                        sched.done(me);
                        r.ok()
                    })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| match h {
                Ok(h) => h.join().ok().flatten(),
                Err(_) => {
                    sched.halt_all("a task's thread could not be started");
                    None
                }
            })
            .collect()
    })
}

/// The sizes of an array of an atomic type written as RAPID text (`num;[1,2,3]`); a record
/// or a single value has none (a record's brackets are its fields).
fn atomic_dims(datatype: &str, lit: &crate::functions::format::LitValue) -> Vec<u32> {
    use crate::functions::format::LitValue;
    let atomic = ["num", "dnum", "bool", "string", "byte"]
        .iter()
        .any(|t| t.eq_ignore_ascii_case(datatype));
    let mut dims = Vec::new();
    let mut at = lit;
    while atomic && dims.len() < 3 {
        let LitValue::List(items) = at else { break };
        dims.push(u32::try_from(items.len()).unwrap_or(u32::MAX));
        match items.first() {
            Some(first) => at = first,
            None => break,
        }
    }
    dims
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]
mod tests {
    use super::*;
    use crate::interp::VirtualHost;

    fn spec(name: &str, number: i32) -> TaskSpec {
        TaskSpec {
            config: TaskConfig::new(name, TaskType::Normal, false),
            number,
        }
    }

    /// Two tasks without a robot wait; each wakes at its deadline, in deadline order, and
    /// the shared time is the later deadline at the end. Returns the wake-up order.
    fn two_waits(sched: &Arc<Scheduler>) -> Vec<(usize, RobotTime)> {
        let log = Arc::new(Mutex::new(Vec::new()));
        let bodies: Vec<Box<dyn FnOnce() + Send>> = [0.05, 0.02]
            .into_iter()
            .enumerate()
            .map(|(me, secs)| {
                let mut host = TaskedHost::new(
                    Arc::clone(sched),
                    me,
                    Box::new(VirtualHost::new()),
                    true,
                    None,
                );
                let log = Arc::clone(&log);
                Box::new(move || {
                    let t = host.wait_until(RobotTime::from_secs_f64(secs)).unwrap();
                    log.lock().unwrap().push((me, t));
                }) as Box<dyn FnOnce() + Send>
            })
            .collect();
        let ends = run_tasks(sched, bodies);
        assert!(ends.iter().all(Option::is_some));
        log.lock().unwrap().clone()
    }

    #[test]
    fn virtual_time_jumps_to_each_deadline_in_order() {
        let halt = Arc::new(AtomicBool::new(false));
        let sched = Scheduler::new(
            vec![spec("A", 1), spec("B", 3)],
            vec![spec("IDLE", 2)],
            halt,
            None,
        );
        let order = two_waits(&sched);
        let list: Vec<(i32, bool, bool)> = sched
            .task_list()
            .iter()
            .map(|t| (t.0.number, t.1, t.2))
            .collect();
        assert_eq!(list, [(1, true, true), (2, false, false), (3, true, true)]);
        assert_eq!(
            order,
            [
                (1, RobotTime::from_secs_f64(0.02)),
                (0, RobotTime::from_secs_f64(0.05))
            ]
        );
    }

    #[test]
    fn real_time_sleeps_until_each_deadline() {
        let halt = Arc::new(AtomicBool::new(false));
        let sched = Scheduler::new(vec![spec("A", 1), spec("B", 2)], Vec::new(), halt, None);
        let clock = Arc::new(crate::controller::MonotonicClock::new());
        sched.use_real_time(clock.clone());
        let order = two_waits(&sched);
        assert_eq!(order.iter().map(|o| o.0).collect::<Vec<_>>(), [1, 0]);
        assert!(order[0].1 >= RobotTime::from_secs_f64(0.02));
        assert!(clock.now() >= RobotTime::from_secs_f64(0.05));
    }
}
