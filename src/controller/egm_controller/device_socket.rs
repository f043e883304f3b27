//! The sockets of the EGM devices, owned by the controller's cycle: before a machine's tick
//! every waiting datagram goes into it, after the tick what it produced goes out, and in
//! lockstep the cycle waits here for the sensor's reply. The machines (`egm::driver`) own no
//! socket; this is the only place EGM datagrams meet `wire::udp`.

use std::time::Duration;

use crate::egm::registry::SourceSpec;
use crate::egm::{DatagramMachine, EgmError, EgmEvent, EventKind};
use crate::time::RobotTime;
use crate::wire::udp::{DEFAULT_DRAIN_LIMIT, UdpTransport};

/// The socket of one EGM device: bound for a UdpUc device, none for the built-in sensor,
/// signals and simulated seams (nothing to carry).
#[derive(Debug, Default)]
pub struct DeviceSocket(Option<UdpTransport>);

impl DeviceSocket {
    /// Binds a UdpUc device's socket (Local Port Number, or any free port) as
    /// [`UdpTransport::for_device`] does; no socket for other sources.
    ///
    /// Error: [`EgmError::DeviceOpen`] (`ERR_UDPUC_COMM`) when the socket cannot be bound.
    pub fn open(spec: &SourceSpec) -> Result<DeviceSocket, EgmError> {
        match spec {
            SourceSpec::Udp {
                device,
                remote,
                local_port,
            } => UdpTransport::for_device(*local_port, *remote)
                .map(|t| DeviceSocket(Some(t)))
                .map_err(|e| EgmError::DeviceOpen {
                    device: device.clone(),
                    local_port: *local_port,
                    reason: e.to_string(),
                }),
            SourceSpec::Builtin { .. } | SourceSpec::Signals { .. } | SourceSpec::Ltapp { .. } => {
                Ok(DeviceSocket(None))
            }
        }
    }

    /// Before the machine's tick at `now`: every waiting datagram (at most
    /// [`DEFAULT_DRAIN_LIMIT`], so a flood cannot stall the cycle) into `machine`.
    pub fn receive(&mut self, now: RobotTime, machine: &mut impl DatagramMachine) {
        let Some(transport) = &mut self.0 else {
            return;
        };
        let result = transport.drain(DEFAULT_DRAIN_LIMIT, |src, bytes| {
            machine.handle_datagram(now, src, bytes);
        });
        if let Err(e) = result {
            machine.transport_error(receive_failed(&e));
        }
    }

    /// After the machine's tick at `now`: the datagram it produced, if any, goes out.
    pub fn send(&mut self, now: RobotTime, machine: &mut impl DatagramMachine) {
        let Some(transport) = &self.0 else {
            return;
        };
        let failed = match machine.poll_transmit(now) {
            Some((to, bytes)) => transport.send_to(bytes, to).err().map(|e| (to, e)),
            None => None,
        };
        if let Some((to, e)) = failed {
            machine.transport_error(EgmEvent::new(
                EventKind::SendError,
                format!("sending to {to} failed: {e}"),
            ));
        }
    }

    /// Lockstep, the controller loop's policy: when `machine` awaits the reply to the message
    /// it sent at `now`, block up to `timeout` (real time) for one valid datagram and hand
    /// it in at `now`. Datagrams from other senders or that are invalid are dropped as usual
    /// and do not end the wait. Either way the machine stops waiting for this message.
    /// `None` when nothing was awaited, else whether the reply came.
    pub fn wait_reply(
        &mut self,
        now: RobotTime,
        timeout: Duration,
        machine: &mut impl DatagramMachine,
    ) -> Option<bool> {
        if !machine.awaiting_reply() {
            return None;
        }
        machine.reply_wait_over();
        let transport = self.0.as_mut()?;
        match transport.wait_for(timeout, |src, bytes| {
            machine.handle_datagram(now, src, bytes)
        }) {
            Ok(came) => Some(came),
            Err(e) => {
                machine.transport_error(receive_failed(&e));
                Some(false)
            }
        }
    }
}

fn receive_failed(e: &std::io::Error) -> EgmEvent {
    EgmEvent::new(
        EventKind::SendError,
        format!("receiving from the UdpUc device failed: {e}"),
    )
}
