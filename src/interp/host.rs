//! The interpreter's only window on the world: time, waiting, output, I/O signals and the
//! robot.
//!
//! The interpreter never touches `std::time`, threads or sockets; the controller (or a test)
//! implements [`Host`]. [`VirtualHost`] is a pure counter: `WaitTime 10` advances its clock by
//! ten seconds at once, so runs are deterministic and take no wall time. It has no robot: its
//! motion methods keep their defaults, which fail with "this controller has no robot".
//! `controller::program_host::ControllerHost` is the host with the virtual robot behind it.
//!
//! # Motion
//!
//! The interpreter side only builds [`crate::robot::command`] values; the host plans and
//! executes them:
//! * [`Host::motion_submit`] queues a move (blocking while the queue is full) and returns its
//!   id; RAPID runs ahead of the robot up to the next stop point;
//! * [`Host::motion_reached`] tells, without blocking, whether a [`MotionWait`] holds; natives
//!   that must wait (a fine point, `WaitRob`) poll it through
//!   [`super::builtins::Ctx::wait_host`], so traps keep running. [`Host::wait_until`] of a host
//!   with a robot returns early whenever the motion state changes (a move ends, the robot
//!   stops), so such waits end on the cycle where the condition becomes true;
//! * [`Host::motion_joints`], [`Host::robot_target_of`] and [`Host::robot_joints_of`] read the
//!   position and do the kinematics of `CJointT`, `CRobT`, `CPos`, `CalcRobT`, `CalcJointT`;
//! * [`Host::motion_modes`] and [`Host::motion_set`] hold the modal settings (`ConfJ`,
//!   `ConfL`, `SingArea`, `VelSet`, `AccSet`, program displacement).
//!
//! Motion errors come back as [`HostError`]s with the RAPID error number (`ERR_ROBLIMIT`,
//! `ERR_OUTSIDE_REACH`) and a message that starts with the ABB event number and title, so
//! `ERROR` handlers can take them and unhandled ones point at the instruction.
//!
//! # The system side
//!
//! [`Host::system`] gives the controller's operating-system services ([`Services`]: the
//! task's sockets), plain Rust types of `crate::system` that the natives in
//! `interp/builtins/sockets.rs` drive. [`VirtualHost`] owns one, and the controller's host
//! hands out that of its `VirtualHost`.
//!
//! # EGM
//!
//! [`Host::egm`] gives the EGM capability ([`EgmHost`]), `None` by default (the EGM
//! instructions then stop the program with "… is not supported by this controller"). The
//! natives in `interp/builtins/egm.rs` fill the registry's request types from RAPID values
//! and name identities by their variable; `controller::egm_controller` implements the capability for
//! any controller-backed host.

use std::fmt;
use std::sync::Arc;

use super::errnum;
use crate::robot::command::{MotionCommand, RobTarget};
use crate::robot::{JointsDeg, Pose, ToolData, WobjData};
use crate::signals::{IoError, SignalTable};
use crate::time::RobotTime;

mod egm_host;
mod egm_path_host;
mod position_events;
mod task_host;
pub use egm_host::{EgmHost, EgmRun};
pub use egm_path_host::EgmPathHost;
pub use position_events::{PositionEventHost, ProgramAction, SearchStop, TriggAction, TriggEvent};
pub use task_host::{RmqMessage, TaskHost};

/// Something the program produced for the outside world.
#[derive(Clone, Debug, PartialEq)]
pub enum Output {
    /// One `TPWrite` line.
    TpWrite(String),
    /// `TPErase`.
    TpErase,
    /// `ErrWrite` (an event-log entry).
    ErrWrite {
        /// `\W`: a warning rather than an error.
        warning: bool,
        /// Header text.
        header: String,
        /// Reason lines (`Reason`, `\RL2` … `\RL4`).
        reason: Vec<String>,
    },
    /// An informational event from the interpreter (interrupt queue full, …).
    Event(String),
}

