//! String functions (`StrLen`, `StrPart`, `StrFind`, `StrMatch`, `StrMemb`, `StrMap`,
//! `ByteToStr`, `StrToByte`) over the runtime library's [`crate::functions::string`].

use super::{Ctx, Registry};
use crate::functions::string as s;
use crate::interp::value::Value;

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add("FUNC num StrLen(string Str)", |cx| {
        Ok(Value::Num(s::str_len(cx.str(0)?) as f32))
    });
    r.add(
        "FUNC string StrPart(string Str, num ChPos, num Len)",
        |cx| {
            let pos = cx.int(1, "ChPos")?;
            let len = cx.int(2, "Len")?;
            let text = cx.str(0)?;
            // ASCII text (the usual case): the part is a slice of the same bytes.
            if let Some(part) = s::ascii_part(text, pos, len) {
                return Ok(Value::str(part));
            }
            let out = s::str_part(text, pos, len).map_err(|e| cx.rt(e))?;
            cx.string(out)
        },
    );
    r.add(
        r"FUNC num StrFind(string Str, num ChPos, string Set, \switch NotInSet)",
        |cx| {
            let pos = cx.int(1, "ChPos")?;
            let n =
                s::str_find(cx.str(0)?, pos, cx.str(2)?, cx.present(3)).map_err(|e| cx.rt(e))?;
            Ok(Value::Num(n as f32))
        },
    );
    r.add(
        "FUNC num StrMatch(string Str, num ChPos, string Pattern)",
        |cx| {
            let pos = cx.int(1, "ChPos")?;
            let n = s::str_match(cx.str(0)?, pos, cx.str(2)?).map_err(|e| cx.rt(e))?;
            Ok(Value::Num(n as f32))
        },
    );
    r.add(
        "FUNC bool StrMemb(string Str, num ChPos, string Set)",
        |cx| {
            let pos = cx.int(1, "ChPos")?;
            let b = s::str_memb(cx.str(0)?, pos, cx.str(2)?).map_err(|e| cx.rt(e))?;
            Ok(Value::Bool(b))
        },
    );
    r.add(
        "FUNC string StrMap(string Str, string FromMap, string ToMap)",
        |cx| {
            let out = s::str_map(cx.str(0)?, cx.str(1)?, cx.str(2)?);
            cx.string(out)
        },
    );
    r.add(
        r"FUNC string ByteToStr(byte BitData, \switch Hex | switch Okt | switch Bin | switch Char)",
        |cx| {
            let b = cx.int(0, "BitData")?;
            let Ok(b) = u8::try_from(b) else {
                return Err(cx.error(
                    crate::interp::errnum::ERR_ARGVALERR,
                    format!("{b} is not a byte (0–255)"),
                ));
            };
            let f = format(cx, 1);
            cx.string(s::byte_to_str(b, f))
        },
    );
    r.add(
        r"FUNC byte StrToByte(string ConStr, \switch Hex | switch Okt | switch Bin | switch Char)",
        |cx| {
            let f = format(cx, 1);
            let b = s::str_to_byte(cx.str(0)?, f).map_err(|e| cx.rt(e))?;
            Ok(Value::Num(b as f32))
        },
    );
}

fn format(cx: &Ctx<'_>, first: usize) -> s::ByteFormat {
    let all = [
        s::ByteFormat::Hex,
        s::ByteFormat::Okt,
        s::ByteFormat::Bin,
        s::ByteFormat::Char,
    ];
    all.into_iter()
        .enumerate()
        .find(|(i, _)| cx.present(first + i))
        .map(|(_, f)| f)
        .unwrap_or_default()
}
