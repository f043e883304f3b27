//! Motion settings and motion functions: `CTool`, `CWObj`, `GripLoad`, `ActUnit`/`DeactUnit`,
//! `MotionSup`, `SoftAct`/`SoftDeact`, `CirPathMode`, `PathAccLim`, `WorldAccLim`,
//! `EOffsOn`/`EOffsSet`/`EOffsOff`, `ORobT`, `DefFrame`, `DefDFrame`, `MirPos`, `ReadMotor`,
//! `IsSyncMoveOn`.
//!
//! What the kinematic robot has no use for is accepted with its arguments checked and
//! changes nothing (`MotionSup`, `SoftAct`/`SoftDeact`: no dynamic model, no servo
//! stiffness); `docs/robot.md` ("Motion settings") lists each decision.

use super::motion::data;
use super::{Ctx, Registry};
use crate::interp::errnum;
use crate::interp::error::{ErrorKind, Exec};
use crate::interp::host::MotionSetting;
use crate::interp::value::Value;
use crate::robot::command::{EXTAX_UNUSED, RobTarget};
use crate::robot::frame_points::{self, FrameError, FrameOrigin};
use crate::robot::{Pose, pose_to_pos_quat, units};
use crate::system::info::SysDataKind;

/// The one mechanical unit (the robot).
const ROBOT_UNIT: &str = "ROB_1";

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add("FUNC tooldata CTool()", |cx| {
        super::system::active_value(cx, SysDataKind::Tool)
    });
    r.add("FUNC wobjdata CWObj()", |cx| {
        super::system::active_value(cx, SysDataKind::Wobj)
    });
    r.add("PROC GripLoad(PERS loaddata Load)", |cx| {
        data::loaddata(cx, cx.value(0)?)?;
        super::system::note_active(cx, SysDataKind::Load, 0);
        Ok(Value::Absent)
    });
    r.add("PROC ActUnit(mecunit MechUnit)", |cx| {
        // The robot is always active.
        unit_arg(cx, 0)?;
        Ok(Value::Absent)
    });
    r.add("PROC DeactUnit(mecunit MechUnit)", |cx| {
        let name = unit_arg(cx, 0)?;
        Err(cx.it.fatal(
            ErrorKind::Host,
            cx.span,
            format!("`DeactUnit {name}`: a TCP robot cannot be deactivated (rapidvc has no external mechanical units)"),
        ))
    });
    r.add(
        r"PROC MotionSup(\switch On | switch Off, \num TuneValue)",
        |cx| {
            if let Some(t) = cx.opt_f64(2)?
                && !(1.0..=300.0).contains(&t)
            {
                return Err(cx.error(
                    errnum::ERR_ARGVALERR,
                    format!("the MotionSup tune value must be 1 to 300 %, not {t}"),
                ));
            }
            Ok(Value::Absent)
        },
    );
    r.add(
        r"PROC SoftAct(\mecunit MechUnit, num Axis, num Softness, \num Ramp)",
        |cx| {
            if cx.present(0) {
                unit_arg(cx, 0)?;
            }
            axis_arg(cx, 1)?;
            let soft = cx.f64(2)?;
            if !(0.0..=100.0).contains(&soft) {
                return Err(cx.error(
                    errnum::ERR_ARGVALERR,
                    format!("the SoftAct softness must be 0 to 100 %, not {soft}"),
                ));
            }
            ramp_arg(cx, 3)?;
            Ok(Value::Absent)
        },
    );
    r.add(r"PROC SoftDeact(\num Ramp)", |cx| {
        ramp_arg(cx, 0)?;
        Ok(Value::Absent)
    });
    r.add(
        r"PROC CirPathMode(\switch PathFrame | switch ObjectFrame | switch CirPointOri | switch Wrist45 | switch Wrist46 | switch Wrist56)",
        |cx| {
            // MoveC turns the tool along the path (the path frame), the default mode.
            const OTHER: [&str; 5] = [
                "ObjectFrame",
                "CirPointOri",
                "Wrist45",
                "Wrist46",
                "Wrist56",
            ];
            for (k, name) in OTHER.iter().enumerate() {
                if cx.present(k + 1) {
                    return Err(cx.unsupported(&format!(
                        "`CirPathMode \\{name}`: MoveC orients the tool only in the path frame, `\\PathFrame`"
                    )));
                }
            }
            Ok(Value::Absent)
        },
    );
    r.add(
        r"PROC PathAccLim(bool AccLim, \num AccMax, bool DecelLim, \num DecelMax)",
        |cx| {
            let acc = acc_limit(cx, 0, 1, "AccMax")?;
            let decel = acc_limit(cx, 2, 3, "DecelMax")?;
            set(cx, MotionSetting::PathAccLim { acc, decel })
        },
    );
    r.add(r"PROC WorldAccLim(\num On | switch Off)", |cx| {
        let lim = match cx.opt_f64(0)? {
            Some(a) => Some(min_acc(cx, a, "WorldAccLim \\On")?),
            None => None,
        };
        set(cx, MotionSetting::WorldAccLim(lim))
    });
    r.add("PROC EOffsSet(extjoint EAxOffs)", |cx| {
        let e = cx.nums::<6>(0)?;
        set(cx, MotionSetting::EOffs(Some(e.map(offset_of))))
    });
    r.add(
        r"PROC EOffsOn(\robtarget ExeP, robtarget ProgPoint)",
        |cx| {
            let prog = data::robtarget(cx, cx.value(1)?)?;
            let exe = if cx.present(0) {
                data::robtarget(cx, cx.value(0)?)?.extax
            } else {
                // The robot's own external axes: rapidvc has none, so every one is unused.
                crate::robot::command::EXTAX_NONE
            };
            let mut off = [0.0; 6];
            for ((o, e), p) in off.iter_mut().zip(exe).zip(prog.extax) {
                if e != EXTAX_UNUSED && p != EXTAX_UNUSED {
                    *o = e - p;
                }
            }
            set(cx, MotionSetting::EOffs(Some(off)))
        },
    );
    r.add("PROC EOffsOff()", |cx| set(cx, MotionSetting::EOffs(None)));
    r.add(
        r"FUNC robtarget ORobT(robtarget OrgPoint, \switch InPDisp | switch InEOffs)",
        |cx| {
            let mut t = data::robtarget(cx, cx.value(0)?)?;
            let modes = cx.it.host.motion_modes();
            if !cx.present(1) {
                // Out of the program displacement frame into the object frame.
                let (trans, rot) = pose_to_pos_quat(&(modes.pdisp * t.pose()));
                t.trans = trans;
                t.rot = rot;
            }
            if !cx.present(2)
                && let Some(off) = modes.eoffs
            {
                for (x, o) in t.extax.iter_mut().zip(off) {
                    if *x != EXTAX_UNUSED {
                        *x -= o;
                    }
                }
            }
            Ok(data::robtarget_value(&t))
        },
    );
    r.add(
        r"FUNC pose DefFrame(robtarget NewP1, robtarget NewP2, robtarget NewP3, \num Origin)",
        |cx| {
            let p: [nalgebra::Vector3<f64>; 3] = [point(cx, 0)?, point(cx, 1)?, point(cx, 2)?];
            let origin = match cx.opt_f64(3)? {
                None => FrameOrigin::First,
                Some(1.0) => FrameOrigin::First,
                Some(2.0) => FrameOrigin::Second,
                Some(3.0) => FrameOrigin::Projection,
                Some(o) => {
                    return Err(cx.error(
                        errnum::ERR_ARGVALERR,
                        format!("\\Origin must be 1, 2 or 3, not {o}"),
                    ));
                }
            };
            let f = frame_points::frame_from_points(&p[0], &p[1], &p[2], origin)
                .map_err(|e| frame_error(cx, e))?;
            Ok(pose_value(&f))
        },
    );
    r.add(
        "FUNC pose DefDFrame(robtarget OldP1, robtarget OldP2, robtarget OldP3, robtarget NewP1, robtarget NewP2, robtarget NewP3)",
        |cx| {
            let mut p = [nalgebra::Vector3::zeros(); 6];
            for (k, slot) in p.iter_mut().enumerate() {
                *slot = point(cx, k)?;
            }
            let [o1, o2, o3, n1, n2, n3] = p;
            let f = frame_points::displacement_frame([&o1, &o2, &o3], [&n1, &n2, &n3])
                .map_err(|e| frame_error(cx, e))?;
            Ok(pose_value(&f))
        },
    );
    r.add(
        r"FUNC robtarget MirPos(robtarget Point, PERS wobjdata MirPlane, \PERS wobjdata WObj, \switch MirY)",
        |cx| {
            let t = data::robtarget(cx, cx.value(0)?)?;
            let plane = data::wobjdata(cx, cx.value(1)?)?;
            let plane = plane.uframe * plane.oframe;
            let frame = if cx.present(2) {
                let w = data::wobjdata(cx, cx.value(2)?)?;
                w.uframe * w.oframe
            } else {
                Pose::identity()
            };
            let world = frame * t.pose();
            let mirrored = frame_points::mirror_in_xy(&world, &plane, cx.present(3));
            let (trans, rot) = pose_to_pos_quat(&(frame.inverse() * mirrored));
            Ok(data::robtarget_value(&RobTarget { trans, rot, ..t }))
        },
    );
    r.add(r"FUNC num ReadMotor(\mecunit MecUnit, num Axis)", |cx| {
        if cx.present(0) {
            unit_arg(cx, 0)?;
        }
        let axis = axis_arg(cx, 1)?;
        let joints = cx.host().motion_joints().map_err(|e| cx.host_err(e))?;
        // rapidvc's motor model: the motor angle is the arm angle (gear ratio 1, no offset).
        let deg = joints.get(axis - 1).copied().unwrap_or(0.0);
        cx.num_result(units::deg_to_rad(deg))
    });
    r.add("FUNC bool IsSyncMoveOn()", |_| {
        // No MultiMove: a task never runs synchronized movements.
        Ok(Value::Bool(false))
    });
}

