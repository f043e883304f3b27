//! What services (Robot Web Services, the live view, later others) may ask of a running
//! controller and what they hear from it: typed requests with replies over one bounded
//! channel, and a broadcast of events.
//!
//! Services never hold controller internals and never take a lock the motion cycle needs. The
//! controller takes requests between program steps (never inside the motion cycle) and
//! publishes events as they happen; a slow or hostile service can only fill its own queue or
//! lag behind the broadcast (it then misses events and is told so), never delay the cycle.
//!
//! The contract in one picture:
//!
//! ```text
//!   service (tokio)                         controller (its own threads)
//!   ServiceHandle::request(Request) ──mpsc──▶ ServiceEndpoint::try_next() → answer via Reply
//!   ServiceHandle::subscribe()      ◀─broadcast── ServiceEndpoint::publish(Event)
//! ```
//!
//! Values cross this boundary in RAPID's units and text forms (mm, degrees, RAPID literal text
//! for data such as `[1,2,3]`), so services need no knowledge of the interpreter's values.

use tokio::sync::{broadcast, mpsc, oneshot};

/// How many requests may wait for the controller (from all services together).
pub const REQUEST_CAPACITY: usize = 256;

/// How many events a subscriber may fall behind before it misses some.
pub const EVENT_CAPACITY: usize = 4096;

/// RAPID execution state of the controller (`rw/rapid/execution`, `ctrlexecstate`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ExecState {
    /// At least one normal task runs.
    Running,
    /// No normal task runs.
    Stopped,
}

/// What `Start` does when the entry routine ends (`cycle`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CycleMode {
    /// Run the entry routine once, then stop.
    Once,
    /// Run it again and again.
    Forever,
    /// Keep the mode set before.
    AsIs,
}

/// Operating mode (`rw/panel/opmode`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OpMode {
    /// Automatic.
    Auto,
    /// Manual, reduced speed (250 mm/s).
    ManualReduced,
    /// Manual, full speed.
    ManualFull,
}

/// Controller state (`rw/panel/ctrlstate`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CtrlState {
    /// Starting up.
    Init,
    /// Motors off.
    MotorsOff,
    /// Motors on: programs can move the robot.
    MotorsOn,
    /// Guard stop.
    GuardStop,
    /// Emergency stop.
    EmergencyStop,
    /// Emergency stop reset, motors still off.
    EmergencyStopReset,
    /// System failure.
    SysFail,
}

/// How a task runs (SYS.cfg `CAB_TASKS -Type`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TaskType {
    /// Started and stopped with the program.
    Normal,
    /// Starts at boot, keeps running, restarts from its program pointer.
    Static,
    /// Starts at boot from the beginning, keeps running.
    SemiStatic,
}

/// Execution state of one task (`rw/rapid/tasks`, `excstate`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TaskExecState {
    /// Loaded, program pointer set, not running.
    Ready,
    /// Running.
    Started,
    /// Stopped with its program pointer kept.
    Stopped,
    /// No program pointer (nothing to run, or after an unrecoverable error).
    Uninitialized,
}

/// One task as services see it.
#[derive(Clone, Debug, PartialEq)]
pub struct TaskInfo {
    /// Task name (`T_ROB1`).
    pub name: String,
    /// Normal, static or semistatic.
    pub task_type: TaskType,
    /// Execution state.
    pub exec_state: TaskExecState,
    /// Takes part when normal tasks are started.
    pub active: bool,
    /// The task that moves the robot.
    pub motion_task: bool,
}

/// One loaded module.
#[derive(Clone, Debug, PartialEq)]
pub struct ModuleInfo {
    /// Module name.
    pub name: String,
    /// A system module (`SYSMODULE`).
    pub system: bool,
}

/// One I/O signal.
#[derive(Clone, Debug, PartialEq)]
pub struct SignalInfo {
    /// Signal name.
    pub name: String,
    /// `DI`, `DO`, `AI`, `AO`, `GI` or `GO`.
    pub kind: crate::signals::SignalKind,
    /// Logical value.
    pub value: f64,
    /// Industrial network (`Local` for signals without a device).
    pub network: String,
    /// Device (`DRV_1` for signals without a device).
    pub device: String,
}

/// Storage class of a RAPID data symbol.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SymbolClass {
    /// `PERS`.
    Pers,
    /// `VAR`.
    Var,
    /// `CONST`.
    Const,
}

