//! Where a run's or stream's references come from: [`EgmSource`] (named by a setup's [`SourceSpec`]) and the other end of a session inside the machines (an external sensor whose datagrams the controller's loop carries, or the built-in sensor in process).

use std::net::{IpAddr, Ipv4Addr, SocketAddr};

use crate::egm::EgmError;
use crate::egm::event::{EgmEvent, EventKind};
use crate::egm::geometry::SignalSource;
use crate::egm::path_correction::SeamProfile;
use crate::egm::registry::SourceSpec;
use crate::egm::sensor::{BuiltinSensor, SensorConfig, SensorPattern};
use crate::egm::session::EgmSession;
use crate::signals::SignalKind;
use crate::time::RobotTime;

/// The address the in-process sensor's replies come "from" (the session accepts any sender
/// for a built-in device).
pub(super) const BUILTIN_ADDR: SocketAddr = SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), 0);

/// A data source, ready for [`crate::egm::EgmDriver::start`] or
/// [`crate::egm::EgmStream::start`].
#[derive(Debug)]
pub enum EgmSource {
    /// A UdpUc device. Its socket is the controller's (`wire::udp`); the machines only
    /// name the remote they talk to.
    Udp {
        /// The device name.
        device: String,
        /// The sensor's address.
        remote: SocketAddr,
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
    /// The source `spec` names (no socket: the controller binds the device's socket and
    /// carries its datagrams).
    pub fn new(spec: &SourceSpec) -> EgmSource {
        match spec {
            SourceSpec::Udp { device, remote, .. } => EgmSource::Udp {
                device: device.clone(),
                remote: *remote,
            },
            SourceSpec::Builtin { device, pattern } => EgmSource::Builtin {
                device: device.clone(),
                pattern: *pattern,
            },
            SourceSpec::Signals { kind, source } => EgmSource::Signals {
                kind: *kind,
                source: *source,
            },
            SourceSpec::Ltapp {
                device,
                joint_type,
                seam,
            } => EgmSource::Seam {
                device: device.clone(),
                joint_type: *joint_type,
                seam: *seam,
            },
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

/// The other end of a session, as the machine sees it: an external sensor at an address
/// (the controller's loop carries the datagrams: [`crate::egm::DatagramMachine`]), or the
/// built-in sensor answering in process.
#[derive(Debug)]
pub(super) enum Peer {
    /// An external sensor at `remote`; `ready` while a datagram waits for
    /// [`crate::egm::DatagramMachine::poll_transmit`].
    External { remote: SocketAddr, ready: bool },
    /// The built-in sensor in process (`None` in a stream, which needs no replies).
    Builtin(Option<Box<BuiltinSensor>>),
}

impl Peer {
    /// The peer for a built-in source; `pose_origin` fixes the built-in sensor's pose origin
    /// (see [`BuiltinSensor::set_pose_origin`]).
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

    /// The peer of an external sensor at `remote`.
    pub(super) fn external(remote: SocketAddr) -> Peer {
        Peer::External {
            remote,
            ready: false,
        }
    }

    /// One datagram is ready in the machine's buffer: an external peer holds it for the
    /// controller's loop; the built-in sensor answers at once into the session. Returns an
    /// event when the sensor could not answer.
    pub(super) fn send(
        &mut self,
        now: RobotTime,
        datagram: &[u8],
        session: &mut EgmSession,
    ) -> Option<EgmEvent> {
        match self {
            Peer::External { ready, .. } => {
                *ready = true;
                None
            }
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

    /// The datagram waiting for the loop, once: `(remote, bytes)` of `buf`.
    pub(super) fn take_transmit<'a>(&mut self, buf: &'a [u8]) -> Option<(SocketAddr, &'a [u8])> {
        match self {
            Peer::External { remote, ready } if *ready => {
                *ready = false;
                Some((*remote, buf))
            }
            _ => None,
        }
    }

    /// True for an external sensor (lockstep waits for its replies).
    pub(super) fn is_external(&self) -> bool {
        matches!(self, Peer::External { .. })
    }
}
