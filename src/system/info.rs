//! What the controller says about itself: the values of `GetSysInfo`, `IsSysId`, `RobOS`,
//! `OpMode`, `RunMode`, `GetTaskName`, the mechanical units (`RobName`, `GetNextMechUnit`,
//! `IsMechUnitActive`, `MaxRobSpeed`) and the active tool, work object and payload
//! (`GetSysData`, `SetSysData`).
//!
//! ABB documents what these functions return on a real controller (its serial number, its
//! RobotWare version, …); a virtual controller has none of them, so rapidvc returns values of
//! its own, chosen so that a program can tell it runs on rapidvc and so that they never
//! change between runs ([`SystemInfo::default`] lists them; `docs/rapid.md` documents them).

use crate::robot::RobotModel;

/// The RobotWare version rapidvc's RAPID follows (the language of RobotWare 6).
pub const ROBOTWARE_VERSION: &str = "6.08.00.00";

/// The serial number of every rapidvc controller (`GetSysInfo(\SerialNo)`, `IsSysId`).
pub const SERIAL_NUMBER: &str = "rapidvc-0000";

/// The name of the motion task (`GetTaskName`): rapidvc runs one task.
pub const MOTION_TASK: &str = "T_ROB1";

/// The name of the robot's mechanical unit (`RobName`, `GetNextMechUnit`).
pub const ROBOT_UNIT: &str = "ROB_1";

/// The operating mode (`OpMode`), as the key switch sets it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum OpMode {
    /// Automatic (`OP_AUTO`): rapidvc's mode unless a service changes it.
    #[default]
    Auto,
    /// Manual, reduced speed (`OP_MAN_PROG`).
    ManualReduced,
    /// Manual, full speed (`OP_MAN_TEST`).
    ManualFull,
}

impl OpMode {
    /// The `symnum` value RAPID compares with `OP_AUTO`, `OP_MAN_PROG`, `OP_MAN_TEST`.
    pub fn symnum(self) -> f32 {
        match self {
            OpMode::Auto => 1.0,
            OpMode::ManualReduced => 2.0,
            OpMode::ManualFull => 3.0,
        }
    }
}

/// `RunMode`: programs run continuously or cycle by cycle; rapidvc has no stepping.
pub const RUN_CONT_CYCLE: f32 = 1.0;

/// The robot of the motion task.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RobotInfo {
    /// The kinematic model (`rapidvc run --robot`).
    pub model: &'static RobotModel,
}

impl RobotInfo {
    /// The mechanical unit's name.
    pub fn unit(&self) -> &'static str {
        ROBOT_UNIT
    }

    /// `GetSysInfo(\RobotType)`: the model's name as ABB writes it (`IRB 2600-12/1.85`).
    pub fn robot_type(&self) -> &'static str {
        self.model.name
    }

    /// `MaxRobSpeed`: the model's maximum TCP speed in mm/s.
    pub fn max_tcp_speed(&self) -> f64 {
        self.model.vmax_tcp
    }

    /// The robot's number of axes.
    pub fn axes(&self) -> u32 {
        6
    }
}

/// The active system data of the motion task, by the names of their persistents: the tool
/// and work object of the latest move instruction or `SetSysData`, the payload of
/// `SetSysData` (`tool0`, `wobj0`, `load0` when the program starts).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ActiveData {
    /// The active tool (`tooldata`).
    pub tool: String,
    /// The active work object (`wobjdata`).
    pub wobj: String,
    /// The active payload (`loaddata`).
    pub load: String,
}

impl Default for ActiveData {
    fn default() -> Self {
        ActiveData {
            tool: "tool0".into(),
            wobj: "wobj0".into(),
            load: "load0".into(),
        }
    }
}

/// Which active system data a type designates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SysDataKind {
    /// `tooldata`.
    Tool,
    /// `wobjdata`.
    Wobj,
    /// `loaddata`.
    Load,
}

impl SysDataKind {
    /// The kind of active data of RAPID type `type_name`, if any.
    pub fn of_type(type_name: &str) -> Option<SysDataKind> {
        match type_name.to_ascii_lowercase().as_str() {
            "tooldata" => Some(SysDataKind::Tool),
            "wobjdata" => Some(SysDataKind::Wobj),
            "loaddata" => Some(SysDataKind::Load),
            _ => None,
        }
    }
}

