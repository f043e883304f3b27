//! The configuration database RAPID reads and writes with `ReadCfgData`, `WriteCfgData` and
//! `SaveCfgData`: the CFG files of the configuration directory (`EIO.cfg`, `SIO.cfg`,
//! `MOC.cfg`, `SYS.cfg`), as they were when the run started.
//!
//! * **Paths.** `/DOMAIN/TYPE/Name` names the instance whose `-Name` is `Name`;
//!   `/DOMAIN/TYPE/Attribute/Value` the instances whose `Attribute` has `Value`, the first of
//!   them, or with `\ListNo` the n-th (from 0; `\ListNo` then holds the next number, or −1,
//!   `END_OF_LIST`, after the last). Domains, types, attributes, names and values are compared
//!   case-insensitively, as RAPID compares names.
//! * **Types.** A CFG file has no schema, so a value's type is its form: a bare number is a
//!   `num`/`dnum` (a quoted number may be read as one too), a quoted string or a bare word a
//!   `string`, an attribute without a value (`-Invert`) a `bool` that is TRUE; an attribute a
//!   file leaves out reads as FALSE into a `bool` (that is how CFG files store FALSE) and is
//!   `ERR_CFG_NOTFND` for any other type. Reading a value into a variable of another type is
//!   `ERR_CFG_ILLTYPE`. Values are the file's, in its units (metres, radians): RAPID converts.
//! * **Writing** changes the database of the run: later reads see it, `SaveCfgData` saves it;
//!   the running controller keeps the configuration it started with (a controller applies
//!   most system parameters at its next restart). An attribute keeps its form; a `bool`
//!   attribute is added or removed; another attribute the instance does not have is
//!   `ERR_CFG_NOTFND`. A text a CFG file cannot hold (a `"` or a line break), a value that is
//!   not a finite number, or a `-Name` another instance of the type has is `ERR_CFG_LIMIT`.
//! * **Saving** writes one domain (or all loaded ones) as a CFG file into a directory the run
//!   allows ([`CfgData::allow_saving_in`]: `rapidvc run --save-cfg` allows the configuration
//!   directory); without one, or for a path that leaves it, a directory that does not exist,
//!   or a file the run read its configuration from, `SaveCfgData` is `ERR_CFG_WRITEFILE`.

use std::fmt;
use std::path::{Component, Path, PathBuf};

use crate::config::cfg::{CfgFile, CfgValue, parse_number};
use crate::source::SourceMap;

/// Why a configuration access failed; [`CfgError::err_name`] is the RAPID error it raises.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CfgError {
    /// No such domain, type, instance or attribute, or a malformed path (`ERR_CFG_NOTFND`).
    NotFound(String),
    /// The variable's type does not fit the value (`ERR_CFG_ILLTYPE`).
    IllType(String),
    /// The value cannot be stored (`ERR_CFG_LIMIT`).
    Limit(String),
    /// `\ListNo` outside the matching instances (`ERR_CFG_OUTOFBOUNDS`).
    OutOfBounds(String),
    /// The file cannot be written there (`ERR_CFG_WRITEFILE`).
    WriteFile(String),
    /// The domain is not loaded or not valid here (`ERR_CFG_ILL_DOMAIN`).
    IllDomain(String),
}

impl CfgError {
    /// The RAPID error constant.
    pub fn err_name(&self) -> &'static str {
        match self {
            CfgError::NotFound(_) => "ERR_CFG_NOTFND",
            CfgError::IllType(_) => "ERR_CFG_ILLTYPE",
            CfgError::Limit(_) => "ERR_CFG_LIMIT",
            CfgError::OutOfBounds(_) => "ERR_CFG_OUTOFBOUNDS",
            CfgError::WriteFile(_) => "ERR_CFG_WRITEFILE",
            CfgError::IllDomain(_) => "ERR_CFG_ILL_DOMAIN",
        }
    }
}

impl fmt::Display for CfgError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CfgError::NotFound(m)
            | CfgError::IllType(m)
            | CfgError::Limit(m)
            | CfgError::OutOfBounds(m)
            | CfgError::WriteFile(m)
            | CfgError::IllDomain(m) => f.write_str(m),
        }
    }
}

/// The RAPID type a value is read into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RapidKind {
    /// `num` or `dnum`.
    Number,
    /// `bool`.
    Bool,
    /// `string`.
    Text,
}

/// A value as RAPID reads or writes it.
#[derive(Clone, Debug, PartialEq)]
pub enum RapidValue {
    /// A number.
    Number(f64),
    /// A bool.
    Bool(bool),
    /// A string.
    Text(String),
}

