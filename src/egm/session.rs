//! The controller side of one EGM session as a sans-IO state machine (quinn-proto style).
//!
//! The caller owns the socket and the clock. Each EGM cycle it
//! 1. hands every datagram that arrived to [`EgmSession::handle_datagram`] (the transport
//!    drains its socket),
//! 2. takes the reference for this cycle with [`EgmSession::poll_reference`],
//! 3. sends what [`EgmSession::poll_transmit`] returns, and
//! 4. sleeps until [`EgmSession::poll_timeout`], calling [`EgmSession::handle_timeout`].
//!
//! Time is the controller's [`RobotTime`] (real or virtual), handed in by the caller;
//! `header.tm` is that time in milliseconds, wrapping at 2^32.
//!
//! **Queue policy.** The default, [`QueuePolicy::Newest`], drains everything that arrived and
//! uses the newest valid message; older ones are counted as `superseded`. This keeps latency
//! bounded when a sensor sends faster than the cycle. [`QueuePolicy::OnePerCycle`] consumes
//! one message per cycle in arrival order from a small bounded queue (dropping the oldest on
//! overflow), which is the literal reading of ABB's manual. Every tested client sends one
//! reply per received datagram, so both behave the same with them.
//!
//! **Comm time-out.** The timer starts at [`EgmSession::start`] and restarts with every
//! accepted reference; datagrams that are dropped or rejected do not count as sensor data.
//! When it expires the session raises event 41822 once and reports
//! [`EgmSession::comm_timed_out`]; the controller then ramps out and raises `ERR_UDPUC_COMM`.

use std::collections::VecDeque;
use std::net::{IpAddr, SocketAddr};
use std::sync::Arc;
use std::time::Duration;

use prost::Message;

use super::convert::{
    DecodeError, EncodeOptions, ReferenceError, ReferenceLimits, decode_reference,
    feedback_non_finite, fill_robot, header_tm, is_truncated,
};
use super::event::{EgmEvent, EventKind};
use super::latency::{LatencyHistogram, fmt_duration};
use super::proto::EgmRobot;
use super::types::{EgmMode, Pose, RobotFeedback, SensorReference, Target};
use crate::time::RobotTime;

/// Largest datagram rapidvc sends, and by default accepts (the clients' receive buffers).
pub const MAX_DATAGRAM_LEN: usize = 1024;
/// Default EGM cycle.
pub const DEFAULT_SAMPLE_PERIOD: Duration = Duration::from_millis(4);
/// Default `\CommTimeout` (ABB's default is not documented; an ABB maintainer recalled 1 s).
pub const DEFAULT_COMM_TIMEOUT: Duration = Duration::from_secs(1);
/// How early [`EgmSession::poll_transmit`] may serve a cycle (at most half a period).
const MAX_EARLY: Duration = Duration::from_millis(1);
/// Most events waiting in the queue; further ones are counted in `events_dropped`.
const EVENT_QUEUE: usize = 32;
/// Largest one-per-cycle queue.
pub const MAX_QUEUE_CAPACITY: usize = 64;

mod drops;
pub use drops::{DropCounts, DropReason, DropTally};

/// Which senders are accepted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SourceFilter {
    /// Only datagrams from the device's remote address **and** port (`--device
    /// NAME=HOST:PORT`, SIO.cfg `RemoteAddress`/`RemotePortNumber`; an IPv4-mapped IPv6
    /// address counts as the IPv4 one). Any other sender, on another host or on the
    /// sensor's host at another port, is dropped (event 90101) and counted. Default.
    #[default]
    Remote,
    /// Any sender (the in-process built-in sensor); references from all of them are used.
    Any,
}

/// How received references are consumed per cycle (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum QueuePolicy {
    /// Use the newest valid message of the cycle; older ones are superseded. Default.
    Newest,
    /// One message per cycle, oldest first, from a queue of at most `capacity` messages.
    OnePerCycle {
        /// Queue length (1..=[`MAX_QUEUE_CAPACITY`]).
        capacity: usize,
    },
}

