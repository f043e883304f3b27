//! Where a run's or stream's references come from: [`EgmSource`] (opened from a setup's [`SourceSpec`]) and the per-tick message path inside the driver (UDP socket, in-process built-in sensor, or I/O signals).

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::time::{Duration, Instant};

use crate::egm::EgmError;
use crate::egm::event::{EgmEvent, EventKind};
use crate::egm::geometry::SignalSource;
use crate::egm::path_correction::SeamProfile;
use crate::egm::registry::SourceSpec;
use crate::egm::sensor::{BuiltinSensor, SensorConfig, SensorPattern};
use crate::egm::session::{EgmSession, Outcome};
use crate::signals::SignalKind;
use crate::time::RobotTime;
use crate::wire::udp::{DEFAULT_DRAIN_LIMIT, UdpTransport};

use super::EventQueue;

/// The address the in-process sensor's replies come "from" (the session accepts any sender
/// for a built-in device).
pub(super) const BUILTIN_ADDR: SocketAddr = SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), 0);

/// An opened data source, ready for [`crate::egm::EgmDriver::start`] or
/// [`crate::egm::EgmStream::start`].
#[derive(Debug)]
pub enum EgmSource {
    /// A UdpUc device: the socket is bound.
    Udp {
        /// The device name.
        device: String,
        /// The socket.
        transport: UdpTransport,
    },
    /// The built-in sensor, run in process: every `EgmRobot` is encoded, handed to the
    /// sensor as bytes and its encoded reply fed back to the session — the same bytes as
    /// over UDP, without a socket.
    Builtin {
        /// The device name.
        device: String,
        /// The sensor's pattern.
        pattern: SensorPattern,
    },
    /// EGMSetupAI/AO/GI signals, read every sample.
    Signals {
        /// `Ai`, `Ao` or `Gi`.
        kind: SignalKind,
        /// The signals.
        source: SignalSource,
    },
    /// A simulated LTAPP seam sensor (path correction only).
    Seam {
        /// The device name.
        device: String,
        /// `JointType` of EGMSetupLTAPP.
        joint_type: f64,
        /// The seam it reports.
        seam: SeamProfile,
    },
}

impl EgmSource {
    /// Opens `spec`: binds a UdpUc device's socket (Local Port Number, or any free port) as
    /// [`UdpTransport::for_device`] does.
    ///
    /// Error: [`EgmError::DeviceOpen`] (`ERR_UDPUC_COMM`) when the socket cannot be bound.
    pub fn open(spec: &SourceSpec) -> Result<EgmSource, EgmError> {
        match spec {
            SourceSpec::Udp {
                device,
                remote,
                local_port,
            } => {
                let transport = UdpTransport::for_device(*local_port, *remote).map_err(|e| {
                    EgmError::DeviceOpen {
                        device: device.clone(),
                        local_port: *local_port,
                        reason: e.to_string(),
                    }
                })?;
                Ok(EgmSource::Udp {
                    device: device.clone(),
                    transport,
                })
            }
            SourceSpec::Builtin { device, pattern } => Ok(EgmSource::Builtin {
                device: device.clone(),
                pattern: *pattern,
            }),
            SourceSpec::Signals { kind, source } => Ok(EgmSource::Signals {
                kind: *kind,
                source: *source,
            }),
            SourceSpec::Ltapp {
                device,
                joint_type,
                seam,
            } => Ok(EgmSource::Seam {
                device: device.clone(),
                joint_type: *joint_type,
                seam: *seam,
            }),
        }
    }

    /// The device name (`None` for signals).
    pub fn device(&self) -> Option<&str> {
        match self {
            EgmSource::Udp { device, .. }
            | EgmSource::Builtin { device, .. }
            | EgmSource::Seam { device, .. } => Some(device),
            EgmSource::Signals { .. } => None,
        }
    }

    /// True for an external UdpUc sensor (lockstep waits for it).
    pub fn is_external(&self) -> bool {
        matches!(self, EgmSource::Udp { .. })
    }
}

