//! RAPID data over RWS: `rw/rapid/symbol/data/RAPID/{task}[/{module}]/{name}` (value as RAPID
//! text, read and write), `rw/rapid/symbol/properties/RAPID/…` (storage class, data type,
//! dimensions) and `rw/rapid/symbols?action=search-symbols` (the data of a task or module).

use std::sync::Arc;

use axum::http::{Method, StatusCode};

use super::repr::{Item, RwsError, State, codes};
use super::{Answer, Outcome, Rq, Shared};
use crate::controller::service::{OpMode, Request, SymbolClass, SymbolInfo, SymbolPath};

/// The symbol named by `[task, name]` or `[task, module, name]` (a `;value` suffix dropped).
pub(super) fn symbol_path(rest: &[&str]) -> Result<SymbolPath, RwsError> {
    let strip = |s: &str| s.split(';').next().unwrap_or(s).to_string();
    match rest {
        [task, name] => Ok(SymbolPath {
            task: task.to_string(),
            module: None,
            name: strip(name),
        }),
        [task, module, name] => Ok(SymbolPath {
            task: task.to_string(),
            module: Some(module.to_string()),
            name: strip(name),
        }),
        _ => Err(RwsError::not_found(format!(
            "no symbol `RAPID/{}`: use RAPID/{{task}}/{{name}} or RAPID/{{task}}/{{module}}/{{name}}",
            rest.join("/")
        ))),
    }
}

/// `RAPID/T_ROB1/Module/name`.
pub(super) fn symburl(p: &SymbolPath) -> String {
    match &p.module {
        Some(m) => format!("RAPID/{}/{m}/{}", p.task, p.name),
        None => format!("RAPID/{}/{}", p.task, p.name),
    }
}

fn class_names(c: SymbolClass) -> (&'static str, &'static str) {
    match c {
        SymbolClass::Pers => ("rap-symproppers", "per"),
        SymbolClass::Var => ("rap-sympropvar", "var"),
        SymbolClass::Const => ("rap-sympropconstant", "con"),
    }
}

fn properties_item(s: &SymbolInfo, list: bool) -> Item {
    let (class, symtyp) = class_names(s.class);
    let class = if list {
        format!("{class}-li")
    } else {
        class.to_string()
    };
    let url = symburl(&s.path);
    let dims: Vec<String> = s.dims.iter().map(u32::to_string).collect();
    let mut item = Item::new(&class, url.clone())
        .field("symburl", &url)
        .field("name", &s.path.name)
        .field("symtyp", symtyp)
        .field("named", "true")
        .field("dattyp", &s.data_type)
        .field("typurl", format!("RAPID/{}", s.data_type))
        .field("ndim", s.dims.len());
    if !dims.is_empty() {
        item = item.field("dim", dims.join(" "));
    }
    item.field(
        "rdonly",
        if s.class == SymbolClass::Const {
            "true"
        } else {
            "false"
        },
    )
}

pub(super) async fn data(shared: &Arc<Shared>, rq: &Rq, rest: &[&str]) -> Outcome {
    let path = symbol_path(rest)?;
    match (&rq.method, rq.action()) {
        (&Method::GET, None) => {
            let s = shared
                .ask(|reply| Request::Symbol {
                    path: path.clone(),
                    reply,
                })
                .await?;
            Ok(Answer::Ok(
                State::new(
                    "rapid",
                    "rw/rapid/",
                    format!("symbol/data/{}", symburl(&path)),
                )
                .item(Item::new("rap-data", symburl(&s.path)).field("value", &s.value)),
            ))
        }
        (&Method::POST, Some("set")) => {
            let value = rq.need("value")?.to_string();
            if value.len() > 1 << 16 {
                return Err(RwsError::bad("a value longer than 64 KiB"));
            }
            check_rmmp(shared, rq).await?;
            shared
                .ask(|reply| Request::SetSymbol { path, value, reply })
                .await?;
            Ok(Answer::NoContent)
        }
        _ => Err(rq.unknown_action()),
    }
}

