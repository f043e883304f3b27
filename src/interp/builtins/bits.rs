//! Bits, number bases and digit strings: `BitAnd` … `BitCheck` and their `…Dnum` forms,
//! `BitSet`/`BitClear` (on a `byte` or a `dnum` variable), `DecToHex`, `HexToDec`,
//! `StrDigCalc`, `StrDigCmp`, `StrOrder`, and the semaphore `TestAndSet`. The rules are in
//! `crate::functions::bits`, `crate::functions::digits` and `crate::functions::string`.

use super::{Ctx, Registry};
use crate::functions::bits::{self, Width};
use crate::functions::digits::{self, DigitError};
use crate::functions::string::str_order;
use crate::interp::errnum;
use crate::interp::error::{Exec, Unwind};
use crate::interp::value::Value;

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add("FUNC byte BitAnd(byte BitData1, byte BitData2)", |cx| {
        binary(cx, Width::Byte, |a, b| a & b)
    });
    r.add("FUNC dnum BitAndDnum(dnum Value1, dnum Value2)", |cx| {
        binary(cx, Width::Dnum, |a, b| a & b)
    });
    r.add("FUNC byte BitOr(byte BitData1, byte BitData2)", |cx| {
        binary(cx, Width::Byte, |a, b| a | b)
    });
    r.add("FUNC dnum BitOrDnum(dnum Value1, dnum Value2)", |cx| {
        binary(cx, Width::Dnum, |a, b| a | b)
    });
    r.add("FUNC byte BitXOr(byte BitData1, byte BitData2)", |cx| {
        binary(cx, Width::Byte, |a, b| a ^ b)
    });
    r.add("FUNC dnum BitXOrDnum(dnum Value1, dnum Value2)", |cx| {
        binary(cx, Width::Dnum, |a, b| a ^ b)
    });
    r.add("FUNC byte BitNeg(byte BitData)", |cx| {
        let a = operand(cx, Width::Byte, 0)?;
        Ok(result(Width::Byte, bits::neg(Width::Byte, a)))
    });
    r.add("FUNC dnum BitNegDnum(dnum Value)", |cx| {
        let a = operand(cx, Width::Dnum, 0)?;
        Ok(result(Width::Dnum, bits::neg(Width::Dnum, a)))
    });
    r.add("FUNC byte BitLSh(byte BitData, num ShiftSteps)", |cx| {
        shift(cx, Width::Byte, true)
    });
    r.add("FUNC dnum BitLShDnum(dnum Value, num ShiftSteps)", |cx| {
        shift(cx, Width::Dnum, true)
    });
    r.add("FUNC byte BitRSh(byte BitData, num ShiftSteps)", |cx| {
        shift(cx, Width::Byte, false)
    });
    r.add("FUNC dnum BitRShDnum(dnum Value, num ShiftSteps)", |cx| {
        shift(cx, Width::Dnum, false)
    });
    r.add("FUNC bool BitCheck(byte BitData, num BitPos)", |cx| {
        let (a, pos) = with_pos(cx, Width::Byte)?;
        Ok(Value::Bool(bits::check(a, pos)))
    });
    r.add("FUNC bool BitCheckDnum(dnum Value, num BitPos)", |cx| {
        let (a, pos) = with_pos(cx, Width::Dnum)?;
        Ok(Value::Bool(bits::check(a, pos)))
    });
    // `BitSet BitData | DnumData, BitPos`: one instruction for a byte or a dnum variable.
    r.add("PROC BitSet(INOUT anynum BitData, num BitPos)", |cx| {
        set_bit(cx, bits::set)
    });
    r.add("PROC BitClear(INOUT anynum BitData, num BitPos)", |cx| {
        set_bit(cx, bits::clear)
    });
    r.add("FUNC string DecToHex(string Str)", |cx| {
        let s = bits::dec_to_hex(cx.str(0)?).map_err(|e| cx.rt(e))?;
        cx.string(s)
    });
    r.add("FUNC string HexToDec(string Str)", |cx| {
        let s = bits::hex_to_dec(cx.str(0)?).map_err(|e| cx.rt(e))?;
        cx.string(s)
    });
    r.add(
        "FUNC stringdig StrDigCalc(stringdig StrDig1, opcalc Operation, stringdig StrDig2)",
        |cx| {
            let r = digits::calc(cx.str(0)?, cx.f64(1)?, cx.str(2)?);
            let s = r.map_err(|e| digit_error(cx, e))?;
            cx.string(s)
        },
    );
    r.add(
        "FUNC bool StrDigCmp(stringdig StrDig1, opnum Relation, stringdig StrDig2)",
        |cx| {
            let r = digits::compare(cx.str(0)?, cx.f64(1)?, cx.str(2)?);
            r.map(Value::Bool).map_err(|e| digit_error(cx, e))
        },
    );
    r.add(
        "FUNC bool StrOrder(string Str1, string Str2, string Order)",
        |cx| Ok(Value::Bool(str_order(cx.str(0)?, cx.str(1)?, cx.str(2)?))),
    );
    // Nothing runs between the test and the set: only one task runs at a time, and a task
    // hands the processor over only between statements or while it waits.
    r.add("FUNC bool TestAndSet(INOUT bool Object)", |cx| {
        let taken = cx.bool(0)?;
        if !taken {
            cx.set(0, Value::Bool(true))?;
        }
        Ok(Value::Bool(!taken))
    });
}

