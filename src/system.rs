//! The controller's operating-system side that RAPID reaches through the interpreter's host:
//! sockets (`sockets.rs`), and the other services a controller offers its programs. Plain Rust
//! types only (no interpreter values), so every host can own one [`Services`] and the natives
//! in `interp/builtins/` translate between RAPID values and these types.

pub mod sockets;

/// The services of one controller, as its RAPID task reaches them (`Host::system`).
#[derive(Debug, Default)]
pub struct Services {
    /// The task's sockets (`SocketCreate` … `SocketClose`).
    pub sockets: sockets::Sockets,
}
