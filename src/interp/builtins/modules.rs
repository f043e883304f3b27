//! Program modules at run time: `Load`, `StartLoad`/`WaitLoad`/`CancelLoad`, `UnLoad`,
//! `EraseModule`, `Save`, `CheckProgRef`, `ModExist`, `ModTime`, and the calls that find
//! procedures by name at run time, `CallByVar` (late binding `%"name"%` is in the
//! interpreter), and `RemainingRetries`.
//!
//! Modules come from the controller's mass storage (`HOME:`, `TEMP:`, `RAMDISK:`, never a
//! host path outside them) and are parsed and checked by the same front end as the program
//! (through the [`ModuleLoader`](crate::interp::relink::ModuleLoader) the program layer
//! gives the interpreter). What rapidvc decides where ABB documents nothing or where a
//! virtual controller differs:
//!
//! * Loading is immediate: `StartLoad` reads the file at once and `WaitLoad` links it, so
//!   nothing runs between them in the background. `\Dynamic` is accepted; every module
//!   loaded stays until `UnLoad`/`EraseModule` or the end of the run.
//! * A syntax error in a loaded module is `ERR_SYNTAX`; a module that does not pass the
//!   semantic check (an unknown name, a wrong type, a duplicate) is `ERR_LINKREF`, with
//!   rapidvc's diagnostic in the error text. rapidvc never runs a program with unresolved
//!   references, so `\CheckRef` changes nothing and `CheckProgRef` always succeeds.
//! * A module cannot be unloaded while one of its routines runs or one of its TRAPs is
//!   connected (`ERR_UNLOAD`).
//! * `Save` (and `UnLoad \Save`) writes the module as a controller does: its text as
//!   loaded, with the initial value of each of its `PERS` declarations replaced by the
//!   persistent's current value (`PERS num n := 1;` becomes `PERS num n := 7;`; one
//!   declared without a value gets ` := value`). Routines, comments and layout stay as
//!   they were.
//! * `UnLoad \ErrIfChanged` raises `ERR_NOTSAVED` (and leaves the module loaded) when a
//!   persistent of the module changed since it was loaded or last saved; the module's code
//!   cannot change while it runs, so its persistents are what can.

use std::path::PathBuf;