/// In a manual mode, writing RAPID data needs remote mastering (`users/rmmp`) granted to the
/// session, as on a controller.
async fn check_rmmp(shared: &Arc<Shared>, rq: &Rq) -> Result<(), RwsError> {
    if shared.ask(Request::OpMode).await? == OpMode::Auto {
        return Ok(());
    }
    let granted = shared
        .registry()
        .sessions
        .get_mut(&rq.session)
        .is_some_and(|s| s.rmmp.is_some());
    if granted {
        Ok(())
    } else {
        Err(RwsError::new(
            StatusCode::FORBIDDEN,
            codes::NOT_ALLOWED,
            "in manual mode, writing RAPID data needs remote mastering: POST users/rmmp first",
        ))
    }
}

pub(super) async fn properties(shared: &Arc<Shared>, rq: &Rq, rest: &[&str]) -> Outcome {
    if rq.method != Method::GET || rq.action().is_some() {
        return Err(rq.unknown_action());
    }
    let path = symbol_path(rest)?;
    let s = shared
        .ask(|reply| Request::Symbol {
            path: path.clone(),
            reply,
        })
        .await?;
    Ok(Answer::Ok(
        State::new(
            "rapid",
            "rw/rapid/",
            format!("symbol/properties/{}", symburl(&path)),
        )
        .item(properties_item(&s, false)),
    ))
}

pub(super) async fn search(shared: &Arc<Shared>, rq: &Rq) -> Outcome {
    match (&rq.method, rq.action()) {
        (&Method::POST, Some("search-symbols" | "search-symbol")) => {}
        _ => return Err(rq.unknown_action()),
    }
    let view = rq.form("view").unwrap_or("block");
    if !view.eq_ignore_ascii_case("block") {
        return Err(RwsError::unsupported(format!(
            "`view={view}` (only view=block)"
        )));
    }
    if let Some(re) = rq.form("regexp").filter(|r| !r.is_empty()) {
        return Err(RwsError::unsupported(format!("`regexp={re}`")));
    }
    let class = match rq
        .form("symtyp")
        .unwrap_or("any")
        .to_ascii_lowercase()
        .as_str()
    {
        "any" | "udef" => None,
        "per" => Some(SymbolClass::Pers),
        "var" => Some(SymbolClass::Var),
        "con" => Some(SymbolClass::Const),
        other => {
            return Err(RwsError::unsupported(format!(
                "`symtyp={other}` (rapidvc searches data: per, var, con, any)"
            )));
        }
    };
    let dattyp = rq.form("dattyp").filter(|d| !d.is_empty());
    let block = rq.form("blockurl").unwrap_or("RAPID");
    let parts: Vec<&str> = block.split('/').filter(|p| !p.is_empty()).collect();
    let (tasks, module): (Vec<String>, Option<&str>) = match parts.as_slice() {
        ["RAPID"] => (
            shared
                .ask(Request::Tasks)
                .await?
                .into_iter()
                .map(|t| t.name)
                .collect(),
            None,
        ),
        ["RAPID", task] => (vec![task.to_string()], None),
        ["RAPID", task, module] => (vec![task.to_string()], Some(*module)),
        _ => {
            return Err(RwsError::bad(format!(
                "`blockurl={block}`: expected RAPID, RAPID/{{task}} or RAPID/{{task}}/{{module}}"
            )));
        }
    };
    let mut st = State::new("rapid", "rw/rapid/", "symbols?action=search-symbols");
    for task in tasks {
        let list = shared
            .ask(|reply| Request::Symbols { task, class, reply })
            .await?;
        for s in list.iter().filter(|s| {
            module.is_none_or(|m| {
                s.path
                    .module
                    .as_deref()
                    .is_some_and(|sm| sm.eq_ignore_ascii_case(m))
            }) && dattyp.is_none_or(|d| s.data_type.eq_ignore_ascii_case(d))
        }) {
            st = st.item(properties_item(s, true));
        }
    }
    Ok(Answer::Ok(st))
}
