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

pub(super) async fn system(shared: &Arc<Shared>, rq: &Rq) -> Outcome {
    if rq.method != Method::GET || rq.action().is_some() {
        return Err(rq.unknown_action());
    }
    let info = shared.ask(Request::System).await?;
    let mut st = State::new("system", "rw/", "system").item(
        Item::new("sys-system-li", info.name.clone())
            .field("name", &info.name)
            .field("rwversion", &info.robotware_version)
            .field("sysid", &info.serial)
            .field("rwversionname", version_name(&info.robotware_version)),
    );
    for o in &info.options {
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

/// One instance: its name first (as the attribute `name`, unless the instance spells its
/// name attribute itself, as SYS.cfg's `Name`), then every attribute.
fn instance_item(domain: &str, type_name: &str, i: &CfgInstance) -> Item {
    let mut attrs = Vec::with_capacity(i.attributes.len() + 1);
    if !i
        .attributes
        .iter()
        .any(|(k, _)| k.eq_ignore_ascii_case("name"))
    {
        attrs.push(Item::new("cfg-ia-t-li", "name").field("value", &i.name));
    }
    for (k, v) in &i.attributes {
        attrs.push(Item::new("cfg-ia-t-li", k.clone()).field("value", v));
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
    fn a_spelled_name_attribute_is_not_repeated() {
        let i = CfgInstance {
            name: "g1".into(),
            attributes: vec![
                ("Name".into(), "g1".into()),
                ("Robot".into(), "ROB_1".into()),
            ],
        };
        let item = instance_item("sys", "MECHANICAL_UNIT_GROUP", &i);
        let Some((_, super::super::repr::FieldValue::Items(a))) = item.fields.first() else {
            panic!("attributes")
        };
        assert_eq!(a.len(), 2);
        assert_eq!(a.first().map(|x| x.title.as_str()), Some("Name"));
    }
}
