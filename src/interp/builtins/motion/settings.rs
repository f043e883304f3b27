//! Modal motion settings: `ConfJ`, `ConfL`, `SingArea`, `VelSet`, `AccSet`, and program
//! displacement (`PDispSet`, `PDispOn`, `PDispOff`).

use super::{data, position};
use crate::interp::builtins::Ctx;
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::host::{MotionSetting, SingAreaMode};
use crate::interp::value::Value;
use crate::robot::Pose;

/// Lowest `AccSet` acceleration (%): smaller values give this (as on a controller).
pub const ACC_MIN_PCT: f64 = 20.0;
/// Lowest `AccSet` ramp (%): smaller values give this.
pub const RAMP_MIN_PCT: f64 = 10.0;

fn set(cx: &mut Ctx<'_>, s: MotionSetting) -> Exec<Value> {
    cx.host().motion_set(s).map_err(|e| cx.host_err(e))?;
    Ok(Value::Absent)
}

/// `ConfJ [\On] | [\Off]` (`\On` when neither is given).
pub(super) fn conf_j(cx: &mut Ctx<'_>) -> Exec<Value> {
    let on = !cx.present(1);
    set(cx, MotionSetting::ConfJ(on))
}

/// `ConfL [\On] | [\Off]` (`\On` when neither is given).
pub(super) fn conf_l(cx: &mut Ctx<'_>) -> Exec<Value> {
    let on = !cx.present(1);
    set(cx, MotionSetting::ConfL(on))
}

/// `SingArea [\Wrist] | [\LockAxis4] | [\Off]` (`\Off` when none is given).
pub(super) fn sing_area(cx: &mut Ctx<'_>) -> Exec<Value> {
    let mode = if cx.present(0) {
        SingAreaMode::Wrist
    } else if cx.present(1) {
        SingAreaMode::LockAxis4
    } else {
        SingAreaMode::Off
    };
    set(cx, MotionSetting::SingArea(mode))
}

/// A positive, finite percentage or speed, else `ERR_ARGVALERR` naming it.
fn positive(cx: &Ctx<'_>, i: usize, what: &str) -> Exec<f64> {
    let x = cx.f64(i)?;
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("{what} must be greater than 0, not {x}"),
        ))
    }
}

/// `VelSet Override, Max`.
pub(super) fn vel_set(cx: &mut Ctx<'_>) -> Exec<Value> {
    let override_pct = positive(cx, 0, "the VelSet override (%)")?;
    let max_tcp = positive(cx, 1, "the VelSet maximum speed (mm/s)")?;
    set(
        cx,
        MotionSetting::VelSet {
            override_pct,
            max_tcp,
        },
    )
}

/// `AccSet Acc, Ramp [\FinePointRamp]`: percentages up to 100; below 20 % (acceleration) or
/// 10 % (ramp) the minimum applies. `\FinePointRamp` is accepted (the profile has no jerk
/// limit).
pub(super) fn acc_set(cx: &mut Ctx<'_>) -> Exec<Value> {
    let acc_pct = positive(cx, 0, "the AccSet acceleration (%)")?.clamp(ACC_MIN_PCT, 100.0);
    let ramp_pct = positive(cx, 1, "the AccSet ramp (%)")?.clamp(RAMP_MIN_PCT, 100.0);
    set(cx, MotionSetting::AccSet { acc_pct, ramp_pct })
}

/// `PDispSet DispFrame`.
pub(super) fn pdisp_set(cx: &mut Ctx<'_>) -> Exec<Value> {
    let frame = data::pose(cx, cx.value(0)?, "displacement frame")?;
    set(cx, MotionSetting::PDisp(frame))
}

/// `PDispOff`.
pub(super) fn pdisp_off(cx: &mut Ctx<'_>) -> Exec<Value> {
    set(cx, MotionSetting::PDisp(Pose::identity()))
}

/// `PDispOn [\Rot] [\ExeP,] ProgPoint, Tool [\WObj]`: the displacement that moves
/// `ProgPoint` to `ExeP` (the robot's current position when not given; the robot must then
/// stand still, so this waits until it is in position), in the object frame. Without `\Rot`
/// only the position is displaced.
pub(super) fn pdisp_on(cx: &mut Ctx<'_>) -> Exec<Value> {
    let prog = data::robtarget(cx, cx.value(2)?)?.pose();
    let tool = data::tooldata(cx, cx.value(3)?)?;
    let wobj = data::opt_wobj(cx, 4)?;
    let exe = if cx.present(1) {
        data::robtarget(cx, cx.value(1)?)?.pose()
    } else {
        position::position_in_wobj(cx, &tool, &wobj)?.pose()
    };
    let disp = if cx.present(0) {
        exe * prog.inverse()
    } else {
        Pose::from_parts(
            (exe.translation.vector - prog.translation.vector).into(),
            nalgebra::UnitQuaternion::identity(),
        )
    };
    set(cx, MotionSetting::PDisp(disp))
}
