//! Services a running controller offers to other programs: Robot Web Services ([`rws`]), and
//! later others. Each runs on a tokio runtime of its own and talks to the controller only
//! through [`crate::controller::service`]: typed requests with replies, and a broadcast of
//! events. A service never holds controller internals, and a slow or hostile client can only
//! fill its own bounded queue.

pub mod rws;