/// One instance: its attributes in file order.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// Attribute names (without `-`) and values.
    pub attrs: Vec<(String, CfgValue)>,
}

impl Instance {
    fn position(&self, attr: &str) -> Option<usize> {
        self.attrs
            .iter()
            .position(|(n, _)| n.eq_ignore_ascii_case(attr))
    }

    fn get(&self, attr: &str) -> Option<&CfgValue> {
        self.position(attr)
            .and_then(|i| self.attrs.get(i))
            .map(|a| &a.1)
    }

    /// The `-Name` of the instance.
    pub fn name(&self) -> Option<&str> {
        match self.get("name")? {
            CfgValue::Str(s) | CfgValue::Word(s) => Some(s),
            _ => None,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
struct TypeData {
    name: String,
    instances: Vec<Instance>,
}

#[derive(Clone, Debug, PartialEq)]
struct Domain {
    name: String,
    /// The header line of the file (`EIO:CFG_1.0:6:1::`).
    header: String,
    types: Vec<TypeData>,
    /// Where it was read from.
    source: Option<PathBuf>,
}

/// The configuration database (see the module doc).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CfgData {
    domains: Vec<Domain>,
    save_dir: Option<PathBuf>,
}

/// Which instances a path selects.
enum Selector {
    Name(String),
    Attr(String, String),
}

struct CfgPath {
    domain: String,
    type_name: String,
    selector: Selector,
}

fn parse_path(text: &str) -> Result<CfgPath, CfgError> {
    let bad = || {
        CfgError::NotFound(format!(
            "`{text}` is not a configuration path: expected /DOMAIN/TYPE/Name or /DOMAIN/TYPE/Attribute/Value"
        ))
    };
    let rest = text.strip_prefix('/').ok_or_else(bad)?;
    let parts: Vec<&str> = rest.split('/').collect();
    if parts.iter().any(|p| p.is_empty()) {
        return Err(bad());
    }
    match parts.as_slice() {
        [d, t, n] => Ok(CfgPath {
            domain: d.to_string(),
            type_name: t.to_string(),
            selector: Selector::Name(n.to_string()),
        }),
        [d, t, a, v] => Ok(CfgPath {
            domain: d.to_string(),
            type_name: t.to_string(),
            selector: Selector::Attr(a.to_string(), v.to_string()),
        }),
        _ => Err(bad()),
    }
}

/// Whether a stored value equals `text` (numbers by value, texts case-insensitively).
fn value_is(v: &CfgValue, text: &str) -> bool {
    match v {
        CfgValue::Str(s) | CfgValue::Word(s) => s.eq_ignore_ascii_case(text),
        CfgValue::Num(x) => parse_number(text.trim()) == Some(*x),
        CfgValue::Flag => ["TRUE", "1"].iter().any(|t| t.eq_ignore_ascii_case(text)),
    }
}

fn bool_word(s: &str) -> Option<bool> {
    if s.eq_ignore_ascii_case("TRUE") {
        Some(true)
    } else if s.eq_ignore_ascii_case("FALSE") {
        Some(false)
    } else {
        None
    }
}

/// Which n-th match `\ListNo` asks for, and the `\ListNo` to hand back after it.
fn pick(list_no: Option<f64>, count: usize, path: &str) -> Result<(usize, Option<f64>), CfgError> {
    if count == 0 {
        return Err(CfgError::NotFound(format!("no instance matches `{path}`")));
    }
    let n = match list_no {
        None => 0,
        Some(n) if n >= 0.0 && n.fract() == 0.0 && (n as usize) < count => n as usize,
        Some(n) => {
            return Err(CfgError::OutOfBounds(format!(
                "\\ListNo {n} is outside the {count} instance(s) that match `{path}` (0 to {})",
                count as i64 - 1
            )));
        }
    };
    let next = list_no.map(|_| if n + 1 < count { (n + 1) as f64 } else { -1.0 });
    Ok((n, next))
}

impl CfgData {
    /// The database of the parsed CFG files `files` (their header lines and paths are taken
    /// from `sources`, where the files were read into).
    pub fn from_files(files: &[CfgFile], sources: &SourceMap) -> CfgData {
        let domains = files
            .iter()
            .map(|f| {
                let src = sources.get(f.source);
                let header = src.text.lines().next().unwrap_or("").trim_end().to_string();
                Domain {
                    name: f.domain.clone(),
                    header,
                    types: f
                        .sections
                        .iter()
                        .map(|s| TypeData {
                            name: s.name.clone(),
                            instances: s
                                .instances
                                .iter()
                                .map(|i| Instance {
                                    attrs: i
                                        .attrs
                                        .iter()
                                        .map(|a| (a.name.clone(), a.value.clone()))
                                        .collect(),
                                })
                                .collect(),
                        })
                        .collect(),
                    source: Some(PathBuf::from(&src.name)),
                }
            })
            .collect();
        CfgData {
            domains,
            save_dir: None,
        }
    }

    /// Add the instances of `type_name` to `domain` when the loaded configuration has none
    /// of that type (the domain is added when missing, with `header` as its file header).
    /// Returns whether it added them.
    pub fn add_if_missing(
        &mut self,
        domain: &str,
        header: &str,
        type_name: &str,
        instances: Vec<Vec<(String, CfgValue)>>,
    ) -> bool {
        if self.instances(domain, type_name).next().is_some() {
            return false;
        }
        let ty = TypeData {
            name: type_name.to_string(),
            instances: instances
                .into_iter()
                .map(|attrs| Instance { attrs })
                .collect(),
        };
        match self
            .domains
            .iter_mut()
            .find(|d| d.name.eq_ignore_ascii_case(domain))
        {
            Some(d) => d.types.push(ty),
            None => self.domains.push(Domain {
                name: domain.to_string(),
                header: header.to_string(),
                types: vec![ty],
                source: None,
            }),
        }
        true
    }

    /// Let `SaveCfgData` write into `dir` (and the directories below it).
    pub fn allow_saving_in(&mut self, dir: impl Into<PathBuf>) {
        self.save_dir = Some(dir.into());
    }

    /// The names of the loaded domains, in file order.
    pub fn domains(&self) -> impl Iterator<Item = &str> {
        self.domains.iter().map(|d| d.name.as_str())
    }

    fn domain(&self, name: &str) -> Option<&Domain> {
        self.domains
            .iter()
            .find(|d| d.name.eq_ignore_ascii_case(name))
    }

    /// The instances of `type_name` in `domain` (every section of that type, in file order).
    pub fn instances<'a>(
        &'a self,
        domain: &str,
        type_name: &'a str,
    ) -> impl Iterator<Item = &'a Instance> {
        self.domain(domain)
            .into_iter()
            .flat_map(|d| d.types.iter())
            .filter(move |t| t.name.eq_ignore_ascii_case(type_name))
            .flat_map(|t| t.instances.iter())
    }

