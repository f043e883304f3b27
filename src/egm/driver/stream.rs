//! A position stream (EGMStreamStart, `\StreamStart`): `EgmRobot` at the sample rate during ordinary RAPID motion, MCI_STOPPED, no replies needed and no comm time-out.

use std::net::SocketAddr;
use std::time::Duration;

use crate::egm::EgmError;
use crate::egm::event::EgmEvent;
use crate::egm::message_log::{LogKind, LogRing, LogRow};
use crate::egm::registry::StreamPlan;
use crate::egm::sensor::SensorPattern;
use crate::egm::session::{EgmSession, Outcome, SourceFilter};
use crate::egm::types::{Joints, MciState, MotorState, RapidExecState};
use crate::robot::{Robot, ToolData, WobjData};
use crate::time::RobotTime;

use super::delay::DelayLine;
use super::feedback::tcp_feedback;
use super::source::{BUILTIN_ADDR, Peer};
use super::{
    DatagramMachine, DriverContext, EgmSource, EventQueue, check_options, forward_events,
    open_session,
};

/// The result of one stream tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StreamTick {
    /// An `EgmRobot` went out this tick.
    pub sent: bool,
    /// Events waiting in [`EgmStream::poll_event`].
    pub events: usize,
}

/// One position stream. Call [`EgmStream::tick`] every motion tick with the joints the
/// motion core commands; the measured position is those joints delayed by the servo delay.
#[derive(Debug)]
pub struct EgmStream {
    name: String,
    device: String,
    robot: Robot,
    tool: ToolData,
    wobj: WobjData,
    session: EgmSession,
    peer: Peer,
    pattern: Option<SensorPattern>,
    buf: Vec<u8>,
    delay: DelayLine,
    servo_delay: Duration,
    events: EventQueue,
    log: LogRing,
    /// The motors' state to report (on until [`EgmStream::set_motors`]).
    motors: MotorState,
}

impl EgmStream {
    /// Starts streaming `plan` at `now` from `current` over `source` (a UdpUc or built-in
    /// device; a built-in device just discards the messages, which still appear in the
    /// log).
    pub fn start(
        now: RobotTime,
        ctx: &DriverContext,
        plan: &StreamPlan,
        source: EgmSource,
        current: &Joints,
    ) -> Result<EgmStream, EgmError> {
        let instruction = "EGMStreamStart";
        check_options(instruction, &ctx.options)?;
        let mut pattern = None;
        let (device, peer, remote, filter) = match source {
            EgmSource::Udp { device, remote } => (
                device,
                Peer::external(remote),
                remote,
                ctx.options.source_filter,
            ),
            EgmSource::Builtin { device, pattern: p } => {
                pattern = Some(p);
                (device, Peer::Builtin(None), BUILTIN_ADDR, SourceFilter::Any)
            }
            EgmSource::Signals { .. } | EgmSource::Seam { .. } => {
                return Err(EgmError::BadSetup {
                    instruction,
                    detail: "a position stream needs a UdpUc setup (EGMSetupUC)".to_string(),
                });
            }
        };
        let mut session = open_session(
            ctx,
            instruction,
            plan.mode,
            (remote, filter),
            plan.sample_period,
            None,
        )?;
        session.start(now);
        let delay = DelayLine::new(ctx.options.servo_delay, ctx.options.tick, *current);
        Ok(EgmStream {
            name: plan.name.clone(),
            device,
            robot: ctx.robot.clone(),
            tool: plan.tool,
            wobj: plan.wobj.clone(),
            session,
            peer,
            pattern,
            buf: Vec::with_capacity(512),
            delay,
            servo_delay: ctx.options.servo_delay,
            events: EventQueue::with_capacity(),
            log: LogRing::new(&plan.name, ctx.options.log_capacity),
            motors: MotorState::On,
        })
    }

    /// The controller's motors were switched on or off: the stream reports it from the next
    /// message on.
    pub fn set_motors(&mut self, on: bool) {
        self.motors = if on { MotorState::On } else { MotorState::Off };
    }

    /// The identity's variable name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The device name.
    pub fn device(&self) -> &str {
        &self.device
    }

    /// One tick at `now` with the joints commanded this tick; `exec` is the program state
    /// to report.
    pub fn tick(&mut self, now: RobotTime, commanded: &Joints, exec: RapidExecState) -> StreamTick {
        // Replies are not needed; the loop hands them in so the socket never fills up, and
        // they are discarded here.
        while self.session.poll_reference().is_some() {}
        let measured = self.delay.push(*commanded);
        let feedback = tcp_feedback(
            (&self.robot, &self.tool, &self.wobj),
            now,
            (&measured, commanded),
            self.servo_delay,
            (self.motors, exec, MciState::Stopped),
        );
        let sent = self
            .session
            .poll_transmit_into(now, &feedback, &mut self.buf);
        if sent {
            if let Some(e) = self.peer.send(now, &self.buf, &mut self.session) {
                self.events.push(e);
            }
            self.log.push(LogRow {
                kind: LogKind::Stream,
                send_time: now,
                recv_time: None,
                seqno: self.session.next_seqno().wrapping_sub(1),
                reference: None,
                feedback: measured,
                state: "streaming",
                utilization: 0.0,
            });
        }
        forward_events(&mut self.session, &mut self.events);
        StreamTick {
            sent,
            events: self.events.len(),
        }
    }

    /// The next event.
    pub fn poll_event(&mut self) -> Option<EgmEvent> {
        self.events.pop()
    }

    /// The oldest log row.
    pub fn pop_log(&mut self) -> Option<LogRow> {
        self.log.pop()
    }

    /// The log ring.
    pub fn log_mut(&mut self) -> &mut LogRing {
        &mut self.log
    }

    /// `EgmRobot`s sent so far.
    pub fn sent(&self) -> u64 {
        self.session.stats().sent
    }

    /// Ends the stream and gives the device back, e.g. to an EGMRun that takes over the same
    /// identity (the controller keeps its socket bound).
    pub fn into_source(mut self) -> EgmSource {
        self.session.stop();
        match self.peer {
            Peer::External { remote, .. } => EgmSource::Udp {
                device: self.device,
                remote,
            },
            Peer::Builtin(_) => EgmSource::Builtin {
                device: self.device,
                pattern: self
                    .pattern
                    .unwrap_or(SensorPattern::Hold(crate::egm::EgmMode::Joint)),
            },
        }
    }
}

impl DatagramMachine for EgmStream {
    fn handle_datagram(&mut self, now: RobotTime, from: SocketAddr, bytes: &[u8]) -> bool {
        self.session.handle_datagram(now, from, bytes) == Outcome::Accepted
    }

    fn poll_transmit(&mut self, _now: RobotTime) -> Option<(SocketAddr, &[u8])> {
        self.peer.take_transmit(&self.buf)
    }

    fn poll_timeout(&self) -> Option<RobotTime> {
        self.session.poll_timeout()
    }

    /// A stream needs no replies.
    fn awaiting_reply(&self) -> bool {
        false
    }

    fn reply_wait_over(&mut self) {}

    fn transport_error(&mut self, event: EgmEvent) {
        self.events.push(event);
    }
}
