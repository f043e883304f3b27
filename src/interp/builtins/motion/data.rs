//! RAPID motion data (`robtarget`, `jointtarget`, `speeddata`, `zonedata`, `tooldata`,
//! `wobjdata`, `loaddata`) to and from the domain types of [`crate::robot::command`].

use crate::interp::builtins::Ctx;
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::value::Value;
use crate::robot::command::{JointTarget, RobTarget, SpeedData, ZoneData};
use crate::robot::{ConfData, JointsDeg, LoadData, Pose, ToolData, WobjData, pose_from_pos_quat};

/// How far the length of a programmed quaternion may be from 1 (the stored decimals of taught
/// orientations stay far inside this; a typo or an all-zero `orient` does not).
pub const QUAT_NORM_TOLERANCE: f64 = 1e-3;

/// The components of a record value, or an internal error naming the expected type.
fn fields<'v>(cx: &Ctx<'_>, v: &'v Value, what: &str) -> Exec<&'v [Value]> {
    v.fields().ok_or_else(|| cx.it.type_bug(cx.span, what, v))
}

fn field<'v>(cx: &Ctx<'_>, f: &'v [Value], i: usize, what: &str, whole: &Value) -> Exec<&'v Value> {
    f.get(i).ok_or_else(|| cx.it.type_bug(cx.span, what, whole))
}

fn nums<const N: usize>(cx: &Ctx<'_>, v: &Value, what: &str) -> Exec<[f64; N]> {
    v.num_fields::<N>()
        .ok_or_else(|| cx.it.type_bug(cx.span, what, v))
}

fn boolean(cx: &Ctx<'_>, v: &Value, what: &str) -> Exec<bool> {
    v.as_bool().ok_or_else(|| cx.it.type_bug(cx.span, what, v))
}

/// An `orient` checked for a usable length (else `ERR_ILLQUAT`).
fn orient(cx: &Ctx<'_>, v: &Value, what: &str) -> Exec<[f64; 4]> {
    let q = nums::<4>(cx, v, "orient")?;
    let norm = q.iter().map(|c| c * c).sum::<f64>().sqrt();
    if !norm.is_finite() || (norm - 1.0).abs() > QUAT_NORM_TOLERANCE {
        return Err(cx.error(
            errnum::ERR_ILLQUAT,
            format!(
                "the orientation of the {what} is not normalised: [{}, {}, {}, {}] has length {norm:.5} (q1² + q2² + q3² + q4² must be 1)",
                q[0], q[1], q[2], q[3]
            ),
        ));
    }
    Ok(q)
}

/// A `pose` value (`[trans, rot]`).
pub fn pose(cx: &Ctx<'_>, v: &Value, what: &str) -> Exec<Pose> {
    let f = fields(cx, v, "pose")?;
    let trans = nums::<3>(cx, field(cx, f, 0, "pose", v)?, "pos")?;
    let rot = orient(cx, field(cx, f, 1, "pose", v)?, what)?;
    Ok(pose_from_pos_quat(trans, rot))
}

/// A `robtarget` value.
pub fn robtarget(cx: &Ctx<'_>, v: &Value) -> Exec<RobTarget> {
    let f = fields(cx, v, "robtarget")?;
    let trans = nums::<3>(cx, field(cx, f, 0, "robtarget", v)?, "pos")?;
    let rot = orient(cx, field(cx, f, 1, "robtarget", v)?, "robtarget")?;
    let conf = nums::<4>(cx, field(cx, f, 2, "robtarget", v)?, "confdata")?;
    let extax = nums::<6>(cx, field(cx, f, 3, "robtarget", v)?, "extjoint")?;
    let mut cf = [0i32; 4];
    for (c, x) in cf.iter_mut().zip(conf) {
        if x.fract() != 0.0 || !x.is_finite() || x.abs() > 1e6 {
            return Err(cx.error(
                errnum::ERR_ARGVALERR,
                format!("the confdata of the robtarget must hold integers, not {x}"),
            ));
        }
        *c = x as i32;
    }
    Ok(RobTarget {
        trans,
        rot,
        robconf: ConfData::from_array(cf),
        extax,
    })
}

/// A `jointtarget` value.
pub fn jointtarget(cx: &Ctx<'_>, v: &Value) -> Exec<JointTarget> {
    let f = fields(cx, v, "jointtarget")?;
    let robax = nums::<6>(cx, field(cx, f, 0, "jointtarget", v)?, "robjoint")?;
    let extax = nums::<6>(cx, field(cx, f, 1, "jointtarget", v)?, "extjoint")?;
    Ok(JointTarget { robax, extax })
}

