//! Signatures of native (built-in) routines, written in a compact RAPID-like notation and
//! parsed once: `PROC TPWrite(string String, \num Num | bool Bool | pos Pos)`,
//! `FUNC num Abs(num Value)`.
//!
//! Parameter syntax: `[\] [INOUT|VAR|PERS|REF] type name [{*[,*[,*]]}]`, with `|` between
//! mutually exclusive optional alternatives. `REF` is a read-only reference used by natives
//! that inspect big values without copying them (`Dim`). Type `anytype` accepts any value
//! type, `anydata` any value type or array of one, `anynum` accepts `num` or `dnum`,
//! `anysignal` any I/O signal or a string naming one, `anydataorsignal` what `anydata`
//! accepts or a signal variable.

use std::fmt;

/// Access mode of a native parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SigMode {
    /// By value.
    In,
    /// INOUT: a variable, or a persistent or a part of one.
    InOut,
    /// VAR: a variable.
    Var,
    /// PERS: an entire persistent.
    Pers,
    /// Read-only reference: any expression; places are passed without copying.
    Ref,
}

/// The type of a native parameter or result.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SigType {
    /// Type name (`num`, `robtarget`, …), or `anytype` / `anynum`.
    pub name: String,
    /// Array rank (`{*}` = 1).
    pub rank: u8,
}

impl SigType {
    /// `anytype`: any value type.
    pub fn is_any(&self) -> bool {
        self.name.eq_ignore_ascii_case("anytype")
    }
    /// `anydata`: any value type or an array of one (`GetDataVal`, `SetDataVal`).
    pub fn is_any_data(&self) -> bool {
        self.name.eq_ignore_ascii_case("anydata")
    }
    /// `anynum`: num or dnum.
    pub fn is_anynum(&self) -> bool {
        self.name.eq_ignore_ascii_case("anynum")
    }
    /// `switch`.
    pub fn is_switch(&self) -> bool {
        self.name.eq_ignore_ascii_case("switch")
    }
}

impl fmt::Display for SigType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.name)?;
        if self.rank > 0 {
            write!(f, "{{*")?;
            for _ in 1..self.rank {
                write!(f, ",*")?;
            }
            write!(f, "}}")?;
        }
        Ok(())
    }
}

/// One native parameter.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SigParam {
    /// Name (matched case-insensitively against `\Name` arguments).
    pub name: String,
    /// Type.
    pub ty: SigType,
    /// Access mode.
    pub mode: SigMode,
    /// Optional (`\`).
    pub optional: bool,
    /// Alternatives group index (shared by the members of one `a | b` group).
    pub group: u16,
}

/// A native routine's signature.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NativeSig {
    /// Name as documented (`TPWrite`).
    pub name: String,
    /// Result type for functions; `None` for procedures (instructions).
    pub ret: Option<SigType>,
    /// Parameters, alternatives flattened.
    pub params: Vec<SigParam>,
}

impl NativeSig {
    /// Parse a signature; `Err` carries a message naming the problem (a bug in the table).
    pub fn parse(text: &str) -> Result<NativeSig, String> {
        let text = text.trim();
        let open = text
            .find('(')
            .ok_or_else(|| format!("no `(` in `{text}`"))?;
        if !text.ends_with(')') {
            return Err(format!("no closing `)` in `{text}`"));
        }
        let head: Vec<&str> = text[..open].split_whitespace().collect();
        let (ret, name) = match head.as_slice() {
            [kw, name] if kw.eq_ignore_ascii_case("PROC") => (None, *name),
            [kw, ty, name] if kw.eq_ignore_ascii_case("FUNC") => (Some(parse_type(ty)?), *name),
            _ => return Err(format!("bad head in `{text}`")),
        };
        let body = &text[open + 1..text.len() - 1];
        let mut params = Vec::new();
        for (group, grp) in body
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty())
            .enumerate()
        {
            let optional = grp.starts_with('\\');
            for alt in grp.split('|') {
                let alt = alt.trim().trim_start_matches('\\');
                params.push(parse_param(alt, optional, group as u16)?);
            }
        }
        Ok(NativeSig {
            name: name.to_string(),
            ret,
            params,
        })
    }

    /// True for functions.
    pub fn is_func(&self) -> bool {
        self.ret.is_some()
    }

    /// Index of the parameter with this (case-insensitive) name.
    pub fn param_index(&self, name: &str) -> Option<usize> {
        self.params
            .iter()
            .position(|p| p.name.eq_ignore_ascii_case(name))
    }
}

fn parse_type(t: &str) -> Result<SigType, String> {
    let (name, rank) = match t.find('{') {
        Some(i) => {
            let dims = &t[i..];
            let rank = dims.matches('*').count() as u8;
            if !(1..=3).contains(&rank) {
                return Err(format!("bad array dims `{t}`"));
            }
            (&t[..i], rank)
        }
        None => (t, 0),
    };
    if name.is_empty() {
        return Err(format!("empty type in `{t}`"));
    }
    Ok(SigType {
        name: name.to_string(),
        rank,
    })
}

fn parse_param(text: &str, optional: bool, group: u16) -> Result<SigParam, String> {
    let words: Vec<&str> = text.split_whitespace().collect();
    let (mode, rest) = match words.first().map(|w| w.to_ascii_uppercase()) {
        Some(w) if w == "INOUT" => (SigMode::InOut, &words[1..]),
        Some(w) if w == "VAR" => (SigMode::Var, &words[1..]),
        Some(w) if w == "PERS" => (SigMode::Pers, &words[1..]),
        Some(w) if w == "REF" => (SigMode::Ref, &words[1..]),
        _ => (SigMode::In, &words[..]),
    };
    let [ty, name] = rest else {
        return Err(format!("bad parameter `{text}`"));
    };
    // `{*}` may be written after the name, as in RAPID.
    let (name, ty) = match name.find('{') {
        Some(i) => (&name[..i], format!("{ty}{}", &name[i..])),
        None => (*name, ty.to_string()),
    };
    Ok(SigParam {
        name: name.to_string(),
        ty: parse_type(&ty)?,
        mode,
        optional,
        group,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_alternatives_and_modes() {
        let s = NativeSig::parse(
            r"PROC TPWrite(string String, \num Num | bool Bool | pos Pos, INOUT num x{*})",
        )
        .unwrap();
        assert_eq!(s.name, "TPWrite");
        assert!(s.ret.is_none());
        assert_eq!(s.params.len(), 5);
        assert!(!s.params[0].optional);
        assert!(s.params[1].optional && s.params[3].optional);
        assert_eq!(s.params[1].group, s.params[3].group);
        assert_eq!(s.params[4].mode, SigMode::InOut);
        assert_eq!(s.params[4].ty.rank, 1);
        let f = NativeSig::parse("FUNC num Abs(num Value)").unwrap();
        assert_eq!(f.ret.unwrap().name, "num");
        assert!(NativeSig::parse("FUNC Abs(num Value)").is_err());
    }
}
