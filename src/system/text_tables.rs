//! The controller's installed text tables: `TextTabGet` finds a table by name, `TextGet` reads
//! one text of it, `TextTabFreeToUse` tells whether a name is still free.
//!
//! A text table is written in the format of ABB's text files for `TextTabInstall`: `#` starts
//! a comment line, the first other line names the table (`name::`), then each text is an
//! index line (`1:`) followed by the text on the next line. rapidvc installs one table of its
//! own, `rapidvc_weekday` (`stdlib/texts/rapidvc_weekday.eng`: the names of the weekdays,
//! indexed 1 = Monday to 7 = Sunday as `GetTime(\WDay)` counts them). Tables are numbered from
//! 1 in the order they are installed.

use std::collections::BTreeMap;

/// The text tables every rapidvc controller has installed.
pub const BUILTIN: &[&str] = &[include_str!("../../stdlib/texts/rapidvc_weekday.eng")];

/// One text table.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TextTable {
    /// Its name (`TextTabGet` compares it case-insensitively).
    pub name: String,
    texts: BTreeMap<u32, String>,
}

impl TextTable {
    /// Read a table in the text-file format (see the module doc); the message names the line
    /// that is wrong.
    pub fn parse(text: &str) -> Result<TextTable, String> {
        let mut lines = text.lines().enumerate();
        let mut name = None;
        let mut texts = BTreeMap::new();
        while let Some((i, line)) = lines.next() {
            let trimmed = line.trim();
            if trimmed.is_empty() || trimmed.starts_with('#') {
                continue;
            }
            let line_no = i + 1;
            if name.is_none() {
                let Some(n) = trimmed.strip_suffix("::").filter(|n| is_name(n)) else {
                    return Err(format!(
                        "line {line_no}: expected the table's name as `name::`, found `{trimmed}`"
                    ));
                };
                name = Some(n.to_string());
                continue;
            }
            let index = trimmed
                .strip_suffix(':')
                .and_then(|n| n.parse::<u32>().ok())
                .filter(|n| *n >= 1)
                .ok_or_else(|| {
                    format!(
                        "line {line_no}: expected an index line such as `1:`, found `{trimmed}`"
                    )
                })?;
            let Some((_, text)) = lines.next() else {
                return Err(format!("line {line_no}: index {index} has no text line"));
            };
            if texts.insert(index, text.to_string()).is_some() {
                return Err(format!("line {line_no}: index {index} appears twice"));
            }
        }
        match name {
            Some(name) => Ok(TextTable { name, texts }),
            None => Err("the file holds no table (`name::`)".into()),
        }
    }

    /// The text at `index`.
    pub fn get(&self, index: u32) -> Option<&str> {
        self.texts.get(&index).map(String::as_str)
    }

    /// How many texts the table holds.
    pub fn len(&self) -> usize {
        self.texts.len()
    }

    /// True when the table holds no text.
    pub fn is_empty(&self) -> bool {
        self.texts.is_empty()
    }
}

fn is_name(s: &str) -> bool {
    let mut chars = s.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// The installed text tables.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TextTables {
    tables: Vec<TextTable>,
}

impl Default for TextTables {
    /// rapidvc's built-in tables ([`BUILTIN`]).
    fn default() -> Self {
        let mut t = TextTables { tables: Vec::new() };
        for text in BUILTIN {
            if let Ok(table) = TextTable::parse(text) {
                t.install(table);
            }
        }
        t
    }
}

impl TextTables {
    /// Install a table; a table of the same name is replaced (keeping its number).
    pub fn install(&mut self, table: TextTable) -> u32 {
        match self.number(&table.name) {
            Some(n) => {
                if let Some(slot) = self.tables.get_mut(n as usize - 1) {
                    *slot = table;
                }
                n
            }
            None => {
                self.tables.push(table);
                self.tables.len() as u32
            }
        }
    }

    /// `TextTabGet`: the number of the table called `name` (case-insensitive), from 1.
    pub fn number(&self, name: &str) -> Option<u32> {
        self.tables
            .iter()
            .position(|t| t.name.eq_ignore_ascii_case(name))
            .map(|i| i as u32 + 1)
    }

    /// `TextGet`: text `index` of table `table`.
    pub fn text(&self, table: u32, index: u32) -> Option<&str> {
        self.tables
            .get((table as usize).checked_sub(1)?)
            .and_then(|t| t.get(index))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_builtin_table() {
        let t = TextTables::default();
        let n = t.number("RAPIDVC_WEEKDAY").expect("installed");
        assert_eq!(n, 1);
        assert_eq!(t.text(n, 1), Some("Monday"));
        assert_eq!(t.text(n, 7), Some("Sunday"));
        assert_eq!(t.text(n, 8), None);
        assert_eq!(t.text(0, 1), None);
        assert_eq!(t.text(2, 1), None);
        assert_eq!(t.number("nothing"), None);
    }

    #[test]
    fn format() {
        let t = TextTable::parse("# c\r\n\r\nparts::\r\n# one\r\n1:\r\nPart ready\r\n3:\r\n\r\n")
            .unwrap();
        assert_eq!(t.name, "parts");
        assert_eq!(t.get(1), Some("Part ready"));
        assert_eq!(t.get(3), Some(""));
        assert_eq!(t.len(), 2);
        for (bad, why) in [
            ("", "no table"),
            ("parts:\n1:\nx\n", "name::"),
            ("parts::\nx\n", "index line"),
            ("parts::\n0:\nx\n", "index line"),
            ("parts::\n1:\n", "no text"),
            ("parts::\n1:\na\n1:\nb\n", "twice"),
            ("9parts::\n", "name::"),
        ] {
            let e = TextTable::parse(bad).unwrap_err();
            assert!(e.contains(why), "{bad:?}: {e}");
        }
    }

    #[test]
    fn install_replaces_by_name() {
        let mut t = TextTables::default();
        let a = t.install(TextTable::parse("mine::\n1:\na\n").unwrap());
        let b = t.install(TextTable::parse("MINE::\n1:\nb\n").unwrap());
        assert_eq!((a, b), (2, 2));
        assert_eq!(t.text(2, 1), Some("b"));
    }
}
