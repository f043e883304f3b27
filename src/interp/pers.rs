//! Persistent data between runs: a human-readable file of RAPID declarations
//! (`PERS num counter := 5;`, `TASK PERS num speeds{3} := [100,200,300];`), read at start and
//! rewritten at the end of a run.
//!
//! Numbers are written with the shortest text that reads back to the same `num`/`dnum`;
//! strings use RAPID's escapes (`""` and `\\`). Arrays are declared as in RAPID
//! (`name{2,3}`; the older form `num{3} name` is read too). Rewriting keeps the file's
//! layout: comments, blank lines, entries the program does not declare and comments after a
//! declaration stay where they are; the value of each declared persistent is replaced in
//! its line, and persistents not stored yet are appended. A line that is not a declaration
//! or a comment, or a name stored twice, is an error (the file is not used or touched).

use std::fmt::Write as _;

use super::value::{Array, Value};
use crate::ir::{Ty, TypeKind, TypeTable};

pub use crate::functions::format::LitValue as Lit;

/// The first line of a new persistents file.
pub const HEADER: &str = "! rapidvc persistents: PERS data saved at the end of a run";

/// One `PERS type name := value;` line.
#[derive(Clone, Debug, PartialEq)]
pub struct PersEntry {
    /// Type name as written.
    pub ty: String,
    /// Data name.
    pub name: String,
    /// Array sizes as declared (`name{2,3}`); empty for a scalar.
    pub dims: Vec<u32>,
    /// The value.
    pub value: Lit,
    /// The line as written (trimmed).
    pub raw: String,
    /// 1-based line number.
    pub line: usize,
}

/// A persistent of the running program, for saving.
#[derive(Clone, Debug, PartialEq)]
pub struct PersValue {
    /// Name as declared.
    pub name: String,
    /// Type name as declared (`num`, `robtarget`).
    pub ty: String,
    /// Array sizes (empty for a scalar).
    pub dims: Vec<u32>,
    /// `TASK PERS`.
    pub task: bool,
    /// Current value.
    pub value: Value,
}

/// Array sizes as declared: `{2,3}`, or nothing for a scalar.
pub fn dims_text(dims: &[u32]) -> String {
    if dims.is_empty() {
        return String::new();
    }
    let d: Vec<String> = dims.iter().map(u32::to_string).collect();
    format!("{{{}}}", d.join(","))
}

impl PersValue {
    /// The declaration as written to the file: `TASK PERS num a{3} := [1,2,3];`.
    pub fn declaration(&self) -> String {
        let mut s = String::new();
        if self.task {
            s.push_str("TASK ");
        }
        let _ = write!(
            s,
            "PERS {} {}{} := {};",
            self.ty,
            self.name,
            dims_text(&self.dims),
            to_text(&self.value)
        );
        s
    }
}

/// The new text of a persistents file: `original` (the file as read at the start, `None`
/// for a new file) with the value of every persistent in `values` replaced in its line and
/// the ones not stored yet appended. Everything else of `original` is kept byte for byte.
pub fn write(original: Option<&str>, values: &[PersValue]) -> String {
    let mut written = vec![false; values.len()];
    let mut out = String::new();
    match original {
        None => {
            out.push_str(HEADER);
            out.push('\n');
        }
        Some(text) => {
            for piece in text.split_inclusive('\n') {
                let body = piece.trim_end_matches(['\n', '\r']);
                let ending = &piece[body.len()..];
                let replaced = match parse_line(body) {
                    Ok(Some(d)) => values
                        .iter()
                        .enumerate()
                        .find(|(i, v)| !written[*i] && v.name.eq_ignore_ascii_case(d.name))
                        .map(|(i, v)| (i, d.indent, v.declaration(), d.trailing)),
                    _ => None,
                };
                match replaced {
                    Some((i, indent, decl, trailing)) => {
                        written[i] = true;
                        out.push_str(indent);
                        out.push_str(&decl);
                        out.push_str(trailing);
                        out.push_str(ending);
                    }
                    None => out.push_str(piece),
                }
            }
            if !out.is_empty() && !out.ends_with('\n') && written.iter().any(|w| !w) {
                out.push('\n');
            }
        }
    }
    for (v, done) in values.iter().zip(&written) {
        if !done {
            out.push_str(&v.declaration());
            out.push('\n');
        }
    }
    out
}