/// Where a RAPID data symbol is: task, optionally module, name (case-insensitive).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct SymbolPath {
    /// Task name.
    pub task: String,
    /// Module name; `None`: any module of the task (task-global data).
    pub module: Option<String>,
    /// Data name.
    pub name: String,
}

/// A RAPID data symbol and its value as RAPID text (`[1,2,3]`, `"text"`, `TRUE`).
#[derive(Clone, Debug, PartialEq)]
pub struct SymbolInfo {
    /// Where it is (the module filled in).
    pub path: SymbolPath,
    /// `PERS`, `VAR` or `CONST`.
    pub class: SymbolClass,
    /// Data type name as RAPID writes it (`num`, `robtarget`, …).
    pub data_type: String,
    /// Array sizes (empty for a scalar).
    pub dims: Vec<u32>,
    /// Value as RAPID literal text.
    pub value: String,
}

/// Severity of an event-log entry (`msgtype`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ElogSeverity {
    /// 1.
    Info,
    /// 2.
    Warning,
    /// 3.
    Error,
}

/// One event-log entry: every event rapidvc prints is one.
#[derive(Clone, Debug, PartialEq)]
pub struct ElogEntry {
    /// Sequence number in its log, from 1.
    pub seq: u64,
    /// Info, warning or error.
    pub severity: ElogSeverity,
    /// Event number (`41822`, `50050`, …).
    pub code: u32,
    /// Title.
    pub title: String,
    /// Description.
    pub description: String,
    /// Controller calendar time of the entry: seconds since 1970-01-01 UTC.
    pub timestamp: f64,
}

/// What the controller says about itself (`rw/system`, `ctrl`).
#[derive(Clone, Debug, PartialEq)]
pub struct SystemInfo {
    /// System name.
    pub name: String,
    /// RobotWare version `M.mm.pp` (e.g. `6.08.00`).
    pub robotware_version: String,
    /// Options as ABB names them (`689-1 Externally Guided Motion (EGM)`).
    pub options: Vec<String>,
    /// Controller serial number.
    pub serial: String,
}

/// A mechanical unit (`rw/motionsystem/mechunits`).
#[derive(Clone, Debug, PartialEq)]
pub struct MechUnitInfo {
    /// Unit name (`ROB_1`).
    pub name: String,
    /// The task that moves it.
    pub task: String,
    /// Number of axes.
    pub axes: u32,
    /// Active tool and work object names of the motion task.
    pub tool: String,
    /// Active work object name.
    pub wobj: String,
    /// Active payload name (`GripLoad`; `load0` when none is held).
    pub payload: String,
}

/// Where the robot is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RobotState {
    /// Controller time (s since start).
    pub time: f64,
    /// Axis values (deg).
    pub joints: [f64; 6],
}

/// The coordinate system of a robtarget request.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Coordinate {
    /// Base frame.
    Base,
    /// World frame.
    World,
    /// Tool frame.
    Tool,
    /// Work object frame.
    Wobj,
}

/// One instance of a CFG type (`rw/cfg/{domain}/{type}/instances`): its name and its
/// attributes as text.
#[derive(Clone, Debug, PartialEq)]
pub struct CfgInstance {
    /// `-Name`.
    pub name: String,
    /// Attribute name and value, in file order.
    pub attributes: Vec<(String, String)>,
}

/// One message of an external queue (RWS `rw/dipc`): what RAPID's RMQ and a service exchange.
/// The data is RMQ text as the sender wrote it (for a RAPID task: the data type and the value,
/// as RAPID's `RMQSendMessage` would carry it).
#[derive(Clone, Debug, PartialEq)]
pub struct DipcMessage {
    /// The sender's queue (a task name, or an external queue), where answers go.
    pub source: String,
    /// Command number (`dipc-cmd`).
    pub cmd: i64,
    /// User-defined number (`dipc-userdef`).
    pub userdef: i64,
    /// Message type (`dipc-msgtype`: 0 or 1).
    pub msgtype: i64,
    /// The data as text.
    pub data: String,
}

/// Why a request failed. Services map these to their protocol's errors (HTTP 404, 400, …).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ServiceError {
    /// No such task, module, symbol, signal, file, unit, …
    #[error("not found: {0}")]
    NotFound(String),
    /// The value does not fit (wrong type, out of range, malformed RAPID text).
    #[error("bad value: {0}")]
    BadValue(String),
    /// Not allowed in the controller's state (motors off, not AUTO, program running, …).
    #[error("not allowed: {0}")]
    NotAllowed(String),
    /// The controller does not take requests any more (shutting down).
    #[error("the controller has stopped")]
    Gone,
}

