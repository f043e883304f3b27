//! Typed access to instance attributes for the domain readers, reporting bad values into the diagnostics.
//!
//! Each reader returns `Ok(None)` when the attribute is absent, `Ok(Some(..))` with the value
//! and its span, or `Err(())` after pushing a [`ConfigError::BadValue`]; [`keep`] folds that
//! into an `Option` and a "something failed" flag so a domain reader can report every problem
//! of an instance before leaving it out.

use crate::diag::Diagnostics;
use crate::source::{SourceId, Span};

use super::ConfigError;
use super::cfg::{CfgInstance, CfgValue};

/// A text attribute (quoted or bare), found under the first of `names` present; reports a
/// flag or a number.
pub(super) fn text_attr(
    src: SourceId,
    inst: &CfgInstance,
    names: &[&str],
    diags: &mut Diagnostics,
) -> Result<Option<(String, Span)>, ()> {
    let Some(attr) = names.iter().find_map(|n| inst.get(n)) else {
        return Ok(None);
    };
    match &attr.value {
        CfgValue::Str(s) | CfgValue::Word(s) => Ok(Some((s.clone(), attr.value_or_name_span()))),
        other => {
            diags.push(ConfigError::BadValue {
                src,
                span: attr.value_or_name_span(),
                name: attr.name.clone(),
                expected: "a quoted text".into(),
                found: found_text(other),
            });
            Err(())
        }
    }
}

/// How a value is shown in a "found …" label.
pub(super) fn found_text(v: &CfgValue) -> String {
    match v {
        CfgValue::Flag => "no value".into(),
        CfgValue::Str(s) => format!("\"{s}\""),
        CfgValue::Num(n) => format!("the number {n}"),
        CfgValue::Word(w) => format!("`{w}`"),
    }
}

/// A numeric attribute; reports anything else.
pub(super) fn num_attr(
    src: SourceId,
    inst: &CfgInstance,
    name: &str,
    diags: &mut Diagnostics,
) -> Result<Option<(f64, Span)>, ()> {
    let Some(attr) = inst.get(name) else {
        return Ok(None);
    };
    match attr.as_num() {
        Some(v) => Ok(Some((v, attr.value_or_name_span()))),
        None => {
            diags.push(ConfigError::BadValue {
                src,
                span: attr.value_or_name_span(),
                name: attr.name.clone(),
                expected: "a number".into(),
                found: found_text(&attr.value),
            });
            Err(())
        }
    }
}

/// A numeric attribute that must lie in `min..=max`; `what` describes the range for the
/// message (e.g. "a number 0 to 20").
pub(super) fn ranged_num_attr(
    src: SourceId,
    inst: &CfgInstance,
    name: &str,
    (min, max): (f64, f64),
    what: &str,
    diags: &mut Diagnostics,
) -> Result<Option<(f64, Span)>, ()> {
    let Some(attr) = inst.get(name) else {
        return Ok(None);
    };
    let span = attr.value_or_name_span();
    match attr.as_num() {
        Some(v) if (min..=max).contains(&v) => Ok(Some((v, span))),
        other => {
            let found = match other {
                Some(v) => format!("{v} is out of range"),
                None => found_text(&attr.value),
            };
            diags.push(ConfigError::BadValue {
                src,
                span,
                name: attr.name.clone(),
                expected: what.to_string(),
                found,
            });
            Err(())
        }
    }
}

/// An integer attribute in `min..=max` (for ports and levels).
pub(super) fn int_attr(
    src: SourceId,
    inst: &CfgInstance,
    names: &[&str],
    (min, max): (i64, i64),
    what: &str,
    diags: &mut Diagnostics,
) -> Result<Option<(i64, Span)>, ()> {
    let Some(attr) = names.iter().find_map(|n| inst.get(n)) else {
        return Ok(None);
    };
    let span = attr.value_or_name_span();
    let num = attr.as_num();
    // The range check keeps the cast exact: |v| is far below 2^53.
    let int = num.filter(|v| v.fract() == 0.0 && *v >= min as f64 && *v <= max as f64);
    match int {
        Some(v) => Ok(Some((v as i64, span))),
        None => {
            let found = match num {
                Some(v) if v.fract() != 0.0 => format!("{v} is not a whole number"),
                Some(v) => format!("{v} is out of range"),
                None => found_text(&attr.value),
            };
            diags.push(ConfigError::BadValue {
                src,
                span,
                name: attr.name.clone(),
                expected: what.to_string(),
                found,
            });
            Err(())
        }
    }
}

/// Warn about every attribute of `inst` that is in neither `used` nor `ignored`.
pub(super) fn warn_unknown(
    src: SourceId,
    section: &str,
    inst: &CfgInstance,
    known: &[&[&str]],
    diags: &mut Diagnostics,
) {
    for attr in &inst.attrs {
        let is_known = known
            .iter()
            .flat_map(|list| list.iter())
            .any(|k| k.eq_ignore_ascii_case(&attr.name));
        if !is_known {
            diags.push(ConfigError::UnknownAttribute {
                src,
                span: attr.name_span,
                name: attr.name.clone(),
                section: section.to_string(),
            });
        }
    }
}

/// Report that the required attribute `name` is missing from `inst` in `section`.
pub(super) fn missing_attr(
    src: SourceId,
    section: &str,
    inst: &CfgInstance,
    name: &str,
    diags: &mut Diagnostics,
) {
    diags.push(ConfigError::MissingAttribute {
        src,
        span: inst.span,
        name: name.to_string(),
        section: section.to_string(),
    });
}

/// The value of an attribute reader, noting a reported failure.
pub(super) fn keep<T>(r: Result<Option<T>, ()>, failed: &mut bool) -> Option<T> {
    r.unwrap_or_else(|()| {
        *failed = true;
        None
    })
}