/// A failure of the host, turned into a RAPID error (when `errno` is set) or a fatal error.
#[derive(Clone, Debug, PartialEq)]
pub struct HostError {
    /// RAPID error number to raise, if the program may handle it.
    pub errno: Option<i32>,
    /// What went wrong.
    pub message: String,
}

impl HostError {
    /// A recoverable error with a RAPID error number.
    pub fn rapid(errno: i32, message: impl Into<String>) -> Self {
        HostError {
            errno: Some(errno),
            message: message.into(),
        }
    }

    /// A fatal error.
    pub fn fatal(message: impl Into<String>) -> Self {
        HostError {
            errno: None,
            message: message.into(),
        }
    }
}

impl fmt::Display for HostError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

/// What a program waits for from the robot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MotionWait {
    /// The move with this id (from [`Host::motion_submit`]) is complete: a fine point reached,
    /// or the corner path of a fly-by point begun.
    Done(u64),
    /// Every queued move is complete and the robot stands still (`WaitRob \InPos`).
    InPos,
    /// The robot does not move right now (`WaitRob \ZeroSpeed`).
    ZeroSpeed,
}

/// `SingArea \Off | \Wrist | \LockAxis4`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SingAreaMode {
    /// `\Off` (the default): paths through singular configurations are refused.
    #[default]
    Off,
    /// `\Wrist`: linear paths may pass close to the wrist singularity.
    Wrist,
    /// `\LockAxis4`.
    LockAxis4,
}

/// A change of a modal motion setting.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MotionSetting {
    /// `ConfJ \On` (true) or `\Off`.
    ConfJ(bool),
    /// `ConfL \On` (true) or `\Off`.
    ConfL(bool),
    /// `SingArea`.
    SingArea(SingAreaMode),
    /// `VelSet Override, Max`.
    VelSet {
        /// Speed override in percent.
        override_pct: f64,
        /// Maximum TCP speed (mm/s).
        max_tcp: f64,
    },
    /// `AccSet Acc, Ramp`.
    AccSet {
        /// Acceleration in percent of normal.
        acc_pct: f64,
        /// Jerk in percent of normal.
        ramp_pct: f64,
    },
    /// Program displacement (`PDispSet`, `PDispOn`); the identity switches it off
    /// (`PDispOff`).
    PDisp(Pose),
    /// `PathAccLim`: TCP acceleration and deceleration limits along the path (mm/s²), `None`
    /// for no limit.
    PathAccLim {
        /// `\AccMax`.
        acc: Option<f64>,
        /// `\DecelMax`.
        decel: Option<f64>,
    },
    /// `WorldAccLim \On := x` (mm/s²) or `\Off` (`None`).
    WorldAccLim(Option<f64>),
    /// External axis offsets (`EOffsSet`, `EOffsOn`), `None` switches them off (`EOffsOff`).
    EOffs(Option<[f64; 6]>),
}

/// A request to the correction generators (`CorrCon`, `CorrWrite`, …).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CorrRequest {
    /// `CorrCon`: a new generator; answers its number.
    Connect,
    /// `CorrWrite`: the offset of generator `n` (path frame, mm).
    Write(u32, [f64; 3]),
    /// `CorrDiscon`: generator `n` is gone.
    Disconnect(u32),
    /// `CorrClear`: every generator is gone.
    Clear,
    /// `CorrRead`: answers the sum of the offsets.
    Read,
    /// The move with this id has `\Corr`.
    Mark(u64),
}

/// The answer to a [`CorrRequest`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CorrAnswer {
    /// The request was carried out.
    Done,
    /// The new generator's number.
    Connected(u32),
    /// The sum of the offsets (path frame, mm).
    Offset([f64; 3]),
}

/// A change of the robot's path as a whole: `StopMove`, `StartMove`, `StorePath`, ….
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PathCommand {
    /// `StopMove [\Quick]`: decelerate on the path and hold.
    Stop {
        /// `\Quick`.
        quick: bool,
    },
    /// `StartMove`: resume the held path.
    Start,
    /// `StopMoveReset`: the stop-move state ends, the robot does not start.
    Reset,
    /// `SpeedRefresh Override`: the ongoing path at this percentage of its planned speed.
    Speed(f64),
    /// `StorePath`.
    Store,
    /// `RestoPath`.
    Restore,
    /// `ClearPath`.
    Clear,
}

