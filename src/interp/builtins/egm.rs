//! The EGM instructions and `EGMGetState` (docs/egm.md, "Instructions"): RAPID arguments become the registry's request types and go to the host's [`EgmHost`]; EGMRunJoint/EGMRunPose, EGMWaitCond and EGMStop wait for the controller while traps keep running.
//!
//! An `egmident` is identified by its variable (docs/egm.md, "Identities and states"): the name of a task-global
//! variable, `MODULE/name` for a `LOCAL` one, `ROUTINE/name` for routine data, with `{k}` for
//! an array element (k counted from 1 in row-major order). The same variable passed through
//! `VAR` parameters keeps its name, so EGMGetId on it is idempotent wherever it is called.
//!
//! Hosts without EGM (the `rapidvc test` runner) make every instruction stop the program with
//! "`EGMGetId` is not supported by this controller". EGMMoveL/EGMMoveC (path correction)
//! live in `egm_path.rs`.

use super::{Ctx, NativeFn, Registry};
use crate::egm_args::{
    ActCommon, ActJoint, ActMove, ActPose, ArgumentError, EgmFrameType, EgmMode, MinMax, RunArgs,
    SetupLtapp, SetupSignals, SetupUc, StopMode, TrackerKind,
};
use crate::interp::NArg;
use crate::interp::errnum;
use crate::interp::error::{ErrorKind, Exec, Unwind};
use crate::interp::host::{EgmHost, EgmRun, HostError, MotionWait};
use crate::interp::place::AbsRoot;
use crate::interp::value::Value;
use crate::ir::GlobalOrigin;
use crate::robot::units::pose_from_pos_quat;
use crate::robot::{LoadData, Pose, ToolData, WobjData};
use crate::signals::{SignalId, SignalKind};

/// How often a waiting EGM instruction looks at the controller (one motion cycle).
const POLL: f64 = 0.004;

