//! The generic reader of ABB's CFG text format: a header line, `#`-separated sections, and instances of `-Attribute value` pairs.
//!
//! The format (observed from RobotWare backups; docs/egm.md, "Configuration files"):
//!
//! ```text
//! EIO:CFG_1.0:6:1::
//! #
//! EIO_SIGNAL:
//!
//!       -Name "ao_MoveX" -SignalType "AO" -MinLog -2000\
//!       -MaxLog 2000 -Access "All"
//! ```
//!
//! * The first line is the header `DOMAIN:CFG_x.y:major:minor::`.
//! * A line holding only `#` separates sections; the next line is the type name with a
//!   colon. A type header without a preceding `#` is accepted too.
//! * Each logical line inside a section is one instance: `-Attribute` names, each followed
//!   by at most one value (a quoted string or a bare token such as a number). An attribute
//!   without a value is a flag. A backslash at the very end of a line (spaces after it are
//!   allowed) continues the logical line on the next one. Blank lines and indentation are
//!   cosmetic.
//! * Strings end at the next `"` on the same line (there are no escapes).
//! * Attribute and type names are compared case-insensitively ([`CfgInstance::get`],
//!   [`CfgFile::sections_named`]); the original spelling is kept.
//!
//! Malformed input never stops the reader: each problem is one diagnostic in the collector
//! and the reader goes on with the next line, so one run reports every error. Only a bad
//! header makes [`parse`] return `None`.

use crate::diag::Diagnostics;
use crate::source::{SourceId, Span};

use super::ConfigError;

/// A parsed CFG file.
#[derive(Clone, Debug, PartialEq)]
pub struct CfgFile {
    /// The file in the source map.
    pub source: SourceId,
    /// The domain from the header (`EIO`, `SIO`, `MOC`, `SYS`, …).
    pub domain: String,
    /// Where the domain is written.
    pub domain_span: Span,
    /// The format version field of the header (`CFG_1.0`).
    pub format: String,
    /// The sections in file order.
    pub sections: Vec<CfgSection>,
}

impl CfgFile {
    /// The sections of one type (case-insensitive), in file order.
    pub fn sections_named<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a CfgSection> {
        self.sections
            .iter()
            .filter(move |s| s.name.eq_ignore_ascii_case(name))
    }
}

/// One section: a type name and its instances.
#[derive(Clone, Debug, PartialEq)]
pub struct CfgSection {
    /// The type name without the colon (`EIO_SIGNAL`).
    pub name: String,
    /// Where the type header is written.
    pub span: Span,
    /// The instances in file order.
    pub instances: Vec<CfgInstance>,
}

/// One instance: its attributes in file order (each name at most once).
#[derive(Clone, Debug, PartialEq)]
pub struct CfgInstance {
    /// From the first attribute to the last value.
    pub span: Span,
    /// The attributes.
    pub attrs: Vec<CfgAttr>,
}

impl CfgInstance {
    /// The attribute called `name` (without the `-`; case-insensitive).
    pub fn get(&self, name: &str) -> Option<&CfgAttr> {
        self.attrs
            .iter()
            .find(|a| a.name.eq_ignore_ascii_case(name))
    }
}

/// One `-Attribute [value]` pair.
#[derive(Clone, Debug, PartialEq)]
pub struct CfgAttr {
    /// The name without the leading `-`, as written.
    pub name: String,
    /// Where `-Name` is written.
    pub name_span: Span,
    /// The value.
    pub value: CfgValue,
    /// Where the value is written (`None` for a flag).
    pub value_span: Option<Span>,
}

impl CfgAttr {
    /// The value's span, or the name's for a flag.
    pub fn value_or_name_span(&self) -> Span {
        self.value_span.unwrap_or(self.name_span)
    }

    /// The text of a string or bare-word value.
    pub fn as_text(&self) -> Option<&str> {
        match &self.value {
            CfgValue::Str(s) | CfgValue::Word(s) => Some(s),
            CfgValue::Num(_) | CfgValue::Flag => None,
        }
    }