/// The modal settings move instructions read when they build a command.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionModes {
    /// `ConfJ \On` (the default after program start).
    pub conf_j: bool,
    /// `ConfL \On` (the default after program start).
    pub conf_l: bool,
    /// The active program displacement (identity when off).
    pub pdisp: Pose,
    /// External axis offsets (`EOffsOn`/`EOffsSet`), `None` when off.
    pub eoffs: Option<[f64; 6]>,
    /// The stop-move state (`StopMove` until `StartMove` or `StopMoveReset`).
    pub stop_move: bool,
    /// The speed override of `SpeedRefresh` (%).
    pub speed_refresh: f64,
}

impl Default for MotionModes {
    fn default() -> Self {
        MotionModes {
            conf_j: true,
            conf_l: true,
            pdisp: Pose::identity(),
            eoffs: None,
            stop_move: false,
            speed_refresh: 100.0,
        }
    }
}

/// The error of a motion method on a host without a robot.
pub fn no_robot() -> HostError {
    HostError::fatal(
        "this controller has no robot: motion instructions and functions need the virtual \
         robot of `rapidvc run`",
    )
}

/// Everything the interpreter needs from the controller.
pub trait Host {
    /// The current robot time (the controller's clock; the program started at or after its
    /// start).
    fn now(&self) -> RobotTime;

    /// Let time pass until `deadline` (same clock as [`Host::now`]) or until something
    /// outside the program may have changed (a signal, a message), whichever comes first;
    /// returns the new current time. A virtual host jumps straight to the deadline.
    fn wait_until(&mut self, deadline: RobotTime) -> Result<RobotTime, HostError>;

    /// Deliver program output (TP lines, event-log entries).
    fn output(&mut self, out: Output);

    /// Current value of an I/O signal (digital 0/1, analog value, group value).
    fn read_signal(&mut self, name: &str) -> Result<f64, HostError>;

    /// Set an output signal (or simulate an input).
    fn write_signal(&mut self, name: &str, value: f64) -> Result<(), HostError>;

    /// The kind of a configured signal (DI, DO, AI, …), `None` when there is no such
    /// signal (`AliasIO`, `ValidIO`).
    fn signal_kind(&self, name: &str) -> Option<crate::signals::SignalKind> {
        let _ = name;
        None
    }

    /// Plan and queue a move; blocks while the motion queue is full. The host numbers the
    /// moves: the `id` in `cmd` is replaced, and the new one is returned (for
    /// [`MotionWait::Done`]). A move that cannot be executed is refused here, before the
    /// robot moves.
    fn motion_submit(&mut self, cmd: MotionCommand) -> Result<u64, HostError> {
        let _ = cmd;
        Err(no_robot())
    }

    /// Whether `wait` holds now (never blocks). An error when the robot stopped on a motion
    /// error, or when the condition can never become true. A host without a robot is always
    /// in position and standing still.
    fn motion_reached(&mut self, wait: MotionWait) -> Result<bool, HostError> {
        match wait {
            MotionWait::Done(_) => Err(no_robot()),
            MotionWait::InPos | MotionWait::ZeroSpeed => Ok(true),
        }
    }

    /// The robot's current axis values (deg).
    fn motion_joints(&mut self) -> Result<JointsDeg, HostError> {
        Err(no_robot())
    }

    /// The modal motion settings (`ConfJ`, `ConfL`, program displacement).
    fn motion_modes(&self) -> MotionModes {
        MotionModes::default()
    }

    /// Change a modal motion setting for the moves queued from now on.
    fn motion_set(&mut self, setting: MotionSetting) -> Result<(), HostError> {
        let _ = setting;
        Err(no_robot())
    }

    /// Change the robot's path as a whole (`StopMove`, `StartMove`, `StorePath`, …).
    fn motion_path(&mut self, cmd: PathCommand) -> Result<(), HostError> {
        let _ = cmd;
        Err(no_robot())
    }