/// A `speeddata` value.
pub fn speeddata(cx: &Ctx<'_>, v: &Value) -> Exec<SpeedData> {
    let [v_tcp, v_ori, v_leax, v_reax] = nums::<4>(cx, v, "speeddata")?;
    Ok(SpeedData {
        v_tcp,
        v_ori,
        v_leax,
        v_reax,
    })
}

/// A `zonedata` value.
pub fn zonedata(cx: &Ctx<'_>, v: &Value) -> Exec<ZoneData> {
    let f = fields(cx, v, "zonedata")?;
    let finep = boolean(cx, field(cx, f, 0, "zonedata", v)?, "bool")?;
    let mut z = [0.0; 6];
    for (k, slot) in z.iter_mut().enumerate() {
        let x = field(cx, f, k + 1, "zonedata", v)?;
        *slot = x
            .as_f64()
            .ok_or_else(|| cx.it.type_bug(cx.span, "num", x))?;
    }
    Ok(ZoneData {
        finep,
        pzone_tcp: z[0],
        pzone_ori: z[1],
        pzone_eax: z[2],
        zone_ori: z[3],
        zone_leax: z[4],
        zone_reax: z[5],
    })
}

/// A `loaddata` value.
pub fn loaddata(cx: &Ctx<'_>, v: &Value) -> Exec<LoadData> {
    let f = fields(cx, v, "loaddata")?;
    let num = |i: usize| -> Exec<f64> {
        let x = field(cx, f, i, "loaddata", v)?;
        x.as_f64().ok_or_else(|| cx.it.type_bug(cx.span, "num", x))
    };
    let mass = num(0)?;
    let cog = nums::<3>(cx, field(cx, f, 1, "loaddata", v)?, "pos")?;
    let aom = nums::<4>(cx, field(cx, f, 2, "loaddata", v)?, "orient")?;
    Ok(LoadData {
        mass,
        cog,
        aom,
        ix: num(3)?,
        iy: num(4)?,
        iz: num(5)?,
    })
}

/// A `tooldata` value.
pub fn tooldata(cx: &Ctx<'_>, v: &Value) -> Exec<ToolData> {
    let f = fields(cx, v, "tooldata")?;
    Ok(ToolData {
        robhold: boolean(cx, field(cx, f, 0, "tooldata", v)?, "bool")?,
        tframe: pose(cx, field(cx, f, 1, "tooldata", v)?, "tool frame")?,
        load: loaddata(cx, field(cx, f, 2, "tooldata", v)?)?,
    })
}

/// A `wobjdata` value.
pub fn wobjdata(cx: &Ctx<'_>, v: &Value) -> Exec<WobjData> {
    let f = fields(cx, v, "wobjdata")?;
    let ufmec = field(cx, f, 2, "wobjdata", v)?;
    Ok(WobjData {
        robhold: boolean(cx, field(cx, f, 0, "wobjdata", v)?, "bool")?,
        ufprog: boolean(cx, field(cx, f, 1, "wobjdata", v)?, "bool")?,
        ufmec: ufmec
            .as_str()
            .ok_or_else(|| cx.it.type_bug(cx.span, "string", ufmec))?
            .to_string(),
        uframe: pose(cx, field(cx, f, 3, "wobjdata", v)?, "user frame")?,
        oframe: pose(cx, field(cx, f, 4, "wobjdata", v)?, "object frame")?,
    })
}

/// Optional `\Tool` argument `i` (`tool0` when absent).
pub fn opt_tool(cx: &Ctx<'_>, i: usize) -> Exec<ToolData> {
    if cx.present(i) {
        tooldata(cx, cx.value(i)?)
    } else {
        Ok(ToolData::tool0())
    }
}

/// Optional `\WObj` argument `i` (`wobj0` when absent).
pub fn opt_wobj(cx: &Ctx<'_>, i: usize) -> Exec<WobjData> {
    if cx.present(i) {
        wobjdata(cx, cx.value(i)?)
    } else {
        Ok(WobjData::wobj0())
    }
}

/// `extjoint` with every axis unused.
fn extax_value(e: &[f64; 6]) -> Value {
    Value::num_record(e)
}

/// A `robtarget` value from the domain type.
pub fn robtarget_value(t: &RobTarget) -> Value {
    let c = t.robconf.to_array().map(f64::from);
    Value::Record(Box::new([
        Value::num_record(&t.trans),
        Value::num_record(&t.rot),
        Value::num_record(&c),
        extax_value(&t.extax),
    ]))
}

/// A `jointtarget` value (unused external axes).
pub fn jointtarget_value(j: &JointsDeg) -> Value {
    Value::Record(Box::new([
        Value::num_record(j),
        extax_value(&crate::robot::command::EXTAX_NONE),
    ]))
}
