//! The `rapidvc` binary: parse arguments, run, map the outcome to an exit code.
use clap::Parser;

fn main() -> std::process::ExitCode {
    rapidvc::cli::run(rapidvc::cli::Cli::parse())
}
