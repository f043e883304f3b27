//! `rw/motionsystem/mechunits`: the mechanical units, one unit's static and dynamic
//! properties (`?resource=static|dynamic`), where it is as a `jointtarget` (`rax_1`…,
//! `eax_a`…) and as a `robtarget` of a tool and work object in a coordinate system
//! (`?tool=&wobj=&coordinate=`).

use std::sync::Arc;

use axum::http::Method;

use super::repr::{Item, RwsError, State};
use super::{Answer, Outcome, Rq, Shared};
use crate::controller::service::{Coordinate, MechUnitInfo, Request};

/// RAPID's value of an axis that does not exist.
const NO_AXIS: f64 = 9e9;

/// An axis value as RobotWare writes it (`9E+09` for a missing axis).
fn axis_text(v: f64) -> String {
    if v >= NO_AXIS {
        "9E+09".to_string()
    } else {
        super::num(v)
    }
}

const EAX: [char; 6] = ['a', 'b', 'c', 'd', 'e', 'f'];

/// The numbers of a RAPID aggregate text (`[[1,2,3],[1,0,0,0],…]`), in order.
pub(super) fn numbers(text: &str) -> Result<Vec<f64>, RwsError> {
    text.split(['[', ']', ','])
        .map(str::trim)
        .filter(|t| !t.is_empty())
        .map(|t| {
            t.parse::<f64>()
                .map_err(|_| RwsError::bad(format!("the controller sent `{t}` in a robtarget")))
        })
        .collect()
}

fn unit_item(u: &MechUnitInfo, resource: &str) -> Result<Item, RwsError> {
    let mut item = Item::new("ms-mechunit", u.name.clone());
    let mut known = false;
    for r in resource.split(';').filter(|r| !r.is_empty()) {
        match r {
            "static" => {
                known = true;
                // rapidvc's one robot: a TCP robot without integrated units.
                item = item
                    .field("task-name", &u.task)
                    .field("is-integrated-unit", "NoIntegratedUnit")
                    .field("has-integrated-unit", "NoIntegratedUnit")
                    .field("type", "TCPRobot")
                    .field("axes", u.axes)
                    .field("axes-total", u.axes);
            }
            "dynamic" => {
                known = true;
                // No jogging in rapidvc: the jog settings are a controller's start values.
                item = item
                    .field("tool-name", &u.tool)
                    .field("wobj-name", &u.wobj)
                    .field("payload-name", &u.payload)
                    .field("total-payload-name", &u.payload)
                    .field("mode", "Activated")
                    .field("jog-mode", "Cartesian")
                    .field("coord-system", "Base")
                    .field("status", "Synchronized");
            }
            other => {
                return Err(RwsError::unsupported(format!(
                    "`resource={other}` (static or dynamic)"
                )));
            }
        }
    }
    if known {
        Ok(item)
    } else {
        Err(RwsError::bad("`resource=` is empty"))
    }
}

fn coordinate(text: &str) -> Result<Coordinate, RwsError> {
    // abb_librws writes World as `Word`.
    match text.to_ascii_lowercase().as_str() {
        "base" => Ok(Coordinate::Base),
        "world" | "word" => Ok(Coordinate::World),
        "tool" => Ok(Coordinate::Tool),
        "wobj" => Ok(Coordinate::Wobj),
        _ => Err(RwsError::bad(format!(
            "`coordinate={text}`: expected Base, World, Tool or Wobj"
        ))),
    }
}

