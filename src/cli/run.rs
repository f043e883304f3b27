//! `rapidvc run FILE…`: load and check the program, run the entry routine on a virtual
//! controller. TP output goes to stdout (one line per `TPWrite`); diagnostics and events to
//! stderr. Exit codes: 0 when the program ends (also by EXIT or Stop), 1 on an unhandled
//! run-time error, 2 when the program cannot be loaded or checked.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use super::{program, render};
use crate::interp::{Interp, Outcome, Output, VirtualHost, pers};

/// Arguments of `rapidvc run`.
#[derive(Debug, clap::Args)]
pub struct RunArgs {
    /// RAPID files or directories (all modules of one task).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// The procedure to start.
    #[arg(long, default_value = "main")]
    pub entry: String,
    /// Configuration directory (EIO.cfg …); default: the directory of the first file.
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Persistents file: loaded at start when it exists, written at the end.
    #[arg(long)]
    pub pers: Option<PathBuf>,
    /// Fail a wait that would go beyond this virtual time (seconds).
    #[arg(long, default_value_t = 86_400.0)]
    pub max_time: f64,
    /// Abort after this many executed statements.
    #[arg(long)]
    pub max_steps: Option<u64>,
    /// Run the entry routine this many times; `ExitCycle` ends a cycle early.
    #[arg(long, default_value_t = 1)]
    pub cycles: u32,
}

/// Run the program.
pub fn run(args: RunArgs) -> ExitCode {
    let loaded = program::load(&args.files, args.config.as_deref());
    render::diagnostics(&loaded.diags, &loaded.sources);
    let Some(prog) = loaded.program.clone() else {
        return ExitCode::from(2);
    };
    let host = VirtualHost::new()
        .with_signals(loaded.signals.clone())
        .with_max_time(args.max_time)
        .with_sink(print_output);
    let mut it = Interp::new(prog, &loaded.registry, Box::new(host));
    it.set_budget(args.max_steps);
    // The main thread has 8 MiB of stack; leave 2 MiB of headroom.
    it.set_stack_budget(6 << 20);
    if let Err(e) = it.init() {
        render::runtime_error(&e, &loaded.sources);
        return ExitCode::from(1);
    }
    let mut kept = Vec::new();
    if let Some(path) = &args.pers
        && path.exists()
    {
        let text = match std::fs::read_to_string(path) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("error: cannot read {}: {e}", path.display());
                return ExitCode::from(2);
            }
        };
        let entries = match pers::parse(&text) {
            Ok(e) => e,
            Err(e) => {
                eprintln!("error: {}: {e}", path.display());
                return ExitCode::from(2);
            }
        };
        let (unknown, warnings) = it.load_persistents(&entries);
        for w in warnings {
            eprintln!("warning: {}: {w}", path.display());
        }
        kept = unknown;
    }
    let mut code = ExitCode::SUCCESS;
    for _ in 0..args.cycles.max(1) {
        match it.run(&args.entry) {
            Ok(Outcome::Completed | Outcome::ExitCycle) => {}
            Ok(Outcome::Exited) => {
                eprintln!("program ended by EXIT");
                break;
            }
            Ok(Outcome::Stopped) => {
                eprintln!("program stopped (Stop)");
                break;
            }
            Err(e) => {
                let _ = std::io::stdout().flush();
                render::runtime_error(&e, &loaded.sources);
                code = ExitCode::from(1);
                break;
            }
        }
    }
    if let Some(path) = &args.pers {
        let text = pers::write(&it.persistents(), &kept);
        if let Err(e) = std::fs::write(path, text) {
            eprintln!("error: cannot write {}: {e}", path.display());
            return ExitCode::from(2);
        }
    }
    code
}

/// Where program output goes: TP lines to stdout, the event log to stderr.
fn print_output(o: &Output) {
    match o {
        Output::TpWrite(s) => {
            let mut out = std::io::stdout().lock();
            let _ = writeln!(out, "{s}");
        }
        Output::TpErase => {}
        Output::ErrWrite {
            warning,
            header,
            reason,
        } => {
            let kind = if *warning { "warning" } else { "error" };
            eprintln!("event log ({kind}): {header}: {}", reason.join(" "));
        }
        Output::Event(e) => eprintln!("event: {e}"),
    }
}