    /// A numeric value (a bare number, or a quoted string holding one).
    pub fn as_num(&self) -> Option<f64> {
        match &self.value {
            CfgValue::Num(n) => Some(*n),
            CfgValue::Str(s) => parse_number(s.trim()),
            CfgValue::Word(_) | CfgValue::Flag => None,
        }
    }
}

/// An attribute value.
#[derive(Clone, Debug, PartialEq)]
pub enum CfgValue {
    /// No value: the attribute's presence means true.
    Flag,
    /// A quoted string (without the quotes).
    Str(String),
    /// A bare number.
    Num(f64),
    /// Another bare token.
    Word(String),
}

/// A finite decimal number (`-2000`, `0.5`, `1E3`); not `inf`/`NaN`.
pub fn parse_number(s: &str) -> Option<f64> {
    let plausible = !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_digit() || matches!(c, '+' | '-' | '.' | 'e' | 'E'))
        && s.chars().any(|c| c.is_ascii_digit());
    if !plausible {
        return None;
    }
    s.parse::<f64>().ok().filter(|v| v.is_finite())
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Newline,
    Hash,
    Attr(String),
    Str(String),
    Word(String),
}

impl Tok {
    fn text(&self) -> String {
        match self {
            Tok::Newline => "end of line".into(),
            Tok::Hash => "#".into(),
            Tok::Attr(a) => format!("-{a}"),
            Tok::Str(s) => format!("\"{s}\""),
            Tok::Word(w) => w.clone(),
        }
    }
}

fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\r' | 0x0c)
}

/// Split `text[start..]` into tokens; continuation backslashes disappear.
fn lex(src: SourceId, text: &str, start: usize, diags: &mut Diagnostics) -> Vec<(Tok, Span)> {
    let b = text.as_bytes();
    let sp = |a: usize, e: usize| Span::new(src, a, e);
    let slice = |a: usize, e: usize| text.get(a..e).unwrap_or("").to_string();
    let mut out = Vec::new();
    let mut i = start;
    while let Some(&c) = b.get(i) {
        match c {
            b'\n' => {
                out.push((Tok::Newline, sp(i, i + 1)));
                i += 1;
            }
            c if is_space(c) => i += 1,
            b'\\' => {
                let mut j = i + 1;
                while b
                    .get(j)
                    .is_some_and(|&d| d == b' ' || d == b'\t' || d == b'\r')
                {
                    j += 1;
                }
                match b.get(j) {
                    Some(b'\n') => i = j + 1,
                    None => i = j,
                    Some(_) => {
                        diags.push(ConfigError::StrayBackslash {
                            src,
                            span: sp(i, i + 1),
                        });
                        i += 1;
                    }
                }
            }
            b'"' => {
                let mut j = i + 1;
                while b.get(j).is_some_and(|&d| d != b'"' && d != b'\n') {
                    j += 1;
                }
                if b.get(j) == Some(&b'"') {
                    out.push((Tok::Str(slice(i + 1, j)), sp(i, j + 1)));
                    i = j + 1;
                } else {
                    let mut end = j;
                    while end > i + 1 && b.get(end - 1).is_some_and(|&d| is_space(d)) {
                        end -= 1;
                    }
                    diags.push(ConfigError::UnterminatedString {
                        src,
                        span: sp(i, end),
                    });
                    out.push((Tok::Str(slice(i + 1, end)), sp(i, end)));
                    i = j;
                }
            }
            b'#' => {
                out.push((Tok::Hash, sp(i, i + 1)));
                i += 1;
            }
            b'-' if b
                .get(i + 1)
                .is_some_and(|&d| d.is_ascii_alphabetic() || d == b'_') =>
            {
                let mut j = i + 1;
                while b
                    .get(j)
                    .is_some_and(|&d| d.is_ascii_alphanumeric() || d == b'_')
                {
                    j += 1;
                }
                out.push((Tok::Attr(slice(i + 1, j)), sp(i, j)));
                i = j;
            }
            _ => {
                let mut j = i;
                while b
                    .get(j)
                    .is_some_and(|&d| !is_space(d) && !matches!(d, b'\n' | b'"' | b'\\'))
                {
                    j += 1;
                }
                out.push((Tok::Word(slice(i, j)), sp(i, j)));
                i = j;
            }
        }
    }
    out
}

