//! Frame and vector functions (`Offs`, `RelTool`, `OrientZYX`, `EulerZYX`, `PoseMult`,
//! `PoseInv`, `PoseVect`, `NOrient`, `Distance`, `VectMagn`, `DotProd`, `CrossProd`) over
//! the runtime library's [`crate::functions::pose`].

use super::{Ctx, Registry};
use crate::functions::pose::{self as p, Pose};
use crate::interp::error::Exec;
use crate::interp::value::Value;

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add(
        "FUNC robtarget Offs(robtarget Point, num XOffset, num YOffset, num ZOffset)",
        |cx| {
            let mut point = cx.value(0)?.clone();
            let t = target_pose(cx, &point)?;
            let moved = p::offs(&t.trans, cx.f64(1)?, cx.f64(2)?, cx.f64(3)?);
            set_pose(&mut point, &moved, None);
            Ok(point)
        },
    );
    r.add(
        r"FUNC robtarget RelTool(robtarget Point, num Dx, num Dy, num Dz, \num Rx, \num Ry, \num Rz)",
        |cx| {
            let mut point = cx.value(0)?.clone();
            let t = target_pose(cx, &point)?;
            let d = [cx.f64(1)?, cx.f64(2)?, cx.f64(3)?];
            let rx = cx.opt_f64(4)?.unwrap_or(0.0);
            let ry = cx.opt_f64(5)?.unwrap_or(0.0);
            let rz = cx.opt_f64(6)?.unwrap_or(0.0);
            let n = p::rel_tool(&t, &d, rx, ry, rz).map_err(|e| cx.rt(e))?;
            set_pose(&mut point, &n.trans, Some(&n.rot));
            Ok(point)
        },
    );
    r.add(
        "FUNC orient OrientZYX(num ZAngle, num YAngle, num XAngle)",
        |cx| {
            let q = p::orient_zyx(cx.f64(0)?, cx.f64(1)?, cx.f64(2)?).map_err(|e| cx.rt(e))?;
            Ok(Value::num_record(&q))
        },
    );
    r.add(
        r"FUNC num EulerZYX(\switch X | switch Y | switch Z, orient Rotation)",
        |cx| {
            let axis = if cx.present(0) {
                p::EulerAxis::X
            } else if cx.present(1) {
                p::EulerAxis::Y
            } else {
                p::EulerAxis::Z
            };
            let q = cx.nums::<4>(3)?;
            let a = p::euler_zyx(axis, &q).map_err(|e| cx.rt(e))?;
            cx.num_result(a)
        },
    );
    r.add("FUNC pose PoseMult(pose Pose1, pose Pose2)", |cx| {
        let a = pose_arg(cx, 0)?;
        let b = pose_arg(cx, 1)?;
        let r = p::pose_mult(&a, &b).map_err(|e| cx.rt(e))?;
        Ok(pose_value(&r))
    });
    r.add("FUNC pose PoseInv(pose Pose)", |cx| {
        let a = pose_arg(cx, 0)?;
        let r = p::pose_inv(&a).map_err(|e| cx.rt(e))?;
        Ok(pose_value(&r))
    });
    r.add("FUNC pos PoseVect(pose Pose, pos Pos)", |cx| {
        let a = pose_arg(cx, 0)?;
        let v = cx.nums::<3>(1)?;
        let r = p::pose_vect(&a, &v).map_err(|e| cx.rt(e))?;
        Ok(Value::num_record(&r))
    });
    r.add("FUNC orient NOrient(orient Rotation)", |cx| {
        let q = cx.nums::<4>(0)?;
        let r = p::norient(&q).map_err(|e| cx.rt(e))?;
        Ok(Value::num_record(&r))
    });
    r.add("FUNC num Distance(pos Point1, pos Point2)", |cx| {
        let d = p::distance(&cx.nums::<3>(0)?, &cx.nums::<3>(1)?);
        cx.num_result(d)
    });
    r.add("FUNC num VectMagn(pos Vector)", |cx| {
        let d = p::vect_magn(&cx.nums::<3>(0)?);
        cx.num_result(d)
    });
    r.add("FUNC num DotProd(pos Vector1, pos Vector2)", |cx| {
        let d = p::dot_prod(&cx.nums::<3>(0)?, &cx.nums::<3>(1)?);
        cx.num_result(d)
    });
    r.add("FUNC pos CrossProd(pos Vector1, pos Vector2)", |cx| {
        let d = p::cross_prod(&cx.nums::<3>(0)?, &cx.nums::<3>(1)?);
        Ok(Value::num_record(&d))
    });
}

/// The pose part (`trans`, `rot`) of a robtarget or pose value.
fn target_pose(cx: &Ctx<'_>, v: &Value) -> Exec<Pose> {
    let f = v.fields().unwrap_or(&[]);
    match (
        f.first().and_then(|t| t.num_fields::<3>()),
        f.get(1).and_then(|r| r.num_fields::<4>()),
    ) {
        (Some(trans), Some(rot)) => Ok(Pose { trans, rot }),
        _ => Err(cx.it.type_bug(cx.span, "pose or robtarget", v)),
    }
}

fn pose_arg(cx: &Ctx<'_>, i: usize) -> Exec<Pose> {
    let v = cx.value(i)?;
    target_pose(cx, v)
}

fn pose_value(p: &Pose) -> Value {
    Value::Record(Box::new([
        Value::num_record(&p.trans),
        Value::num_record(&p.rot),
    ]))
}

fn set_pose(v: &mut Value, trans: &[f64; 3], rot: Option<&[f64; 4]>) {
    if let Value::Record(f) = v {
        if let Some(t) = f.get_mut(0) {
            *t = Value::num_record(trans);
        }
        if let (Some(r), Some(q)) = (f.get_mut(1), rot) {
            *r = Value::num_record(q);
        }
    }
}