/// The answer channel of one request.
pub type Reply<T> = oneshot::Sender<Result<T, ServiceError>>;

/// A request from a service. Each carries the channel its answer goes to.
#[derive(Debug)]
pub enum Request {
    /// Execution state and cycle mode.
    Execution(Reply<(ExecState, CycleMode)>),
    /// Start the normal tasks (from their program pointers).
    Start {
        /// Cycle mode.
        cycle: CycleMode,
        /// Reply when started.
        reply: Reply<()>,
    },
    /// Stop the normal tasks (the robot stops on its path; program pointers kept).
    Stop(Reply<()>),
    /// Program pointers of the normal tasks to their entry routine.
    ResetPp(Reply<()>),
    /// Controller state.
    CtrlState(Reply<CtrlState>),
    /// Motors on (`true`) or off.
    SetMotors {
        /// On or off.
        on: bool,
        /// Reply when done.
        reply: Reply<()>,
    },
    /// Operating mode.
    OpMode(Reply<OpMode>),
    /// Change the operating mode.
    SetOpMode {
        /// New mode.
        mode: OpMode,
        /// Reply when done.
        reply: Reply<()>,
    },
    /// Speed ratio in percent (0–100).
    SpeedRatio(Reply<u8>),
    /// Change the speed ratio.
    SetSpeedRatio {
        /// Percent, 0–100.
        percent: u8,
        /// Reply when done.
        reply: Reply<()>,
    },
    /// Every task.
    Tasks(Reply<Vec<TaskInfo>>),
    /// Activate or deactivate a task.
    SetTaskActive {
        /// Task name.
        task: String,
        /// Active or not.
        active: bool,
        /// Reply when done.
        reply: Reply<()>,
    },
    /// The modules of a task.
    Modules {
        /// Task name.
        task: String,
        /// The modules.
        reply: Reply<Vec<ModuleInfo>>,
    },
    /// Every signal.
    Signals(Reply<Vec<SignalInfo>>),
    /// One signal by name.
    Signal {
        /// Signal name.
        name: String,
        /// The signal.
        reply: Reply<SignalInfo>,
    },
    /// Set a signal (outputs; inputs are simulated).
    SetSignal {
        /// Signal name.
        name: String,
        /// Logical value.
        value: f64,
        /// Reply when set.
        reply: Reply<()>,
    },
    /// Read a data symbol.
    Symbol {
        /// Where.
        path: SymbolPath,
        /// Value and properties.
        reply: Reply<SymbolInfo>,
    },
    /// Write a data symbol (`PERS` or `VAR`) from RAPID text.
    SetSymbol {
        /// Where.
        path: SymbolPath,
        /// RAPID literal text.
        value: String,
        /// Reply when written.
        reply: Reply<()>,
    },
    /// Data symbols of a task (all modules), optionally of one class.
    Symbols {
        /// Task name.
        task: String,
        /// Only this class.
        class: Option<SymbolClass>,
        /// The symbols.
        reply: Reply<Vec<SymbolInfo>>,
    },
    /// Event-log entries of a domain (0: common), oldest first.
    Elog {
        /// Domain.
        domain: u32,
        /// Entries.
        reply: Reply<Vec<ElogEntry>>,
    },
    /// Clear an event-log domain.
    ClearElog {
        /// Domain.
        domain: u32,
        /// Reply when cleared.
        reply: Reply<()>,
    },
    /// Where the robot is.
    Robot(Reply<RobotState>),
    /// The TCP of `tool` in `coordinate` of `wobj` as a robtarget (RAPID text).
    RobTarget {
        /// Tool name (a `tooldata` of the motion task), `tool0` by default.
        tool: Option<String>,
        /// Work object name, `wobj0` by default.
        wobj: Option<String>,
        /// Coordinate system.
        coordinate: Coordinate,
        /// The robtarget as RAPID text.
        reply: Reply<String>,
    },
    /// System name, version and options.
    System(Reply<SystemInfo>),
    /// The mechanical units.
    MechUnits(Reply<Vec<MechUnitInfo>>),
    /// Instances of a configuration type (`moc`, `sys`, `eio`, `sio` and the type name).
    Cfg {
        /// Domain (`MOC`, `SYS`, `EIO`, `SIO`; case-insensitive).
        domain: String,
        /// Type (`MECHANICAL_UNIT`, `EIO_SIGNAL`, …).
        type_name: String,
        /// Instances.
        reply: Reply<Vec<CfgInstance>>,
    },
    /// Create an external message queue (RWS `rw/dipc?action=dipc-create`) that RAPID tasks can
    /// send to with `RMQSendMessage` after `RMQFindSlot`.
    DipcCreate {
        /// Queue name.
        queue: String,
        /// Buffer size in bytes the queue may hold.
        size: u32,
        /// Largest message in bytes.
        max_message: u32,
        /// `true` when created, `false` when a queue of that name existed already.
        reply: Reply<bool>,
    },
    /// Send a message to a queue: a task's RMQ (by task name) or an external queue.
    DipcSend {
        /// Target queue or task name.
        target: String,
        /// The message.
        message: DipcMessage,
        /// Reply when queued.
        reply: Reply<()>,
    },
    /// Take the oldest message of an external queue, if any (never waits).
    DipcRead {
        /// Queue name.
        queue: String,
        /// The message, or `None` when the queue is empty.
        reply: Reply<Option<DipcMessage>>,
    },
    /// Where the controller's mass storage roots are on the host (`HOME`, `TEMP`,
    /// `RAMDISK`), for file services that apply the same sandbox as RAPID's file
    /// instructions.
    FileRoots(Reply<Vec<(String, std::path::PathBuf)>>),
}