    /// (type index, instance index) of every instance `path` selects.
    fn matches(&self, path: &str) -> Result<(usize, Vec<(usize, usize)>), CfgError> {
        let p = parse_path(path)?;
        let di = self
            .domains
            .iter()
            .position(|d| d.name.eq_ignore_ascii_case(&p.domain))
            .ok_or_else(|| {
                CfgError::NotFound(format!(
                    "`{path}`: the configuration has no domain {} (loaded: {})",
                    p.domain,
                    self.loaded_list()
                ))
            })?;
        let d = &self.domains[di];
        if !d
            .types
            .iter()
            .any(|t| t.name.eq_ignore_ascii_case(&p.type_name))
        {
            return Err(CfgError::NotFound(format!(
                "`{path}`: {} has no type {}",
                d.name, p.type_name
            )));
        }
        let mut found = Vec::new();
        for (ti, t) in d.types.iter().enumerate() {
            if !t.name.eq_ignore_ascii_case(&p.type_name) {
                continue;
            }
            for (ii, inst) in t.instances.iter().enumerate() {
                let hit = match &p.selector {
                    Selector::Name(n) => inst.name().is_some_and(|m| m.eq_ignore_ascii_case(n)),
                    Selector::Attr(a, v) => inst.get(a).is_some_and(|x| value_is(x, v)),
                };
                if hit {
                    found.push((ti, ii));
                }
            }
        }
        Ok((di, found))
    }

    fn loaded_list(&self) -> String {
        if self.domains.is_empty() {
            "none".into()
        } else {
            self.domains().collect::<Vec<_>>().join(", ")
        }
    }

