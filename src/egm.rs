//! Externally Guided Motion (EGM): the ABB wire protocol (protobuf over UDP), sans-IO session, built-in sensor, servo law, and the controller-side machinery (identities, per-tick runs, streams, path-correction links, message log).
//!
//! Layers, each in its own file:
//! * [`proto`]: prost types generated from `proto/egm.proto` (ABB's names, V1.1 + RW7 fields).
//! * [`types`]: plain domain data (mm, degrees, quaternion `[w, x, y, z]`).
//! * [`convert`]: proto ↔ domain, with every validation rule of a receiving controller.
//! * [`session`]: the controller side as a sans-IO state machine (`handle_datagram`,
//!   `poll_transmit`, `poll_timeout`), in the style of quinn-proto.
//! * no socket: the controller's cycle owns the UDP transports (`wire::udp`, a thin
//!   `std::net::UdpSocket` shell that makes no protocol decisions), drains them into the
//!   machines and sends what they produce ([`DatagramMachine`]).
//! * [`sensor`]: the built-in sensor (patterns, path correction), sans-IO as well.
//! * [`servo`]: the EGM control law the motion core calls each tick.
//! * [`geometry`], [`path_correction`]: pure pose-mode geometry and path-correction math.
//! * [`registry`]: the EGM identities of a task and their state machine — what every EGM
//!   instruction checks and changes; it hands out plans with every default applied.
//! * [`driver`]: one EGMRunJoint/EGMRunPose per tick ([`EgmDriver`]), position streams
//!   ([`EgmStream`]) and the message side of path correction ([`CorrectionLink`]), sans-IO
//!   state machines talking to an external UdpUc sensor through the controller's loop, to
//!   the in-process built-in sensor, or reading I/O signals.
//! * [`message_log`]: the `--egm-log` rows and their CSV writer.
//! * [`event`], [`latency`]: event-log entries and latency statistics.
//!
//! Nothing here may panic on input from the network: the lint wall below forbids `unwrap`,
//! `expect` and panicking indexing outside tests.
#![deny(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

pub mod convert;
pub mod driver;
pub mod event;
pub mod geometry;
pub mod latency;
pub mod message_log;
pub mod path_correction;
mod presence;
pub mod proto;
pub mod registry;
pub mod sensor;
pub mod servo;
pub mod session;
#[cfg(test)]
pub(crate) mod test_support;
pub mod types;

pub use driver::{
    CorrectionLink, DatagramMachine, DriverContext, DriverOptions, EgmDriver, EgmEnd, EgmSource,
    EgmStream, EgmTick, StreamTick,
};
pub use event::{EgmEvent, EventKind};
pub use registry::{CorrState, EgmError, EgmId, EgmRegistry, EgmState, RegistryConfig};
pub use session::{EgmConfig, EgmSession, EgmStats, Outcome, QueuePolicy, SourceFilter};
pub use types::{
    EgmMode, ExternalAxes, JointReference, Joints, MciState, MotorState, PathCorrection, Pose,
    PoseReference, RapidData, RapidExecState, RobotFeedback, SensorHeader, SensorReference, Target,
};
