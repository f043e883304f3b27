//! The `rapidvc` binary: parse arguments, run, map the outcome to an exit code.
use clap::Parser;

/// mimalloc: see Cargo.toml.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> std::process::ExitCode {
    rapidvc::cli::run(rapidvc::cli::Cli::parse())
}
