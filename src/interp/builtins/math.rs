//! Arithmetic functions (`Abs`, `Round`, `Trunc`, `Sqrt`, `Pow`, `Exp`, trigonometry in
//! degrees, num/dnum conversions) over the runtime library's [`crate::functions::math`].

use super::{Ctx, Registry};
use crate::functions::math as m;
use crate::interp::error::Exec;
use crate::interp::value::Value;

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add("FUNC num Abs(num Input)", |cx| {
        cx.num_result(m::abs(cx.f64(0)?))
    });
    r.add("FUNC dnum AbsDnum(dnum Input)", |cx| {
        Ok(Value::Dnum(m::abs(cx.f64(0)?)))
    });
    r.add(r"FUNC num Round(num Val, \num Dec)", |cx| {
        let dec = dec(cx, 1)?;
        let x = cx.num(0)?;
        if let Some(r) = whole(x, dec, f32::round) {
            return Ok(Value::Num(r));
        }
        m::round_num(x, dec).map(Value::Num).map_err(|e| cx.rt(e))
    });
    r.add(r"FUNC num Trunc(num Val, \num Dec)", |cx| {
        let dec = dec(cx, 1)?;
        let x = cx.num(0)?;
        if let Some(r) = whole(x, dec, f32::trunc) {
            return Ok(Value::Num(r));
        }
        m::trunc_num(x, dec).map(Value::Num).map_err(|e| cx.rt(e))
    });
    r.add(r"FUNC dnum RoundDnum(dnum Val, \num Dec)", |cx| {
        let dec = dec(cx, 1)?;
        m::round_dnum(cx.f64(0)?, dec)
            .map(Value::Dnum)
            .map_err(|e| cx.rt(e))
    });
    r.add(r"FUNC dnum TruncDnum(dnum Val, \num Dec)", |cx| {
        let dec = dec(cx, 1)?;
        m::trunc_dnum(cx.f64(0)?, dec)
            .map(Value::Dnum)
            .map_err(|e| cx.rt(e))
    });
    r.add("FUNC num Sqrt(num Value)", |cx| unary(cx, m::sqrt));
    r.add("FUNC dnum SqrtDnum(dnum Value)", |cx| unary_d(cx, m::sqrt));
    r.add("FUNC num Exp(num Exponent)", |cx| unary(cx, m::exp));
    r.add("FUNC num Pow(num Base, num Exponent)", |cx| {
        let x = m::pow(cx.f64(0)?, cx.f64(1)?).map_err(|e| cx.rt(e))?;
        cx.num_result(x)
    });
    r.add("FUNC dnum PowDnum(dnum Base, dnum Exponent)", |cx| {
        let x = m::pow(cx.f64(0)?, cx.f64(1)?).map_err(|e| cx.rt(e))?;
        Ok(Value::Dnum(x))
    });
    r.add("FUNC num Sin(num Angle)", |cx| unary(cx, m::sin));
    r.add("FUNC num Cos(num Angle)", |cx| unary(cx, m::cos));
    r.add("FUNC num Tan(num Angle)", |cx| unary(cx, m::tan));
    r.add("FUNC num ASin(num Value)", |cx| unary(cx, m::asin));
    r.add("FUNC num ACos(num Value)", |cx| unary(cx, m::acos));
    r.add("FUNC num ATan(num Value)", |cx| unary(cx, m::atan));
    r.add("FUNC num ATan2(num Y, num X)", |cx| {
        let x = m::atan2(cx.f64(0)?, cx.f64(1)?).map_err(|e| cx.rt(e))?;
        cx.num_result(x)
    });
    r.add("FUNC dnum NumToDnum(num Value)", |cx| {
        Ok(Value::Dnum(cx.f64(0)?))
    });
    r.add(r"FUNC num DnumToNum(dnum Value, \switch Integer)", |cx| {
        let v = cx.f64(0)?;
        if cx.present(1) && v.fract() != 0.0 {
            return Err(cx.error(
                crate::interp::errnum::ERR_INT_NOTVAL,
                format!("{v} is not an integer"),
            ));
        }
        cx.num_result(v)
    });
}

/// `Round`/`Trunc` to no decimals of a `num` below 2^23 in magnitude, where the runtime
/// library's decimal rule gives what `f` gives: the shortest decimal of such a number
/// lies on the same side of every integer and every half-integer as the number itself.
/// A zero result is +0 (as the library's).
pub(crate) fn whole(x: f32, dec: i32, f: fn(f32) -> f32) -> Option<f32> {
    (dec == 0 && x.abs() < 8_388_608.0).then(|| f(x) + 0.0)
}

fn dec(cx: &Ctx<'_>, i: usize) -> Exec<i32> {
    Ok(match cx.opt_f64(i)? {
        Some(d) => d.clamp(i32::MIN as f64, i32::MAX as f64) as i32,
        None => 0,
    })
}

fn unary(cx: &mut Ctx<'_>, f: fn(f64) -> crate::functions::RtResult<f64>) -> Exec<Value> {
    let x = f(cx.f64(0)?).map_err(|e| cx.rt(e))?;
    cx.num_result(x)
}

fn unary_d(cx: &mut Ctx<'_>, f: fn(f64) -> crate::functions::RtResult<f64>) -> Exec<Value> {
    let x = f(cx.f64(0)?).map_err(|e| cx.rt(e))?;
    Ok(Value::Dnum(x))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whole_numbers_are_the_runtime_library_results() {
        let mut xs: Vec<f32> = (-2000..2000).map(|i| i as f32 * 0.25).collect();
        let mut s = 0x1234_5678_u32;
        for _ in 0..50_000 {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            let x = f32::from_bits(s);
            if x.is_finite() {
                xs.push(x);
            }
            xs.push((s % 20_000_000) as f32 / 7.0 - 1_000_000.0);
        }
        xs.extend([-0.0, -0.4, -0.5, 0.4]);
        for k in [0.5f32, 1.5, 2.5, 8_388_607.5, 4_194_303.5] {
            for x in [
                k,
                -k,
                f32::from_bits(k.to_bits() - 1),
                f32::from_bits(k.to_bits() + 1),
            ] {
                xs.push(x);
            }
        }
        for x in xs {
            let bits = |r: crate::functions::RtResult<f32>| r.map(f32::to_bits);
            if let Some(r) = whole(x, 0, f32::round) {
                assert_eq!(Ok(r.to_bits()), bits(m::round_num(x, 0)), "Round({x})");
            }
            if let Some(r) = whole(x, 0, f32::trunc) {
                assert_eq!(Ok(r.to_bits()), bits(m::trunc_num(x, 0)), "Trunc({x})");
            }
        }
    }
}
