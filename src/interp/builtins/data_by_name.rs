//! Data reached by name and data asked about itself: `GetDataVal`, `SetDataVal`, `ArgName`,
//! `IsPers`, `IsVar`, `Type`.
//!
//! A name given as text is looked up as the calling routine would see it: its routine data
//! first, then module data (a `LOCAL` declaration only from its own module). Only entire
//! data objects are found (`"reg1"`, not `"reg{1}"` or `"p10.trans"`); predefined error
//! numbers and mechanical units are not data objects here. A signal of the I/O
//! configuration is one for `GetDataVal` into a signal variable of its kind: the variable
//! is connected to it, as `AliasIO` does (`GetDataVal "do_gripper", sig;`). The value and the target
//! must have the same type (`ERR_SYMBOL_TYPE`) and, for arrays, the same sizes (`ERR_INVDIM`);
//! a name nobody declared, or a constant `SetDataVal` would change, is `ERR_SYM_ACCESS`.
//!
//! `ArgName` follows a reference parameter to the data the caller passed. The data behind an
//! IN parameter (a copy) is not followed: that is reported as not supported, by name.
//! `Type` answers with the name of the type after aliases are resolved (rapidvc keeps no
//! alias names at run time), so `\BaseName` gives the same answer.

use super::{Ctx, Registry};
use crate::interp::NArg;
use crate::interp::errnum;
use crate::interp::error::{ErrorKind, Exec};
use crate::interp::place::{AbsPlace, AbsRoot, Step};
use crate::interp::value::Value;
use crate::ir::{GlobalOrigin, ParamSlot, Storage, Ty};

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add(
        r"PROC GetDataVal(string Object, \datapos Block, INOUT anydataorsignal Value)",
        get_data_val,
    );
    r.add(
        r"PROC SetDataVal(string Object, \datapos Block, anydata Value)",
        set_data_val,
    );
    r.add(
        r"FUNC string ArgName(REF anydata Parameter, \INOUT num ErrorNumber)",
        arg_name,
    );
    r.add("FUNC bool IsPers(INOUT anydata DatObj)", |cx| {
        let pers = matches!(what_is(cx, 0), Some(Origin::Global(g)) if cx.it.prog.globals[g].storage == Storage::Pers);
        Ok(Value::Bool(pers))
    });
    r.add("FUNC bool IsVar(INOUT anydata DatObj)", |cx| {
        let var = match what_is(cx, 0) {
            Some(Origin::Global(g)) => cx.it.prog.globals[g].storage == Storage::Var,
            Some(Origin::Routine { .. }) => true,
            None => false,
        };
        Ok(Value::Bool(var))
    });
    r.add(
        r"FUNC string Type(REF anydata Data, \switch BaseName)",
        type_name,
    );
}

/// The arguments `\Block` and `Value` of `GetDataVal`/`SetDataVal`.
const BLOCK: usize = 1;
const VALUE: usize = 2;

/// Where the data behind a reference argument is declared.
enum Origin {
    /// Module data.
    Global(usize),
    /// Routine data or a value parameter: the routine and the slot in its frame.
    Routine {
        routine: crate::ir::RoutineId,
        slot: u32,
    },
}

/// The data object behind reference argument `i` (its entire object, whatever path the
/// argument adds).
fn what_is(cx: &Ctx<'_>, i: usize) -> Option<Origin> {
    let NArg::Ref(place) = cx.arg(i)? else {
        return None;
    };
    match place.root {
        AbsRoot::Global(g) => Some(Origin::Global(g as usize)),
        AbsRoot::Stack(abs) => {
            let frame = cx.it.frames.iter().rev().find(|f| f.bp <= abs)?;
            Some(Origin::Routine {
                routine: frame.routine,
                slot: abs - frame.bp,
            })
        }
        AbsRoot::Absent => None,
    }
}

/// The declared type of value slot `slot` of `routine` (routine data, value parameters,
/// `FOR` variables).
fn slot_ty(cx: &Ctx<'_>, routine: crate::ir::RoutineId, slot: u32) -> Option<(Ty, String)> {
    let r = cx.it.prog.routines.get(routine.0 as usize)?;
    if let Some(l) = r.locals.iter().find(|l| l.slot == slot) {
        return Some((l.ty, l.name.clone()));
    }
    r.params
        .iter()
        .find(|p| p.slot == ParamSlot::Value(slot))
        .map(|p| (p.ty, p.name.clone()))
}

/// The type of what reference argument `i` designates, following its path.
fn ref_ty(cx: &Ctx<'_>, i: usize) -> Option<Ty> {
    let NArg::Ref(place) = cx.arg(i)? else {
        return None;
    };
    let mut ty = match what_is(cx, i)? {
        Origin::Global(g) => cx.it.prog.globals.get(g)?.ty,
        Origin::Routine { routine, slot } => slot_ty(cx, routine, slot)?.0,
    };
    for step in &place.path {
        ty = match step {
            Step::Field(f) if ty.rank == 0 => {
                cx.it.prog.types.fields(ty.base)?.get(*f as usize)?.ty
            }
            Step::Elem(_) if ty.rank > 0 => ty.elem(),
            _ => return None,
        };
    }
    Some(ty)
}