/// Session configuration (from EGMSetupUC, EGMAct*, the UdpUc device and rapidvc options).
#[derive(Clone, Debug, PartialEq)]
pub struct EgmConfig {
    /// Which message the sensor sends.
    pub mode: EgmMode,
    /// The device's Remote Address and Remote Port Number.
    pub remote: SocketAddr,
    /// Which senders are accepted.
    pub source_filter: SourceFilter,
    /// EGM cycle (`\SampleRate`).
    pub sample_period: Duration,
    /// `\CommTimeout`; `None` for a position stream, which needs no replies.
    pub comm_timeout: Option<Duration>,
    /// Queue policy.
    pub queue: QueuePolicy,
    /// Longest datagram accepted from the sensor.
    pub max_datagram_len: usize,
    /// Bounds on references.
    pub limits: ReferenceLimits,
    /// What to fill in `EgmRobot` beyond the mandatory fields.
    pub encode: EncodeOptions,
    /// Repeated events of one kind are reported at most this often (with a count).
    pub event_repeat: Duration,
}

impl EgmConfig {
    /// Defaults for `mode` talking to `remote`: 4 ms cycle, 1 s comm time-out, newest-message
    /// policy, remote address-and-port filter, 1024-byte limit, sanity bounds, one event per kind per second.
    pub fn new(mode: EgmMode, remote: SocketAddr) -> Self {
        EgmConfig {
            mode,
            remote,
            source_filter: SourceFilter::Remote,
            sample_period: DEFAULT_SAMPLE_PERIOD,
            comm_timeout: Some(DEFAULT_COMM_TIMEOUT),
            queue: QueuePolicy::Newest,
            max_datagram_len: MAX_DATAGRAM_LEN,
            limits: ReferenceLimits::default(),
            encode: EncodeOptions::default(),
            event_repeat: Duration::from_secs(1),
        }
    }
}

/// A configuration the session cannot run with.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ConfigError {
    /// The sample period is zero.
    #[error("the EGM sample period must be greater than zero")]
    ZeroSamplePeriod,
    /// The comm time-out is zero.
    #[error("\\CommTimeout must be greater than zero")]
    ZeroCommTimeout,
    /// The one-per-cycle queue capacity is 0 or too large.
    #[error("the EGM receive queue capacity must be 1..={max}, not {got}")]
    QueueCapacity {
        /// Requested capacity.
        got: usize,
        /// Largest allowed.
        max: usize,
    },
    /// The datagram limit is zero.
    #[error("the EGM datagram limit must be greater than zero")]
    ZeroDatagramLimit,
}

/// Lifecycle of a session.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SessionState {
    /// Created, never started.
    Idle,
    /// Sending every cycle.
    Running,
    /// Stopped; [`EgmSession::start`] begins a new session with seqno 0.
    Stopped,
}

/// What [`EgmSession::handle_datagram`] did with a datagram.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Decoded, validated and queued.
    Accepted,
    /// The session is not running; the datagram was counted and ignored.
    Ignored,
    /// Dropped or rejected, and counted.
    Dropped(DropReason),
}

/// Counters of one session object (cumulative over restarts; see [`EgmSession::reset_stats`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EgmStats {
    /// `EgmRobot` datagrams produced.
    pub sent: u64,
    /// Datagrams handed to `handle_datagram`.
    pub received: u64,
    /// Accepted references.
    pub accepted: u64,
    /// Dropped: not from the device's remote address and port.
    pub wrong_source: u64,
    /// Dropped: too long.
    pub oversized: u64,
    /// Dropped: a protobuf message cut short.
    pub truncated: u64,
    /// Dropped: did not decode.
    pub malformed: u64,
    /// Rejected: NaN or infinity.
    pub not_finite: u64,
    /// Rejected: target or required value missing.
    pub incomplete: u64,
    /// Rejected: out of bounds.
    pub out_of_range: u64,
    /// Rejected: wrong message type for the mode.
    pub wrong_type: u64,
    /// Ignored while the session was not running.
    pub ignored_idle: u64,
    /// Valid references replaced by a newer one in the same cycle (newest policy).
    pub superseded: u64,
    /// References dropped because the one-per-cycle queue was full.
    pub queue_overflow: u64,
    /// Cycles skipped because `poll_transmit` was called late.
    pub late_cycles: u64,
    /// Cycles not sent because the feedback was not finite.
    pub unsendable: u64,
    /// Events lost because the event queue was full.
    pub events_dropped: u64,
    /// Time from the latest `EgmRobot` sent to each accepted reply (sensor turnaround plus
    /// network and scheduling delay).
    pub turnaround: LatencyHistogram,
}