use super::{Ctx, Registry};
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::pers;
use crate::interp::relink::{LinkError, NewModule, Session};
use crate::interp::value::Value;
use crate::ir::{GlobalOrigin, RoutineKind, Storage};

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    // ABB: "ModExist is used to check whether a given module exists in the program task";
    // module names are compared without regard to case, as every RAPID name.
    r.add("FUNC bool ModExist(string ModuleName)", |cx| {
        let name = cx.str(0)?;
        let found = cx
            .it
            .prog
            .modules
            .iter()
            .any(|m| m.name.eq_ignore_ascii_case(name));
        Ok(Value::Bool(found))
    });
    r.add(
        r"PROC Load(\switch Dynamic, string FilePath, \string File, \switch CheckRef)",
        |cx| {
            cx.it.loader_or(cx.span, "Load")?;
            let path = full_path(cx, 1, 2)?;
            let session = read_module(cx, &path)?;
            link(cx, &session)
        },
    );
    r.add(
        r"PROC StartLoad(\switch Dynamic, string FilePath, \string File, VAR loadsession LoadNo)",
        |cx| {
            cx.it.loader_or(cx.span, "StartLoad")?;
            let id = session_id(cx, 3)?;
            if cx
                .it
                .modules
                .sessions
                .iter()
                .any(|(s, _)| *s == id && id != 0)
            {
                return Err(cx.error(
                    errnum::ERR_LOADNO_INUSE,
                    "the load session is in use: WaitLoad or CancelLoad it first",
                ));
            }
            let path = full_path(cx, 1, 2)?;
            let session = read_module(cx, &path)?;
            cx.it.modules.next_session = cx.it.modules.next_session.wrapping_add(1).max(1);
            let id = cx.it.modules.next_session;
            cx.it.modules.sessions.push((id, session));
            cx.set(3, Value::Record(Box::new([Value::Num(id as f32)])))?;
            Ok(Value::Absent)
        },
    );
    r.add(
        r"PROC WaitLoad(\string UnloadPath, \string UnloadFile, VAR loadsession LoadNo, \switch CheckRef)",
        |cx| {
            cx.it.loader_or(cx.span, "WaitLoad")?;
            let session = take_session(cx, 2)?;
            if cx.present(0) {
                let path = full_path(cx, 0, 1)?;
                unload(cx, &path)?;
            }
            link(cx, &session)
        },
    );
    r.add(r"PROC CancelLoad(VAR loadsession LoadNo)", |cx| {
        take_session(cx, 0)?;
        Ok(Value::Absent)
    });
    r.add(
        r"PROC UnLoad(\switch ErrIfChanged | switch Save, string FilePath, \string File)",
        |cx| {
            cx.it.loader_or(cx.span, "UnLoad")?;
            let path = full_path(cx, 2, 3)?;
            if cx.present(0) {
                let name = loaded_from(cx, &path)?;
                let (_, now) = text_now(cx, &name)?;
                let then = cx
                    .it
                    .modules
                    .saved_pers
                    .iter()
                    .find(|(n, _)| n.eq_ignore_ascii_case(&name))
                    .map(|(_, v)| v.as_str());
                if then.is_some_and(|t| t != now) {
                    return Err(cx.error(
                        errnum::ERR_NOTSAVED,
                        format!(
                            "module `{name}` changed since it was loaded or saved (its persistents have other values); save it first or unload it without \\ErrIfChanged"
                        ),
                    ));
                }
            }
            if cx.present(1) {
                let name = loaded_from(cx, &path)?;
                save(cx, &name, &path)?;
            }
            unload(cx, &path)
        },
    );
    r.add(r"PROC EraseModule(string ModuleName)", |cx| {
        cx.it.loader_or(cx.span, "EraseModule")?;
        let name = module_name(cx, 0)?;
        remove(cx, &name)
    });
    r.add(
        r"PROC Save(\string TaskName, string ModuleName, \string FilePath, \string File)",
        |cx| {
            cx.it.loader_or(cx.span, "Save")?;
            if cx.present(0) {
                // One task per program (several tasks are a controller of several programs).
                let task = cx.str(0)?.to_string();
                let own = cx
                    .host()
                    .system()
                    .map(|s| s.info.task.clone())
                    .unwrap_or_else(|| "T_ROB1".to_string());
                if !task.eq_ignore_ascii_case(&own) {
                    return Err(cx.error(
                        errnum::ERR_ARGVALERR,
                        format!("there is no task `{task}` in this program (it is `{own}`)"),
                    ));
                }
            }
            let name = module_name(cx, 1)?;
            let path = if cx.present(2) {
                full_path(cx, 2, 3)?
            } else {
                let Some(file) = cx.it.modules.loader.as_ref().and_then(|l| l.module(&name)) else {
                    return Err(cx.error(errnum::ERR_MODULE, format!("no module `{name}`")));
                };
                match (file.path, cx.present(3)) {
                    (Some(p), _) => p,
                    (None, true) => format!("HOME:/{}", cx.str(3)?),
                    (None, false) => {
                        return Err(cx.error(
                            errnum::ERR_MODULE,
                            format!(
                                "module `{name}` was not loaded from the controller's mass \
                                 storage: give \\FilePath"
                            ),
                        ));
                    }
                }
            };
            save(cx, &name, &path)?;
            Ok(Value::Absent)
        },
    );
    // rapidvc never runs a program with unresolved references (see the module notes).
    r.add(r"PROC CheckProgRef()", |_| Ok(Value::Absent));
    r.add(r"FUNC num ModTime(string Object)", |cx| {
        let name = cx.str(0)?.to_string();
        let file = cx.it.modules.loader.as_ref().and_then(|l| l.module(&name));
        match file {
            None if cx.it.modules.loader.is_none() => {
                cx.it.loader_or(cx.span, "ModTime")?;
                Ok(Value::Absent)
            }
            None => Err(cx.error(errnum::ERR_MODULE, format!("no module `{name}`"))),
            Some(f) => match f.modified {
                Some(t) => cx.num_result(t),
                None => Err(cx.error(
                    errnum::ERR_FILEACC,
                    format!("module `{name}` was not read from a file with a time"),
                )),
            },
        }
    });
    r.add(r"PROC CallByVar(string Name, num Number)", call_by_var);
    // ABB: "RemainingRetries is used to find out how many RETRY that is left to do from the
    // error handler"; outside a handler every retry is left.
    r.add(r"FUNC num RemainingRetries()", |cx| {
        let limit = cx.it.retry_limit;
        let used = match cx.it.frames.last() {
            Some(f) if f.handling.is_some() => f.retries,
            _ => 0,
        };
        Ok(Value::Num(limit.saturating_sub(used) as f32))
    });
}