fn set(cx: &mut Ctx<'_>, s: MotionSetting) -> Exec<Value> {
    cx.host().motion_set(s).map_err(|e| cx.host_err(e))?;
    Ok(Value::Absent)
}

/// The name of mecunit argument `i`: only `ROB_1` exists.
fn unit_arg(cx: &Ctx<'_>, i: usize) -> Exec<String> {
    let name = cx
        .value(i)?
        .fields()
        .and_then(|f| f.first())
        .and_then(|n| n.as_str())
        .unwrap_or_default()
        .to_string();
    if name.eq_ignore_ascii_case(ROBOT_UNIT) || name.is_empty() {
        Ok(ROBOT_UNIT.to_string())
    } else {
        Err(cx.it.fatal(
            ErrorKind::Unsupported,
            cx.span,
            format!("mechanical unit `{name}` does not exist: rapidvc has one, `{ROBOT_UNIT}`"),
        ))
    }
}

/// Axis number argument `i`, 1 to 6.
fn axis_arg(cx: &Ctx<'_>, i: usize) -> Exec<usize> {
    let a = cx.f64(i)?;
    if a.fract() == 0.0 && (1.0..=6.0).contains(&a) {
        Ok(a as usize)
    } else {
        Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("the axis must be 1 to 6, not {a}"),
        ))
    }
}