/// The data object called `name` as the calling routine sees it: its place, type and
/// storage class.
pub(super) fn find_by_name(cx: &Ctx<'_>, name: &str) -> Option<(AbsPlace, Ty, Storage)> {
    // `\Block` (from `GetNextSym`): the module data of that module, LOCAL ones included.
    if cx.present(BLOCK)
        && let Ok(Some([Value::Num(b)])) = cx.value(BLOCK).map(|v| v.fields())
    {
        let module = crate::ir::ModuleId((*b as u32).saturating_sub(1));
        let found = cx.it.prog.globals.iter().enumerate().find(|(_, g)| {
            g.name.eq_ignore_ascii_case(name) && g.origin == GlobalOrigin::Module(module)
        });
        return found.map(|(i, g)| (AbsPlace::global(i as u32), g.ty, g.storage));
    }
    let frame = cx.it.frames.last()?;
    let routine = cx.it.prog.routines.get(frame.routine.0 as usize)?;
    if let Some(l) = routine
        .locals
        .iter()
        .find(|l| l.name.eq_ignore_ascii_case(name))
    {
        let place = AbsPlace {
            root: AbsRoot::Stack(frame.bp + l.slot),
            path: Vec::new(),
        };
        return Some((place, l.ty, Storage::Var));
    }
    let module = routine.module;
    let found = cx.it.prog.globals.iter().enumerate().find(|(_, g)| {
        g.name.eq_ignore_ascii_case(name)
            && match g.origin {
                GlobalOrigin::Module(m) => !g.local || m == module,
                _ => false,
            }
    });
    found.map(|(i, g)| (AbsPlace::global(i as u32), g.ty, g.storage))
}

/// Is module data `g` in a read-only (stdlib) module?
fn read_only_module(cx: &Ctx<'_>, place: &AbsPlace) -> bool {
    match place.root {
        AbsRoot::Global(g) => match cx.it.prog.globals[g as usize].origin {
            GlobalOrigin::Module(m) => cx.it.prog.modules[m.0 as usize].stdlib,
            _ => true,
        },
        _ => false,
    }
}

/// The data object `Object` (argument 0) of the same type as `target`.
fn object(cx: &Ctx<'_>, target: Option<Ty>) -> Exec<(AbsPlace, Storage)> {
    let name = cx.str(0)?;
    let Some((place, ty, storage)) = find_by_name(cx, name) else {
        return Err(cx.error(
            errnum::ERR_SYM_ACCESS,
            format!("there is no data object `{name}` that this routine can reach"),
        ));
    };
    if let Some(t) = target
        && t != ty
    {
        let types = &cx.it.prog.types;
        let (kind, message) = if t.base == ty.base {
            (errnum::ERR_INVDIM, "has other dimensions than")
        } else {
            (errnum::ERR_SYMBOL_TYPE, "is of another type than")
        };
        return Err(cx.error(
            kind,
            format!(
                "`{name}` ({}) {message} the value ({})",
                types.display(ty),
                types.display(t)
            ),
        ));
    }
    Ok((place, storage))
}

fn get_data_val(cx: &mut Ctx<'_>) -> Exec<Value> {
    let target = ref_ty(cx, VALUE);
    // A signal variable and a name RAPID data does not have: the configured signal.
    if let Some(t) = target
        && t.rank == 0
        && cx.it.prog.types.name(t.base).starts_with("signal")
        && find_by_name(cx, cx.str(0)?).is_none()
    {
        return connect_signal(cx, t);
    }
    let (place, _) = object(cx, target)?;
    let value = cx
        .it
        .abs_get(&place)
        .map_err(|e| cx.it.walk_err(e, cx.span))?
        .clone();
    if !crate::interp::place::same_dims(cx.value(VALUE)?, &value) {
        return Err(cx.error(
            errnum::ERR_INVDIM,
            format!("`{}` has other array sizes than the variable", cx.str(0)?),
        ));
    }
    cx.set(VALUE, value)?;
    Ok(Value::Absent)
}

/// `GetDataVal "name", sig;` with a signal of the I/O configuration called `name`: `sig`
/// (of type `ty`) is connected to it.
fn connect_signal(cx: &mut Ctx<'_>, ty: Ty) -> Exec<Value> {
    let name = cx.str(0)?.to_string();
    let Some(kind) = cx.host().signal_kind(&name) else {
        return Err(cx.error(
            errnum::ERR_SYM_ACCESS,
            format!(
                "there is no data object or configured I/O signal `{name}` that this routine can reach"
            ),
        ));
    };
    let want = cx.it.prog.types.name(ty.base).to_string();
    if !want.eq_ignore_ascii_case(kind.rapid_type()) {
        return Err(cx.error(
            errnum::ERR_SYMBOL_TYPE,
            format!(
                "`{name}` is a {} signal ({}), the variable a {want}",
                kind.as_str(),
                kind.rapid_type()
            ),
        ));
    }
    cx.set(VALUE, Value::Record(vec![Value::str(&name)].into()))?;
    Ok(Value::Absent)
}

