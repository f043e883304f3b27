//! The catalogue of ABB RobotWare options rapidvc does not have (`sema/options.txt`): which
//! option an instruction, function or data type belongs to, so that `rapidvc check` says
//! "`ArcL` needs the option 633-4 Arc, which rapidvc does not have" instead of "not
//! supported". A name is looked up only when the program declares nothing of that name.

use std::collections::HashMap;
use std::fmt;
use std::sync::OnceLock;

/// The catalogue's text.
const TABLE: &str = include_str!("options.txt");

/// One RobotWare option.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RobotOption {
    /// ABB's option number (`633-4`), when it is known.
    pub number: Option<&'static str>,
    /// The option's name (`Arc`).
    pub name: &'static str,
    /// Its instructions, functions and data types.
    pub names: Vec<&'static str>,
}

impl fmt::Display for RobotOption {
    /// `633-4 Arc`, or the name alone.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.number {
            Some(n) => write!(f, "{n} {}", self.name),
            None => f.write_str(self.name),
        }
    }
}

struct Catalogue {
    options: Vec<RobotOption>,
    /// Folded name → option index.
    by_name: HashMap<String, usize>,
}

/// Read the table; a malformed line is a bug in rapidvc's source, reported by the unit test.
fn parse(text: &'static str) -> Result<Vec<RobotOption>, String> {
    let mut options: Vec<RobotOption> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        if let Some(rest) = line.strip_prefix("option ") {
            let (number, name) = rest
                .split_once(' ')
                .ok_or_else(|| format!("line {}: `option NUMBER NAME`", i + 1))?;
            options.push(RobotOption {
                number: (number != "-").then_some(number),
                name: name.trim(),
                names: Vec::new(),
            });
            continue;
        }
        let option = options
            .last_mut()
            .ok_or_else(|| format!("line {}: names before the first option", i + 1))?;
        option.names.extend(line.split_whitespace());
    }
    Ok(options)
}

fn catalogue() -> &'static Catalogue {
    static CATALOGUE: OnceLock<Catalogue> = OnceLock::new();
    CATALOGUE.get_or_init(|| {
        let options = parse(TABLE).unwrap_or_default();
        let mut by_name = HashMap::new();
        for (i, o) in options.iter().enumerate() {
            for n in &o.names {
                by_name.entry(n.to_ascii_lowercase()).or_insert(i);
            }
        }
        Catalogue { options, by_name }
    })
}

/// Every option of the catalogue.
pub fn options() -> &'static [RobotOption] {
    &catalogue().options
}

/// The option `name` (an instruction, function or data type; case-insensitive) belongs to.
pub fn lookup(name: &str) -> Option<&'static RobotOption> {
    let c = catalogue();
    c.by_name
        .get(&name.to_ascii_lowercase())
        .and_then(|&i| c.options.get(i))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_reads_and_names_are_unique_identifiers() {
        let parsed = parse(TABLE).expect("the table parses");
        assert_eq!(parsed.len(), options().len());
        let mut seen = std::collections::HashSet::new();
        for o in &parsed {
            assert!(!o.names.is_empty(), "{o}");
            if let Some(n) = o.number {
                let (a, b) = n.split_once('-').expect("NNN-N");
                assert!(a.parse::<u32>().is_ok() && b.parse::<u32>().is_ok(), "{n}");
            }
            for n in &o.names {
                assert!(seen.insert(n.to_ascii_lowercase()), "{n} twice");
                let mut c = n.chars();
                assert!(c.next().is_some_and(|c| c.is_ascii_alphabetic()), "{n}");
                assert!(c.all(|c| c.is_ascii_alphanumeric() || c == '_'), "{n}");
                assert!(n.len() <= 32, "{n}");
            }
        }
    }

    #[test]
    fn lookups() {
        let arc = lookup("arcl").expect("ArcL");
        assert_eq!(arc.to_string(), "633-4 Arc");
        assert_eq!(lookup("WZBoxDef").map(|o| o.name), Some("World Zones"));
        assert_eq!(lookup("seamdata").map(|o| o.name), Some("Arc"));
        assert_eq!(
            lookup("FCAct").map(|o| o.to_string()).as_deref(),
            Some("Force Control")
        );
        assert!(lookup("MoveL").is_none());
        assert!(lookup("").is_none());
    }
}