/// Optional `\Ramp` argument `i` (%, at least 100).
fn ramp_arg(cx: &Ctx<'_>, i: usize) -> Exec<()> {
    match cx.opt_f64(i)? {
        Some(r) if !(r >= 100.0 && r.is_finite()) => Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("the ramp must be at least 100 %, not {r}"),
        )),
        _ => Ok(()),
    }
}

/// Smallest acceleration limit `PathAccLim` and `WorldAccLim` take (m/s²).
const MIN_ACC_M_S2: f64 = 0.1;

/// An acceleration limit in m/s² (at least 0.1), as mm/s².
fn min_acc(cx: &Ctx<'_>, a: f64, what: &str) -> Exec<f64> {
    if a.is_finite() && a >= MIN_ACC_M_S2 {
        Ok(units::m_to_mm(a))
    } else {
        Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("{what} must be at least {MIN_ACC_M_S2} m/s², not {a}"),
        ))
    }
}

/// `PathAccLim`'s switch `on` with its value `max`: the limit in mm/s² when on.
fn acc_limit(cx: &Ctx<'_>, on: usize, max: usize, what: &str) -> Exec<Option<f64>> {
    if !cx.bool(on)? {
        return Ok(None);
    }
    match cx.opt_f64(max)? {
        Some(a) => min_acc(cx, a, &format!("\\{what}")).map(Some),
        None => Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("a limit that is on needs `\\{what}`"),
        )),
    }
}

/// An `extjoint` offset: 9E9 (an unused axis) is no offset.
fn offset_of(x: f64) -> f64 {
    if x == EXTAX_UNUSED { 0.0 } else { x }
}

fn point(cx: &Ctx<'_>, i: usize) -> Exec<nalgebra::Vector3<f64>> {
    let t = data::robtarget(cx, cx.value(i)?)?;
    Ok(nalgebra::Vector3::from(t.trans))
}

fn frame_error(cx: &Ctx<'_>, e: FrameError) -> crate::interp::error::Unwind {
    cx.error(errnum::ERR_FRAME, format!("no frame: {e}"))
}

fn pose_value(p: &Pose) -> Value {
    let (trans, rot) = pose_to_pos_quat(p);
    Value::Record(Box::new([
        Value::num_record(&trans),
        Value::num_record(&rot),
    ]))
}