    /// `ReadCfgData`: attribute `attr` of the instance `path` selects, as `kind`; with
    /// `list_no`, the next `\ListNo`.
    pub fn read(
        &self,
        path: &str,
        attr: &str,
        kind: RapidKind,
        list_no: Option<f64>,
    ) -> Result<(RapidValue, Option<f64>), CfgError> {
        let (di, found) = self.matches(path)?;
        let (n, next) = pick(list_no, found.len(), path)?;
        let (ti, ii) = found[n];
        let inst = &self.domains[di].types[ti].instances[ii];
        let ill = |what: &str| {
            CfgError::IllType(format!(
                "`{attr}` of `{path}` is {what}, which cannot be read into a {}",
                match kind {
                    RapidKind::Number => "num or dnum",
                    RapidKind::Bool => "bool",
                    RapidKind::Text => "string",
                }
            ))
        };
        let value = match (inst.get(attr), kind) {
            (None, RapidKind::Bool) => RapidValue::Bool(false),
            (None, _) => {
                return Err(CfgError::NotFound(format!(
                    "`{path}` has no attribute `{attr}`"
                )));
            }
            (Some(CfgValue::Num(x)), RapidKind::Number) => RapidValue::Number(*x),
            (Some(CfgValue::Str(s)), RapidKind::Number) => match parse_number(s.trim()) {
                Some(x) => RapidValue::Number(x),
                None => return Err(ill("a text")),
            },
            (Some(CfgValue::Str(s) | CfgValue::Word(s)), RapidKind::Text) => {
                RapidValue::Text(s.clone())
            }
            (Some(CfgValue::Flag), RapidKind::Bool) => RapidValue::Bool(true),
            (Some(CfgValue::Str(s) | CfgValue::Word(s)), RapidKind::Bool) => match bool_word(s) {
                Some(b) => RapidValue::Bool(b),
                None => return Err(ill("a text")),
            },
            (Some(CfgValue::Num(_)), _) => return Err(ill("a number")),
            (Some(CfgValue::Flag), _) => return Err(ill("a flag (a bool)")),
            (Some(CfgValue::Word(_)), RapidKind::Number) => return Err(ill("a word")),
        };
        Ok((value, next))
    }

    /// `WriteCfgData`: set attribute `attr` of the instance `path` selects; with `list_no`,
    /// the next `\ListNo`.
    pub fn write(
        &mut self,
        path: &str,
        attr: &str,
        value: &RapidValue,
        list_no: Option<f64>,
    ) -> Result<Option<f64>, CfgError> {
        let (di, found) = self.matches(path)?;
        let (n, next) = pick(list_no, found.len(), path)?;
        let (ti, ii) = found[n];
        if let RapidValue::Text(s) = value {
            if s.contains(['"', '\n', '\r']) {
                return Err(CfgError::Limit(format!(
                    "a CFG file cannot hold the text {s:?} (a quote or a line break)"
                )));
            }
            if attr.eq_ignore_ascii_case("name") {
                let t = &self.domains[di].types[ti];
                let taken = t.instances.iter().enumerate().any(|(j, other)| {
                    j != ii && other.name().is_some_and(|m| m.eq_ignore_ascii_case(s))
                });
                if taken {
                    return Err(CfgError::Limit(format!(
                        "another {} instance is already called `{s}`",
                        t.name
                    )));
                }
            }
        }
        if let RapidValue::Number(x) = value
            && !x.is_finite()
        {
            return Err(CfgError::Limit(format!("{x} is not a finite number")));
        }
        let inst = &mut self.domains[di].types[ti].instances[ii];
        let pos = inst.position(attr);
        let ill = |what: &str| {
            CfgError::IllType(format!(
                "`{attr}` of `{path}` is {what}; it cannot be set from a {}",
                match value {
                    RapidValue::Number(_) => "number",
                    RapidValue::Bool(_) => "bool",
                    RapidValue::Text(_) => "string",
                }
            ))
        };
        let Some(i) = pos else {
            return match value {
                RapidValue::Bool(true) => {
                    inst.attrs.push((attr.to_string(), CfgValue::Flag));
                    Ok(next)
                }
                RapidValue::Bool(false) => Ok(next),
                _ => Err(CfgError::NotFound(format!(
                    "`{path}` has no attribute `{attr}`"
                ))),
            };
        };
        let slot = &mut inst.attrs[i].1;
        let new = match (&*slot, value) {
            (CfgValue::Num(_), RapidValue::Number(x)) => CfgValue::Num(*x),
            (CfgValue::Str(s), RapidValue::Number(x)) if parse_number(s.trim()).is_some() => {
                CfgValue::Str(number_text(*x))
            }
            (CfgValue::Str(_), RapidValue::Text(t)) => CfgValue::Str(t.clone()),
            (CfgValue::Word(_), RapidValue::Text(t)) => {
                if !t.is_empty()
                    && !t.contains(char::is_whitespace)
                    && !t.starts_with('-')
                    && parse_number(t).is_none()
                {
                    CfgValue::Word(t.clone())
                } else {
                    CfgValue::Str(t.clone())
                }
            }
            (CfgValue::Flag, RapidValue::Bool(true)) => CfgValue::Flag,
            (CfgValue::Flag, RapidValue::Bool(false)) => {
                inst.attrs.remove(i);
                return Ok(next);
            }
            (CfgValue::Str(s) | CfgValue::Word(s), RapidValue::Bool(b))
                if bool_word(s).is_some() =>
            {
                CfgValue::Word(if *b { "TRUE" } else { "FALSE" }.into())
            }
            (CfgValue::Num(_), _) => return Err(ill("a number")),
            (CfgValue::Flag, _) => return Err(ill("a flag (a bool)")),
            (CfgValue::Str(_) | CfgValue::Word(_), _) => return Err(ill("a text")),
        };
        *slot = new;
        Ok(next)
    }