impl Request {
    /// Answer this request with `error`, whatever it asks: for an endpoint that does not serve
    /// a kind of request (yet), so the service gets a clear error instead of waiting.
    pub fn refuse(self, error: ServiceError) {
        fn no<T>(reply: Reply<T>, error: ServiceError) {
            let _ = reply.send(Err(error));
        }
        match self {
            Request::Execution(r) => no(r, error),
            Request::Start { reply, .. } => no(reply, error),
            Request::Stop(r) | Request::ResetPp(r) => no(r, error),
            Request::CtrlState(r) => no(r, error),
            Request::SetMotors { reply, .. }
            | Request::SetOpMode { reply, .. }
            | Request::SetSpeedRatio { reply, .. }
            | Request::SetTaskActive { reply, .. }
            | Request::SetSignal { reply, .. }
            | Request::SetSymbol { reply, .. }
            | Request::ClearElog { reply, .. }
            | Request::DipcSend { reply, .. } => no(reply, error),
            Request::OpMode(r) => no(r, error),
            Request::SpeedRatio(r) => no(r, error),
            Request::Tasks(r) => no(r, error),
            Request::Modules { reply, .. } => no(reply, error),
            Request::Signals(r) => no(r, error),
            Request::Signal { reply, .. } => no(reply, error),
            Request::Symbol { reply, .. } => no(reply, error),
            Request::Symbols { reply, .. } => no(reply, error),
            Request::Elog { reply, .. } => no(reply, error),
            Request::Robot(r) => no(r, error),
            Request::RobTarget { reply, .. } => no(reply, error),
            Request::System(r) => no(r, error),
            Request::MechUnits(r) => no(r, error),
            Request::Cfg { reply, .. } => no(reply, error),
            Request::DipcCreate { reply, .. } => no(reply, error),
            Request::DipcRead { reply, .. } => no(reply, error),
            Request::FileRoots(r) => no(r, error),
        }
    }
}

/// Something that happened in the controller.
#[derive(Clone, Debug, PartialEq)]
pub enum Event {
    /// RAPID execution state or cycle mode changed.
    Execution {
        /// State.
        state: ExecState,
        /// Cycle mode.
        cycle: CycleMode,
    },
    /// Controller state changed.
    CtrlState(CtrlState),
    /// Operating mode changed.
    OpMode(OpMode),
    /// Speed ratio changed.
    SpeedRatio(u8),
    /// A task changed state.
    Task(TaskInfo),
    /// A signal changed.
    Signal {
        /// Signal name.
        name: String,
        /// New logical value.
        value: f64,
    },
    /// A persistent was written (by RAPID or a service).
    Pers {
        /// Where.
        path: SymbolPath,
        /// New value as RAPID text.
        value: String,
    },
    /// A new event-log entry (domain and entry).
    Elog(u32, ElogEntry),
    /// A sample of the robot's position (decimated for services).
    Robot(RobotState),
    /// A message arrived in an external queue (it stays there until read with `DipcRead`).
    Dipc {
        /// Queue name.
        queue: String,
        /// The message.
        message: DipcMessage,
    },
}

/// The services' side: cloneable, usable from any tokio task.
#[derive(Clone, Debug)]
pub struct ServiceHandle {
    requests: mpsc::Sender<Request>,
    events: broadcast::Sender<Event>,
}

