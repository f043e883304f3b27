//! The sensor side of one path-corrected sequence (EGMMoveL/EGMMoveC): `EgmRobot` at the EGMActMove rate and the corrections that come back — from a UdpUc or built-in device (`EgmSensorPathCorr`), signals (`\<p>R2y`, `\<p>R3z`), or a simulated LTAPP seam — for the motion core's [`crate::egm::path_correction::PathCorrector`].
//!
//! The motion core owns the geometry (path frame, arc length, smoothing, APTR/LATR
//! scheduling, all in `egm::path_correction`); this link only moves messages. Per motion tick:
//!
//! ```text
//! t = link.tick(now, &CorrectionInput { commanded, tool, wobj, tcp_s, look_ahead });
//! if let Some(c) = t.correction { corrector.measurement(now_s, c.pos, c.age_s()) }
//! if let Some(err) = t.failed { stop the movement: ERR_UDPUC_COMM (41822) }
//! ```

use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;

use crate::egm::EgmError;
use crate::egm::event::EgmEvent;
use crate::egm::geometry::SignalSource;
use crate::egm::message_log::{LogKind, LogRing, LogRow};
use crate::egm::path_correction::{SeamProfile, Tracker};
use crate::egm::registry::{MovePlan, TrackerKind};
use crate::egm::session::{EgmSession, EgmStats, Outcome, SourceFilter};
use crate::egm::types::{EgmMode, Joints, MciState, MotorState, RapidExecState, Target};
use crate::robot::{Robot, ToolData, WobjData};
use crate::signals::SignalTable;
use crate::time::RobotTime;

use super::delay::DelayLine;
use super::feedback::tcp_feedback;
use super::source::{BUILTIN_ADDR, Peer};
use super::{
    DatagramMachine, DriverContext, EgmSource, EventQueue, check_options, forward_events,
    open_session,
};

/// One correction from the sensor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Correction {
    /// When it arrived (controller time).
    pub received_at: RobotTime,
    /// x, y, z in the path frame, mm (only y and z correct the path; x is passed on for the
    /// corrector's checks).
    pub pos: [f64; 3],
    /// How long before arrival it was measured.
    pub age: Duration,
}

impl Correction {
    /// The age in seconds (what [`crate::egm::path_correction::PathCorrector::measurement`]
    /// takes).
    pub fn age_s(&self) -> f64 {
        self.age.as_secs_f64()
    }
}

/// What the link needs from the motion core each tick.
#[derive(Clone, Copy, Debug)]
pub struct CorrectionInput<'a> {
    /// The joints commanded this tick.
    pub commanded: Joints,
    /// The tool of the EGMMoveL/EGMMoveC (for the Cartesian feedback).
    pub tool: &'a ToolData,
    /// Its work object (the feedback is relative to it).
    pub wobj: &'a WobjData,
    /// The TCP's arc length along the programmed path since the sequence started, mm (a
    /// simulated seam is sensed there).
    pub tcp_s: f64,
    /// The sensor frame's distance ahead of the TCP along the path, mm (a simulated
    /// look-ahead seam sensor is sensed there; ignored for APTR).
    pub look_ahead: f64,
}

/// The result of one tick.
#[derive(Clone, Debug, PartialEq)]
pub struct CorrectionTick {
    /// A new correction arrived.
    pub correction: Option<Correction>,
    /// An `EgmRobot` went out (or the signals or seam were sampled).
    pub sent: bool,
    /// Events waiting in [`CorrectionLink::poll_event`].
    pub events: usize,
    /// Set once, on the tick the comm time-out expired (`ERR_UDPUC_COMM`); the link then
    /// stops sending.
    pub failed: Option<EgmError>,
}

#[derive(Debug)]
enum Feed {
    Session {
        session: Box<EgmSession>,
        peer: Peer,
        buf: Vec<u8>,
        device: String,
    },
    Signals {
        source: SignalSource,
        next: RobotTime,
    },
    Seam {
        seam: SeamProfile,
        tracker: TrackerKind,
        next: RobotTime,
    },
}

/// The message side of one corrected sequence (see the module docs).
#[derive(Debug)]
pub struct CorrectionLink {
    name: String,
    feed: Feed,
    robot: Robot,
    signals: Arc<SignalTable>,
    delay: DelayLine,
    tick_period: Duration,
    sample_period: Duration,
    servo_delay: Duration,
    comm_timeout: Duration,
    failed: bool,
    samples: u32,
    awaiting: bool,
    events: EventQueue,
    log: LogRing,
    pending: Option<LogRow>,
}