fn set_data_val(cx: &mut Ctx<'_>) -> Exec<Value> {
    let ty = match cx.args.get(VALUE) {
        Some(crate::ir::Arg::Value(e)) => value_ty(cx, e),
        _ => None,
    };
    let (place, storage) = object(cx, ty)?;
    if storage == Storage::Const || read_only_module(cx, &place) {
        return Err(cx.error(
            errnum::ERR_SYM_ACCESS,
            format!("`{}` is read-only: SetDataVal cannot change it", cx.str(0)?),
        ));
    }
    let value = cx.value(VALUE)?.clone();
    let old = cx
        .it
        .abs_get(&place)
        .map_err(|e| cx.it.walk_err(e, cx.span))?;
    if !crate::interp::place::same_dims(old, &value) {
        return Err(cx.error(
            errnum::ERR_INVDIM,
            format!("`{}` has other array sizes than the value", cx.str(0)?),
        ));
    }
    cx.it.store_abs(&place, value, cx.span)?;
    Ok(Value::Absent)
}

/// The static type of an IN argument, as far as it is known without the compiler: data,
/// literals, and the results of functions and records are matched by shape instead.
fn value_ty(cx: &Ctx<'_>, e: &crate::ir::Expr) -> Option<Ty> {
    use crate::ir::ExprKind as K;
    match &e.kind {
        K::Num(_) => Some(Ty::NUM),
        K::Dnum(_) => Some(Ty::DNUM),
        K::Bool(_) => Some(Ty::BOOL),
        K::Str(_) => Some(Ty::STRING),
        K::Global(g) => cx.it.prog.globals.get(*g as usize).map(|g| g.ty),
        K::Local(s) => {
            let frame = cx.it.frames.last()?;
            slot_ty(cx, frame.routine, *s).map(|t| t.0)
        }
        _ => None,
    }
}

fn arg_name(cx: &mut Ctx<'_>) -> Exec<Value> {
    let name = match cx.arg(0) {
        Some(NArg::Ref(place)) if place.path.is_empty() => match what_is(cx, 0) {
            Some(Origin::Global(g)) => Ok(cx.it.prog.globals[g].name.clone()),
            Some(Origin::Routine { routine, slot }) => {
                let r = &cx.it.prog.routines[routine.0 as usize];
                // An IN parameter holds a copy: the caller's data is not known here.
                if let Some(p) = r.params.iter().find(|p| p.slot == ParamSlot::Value(slot)) {
                    return Err(in_param_unsupported(cx, &p.name));
                }
                slot_ty(cx, routine, slot)
                    .map(|(_, n)| n)
                    .ok_or("a FOR variable")
            }
            None => Err("not a data object"),
        },
        Some(NArg::Ref(_)) => Err("a component or element, not an entire data object"),
        Some(NArg::Switch) => Err("a switch"),
        _ => Err("an expression, not a data object"),
    };
    match name {
        Ok(n) => {
            if cx.present(1) {
                cx.set(1, Value::Num(0.0))?;
            }
            cx.string(n)
        }
        Err(_) if cx.present(1) => {
            cx.set(1, Value::Num(errnum::ERR_ARGNAME as f32))?;
            Ok(Value::str(""))
        }
        Err(why) => Err(cx.error(
            errnum::ERR_ARGNAME,
            format!("the argument of ArgName is {why}"),
        )),
    }
}

fn in_param_unsupported(cx: &Ctx<'_>, param: &str) -> crate::interp::error::Unwind {
    cx.it.fatal(
        ErrorKind::Unsupported,
        cx.span,
        format!(
            "`ArgName` of the IN parameter `{param}` is not supported by rapidvc: an IN \
             parameter holds a copy, and rapidvc does not keep the name of the data it was \
             copied from (pass it as INOUT, or pass the name)"
        ),
    )
}

/// The static type of argument `i` (a reference's, or an IN argument's as far as
/// [`value_ty`] knows it), else `None`.
pub(super) fn arg_type(cx: &Ctx<'_>, i: usize) -> Option<Ty> {
    match cx.arg(i) {
        Some(NArg::Ref(_)) => ref_ty(cx, i),
        _ => match cx.args.get(i) {
            Some(crate::ir::Arg::Value(e)) => value_ty(cx, e),
            _ => None,
        },
    }
}

fn type_name(cx: &mut Ctx<'_>) -> Exec<Value> {
    let ty = match arg_type(cx, 0) {
        Some(t) => t,
        None => match cx.value(0)? {
            Value::Num(_) => Ty::NUM,
            Value::Dnum(_) => Ty::DNUM,
            Value::Bool(_) => Ty::BOOL,
            Value::Str(_) => Ty::STRING,
            _ => {
                return Err(cx.it.fatal(
                    ErrorKind::Unsupported,
                    cx.span,
                    "`Type` of a computed record value is not supported by rapidvc \
                     (give it a data object)",
                ));
            }
        },
    };
    // Arrays: the element type's name, as ABB's Type gives it.
    let name = cx.it.prog.types.name(ty.base).to_string();
    cx.string(name)
}
