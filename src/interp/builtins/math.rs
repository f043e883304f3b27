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
        m::round_num(cx.num(0)?, dec)
            .map(Value::Num)
            .map_err(|e| cx.rt(e))
    });
    r.add(r"FUNC num Trunc(num Val, \num Dec)", |cx| {
        let dec = dec(cx, 1)?;
        m::trunc_num(cx.num(0)?, dec)
            .map(Value::Num)
            .map_err(|e| cx.rt(e))
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