pub(super) async fn mechunits(shared: &Arc<Shared>, rq: &Rq, rest: &[&str]) -> Outcome {
    if rq.method != Method::GET || rq.action().is_some() {
        return Err(rq.unknown_action());
    }
    let units = shared.ask(Request::MechUnits).await?;
    let Some(name) = rest.first() else {
        let mut st = State::new("motionsystem", "rw/motionsystem/", "mechunits");
        for u in &units {
            st = st.item(
                Item::new("ms-mechunit-li", u.name.clone())
                    .link("self", format!("mechunits/{}", u.name)),
            );
        }
        return Ok(Answer::Ok(st));
    };
    let unit = super::find_ci(&units, name, |u| &u.name)
        .ok_or_else(|| RwsError::not_found(format!("no mechanical unit `{name}`")))?;
    let base = "rw/motionsystem/mechunits/";
    match rest.get(1..).unwrap_or_default() {
        [] => {
            let resource = rq.query("resource").unwrap_or("static;dynamic");
            Ok(Answer::Ok(
                State::new("motionsystem", base, unit.name.clone())
                    .item(unit_item(unit, resource)?),
            ))
        }
        ["jointtarget"] => {
            let robot = shared.ask(Request::Robot).await?;
            let mut item = Item::new("ms-jointtarget", unit.name.clone());
            for (i, j) in robot.joints.iter().enumerate() {
                item = item.field(&format!("rax_{}", i + 1), axis_text(*j));
            }
            for c in EAX {
                item = item.field(&format!("eax_{c}"), axis_text(NO_AXIS));
            }
            Ok(Answer::Ok(
                State::new("motionsystem", base, format!("{}/jointtarget", unit.name)).item(item),
            ))
        }
        ["robtarget"] => {
            // Without `tool`/`wobj` (abb_librws' "active" request), the active ones: what
            // `?resource=dynamic` names.
            let named = |key: &str, active: &str| {
                Some(
                    rq.query(key)
                        .filter(|t| !t.is_empty())
                        .unwrap_or(active)
                        .to_string(),
                )
            };
            let tool = named("tool", &unit.tool);
            let wobj = named("wobj", &unit.wobj);
            let coordinate = coordinate(rq.query("coordinate").unwrap_or("Base"))?;
            let text = shared
                .ask(|reply| Request::RobTarget {
                    tool,
                    wobj,
                    coordinate,
                    reply,
                })
                .await?;
            let n = numbers(&text)?;
            let [x, y, z, q1, q2, q3, q4, cf1, cf4, cf6, cfx, ext @ ..] = n.as_slice() else {
                return Err(RwsError::bad(format!(
                    "the controller sent `{text}` as a robtarget"
                )));
            };
            if ext.len() != 6 {
                return Err(RwsError::bad(format!(
                    "the controller sent `{text}` as a robtarget"
                )));
            }
            let mut item = Item::new("ms-robtargets", unit.name.clone());
            for (k, v) in [
                ("x", x),
                ("y", y),
                ("z", z),
                ("q1", q1),
                ("q2", q2),
                ("q3", q3),
                ("q4", q4),
                ("cf1", cf1),
                ("cf4", cf4),
                ("cf6", cf6),
                ("cfx", cfx),
            ] {
                item = item.field(k, super::num(*v));
            }
            // abb_robot_client reads `eaxa`…, abb_librws `eax_a`…: both are written.
            for (c, v) in EAX.iter().zip(ext) {
                item = item.field(&format!("eax{c}"), axis_text(*v));
            }
            for (c, v) in EAX.iter().zip(ext) {
                item = item.field(&format!("eax_{c}"), axis_text(*v));
            }
            Ok(Answer::Ok(
                State::new("motionsystem", base, format!("{}/robtarget", unit.name)).item(item),
            ))
        }
        _ => Err(RwsError::not_found(format!("no resource {}", rq.path))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn robtarget_text_gives_its_numbers() {
        let n = numbers("[[1,2.5,-3],[1,0,0,0],[0,-1,0,0],[9E+09,9E9,9E+09,9E+09,9E+09,9E+09]]")
            .unwrap_or_default();
        assert_eq!(n.len(), 17);
        assert_eq!(n.get(1), Some(&2.5));
        assert_eq!(axis_text(n[16]), "9E+09");
        assert!(numbers("[1,x]").is_err());
    }

    #[test]
    fn librws_spelling_of_world_is_accepted() {
        assert_eq!(coordinate("Word"), Ok(Coordinate::World));
        assert!(coordinate("Galaxy").is_err());
    }
}
