//! `--answers FILE` of `rapidvc run` and `rapidvc test`: where the operator dialogs get their
//! answers (the file, else — for a run — the terminal when standard input is one, else
//! nobody). The file
//! format is described in `crate::interp::operator` and `docs/rapid.md`.

use std::io::IsTerminal;
use std::path::Path;

use crate::interp::operator::{AnswersFile, Operator};

/// Read the answers file, when one is given.
pub fn read(path: Option<&Path>) -> Result<Option<AnswersFile>, String> {
    path.map(AnswersFile::read).transpose()
}

/// The operator of a run, or of test `test` (its section of the file). Only a run asks the
/// terminal: tests stay deterministic, answered by the file or by nobody.
pub fn operator(file: Option<&AnswersFile>, test: Option<&str>) -> Operator {
    match (file, test) {
        (Some(f), Some(name)) => f.for_test(name),
        (Some(f), None) => f.for_run(),
        (None, None) if std::io::stdin().is_terminal() => Operator::terminal(),
        (None, _) => Operator::nobody(),
    }
}

/// A warning when answers were left over (the program asked fewer dialogs than the file
/// answers).
pub fn unused_warning(op: &Operator) -> Option<String> {
    op.unused().map(|(path, line, n)| {
        format!(
            "{path}:{line}: {n} answer{} not used (the program asked fewer dialogs)",
            if n == 1 { " was" } else { "s were" }
        )
    })
}
