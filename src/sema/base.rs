//! The names of base RobotWare's instructions and functions (`sema/base.txt`), so that a call
//! reaching no routine is told apart: ABB's name rapidvc lacks ("not supported by rapidvc")
//! or the program's own routine that is missing ("not declared").

use std::collections::HashSet;
use std::sync::OnceLock;

/// The table's text.
const TABLE: &str = include_str!("base.txt");

/// The table's names, in order.
fn names() -> impl Iterator<Item = &'static str> {
    TABLE
        .lines()
        .map(str::trim)
        .filter(|l| !l.starts_with('#'))
        .flat_map(str::split_whitespace)
}

/// True when `name` (case-insensitive) is an instruction or function of base RobotWare.
pub fn is_base_routine(name: &str) -> bool {
    static SET: OnceLock<HashSet<String>> = OnceLock::new();
    SET.get_or_init(|| names().map(str::to_ascii_lowercase).collect())
        .contains(&name.to_ascii_lowercase())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_identifiers_outside_the_option_catalogue() {
        let mut seen = HashSet::new();
        for n in names() {
            assert!(seen.insert(n.to_ascii_lowercase()), "{n} twice");
            let mut c = n.chars();
            assert!(c.next().is_some_and(|c| c.is_ascii_alphabetic()), "{n}");
            assert!(c.all(|c| c.is_ascii_alphanumeric() || c == '_'), "{n}");
            assert!(
                super::super::options::lookup(n).is_none(),
                "{n} belongs to an option"
            );
        }
        assert!(seen.len() > 300);
        assert!(is_base_routine("waittestandset"));
        assert!(!is_base_routine("FooBarBaz"));
        assert!(!is_base_routine("ArcL"));
    }
}
