//! Domain types shared by the interpreter and the motion core: speed, zone, targets and the
//! motion commands RAPID's move instructions put into the motion queue. Plain data, no
//! behaviour beyond small accessors.

use crate::source::Span;

use super::conf::ConfData;
use super::frames::{LoadData, ToolData, WobjData};
use super::units::pose_from_pos_quat;
use super::{JointsDeg, Pose};

/// Value RAPID uses for an unused external axis (`9E9`).
pub const EXTAX_UNUSED: f64 = 9e9;

/// `extax` with every axis unused.
pub const EXTAX_NONE: [f64; 6] = [EXTAX_UNUSED; 6];

/// `speeddata [v_tcp, v_ori, v_leax, v_reax]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpeedData {
    /// TCP speed (mm/s).
    pub v_tcp: f64,
    /// Reorientation speed of the tool (deg/s).
    pub v_ori: f64,
    /// Linear external axes (mm/s).
    pub v_leax: f64,
    /// Rotating external axes (deg/s).
    pub v_reax: f64,
}

impl SpeedData {
    /// A predefined `vN`: `[N, 500, 5000, 1000]` (docs/robot.md, "Profiles and acceleration").
    pub const fn v(v_tcp: f64) -> SpeedData {
        SpeedData {
            v_tcp,
            v_ori: 500.0,
            v_leax: 5000.0,
            v_reax: 1000.0,
        }
    }
}

/// `zonedata [finep, pzone_tcp, pzone_ori, pzone_eax, zone_ori, zone_leax, zone_reax]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ZoneData {
    /// TRUE: a stop point (`fine`); the zone sizes are ignored.
    pub finep: bool,
    /// Zone radius of the TCP (mm).
    pub pzone_tcp: f64,
    /// Zone radius for reorientation, as a TCP distance (mm).
    pub pzone_ori: f64,
    /// Zone radius for external axes, as a TCP distance (mm).
    pub pzone_eax: f64,
    /// Zone size for reorientation (deg).
    pub zone_ori: f64,
    /// Zone size for linear external axes (mm).
    pub zone_leax: f64,
    /// Zone size for rotating external axes (deg).
    pub zone_reax: f64,
}

impl ZoneData {
    /// RAPID `fine`: `[TRUE, 0, 0, 0, 0, 0, 0]`.
    pub const FINE: ZoneData = ZoneData {
        finep: true,
        pzone_tcp: 0.0,
        pzone_ori: 0.0,
        pzone_eax: 0.0,
        zone_ori: 0.0,
        zone_leax: 0.0,
        zone_reax: 0.0,
    };
}

/// `robtarget [trans, rot, robconf, extax]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RobTarget {
    /// Position (mm) in the object frame.
    pub trans: [f64; 3],
    /// Orientation `[q1, q2, q3, q4]` = `[w, x, y, z]`.
    pub rot: [f64; 4],
    /// Axis configuration.
    pub robconf: ConfData,
    /// External axes (`9E9` = unused).
    pub extax: [f64; 6],
}

impl RobTarget {
    /// The target as a pose in its object frame.
    pub fn pose(&self) -> Pose {
        pose_from_pos_quat(self.trans, self.rot)
    }
}

/// `jointtarget [robax, extax]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointTarget {
    /// Robot axes (deg).
    pub robax: JointsDeg,
    /// External axes (`9E9` = unused).
    pub extax: [f64; 6],
}

/// The optional speed argument of a move instruction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SpeedOverride {
    /// `\V`: TCP speed in mm/s, replacing `v_tcp`.
    V(f64),
    /// `\T`: total time of the movement in seconds.
    T(f64),
}

/// What every move instruction carries besides its target(s).
#[derive(Clone, Debug, PartialEq)]
pub struct MoveArgs {
    /// Unique, increasing id of the command (the interpreter numbers them).
    pub id: u64,
    /// The RAPID instruction, for traces and error messages.
    pub source: Option<Span>,
    /// `speeddata`.
    pub speed: SpeedData,
    /// `\V` or `\T`.
    pub speed_override: Option<SpeedOverride>,
    /// `zonedata` (with `\Z` already folded into `pzone_tcp`).
    pub zone: ZoneData,
    /// The active tool.
    pub tool: ToolData,
    /// `\WObj` (`wobj0` when not given).
    pub wobj: WobjData,
    /// `\TLoad`.
    pub tload: Option<LoadData>,
    /// Program displacement active when the instruction ran (identity when PDispOff).
    pub pdisp: Pose,
}