    /// The correction generators of `\Corr` moves (`CorrCon`, `CorrWrite`, …).
    fn motion_corr(&mut self, req: CorrRequest) -> Result<CorrAnswer, HostError> {
        let _ = req;
        Err(no_robot())
    }

    /// Where the TCP of `tool` is at `joints`, as a robtarget in the object frame of `wobj`
    /// with program displacement `pdisp` removed, with the configuration of `joints`
    /// (`CRobT`, `CalcRobT`).
    fn robot_target_of(
        &self,
        joints: &JointsDeg,
        tool: &ToolData,
        wobj: &WobjData,
        pdisp: &Pose,
    ) -> Result<RobTarget, HostError> {
        let _ = (joints, tool, wobj, pdisp);
        Err(no_robot())
    }

    /// The axis values that put the TCP of `tool` at `target` (object frame of `wobj`,
    /// displaced by `pdisp`) in the target's configuration (`CalcJointT`).
    fn robot_joints_of(
        &self,
        target: &RobTarget,
        tool: &ToolData,
        wobj: &WobjData,
        pdisp: &Pose,
    ) -> Result<JointsDeg, HostError> {
        let _ = (target, tool, wobj, pdisp);
        Err(no_robot())
    }

    /// The concrete host, for a front end that needs it back after a run (e.g. to finish the
    /// controller and print its summary).
    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        None
    }

    /// The EGM capability, when this controller has one (the EGM instructions fail with
    /// "not supported by this controller" otherwise).
    fn egm(&mut self) -> Option<&mut dyn EgmHost> {
        None
    }

    /// The EGM path-correction capability (EGMMoveL, EGMMoveC), when this controller has one.
    fn egm_path(&mut self) -> Option<&mut dyn EgmPathHost> {
        None
    }

    /// The controller's system side: calendar, system information, configuration database,
    /// text tables (`crate::system`), when this host has one (the instructions and functions
    /// that need it fail with "… is not supported by this controller" otherwise).
    fn system(&mut self) -> Option<&mut crate::system::Services> {
        None
    }

    /// An error when the run's time limit (`--max-time`) has been reached: for waits that
    /// do not go through [`Host::wait_until`] (a socket instruction waits on its socket, in
    /// real time, a slice at a time). A host without a limit never fails.
    fn check_time_limit(&mut self) -> Result<(), HostError> {
        Ok(())
    }

    /// Run `f` on the system side where it may block for a short while (a socket
    /// instruction waiting for its peer, a few tens of milliseconds per call): a host that
    /// schedules several tasks lets the other tasks run meanwhile and notices a stop request
    /// after it. False (and `f` not called) when this host has no system side.
    fn system_blocking(&mut self, f: &mut dyn FnMut(&mut crate::system::Services)) -> bool {
        match self.system() {
            Some(s) => {
                f(s);
                true
            }
            None => false,
        }
    }

    /// The position-event capability (`TriggL`, `MoveLDO`, `SearchL`, …), when this
    /// controller has one.
    fn position_events(&mut self) -> Option<&mut dyn PositionEventHost> {
        None
    }

    /// Let the other RAPID tasks run (the end of a time slice; see `interp::tasks`). A host
    /// of a single task returns at once.
    fn yield_now(&mut self) -> Result<(), HostError> {
        Ok(())
    }

    /// The capability of a host running among several RAPID tasks (`WaitSyncTask`, the
    /// RAPID message queue, task numbers), `None` for a single task.
    fn tasks(&mut self) -> Option<&mut dyn TaskHost> {
        None
    }
}

/// A callback that receives program output.
pub type OutputSink = Box<dyn FnMut(&Output) + Send>;

/// A deterministic host: a virtual clock that jumps, output kept in memory (or handed to a
/// callback), signals in a shared [`SignalTable`].
pub struct VirtualHost {
    now: RobotTime,
    max_time: Option<f64>,
    outputs: Vec<Output>,
    sink: Option<OutputSink>,
    signals: Arc<SignalTable>,
    system: crate::system::Services,
}