/// The EGM signatures with their implementations.
const NATIVES: &[(&str, NativeFn)] = &[
    (r"PROC EGMGetId(VAR egmident EGMid)", egm_get_id),
    (r"PROC EGMReset(VAR egmident EGMid)", egm_reset),
    (
        r"FUNC egmstate EGMGetState(VAR egmident EGMid, \VAR egmcorrstate CorrectionState)",
        egm_get_state,
    ),
    (
        r"PROC EGMSetupUC(VAR mecunit MecUnit, VAR egmident EGMid, string ExtConfigName, string UCDevice, \switch Joint | switch Pose | switch PathCorr, \switch APTR | switch LATR, \num CommTimeout)",
        egm_setup_uc,
    ),
    (
        r"PROC EGMSetupAI(VAR mecunit MecUnit, VAR egmident EGMid, string ExtConfigName, \switch Joint | switch Pose | switch PathCorr, \switch APTR, \VAR signalai aiR1x, \VAR signalai aiR2y, \VAR signalai aiR3z, \VAR signalai aiR4rx, \VAR signalai aiR5ry, \VAR signalai aiR6rz, \VAR signalai aiE1, \VAR signalai aiE2, \VAR signalai aiE3, \VAR signalai aiE4, \VAR signalai aiE5, \VAR signalai aiE6)",
        egm_setup_ai,
    ),
    (
        r"PROC EGMSetupAO(VAR mecunit MecUnit, VAR egmident EGMid, string ExtConfigName, \switch Joint | switch Pose | switch PathCorr, \switch APTR, \VAR signalao aoR1x, \VAR signalao aoR2y, \VAR signalao aoR3z, \VAR signalao aoR4rx, \VAR signalao aoR5ry, \VAR signalao aoR6rz, \VAR signalao aoE1, \VAR signalao aoE2, \VAR signalao aoE3, \VAR signalao aoE4, \VAR signalao aoE5, \VAR signalao aoE6)",
        egm_setup_ao,
    ),
    (
        r"PROC EGMSetupGI(VAR mecunit MecUnit, VAR egmident EGMid, string ExtConfigName, \switch Joint | switch Pose | switch PathCorr, \switch APTR, \VAR signalgi giR1x, \VAR signalgi giR2y, \VAR signalgi giR3z, \VAR signalgi giR4rx, \VAR signalgi giR5ry, \VAR signalgi giR6rz, \VAR signalgi giE1, \VAR signalgi giE2, \VAR signalgi giE3, \VAR signalgi giE4, \VAR signalgi giE5, \VAR signalgi giE6)",
        egm_setup_gi,
    ),
    (
        r"PROC EGMSetupLTAPP(VAR mecunit MecUnit, VAR egmident EGMid, string ExtConfigName, string Device, num JointType, \switch APTR | switch LATR)",
        egm_setup_ltapp,
    ),
    (
        r"PROC EGMActJoint(VAR egmident EGMid, \switch StreamStart, \PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, \VAR signaldo DOToSensor, \PERS dnum DataToSensor{*}, \VAR signaldi DIFromSensor, \PERS dnum DataFromSensor{*}, \egm_minmax J1, \egm_minmax J2, \egm_minmax J3, \egm_minmax J4, \egm_minmax J5, \egm_minmax J6, \egm_minmax J7, \num LpFilter, \num SampleRate, \num MaxPosDeviation, \num MaxSpeedDeviation)",
        egm_act_joint,
    ),
    (
        r"PROC EGMActPose(VAR egmident EGMid, \switch StreamStart, \PERS tooldata Tool, \PERS wobjdata WObj, \PERS loaddata TLoad, \VAR signaldo DOToSensor, \PERS dnum DataToSensor{*}, \VAR signaldi DIFromSensor, \PERS dnum DataFromSensor{*}, pose CorrFrame, egmframetype CorrFrType, pose SensorFrame, egmframetype SensFrType, \egm_minmax x, \egm_minmax y, \egm_minmax z, \egm_minmax rx, \egm_minmax ry, \egm_minmax rz, \num LpFilter, \num SampleRate, \num MaxPosDeviation, \num MaxSpeedDeviation)",
        egm_act_pose,
    ),
    (
        r"PROC EGMActMove(VAR egmident EGMid, pose SensorFrame, \num SampleRate)",
        egm_act_move,
    ),
    (
        r"PROC EGMRunJoint(VAR egmident EGMid, egmstopmode Mode, \switch NoWaitCond, \switch J1, \switch J2, \switch J3, \switch J4, \switch J5, \switch J6, \switch J7, \num CondTime, \num RampInTime, \num RampOutTime, \num PosCorrGain)",
        egm_run_joint,
    ),
    (
        r"PROC EGMRunPose(VAR egmident EGMid, egmstopmode Mode, \switch NoWaitCond, \switch x, \switch y, \switch z, \switch rx, \switch ry, \switch rz, \num CondTime, \num RampInTime, \num RampOutTime, \pose Offset, \num PosCorrGain)",
        egm_run_pose,
    ),
    (
        r"PROC EGMStop(VAR egmident EGMid, egmstopmode Mode, \num RampOutTime)",
        egm_stop,
    ),
    (r"PROC EGMWaitCond(VAR egmident EGMid)", egm_wait_cond),
    (
        r"PROC EGMStreamStart(VAR egmident EGMid, \num SampleRate)",
        egm_stream_start,
    ),
    (r"PROC EGMStreamStop(VAR egmident EGMid)", egm_stream_stop),
];

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    for (sig, f) in NATIVES {
        r.add(sig, *f);
    }
}

// ----- the host -----

/// Calls the host's EGM capability; a host without one stops the program.
fn with_egm<T>(
    cx: &mut Ctx<'_>,
    f: impl FnOnce(&mut dyn EgmHost) -> Result<T, HostError>,
) -> Exec<T> {
    let r = cx.host().egm().map(f);
    match r {
        Some(Ok(v)) => Ok(v),
        Some(Err(e)) => Err(cx.host_err(e)),
        None => Err(no_egm(cx)),
    }
}

fn no_egm(cx: &Ctx<'_>) -> Unwind {
    let msg = format!(
        "`{}` is not supported by this controller (it has no EGM; `rapidvc run` has)",
        cx.name()
    );
    cx.it.fatal(ErrorKind::Unsupported, cx.span, msg)
}