/// `FilePath` (argument `path`) with `\File` (argument `file`) appended when given.
fn full_path(cx: &Ctx<'_>, path: usize, file: usize) -> Exec<String> {
    let p = cx.str(path)?.to_string();
    if !cx.present(file) {
        return Ok(p);
    }
    let f = cx.str(file)?;
    Ok(if p.ends_with('/') || p.ends_with(':') {
        format!("{p}{f}")
    } else {
        format!("{p}/{f}")
    })
}

/// The host file behind controller path `path` (refused paths: `ERR_FILEACC`).
fn host_path(cx: &mut Ctx<'_>, path: &str) -> Exec<PathBuf> {
    super::files::resolve(cx, path, errnum::ERR_FILEACC)
}

/// Read the module file at controller path `path`.
fn read_module(cx: &mut Ctx<'_>, path: &str) -> Exec<Session> {
    let host = host_path(cx, path)?;
    let bytes = match std::fs::read(&host) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(cx.error(errnum::ERR_FILNOTFND, format!("no file `{path}`")));
        }
        Err(e) => {
            return Err(cx.error(errnum::ERR_IOERROR, format!("`{path}` cannot be read: {e}")));
        }
    };
    // RAPID files are UTF-8 or, from older controllers, Latin-1.
    let text = match String::from_utf8(bytes) {
        Ok(t) => t,
        Err(e) => e.into_bytes().iter().map(|&b| char::from(b)).collect(),
    };
    let modified = std::fs::metadata(&host)
        .and_then(|m| m.modified())
        .ok()
        .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
        .map(|d| d.as_secs() as f64);
    Ok(Session {
        path: path.to_string(),
        text,
        modified,
    })
}

/// Link the module read into the program.
fn link(cx: &mut Ctx<'_>, s: &Session) -> Exec<Value> {
    let registry = cx.it.registry.clone();
    let host = host_path(cx, &s.path)?;
    let linked = match cx.it.modules.loader.as_mut() {
        Some(l) => l.add(
            &registry,
            NewModule {
                path: &s.path,
                text: &s.text,
                modified: s.modified,
            },
        ),
        None => return Ok(Value::Absent),
    };
    let prog = linked.map_err(|e| link_error(cx, e))?;
    let name = prog
        .modules
        .last()
        .map(|m| m.name.clone())
        .unwrap_or_default();
    if let Err(e) = cx.it.relink(prog) {
        // Back to the program without it (the loader has it already).
        if let Some(l) = cx.it.modules.loader.as_mut() {
            let _ = l.remove(&registry, &name);
        }
        return Err(link_error(cx, e));
    }
    let (_, values) = text_now(cx, &name)?;
    cx.it.modules.saved_pers.push((name.clone(), values));
    cx.it.modules.loaded_from.push((host, name));
    Ok(Value::Absent)
}

fn link_error(cx: &Ctx<'_>, e: LinkError) -> crate::interp::error::Unwind {
    cx.error(e.errno, e.message)
}

/// The session number in `loadsession` argument `i` (0: never started).
fn session_id(cx: &Ctx<'_>, i: usize) -> Exec<u32> {
    match cx.value(i)?.fields() {
        Some([Value::Num(n)]) => Ok(*n as u32),
        _ => Ok(0),
    }
}

