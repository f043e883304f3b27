//! Searching the program's data: `SetDataSearch` starts a search, `GetNextSym` walks its
//! results (name and `datapos` block, which `GetDataVal`/`SetDataVal \Block` take), and
//! `SetAllDataVal` sets every matching data object at once.
//!
//! What rapidvc searches and decides where ABB documents nothing:
//! * Module data of the program's own modules (and modules loaded at run time), in module
//!   and declaration order, the controller's USER module (`reg1` … `reg5`) first. rapidvc's
//!   other embedded system modules (speeds, zones, `tool0`, …) are not searched.
//! * `\Object` is a regular expression matched anywhere in the name, without regard to case
//!   (write `^…$` to match whole names); without it every name matches.
//! * `\InRout` (routine data) is not supported: routine data exist only while their routine
//!   runs, and rapidvc reports the search as unsupported rather than finding nothing.
//! * `SetAllDataVal` sets variables and persistents (constants are never changed); the
//!   value must be of the searched type (`ERR_SYMBOL_TYPE`). `\Hidden` is accepted: rapidvc
//!   has no routine data in the search to hide.

use super::{Ctx, Registry};
use crate::interp::ErrorKind;
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::place::AbsPlace;
use crate::interp::value::Value;
use crate::ir::{GlobalOrigin, Storage};

/// A search of `SetDataSearch` and where `GetNextSym` is in it.
#[derive(Debug, Clone, Default)]
pub(crate) struct Search {
    /// The matching data: (name, module number + 1 as the `datapos` block).
    found: Vec<(String, u32)>,
    next: usize,
}

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add(
        r"PROC SetDataSearch(string Type, \string TypeMod, \string Object, \switch PersSym, \switch VarSym, \switch ConstSym, \switch InTask | string InMod, \string InRout, \switch GlobalSym | switch LocalSym)",
        |cx| {
            let filter = Filter {
                ty: 0,
                type_mod: Some(1),
                object: Some(2),
                storage: Some((3, 4, 5)),
                in_mod: Some(7),
                in_rout: Some(8),
                scope: Some((9, 10)),
            };
            let found = search(cx, &filter)?;
            cx.it.modules.search = Some(Search { found, next: 0 });
            Ok(Value::Absent)
        },
    );
    r.add(
        r"FUNC bool GetNextSym(INOUT string Object, INOUT datapos Block, \switch Recursive)",
        |cx| {
            let next = cx.it.modules.search.as_mut().and_then(|s| {
                let item = s.found.get(s.next).cloned();
                s.next += 1;
                item
            });
            let Some((name, block)) = next else {
                return Ok(Value::Bool(false));
            };
            cx.set(0, Value::str(&name))?;
            cx.set(1, Value::Record(Box::new([Value::Num(block as f32)])))?;
            Ok(Value::Bool(true))
        },
    );
    r.add(
        r"PROC SetAllDataVal(string Type, \string TypeMod, \string Object, \switch Hidden, anytype Value)",
        |cx| {
            let filter = Filter {
                ty: 0,
                type_mod: Some(1),
                object: Some(2),
                storage: None,
                in_mod: None,
                in_rout: None,
                scope: None,
            };
            let found = search(cx, &filter)?;
            let value = cx.value(4)?.clone();
            let prog = cx.it.prog.clone();
            let type_name = cx.str(0)?.to_string();
            for (name, block) in found {
                let g = prog.globals.iter().position(|g| {
                    g.name == name && g.origin == GlobalOrigin::Module(crate::ir::ModuleId(block - 1))
                });
                let Some(g) = g else { continue };
                let decl = &prog.globals[g];
                if decl.storage == Storage::Const {
                    continue;
                }
                if !crate::interp::pers::fits(&prog.types, decl.ty, &value)
                    || !crate::interp::place::same_dims(&cx.it.globals[g], &value)
                {
                    return Err(cx.error(
                        errnum::ERR_SYMBOL_TYPE,
                        format!("the value is not a `{type_name}` as `{name}` is"),
                    ));
                }
                cx.it
                    .store_abs(&AbsPlace::global(g as u32), value.clone(), cx.span)?;
            }
            Ok(Value::Absent)
        },
    );
}

/// Which arguments of the native say what to search.
struct Filter {
    ty: usize,
    type_mod: Option<usize>,
    object: Option<usize>,
    /// `\PersSym`, `\VarSym`, `\ConstSym`.
    storage: Option<(usize, usize, usize)>,
    in_mod: Option<usize>,
    in_rout: Option<usize>,
    /// `\GlobalSym`, `\LocalSym`.
    scope: Option<(usize, usize)>,
}

/// The data matching the arguments: (name, module number + 1).
fn search(cx: &Ctx<'_>, f: &Filter) -> Exec<Vec<(String, u32)>> {
    let given = |i: Option<usize>| i.is_some_and(|i| cx.present(i));
    if given(f.in_rout) {
        return Err(cx.it.fatal(
            ErrorKind::Unsupported,
            cx.span,
            "searching routine data (`\\InRout`) is not supported by rapidvc: it searches \
             module data",
        ));
    }
    let prog = &cx.it.prog;
    let type_name = cx.str(f.ty)?;
    let Some(ty) = prog.types.lookup(type_name) else {
        return Err(cx.error(
            errnum::ERR_SYMBOL_TYPE,
            format!("there is no data type `{type_name}`"),
        ));
    };
    let type_mod = match f.type_mod {
        Some(i) if cx.present(i) => Some(cx.str(i)?),
        _ => None,
    };
    if let Some(m) = type_mod
        && !prog.modules.iter().any(|x| x.name.eq_ignore_ascii_case(m))
    {
        return Err(cx.error(errnum::ERR_MODULE, format!("no module `{m}`")));
    }
    let pattern = match f.object {
        Some(i) if cx.present(i) => {
            let text = cx.str(i)?;
            let re = regex::RegexBuilder::new(text)
                .case_insensitive(true)
                .size_limit(1 << 20)
                .build()
                .map_err(|e| {
                    cx.error(
                        errnum::ERR_ARGVALERR,
                        format!("`{text}` is not a regular expression: {e}"),
                    )
                })?;
            Some(re)
        }
        _ => None,
    };
    let (pers, var, cons) = match f.storage {
        Some((p, v, c)) => (cx.present(p), cx.present(v), cx.present(c)),
        None => (false, false, false),
    };
    let any_storage = !(pers || var || cons);
    let in_mod = match f.in_mod {
        Some(i) if cx.present(i) => Some(cx.str(i)?),
        _ => None,
    };
    let (global_only, local_only) = match f.scope {
        Some((g, l)) => (cx.present(g), cx.present(l)),
        None => (false, false),
    };
    let mut found = Vec::new();
    for g in &prog.globals {
        let GlobalOrigin::Module(m) = g.origin else {
            continue;
        };
        let module = &prog.modules[m.0 as usize];
        let storage_ok = any_storage
            || match g.storage {
                Storage::Pers => pers,
                Storage::Var => var,
                Storage::Const => cons,
            };
        let ok = !module.stdlib
            && prog.types.resolve(g.ty.base) == prog.types.resolve(ty)
            && storage_ok
            && in_mod.is_none_or(|n| module.name.eq_ignore_ascii_case(n))
            && (!global_only || !g.local)
            && (!local_only || g.local)
            && pattern.as_ref().is_none_or(|re| re.is_match(&g.name));
        if ok {
            found.push((g.name.clone(), m.0 + 1));
        }
    }
    Ok(found)
}
