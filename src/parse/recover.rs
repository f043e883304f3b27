//! Explaining skipped regions: when the fast parser had to skip text (a `bad_*` rule), the
//! diagnostic parser re-parses it from its start with the strict rule that failed, and pest's
//! furthest failure becomes a [`ParseErrorKind::Syntax`] that names the expected tokens.

use pest::Parser;
use pest::error::{ErrorVariant, InputLocation};

use super::error::ParseErrorKind;
use super::grammar::diag::{DiagParser, Rule};
use super::names::{self, Expected};
use crate::source::{SourceId, Span};

/// What kind of construct a skipped region stood for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Region {
    /// Text before a MODULE.
    Top,
    /// A module head after `MODULE`.
    ModuleHead,
    /// A module-level item.
    Item,
    /// A routine head.
    RoutineHead,
    /// A record component.
    Field,
    /// A statement (or a declaration among statements).
    Statement,
}

/// Explain the region `start..end` of `text`.
pub(crate) fn diagnose(
    file: SourceId,
    text: &str,
    start: usize,
    end: usize,
    region: Region,
) -> ParseErrorKind {
    let first = first_word(text, start);
    let is_decl = ["VAR", "PERS", "CONST", "LOCAL", "TASK"]
        .iter()
        .any(|k| first.eq_ignore_ascii_case(k));
    match region {
        Region::Top => expected_at(
            file,
            text,
            start,
            region,
            vec![Expected::Keyword("`MODULE`")],
        ),
        Region::ModuleHead => strict(file, text, start, Rule::diag_module_head, region),
        Region::RoutineHead => match parse_len(text, start, Rule::diag_routine_head) {
            Err(f) if f.expected.is_empty() && text.as_bytes().get(f.pos) == Some(&b'(') => {
                ParseErrorKind::Syntax {
                    span: Span::new(file, f.pos, f.pos + 1),
                    expected: "the end of the TRAP head".into(),
                    found: "`(`".into(),
                    label: "a TRAP has no parameter list".into(),
                    help: Some(
                        "a trap routine is `TRAP name … ENDTRAP`; it takes no parameters".into(),
                    ),
                }
            }
            Err(f) => syntax(file, text, start, region, f),
            Ok(_) => strict(file, text, start, Rule::diag_routine_head, region),
        },
        Region::Field => strict(file, text, start, Rule::record_field, region),
        Region::Statement if is_decl => match parse_len(text, start, Rule::data_decl) {
            Ok(len) => ParseErrorKind::MisplacedDeclaration {
                span: Span::new(file, start, start + len),
                what: "data declaration inside a compound statement",
                help: "declare routine data at the start of the routine, before its statements",
            },
            Err(e) => syntax(file, text, start, region, e),
        },
        Region::Statement => strict(file, text, start, Rule::statement, region),
        Region::Item => {
            if is_decl {
                return strict(file, text, start, Rule::data_decl, region);
            }
            if first.eq_ignore_ascii_case("RECORD") {
                return strict(file, text, start, Rule::record_decl, region);
            }
            if first.eq_ignore_ascii_case("ALIAS") {
                return strict(file, text, start, Rule::alias_decl, region);
            }
            match parse_len(text, start, Rule::statement) {
                Ok(len) => ParseErrorKind::StatementOutsideRoutine {
                    span: Span::new(file, start, (start + len).min(end.max(start + len))),
                },
                Err(_) => expected_at(
                    file,
                    text,
                    start,
                    region,
                    vec![
                        Expected::Thing("a data declaration"),
                        Expected::Thing("a type definition"),
                        Expected::Thing("a routine (PROC, FUNC or TRAP)"),
                        Expected::Closer("`ENDMODULE`"),
                    ],
                ),
            }
        }
    }
}

/// A failed strict parse: pest's furthest position and the rules it tried there.
struct Failure {
    pos: usize,
    expected: Vec<Expected>,
    message: Option<String>,
}