impl MoveArgs {
    /// The arguments of move `id` at `speed` with `zone` and `tool`, as a move instruction
    /// without optional arguments has them: no `\V`/`\T`, `wobj0`, no `\TLoad`, no program
    /// displacement, no source span.
    pub fn new(id: u64, speed: SpeedData, zone: ZoneData, tool: ToolData) -> Self {
        MoveArgs {
            id,
            source: None,
            speed,
            speed_override: None,
            zone,
            tool,
            wobj: WobjData::wobj0(),
            tload: None,
            pdisp: Pose::identity(),
        }
    }
}

/// `MoveAbsJ ToJointPos [\NoEOffs], Speed, Zone, Tool [\WObj]`: joint interpolation to axis
/// values, no IK and no configuration check.
#[derive(Clone, Debug, PartialEq)]
pub struct MoveAbsJ {
    /// The common arguments.
    pub args: MoveArgs,
    /// The goal.
    pub target: JointTarget,
    /// `\NoEOffs`: ignore external axis offsets.
    pub no_eoffs: bool,
}

/// `MoveJ ToPoint, Speed, Zone, Tool [\WObj]`: joint interpolation to a robtarget.
#[derive(Clone, Debug, PartialEq)]
pub struct MoveJ {
    /// The common arguments.
    pub args: MoveArgs,
    /// The goal.
    pub target: RobTarget,
    /// `ConfJ\On` (true) or `\Off` when the instruction ran.
    pub conf_check: bool,
}

/// `MoveL ToPoint, Speed, Zone, Tool [\WObj]`: straight TCP line to a robtarget.
#[derive(Clone, Debug, PartialEq)]
pub struct MoveL {
    /// The common arguments.
    pub args: MoveArgs,
    /// The goal.
    pub target: RobTarget,
    /// `ConfL\On` (true) or `\Off` when the instruction ran.
    pub conf_check: bool,
}

/// `MoveC CirPoint, ToPoint, Speed, Zone, Tool [\WObj]`: circular arc through CirPoint.
#[derive(Clone, Debug, PartialEq)]
pub struct MoveC {
    /// The common arguments.
    pub args: MoveArgs,
    /// The circle point (its orientation only picks the direction of reorientation).
    pub cir_point: RobTarget,
    /// The goal.
    pub to_point: RobTarget,
    /// `ConfL\On` (true) or `\Off` when the instruction ran.
    pub conf_check: bool,
}

/// One entry of the motion queue.
#[derive(Clone, Debug, PartialEq)]
pub enum MotionCommand {
    /// `MoveAbsJ`.
    MoveAbsJ(MoveAbsJ),
    /// `MoveJ`.
    MoveJ(MoveJ),
    /// `MoveL`.
    MoveL(MoveL),
    /// `MoveC`.
    MoveC(MoveC),
}

impl MotionCommand {
    /// The common arguments of a move.
    pub fn args(&self) -> &MoveArgs {
        match self {
            MotionCommand::MoveAbsJ(m) => &m.args,
            MotionCommand::MoveJ(m) => &m.args,
            MotionCommand::MoveL(m) => &m.args,
            MotionCommand::MoveC(m) => &m.args,
        }
    }

    /// The command's id.
    pub fn id(&self) -> u64 {
        self.args().id
    }

    /// The RAPID instruction it came from.
    pub fn source(&self) -> Option<Span> {
        self.args().source
    }

    /// The instruction name as written in RAPID.
    pub fn name(&self) -> &'static str {
        match self {
            MotionCommand::MoveAbsJ(_) => "MoveAbsJ",
            MotionCommand::MoveJ(_) => "MoveJ",
            MotionCommand::MoveL(_) => "MoveL",
            MotionCommand::MoveC(_) => "MoveC",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn predefined_data() {
        let v1000 = SpeedData::v(1000.0);
        assert_eq!(
            (v1000.v_tcp, v1000.v_ori, v1000.v_leax, v1000.v_reax),
            (1000.0, 500.0, 5000.0, 1000.0)
        );
        let fine = ZoneData::FINE;
        assert!(fine.finep && fine.pzone_tcp == 0.0);
        let t = RobTarget {
            trans: [1.0, 2.0, 3.0],
            rot: [1.0, 0.0, 0.0, 0.0],
            robconf: ConfData::default(),
            extax: EXTAX_NONE,
        };
        assert_eq!(t.pose().translation.vector.z, 3.0);
        let cmd = MotionCommand::MoveJ(MoveJ {
            args: MoveArgs {
                speed_override: Some(SpeedOverride::T(2.0)),
                ..MoveArgs::new(7, v1000, ZoneData::FINE, ToolData::tool0())
            },
            target: t,
            conf_check: true,
        });
        assert_eq!((cmd.id(), cmd.name(), cmd.source()), (7, "MoveJ", None));
    }
}
