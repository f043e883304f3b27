//! Persistent data between runs: a human-readable file of RAPID-style declarations
//! (`PERS num counter := 5;`), read at start and written at the end of a run.
//!
//! Numbers are written with the shortest text that reads back to the same `num`/`dnum`;
//! strings use RAPID's escapes (`""` and `\\`). Entries the current program does not
//! declare are kept and written back unchanged.

use std::fmt::Write as _;

use super::value::{Array, Value};
use crate::ir::{Ty, TypeKind, TypeTable};

pub use crate::rtlib::format::LitValue as Lit;

/// One `PERS type name := value;` line.
#[derive(Clone, Debug, PartialEq)]
pub struct PersEntry {
    /// Type name as written.
    pub ty: String,
    /// Data name.
    pub name: String,
    /// The value.
    pub value: Lit,
    /// The line as written (kept for entries the program does not declare).
    pub raw: String,
}

/// A persistent of the running program, for saving.
#[derive(Clone, Debug, PartialEq)]
pub struct PersValue {
    /// Name as declared.
    pub name: String,
    /// Type as written in a declaration (`num`, `robtarget{*}` for arrays).
    pub ty: String,
    /// `TASK PERS`.
    pub task: bool,
    /// Current value.
    pub value: Value,
}

/// The text of a persistents file: a header comment, then one line per persistent, then the
/// kept lines of entries the program does not declare.
pub fn write(values: &[PersValue], kept: &[PersEntry]) -> String {
    let mut s = String::from("! rapidvc persistents: PERS data saved at the end of a run\n");
    for v in values {
        let _ = writeln!(
            s,
            "{}PERS {} {} := {};",
            if v.task { "TASK " } else { "" },
            v.ty,
            v.name,
            to_text(&v.value)
        );
    }
    for k in kept {
        s.push_str(&k.raw);
        s.push('\n');
    }
    s
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

/// Parse a persistents file. Blank lines and `!` comments are ignored; values are RAPID
/// literals (numbers, strings, TRUE/FALSE, aggregates), read like `StrToVal` reads them.
pub fn parse(text: &str) -> Result<Vec<PersEntry>, PersError> {
    let mut out = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('!') {
            continue;
        }
        let err = |m: &str| PersError {
            line: i + 1,
            message: m.to_string(),
        };
        let rest = strip_kw(line, "TASK").unwrap_or(line);
        let rest =
            strip_kw(rest, "PERS").ok_or_else(|| err("expected `PERS type name := value;`"))?;
        let (decl, val) = rest.split_once(":=").ok_or_else(|| err("expected `:=`"))?;
        let mut words = decl.split_whitespace();
        let (Some(ty), Some(name), None) = (words.next(), words.next(), words.next()) else {
            return Err(err("expected a type and a name before `:=`"));
        };
        let val = val
            .trim()
            .strip_suffix(';')
            .ok_or_else(|| err("expected `;` at the end of the line"))?;
        let value = crate::rtlib::format::parse_value(val)
            .ok_or_else(|| err("the value is not a RAPID literal or aggregate"))?;
        out.push(PersEntry {
            ty: ty.to_string(),
            name: name.to_string(),
            value,
            raw: line.to_string(),
        });
    }
    Ok(out)
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
        Value::Num(x) => {
            let _ = write!(s, "{x}");
        }
        Value::Dnum(x) => {
            let _ = write!(s, "{x}");
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
