//! Raw data (`rawbytes`): `PackRawBytes`, `UnpackRawBytes`, `CopyRawBytes`, `ClearRawBytes`,
//! `RawBytesLen`, with the byte formats of `functions::raw_bytes`.
//!
//! A `rawbytes` value is the non-value record `[len, bytes]`: the number of valid bytes and
//! the bytes themselves as the characters U+0000–U+00FF of a string (so copying a record that
//! holds one shares the bytes instead of copying 1024 values).

use super::{Ctx, Registry};
use crate::functions::raw_bytes::{self as rb, IntFormat};
use crate::interp::errnum;
use crate::interp::error::{ErrorKind, Exec};
use crate::interp::value::{MAX_STRING, Value};

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add(
        r"PROC PackRawBytes(anytype Value, VAR rawbytes RawData, \switch Network, num StartIndex, \switch Hex1 | inttypes IntX | switch Float4 | switch ASCII)",
        pack,
    );
    r.add(
        r"PROC UnpackRawBytes(VAR rawbytes RawData, \switch Network, num StartIndex, VAR anytype Value, \switch Hex1 | inttypes IntX | switch Float4 | num ASCII)",
        unpack,
    );
    r.add(
        r"PROC CopyRawBytes(VAR rawbytes FromRawData, num FromIndex, VAR rawbytes ToRawData, num ToIndex, \num NoOfBytes)",
        |cx| {
            let from = raw_of(cx, 0)?;
            let mut to = raw_of(cx, 2)?;
            let (fi, ti, n) = (cx.f64(1)?, cx.f64(3)?, cx.opt_f64(4)?);
            rb::copy(&from, fi, &mut to, ti, n).map_err(|e| cx.rt(e))?;
            cx.set(2, raw_value(&to))?;
            Ok(Value::Absent)
        },
    );
    r.add(
        r"PROC ClearRawBytes(VAR rawbytes RawData, \num FromIndex)",
        |cx| {
            let mut raw = raw_of(cx, 0)?;
            let from = cx.opt_f64(1)?;
            rb::clear(&mut raw, from).map_err(|e| cx.rt(e))?;
            cx.set(0, raw_value(&raw))?;
            Ok(Value::Absent)
        },
    );
    r.add("FUNC num RawBytesLen(VAR rawbytes RawData)", |cx| {
        Ok(Value::Num(raw_of(cx, 0)?.len() as f32))
    });
}

/// The valid bytes of `rawbytes` argument `i`.
pub(crate) fn raw_of(cx: &Ctx<'_>, i: usize) -> Exec<Vec<u8>> {
    let v = cx.value(i)?;
    let Some([Value::Num(len), Value::Str(bytes)]) = v.fields() else {
        return Err(cx.it.type_bug(cx.span, "rawbytes", v));
    };
    let bytes: Option<Vec<u8>> = bytes
        .chars()
        .map(|c| u8::try_from(u32::from(c)).ok())
        .collect();
    match bytes {
        Some(b) if b.len() as f32 == *len && b.len() <= rb::CAPACITY => Ok(b),
        _ => Err(cx.it.fatal(
            ErrorKind::Host,
            cx.span,
            "the rawbytes data is damaged (its hidden components were changed); clear it \
             with ClearRawBytes",
        )),
    }
}

/// A `rawbytes` value holding `bytes` (at most 1024).
pub(crate) fn raw_value(bytes: &[u8]) -> Value {
    Value::Record(Box::new([
        Value::Num(bytes.len() as f32),
        Value::str(&rb::bytes_text(bytes)),
    ]))
}

/// Which of `\Hex1 | \IntX | \Float4 | \ASCII` (arguments `first` … `first + 3`) was given.
enum Format {
    Hex1,
    Int(IntFormat),
    Float4,
    Ascii,
}

fn format(cx: &Ctx<'_>, first: usize, func: &'static str) -> Exec<Format> {
    if cx.present(first) {
        Ok(Format::Hex1)
    } else if cx.present(first + 1) {
        let code = cx.f64(first + 1)?;
        IntFormat::from_code(func, code)
            .map(Format::Int)
            .map_err(|e| cx.rt(e))
    } else if cx.present(first + 2) {
        Ok(Format::Float4)
    } else if cx.present(first + 3) {
        Ok(Format::Ascii)
    } else {
        Err(cx.error(
            errnum::ERR_ARGVALERR,
            "one of \\Hex1, \\IntX, \\Float4 or \\ASCII must be given",
        ))
    }
}