/// End the load session in argument `i` and give its module.
fn take_session(cx: &mut Ctx<'_>, i: usize) -> Exec<Session> {
    let id = session_id(cx, i)?;
    let pos = cx.it.modules.sessions.iter().position(|(s, _)| *s == id);
    let Some(pos) = pos.filter(|_| id != 0) else {
        return Err(cx.error(
            errnum::ERR_LOADNO_NOUSE,
            "the load session is not in use (no StartLoad for it, or it ended)",
        ));
    };
    let (_, session) = cx.it.modules.sessions.remove(pos);
    cx.set(i, Value::Record(Box::new([Value::Num(0.0)])))?;
    Ok(session)
}

/// The module loaded from controller path `path`.
fn loaded_from(cx: &mut Ctx<'_>, path: &str) -> Exec<String> {
    let host = host_path(cx, path)?;
    let found = cx
        .it
        .modules
        .loaded_from
        .iter()
        .find(|(h, _)| *h == host)
        .map(|(_, n)| n.clone());
    found.ok_or_else(|| {
        cx.error(
            errnum::ERR_UNLOAD,
            format!("no module was loaded from `{path}`"),
        )
    })
}

/// Unload the module loaded from `path`.
fn unload(cx: &mut Ctx<'_>, path: &str) -> Exec<Value> {
    let name = loaded_from(cx, path)?;
    remove(cx, &name)
}

/// The module called by string argument `i` (`ERR_MODULE` when there is none).
fn module_name(cx: &Ctx<'_>, i: usize) -> Exec<String> {
    let name = cx.str(i)?;
    cx.it
        .prog
        .modules
        .iter()
        .find(|m| m.name.eq_ignore_ascii_case(name) && !m.stdlib)
        .map(|m| m.name.clone())
        .ok_or_else(|| cx.error(errnum::ERR_MODULE, format!("no module `{name}`")))
}

/// Take module `name` out of the program.
fn remove(cx: &mut Ctx<'_>, name: &str) -> Exec<Value> {
    let registry = cx.it.registry.clone();
    let Some(loader) = cx.it.modules.loader.as_mut() else {
        return Ok(Value::Absent);
    };
    let Some(file) = loader.module(name) else {
        return Err(cx.error(errnum::ERR_MODULE, format!("no module `{name}`")));
    };
    let prog = loader
        .remove(&registry, name)
        .map_err(|e| LinkError {
            errno: errnum::ERR_UNLOAD,
            message: e.message,
        })
        .map_err(|e| link_error(cx, e))?;
    if let Err(e) = cx.it.relink(prog) {
        // Put it back: the program goes on as it was.
        if let Some(l) = cx.it.modules.loader.as_mut() {
            let _ = l.add(
                &registry,
                NewModule {
                    path: file.path.as_deref().unwrap_or(""),
                    text: &file.text,
                    modified: file.modified,
                },
            );
        }
        return Err(link_error(cx, e));
    }
    cx.it
        .modules
        .loaded_from
        .retain(|(_, n)| !n.eq_ignore_ascii_case(name));
    cx.it
        .modules
        .saved_pers
        .retain(|(n, _)| !n.eq_ignore_ascii_case(name));
    Ok(Value::Absent)
}