/// Parse `rule` at `start`; the length it matched, or where and why it failed.
fn parse_len(text: &str, start: usize, rule: Rule) -> Result<usize, Failure> {
    let input = text.get(start..).unwrap_or("");
    match DiagParser::parse(rule, input) {
        Ok(pairs) => Ok(pairs.last().map(|p| p.as_span().end()).unwrap_or(0)),
        Err(e) => {
            let pos = match e.location {
                InputLocation::Pos(p) => p,
                InputLocation::Span((p, _)) => p,
            };
            let (expected, message) = match &e.variant {
                ErrorVariant::ParsingError { positives, .. } => (
                    positives
                        .iter()
                        .filter_map(|r| names::expected(*r))
                        .collect(),
                    None,
                ),
                ErrorVariant::CustomError { message } => (Vec::new(), Some(message.clone())),
            };
            Err(Failure {
                pos: start + pos,
                expected,
                message,
            })
        }
    }
}

fn strict(file: SourceId, text: &str, start: usize, rule: Rule, region: Region) -> ParseErrorKind {
    match parse_len(text, start, rule) {
        Err(f) => syntax(file, text, start, region, f),
        // The strict rule accepts what the fast parser skipped: only possible for constructs
        // that are valid alone but not in this place.
        Ok(len) => ParseErrorKind::Syntax {
            span: Span::new(file, start, start + len),
            expected: "something else here".into(),
            found: describe(text, start).0,
            label: "not allowed here".into(),
            help: None,
        },
    }
}

fn syntax(file: SourceId, text: &str, _start: usize, region: Region, f: Failure) -> ParseErrorKind {
    if let Some(message) = f.message {
        return ParseErrorKind::Limit {
            span: Span::new(file, f.pos, f.pos),
            reason: message,
        };
    }
    expected_at(file, text, f.pos, region, f.expected)
}

/// The error for "expected one of `items` at `pos`".
fn expected_at(
    file: SourceId,
    text: &str,
    pos: usize,
    region: Region,
    mut items: Vec<Expected>,
) -> ParseErrorKind {
    if text.as_bytes().get(pos) == Some(&b'"') && unterminated_string(text, pos) {
        let end = text[pos..]
            .find(['\n', '\r'])
            .map_or(text.len(), |n| pos + n);
        return ParseErrorKind::UnterminatedString {
            span: Span::new(file, pos, end),
        };
    }
    items.sort();
    items.dedup();
    // Where an operand may start, list "an expression" rather than its many first tokens.
    if items.contains(&Expected::Thing("a name")) && items.contains(&Expected::Thing("a number")) {
        items.retain(|e| {
            !matches!(
                e,
                Expected::Thing("a name" | "a number" | "a string")
                    | Expected::Token("`(`" | "`[`")
                    | Expected::Keyword("`TRUE`" | "`FALSE`" | "`NOT`")
            )
        });
        items.push(Expected::Thing("an expression"));
        items.sort();
        items.dedup();
    }
    if items.contains(&Expected::Thing("an expression")) {
        items.retain(|e| *e != Expected::Thing("a name"));
    }
    let then = items.contains(&Expected::Keyword("`THEN`"));
    let semi = items.contains(&Expected::Token("`;`"));
    // After `IF cond` (or `WHILE cond`), `THEN` (`DO`) is what is meant, although the compact
    // IF makes any simple statement valid there too.
    for kw in ["`THEN`", "`DO`"] {
        if items.contains(&Expected::Keyword(kw)) {
            items.retain(|e| *e == Expected::Keyword(kw) || *e == Expected::Operator);
        }
    }
    if items.iter().any(|e| matches!(e, Expected::Closer(_))) {
        items.retain(|e| *e != Expected::Thing("a statement"));
    }
    // Accesses and calls that could continue a name are rarely what is missing.
    let ends = ["`;`", "`,`", "`)`", "`]`", "`}`"];
    if items
        .iter()
        .any(|e| matches!(e, Expected::Token(t) if ends.contains(t)))
    {
        items.retain(|e| {
            !matches!(
                e,
                Expected::Token("`(`" | "`.`" | "`{`" | "`:=`" | "`:`" | "`[`")
            )
        });
    }
    let semi_text = match region {
        Region::Statement => "`;` after the statement",
        _ => "`;` after the declaration",
    };
    let mut words: Vec<&str> = items
        .iter()
        .map(|e| match e {
            Expected::Token("`;`") => semi_text,
            e => e.text(),
        })
        .collect();
    if semi {
        // Put the `;` first: it is by far the most common omission.
        if let Some(i) = words.iter().position(|w| *w == semi_text) {
            let w = words.remove(i);
            words.insert(0, w);
        }
    }
    if words.is_empty() {
        words.push("valid RAPID");
    }
    let expected = join_or(&words);
    let (mut found, found_span) = describe(text, pos);
    let wants_name = ["a name", "a statement", "an expression"]
        .iter()
        .any(|w| words.contains(w));
    if wants_name && is_reserved(text.get(found_span.0..found_span.1).unwrap_or("")) {
        found = format!("the reserved word {found}");
    }
    // A missing `;` at the end of a line: point at the end of that line, not at the next one.
    let prev = prev_token_end(text, pos);
    let at_end = text.get(pos..).is_none_or(|rest| rest.trim().is_empty());
    let (span, label) = if at_end
        || (semi
            && text
                .get(prev..pos)
                .is_some_and(|s| s.contains(['\n', '\r'])))
    {
        (
            Span::new(file, prev, prev),
            format!("expected {} here", words[0]),
        )
    } else {
        (
            Span::new(file, found_span.0, found_span.1),
            format!("expected {}", words[0]),
        )
    };
    let head = first_word_after_local(text, pos);
    let help = if then {
        Some("a block IF is `IF cond THEN … ENDIF`; the compact form `IF cond stmt;` takes one simple statement".to_string())
    } else if region == Region::RoutineHead && head.eq_ignore_ascii_case("FUNC") {
        Some("a function head is `FUNC type name (parameters)`".to_string())
    } else {
        None
    };
    ParseErrorKind::Syntax {
        span,
        expected,
        found,
        label,
        help,
    }
}

