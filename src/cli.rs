//! Command-line interface: clap definitions (one file per subcommand under `cli/`), choice of
//! diagnostic renderer, exit codes. The only module that prints, reads arguments or exits.

use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod answers;
pub mod bench;
mod check;
mod dump_ast;
mod files;
mod interrupt;
pub mod num;
mod progress_line;
mod render;
pub mod robots;
pub mod run;
pub mod sensor;
pub mod serve;
mod test;

/// rapidvc — an open, headless virtual ABB robot controller (RAPID + EGM).
#[derive(Debug, Parser)]
#[command(name = "rapidvc", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Check RAPID files or directories for syntax and semantic errors.
    Check(check::CheckArgs),
    /// Run a RAPID program on the virtual controller (TP output on stdout).
    Run(Box<run::RunArgs>),
    /// Boot a controller that stays up: run the program in real time, started, stopped and
    /// inspected over Robot Web Services 1.0 (plain HTTP, as on an IRC5), until Ctrl-C.
    Serve(Box<serve::ServeArgs>),
    /// Run every `PROC test_*` of RAPID test modules (`Assert cond \Msg:="…"`).
    Test(test::TestArgs),
    /// Print the syntax tree of one file (for debugging the parser).
    #[command(hide = true)]
    DumpAst(dump_ast::DumpAstArgs),
    /// List the robot models with reach, axis ranges and speeds.
    Robots(robots::RobotsArgs),
    /// Measure the motion core: virtual-time speed, or real-time cycle jitter under load.
    Bench(bench::BenchArgs),
    /// Run the built-in EGM sensor over UDP: reply to a controller with a target pattern and
    /// print what arrives plus latency statistics.
    Sensor(Box<sensor::SensorArgs>),
}

/// Run the parsed command line and return the process exit code.
pub fn run(cli: Cli) -> ExitCode {
    match cli.command {
        Command::Check(args) => check::run(args),
        Command::DumpAst(args) => dump_ast::run(args),
        Command::Run(args) => run::run(*args),
        Command::Serve(args) => serve::run(*args),
        Command::Robots(args) => robots::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Sensor(args) => sensor::run(*args),
        Command::Test(args) => test::run(args),
    }
}
