//! `rw/system` (system name, RobotWare version, options), `ctrl` (controller identity and
//! type) and `rw/cfg/{domain}/{type}/instances` (configuration instances).

use std::sync::Arc;

use axum::http::Method;

use super::repr::{Item, State};
use super::{Answer, Outcome, Rq, Shared};
use crate::controller::service::{CfgInstance, Request};

/// The version name clients parse as `major.minor.revision.build` (abb_egm_rws_managers
/// wants three `N.` groups): the controller's `M.mm.pp` with build `00`.
pub(super) fn version_name(version: &str) -> String {
    if version.split('.').count() >= 4 {
        version.to_string()
    } else {
        format!("{version}.00")
    }
}

/// The option name of ABB's StateMachine add-in (version 1.1), which abb_egm_rws_managers
/// looks for before it reads the add-in's RAPID data.
const STATE_MACHINE: &str = "StateMachine Core";

/// The module of the StateMachine add-in's RAPID that holds its state (`current_state`).
const STATE_MACHINE_MODULE: &str = "TRobMain";

/// Whether every motion task has the StateMachine add-in's main module loaded: rapidvc does
/// not ship the add-in, but a system whose motion task has RAPID of that shape (loaded by the
/// user) is listed with the add-in's option, so the ROS drivers use it.
async fn state_machine_loaded(shared: &Arc<Shared>) -> Result<bool, super::repr::RwsError> {
    let tasks = shared.ask(Request::Tasks).await?;
    let mut any = false;
    for t in tasks.into_iter().filter(|t| t.motion_task) {
        let task = t.name;
        let modules = shared.ask(|reply| Request::Modules { task, reply }).await?;
        if !modules
            .iter()
            .any(|m| m.name.eq_ignore_ascii_case(STATE_MACHINE_MODULE))
        {
            return Ok(false);
        }
        any = true;
    }
    Ok(any)
}

pub(super) async fn system(shared: &Arc<Shared>, rq: &Rq) -> Outcome {
    if rq.method != Method::GET || rq.action().is_some() {
        return Err(rq.unknown_action());
    }
    let info = shared.ask(Request::System).await?;
    let mut options = info.options.clone();
    if state_machine_loaded(shared).await? {
        options.push(STATE_MACHINE.to_string());
    }
    let mut st = State::new("system", "rw/", "system").item(
        Item::new("sys-system-li", info.name.clone())
            .field("name", &info.name)
            .field("rwversion", &info.robotware_version)
            .field("sysid", &info.serial)
            .field("rwversionname", version_name(&info.robotware_version)),
    );
    for o in &options {
        st = st.item(Item::new("sys-option-li", o.clone()).field("option", o));
    }
    Ok(Answer::Ok(st))
}

pub(super) async fn ctrl(shared: &Arc<Shared>, rq: &Rq) -> Outcome {
    if rq.method != Method::GET || rq.action().is_some() {
        return Err(rq.unknown_action());
    }
    let info = shared.ask(Request::System).await?;
    Ok(Answer::Ok(
        State::new("ctrl", "", "ctrl").item(
            Item::new("ctrl-identity-info-li", "identity")
                .field("ctrl-name", &info.name)
                .field("ctrl-type", "Virtual Controller")
                .field("ctrl-id", &info.serial),
        ),
    ))
}

/// How a domain spells the name attribute: `name` in MOC, `Name` elsewhere (as RobotWare's
/// own files and abb_librws spell them), whatever the loaded file wrote.
fn name_title(domain: &str) -> &'static str {
    if domain.eq_ignore_ascii_case("moc") {
        "name"
    } else {
        "Name"
    }
}

/// One instance: its name first, then every other attribute in file order.
fn instance_item(domain: &str, type_name: &str, i: &CfgInstance) -> Item {
    let mut attrs = Vec::with_capacity(i.attributes.len() + 1);
    attrs.push(Item::new("cfg-ia-t-li", name_title(domain)).field("value", &i.name));
    for (k, v) in &i.attributes {
        if !k.eq_ignore_ascii_case("name") {
            attrs.push(Item::new("cfg-ia-t-li", k.clone()).field("value", v));
        }
    }
    Item::new("cfg-dt-instance-li", i.name.clone())
        .link("self", format!("{domain}/{type_name}/instances/{}", i.name))
        .items("attrib", attrs)
}

pub(super) async fn cfg(shared: &Arc<Shared>, rq: &Rq, domain: &str, type_name: &str) -> Outcome {
    if rq.method != Method::GET || rq.action().is_some() {
        return Err(rq.unknown_action());
    }
    let (d, t) = (domain.to_string(), type_name.to_string());
    let list = shared
        .ask(|reply| Request::Cfg {
            domain: d,
            type_name: t,
            reply,
        })
        .await?;
    let mut st = State::new("cfg", "rw/cfg/", format!("{domain}/{type_name}/instances"));
    for i in &list {
        st = st.item(instance_item(domain, type_name, i));
    }
    Ok(Answer::Ok(st))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn version_names_have_four_parts() {
        assert_eq!(version_name("6.08.01"), "6.08.01.00");
        assert_eq!(version_name("6.08.01.00"), "6.08.01.00");
    }

    #[test]
    fn the_name_attribute_is_spelled_as_the_domain_does() {
        let i = CfgInstance {
            name: "g1".into(),
            attributes: vec![
                ("name".into(), "g1".into()),
                ("Robot".into(), "ROB_1".into()),
            ],
        };
        let titles = |domain| {
            let item = instance_item(domain, "T", &i);
            let Some((_, super::super::repr::FieldValue::Items(a))) = item.fields.first() else {
                panic!("attributes")
            };
            a.iter().map(|x| x.title.clone()).collect::<Vec<_>>()
        };
        assert_eq!(titles("sys"), ["Name", "Robot"]);
        assert_eq!(titles("MOC"), ["name", "Robot"]);
    }
}