impl CorrectionLink {
    /// Starts the exchange of `plan` at `now` with the robot at `current`.
    ///
    /// Errors: bad options ([`EgmError::BadSetup`]); a built-in pattern that is not a path
    /// correction ([`EgmError::BadDevice`]).
    pub fn start(
        now: RobotTime,
        ctx: &DriverContext,
        plan: &MovePlan,
        source: EgmSource,
        current: &Joints,
    ) -> Result<CorrectionLink, EgmError> {
        let instruction = "EGMMoveL";
        check_options(instruction, &ctx.options)?;
        let session = |remote, filter| {
            let mut s = open_session(
                ctx,
                instruction,
                EgmMode::PathCorr,
                (remote, filter),
                plan.sample_period,
                Some(plan.comm_timeout),
            )?;
            s.start(now);
            Ok::<_, EgmError>(Box::new(s))
        };
        let feed = match source {
            EgmSource::Udp { device, remote } => Feed::Session {
                session: session(remote, ctx.options.source_filter)?,
                peer: Peer::external(remote),
                buf: Vec::with_capacity(512),
                device,
            },
            EgmSource::Builtin { device, pattern } => {
                if pattern.mode() != EgmMode::PathCorr {
                    return Err(EgmError::BadDevice {
                        instruction,
                        device,
                        detail: format!(
                            "the built-in sensor talks {} mode, path correction needs a `pathcorr` pattern",
                            pattern.mode()
                        ),
                    });
                }
                Feed::Session {
                    session: session(BUILTIN_ADDR, SourceFilter::Any)?,
                    peer: Peer::builtin(&device, pattern, None)?,
                    buf: Vec::with_capacity(512),
                    device,
                }
            }
            EgmSource::Signals { source, .. } => Feed::Signals { source, next: now },
            EgmSource::Seam { seam, .. } => Feed::Seam {
                seam,
                tracker: plan.tracker,
                next: now,
            },
        };
        Ok(CorrectionLink {
            name: plan.name.clone(),
            feed,
            robot: ctx.robot.clone(),
            signals: Arc::clone(&ctx.signals),
            delay: DelayLine::new(ctx.options.servo_delay, ctx.options.tick, *current),
            tick_period: ctx.options.tick,
            sample_period: plan.sample_period,
            servo_delay: ctx.options.servo_delay,
            comm_timeout: plan.comm_timeout,
            failed: false,
            samples: 0,
            awaiting: false,
            events: EventQueue::with_capacity(),
            log: LogRing::new(&plan.name, ctx.options.log_capacity),
            pending: None,
        })
    }

