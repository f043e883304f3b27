//! rapidvc's options of EGM runs and streams (not RAPID arguments) and the context every run shares.

use std::sync::Arc;
use std::time::Duration;

use crate::egm::EgmError;
use crate::egm::convert::EncodeOptions;
use crate::egm::message_log::DEFAULT_LOG_CAPACITY;
use crate::egm::servo::{DEFAULT_SERVO_DELAY, MAX_SERVO_DELAY, MIN_PERIOD};
use crate::egm::session::{DropTally, QueuePolicy, SourceFilter};
use crate::robot::Robot;
use crate::signals::SignalTable;

/// Most events waiting in a driver; further ones are counted and lost.
pub const MAX_EVENTS: usize = 64;
/// Default lockstep wait for one reply (real time).
pub const DEFAULT_REPLY_TIMEOUT: Duration = Duration::from_millis(100);

/// rapidvc options of every EGM run and stream (not RAPID arguments).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DriverOptions {
    /// The motion tick the driver is called at (4 ms).
    pub tick: Duration,
    /// Delay from commanded to measured position (12 ms; see `egm::servo`).
    pub servo_delay: Duration,
    /// How received references are consumed (newest per cycle).
    pub queue: QueuePolicy,
    /// Which senders a UdpUc session accepts (the device's remote address and port).
    pub source_filter: SourceFilter,
    /// Extra `EgmRobot` content.
    pub encode: EncodeOptions,
    /// Repeated session events are reported at most this often.
    pub event_repeat: Duration,
    /// Lockstep: how long [`crate::egm::EgmDriver::wait_reply`] waits for one reply (real time).
    pub reply_timeout: Duration,
    /// Rows kept in the log ring (0: no log).
    pub log_capacity: usize,
}

impl Default for DriverOptions {
    fn default() -> Self {
        DriverOptions {
            tick: Duration::from_millis(4),
            servo_delay: DEFAULT_SERVO_DELAY,
            queue: QueuePolicy::Newest,
            source_filter: SourceFilter::Remote,
            encode: EncodeOptions::default(),
            event_repeat: Duration::from_secs(1),
            reply_timeout: DEFAULT_REPLY_TIMEOUT,
            log_capacity: DEFAULT_LOG_CAPACITY,
        }
    }
}

/// What every run and stream of a controller shares.
#[derive(Clone, Debug)]
pub struct DriverContext {
    /// The robot (model, base).
    pub robot: Robot,
    /// The I/O signals (signal sources, `\DOToSensor`, `\DIFromSensor`).
    pub signals: Arc<SignalTable>,
    /// rapidvc options.
    pub options: DriverOptions,
    /// Datagrams every session of the controller dropped, by cause (the end-of-run totals).
    pub drops: Arc<DropTally>,
}

/// The tick must allow a servo step and the servo delay must be modelled (egm::servo).
pub(crate) fn check_options(
    instruction: &'static str,
    opts: &DriverOptions,
) -> Result<(), EgmError> {
    if opts.tick < MIN_PERIOD {
        return Err(EgmError::BadSetup {
            instruction,
            detail: format!(
                "the motion tick {:?} is shorter than {MIN_PERIOD:?}",
                opts.tick
            ),
        });
    }
    if opts.servo_delay > MAX_SERVO_DELAY {
        return Err(EgmError::BadSetup {
            instruction,
            detail: format!(
                "the servo delay {:?} is longer than {MAX_SERVO_DELAY:?}",
                opts.servo_delay
            ),
        });
    }
    Ok(())
}