impl EgmStats {
    /// All datagrams dropped or rejected, for any reason.
    pub fn dropped(&self) -> u64 {
        self.wrong_source
            + self.oversized
            + self.truncated
            + self.malformed
            + self.not_finite
            + self.incomplete
            + self.out_of_range
            + self.wrong_type
    }
}

/// Per-kind event rate limiting.
#[derive(Clone, Copy, Debug, Default)]
struct Throttle {
    last: Option<RobotTime>,
    suppressed: u64,
}

/// Event kinds the session throttles, in a fixed order.
const THROTTLED: [EventKind; 7] = [
    EventKind::Oversized,
    EventKind::Malformed,
    EventKind::InvalidReference,
    EventKind::OutOfBounds,
    EventKind::WrongMessageType,
    EventKind::FeedbackNotFinite,
    EventKind::QueueOverflow,
];

/// One EGM session, controller side.
#[derive(Debug)]
pub struct EgmSession {
    config: EgmConfig,
    state: SessionState,
    seqno: u32,
    next_transmit: RobotTime,
    last_transmit: Option<RobotTime>,
    comm_timer_start: RobotTime,
    timed_out: bool,
    queue: VecDeque<SensorReference>,
    latest: Option<SensorReference>,
    current: Option<SensorReference>,
    fallback_pose: Pose,
    events: VecDeque<EgmEvent>,
    throttle: [Throttle; THROTTLED.len()],
    wrong_source_reported: bool,
    scratch: EgmRobot,
    stats: EgmStats,
    tally: Option<Arc<DropTally>>,
}