    /// The text of `domain` as a CFG file.
    pub fn domain_text(&self, domain: &str) -> Option<String> {
        let d = self.domain(domain)?;
        let mut out = String::new();
        out.push_str(&d.header);
        out.push('\n');
        for t in &d.types {
            out.push_str("#\n");
            out.push_str(&t.name);
            out.push_str(":\n");
            for inst in &t.instances {
                out.push_str("\n     ");
                for (name, value) in &inst.attrs {
                    out.push_str(" -");
                    out.push_str(name);
                    match value {
                        CfgValue::Flag => {}
                        CfgValue::Str(s) => {
                            out.push_str(" \"");
                            out.push_str(s);
                            out.push('"');
                        }
                        CfgValue::Word(w) => {
                            out.push(' ');
                            out.push_str(w);
                        }
                        CfgValue::Num(x) => {
                            out.push(' ');
                            out.push_str(&number_text(*x));
                        }
                    }
                }
                out.push('\n');
            }
            out.push('\n');
        }
        Some(out)
    }

    /// `SaveCfgData`: write `domain` (every loaded domain when `None`) into directory
    /// `dir_path` of the controller's file system, as `file` or `DOMAIN.cfg`. Returns the
    /// files written.
    pub fn save(
        &self,
        dir_path: &str,
        file: Option<&str>,
        domain: Option<&str>,
    ) -> Result<Vec<PathBuf>, CfgError> {
        let root = self.save_dir.as_ref().ok_or_else(|| {
            CfgError::WriteFile(
                "this controller has no file system to save the configuration in \
                 (`rapidvc run --save-cfg` lets SaveCfgData write into the configuration directory)"
                    .into(),
            )
        })?;
        let dir = resolve_dir(root, dir_path)?;
        let targets: Vec<(&Domain, String)> = match domain {
            Some(name) => {
                let d = self.domain(name).ok_or_else(|| {
                    CfgError::IllDomain(format!(
                        "the configuration domain {name} is not in use (loaded: {})",
                        self.loaded_list()
                    ))
                })?;
                let file_name = match file {
                    Some(f) => plain_file_name(f)?,
                    None => format!("{}.cfg", d.name),
                };
                vec![(d, file_name)]
            }
            None => {
                if file.is_some() {
                    return Err(CfgError::IllDomain(
                        "\\File names one file; it cannot be used with ALL_DOMAINS".into(),
                    ));
                }
                if self.domains.is_empty() {
                    return Err(CfgError::IllDomain(
                        "no configuration domain is loaded".into(),
                    ));
                }
                self.domains
                    .iter()
                    .map(|d| (d, format!("{}.cfg", d.name)))
                    .collect()
            }
        };
        let mut written = Vec::new();
        for (d, name) in targets {
            let target = dir.join(&name);
            for input in self.domains.iter().filter_map(|d| d.source.as_deref()) {
                if same_file(&target, input) {
                    return Err(CfgError::WriteFile(format!(
                        "{} is a file the run read its configuration from; it is not overwritten",
                        target.display()
                    )));
                }
            }
            let text = self.domain_text(&d.name).unwrap_or_default();
            write_new(&target, &text).map_err(|e| {
                CfgError::WriteFile(format!("cannot write {}: {e}", target.display()))
            })?;
            written.push(target);
        }
        Ok(written)
    }
}

/// A number as a CFG file writes it.
fn number_text(x: f64) -> String {
    if x == x.trunc() && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else {
        format!("{x}")
    }
}