impl fmt::Debug for VirtualHost {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("VirtualHost")
            .field("now", &self.now)
            .field("outputs", &self.outputs.len())
            .finish()
    }
}

impl Default for VirtualHost {
    fn default() -> Self {
        Self::new()
    }
}

impl VirtualHost {
    /// Time 0, no time limit, output kept in memory, the built-in signals.
    pub fn new() -> Self {
        VirtualHost {
            now: RobotTime::ZERO,
            max_time: None,
            outputs: Vec::new(),
            sink: None,
            signals: Arc::new(SignalTable::with_builtins()),
            system: crate::system::Services::default(),
        }
    }

    /// Use this system side (calendar start, system information, configuration data); the
    /// default has rapidvc's values and no configuration files.
    pub fn with_system(mut self, system: crate::system::Services) -> Self {
        self.system = system;
        self
    }

    /// Use this signal table (shared with whoever else reads or drives the signals).
    pub fn with_signals(mut self, signals: Arc<SignalTable>) -> Self {
        self.signals = signals;
        self
    }

    /// The signal table.
    pub fn signals(&self) -> &Arc<SignalTable> {
        &self.signals
    }

    /// Fail waits that would pass this virtual time (a guard against programs that wait
    /// forever for something nobody will do).
    pub fn with_max_time(mut self, seconds: f64) -> Self {
        self.max_time = Some(seconds);
        self
    }

    /// Hand every output to `sink` as it happens instead of keeping it.
    pub fn with_sink(mut self, sink: impl FnMut(&Output) + Send + 'static) -> Self {
        self.sink = Some(Box::new(sink));
        self
    }

    /// Output kept so far (empty when a sink is set).
    pub fn outputs(&self) -> &[Output] {
        &self.outputs
    }

    /// The `TPWrite` lines kept so far.
    pub fn tp_lines(&self) -> Vec<String> {
        self.outputs
            .iter()
            .filter_map(|o| match o {
                Output::TpWrite(s) => Some(s.clone()),
                _ => None,
            })
            .collect()
    }

    /// Move the clock (tests).
    pub fn set_time(&mut self, t: RobotTime) {
        self.now = t;
    }
}

impl Host for VirtualHost {
    fn now(&self) -> RobotTime {
        self.now
    }

    fn wait_until(&mut self, deadline: RobotTime) -> Result<RobotTime, HostError> {
        if let Some(max) = self.max_time
            && deadline > RobotTime::from_secs_f64(max)
        {
            return Err(HostError::fatal(format!(
                "the program waits beyond the virtual time limit of {max} s \
                 (nothing in a virtual run can end this wait; use --max-time to raise it)"
            )));
        }
        if deadline > self.now {
            self.now = deadline;
        }
        Ok(self.now)
    }

    fn output(&mut self, out: Output) {
        match &mut self.sink {
            Some(f) => f(&out),
            None => self.outputs.push(out),
        }
    }

    fn read_signal(&mut self, name: &str) -> Result<f64, HostError> {
        let id = self.signals.lookup_or_err(name).map_err(io_error)?;
        self.signals
            .value(id)
            .ok_or_else(|| HostError::fatal(format!("signal `{name}` has no value")))
    }

    fn write_signal(&mut self, name: &str, value: f64) -> Result<(), HostError> {
        let id = self.signals.lookup_or_err(name).map_err(io_error)?;
        self.signals.set(id, value).map(drop).map_err(io_error)
    }

    fn system(&mut self) -> Option<&mut crate::system::Services> {
        Some(&mut self.system)
    }

    fn signal_kind(&self, name: &str) -> Option<crate::signals::SignalKind> {
        let id = self.signals.lookup(name)?;
        self.signals.def(id).map(|d| d.kind)
    }
}

/// A signal-table error as a RAPID error (or a fatal one when it names no RAPID error).
pub fn io_error(e: IoError) -> HostError {
    match e.err_name().and_then(errnum::by_name) {
        Some(d) => HostError::rapid(d.num, e.to_string()),
        None => HostError::fatal(e.to_string()),
    }
}