/// Module `name` as `Save` writes it (its text with the current values of its persistents),
/// and those values alone as text (to tell whether they changed).
fn text_now(cx: &Ctx<'_>, name: &str) -> Exec<(String, String)> {
    let Some(loader) = cx.it.modules.loader.as_ref() else {
        return Err(cx.error(errnum::ERR_MODULE, format!("no module `{name}`")));
    };
    let Some(file) = loader.module(name) else {
        return Err(cx.error(errnum::ERR_MODULE, format!("no module `{name}`")));
    };
    let prog = &cx.it.prog;
    let Some(mid) = prog
        .modules
        .iter()
        .position(|m| m.name.eq_ignore_ascii_case(name))
    else {
        return Err(cx.error(errnum::ERR_MODULE, format!("no module `{name}`")));
    };
    // (start, end, replacement) in the text the declarations were read from.
    let mut edits: Vec<(usize, usize, String)> = Vec::new();
    let mut values = String::new();
    let mut base: Option<crate::source::SourceText> = None;
    for (i, g) in prog.globals.iter().enumerate() {
        let in_module = matches!(g.origin, GlobalOrigin::Module(m) if m.0 as usize == mid);
        if !in_module || g.storage != Storage::Pers {
            continue;
        }
        let Some(value) = cx.it.globals.get(i) else {
            continue;
        };
        let text = pers::to_text(value);
        values.push_str(&g.name);
        values.push('=');
        values.push_str(&text);
        values.push('\n');
        let source = &loader.sources().get(g.span.source).text;
        if base
            .as_ref()
            .is_some_and(|b| !crate::source::SourceText::ptr_eq(b, source))
        {
            // Declarations from two texts: not one module file; keep the text as loaded.
            return Ok((file.text.to_string(), values));
        }
        base = Some(source.clone());
        let edit = match &g.init {
            Some(init) => Some((init.span.start as usize, init.span.end as usize, text)),
            // `PERS num n;` gets its value before the `;`.
            None => {
                let decl = source.get(g.span.start as usize..g.span.end as usize);
                decl.and_then(|d| d.trim_end().strip_suffix(';'))
                    .map(|d| g.span.start as usize + d.trim_end().len())
                    .map(|at| (at, at, format!(" := {text}")))
            }
        };
        edits.extend(edit);
    }
    let Some(base) = base else {
        return Ok((file.text.to_string(), values));
    };
    edits.sort_by_key(|e| e.0);
    let mut out = String::with_capacity(base.len());
    let mut at = 0;
    for (start, end, text) in edits {
        let Some(kept) = base.get(at..start).filter(|_| end >= start) else {
            return Ok((file.text.to_string(), values));
        };
        out.push_str(kept);
        out.push_str(&text);
        at = end;
    }
    out.push_str(base.get(at..).unwrap_or(""));
    Ok((out, values))
}

/// Write module `name` to controller path `path`, with the current values of its
/// persistents.
fn save(cx: &mut Ctx<'_>, name: &str, path: &str) -> Exec<()> {
    let (text, values) = text_now(cx, name)?;
    let host = host_path(cx, path)?;
    std::fs::write(&host, text.as_bytes()).map_err(|e| {
        cx.error(
            errnum::ERR_IOERROR,
            format!("module `{name}` cannot be written to `{path}`: {e}"),
        )
    })?;
    let saved = &mut cx.it.modules.saved_pers;
    match saved.iter_mut().find(|(n, _)| n.eq_ignore_ascii_case(name)) {
        Some((_, v)) => *v = values,
        None => saved.push((name.to_string(), values)),
    }
    Ok(())
}

/// `CallByVar Name, Number`: calls the procedure `Name` followed by the number, e.g.
/// `CallByVar "proc", 2` calls `proc2` (the procedure must take no arguments).
fn call_by_var(cx: &mut Ctx<'_>) -> Exec<Value> {
    let n = cx.int(1, "Number")?;
    if n < 0 {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("Number must be 0 or more, not {n}"),
        ));
    }
    let name = format!("{}{n}", cx.str(0)?);
    let code = cx.it.code.clone();
    let p = code.prog.clone();
    let Some(rid) = p
        .procs_by_name
        .get(&name.to_ascii_uppercase())
        .and_then(|l| {
            let module = cx.it.frames.last().map(|f| cx.p.routine(f.routine).module);
            l.iter()
                .copied()
                .find(|&r| !p.routine(r).local || Some(p.routine(r).module) == module)
        })
    else {
        return Err(cx.error(
            errnum::ERR_REFUNKPRC,
            format!("there is no procedure `{name}`"),
        ));
    };
    let r = p.routine(rid);
    if r.kind != RoutineKind::Proc || r.params.iter().any(|q| !q.optional) {
        return Err(cx.error(
            errnum::ERR_CALLPROC,
            format!(
                "`{}` needs arguments: CallByVar calls procedures without any",
                r.name
            ),
        ));
    }
    let span = cx.span;
    let (bp, rbp) = (cx.it.sp, cx.it.refs.len());
    for q in &r.params {
        match q.slot {
            crate::ir::ParamSlot::Value(_) => cx.it.push_value(Value::Absent),
            crate::ir::ParamSlot::Ref(_) => cx.it.refs.push(crate::interp::place::AbsPlace {
                root: crate::interp::place::AbsRoot::Absent,
                path: Vec::new(),
            }),
        }
    }
    cx.it.enter(&code, rid, bp, rbp, span)?;
    Ok(Value::Absent)
}