/// An argument the registry refused before anything reached the controller (fatal, with
/// its event).
fn egm_error(cx: &Ctx<'_>, e: &ArgumentError) -> Unwind {
    cx.it.fatal(ErrorKind::Host, cx.span, e.event().to_string())
}

/// Waits (traps keep running) until the host says `done`.
fn wait_for(
    cx: &mut Ctx<'_>,
    ident: &str,
    mut done: impl FnMut(&mut dyn EgmHost, &str) -> Result<bool, HostError>,
) -> Exec<()> {
    cx.wait_host(None, POLL, |h| match h.egm() {
        Some(e) => done(e, ident),
        None => Ok(true),
    })
    .map(drop)
}

// ----- arguments -----

/// The identity name of the `egmident` reference argument `i` (see the module docs).
pub(super) fn ident(cx: &Ctx<'_>, i: usize) -> Exec<String> {
    let Some(NArg::Ref(place)) = cx.arg(i) else {
        return Err(cx.it.fatal(
            ErrorKind::Host,
            cx.span,
            "internal error: the egmident argument is not a variable",
        ));
    };
    let p = cx.p;
    let mut name = match place.root {
        AbsRoot::Global(g) => match p.globals.get(g as usize) {
            Some(gl) => match (&gl.origin, gl.local) {
                (GlobalOrigin::Module(m), true) => {
                    let module = p.modules.get(m.0 as usize).map_or("?", |m| m.name.as_str());
                    format!("{module}/{}", gl.name)
                }
                _ => gl.name.clone(),
            },
            None => format!("global#{g}"),
        },
        AbsRoot::Stack(idx) => cx
            .it
            .frames
            .iter()
            .rev()
            .find(|f| f.bp <= idx)
            .map(|f| {
                let r = p.routine(f.routine);
                let slot = idx - f.bp;
                let local = r.locals.iter().find(|l| l.slot == slot);
                match local {
                    Some(l) => format!("{}/{}", r.name, l.name),
                    None => format!("{}/#{slot}", r.name),
                }
            })
            .unwrap_or_else(|| format!("stack#{idx}")),
        AbsRoot::Absent => {
            return Err(cx
                .it
                .fatal(ErrorKind::Host, cx.span, "the egmident argument is missing"));
        }
    };
    for step in &place.path {
        if let crate::interp::place::Step::Elem(k) = step {
            name.push_str(&format!("{{{}}}", k + 1));
        }
    }
    Ok(name)
}

/// The name held by a `mecunit` or signal value.
fn object_name(v: &Value) -> Option<&str> {
    match v {
        Value::Record(f) => f.first().and_then(Value::as_str),
        Value::Str(s) => Some(s),
        _ => None,
    }
}

fn mecunit(cx: &Ctx<'_>, i: usize) -> Exec<String> {
    let v = cx.value(i)?;
    object_name(v)
        .map(str::to_string)
        .ok_or_else(|| cx.it.type_bug(cx.span, "mecunit", v))
}

/// Optional signal argument `i`: the host's id of the signal the variable is connected to.
fn signal(cx: &mut Ctx<'_>, i: usize) -> Exec<Option<SignalId>> {
    if !cx.present(i) {
        return Ok(None);
    }
    let name = {
        let v = cx.value(i)?;
        object_name(v).unwrap_or("").to_string()
    };
    if name.is_empty() {
        return Err(cx.error(
            errnum::ERR_NO_ALIASIO_DEF,
            "the signal variable is not connected to an I/O signal (use AliasIO)",
        ));
    }
    with_egm(cx, |h| h.egm_signal(&name)).map(Some)
}

fn pose_of(v: &Value) -> Option<Pose> {
    let f = v.fields()?;
    let pos = f.first()?.num_fields::<3>()?;
    let rot = f.get(1)?.num_fields::<4>()?;
    Some(pose_from_pos_quat(pos, rot))
}

fn load_of(v: &Value) -> Option<LoadData> {
    let f = v.fields()?;
    Some(LoadData {
        mass: f.first()?.as_f64()?,
        cog: f.get(1)?.num_fields::<3>()?,
        aom: f.get(2)?.num_fields::<4>()?,
        ix: f.get(3)?.as_f64()?,
        iy: f.get(4)?.as_f64()?,
        iz: f.get(5)?.as_f64()?,
    })
}