/// A parse error in a persistents file.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("line {line}: {message}")]
pub struct PersError {
    /// 1-based line.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

/// Parse a persistents file. Blank lines and `!` comments are skipped; values are RAPID
/// literals (numbers, strings, TRUE/FALSE, aggregates), read like `StrToVal` reads them.
pub fn parse(text: &str) -> Result<Vec<PersEntry>, PersError> {
    let mut out: Vec<PersEntry> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let err = |message: String| PersError {
            line: i + 1,
            message,
        };
        let Some(d) = parse_line(raw).map_err(err)? else {
            continue;
        };
        if let Some(first) = out.iter().find(|e| e.name.eq_ignore_ascii_case(d.name)) {
            return Err(err(format!(
                "`{}` is stored twice (first at line {})",
                d.name, first.line
            )));
        }
        out.push(PersEntry {
            ty: d.ty.to_string(),
            name: d.name.to_string(),
            dims: d.dims,
            value: d.value,
            raw: raw.trim().to_string(),
            line: i + 1,
        });
    }
    Ok(out)
}

/// One declaration line, split up (slices of the line).
struct Decl<'a> {
    /// White space before the declaration.
    indent: &'a str,
    ty: &'a str,
    name: &'a str,
    dims: Vec<u32>,
    value: Lit,
    /// What follows the `;` (white space and a comment).
    trailing: &'a str,
}

/// A line of a persistents file: `None` for a blank or comment line.
fn parse_line(raw: &str) -> Result<Option<Decl<'_>>, String> {
    let line = raw.trim_start();
    let indent = &raw[..raw.len() - line.len()];
    if line.trim().is_empty() || line.starts_with('!') {
        return Ok(None);
    }
    let rest = strip_kw(line, "TASK").unwrap_or(line);
    let rest =
        strip_kw(rest, "PERS").ok_or("expected `PERS type name := value;` or a `!` comment")?;
    let (decl, after) = rest.split_once(":=").ok_or("expected `:=`")?;
    let (ty, name, dims) = parse_decl(decl)?;
    let end = statement_end(after).ok_or("expected `;` after the value")?;
    let (val, trailing) = (&after[..end], &after[end + 1..]);
    let t = trailing.trim_start();
    if !(t.is_empty() || t.starts_with('!')) {
        return Err(format!("unexpected `{}` after `;`", t.trim_end()));
    }
    let value = crate::functions::format::parse_value(val.trim())
        .ok_or("the value is not a RAPID literal or aggregate")?;
    Ok(Some(Decl {
        indent,
        ty,
        name,
        dims,
        value,
        trailing,
    }))
}

/// `type name`, `type name{2,3}` or (older files) `type{2,3} name`.
fn parse_decl(decl: &str) -> Result<(&str, &str, Vec<u32>), String> {
    let bad = || "expected a type and a name before `:=` (`num counter`, `num speeds{3}`)";
    let (words, dims): (Vec<&str>, Vec<u32>) = match decl.find('{') {
        None => (decl.split_whitespace().collect(), Vec::new()),
        Some(open) => {
            let close = decl.find('}').filter(|&c| c > open).ok_or("missing `}`")?;
            let (before, after) = (&decl[..open], &decl[close + 1..]);
            if after.contains(['{', '}']) {
                return Err("one list of array sizes is allowed".into());
            }
            let dims = decl[open + 1..close]
                .split(',')
                .map(|d| d.trim().parse::<u32>().ok().filter(|&n| n > 0))
                .collect::<Option<Vec<u32>>>()
                .filter(|d| (1..=3).contains(&d.len()))
                .ok_or("array sizes are one to three whole numbers above 0, as in `{2,3}`")?;
            let mut words: Vec<&str> = before.split_whitespace().collect();
            let glued = before.ends_with(|c: char| !c.is_whitespace());
            // `type{3} name` (sizes glued to the type) or `type name{3}` / `type name {3}`.
            if glued && words.len() == 1 {
                words.extend(after.split_whitespace());
            } else if after.trim().is_empty() {
                // sizes after the name
            } else {
                return Err(bad().into());
            }
            (words, dims)
        }
    };
    match words[..] {
        [ty, name] if is_identifier(ty) && is_identifier(name) => Ok((ty, name, dims)),
        _ => Err(bad().into()),
    }
}

fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// The byte index of the `;` that ends the statement (outside string literals).
fn statement_end(s: &str) -> Option<usize> {
    let mut in_string = false;
    for (i, c) in s.char_indices() {
        match c {
            '"' => in_string = !in_string,
            ';' if !in_string => return Some(i),
            _ => {}
        }
    }
    None
}

