//! The CSV files `rapidvc run` writes (`--trace`, `--egm-log`): a header line and comma-separated fields, read by column name.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

/// A CSV file's header and rows of fields.
pub struct Csv {
    /// Column names.
    pub header: Vec<String>,
    /// Fields of every row after the header.
    pub rows: Vec<Vec<String>>,
}

impl Csv {
    /// Reads `path` (it must exist and have a header).
    pub fn read(path: &Path) -> Csv {
        let text = std::fs::read_to_string(path)
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
        let mut lines = text.lines();
        let header = lines
            .next()
            .expect("a header line")
            .split(',')
            .map(str::to_string)
            .collect();
        let rows = lines
            .map(|l| l.split(',').map(str::to_string).collect())
            .collect();
        Csv { header, rows }
    }

    /// The index of column `name`.
    pub fn col(&self, name: &str) -> usize {
        self.header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name} in {:?}", self.header))
    }
}