fn pose(cx: &Ctx<'_>, i: usize) -> Exec<Pose> {
    let v = cx.value(i)?;
    pose_of(v).ok_or_else(|| cx.it.type_bug(cx.span, "pose", v))
}

fn opt_pose(cx: &Ctx<'_>, i: usize) -> Exec<Option<Pose>> {
    if cx.present(i) {
        pose(cx, i).map(Some)
    } else {
        Ok(None)
    }
}

fn opt_tool(cx: &Ctx<'_>, i: usize) -> Exec<Option<ToolData>> {
    if !cx.present(i) {
        return Ok(None);
    }
    let v = cx.value(i)?;
    let tool = v.fields().and_then(|f| {
        Some(ToolData {
            robhold: f.first()?.as_bool()?,
            tframe: pose_of(f.get(1)?)?,
            load: load_of(f.get(2)?)?,
        })
    });
    tool.map(Some)
        .ok_or_else(|| cx.it.type_bug(cx.span, "tooldata", v))
}

fn opt_wobj(cx: &Ctx<'_>, i: usize) -> Exec<Option<WobjData>> {
    if !cx.present(i) {
        return Ok(None);
    }
    let v = cx.value(i)?;
    let wobj = v.fields().and_then(|f| {
        Some(WobjData {
            robhold: f.first()?.as_bool()?,
            ufprog: f.get(1)?.as_bool()?,
            ufmec: f.get(2)?.as_str()?.to_string(),
            uframe: pose_of(f.get(3)?)?,
            oframe: pose_of(f.get(4)?)?,
        })
    });
    wobj.map(Some)
        .ok_or_else(|| cx.it.type_bug(cx.span, "wobjdata", v))
}

fn opt_load(cx: &Ctx<'_>, i: usize) -> Exec<Option<LoadData>> {
    if !cx.present(i) {
        return Ok(None);
    }
    let v = cx.value(i)?;
    load_of(v)
        .map(Some)
        .ok_or_else(|| cx.it.type_bug(cx.span, "loaddata", v))
}

fn opt_minmax(cx: &Ctx<'_>, i: usize) -> Exec<Option<MinMax>> {
    if !cx.present(i) {
        return Ok(None);
    }
    let [min, max] = cx.nums::<2>(i)?;
    Ok(Some(MinMax { min, max }))
}

fn switches<const N: usize>(cx: &Ctx<'_>, first: usize) -> [bool; N] {
    std::array::from_fn(|k| cx.present(first + k))
}

/// `\Joint | \Pose | \PathCorr` starting at argument `first`.
fn mode(cx: &Ctx<'_>, first: usize) -> Exec<EgmMode> {
    if cx.present(first) {
        Ok(EgmMode::Joint)
    } else if cx.present(first + 1) {
        Ok(EgmMode::Pose)
    } else if cx.present(first + 2) {
        Ok(EgmMode::PathCorr)
    } else {
        Err(cx.it.fatal(
            ErrorKind::Host,
            cx.span,
            format!(
                "{} needs one of the switches \\Joint, \\Pose or \\PathCorr",
                cx.name()
            ),
        ))
    }
}

/// `\APTR | \LATR` starting at argument `first` (`latr`: whether `\LATR` exists).
fn tracker(cx: &Ctx<'_>, first: usize, latr: bool) -> Option<TrackerKind> {
    if cx.present(first) {
        Some(TrackerKind::Aptr)
    } else if latr && cx.present(first + 1) {
        Some(TrackerKind::Latr)
    } else {
        None
    }
}

fn run_args(cx: &Ctx<'_>, instruction: &'static str, first_num: usize) -> Exec<RunArgs> {
    let stop_mode = StopMode::from_value(instruction, cx.f64(1)?).map_err(|e| egm_error(cx, &e))?;
    Ok(RunArgs {
        stop_mode,
        no_wait_cond: cx.present(2),
        cond_time: cx.opt_f64(first_num)?,
        ramp_in_time: cx.opt_f64(first_num + 1)?,
        ramp_out_time: cx.opt_f64(first_num + 2)?,
        pos_corr_gain: None,
    })
}