/// The controller's side of the contract.
#[derive(Debug)]
pub struct ServiceEndpoint {
    requests: mpsc::Receiver<Request>,
    events: broadcast::Sender<Event>,
}

/// A connected pair.
pub fn channel() -> (ServiceHandle, ServiceEndpoint) {
    let (rtx, rrx) = mpsc::channel(REQUEST_CAPACITY);
    let (etx, _) = broadcast::channel(EVENT_CAPACITY);
    (
        ServiceHandle {
            requests: rtx,
            events: etx.clone(),
        },
        ServiceEndpoint {
            requests: rrx,
            events: etx,
        },
    )
}

impl ServiceHandle {
    /// Send a request built around its reply channel and wait for the answer.
    ///
    /// ```ignore
    /// let state = handle.ask(Request::CtrlState).await?;
    /// ```
    pub async fn ask<T>(&self, make: impl FnOnce(Reply<T>) -> Request) -> Result<T, ServiceError> {
        let (tx, rx) = oneshot::channel();
        self.requests
            .send(make(tx))
            .await
            .map_err(|_| ServiceError::Gone)?;
        rx.await.map_err(|_| ServiceError::Gone)?
    }

    /// Every event from now on.
    pub fn subscribe(&self) -> broadcast::Receiver<Event> {
        self.events.subscribe()
    }
}

/// A sender of events for another thread of the controller than the endpoint's.
#[derive(Clone, Debug)]
pub struct EventPublisher {
    events: broadcast::Sender<Event>,
}

impl EventPublisher {
    /// Tell every subscriber (never blocks; nobody listening is fine).
    pub fn publish(&self, event: Event) {
        let _ = self.events.send(event);
    }

    /// True when a service listens.
    pub fn has_subscribers(&self) -> bool {
        self.events.receiver_count() > 0
    }
}

impl ServiceEndpoint {
    /// The next waiting request, if any (never blocks).
    pub fn try_next(&mut self) -> Option<Request> {
        self.requests.try_recv().ok()
    }

    /// A publisher for another thread of the controller.
    pub fn publisher(&self) -> EventPublisher {
        EventPublisher {
            events: self.events.clone(),
        }
    }

    /// Tell every subscriber (never blocks; nobody listening is fine).
    pub fn publish(&self, event: Event) {
        let _ = self.events.send(event);
    }

    /// True when a service listens.
    pub fn has_subscribers(&self) -> bool {
        self.events.receiver_count() > 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A request reaches the endpoint with its reply channel, the answer reaches the asker,
    /// and events reach every subscriber.
    #[test]
    fn requests_are_answered_and_events_broadcast() {
        let rt = tokio::runtime::Builder::new_current_thread()
            .build()
            .unwrap_or_else(|e| panic!("runtime: {e}"));
        let (handle, mut endpoint) = channel();
        let mut events = handle.subscribe();
        assert!(endpoint.has_subscribers());
        rt.block_on(async {
            let asker = handle.ask(Request::SpeedRatio);
            let answer = async {
                loop {
                    if let Some(Request::SpeedRatio(reply)) = endpoint.try_next() {
                        let _ = reply.send(Ok(42));
                        break;
                    }
                    tokio::task::yield_now().await;
                }
            };
            let (got, ()) = tokio::join!(asker, answer);
            assert_eq!(got, Ok(42));
        });
        endpoint.publish(Event::SpeedRatio(50));
        assert_eq!(events.try_recv().ok(), Some(Event::SpeedRatio(50)));
        drop(endpoint);
        let gone = rt.block_on(handle.ask(Request::OpMode));
        assert_eq!(gone, Err(ServiceError::Gone));
    }

    /// `refuse` answers a request of any kind with the error, so a service never waits for a
    /// request its controller does not serve.
    #[test]
    fn refused_requests_answer_with_the_error() {
        let rt = tokio::runtime::Builder::new_current_thread()
            .build()
            .unwrap_or_else(|e| panic!("runtime: {e}"));
        let (handle, mut endpoint) = channel();
        rt.block_on(async {
            let asker = handle.ask(|reply| Request::DipcRead {
                queue: "Q".into(),
                reply,
            });
            let answer = async {
                loop {
                    if let Some(request) = endpoint.try_next() {
                        request.refuse(ServiceError::NotAllowed("no queues".into()));
                        break;
                    }
                    tokio::task::yield_now().await;
                }
            };
            let (got, ()) = tokio::join!(asker, answer);
            assert_eq!(got, Err(ServiceError::NotAllowed("no queues".into())));
        });
    }
}