/// The directory `dir_path` (`SYSPAR`, `HOME:/SYSPAR`, `""`) under `root`: it must exist and
/// stay inside `root`, symbolic links included.
fn resolve_dir(root: &Path, dir_path: &str) -> Result<PathBuf, CfgError> {
    let refuse = |why: &str| {
        CfgError::WriteFile(format!(
            "cannot save into `{dir_path}`: {why} (the configuration is saved below {})",
            root.display()
        ))
    };
    let home = dir_path
        .get(..5)
        .is_some_and(|p| p.eq_ignore_ascii_case("HOME:"));
    let rel = match dir_path.get(5..) {
        Some(rest) if home => rest.trim_start_matches(['/', '\\']),
        _ => dir_path,
    };
    if rel.contains(':') {
        return Err(refuse("only HOME: is available"));
    }
    if rel.starts_with(['/', '\\']) {
        return Err(refuse("an absolute path"));
    }
    let rel_path = Path::new(rel);
    if rel_path
        .components()
        .any(|c| !matches!(c, Component::Normal(_) | Component::CurDir))
    {
        return Err(refuse(
            "`..` and absolute paths leave the controller's directory",
        ));
    }
    let root_real = root
        .canonicalize()
        .map_err(|e| refuse(&format!("the directory is not there ({e})")))?;
    let real = root_real
        .join(rel_path)
        .canonicalize()
        .map_err(|_| refuse("the directory does not exist"))?;
    if !real.starts_with(&root_real) {
        return Err(refuse("it leads out of the controller's directory"));
    }
    if !real.is_dir() {
        return Err(refuse("it is not a directory"));
    }
    Ok(real)
}

/// `\File`: a plain file name.
fn plain_file_name(f: &str) -> Result<String, CfgError> {
    let ok = !f.is_empty()
        && f != "."
        && f != ".."
        && !f.contains(['/', '\\', ':'])
        && !f.chars().any(char::is_control);
    if ok {
        Ok(f.to_string())
    } else {
        Err(CfgError::WriteFile(format!(
            "`{f}` is not a file name (\\File names a file in the directory)"
        )))
    }
}

/// Whether `a` and `b` are the same file (after resolving links); false when `a` does not
/// exist.
fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => false,
    }
}

