//! `rapidvc check PATH…`: parse and check RAPID files, print diagnostics (human or JSON),
//! exit 0 when clean (warnings allowed), 1 when errors were found, 2 on usage or I/O errors.

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use miette::{GraphicalReportHandler, GraphicalTheme};

use crate::ast;
use crate::diag::Diagnostics;
use crate::parse;
use crate::program::{self, rapid_files};
use crate::source::{SourceId, SourceMap};

/// Arguments of `rapidvc check`.
#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    /// Files or directories (searched recursively for .mod, .modx, .sys, .prg).
    #[arg(required = true)]
    pub paths: Vec<PathBuf>,
    /// Check syntax and structure only (no name resolution): for a single module taken out
    /// of a larger program.
    #[arg(long)]
    pub syntax: bool,
    /// Output format of the diagnostics.
    #[arg(long, value_enum, default_value_t = Format::Human)]
    pub format: Format,
}

/// How diagnostics are printed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// Source snippets with labels (on stderr), and a summary line.
    Human,
    /// One JSON array of diagnostics on stdout.
    Json,
}

/// How much the check covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Depth {
    /// Syntax and structure of each file on its own.
    Syntax,
    /// Everything rapidvc can check for the files as one program. Until the semantic pass
    /// exists, that is syntax and structure too.
    Full,
}

/// Run the check.
pub fn run(args: CheckArgs) -> ExitCode {
    if !args.syntax && is_system(&args.paths) {
        return check_system(&args);
    }
    let files = match rapid_files::find_rapid_files(&args.paths) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let depth = if args.syntax {
        Depth::Syntax
    } else {
        Depth::Full
    };
    let mut map = SourceMap::new();
    let mut diags = Diagnostics::new();
    let mut io_failed = false;
    let mut ids = Vec::with_capacity(files.len());
    for path in &files {
        match rapid_files::load_file(&mut map, path) {
            Ok(id) => ids.push(id),
            Err(e) => {
                eprintln!("error: {e}");
                io_failed = true;
            }
        }
    }
    let mut independent = None;
    let mut parsed: Vec<ast::File> = Vec::with_capacity(ids.len());
    for (file, file_diags) in parse_all(&map, &ids) {
        diags.extend(file_diags);
        parsed.push(file);
    }
    match depth {
        Depth::Syntax => {}
        // The semantic pass (names, types, signatures over all `parsed` files), once the
        // files parse: the configuration next to them gives the I/O signals.
        Depth::Full => {
            if !diags.has_errors() && !io_failed {
                let registry = crate::interp::Registry::standard();
                independent =
                    program::check_files(&parsed, &args.paths, &mut map, &registry, &mut diags);
            }
        }
    }
    diags.sort();
    if let (Some(note), Format::Human) = (&independent, args.format) {
        eprintln!("{note}");
    }
    report(&diags, &map, args.format, files.len());
    if io_failed {
        ExitCode::from(2)
    } else if diags.has_errors() {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

/// True when the paths are a controller backup folder or carry task prefixes
/// (`T_ROB1=main.mod`): each task is then checked as its own program.
fn is_system(paths: &[PathBuf]) -> bool {
    use program::system::{is_backup, split_task_prefix};
    matches!(paths, [one] if is_backup(one))
        || paths.iter().any(|p| split_task_prefix(p).0.is_some())
}

/// Check every task of a system (see `program::system`), with the checks across tasks.
fn check_system(args: &CheckArgs) -> ExitCode {
    let mut loaded = program::system::load_system(&args.paths, None);
    let files: usize = loaded.tasks.iter().map(|t| t.files.len()).sum();
    loaded.diags.sort();
    report(&loaded.diags, &loaded.sources, args.format, files);
    if loaded.io_failed {
        ExitCode::from(2)
    } else if loaded.diags.has_errors() {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

/// Parse and structure-check the files `ids` of `map`, each on its own, on as many threads as
/// the parser uses (a large file is also cut into pieces: see [`parse::ParseOptions`]). The
/// result is in the order of `ids`, so the output does not depend on the threads.
fn parse_all(map: &SourceMap, ids: &[SourceId]) -> Vec<(ast::File, Diagnostics)> {
    let one = |id: SourceId| {
        let mut d = Diagnostics::new();
        let file = parse::parse_file(id, &map.get(id).text, &mut d);
        parse::check_structure(&file, &mut d);
        (file, d)
    };
    let threads = parse::ParseOptions::default().threads;
    let (_, results) = parse::jobs::run(threads, ids.to_vec(), one, || ());
    // (A file no thread delivered is parsed here.)
    ids.iter()
        .zip(results)
        .map(|(&id, r)| r.unwrap_or_else(|| one(id)))
        .collect()
}

fn report(diags: &Diagnostics, map: &SourceMap, format: Format, files: usize) {
    match format {
        Format::Json => {
            let mut out = std::io::stdout().lock();
            let _ = writeln!(out, "{}", diags.to_json(map));
        }
        Format::Human => {
            let color = std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none();
            let theme = if color {
                GraphicalTheme::unicode()
            } else {
                GraphicalTheme::unicode_nocolor()
            };
            let width = terminal_width().unwrap_or(100);
            let handler = GraphicalReportHandler::new_themed(theme)
                .with_width(width)
                .with_links(false);
            let mut err = std::io::stderr().lock();
            let _ = write!(err, "{}", diags.render_with(&handler, map));
            let plural = |n: usize, w: &str| format!("{n} {w}{}", if n == 1 { "" } else { "s" });
            let _ = writeln!(
                err,
                "checked {}: {}, {}",
                plural(files, "file"),
                plural(diags.error_count(), "error"),
                plural(diags.warning_count(), "warning")
            );
        }
    }
}

fn terminal_width() -> Option<usize> {
    std::env::var("COLUMNS").ok().and_then(|c| c.parse().ok())
}