    /// The identity's variable name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The session's counters (UdpUc and built-in devices).
    pub fn session_stats(&self) -> Option<&EgmStats> {
        match &self.feed {
            Feed::Session { session, .. } => Some(session.stats()),
            _ => None,
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

    /// One motion tick at `now`.
    pub fn tick(&mut self, now: RobotTime, input: &CorrectionInput<'_>) -> CorrectionTick {
        let measured = self.delay.push(input.commanded);
        if self.failed {
            return CorrectionTick {
                correction: None,
                sent: false,
                events: self.events.len(),
                failed: None,
            };
        }
        let due = |next: &mut RobotTime, period: Duration, half: Duration| {
            if now.saturating_add(half) < *next {
                return false;
            }
            *next = next.saturating_add(period);
            if *next <= now {
                *next = now.saturating_add(period);
            }
            true
        };
        let half = self.tick_period / 2;
        let mut failed = None;
        let (correction, sent) = match &mut self.feed {
            Feed::Session {
                session,
                peer,
                buf,
                device,
            } => {
                session.handle_timeout(now);
                let correction = session.poll_reference().and_then(|r| match r.target {
                    Target::PathCorr(pc) => Some(Correction {
                        received_at: r.received_at,
                        pos: pc.pos,
                        age: Duration::from_millis(u64::from(pc.age_ms)),
                    }),
                    _ => None,
                });
                if session.comm_timed_out() {
                    self.failed = true;
                    session.stop();
                    failed = Some(EgmError::CommTimeout {
                        device: device.clone(),
                        timeout: self.comm_timeout,
                    });
                }
                forward_events(session, &mut self.events);
                if let (Some(c), Some(row)) = (&correction, &mut self.pending) {
                    row.recv_time = Some(c.received_at);
                    row.reference = Some(reference_of(c));
                }
                let feedback = tcp_feedback(
                    (&self.robot, input.tool, input.wobj),
                    now,
                    (&measured, &input.commanded),
                    self.servo_delay,
                    (MotorState::On, RapidExecState::Running, MciState::Running),
                );
                let sent = !self.failed && session.poll_transmit_into(now, &feedback, buf);
                if sent {
                    if let Some(e) = peer.send(now, buf, session) {
                        self.events.push(e);
                    }
                    self.awaiting = peer.is_external();
                    if let Some(done) = self.pending.take() {
                        self.log.push(done);
                    }
                    self.pending = Some(LogRow {
                        kind: LogKind::PathCorr,
                        send_time: now,
                        recv_time: None,
                        seqno: session.next_seqno().wrapping_sub(1),
                        reference: None,
                        feedback: measured,
                        state: "correcting",
                        utilization: 0.0,
                    });
                }
                forward_events(session, &mut self.events);
                (correction, sent)
            }
            Feed::Signals { source, next } => {
                if !due(next, self.sample_period, half) {
                    (None, false)
                } else {
                    match source.joint_reference(&self.signals, &[0.0; 6]) {
                        Ok(v) => {
                            let [_, y, z, ..] = v;
                            (Some(now_correction(now, [0.0, y, z])), true)
                        }
                        Err(e) => {
                            self.events.push(EgmError::Signal(e).event());
                            (None, true)
                        }
                    }
                }
            }
            Feed::Seam {
                seam,
                tracker,
                next,
            } => {
                if !due(next, self.sample_period, half) {
                    (None, false)
                } else {
                    let tracker = match tracker {
                        TrackerKind::Aptr => Tracker::Aptr,
                        TrackerKind::Latr => Tracker::Latr {
                            look_ahead: input.look_ahead,
                        },
                    };
                    let off = seam.sensed_at(tracker, input.tcp_s);
                    (Some(now_correction(now, [0.0, off.y, off.z])), true)
                }
            }
        };
        if sent && !matches!(self.feed, Feed::Session { .. }) {
            let n = self.samples;
            self.samples = self.samples.wrapping_add(1);
            self.log.push(LogRow {
                kind: LogKind::PathCorr,
                send_time: now,
                recv_time: correction.map(|c| c.received_at),
                seqno: n,
                reference: correction.as_ref().map(reference_of),
                feedback: measured,
                state: "correcting",
                utilization: 0.0,
            });
        }
        if failed.is_some()
            && let Some(done) = self.pending.take()
        {
            self.log.push(done);
        }
        CorrectionTick {
            correction,
            sent,
            events: self.events.len(),
            failed,
        }
    }

    /// Ends the sequence (the fine point was reached): flushes the log.
    pub fn finish(&mut self) {
        if let Feed::Session { session, .. } = &mut self.feed {
            session.stop();
        }
        if let Some(done) = self.pending.take() {
            self.log.push(done);
        }
        self.awaiting = false;
    }
}

impl DatagramMachine for CorrectionLink {
    fn handle_datagram(&mut self, now: RobotTime, from: SocketAddr, bytes: &[u8]) -> bool {
        let Feed::Session { session, .. } = &mut self.feed else {
            return false;
        };
        let accepted = session.handle_datagram(now, from, bytes) == Outcome::Accepted;
        if accepted {
            self.awaiting = false;
        }
        accepted
    }

    fn poll_transmit(&mut self, _now: RobotTime) -> Option<(SocketAddr, &[u8])> {
        match &mut self.feed {
            Feed::Session { peer, buf, .. } => peer.take_transmit(buf),
            _ => None,
        }
    }

    fn poll_timeout(&self) -> Option<RobotTime> {
        if self.failed {
            return None;
        }
        match &self.feed {
            Feed::Session { session, .. } => session.poll_timeout(),
            Feed::Signals { next, .. } | Feed::Seam { next, .. } => Some(*next),
        }
    }

    fn awaiting_reply(&self) -> bool {
        self.awaiting && !self.failed
    }

    fn reply_wait_over(&mut self) {
        self.awaiting = false;
    }

    fn transport_error(&mut self, event: EgmEvent) {
        self.events.push(event);
    }
}

fn now_correction(now: RobotTime, pos: [f64; 3]) -> Correction {
    Correction {
        received_at: now,
        pos,
        age: Duration::ZERO,
    }
}

/// The log's reference columns of a correction: x, y, z mm, age ms.
fn reference_of(c: &Correction) -> [f64; 6] {
    let [x, y, z] = c.pos;
    [x, y, z, c.age.as_millis() as f64, 0.0, 0.0]
}