/// Write `text` to `path` through a temporary file in the same directory, so that a full disk
/// never leaves half a file; an existing file is replaced, a directory is not.
fn write_new(path: &Path, text: &str) -> std::io::Result<()> {
    if path.is_dir() {
        return Err(std::io::Error::other("it is a directory"));
    }
    let tmp = path.with_extension(format!("rapidvc-{}.tmp", std::process::id()));
    let result = std::fs::write(&tmp, text).and_then(|()| std::fs::rename(&tmp, path));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::Diagnostics;

    const EIO: &str = "EIO:CFG_1.0:6:1::\n#\nEIO_SIGNAL:\n\n      -Name \"doGripper\" -SignalType \"DO\" -Device \"USERIO\"\n\n      -Name \"diPart\" -SignalType \"DI\" -Device \"USERIO\" -Invert\n\n      -Name \"aoSpeed\" -SignalType \"AO\" -MinLog -2000 -MaxLog 2000 -Access All\n#\nEIO_ACCESS:\n\n      -Name \"All\" -Rapid\n";

    fn data(texts: &[(&str, &str)]) -> CfgData {
        let mut sources = SourceMap::new();
        let mut diags = Diagnostics::new();
        let files: Vec<CfgFile> = texts
            .iter()
            .map(|(name, text)| {
                let id = sources.add(*name, *text);
                crate::config::cfg::parse(id, text, &mut diags).unwrap()
            })
            .collect();
        assert!(diags.is_empty());
        CfgData::from_files(&files, &sources)
    }

    fn read(d: &CfgData, path: &str, attr: &str, kind: RapidKind) -> Result<RapidValue, CfgError> {
        d.read(path, attr, kind, None).map(|(v, _)| v)
    }

    #[test]
    fn reads_by_name_and_by_attribute() {
        let d = data(&[("EIO.cfg", EIO)]);
        assert_eq!(
            read(
                &d,
                "/EIO/EIO_SIGNAL/doGripper",
                "SignalType",
                RapidKind::Text
            ),
            Ok(RapidValue::Text("DO".into()))
        );
        assert_eq!(
            read(&d, "/eio/eio_signal/AOSPEED", "minlog", RapidKind::Number),
            Ok(RapidValue::Number(-2000.0))
        );
        assert_eq!(
            read(&d, "/EIO/EIO_SIGNAL/diPart", "Invert", RapidKind::Bool),
            Ok(RapidValue::Bool(true))
        );
        assert_eq!(
            read(&d, "/EIO/EIO_SIGNAL/doGripper", "Invert", RapidKind::Bool),
            Ok(RapidValue::Bool(false))
        );
        assert_eq!(
            read(&d, "/EIO/EIO_SIGNAL/aoSpeed", "Access", RapidKind::Text),
            Ok(RapidValue::Text("All".into()))
        );
        // By attribute, walking the list.
        let mut list = Some(0.0);
        let mut names = Vec::new();
        while list != Some(-1.0) {
            let (v, next) = d
                .read(
                    "/EIO/EIO_SIGNAL/Device/USERIO",
                    "Name",
                    RapidKind::Text,
                    list,
                )
                .unwrap();
            names.push(v);
            list = next;
        }
        assert_eq!(
            names,
            [
                RapidValue::Text("doGripper".into()),
                RapidValue::Text("diPart".into())
            ]
        );
        assert_eq!(
            read(&d, "/EIO/EIO_SIGNAL/MaxLog/2E3", "Name", RapidKind::Text),
            Ok(RapidValue::Text("aoSpeed".into()))
        );
    }

    #[test]
    fn errors_name_the_rapid_error() {
        let d = data(&[("EIO.cfg", EIO)]);
        let e = |path: &str, attr: &str, kind, list| {
            d.read(path, attr, kind, list).unwrap_err().err_name()
        };
        use RapidKind::*;
        assert_eq!(
            e("/EIO/EIO_SIGNAL/nothing", "Name", Text, None),
            "ERR_CFG_NOTFND"
        );
        assert_eq!(e("/MOC/ARM/rob1_1", "x", Number, None), "ERR_CFG_NOTFND");
        assert_eq!(e("/EIO/NO_TYPE/x", "x", Number, None), "ERR_CFG_NOTFND");
        assert_eq!(
            e("EIO/EIO_SIGNAL/doGripper", "Name", Text, None),
            "ERR_CFG_NOTFND"
        );
        assert_eq!(e("/EIO/EIO_SIGNAL", "Name", Text, None), "ERR_CFG_NOTFND");
        assert_eq!(e("/EIO//doGripper", "Name", Text, None), "ERR_CFG_NOTFND");
        assert_eq!(
            e("/EIO/EIO_SIGNAL/doGripper", "MinLog", Number, None),
            "ERR_CFG_NOTFND"
        );
        assert_eq!(
            e("/EIO/EIO_SIGNAL/doGripper", "Name", Number, None),
            "ERR_CFG_ILLTYPE"
        );
        assert_eq!(
            e("/EIO/EIO_SIGNAL/aoSpeed", "MinLog", Text, None),
            "ERR_CFG_ILLTYPE"
        );
        assert_eq!(
            e("/EIO/EIO_SIGNAL/diPart", "Invert", Number, None),
            "ERR_CFG_ILLTYPE"
        );
        assert_eq!(
            e("/EIO/EIO_SIGNAL/aoSpeed", "Access", Bool, None),
            "ERR_CFG_ILLTYPE"
        );
        for bad in [-1.0, 2.0, 0.5, f64::NAN] {
            assert_eq!(
                e("/EIO/EIO_SIGNAL/Device/USERIO", "Name", Text, Some(bad)),
                "ERR_CFG_OUTOFBOUNDS",
                "{bad}"
            );
        }
    }

    #[test]
    fn writes_keep_the_form_and_round_trip() {
        let mut d = data(&[("EIO.cfg", EIO)]);
        d.write(
            "/EIO/EIO_SIGNAL/aoSpeed",
            "MaxLog",
            &RapidValue::Number(1500.5),
            None,
        )
        .unwrap();
        d.write(
            "/EIO/EIO_SIGNAL/doGripper",
            "Device",
            &RapidValue::Text("d652".into()),
            None,
        )
        .unwrap();
        d.write(
            "/EIO/EIO_SIGNAL/aoSpeed",
            "Access",
            &RapidValue::Text("Read Only".into()),
            None,
        )
        .unwrap();
        d.write(
            "/EIO/EIO_SIGNAL/diPart",
            "Invert",
            &RapidValue::Bool(false),
            None,
        )
        .unwrap();
        d.write(
            "/EIO/EIO_SIGNAL/doGripper",
            "Invert",
            &RapidValue::Bool(true),
            None,
        )
        .unwrap();
        assert_eq!(
            read(&d, "/EIO/EIO_SIGNAL/aoSpeed", "MaxLog", RapidKind::Number),
            Ok(RapidValue::Number(1500.5))
        );
        assert_eq!(
            read(&d, "/EIO/EIO_SIGNAL/diPart", "Invert", RapidKind::Bool),
            Ok(RapidValue::Bool(false))
        );
        let text = d.domain_text("eio").unwrap();
        let again = data(&[("EIO2.cfg", text.as_str())]);
        assert_eq!(again.domains, {
            let mut expected = d.domains.clone();
            expected[0].source = Some(PathBuf::from("EIO2.cfg"));
            expected
        });
        assert!(
            text.starts_with("EIO:CFG_1.0:6:1::\n#\nEIO_SIGNAL:\n"),
            "{text}"
        );
        assert!(text.contains("-Access \"Read Only\""), "{text}");
        assert!(text.contains("-Device \"d652\" -Invert"), "{text}");
    }

    #[test]
    fn write_errors() {
        let mut d = data(&[("EIO.cfg", EIO)]);
        let mut e = |path: &str, attr: &str, v: RapidValue| {
            d.write(path, attr, &v, None).unwrap_err().err_name()
        };
        assert_eq!(
            e(
                "/EIO/EIO_SIGNAL/aoSpeed",
                "MinLog",
                RapidValue::Text("x".into())
            ),
            "ERR_CFG_ILLTYPE"
        );
        assert_eq!(
            e(
                "/EIO/EIO_SIGNAL/aoSpeed",
                "Name",
                RapidValue::Text("diPart".into())
            ),
            "ERR_CFG_LIMIT"
        );
        assert_eq!(
            e(
                "/EIO/EIO_SIGNAL/aoSpeed",
                "Name",
                RapidValue::Text("a\"b".into())
            ),
            "ERR_CFG_LIMIT"
        );
        assert_eq!(
            e(
                "/EIO/EIO_SIGNAL/aoSpeed",
                "MinLog",
                RapidValue::Number(f64::INFINITY)
            ),
            "ERR_CFG_LIMIT"
        );
        assert_eq!(
            e(
                "/EIO/EIO_SIGNAL/aoSpeed",
                "Label",
                RapidValue::Text("x".into())
            ),
            "ERR_CFG_NOTFND"
        );
        assert_eq!(
            e(
                "/EIO/EIO_SIGNAL/nothing",
                "Name",
                RapidValue::Text("x".into())
            ),
            "ERR_CFG_NOTFND"
        );
    }

    #[test]
    fn saving_stays_in_its_directory() {
        let dir = std::env::temp_dir().join(format!("rapidvc-cfg-save-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("SYSPAR")).unwrap();
        let input = dir.join("EIO.cfg");
        std::fs::write(&input, EIO).unwrap();
        let mut d = data(&[(input.to_str().unwrap(), EIO)]);
        assert_eq!(
            d.save("", None, Some("EIO")).unwrap_err().err_name(),
            "ERR_CFG_WRITEFILE",
            "no place to save is allowed yet"
        );
        d.allow_saving_in(&dir);
        let written = d.save("HOME:/SYSPAR", None, Some("eio")).unwrap();
        assert_eq!(
            written,
            [dir.canonicalize().unwrap().join("SYSPAR/EIO.cfg")]
        );
        assert_eq!(
            std::fs::read_to_string(&written[0]).unwrap(),
            d.domain_text("EIO").unwrap()
        );
        let named = d.save("SYSPAR", Some("MYEIO.cfg"), Some("EIO")).unwrap();
        assert!(named[0].ends_with("SYSPAR/MYEIO.cfg"));
        let all = d.save("SYSPAR", None, None).unwrap();
        assert_eq!(all.len(), 1);
        for (path, file, domain, err) in [
            ("", None, Some("EIO"), "ERR_CFG_WRITEFILE"), // the input file itself
            ("..", None, Some("EIO"), "ERR_CFG_WRITEFILE"),
            ("SYSPAR/../..", None, Some("EIO"), "ERR_CFG_WRITEFILE"),
            ("/tmp", None, Some("EIO"), "ERR_CFG_WRITEFILE"),
            ("TEMP:", None, Some("EIO"), "ERR_CFG_WRITEFILE"),
            ("NOPE", None, Some("EIO"), "ERR_CFG_WRITEFILE"),
            ("SYSPAR", Some("../x.cfg"), Some("EIO"), "ERR_CFG_WRITEFILE"),
            ("SYSPAR", None, Some("MOC"), "ERR_CFG_ILL_DOMAIN"),
            ("SYSPAR", Some("x.cfg"), None, "ERR_CFG_ILL_DOMAIN"),
        ] {
            assert_eq!(
                d.save(path, file, domain).unwrap_err().err_name(),
                err,
                "{path} {file:?} {domain:?}"
            );
        }
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(std::env::temp_dir(), dir.join("out")).unwrap();
            assert_eq!(
                d.save("out", None, Some("EIO")).unwrap_err().err_name(),
                "ERR_CFG_WRITEFILE"
            );
        }
        assert_eq!(
            std::fs::read_to_string(&input).unwrap(),
            EIO,
            "the input is untouched"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
