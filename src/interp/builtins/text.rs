//! Text output and conversion: `TPWrite`, `TPErase`, `ValToStr`, `NumToStr`, `DnumToStr`,
//! `StrToVal`, with the number formatting of [`crate::functions::format`].

use super::{Ctx, Registry};
use crate::functions::format as f;
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::host::Output;
use crate::interp::value::{MAX_STRING, Value};

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add(
        r"PROC TPWrite(string String, \num Num | dnum Dnum | bool Bool | pos Pos | orient Orient)",
        tp_write,
    );
    r.add("PROC TPErase()", |cx| {
        cx.host().output(Output::TpErase);
        Ok(Value::Absent)
    });
    r.add("FUNC string ValToStr(anytype Val)", |cx| {
        let s = val_to_str(cx.value(0)?);
        cx.string(s)
    });
    r.add(
        r"FUNC string NumToStr(num Val, num Dec, \switch Exp)",
        |cx| {
            let dec = cx.int(1, "Dec")?.clamp(-1, 99) as i32;
            let x = cx.num(0)?;
            if !cx.present(2)
                && let Some(s) = int_to_str(x, dec)
            {
                return Ok(Value::Str(s.into()));
            }
            let s = f::num_to_str(x, dec, cx.present(2)).map_err(|e| cx.rt(e))?;
            cx.string(s)
        },
    );
    r.add(
        r"FUNC string DnumToStr(dnum Val, num Dec, \switch Exp)",
        |cx| {
            let dec = cx.int(1, "Dec")?.clamp(-1, 99) as i32;
            let s = f::dnum_to_str(cx.f64(0)?, dec, cx.present(2)).map_err(|e| cx.rt(e))?;
            cx.string(s)
        },
    );
    r.add("FUNC bool StrToVal(string Str, VAR anytype Val)", |cx| {
        let Some(lit) = f::parse_value(cx.str(0)?) else {
            return Ok(Value::Bool(false));
        };
        let mut v = cx.value(1)?.clone();
        if !fill(&mut v, &lit) {
            return Ok(Value::Bool(false));
        }
        cx.set(1, v)?;
        Ok(Value::Bool(true))
    });
}

/// The text of string argument `text` followed by the value of the first present of the
/// alternatives `\Num | \Dnum | \Bool | \Pos | \Orient` starting at argument `alt`
/// (`TPWrite`, `Write`).
pub(super) fn compose(cx: &Ctx<'_>, text: usize, alt: usize) -> Exec<String> {
    let mut s = cx.str(text)?.to_string();
    if cx.present(alt) {
        s.push_str(&f::format_num(cx.num(alt)?));
    } else if cx.present(alt + 1) {
        s.push_str(&f::format_dnum(cx.f64(alt + 1)?));
    } else if cx.present(alt + 2) {
        s.push_str(f::format_bool(cx.bool(alt + 2)?));
    } else if cx.present(alt + 3) {
        s.push_str(&val_to_str(cx.value(alt + 3)?));
    } else if cx.present(alt + 4) {
        s.push_str(&val_to_str(cx.value(alt + 4)?));
    }
    Ok(s)
}

fn tp_write(cx: &mut Ctx<'_>) -> Exec<Value> {
    let s = compose(cx, 0, 1)?;
    let n = s.chars().count();
    if n > MAX_STRING {
        return Err(cx.error(
            errnum::ERR_STRTOOLNG,
            format!("TPWrite text of {n} characters (at most {MAX_STRING})"),
        ));
    }
    cx.host().output(Output::TpWrite(s));
    Ok(Value::Absent)
}

/// `NumToStr(x, dec)` without `\Exp` for an integer `x` below 2^24 in magnitude (where the
/// shortest decimal of the `num` is the integer itself), written directly: the common
/// case, the same text as [`f::num_to_str`].
pub(crate) fn int_to_str(x: f32, dec: i32) -> Option<String> {
    use std::fmt::Write;
    if !(0..=8).contains(&dec) || x.fract() != 0.0 || x.abs() >= 16_777_216.0 {
        return None;
    }
    let mut s = String::with_capacity(16);
    let _ = write!(s, "{}", x as i32);
    if dec > 0 {
        s.push('.');
        for _ in 0..dec {
            s.push('0');
        }
    }
    Some(s)
}

/// A value as ValToStr writes it.
pub(crate) fn val_to_str(v: &Value) -> String {
    match v {
        Value::Num(x) => f::format_num(*x),
        Value::Dnum(x) => f::format_dnum(*x),
        Value::Bool(b) => f::format_bool(*b).to_string(),
        Value::Str(s) => f::quote_string(s),
        Value::Record(fs) => f::format_list(fs.iter().map(val_to_str)),
        Value::Array(a) => f::format_list(a.data.iter().map(val_to_str)),
        Value::Absent => String::new(),
    }
}

/// Overwrite `target` with a parsed literal of the same shape (StrToVal); false when the
/// shapes or ranges differ.
pub(crate) fn fill(target: &mut Value, lit: &f::LitValue) -> bool {
    match target {
        Value::Num(x) => match lit.as_num() {
            Some(v) => {
                *x = v;
                true
            }
            None => false,
        },
        Value::Dnum(x) => match lit.as_dnum() {
            Some(v) => {
                *x = v;
                true
            }
            None => false,
        },
        Value::Bool(x) => match lit.as_bool() {
            Some(v) => {
                *x = v;
                true
            }
            None => false,
        },
        Value::Str(x) => match lit.as_str() {
            Some(v) if v.chars().count() <= MAX_STRING => {
                *x = v.into();
                true
            }
            _ => false,
        },
        Value::Record(fs) => match lit.as_list() {
            Some(items) if items.len() == fs.len() => {
                fs.iter_mut().zip(items).all(|(f, l)| fill(f, l))
            }
            _ => false,
        },
        Value::Array(a) => {
            let mut flat = Vec::new();
            flatten(lit, a.rank as usize, &mut flat);
            flat.len() == a.data.len() && a.data.iter_mut().zip(flat).all(|(v, l)| fill(v, l))
        }
        Value::Absent => false,
    }
}

fn flatten<'a>(lit: &'a f::LitValue, depth: usize, out: &mut Vec<&'a f::LitValue>) {
    match lit.as_list() {
        Some(items) if depth > 0 => {
            for i in items {
                flatten(i, depth - 1, out);
            }
        }
        _ => out.push(lit),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integer_num_to_str_is_the_runtime_library_text() {
        let mut xs: Vec<f32> = (-3000..3000).map(|i| i as f32).collect();
        xs.extend([-0.0, 16_777_215.0, -16_777_215.0, 1_000_000.0, 8_388_608.0]);
        for x in xs {
            for dec in 0..=8 {
                let fast = int_to_str(x, dec).expect("an integer below 2^24");
                assert_eq!(Ok(fast), f::num_to_str(x, dec, false), "{x} {dec}");
            }
        }
        assert_eq!(int_to_str(0.5, 0), None);
        assert_eq!(int_to_str(16_777_216.0, 0), None);
        assert_eq!(int_to_str(3.0, -1), None);
    }
}
