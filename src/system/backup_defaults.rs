//! The configuration a controller backup has for rapidvc's one robot and its motion task,
//! for the types the loaded configuration does not give: what Robot Web Services'
//! `rw/cfg/{domain}/{type}/instances` answers when a client (abb_librws, the ROS drivers)
//! reads the system's structure at start-up.
//!
//! The values are the controller's real ones: the robot model's axis ranges (in radians, as
//! MOC.cfg stores them), six rotating axes, the robot at the world origin, one motion task.
//! The instance names follow a single-robot backup: mechanical unit and robot `ROB_1`,
//! joints, arms and transmissions `rob1_1`…`rob1_6`, motion group `rob1`. A type the loaded
//! MOC.cfg or SYS.cfg gives is served as loaded (docs/rws.md).

use crate::config::cfg::CfgValue;
use crate::robot::RobotModel;
use crate::robot::units::deg_to_rad;

use super::cfg_data::CfgData;

/// The header of a MOC.cfg made by RobotWare 6.
const MOC_HEADER: &str = "MOC:CFG_1.0:6:0::";
/// The header of a SYS.cfg made by RobotWare 6.
const SYS_HEADER: &str = "SYS:CFG_1.0:6:0::";

/// The motion group of the one robot (SYS.cfg `MECHANICAL_UNIT_GROUP`).
pub const MOTION_GROUP: &str = "rob1";

fn text(k: &str, v: &str) -> (String, CfgValue) {
    (k.to_string(), CfgValue::Str(v.to_string()))
}

fn num(k: &str, v: f64) -> (String, CfgValue) {
    (k.to_string(), CfgValue::Num(v))
}

fn flag(k: &str) -> (String, CfgValue) {
    (k.to_string(), CfgValue::Flag)
}

/// Add the defaults for `unit` (the robot, `ROB_1`) of `model`, moved by `task`, to `cfg`
/// where it has no instance of a type. Returns the types added (`MOC/JOINT`, …).
pub fn complete(cfg: &mut CfgData, model: &RobotModel, unit: &str, task: &str) -> Vec<String> {
    let joint = |i: usize| format!("rob1_{i}");
    let mut added = Vec::new();
    let mut add = |domain: &str, header: &str, ty: &str, inst: Vec<Vec<(String, CfgValue)>>| {
        if cfg.add_if_missing(domain, header, ty, inst) {
            added.push(format!("{domain}/{ty}"));
        }
    };
    add(
        "MOC",
        MOC_HEADER,
        "MECHANICAL_UNIT",
        vec![vec![
            text("name", unit),
            text("use_robot", unit),
            flag("activate_at_start_up"),
            flag("deactivation_forbidden"),
        ]],
    );
    let mut robot = vec![text("name", unit), text("use_robot_type", model.name)];
    for i in 0..6 {
        robot.push(text(&format!("use_joint_{i}"), &joint(i + 1)));
    }
    robot.extend([
        num("base_frame_pos_x", 0.0),
        num("base_frame_pos_y", 0.0),
        num("base_frame_pos_z", 0.0),
        num("base_frame_orient_u0", 1.0),
        num("base_frame_orient_u1", 0.0),
        num("base_frame_orient_u2", 0.0),
        num("base_frame_orient_u3", 0.0),
    ]);
    add("MOC", MOC_HEADER, "ROBOT", vec![robot]);
    add(
        "MOC",
        MOC_HEADER,
        "JOINT",
        (1..=6)
            .map(|i| {
                vec![
                    text("name", &joint(i)),
                    num("logical_axis", i as f64),
                    // Robot axes have no kinematic axis number (that is for additional axes).
                    num("kinematic_axis_number", -1.0),
                    text("use_arm", &joint(i)),
                    text("use_transmission", &joint(i)),
                ]
            })
            .collect(),
    );
    add(
        "MOC",
        MOC_HEADER,
        "ARM",
        model
            .joint_limits
            .iter()
            .enumerate()
            .map(|(i, l)| {
                vec![
                    text("name", &joint(i + 1)),
                    num("lower_joint_bound", deg_to_rad(l.min)),
                    num("upper_joint_bound", deg_to_rad(l.max)),
                ]
            })
            .collect(),
    );
    add(
        "MOC",
        MOC_HEADER,
        "TRANSMISSION",
        (1..=6)
            .map(|i| vec![text("name", &joint(i)), flag("rotating_move")])
            .collect(),
    );
    add(
        "SYS",
        SYS_HEADER,
        "MECHANICAL_UNIT_GROUP",
        vec![vec![text("Name", MOTION_GROUP), text("Robot", unit)]],
    );
    add(
        "SYS",
        SYS_HEADER,
        "CAB_TASKS",
        vec![vec![
            text("Name", task),
            text("Type", "NORMAL"),
            flag("MotionTask"),
            text("UseMechanicalUnitGroup", MOTION_GROUP),
        ]],
    );
    added
}

/// `cfg` completed with the defaults of the system's robot (none without a robot), its motion
/// task `task`.
pub fn completed(cfg: &CfgData, info: &super::info::SystemInfo, task: &str) -> CfgData {
    let mut cfg = cfg.clone();
    if let Some(r) = &info.robot {
        complete(&mut cfg, r.model, r.unit(), task);
    }
    cfg
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_empty_configuration_gets_a_single_robot_backup() {
        let mut cfg = CfgData::default();
        let model = crate::robot::default_model();
        let added = complete(&mut cfg, model, "ROB_1", "T_ROB1");
        assert_eq!(added.len(), 7, "{added:?}");
        assert_eq!(cfg.instances("moc", "joint").count(), 6);
        let arm = cfg.instances("MOC", "ARM").next().expect("an arm");
        let upper = arm
            .attrs
            .iter()
            .find(|(k, _)| k == "upper_joint_bound")
            .map(|(_, v)| v.clone());
        assert_eq!(
            upper,
            Some(CfgValue::Num(deg_to_rad(model.joint_limits[0].max)))
        );
        assert_eq!(
            cfg.instances("SYS", "CAB_TASKS")
                .next()
                .and_then(|i| i.name()),
            Some("T_ROB1")
        );
    }

    #[test]
    fn a_loaded_type_is_kept() {
        let mut cfg = CfgData::default();
        cfg.add_if_missing(
            "MOC",
            MOC_HEADER,
            "MECHANICAL_UNIT",
            vec![vec![text("name", "ROB_1")]],
        );
        let added = complete(&mut cfg, crate::robot::default_model(), "ROB_1", "T_ROB1");
        assert!(!added.iter().any(|a| a == "MOC/MECHANICAL_UNIT"));
        let mu = cfg
            .instances("MOC", "MECHANICAL_UNIT")
            .next()
            .expect("unit");
        assert_eq!(mu.attrs.len(), 1);
    }
}