fn operand(cx: &Ctx<'_>, w: Width, i: usize) -> Exec<u64> {
    bits::operand(w, cx.f64(i)?, func(cx)).map_err(|e| cx.rt(e))
}

/// The native's name as a `'static` text for runtime-library errors.
fn func(cx: &Ctx<'_>) -> &'static str {
    const NAMES: &[&str] = &[
        "BitAnd",
        "BitAndDnum",
        "BitOr",
        "BitOrDnum",
        "BitXOr",
        "BitXOrDnum",
        "BitNeg",
        "BitNegDnum",
        "BitLSh",
        "BitLShDnum",
        "BitRSh",
        "BitRShDnum",
        "BitCheck",
        "BitCheckDnum",
        "BitSet",
        "BitClear",
    ];
    NAMES
        .iter()
        .find(|n| n.eq_ignore_ascii_case(cx.name()))
        .copied()
        .unwrap_or("bit operation")
}

fn result(w: Width, x: u64) -> Value {
    match w {
        Width::Byte => Value::Num(x as f32),
        Width::Dnum => Value::Dnum(x as f64),
    }
}

fn binary(cx: &mut Ctx<'_>, w: Width, f: fn(u64, u64) -> u64) -> Exec<Value> {
    let a = operand(cx, w, 0)?;
    let b = operand(cx, w, 1)?;
    Ok(result(w, f(a, b)))
}

fn shift(cx: &mut Ctx<'_>, w: Width, left: bool) -> Exec<Value> {
    let a = operand(cx, w, 0)?;
    let n = bits::shift(w, cx.f64(1)?, func(cx)).map_err(|e| cx.rt(e))?;
    Ok(result(
        w,
        if left {
            bits::lsh(w, a, n)
        } else {
            bits::rsh(a, n)
        },
    ))
}

/// The operand (argument 0) and bit position (argument 1) of `w`.
fn with_pos(cx: &Ctx<'_>, w: Width) -> Exec<(u64, u32)> {
    let a = operand(cx, w, 0)?;
    let pos = bits::bit_pos(w, cx.f64(1)?, func(cx)).map_err(|e| cx.rt(e))?;
    Ok((a, pos))
}

fn set_bit(cx: &mut Ctx<'_>, f: fn(u64, u32) -> u64) -> Exec<Value> {
    let w = match cx.value(0)? {
        Value::Dnum(_) => Width::Dnum,
        _ => Width::Byte,
    };
    let (a, pos) = with_pos(cx, w)?;
    cx.set(0, result(w, f(a, pos)))?;
    Ok(Value::Absent)
}

fn digit_error(cx: &Ctx<'_>, e: DigitError) -> Unwind {
    let num = errnum::by_name(e.err_name()).map_or(errnum::ERR_ARGVALERR, |d| d.num);
    cx.error(num, format!("{}: {e}", cx.name()))
}
