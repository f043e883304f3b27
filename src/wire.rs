//! The wire: the transports that move datagrams between rapidvc and its peers, beneath the
//! protocol machines (`egm`). A transport makes no protocol decision: it binds, sends and
//! drains bytes, and hands each datagram with its source address to the caller.
//!
//! * [`udp`]: one non-blocking UDP socket per EGM UdpUc device.
//!
//! Nothing here may panic on input from the network: the lint wall below forbids `unwrap`,
//! `expect` and panicking indexing outside tests.
#![deny(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

pub mod udp;