/// The arguments EGMActJoint and EGMActPose share (indexes 1–8, and the four numbers from
/// `nums`).
fn act_common(cx: &mut Ctx<'_>, nums: usize) -> Exec<ActCommon> {
    let do_to_sensor = signal(cx, 5)?;
    let di_from_sensor = signal(cx, 7)?;
    Ok(ActCommon {
        stream_start: cx.present(1),
        tool: opt_tool(cx, 2)?,
        wobj: opt_wobj(cx, 3)?,
        tload: opt_load(cx, 4)?,
        do_to_sensor,
        data_to_sensor: cx.present(6),
        di_from_sensor,
        data_from_sensor: cx.present(8),
        lp_filter: cx.opt_f64(nums)?,
        sample_rate: cx.opt_f64(nums + 1)?,
        max_pos_deviation: cx.opt_f64(nums + 2)?,
        max_speed_deviation: cx.opt_f64(nums + 3)?,
    })
}

// ----- instructions -----

fn egm_get_id(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = ident(cx, 0)?;
    with_egm(cx, |h| h.egm_get_id(&id))?;
    Ok(Value::Absent)
}

fn egm_reset(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = ident(cx, 0)?;
    with_egm(cx, |h| h.egm_reset(&id))?;
    Ok(Value::Absent)
}

fn egm_get_state(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = ident(cx, 0)?;
    let (state, corr) = with_egm(cx, |h| h.egm_get_state(&id))?;
    if cx.present(1) {
        cx.set(1, Value::Num(corr.value() as f32))?;
    }
    Ok(Value::Num(state.value() as f32))
}

fn egm_setup_uc(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = ident(cx, 1)?;
    let args = SetupUc {
        mecunit: mecunit(cx, 0)?,
        profile: cx.str(2)?.to_string(),
        device: cx.str(3)?.to_string(),
        mode: mode(cx, 4)?,
        tracker: tracker(cx, 7, true),
        comm_timeout: cx.opt_f64(9)?,
    };
    with_egm(cx, |h| h.egm_setup_uc(&id, &args))?;
    Ok(Value::Absent)
}

fn egm_setup_signals(cx: &mut Ctx<'_>, kind: SignalKind) -> Exec<Value> {
    let id = ident(cx, 1)?;
    let mut mapping = [None; 6];
    for (k, slot) in mapping.iter_mut().enumerate() {
        *slot = signal(cx, 7 + k)?;
    }
    let mut ext = [None; 6];
    for (k, slot) in ext.iter_mut().enumerate() {
        *slot = signal(cx, 13 + k)?;
    }
    let args = SetupSignals {
        mecunit: mecunit(cx, 0)?,
        profile: cx.str(2)?.to_string(),
        kind,
        mode: mode(cx, 3)?,
        tracker: tracker(cx, 6, false),
        mapping,
        ext,
    };
    with_egm(cx, |h| h.egm_setup_signals(&id, &args))?;
    Ok(Value::Absent)
}

fn egm_setup_ai(cx: &mut Ctx<'_>) -> Exec<Value> {
    egm_setup_signals(cx, SignalKind::Ai)
}

fn egm_setup_ao(cx: &mut Ctx<'_>) -> Exec<Value> {
    egm_setup_signals(cx, SignalKind::Ao)
}

fn egm_setup_gi(cx: &mut Ctx<'_>) -> Exec<Value> {
    egm_setup_signals(cx, SignalKind::Gi)
}

fn egm_setup_ltapp(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = ident(cx, 1)?;
    let Some(tracker) = tracker(cx, 5, true) else {
        return Err(cx.it.fatal(
            ErrorKind::Host,
            cx.span,
            "EGMSetupLTAPP needs one of the switches \\APTR or \\LATR",
        ));
    };
    let args = SetupLtapp {
        mecunit: mecunit(cx, 0)?,
        profile: cx.str(2)?.to_string(),
        device: cx.str(3)?.to_string(),
        joint_type: cx.f64(4)?,
        tracker,
    };
    with_egm(cx, |h| h.egm_setup_ltapp(&id, &args))?;
    Ok(Value::Absent)
}