fn strip_kw<'a>(s: &'a str, kw: &str) -> Option<&'a str> {
    let head = s.get(..kw.len())?;
    let tail = s.get(kw.len()..)?;
    if head.eq_ignore_ascii_case(kw) && tail.starts_with(char::is_whitespace) {
        Some(tail.trim_start())
    } else {
        None
    }
}

/// Overwrite `target` with a literal of the same shape; false when the shapes differ.
pub fn fill(target: &mut Value, lit: &Lit) -> bool {
    super::builtins::fill_literal(target, lit)
}

/// A value as persistents-file text (RAPID aggregate syntax, exact numbers).
pub fn to_text(v: &Value) -> String {
    let mut s = String::new();
    write_value(&mut s, v);
    s
}

fn write_value(s: &mut String, v: &Value) {
    match v {
        // −0 is written as 0 (RAPID's literals have no negative zero).
        Value::Num(x) => {
            let _ = write!(s, "{}", if *x == 0.0 { 0.0 } else { *x });
        }
        Value::Dnum(x) => {
            let _ = write!(s, "{}", if *x == 0.0 { 0.0 } else { *x });
        }
        Value::Bool(b) => s.push_str(if *b { "TRUE" } else { "FALSE" }),
        Value::Str(t) => {
            s.push('"');
            for c in t.chars() {
                match c {
                    '"' => s.push_str("\"\""),
                    '\\' => s.push_str("\\\\"),
                    c if (c as u32) < 0x20 || (0x7f..0x100).contains(&(c as u32)) => {
                        let _ = write!(s, "\\{:02X}", c as u32);
                    }
                    c => s.push(c),
                }
            }
            s.push('"');
        }
        Value::Record(fs) => write_list(s, fs.iter()),
        Value::Array(a) => write_array(s, a, 0, 0),
        Value::Absent => s.push_str("[]"),
    }
}

fn write_list<'a>(s: &mut String, items: impl Iterator<Item = &'a Value>) {
    s.push('[');
    for (i, v) in items.enumerate() {
        if i > 0 {
            s.push(',');
        }
        write_value(s, v);
    }
    s.push(']');
}

fn write_array(s: &mut String, a: &Array, dim: usize, offset: usize) {
    let n = a.dims[dim] as usize;
    let stride: usize = a.dims[dim + 1..a.rank as usize]
        .iter()
        .map(|&d| d as usize)
        .product();
    s.push('[');
    for i in 0..n {
        if i > 0 {
            s.push(',');
        }
        if dim + 1 == a.rank as usize {
            if let Some(v) = a.data.get(offset + i) {
                write_value(s, v);
            }
        } else {
            write_array(s, a, dim + 1, offset + i * stride);
        }
    }
    s.push(']');
}

/// Do two values have the same shape (same kinds, record lengths and array sizes)?
pub fn same_shape(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Num(_), Value::Num(_))
        | (Value::Dnum(_), Value::Dnum(_))
        | (Value::Bool(_), Value::Bool(_))
        | (Value::Str(_), Value::Str(_)) => true,
        (Value::Record(x), Value::Record(y)) => {
            x.len() == y.len() && x.iter().zip(y.iter()).all(|(p, q)| same_shape(p, q))
        }
        (Value::Array(x), Value::Array(y)) => {
            x.dims == y.dims && x.data.iter().zip(&y.data).all(|(p, q)| same_shape(p, q))
        }
        _ => false,
    }
}