fn is_type_name(s: &str) -> bool {
    let mut chars = s.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Parse the header line; `(domain, domain span, format)`.
fn header(src: SourceId, text: &str) -> Option<(String, Span, String)> {
    let line = text.split('\n').next().unwrap_or("").trim_end();
    let parts: Vec<&str> = line.split(':').collect();
    let domain = *parts.first()?;
    let format = *parts.get(1)?;
    let ok = parts.len() >= 4
        && !domain.is_empty()
        && domain
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_')
        && format.starts_with("CFG_");
    ok.then(|| {
        (
            domain.to_string(),
            Span::new(src, 0, domain.len()),
            format.to_string(),
        )
    })
}

/// Parse a CFG file. Problems go to `diags`; `None` only when the header is not a CFG
/// header.
pub fn parse(src: SourceId, text: &str, diags: &mut Diagnostics) -> Option<CfgFile> {
    let first_line_end = text.find('\n').unwrap_or(text.len());
    let Some((domain, domain_span, format)) = header(src, text) else {
        let end = text
            .get(..first_line_end)
            .map(|l| l.trim_end().len())
            .unwrap_or(0);
        diags.push(ConfigError::BadHeader {
            src,
            span: Span::new(src, 0, end),
        });
        return None;
    };
    let tokens = lex(src, text, first_line_end, diags);
    let mut file = CfgFile {
        source: src,
        domain,
        domain_span,
        format,
        sections: Vec::new(),
    };
    let mut current: Option<usize> = None;
    let mut expect_type = false;
    let mut orphan_reported = false;
    for line in tokens.split(|(t, _)| *t == Tok::Newline) {
        let Some(((first, first_span), rest)) = line.split_first() else {
            continue;
        };
        let line_span = line
            .last()
            .map(|(_, s)| first_span.merge(*s))
            .unwrap_or(*first_span);
        match first {
            Tok::Hash => {
                if let Some(((_, s), _)) = rest.split_first() {
                    let junk = line.last().map(|(_, e)| s.merge(*e)).unwrap_or(*s);
                    diags.push(ConfigError::ExpectedType { src, span: junk });
                }
                current = None;
                expect_type = true;
                orphan_reported = true;
            }
            Tok::Word(w) if rest.is_empty() && w.ends_with(':') => {
                let name = w.trim_end_matches(':');
                if is_type_name(name) {
                    file.sections.push(CfgSection {
                        name: name.to_string(),
                        span: *first_span,
                        instances: Vec::new(),
                    });
                    current = Some(file.sections.len() - 1);
                    orphan_reported = false;
                } else {
                    diags.push(ConfigError::ExpectedType {
                        src,
                        span: *first_span,
                    });
                    current = None;
                    orphan_reported = true;
                }
                expect_type = false;
            }
            _ if expect_type => {
                diags.push(ConfigError::ExpectedType {
                    src,
                    span: line_span,
                });
                expect_type = false;
            }
            _ => {
                let Some(instance) = instance(src, line, diags) else {
                    continue;
                };
                match current.and_then(|i| file.sections.get_mut(i)) {
                    Some(section) => section.instances.push(instance),
                    None if !orphan_reported => {
                        diags.push(ConfigError::NoSection {
                            src,
                            span: instance.span,
                        });
                        orphan_reported = true;
                    }
                    None => {}
                }
            }
        }
    }
    Some(file)
}

/// One logical line as an instance (`None` when it holds no attribute).
fn instance(src: SourceId, line: &[(Tok, Span)], diags: &mut Diagnostics) -> Option<CfgInstance> {
    let mut attrs: Vec<CfgAttr> = Vec::new();
    let mut reported = false;
    for (tok, span) in line {
        match tok {
            Tok::Attr(name) => attrs.push(CfgAttr {
                name: name.clone(),
                name_span: *span,
                value: CfgValue::Flag,
                value_span: None,
            }),
            Tok::Str(_) | Tok::Word(_) => match attrs.last_mut() {
                Some(attr) if attr.value_span.is_none() => {
                    attr.value = match tok {
                        Tok::Str(s) => CfgValue::Str(s.clone()),
                        _ => {
                            let w = tok.text();
                            match parse_number(&w) {
                                Some(n) => CfgValue::Num(n),
                                None => CfgValue::Word(w),
                            }
                        }
                    };
                    attr.value_span = Some(*span);
                }
                _ if !reported => {
                    diags.push(ConfigError::ExpectedAttribute {
                        src,
                        span: *span,
                        found: tok.text(),
                    });
                    reported = true;
                }
                _ => {}
            },
            Tok::Hash | Tok::Newline => {
                if !reported {
                    diags.push(ConfigError::ExpectedAttribute {
                        src,
                        span: *span,
                        found: tok.text(),
                    });
                    reported = true;
                }
            }
        }
    }
    let first = attrs.first()?.name_span;
    let last = attrs.last().map(CfgAttr::value_or_name_span)?;
    // Keep the first of duplicated attribute names.
    let mut kept: Vec<CfgAttr> = Vec::with_capacity(attrs.len());
    for a in attrs {
        match kept.iter().find(|k| k.name.eq_ignore_ascii_case(&a.name)) {
            Some(k) => diags.push(ConfigError::DuplicateAttribute {
                src,
                span: a.name_span,
                first: k.name_span,
                name: a.name.clone(),
            }),
            None => kept.push(a),
        }
    }
    Some(CfgInstance {
        span: first.merge(last),
        attrs: kept,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::SourceMap;

    fn run(text: &str) -> (SourceMap, Option<CfgFile>, Diagnostics) {
        let mut map = SourceMap::new();
        let id = map.add("EIO.cfg", text);
        let mut diags = Diagnostics::new();
        let f = parse(id, text, &mut diags);
        (map, f, diags)
    }

    fn ok(text: &str) -> CfgFile {
        let (map, f, diags) = run(text);
        assert!(diags.is_empty(), "{}", diags.render_plain(&map, 80));
        f.unwrap()
    }

    fn rendered(text: &str) -> String {
        let (map, _, diags) = run(text);
        diags.render_plain(&map, 80)
    }

    #[test]
    fn reads_sections_instances_and_values() {
        let text = "EIO:CFG_1.0:6:1::\r\n#\r\nEIO_BUS:\r\n\r\n      -Name \"Virtual1\" -ConnectorID \"SIM1\"\r\n#\r\nEIO_SIGNAL:\r\n\r\n      -Name \"ao1\" -SignalType \"AO\" -MinLog -2000\\\r\n      -MaxLog 2e3 -Invert -Access All\r\n\r\n      -Name \"d\u{e9}\" -SignalType \"DI\" -Rapid  \r\n";
        let f = ok(text);
        assert_eq!(f.domain, "EIO");
        assert_eq!(f.format, "CFG_1.0");
        assert_eq!(f.sections.len(), 2);
        assert_eq!(f.sections[0].name, "EIO_BUS");
        let sig = f.sections_named("eio_signal").next().unwrap();
        assert_eq!(sig.instances.len(), 2);
        let ao = &sig.instances[0];
        assert_eq!(ao.attrs.len(), 6);
        assert_eq!(ao.get("name").unwrap().as_text(), Some("ao1"));
        assert_eq!(ao.get("MINLOG").unwrap().value, CfgValue::Num(-2000.0));
        assert_eq!(ao.get("MaxLog").unwrap().as_num(), Some(2000.0));
        assert_eq!(ao.get("Invert").unwrap().value, CfgValue::Flag);
        assert_eq!(ao.get("Invert").unwrap().value_span, None);
        assert_eq!(
            ao.get("Access").unwrap().value,
            CfgValue::Word("All".into())
        );
        assert_eq!(ao.get("SignalType").unwrap().as_num(), None);
        // The instance spans both physical lines.
        let snippet = &text[ao.span.start as usize..ao.span.end as usize];
        assert!(snippet.starts_with("-Name \"ao1\"") && snippet.ends_with("-Access All"));
        let di = &sig.instances[1];
        assert_eq!(di.get("Name").unwrap().as_text(), Some("dé"));
        assert_eq!(di.get("Rapid").unwrap().value, CfgValue::Flag);
        let name = di.get("Name").unwrap();
        assert_eq!(
            &text[name.name_span.start as usize..name.name_span.end as usize],
            "-Name"
        );
    }

    #[test]
    fn continuation_after_value_without_space_and_at_eof() {
        let f = ok(
            "SIO:CFG_1.0:6:1::\n#\nCOM_TRP:\n\n  -Name \"EGMsensor\" -Type \"UDPUC\" -PhyChannel \"\"\\\n  -RemoteAdress \"127.0.0.1\" -RemotePortNumber 6510\\",
        );
        let inst = &f.sections[0].instances[0];
        assert_eq!(inst.attrs.len(), 5);
        assert_eq!(inst.get("PhyChannel").unwrap().as_text(), Some(""));
        assert_eq!(inst.get("RemotePortNumber").unwrap().as_num(), Some(6510.0));
        assert_eq!(f.domain, "SIO");
    }

    #[test]
    fn header_only_and_section_without_hash() {
        assert!(ok("MOC:CFG_1.0:6:0::").sections.is_empty());
        assert!(ok("MOC:CFG_1.0:6:0::\n").sections.is_empty());
        let f = ok("EIO:CFG_1.0:6:0::\nEIO_SIGNAL:\n  -Name \"doNew\" -SignalType \"DO\"\n");
        assert_eq!(f.sections[0].instances.len(), 1);
        let f = ok(
            "MOC:CFG_1.0:6:0::\n#\nEXT_MOTION_DATA:\n\n  -name \"pathCorr\" -ext_motion_level 2\n\n  -name \"raw\" -ext_motion_Kp 10 -do_not_restart_after_motors_off\n",
        );
        let i = &f.sections[0].instances;
        assert_eq!(i.len(), 2);
        assert_eq!(i[1].get("EXT_MOTION_KP").unwrap().as_num(), Some(10.0));
        assert_eq!(
            i[1].get("do_not_restart_after_motors_off").unwrap().value,
            CfgValue::Flag
        );
    }

    #[test]
    fn numbers() {
        assert_eq!(parse_number("-2000"), Some(-2000.0));
        assert_eq!(parse_number("0.5"), Some(0.5));
        assert_eq!(parse_number("1E3"), Some(1000.0));
        assert_eq!(parse_number("inf"), None);
        assert_eq!(parse_number("NaN"), None);
        assert_eq!(parse_number("1e999"), None);
        assert_eq!(parse_number("-"), None);
        assert_eq!(parse_number("0x10"), None);
        assert_eq!(parse_number(""), None);
    }

    #[test]
    fn bad_header() {
        let (_, f, diags) = run("EIO_SIGNAL:\n -Name \"x\"\n");
        assert!(f.is_none());
        assert_eq!(diags.error_count(), 1);
        insta::assert_snapshot!(rendered("EIO_SIGNAL:\n -Name \"x\"\n"));
        insta::assert_snapshot!("empty_file", rendered(""));
    }

    #[test]
    fn unterminated_string_and_stray_backslash() {
        let text = "EIO:CFG_1.0:6:1::\n#\nEIO_SIGNAL:\n\n  -SignalType \"DO\" -Name \"do1\n\n  -Name \"do2\" \\ -SignalType \"DO\"\n";
        let (_, f, diags) = run(text);
        assert_eq!(diags.error_count(), 2);
        // Reading goes on: both instances are there.
        assert_eq!(f.unwrap().sections[0].instances.len(), 2);
        insta::assert_snapshot!(rendered(text));
    }

    #[test]
    fn values_without_attributes() {
        let text = "EIO:CFG_1.0:6:1::\n#\nEIO_SIGNAL:\n\n  Name \"do1\" -SignalType \"DO\"\n\n  -Name \"do2\" \"extra\" -SignalType \"DO\"\n";
        let (_, f, diags) = run(text);
        assert_eq!(diags.error_count(), 2);
        let f = f.unwrap();
        assert_eq!(f.sections[0].instances[0].attrs.len(), 1);
        assert_eq!(f.sections[0].instances[1].attrs.len(), 2);
        insta::assert_snapshot!(rendered(text));
    }

    #[test]
    fn hash_lines_and_type_headers() {
        let text = "EIO:CFG_1.0:6:1::\n# comment\nEIO_SIGNAL:\n  -Name \"a\"\n#\n  -Name \"b\"\n#\n1BAD:\n  -Name \"c\"\n";
        let (_, f, diags) = run(text);
        assert_eq!(diags.error_count(), 3);
        let f = f.unwrap();
        assert_eq!(f.sections.len(), 1);
        assert_eq!(f.sections[0].instances.len(), 1);
        insta::assert_snapshot!(rendered(text));
    }

    #[test]
    fn instance_before_any_section() {
        let text =
            "EIO:CFG_1.0:6:1::\n\n  -Name \"a\"\n\n  -Name \"b\"\n#\nEIO_SIGNAL:\n  -Name \"c\"\n";
        let (_, f, diags) = run(text);
        // One error for the orphans, then reading continues.
        assert_eq!(diags.error_count(), 1);
        assert_eq!(f.unwrap().sections[0].instances.len(), 1);
        insta::assert_snapshot!(rendered(text));
    }

    #[test]
    fn duplicate_attribute_is_a_warning() {
        let text =
            "EIO:CFG_1.0:6:1::\n#\nEIO_SIGNAL:\n  -Name \"a\" -SignalType \"DO\" -name \"b\"\n";
        let (_, f, diags) = run(text);
        assert_eq!(diags.error_count(), 0);
        assert_eq!(diags.warning_count(), 1);
        let inst = &f.unwrap().sections[0].instances[0];
        assert_eq!(inst.get("Name").unwrap().as_text(), Some("a"));
        assert_eq!(inst.attrs.len(), 2);
        insta::assert_snapshot!(rendered(text));
    }

    mod props {
        use super::*;
        use proptest::prelude::*;

        proptest! {
            /// Any text after a valid header parses without panicking, and every span the
            /// reader produces lies inside the text.
            #[test]
            fn reader_is_total(body in "[-#a-zA-Z0-9_:\" \\\\\n\r\t.é]{0,120}") {
                let text = format!("EIO:CFG_1.0:6:1::\n{body}");
                let (_, f, diags) = run(&text);
                let f = f.unwrap();
                for sec in &f.sections {
                    prop_assert!(sec.span.end as usize <= text.len());
                    for inst in &sec.instances {
                        prop_assert!(inst.span.end as usize <= text.len());
                        prop_assert!(!inst.attrs.is_empty());
                    }
                }
                let _ = diags.len();
            }

            #[test]
            fn any_first_line(text in ".{0,60}") {
                let (_, _, _) = run(&text);
            }
        }
    }
}