fn join_or(words: &[&str]) -> String {
    const MAX: usize = 6;
    let shown: Vec<&str> = words.iter().take(MAX).copied().collect();
    let mut s = String::new();
    for (i, w) in shown.iter().enumerate() {
        if i > 0 {
            s.push_str(if i + 1 == shown.len() && words.len() <= MAX {
                " or "
            } else {
                ", "
            });
        }
        s.push_str(w);
    }
    if words.len() > MAX {
        s.push_str(", …");
    }
    s
}

/// The token at `pos`, described for a message, and its byte range.
pub(crate) fn describe(text: &str, pos: usize) -> (String, (usize, usize)) {
    let Some(rest) = text.get(pos..) else {
        return ("the end of the file".into(), (text.len(), text.len()));
    };
    let mut chars = rest.chars();
    let Some(c) = chars.next() else {
        return ("the end of the file".into(), (pos, pos));
    };
    let word_len =
        |pred: &dyn Fn(char) -> bool| rest.find(|c: char| !pred(c)).unwrap_or(rest.len());
    if c.is_ascii_alphabetic() || c == '_' {
        let n = word_len(&|c| c.is_ascii_alphanumeric() || c == '_');
        return (format!("`{}`", shorten(&rest[..n])), (pos, pos + n));
    }
    if c.is_ascii_digit() || (c == '.' && chars.next().is_some_and(|d| d.is_ascii_digit())) {
        let n = word_len(&|c| c.is_ascii_alphanumeric() || c == '.' || c == '_');
        return (format!("`{}`", shorten(&rest[..n])), (pos, pos + n));
    }
    if c == '"' {
        let n = rest[1..]
            .find(['"', '\n', '\r'])
            .map_or(rest.len(), |i| i + 2)
            .min(rest.len());
        return ("a string".into(), (pos, pos + n));
    }
    for op in [":=", "<=", ">=", "<>"] {
        if rest.starts_with(op) {
            return (format!("`{op}`"), (pos, pos + 2));
        }
    }
    let n = c.len_utf8();
    if c.is_control() {
        return (format!("character U+{:04X}", c as u32), (pos, pos + n));
    }
    (format!("`{c}`"), (pos, pos + n))
}

