//! The interpreter's only window on the world: time, waiting, output and I/O signals.
//!
//! The interpreter never touches `std::time`, threads or sockets; the controller (or a test)
//! implements [`Host`]. [`VirtualHost`] is a pure counter: `WaitTime 10` advances its clock by
//! ten seconds at once, so runs are deterministic and take no wall time.
//!
//! Motion and EGM (issues 4 and 5) plug in without touching the interpreter core:
//! 1. add capability methods to [`Host`] with default implementations that return
//!    `HostError::fatal("… is not supported by this controller")` (e.g.
//!    `submit(&mut self, cmd: robot::MotionCommand)`, `standstill(&self) -> bool`,
//!    `robot_position(&self) -> …`, EGM session calls);
//! 2. write the natives in `interp/builtins/motion.rs` (and `egm.rs`) against those methods
//!    through [`super::builtins::Ctx::host`]; a native that must wait (a fine point, `WaitRob`,
//!    an EGM movement) uses [`super::builtins::Ctx::wait_host`], which keeps running traps;
//! 3. or, from the controller, swap an implementation with
//!    [`super::Registry::replace`] (same signature, so programs keep checking).
//!
//! Until then the motion and EGM natives fail with "`MoveJ` is not yet supported by rapidvc
//! (virtual robot: issue 4)": a clear run-time error, never a silent no-op.

use std::fmt;
use std::sync::Arc;

use super::errnum;
use crate::io::{IoError, SignalTable};

mod egm;
pub use egm::{EgmHost, EgmRun};

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

/// Everything the interpreter needs from the controller.
pub trait Host {
    /// Current time in seconds since the program started.
    fn now(&self) -> f64;

    /// Let time pass until `deadline` (seconds, same clock as [`Host::now`]) or until
    /// something outside the program may have changed (a signal, a message), whichever comes
    /// first; returns the new current time. A virtual host jumps straight to the deadline.
    fn wait_until(&mut self, deadline: f64) -> Result<f64, HostError>;

    /// Deliver program output (TP lines, event-log entries).
    fn output(&mut self, out: Output);

    /// Current value of an I/O signal (digital 0/1, analog value, group value).
    fn read_signal(&mut self, name: &str) -> Result<f64, HostError>;

    /// Set an output signal (or simulate an input).
    fn write_signal(&mut self, name: &str, value: f64) -> Result<(), HostError>;

    /// The EGM capability, when this controller has one (the EGM instructions fail with
    /// "not supported by this controller" otherwise).
    fn egm(&mut self) -> Option<&mut dyn EgmHost> {
        None
    }
}

/// A callback that receives program output.
pub type OutputSink = Box<dyn FnMut(&Output) + Send>;

/// A deterministic host: a virtual clock that jumps, output kept in memory (or handed to a
/// callback), signals in a shared [`SignalTable`].
pub struct VirtualHost {
    now: f64,
    max_time: Option<f64>,
    outputs: Vec<Output>,
    sink: Option<OutputSink>,
    signals: Arc<SignalTable>,
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
            now: 0.0,
            max_time: None,
            outputs: Vec::new(),
            sink: None,
            signals: Arc::new(SignalTable::with_builtins()),
        }
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
    pub fn set_time(&mut self, t: f64) {
        self.now = t;
    }
}

impl Host for VirtualHost {
    fn now(&self) -> f64 {
        self.now
    }

    fn wait_until(&mut self, deadline: f64) -> Result<f64, HostError> {
        if let Some(max) = self.max_time
            && deadline > max
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
}

/// A signal-table error as a RAPID error (or a fatal one when it names no RAPID error).
pub fn io_error(e: IoError) -> HostError {
    match e.err_name().and_then(errnum::by_name) {
        Some(d) => HostError::rapid(d.num, e.to_string()),
        None => HostError::fatal(e.to_string()),
    }
}