impl ActiveData {
    /// The name of the active data of `kind`.
    pub fn get(&self, kind: SysDataKind) -> &str {
        match kind {
            SysDataKind::Tool => &self.tool,
            SysDataKind::Wobj => &self.wobj,
            SysDataKind::Load => &self.load,
        }
    }

    /// Make `name` the active data of `kind`.
    pub fn set(&mut self, kind: SysDataKind, name: &str) {
        let slot = match kind {
            SysDataKind::Tool => &mut self.tool,
            SysDataKind::Wobj => &mut self.wobj,
            SysDataKind::Load => &mut self.load,
        };
        if slot.as_str() != name {
            *slot = name.to_string();
        }
    }
}

/// What the controller says about itself (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct SystemInfo {
    /// `GetSysInfo(\SerialNo)`.
    pub serial: String,
    /// `GetSysInfo(\SWVersion)`.
    pub sw_version: String,
    /// `GetSysInfo(\CtrlId)`.
    pub ctrl_id: String,
    /// `GetSysInfo(\LanIp)`.
    pub lan_ip: String,
    /// `GetSysInfo(\CtrlLang)`.
    pub language: String,
    /// `GetSysInfo(\SystemName)`.
    pub system_name: String,
    /// The task's name (`GetTaskName`).
    pub task: String,
    /// The operating mode (`OpMode`).
    pub op_mode: OpMode,
    /// The robot of the motion task (`None`: a controller without a robot).
    pub robot: Option<RobotInfo>,
    /// The active tool, work object and payload.
    pub active: ActiveData,
}

impl Default for SystemInfo {
    /// rapidvc's values, with the default robot model.
    fn default() -> Self {
        SystemInfo {
            serial: SERIAL_NUMBER.into(),
            sw_version: format!(
                "{ROBOTWARE_VERSION} (rapidvc {})",
                env!("CARGO_PKG_VERSION")
            ),
            ctrl_id: "rapidvc".into(),
            lan_ip: "127.0.0.1".into(),
            language: "en".into(),
            system_name: "rapidvc".into(),
            task: MOTION_TASK.into(),
            op_mode: OpMode::Auto,
            robot: Some(RobotInfo {
                model: crate::robot::default_model(),
            }),
            active: ActiveData::default(),
        }
    }
}

impl SystemInfo {
    /// These values with `model` as the robot.
    pub fn with_robot(mut self, model: &'static RobotModel) -> Self {
        self.robot = Some(RobotInfo { model });
        self
    }

    /// `IsSysId`: whether `id` is this system's identity (its serial number; case matters,
    /// as for any identity text).
    pub fn is_sys_id(&self, id: &str) -> bool {
        id == self.serial
    }

    /// The mechanical units, in `GetNextMechUnit` order.
    pub fn mech_units(&self) -> Vec<RobotInfo> {
        self.robot.iter().copied().collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_rapidvcs_values() {
        let info = SystemInfo::default();
        assert_eq!(info.serial, "rapidvc-0000");
        assert!(info.sw_version.starts_with("6.08.00.00 (rapidvc "));
        assert!(info.sw_version.len() <= 80);
        assert!(info.is_sys_id("rapidvc-0000"));
        assert!(!info.is_sys_id("RAPIDVC-0000"));
        let robot = info.robot.expect("a robot");
        assert_eq!(robot.robot_type(), "IRB 2600-12/1.85");
        assert_eq!(robot.unit(), "ROB_1");
        assert!(robot.max_tcp_speed() > 1000.0);
        assert_eq!(info.op_mode.symnum(), 1.0);
        assert_eq!(info.mech_units().len(), 1);
    }

    #[test]
    fn active_data_by_kind() {
        let mut a = ActiveData::default();
        assert_eq!(a.get(SysDataKind::Tool), "tool0");
        a.set(SysDataKind::Wobj, "wobjTable");
        assert_eq!(a.get(SysDataKind::Wobj), "wobjTable");
        assert_eq!(SysDataKind::of_type("ToolData"), Some(SysDataKind::Tool));
        assert_eq!(SysDataKind::of_type("pose"), None);
    }
}
