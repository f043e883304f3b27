//! `rapidvc dump-ast FILE` (hidden): print the syntax tree dump used by the golden tests.

use std::path::PathBuf;
use std::process::ExitCode;

use crate::diag::Diagnostics;
use crate::parse;
use crate::program::rapid_files;
use crate::source::SourceMap;

/// Arguments of `rapidvc dump-ast`.
#[derive(Debug, clap::Args)]
pub struct DumpAstArgs {
    /// The RAPID file.
    pub file: PathBuf,
}

/// Print the dump on stdout and the diagnostics on stderr; exit 1 when there are errors.
pub fn run(args: DumpAstArgs) -> ExitCode {
    let mut map = SourceMap::new();
    let id = match rapid_files::load_file(&mut map, &args.file) {
        Ok(id) => id,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let mut diags = Diagnostics::new();
    let file = parse::parse_file(id, &map.get(id).text, &mut diags);
    parse::check_structure(&file, &mut diags);
    print!("{}", file.dump());
    eprint!("{}", diags.render_plain(&map, 100));
    if diags.has_errors() {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}