/// Does a run-time value fit a static type?
pub fn fits(types: &TypeTable, ty: Ty, v: &Value) -> bool {
    if ty.rank > 0 {
        return match v {
            Value::Array(a) => {
                a.rank == ty.rank && a.data.iter().all(|x| fits(types, ty.elem(), x))
            }
            _ => false,
        };
    }
    match (&types.get(types.resolve(ty.base)).kind, v) {
        (TypeKind::Num, Value::Num(_))
        | (TypeKind::Dnum, Value::Dnum(_))
        | (TypeKind::Bool, Value::Bool(_))
        | (TypeKind::String, Value::Str(_)) => true,
        (TypeKind::Record { fields, .. }, Value::Record(vs)) => {
            fields.len() == vs.len()
                && fields
                    .iter()
                    .zip(vs.iter())
                    .all(|(f, x)| fits(types, f.ty, x))
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_through_text() {
        let text = "! saved\nPERS num n := 16777216;\nTASK PERS robjoint j := [1.5,-2,3,4,5,6];\nPERS string s := \"a\"\"b\\\\c\\07\";\n";
        let e = parse(text).unwrap();
        assert_eq!(e.len(), 3);
        assert_eq!(e[0].value, Lit::Num(16777216.0));
        assert_eq!(e[2].value, Lit::Str("a\"b\\c\u{7}".into()));
        let mut v = Value::num_record(&[0.0; 6]);
        assert!(fill(&mut v, &e[1].value));
        assert_eq!(to_text(&v), "[1.5,-2,3,4,5,6]");
        let mut s = Value::str("");
        assert!(fill(&mut s, &e[2].value));
        assert_eq!(to_text(&s), "\"a\"\"b\\\\c\\07\"");
        assert!(parse("PERS num x := [1,;").is_err());
        assert!(parse("VAR num x := 1;").is_err());
    }

    #[test]
    fn arrays_are_declared_as_in_rapid() {
        let e = parse("PERS num arr{3} := [1,2,3];\nTASK PERS num grid {2, 2} := [[1,2],[3,4]];\nPERS num{2} old := [5,6]; ! written by older versions\n").unwrap();
        assert_eq!(
            (e[0].name.as_str(), e[0].dims.as_slice()),
            ("arr", &[3][..])
        );
        assert_eq!(
            (e[1].name.as_str(), e[1].dims.as_slice()),
            ("grid", &[2, 2][..])
        );
        assert_eq!(
            (e[2].name.as_str(), e[2].dims.as_slice()),
            ("old", &[2][..])
        );
        for bad in [
            "PERS num arr{0} := [1];",
            "PERS num arr{1,2,3,4} := [1];",
            "PERS num arr{x} := [1];",
            "PERS num arr{2 := [1,2];",
            "PERS num {2} arr := [1,2];",
            "PERS num arr{2}{2} := [1,2];",
            "PERS num a b := 1;",
            "PERS num 1a := 1;",
            "PERS num a := 1; junk",
            "PERS num a := 1;\nPERS num A := 2;",
        ] {
            assert!(parse(bad).is_err(), "{bad}");
        }
        // `;` and `!` inside a string are part of the value.
        let e = parse("PERS string s := \"a;b!c\"; ! note").unwrap();
        assert_eq!(e[0].value, Lit::Str("a;b!c".into()));
    }

    #[test]
    fn rewriting_keeps_the_layout() {
        let old = "! header\r\n\r\n  PERS num arr{3} := [1,2,3]; ! speeds\r\nPERS string other := \"x\";\r\nPERS num{2} b := [0,0];";
        let arr = PersValue {
            name: "ARR".into(),
            ty: "num".into(),
            dims: vec![3],
            task: true,
            value: Value::Array(Box::new(Array {
                dims: [3, 1, 1],
                rank: 1,
                data: vec![Value::Num(4.0), Value::Num(-0.0), Value::Num(0.5)],
            })),
        };
        let b = PersValue {
            name: "b".into(),
            ty: "num".into(),
            dims: vec![2],
            task: false,
            value: Value::Array(Box::new(Array {
                dims: [2, 1, 1],
                rank: 1,
                data: vec![Value::Num(7.0), Value::Num(8.0)],
            })),
        };
        let n = PersValue {
            name: "n".into(),
            ty: "num".into(),
            dims: vec![],
            task: false,
            value: Value::Num(3.0),
        };
        assert_eq!(
            write(Some(old), &[arr, b, n.clone()]),
            "! header\r\n\r\n  TASK PERS num ARR{3} := [4,0,0.5]; ! speeds\r\nPERS string other := \"x\";\r\nPERS num b{2} := [7,8];\nPERS num n := 3;\n"
        );
        assert_eq!(write(Some(old), &[]), old);
        assert_eq!(write(None, &[n]), format!("{HEADER}\nPERS num n := 3;\n"));
    }

    #[test]
    fn arrays_are_nested() {
        let mut a = Value::Array(Box::new(Array {
            dims: [2, 2, 1],
            rank: 2,
            data: vec![Value::Num(0.0); 4],
        }));
        let e = parse("PERS num a := [[1,2],[3,4]];").unwrap();
        assert!(fill(&mut a, &e[0].value));
        assert_eq!(to_text(&a), "[[1,2],[3,4]]");
        let bad = parse("PERS num a := [[1,2],[3]];").unwrap();
        assert!(!fill(&mut a, &bad[0].value));
    }
}