impl EgmSession {
    /// A new idle session; checks the configuration.
    pub fn new(config: EgmConfig) -> Result<Self, ConfigError> {
        if config.sample_period.is_zero() {
            return Err(ConfigError::ZeroSamplePeriod);
        }
        if config.comm_timeout.is_some_and(|t| t.is_zero()) {
            return Err(ConfigError::ZeroCommTimeout);
        }
        if config.max_datagram_len == 0 {
            return Err(ConfigError::ZeroDatagramLimit);
        }
        let capacity = match config.queue {
            QueuePolicy::Newest => 1,
            QueuePolicy::OnePerCycle { capacity } => {
                if capacity == 0 || capacity > MAX_QUEUE_CAPACITY {
                    return Err(ConfigError::QueueCapacity {
                        got: capacity,
                        max: MAX_QUEUE_CAPACITY,
                    });
                }
                capacity
            }
        };
        Ok(EgmSession {
            config,
            state: SessionState::Idle,
            seqno: 0,
            next_transmit: RobotTime::ZERO,
            last_transmit: None,
            comm_timer_start: RobotTime::ZERO,
            timed_out: false,
            queue: VecDeque::with_capacity(capacity + 1),
            latest: None,
            current: None,
            fallback_pose: Pose::IDENTITY,
            events: VecDeque::with_capacity(EVENT_QUEUE),
            throttle: [Throttle::default(); THROTTLED.len()],
            wrong_source_reported: false,
            scratch: EgmRobot::default(),
            stats: EgmStats::default(),
            tally: None,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &EgmConfig {
        &self.config
    }

    /// The lifecycle state.
    pub fn state(&self) -> SessionState {
        self.state
    }

    /// True while the session sends every cycle.
    pub fn is_running(&self) -> bool {
        self.state == SessionState::Running
    }

    /// Starts a session at `now`: seqno restarts at 0, the first datagram is due at once, the
    /// comm timer starts, queued and current references are forgotten.
    pub fn start(&mut self, now: RobotTime) {
        self.state = SessionState::Running;
        self.seqno = 0;
        self.next_transmit = now;
        self.last_transmit = None;
        self.comm_timer_start = now;
        self.timed_out = false;
        self.queue.clear();
        self.latest = None;
        self.current = None;
        self.throttle = [Throttle::default(); THROTTLED.len()];
        self.wrong_source_reported = false;
    }

    /// Ends the session; nothing is sent until the next [`EgmSession::start`].
    pub fn stop(&mut self) {
        self.state = SessionState::Stopped;
        self.queue.clear();
    }

    /// The seqno the next `EgmRobot` will carry.
    pub fn next_seqno(&self) -> u32 {
        self.seqno
    }

    /// True once the comm time-out expired in this session (event 41822 was raised).
    pub fn comm_timed_out(&self) -> bool {
        self.timed_out
    }

    /// Counters and latency.
    pub fn stats(&self) -> &EgmStats {
        &self.stats
    }

    /// Also counts every datagram this session drops in `tally` (the run-wide totals).
    pub fn share_drops(&mut self, tally: Arc<DropTally>) {
        self.tally = Some(tally);
    }

    /// Counts a datagram dropped for `reason` (here and in the shared tally).
    fn count_drop(&mut self, reason: DropReason) {
        let st = &mut self.stats;
        let counter = match reason {
            DropReason::WrongSource => &mut st.wrong_source,
            DropReason::Oversized => &mut st.oversized,
            DropReason::Truncated => &mut st.truncated,
            DropReason::Malformed => &mut st.malformed,
            DropReason::NotFinite => &mut st.not_finite,
            DropReason::Incomplete => &mut st.incomplete,
            DropReason::OutOfRange => &mut st.out_of_range,
            DropReason::WrongType => &mut st.wrong_type,
            DropReason::Late => &mut st.ignored_idle,
            DropReason::QueueOverflow => &mut st.queue_overflow,
            DropReason::Superseded => &mut st.superseded,
        };
        *counter = counter.saturating_add(1);
        if let Some(t) = &self.tally {
            t.add(reason);
        }
    }

    /// Clears the counters.
    pub fn reset_stats(&mut self) {
        self.stats = EgmStats::default();
    }

    /// The next event, if any.
    pub fn poll_event(&mut self) -> Option<EgmEvent> {
        self.events.pop_front()
    }

    /// The reference in force: the last one returned by [`EgmSession::poll_reference`]. It
    /// stays in force while the sensor is quiet.
    pub fn current_reference(&self) -> Option<&SensorReference> {
        self.current.as_ref()
    }

    /// The reference for this cycle per the queue policy, or `None` when nothing new arrived
    /// (the caller keeps [`EgmSession::current_reference`]).
    pub fn poll_reference(&mut self) -> Option<SensorReference> {
        let next = self.queue.pop_front();
        if next.is_some() {
            self.current = next;
        }
        next
    }

    /// When the session next needs attention: the next transmit or the comm time-out.
    pub fn poll_timeout(&self) -> Option<RobotTime> {
        if !self.is_running() {
            return None;
        }
        let comm = self
            .config
            .comm_timeout
            .filter(|_| !self.timed_out)
            .map(|t| self.comm_timer_start.saturating_add(t));
        Some(match comm {
            Some(c) => c.min(self.next_transmit),
            None => self.next_transmit,
        })
    }

    /// Processes timers: raises 41822 once when no valid sensor data came within the comm
    /// time-out.
    pub fn handle_timeout(&mut self, now: RobotTime) {
        if !self.is_running() || self.timed_out {
            return;
        }
        let Some(timeout) = self.config.comm_timeout else {
            return;
        };
        if now >= self.comm_timer_start.saturating_add(timeout) {
            self.timed_out = true;
            let detail = format!(
                "no valid sensor message from {} within \\CommTimeout {}",
                self.config.remote,
                fmt_duration(timeout)
            );
            self.push_event(EgmEvent::new(EventKind::CommTimeout, detail));
        }
    }

    /// Builds the `EgmRobot` due at `now`, or `None` when none is due (or the session is not
    /// running, or the feedback is not finite).
    pub fn poll_transmit(&mut self, now: RobotTime, feedback: &RobotFeedback) -> Option<Vec<u8>> {
        let mut buf = Vec::with_capacity(512);
        self.poll_transmit_into(now, feedback, &mut buf)
            .then_some(buf)
    }

    /// As [`EgmSession::poll_transmit`], writing into `buf` (cleared first) so a caller can
    /// reuse one buffer; returns whether a datagram was produced.
    pub fn poll_transmit_into(
        &mut self,
        now: RobotTime,
        feedback: &RobotFeedback,
        buf: &mut Vec<u8>,
    ) -> bool {
        buf.clear();
        if !self.is_running() {
            return false;
        }
        self.handle_timeout(now);
        // A cycle may be served a little early (clock jitter), but never a whole motion
        // tick early when the sample period spans several ticks.
        let early = (self.config.sample_period / 2).min(MAX_EARLY);
        if now.saturating_add(early) < self.next_transmit {
            return false;
        }
        self.advance_schedule(now);
        if let Some(field) = feedback_non_finite(feedback) {
            self.stats.unsendable += 1;
            self.report(
                EventKind::FeedbackNotFinite,
                now,
                format!("`{field}` is not finite; this cycle's EgmRobot was not sent"),
            );
            return false;
        }
        let tm = header_tm(now);
        fill_robot(
            &mut self.scratch,
            self.seqno,
            tm,
            feedback,
            &self.config.encode,
        );
        if self.scratch.encode(buf).is_err() || buf.len() > MAX_DATAGRAM_LEN {
            // Unreachable with the bounded domain types (tested); never send a datagram the
            // clients would truncate.
            let len = buf.len();
            buf.clear();
            self.stats.unsendable += 1;
            self.report(
                EventKind::Oversized,
                now,
                format!("EgmRobot of {len} bytes exceeds {MAX_DATAGRAM_LEN}; not sent"),
            );
            return false;
        }
        self.seqno = self.seqno.wrapping_add(1);
        self.last_transmit = Some(now);
        self.fallback_pose = feedback.planned_pose;
        self.stats.sent += 1;
        true
    }

    fn advance_schedule(&mut self, now: RobotTime) {
        let period = self.config.sample_period;
        let half = period / 2;
        self.next_transmit = self.next_transmit.saturating_add(period);
        if self.next_transmit.saturating_add(half) <= now {
            // Called more than a cycle late: count the skipped cycles and re-phase.
            let behind = now.saturating_since(self.next_transmit);
            let skipped = behind.as_nanos() / period.as_nanos().max(1) + 1;
            self.stats.late_cycles += u64::try_from(skipped).unwrap_or(u64::MAX);
            self.next_transmit = now.saturating_add(period);
        }
    }

    /// Handles one datagram from `src` that arrived at `now`. Never panics; every drop is
    /// counted and reported (rate-limited) as an event.
    pub fn handle_datagram(&mut self, now: RobotTime, src: SocketAddr, bytes: &[u8]) -> Outcome {
        self.stats.received += 1;
        if !self.is_running() {
            self.count_drop(DropReason::Late);
            return Outcome::Ignored;
        }
        if let Some(expected) = self.unexpected_sender(src) {
            self.count_drop(DropReason::WrongSource);
            if !self.wrong_source_reported {
                self.wrong_source_reported = true;
                let detail = format!(
                    "datagram from {src} dropped: {expected}; further ones are counted only"
                );
                self.push_event(EgmEvent::new(EventKind::UnexpectedSender, detail));
            }
            return Outcome::Dropped(DropReason::WrongSource);
        }
        if bytes.len() > self.config.max_datagram_len {
            self.count_drop(DropReason::Oversized);
            let detail = format!(
                "{} bytes from {src}; the limit is {}",
                bytes.len(),
                self.config.max_datagram_len
            );
            self.report(EventKind::Oversized, now, detail);
            return Outcome::Dropped(DropReason::Oversized);
        }
        let previous = match self.latest.as_ref().map(|r| &r.target) {
            Some(Target::Pose(p)) => p.pose,
            _ => self.fallback_pose,
        };
        let mode = self.config.mode;
        match decode_reference(bytes, mode, &previous, &self.config.limits, now) {
            Ok(reference) => {
                self.accept(now, reference);
                Outcome::Accepted
            }
            Err(DecodeError::Malformed { expected, source }) => {
                let (reason, what) = if is_truncated(bytes) {
                    (DropReason::Truncated, "cut short")
                } else {
                    (DropReason::Malformed, "not")
                };
                self.count_drop(reason);
                let detail = format!(
                    "{} bytes from {src}: {what} an {expected}: {source}",
                    bytes.len()
                );
                self.report(EventKind::Malformed, now, detail);
                Outcome::Dropped(reason)
            }
            Err(DecodeError::Rejected(err)) => {
                let (reason, kind) = classify(&err);
                self.count_drop(reason);
                self.report(kind, now, format!("from {src}: {err}"));
                Outcome::Dropped(reason)
            }
        }
    }

    /// Why `src` may not send to this session, if it may not.
    fn unexpected_sender(&self, src: SocketAddr) -> Option<String> {
        let remote = self.config.remote;
        let ours = canonical(src.ip()) == canonical(remote.ip()) && src.port() == remote.port();
        match self.config.source_filter {
            SourceFilter::Any => None,
            SourceFilter::Remote if ours => None,
            SourceFilter::Remote => Some(format!(
                "only the device's remote address {remote} may send to this session"
            )),
        }
    }

    fn accept(&mut self, now: RobotTime, reference: SensorReference) {
        self.stats.accepted += 1;
        if let Some(sent) = self.last_transmit {
            self.stats.turnaround.record(now.saturating_since(sent));
        }
        self.comm_timer_start = now;
        self.latest = Some(reference);
        match self.config.queue {
            QueuePolicy::Newest => {
                if self.queue.pop_front().is_some() {
                    self.count_drop(DropReason::Superseded);
                }
                self.queue.push_back(reference);
            }
            QueuePolicy::OnePerCycle { capacity } => {
                self.queue.push_back(reference);
                if self.queue.len() > capacity {
                    self.queue.pop_front();
                    self.count_drop(DropReason::QueueOverflow);
                    let detail = format!(
                        "more than {capacity} messages waiting; the oldest was dropped (the sensor sends faster than the EGM cycle)"
                    );
                    self.report(EventKind::QueueOverflow, now, detail);
                }
            }
        }
    }

    /// Emits an event of a throttled kind: the first at once, then at most one per
    /// `event_repeat` carrying the number of suppressed ones.
    fn report(&mut self, kind: EventKind, now: RobotTime, detail: String) {
        let Some(index) = THROTTLED.iter().position(|k| *k == kind) else {
            self.push_event(EgmEvent::new(kind, detail));
            return;
        };
        let repeat = self.config.event_repeat;
        let Some(slot) = self.throttle.get_mut(index) else {
            return;
        };
        let due = slot
            .last
            .is_none_or(|last| now.saturating_since(last) >= repeat);
        if !due {
            slot.suppressed += 1;
            return;
        }
        let suppressed = std::mem::take(&mut slot.suppressed);
        slot.last = Some(now);
        let detail = if suppressed > 0 {
            format!("{detail} ({suppressed} more since the last report)")
        } else {
            detail
        };
        self.push_event(EgmEvent::new(kind, detail));
    }

    fn push_event(&mut self, event: EgmEvent) {
        if self.events.len() >= EVENT_QUEUE {
            self.stats.events_dropped += 1;
        } else {
            self.events.push_back(event);
        }
    }
}

fn canonical(ip: IpAddr) -> IpAddr {
    ip.to_canonical()
}

fn classify(err: &ReferenceError) -> (DropReason, EventKind) {
    match err {
        ReferenceError::NotFinite { .. } => (DropReason::NotFinite, EventKind::InvalidReference),
        ReferenceError::OutOfRange { .. } => (DropReason::OutOfRange, EventKind::OutOfBounds),
        ReferenceError::WrongMessageType { .. } => {
            (DropReason::WrongType, EventKind::WrongMessageType)
        }
        ReferenceError::TooFewValues { .. }
        | ReferenceError::MissingTarget { .. }
        | ReferenceError::MissingRequired { .. }
        | ReferenceError::ZeroQuaternion => (DropReason::Incomplete, EventKind::InvalidReference),
    }
}

#[cfg(test)]
mod tests;