/// The other end of a session.
#[derive(Debug)]
pub(super) enum Peer {
    /// A real socket.
    Udp(UdpTransport),
    /// The built-in sensor in process (`None` in a stream, which needs no replies).
    Builtin(Option<Box<BuiltinSensor>>),
}

impl Peer {
    /// The peer for a UdpUc or built-in source; `pose_origin` fixes the built-in sensor's
    /// pose origin (see [`BuiltinSensor::set_pose_origin`]).
    pub(super) fn builtin(
        device: &str,
        pattern: SensorPattern,
        pose_origin: Option<crate::egm::Pose>,
    ) -> Result<Peer, EgmError> {
        let mut sensor =
            BuiltinSensor::new(SensorConfig::new(pattern)).map_err(|e| EgmError::Sensor {
                device: device.to_string(),
                reason: e.to_string(),
            })?;
        sensor.set_pose_origin(pose_origin);
        Ok(Peer::Builtin(Some(Box::new(sensor))))
    }

    /// Hands every waiting datagram to the session; returns whether one was accepted.
    pub(super) fn receive(
        &mut self,
        now: RobotTime,
        session: &mut EgmSession,
        events: &mut EventQueue,
    ) -> bool {
        let Peer::Udp(transport) = self else {
            return false;
        };
        let mut accepted = false;
        let result = transport.drain(DEFAULT_DRAIN_LIMIT, |src, bytes| {
            accepted |= session.handle_datagram(now, src, bytes) == Outcome::Accepted;
        });
        if let Err(e) = result {
            events.push(EgmEvent::new(
                EventKind::SendError,
                format!("receiving from the UdpUc device failed: {e}"),
            ));
        }
        accepted
    }

    /// Sends one datagram; the built-in sensor answers at once into the session. Returns an
    /// event when sending failed or the sensor could not answer.
    pub(super) fn send(
        &mut self,
        now: RobotTime,
        datagram: &[u8],
        session: &mut EgmSession,
    ) -> Option<EgmEvent> {
        match self {
            Peer::Udp(transport) => transport.send(datagram).err().map(|e| {
                EgmEvent::new(
                    EventKind::SendError,
                    format!("sending to {} failed: {e}", transport.remote()),
                )
            }),
            Peer::Builtin(None) => None,
            Peer::Builtin(Some(sensor)) => {
                match sensor.handle_datagram(now.since_start(), datagram) {
                    Ok(reply) => {
                        session.handle_datagram(now, BUILTIN_ADDR, &reply);
                        None
                    }
                    Err(e) => Some(EgmEvent::new(EventKind::BuiltinSensor, e.to_string())),
                }
            }
        }
    }

    /// Lockstep: blocks up to `timeout` (real time) for one valid datagram and hands it to
    /// the session at `now`; returns whether one was accepted. Only a UDP peer waits.
    pub(super) fn wait_reply(
        &mut self,
        now: RobotTime,
        timeout: Duration,
        session: &mut EgmSession,
        events: &mut EventQueue,
    ) -> bool {
        let Peer::Udp(transport) = self else {
            return false;
        };
        let start = Instant::now();
        let deadline = start.checked_add(timeout).unwrap_or(start);
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return false;
            }
            match transport.recv_timeout(left) {
                Ok(Some((src, bytes))) => {
                    if session.handle_datagram(now, src, bytes) == Outcome::Accepted {
                        return true;
                    }
                }
                Ok(None) => return false,
                Err(e) => {
                    events.push(EgmEvent::new(
                        EventKind::SendError,
                        format!("receiving from the UdpUc device failed: {e}"),
                    ));
                    return false;
                }
            }
        }
    }

    /// The socket, for lockstep waits.
    pub(super) fn transport(&mut self) -> Option<&mut UdpTransport> {
        match self {
            Peer::Udp(t) => Some(t),
            Peer::Builtin(_) => None,
        }
    }
}