fn pack(cx: &mut Ctx<'_>) -> Exec<Value> {
    const F: &str = "PackRawBytes";
    let network = cx.present(2);
    let start = cx.f64(3)?;
    let value = cx.value(0)?.clone();
    let number = |cx: &Ctx<'_>, what: &str| match &value {
        Value::Num(x) => Ok(*x as f64),
        Value::Dnum(x) => Ok(*x),
        _ => Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("{what} packs a num or dnum value"),
        )),
    };
    let bytes = match format(cx, 4, F)? {
        Format::Int(fmt) => {
            rb::int_bytes(F, number(cx, "\\IntX")?, fmt, network).map_err(|e| cx.rt(e))?
        }
        Format::Float4 => rb::float4_bytes(F, number(cx, "\\Float4")?, network)
            .map_err(|e| cx.rt(e))?
            .to_vec(),
        Format::Hex1 => match &value {
            Value::Num(x) => vec![rb::byte_of(F, *x as f64).map_err(|e| cx.rt(e))?],
            _ => {
                return Err(cx.error(errnum::ERR_ARGVALERR, "\\Hex1 packs a byte value"));
            }
        },
        Format::Ascii => match &value {
            Value::Str(s) => rb::text_bytes(F, s).map_err(|e| cx.rt(e))?,
            Value::Num(x) => vec![rb::byte_of(F, *x as f64).map_err(|e| cx.rt(e))?],
            _ => {
                return Err(cx.error(
                    errnum::ERR_ARGVALERR,
                    "\\ASCII packs a string or a byte value",
                ));
            }
        },
    };
    let mut raw = raw_of(cx, 1)?;
    rb::place(F, &mut raw, start, &bytes).map_err(|e| cx.rt(e))?;
    cx.set(1, raw_value(&raw))?;
    Ok(Value::Absent)
}

fn unpack(cx: &mut Ctx<'_>) -> Exec<Value> {
    const F: &str = "UnpackRawBytes";
    let raw = raw_of(cx, 0)?;
    let network = cx.present(1);
    let start = cx.f64(2)?;
    let target = cx.value(3)?.clone();
    let bytes = |cx: &Ctx<'_>, n: usize| {
        rb::take(F, &raw, start, n)
            .map(<[u8]>::to_vec)
            .map_err(|e| cx.rt(e))
    };
    let wrong = |cx: &Ctx<'_>, what: &str| {
        Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("{what} unpacks into {}", describe(&target)),
        ))
    };
    let new = match format(cx, 4, F)? {
        Format::Int(fmt) => {
            let v = rb::int_value(&bytes(cx, fmt.size)?, fmt, network);
            match &target {
                Value::Num(_) => Value::Num(rb::int_as_num(F, v).map_err(|e| cx.rt(e))?),
                Value::Dnum(_) => Value::Dnum(rb::int_as_dnum(F, v).map_err(|e| cx.rt(e))?),
                _ => return wrong(cx, "\\IntX needs a num or dnum; it cannot unpack"),
            }
        }
        Format::Float4 => {
            let f = rb::float4_value(F, &bytes(cx, 4)?, network).map_err(|e| cx.rt(e))?;
            match &target {
                Value::Num(_) => Value::Num(f),
                Value::Dnum(_) => Value::Dnum(f as f64),
                _ => return wrong(cx, "\\Float4 needs a num or dnum; it cannot unpack"),
            }
        }
        Format::Hex1 => match &target {
            Value::Num(_) => Value::Num(f32::from(bytes(cx, 1)?.first().copied().unwrap_or(0))),
            _ => return wrong(cx, "\\Hex1 needs a byte; it cannot unpack"),
        },
        Format::Ascii => {
            let n = cx.f64(7)?;
            if n.fract() != 0.0 || !(1.0..=MAX_STRING as f64).contains(&n) {
                return Err(cx.error(
                    errnum::ERR_ARGVALERR,
                    format!("\\ASCII:={n} is not a number of characters 1–{MAX_STRING}"),
                ));
            }
            let b = bytes(cx, n as usize)?;
            match &target {
                Value::Str(_) => Value::str(&rb::bytes_text(&b)),
                Value::Num(_) if b.len() == 1 => {
                    Value::Num(f32::from(b.first().copied().unwrap_or(0)))
                }
                Value::Num(_) => {
                    return Err(cx.error(
                        errnum::ERR_ARGVALERR,
                        "\\ASCII unpacks 1 character into a byte",
                    ));
                }
                _ => return wrong(cx, "\\ASCII needs a string or a byte; it cannot unpack"),
            }
        }
    };
    cx.set(3, new)?;
    Ok(Value::Absent)
}

fn describe(v: &Value) -> &'static str {
    match v {
        Value::Num(_) => "a num",
        Value::Dnum(_) => "a dnum",
        Value::Bool(_) => "a bool",
        Value::Str(_) => "a string",
        Value::Record(_) => "a record",
        Value::Array(_) => "an array",
        Value::Absent => "an absent value",
    }
}
