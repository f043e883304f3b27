//! rapidvc — an open, headless virtual ABB robot controller.
//!
//! It parses and runs RAPID programs against a kinematic virtual 6-axis robot and implements
//! ABB's Externally Guided Motion (EGM) over the real wire protocol (protobuf over UDP).
//!
//! Phases and layers (see `docs/architecture.md`, "Modules" and "Layers"): `source` →
//! `parse` (pest, AST with spans) → `sema` (names, types) → `ir` → `program` (the one way
//! from source to a checked program) → `interp` (the interpreter) → `controller` (program
//! execution, the cycle, clocks) over `motion` (sans-IO motion core), `egm` (the EGM protocol
//! machines) and `wire` (sockets); `signals`, `config` and `output` (traces, plots, the view)
//! beside them, `system` (the controller's operating-system side RAPID reaches through the
//! interpreter's host: calendar, system information, configuration data) below `interp`,
//! `robot` (kinematics, pure math) and `functions` (RAPID's predefined functions)
//! underneath. Only `cli` prints, reads the environment or exits.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod ast;
#[cfg(feature = "cli")]
pub mod cli;
pub mod config;
pub mod controller;
pub mod diag;
pub mod egm;
pub mod egm_args;
pub mod events;
pub mod functions;
pub mod interp;
pub mod ir;
pub mod mass_storage;
pub mod motion;
pub mod output;
pub mod parse;
pub mod program;
pub mod robot;
pub mod sema;
pub mod services;
pub mod signals;
pub mod source;
pub mod system;
pub mod time;
pub mod wire;
