//! `rapidvc check PATH…`.

use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `rapidvc check`.
#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    /// Files or directories (searched recursively for .mod, .modx, .sys, .prg).
    #[arg(required = true)]
    pub paths: Vec<PathBuf>,
}

/// Run the check.
pub fn run(_args: CheckArgs) -> ExitCode {
    eprintln!("rapidvc check: the RAPID front end is being built (issue 2)");
    ExitCode::from(2)
}