/// RAPID's reserved words (they cannot be used as names).
pub(crate) const RESERVED: [&str; 58] = [
    "ALIAS",
    "AND",
    "BACKWARD",
    "CASE",
    "CONNECT",
    "CONST",
    "DEFAULT",
    "DIV",
    "DO",
    "ELSE",
    "ELSEIF",
    "ENDFOR",
    "ENDFUNC",
    "ENDIF",
    "ENDMODULE",
    "ENDPROC",
    "ENDRECORD",
    "ENDTEST",
    "ENDTRAP",
    "ENDWHILE",
    "ERROR",
    "EXIT",
    "FALSE",
    "FOR",
    "FROM",
    "FUNC",
    "GOTO",
    "IF",
    "INOUT",
    "LOCAL",
    "MOD",
    "MODULE",
    "NOSTEPIN",
    "NOT",
    "NOVIEW",
    "OR",
    "PERS",
    "PROC",
    "RAISE",
    "READONLY",
    "RECORD",
    "RETRY",
    "RETURN",
    "STEP",
    "SYSMODULE",
    "TASK",
    "TEST",
    "THEN",
    "TO",
    "TRAP",
    "TRUE",
    "TRYNEXT",
    "UNDO",
    "VAR",
    "VIEWONLY",
    "WHILE",
    "WITH",
    "XOR",
];

fn is_reserved(word: &str) -> bool {
    RESERVED.iter().any(|r| r.eq_ignore_ascii_case(word))
}

fn shorten(s: &str) -> String {
    if s.chars().count() > 40 {
        let mut t: String = s.chars().take(40).collect();
        t.push('…');
        t
    } else {
        s.to_string()
    }
}

/// The first word of the line holding `pos`, after an optional `LOCAL`.
fn first_word_after_local(text: &str, pos: usize) -> &str {
    let line_start = text
        .get(..pos)
        .and_then(|t| t.rfind(['\n', '\r']))
        .map_or(0, |i| i + 1);
    let rest = text.get(line_start..).unwrap_or("");
    let mut start = line_start + rest.len() - rest.trim_start().len();
    let w = first_word(text, start);
    if w.eq_ignore_ascii_case("LOCAL") {
        start += w.len();
        let rest = text.get(start..).unwrap_or("");
        start += rest.len() - rest.trim_start().len();
        return first_word(text, start);
    }
    w
}

fn first_word(text: &str, start: usize) -> &str {
    let rest = text.get(start..).unwrap_or("");
    let n = rest
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    &rest[..n]
}

/// True when the string starting at `pos` has no closing quote on its line.
fn unterminated_string(text: &str, pos: usize) -> bool {
    let b = text.as_bytes();
    let mut i = pos + 1;
    while i < b.len() {
        match b[i] {
            b'"' if b.get(i + 1) == Some(&b'"') => i += 2,
            b'"' => return false,
            b'\n' | b'\r' => return true,
            _ => i += 1,
        }
    }
    true
}

/// The end of the last token before `pos`, skipping white space and comments backwards.
pub(crate) fn prev_token_end(text: &str, pos: usize) -> usize {
    let mut p = pos.min(text.len());
    loop {
        let trimmed = text[..p].trim_end();
        p = trimmed.len();
        let line_start = text[..p].rfind(['\n', '\r']).map_or(0, |i| i + 1);
        match comment_start(&text[line_start..p]) {
            Some(c) => p = line_start + c,
            None => return p,
        }
    }
}

/// Offset of the `!` that starts a comment in `line`, if any (outside strings).
fn comment_start(line: &str) -> Option<usize> {
    let mut in_string = false;
    for (i, b) in line.bytes().enumerate() {
        match b {
            b'"' => in_string = !in_string,
            b'!' if !in_string => return Some(i),
            _ => {}
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn describes_tokens() {
        assert_eq!(describe("ENDIF x", 0).0, "`ENDIF`");
        assert_eq!(describe("1.5e3;", 0), ("`1.5e3`".to_string(), (0, 5)));
        assert_eq!(describe("", 0).0, "the end of the file");
        assert_eq!(describe("\u{1}", 0).0, "character U+0001");
        assert_eq!(describe(":= 1", 0).0, "`:=`");
    }

    #[test]
    fn previous_token_skips_comments() {
        let t = "x := 1 ! a \"comment\"\r\n  y";
        assert_eq!(prev_token_end(t, t.len() - 1), 6);
        assert_eq!(prev_token_end("a \"!\" b", 6), 5);
    }

    #[test]
    fn joins_words() {
        assert_eq!(join_or(&["a"]), "a");
        assert_eq!(join_or(&["a", "b", "c"]), "a, b or c");
    }
}
