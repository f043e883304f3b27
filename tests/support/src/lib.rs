//! What rapidvc's integration tests share, as one crate (a dev-dependency of rapidvc), so no
//! test file copies a helper or includes one by `#[path]`:
//!
//! - [`procs`]: `rapidvc` and sensor scripts as child processes, every wait bounded;
//! - [`csv`], [`summary`], [`view_page`]: reading what a run wrote (traces, logs, the summary
//!   line, the view page's data);
//! - [`egm_loop`], [`egm_wire`]: an EGM controller loop over loopback and the sensor's messages;
//! - [`egm_pair`]: a controller-side EGM machine and a sensor joined in memory, in virtual time;
//! - [`robot`]: robot fixtures (tools of the manual's examples) and joint assertions;
//! - [`src_files`]: the crate's own sources, for the tests that read the code (layers, catalogue);
//! - [`gen_program`]: large valid RAPID programs for the parser's tests and benchmarks;
//! - [`fixed_iters`]: the benchmarks' fixed-iteration mode, for counting instructions;
//! - [`rws_http`], [`serve`]: the RWS tests' HTTP client and a real `rapidvc serve`;
//! - [`sandbox`]: a HOME with links pointing out of it, for the mass-storage attacks.
//!
//! The path of the `rapidvc` binary is known only to the test crates (`CARGO_BIN_EXE_rapidvc`
//! at their compile time): [`rapidvc!`] expands there.

pub mod csv;
pub mod egm_loop;
pub mod egm_pair;
pub mod egm_wire;
pub mod fixed_iters;
pub mod gen_program;
pub mod procs;
pub mod robot;
pub mod rws_http;
pub mod sandbox;
pub mod serve;
pub mod src_files;
pub mod summary;
pub mod view_page;

/// `std::process::Command` for the `rapidvc` binary of the package under test (expands in
/// the test crate, where Cargo defines `CARGO_BIN_EXE_rapidvc`).
#[macro_export]
macro_rules! rapidvc {
    () => {
        ::std::process::Command::new(env!("CARGO_BIN_EXE_rapidvc"))
    };
}
