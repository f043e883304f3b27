//! EGM event-log entries ([`EgmEvent`], [`EventKind`]): part of the shared EGM vocabulary in
//! [`crate::egm_args::event`], so the interpreter can report an argument error with the same
//! number and text as the controller; re-exported here for the EGM machines.

pub use crate::egm_args::event::*;