fn egm_act_joint(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = ident(cx, 0)?;
    let common = act_common(cx, 16)?;
    let mut windows = [None; 7];
    for (k, w) in windows.iter_mut().enumerate() {
        *w = opt_minmax(cx, 9 + k)?;
    }
    let args = ActJoint { common, windows };
    with_egm(cx, |h| h.egm_act_joint(&id, &args))?;
    Ok(Value::Absent)
}

fn frame_type(cx: &Ctx<'_>, i: usize, argument: &'static str) -> Exec<EgmFrameType> {
    EgmFrameType::from_argument("EGMActPose", argument, cx.f64(i)?).map_err(|e| egm_error(cx, &e))
}

fn egm_act_pose(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = ident(cx, 0)?;
    let common = act_common(cx, 19)?;
    let mut windows = [None; 6];
    for (k, w) in windows.iter_mut().enumerate() {
        *w = opt_minmax(cx, 13 + k)?;
    }
    let args = ActPose {
        common,
        corr_frame: pose(cx, 9)?,
        corr_type: frame_type(cx, 10, "CorrFrType")?,
        sensor_frame: pose(cx, 11)?,
        sens_type: frame_type(cx, 12, "SensFrType")?,
        windows,
    };
    with_egm(cx, |h| h.egm_act_pose(&id, &args))?;
    Ok(Value::Absent)
}

fn egm_act_move(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = ident(cx, 0)?;
    let args = ActMove {
        sensor_frame: pose(cx, 1)?,
        sample_rate: cx.opt_f64(2)?,
    };
    with_egm(cx, |h| h.egm_act_move(&id, &args))?;
    Ok(Value::Absent)
}

/// Starts the run; unless `\NoWaitCond`, waits for its end (an error of the run is raised
/// here: `ERR_UDPUC_COMM` is catchable).
fn start_and_wait(cx: &mut Ctx<'_>, id: String, run: EgmRun) -> Exec<Value> {
    let span = cx.span;
    // The robot must stand in the fine point the last move ended in (also after `\Conc`).
    super::motion::wait_for(cx, MotionWait::InPos)?;
    let no_wait = run.args().no_wait_cond;
    with_egm(cx, |h| h.egm_run(&id, &run, span))?;
    if !no_wait {
        wait_for(cx, &id, |h, id| h.egm_run_done(id, false))?;
    }
    Ok(Value::Absent)
}

fn egm_run_joint(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = ident(cx, 0)?;
    let mut args = run_args(cx, "EGMRunJoint", 10)?;
    args.pos_corr_gain = cx.opt_f64(13)?;
    let axes = switches::<7>(cx, 3);
    start_and_wait(cx, id, EgmRun::Joint { args, axes })
}

fn egm_run_pose(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = ident(cx, 0)?;
    let mut args = run_args(cx, "EGMRunPose", 9)?;
    args.pos_corr_gain = cx.opt_f64(13)?;
    let directions = switches::<6>(cx, 3);
    let offset = opt_pose(cx, 12)?;
    start_and_wait(
        cx,
        id,
        EgmRun::Pose {
            args,
            directions,
            offset,
        },
    )
}

fn egm_stop(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = ident(cx, 0)?;
    let mode = StopMode::from_value("EGMStop", cx.f64(1)?).map_err(|e| egm_error(cx, &e))?;
    let ramp_out = cx.opt_f64(2)?;
    with_egm(cx, |h| h.egm_stop(&id, mode, ramp_out))?;
    wait_for(cx, &id, |h, id| h.egm_run_active(id).map(|a| !a))?;
    with_egm(cx, |h| h.egm_stop_done(&id))?;
    Ok(Value::Absent)
}

fn egm_wait_cond(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = ident(cx, 0)?;
    wait_for(cx, &id, |h, id| h.egm_run_done(id, true))?;
    Ok(Value::Absent)
}

fn egm_stream_start(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = ident(cx, 0)?;
    let rate = cx.opt_f64(1)?;
    with_egm(cx, |h| h.egm_stream_start(&id, rate))?;
    Ok(Value::Absent)
}

fn egm_stream_stop(cx: &mut Ctx<'_>) -> Exec<Value> {
    let id = ident(cx, 0)?;
    with_egm(cx, |h| h.egm_stream_stop(&id))?;
    Ok(Value::Absent)
}
