//! The pest grammar bindings: [`RapidParser`] builds the syntax tree; [`diag::DiagParser`]
//! re-parses broken regions to name the expected tokens. This is the only pest importer
//! besides the builders, which walk the pairs it produces.

pub(crate) mod diag;

/// The fast parser: punctuation is silent (no pairs), recovery rules are included.
#[derive(pest_derive::Parser)]
#[grammar = "grammar/lexical.pest"]
#[grammar = "grammar/marks_fast.pest"]
#[grammar = "grammar/tokens.pest"]
#[grammar = "grammar/expr.pest"]
#[grammar = "grammar/stmt.pest"]
#[grammar = "grammar/stmt_fast.pest"]
#[grammar = "grammar/routine.pest"]
#[grammar = "grammar/module.pest"]
#[grammar = "grammar/recover.pest"]
pub(crate) struct RapidParser;

/// A pair of the fast parser.
pub(crate) type Pair<'i> = pest::iterators::Pair<'i, Rule>;

#[cfg(test)]
mod tests {
    use pest::Parser;

    use super::{RapidParser, Rule};
    use crate::parse::recover::RESERVED;

    /// `text` is a whole identifier for the `ident` rule.
    fn is_ident(text: &str) -> bool {
        RapidParser::parse(Rule::ident, text)
            .ok()
            .and_then(|mut p| p.next())
            .is_some_and(|p| p.as_str() == text)
    }

    fn is_reserved(word: &str) -> bool {
        RESERVED.iter().any(|r| r.eq_ignore_ascii_case(word))
    }

    #[test]
    fn reserved_words_are_never_names() {
        for w in RESERVED {
            let mixed: String = w
                .chars()
                .enumerate()
                .map(|(i, c)| {
                    if i % 2 == 1 {
                        c.to_ascii_lowercase()
                    } else {
                        c
                    }
                })
                .collect();
            for v in [w.to_string(), w.to_ascii_lowercase(), mixed] {
                assert!(!is_ident(&v), "{v} is reserved");
                assert!(
                    RapidParser::parse(Rule::ident, &format!("{v} x")).is_err(),
                    "{v} is reserved"
                );
            }
        }
    }

    #[test]
    fn words_near_reserved_words_are_names() {
        for w in RESERVED {
            let mut near = vec![
                format!("{w}X"),
                format!("{w}1"),
                format!("{w}_"),
                format!("X{w}"),
            ];
            for n in 1..w.len() {
                near.push(w[..n].to_string());
                near.push(format!("{}Q{}", &w[..n], &w[n..]));
                let mut changed = w.as_bytes().to_vec();
                changed[n] = if changed[n] == b'Z' { b'Y' } else { b'Z' };
                near.push(String::from_utf8(changed).unwrap_or_default());
            }
            for v in near.iter().filter(|v| !is_reserved(v)) {
                assert!(is_ident(v), "{v} is a name");
                assert!(is_ident(&v.to_ascii_lowercase()), "{v} is a name");
            }
        }
        for name in [
            "p10", "v500", "t1_2", "MoveL", "x", "Q", "tool0", "a_b", "ENDIFS",
        ] {
            assert!(is_ident(name), "{name} is a name");
        }
        for not_name in ["1a", "_a", "", " a"] {
            assert!(!is_ident(not_name), "{not_name:?} is not a name");
        }
    }
}
