//! The planner: turns a `MotionCommand` into a [`Segment`] of per-cycle samples before the
//! robot moves, so unreachable targets, axis limits, singularities and impossible circles are
//! reported while the robot still stands where it is (docs/robot.md, "Planning").
//!
//! Pure and deterministic: the same commands from the same start give the same samples. It
//! runs outside the motion cycle (on the caller's thread), since it does the inverse
//! kinematics of a whole linear move at once.

mod corner;
pub mod path;
mod sampling;
mod track;
mod triggers;

use std::time::Duration;

use nalgebra::Point3;

use crate::robot::command::{MotionCommand, MoveArgs, SpeedOverride};
use crate::robot::trigger::PathTrigger;
use crate::robot::{
    JointsDeg, KinError, Pose, Robot, ToolData, flange_target, frames::target_from_flange,
};

use super::event::{InstrRef, MotionError, PathPlace};
use super::limits::{self, MIN_PATH_MM};
use super::profile::{Profile, ProfileLimits};
use super::segment::{Sample, Segment};
use super::settings::MotionSettings;
use path::{Arc, Geometry, OriPath};

/// A segment ready for the executor, plus warnings found while planning it (e.g. a corner
/// path that could not be built: the previous fly-by point becomes a stop point).
#[derive(Debug)]
pub struct Planned {
    /// The segment.
    pub segment: Segment,
    /// Warnings (not errors: the move is accepted).
    pub warnings: Vec<MotionError>,
}

/// What the planner remembers of the last segment it planned, for the next corner path.
#[derive(Debug, Default)]
struct Prev {
    start: JointsDeg,
    samples: Vec<Sample>,
    /// The segment's own corner resume index (its first samples belong to the corner before).
    resume_at: usize,
    /// Zone radius (mm) at its end, already halved by its own length; 0 for stop points.
    zone: f64,
    /// Samples in its ramp-down.
    ramp_down: usize,
    /// The robot-held tool of a Cartesian move (corner paths between two such moves with the
    /// same tool are blended in Cartesian space, all others in joint space).
    cartesian_tool: Option<ToolData>,
}

/// The motion planner (see the module docs).
#[derive(Debug)]
pub struct Planner {
    robot: Robot,
    period: Duration,
    dt: f64,
    settings: MotionSettings,
    start: JointsDeg,
    prev: Option<Prev>,
    prev_spare: Prev,
    spare: Vec<Segment>,
    /// Position events and instruction name for the next planned move
    /// ([`Planner::set_triggers`]).
    pending_triggers: Vec<PathTrigger>,
    pending_name: Option<&'static str>,
}

/// The planning state put aside by [`Planner::store`].
#[derive(Debug)]
pub struct PlanCheckpoint {
    start: JointsDeg,
    prev: Option<Prev>,
}

/// The measured shape of a move: TCP path length (mm) and reorientation (deg).
#[derive(Clone, Copy, Debug)]
struct Extent {
    length: f64,
    reorient: f64,
}

impl Planner {
    /// A planner for `robot` at cycle `period`, starting at joints `start`.
    pub fn new(robot: Robot, period: Duration, start: JointsDeg) -> Planner {
        let period = period.clamp(
            super::settings::PERIOD_RANGE.0,
            super::settings::PERIOD_RANGE.1,
        );
        Planner {
            robot,
            period,
            dt: period.as_secs_f64(),
            settings: MotionSettings::default(),
            start,
            prev: None,
            prev_spare: Prev::default(),
            spare: Vec::new(),
            pending_triggers: Vec::new(),
            pending_name: None,
        }
    }

    /// The robot.
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// The motion cycle.
    pub fn period(&self) -> Duration {
        self.period
    }

    /// Joints where the next planned move starts (the end of the last one).
    pub fn start(&self) -> JointsDeg {
        self.start
    }

    /// Restart planning from `q` (after a stop, an error or external guidance). The last
    /// planned fly-by point is forgotten.
    pub fn set_start(&mut self, q: JointsDeg) {
        self.start = q;
        self.forget_prev();
    }

    /// Put the planning state aside (`StorePath`): the start and the last fly-by point.
    /// Planning goes on from `q`.
    pub fn store(&mut self, q: JointsDeg) -> PlanCheckpoint {
        let cp = PlanCheckpoint {
            start: self.start,
            prev: self.prev.take(),
        };
        self.start = q;
        cp
    }

    /// Take the planning state back (`RestoPath`): moves queued from now on follow the stored
    /// path's last move.
    pub fn restore(&mut self, cp: PlanCheckpoint) {
        self.forget_prev();
        self.start = cp.start;
        self.prev = cp.prev;
    }

    fn forget_prev(&mut self) {
        if let Some(p) = self.prev.take() {
            self.prev_spare = p;
        }
    }

    /// The modal settings (`VelSet`, `AccSet`, `SingArea`).
    pub fn settings(&self) -> &MotionSettings {
        &self.settings
    }

    /// Change the modal settings for moves planned from now on.
    pub fn set_settings(&mut self, s: MotionSettings) {
        self.settings = s;
    }

    /// Position events for the next move planned (consumed by the next [`Planner::plan`],
    /// also when it fails), and the name of the RAPID instruction it comes from when that is
    /// not the command's own (`MoveLDO`, `TriggL`, `SearchL`).
    pub fn set_triggers(&mut self, triggers: &[PathTrigger], name: Option<&'static str>) {
        self.pending_triggers.clear();
        self.pending_triggers.extend_from_slice(triggers);
        self.pending_name = name;
    }

    /// Give a used segment back so its buffers are reused.
    pub fn recycle(&mut self, mut seg: Segment) {
        seg.clear();
        if self.spare.len() < 64 {
            self.spare.push(seg);
        }
    }

    /// Plan one move from the end of the previous one. On error nothing changes: the robot
    /// keeps its plan and the move is not executed.
    pub fn plan(&mut self, cmd: &MotionCommand) -> Result<Planned, MotionError> {
        let name = self.pending_name.take().unwrap_or(cmd.name());
        let triggers = std::mem::take(&mut self.pending_triggers);
        let planned = self.plan_named(cmd, name);
        let mut triggers = triggers;
        let result = match planned {
            Ok(mut p) => {
                let start_tcp = self
                    .robot
                    .tcp_world(&p.segment.start, &cmd.args().tool)
                    .translation
                    .vector
                    .into();
                triggers::place_all(
                    &p.segment.samples,
                    start_tcp,
                    &triggers,
                    self.dt,
                    &mut p.segment.triggers,
                );
                Ok(p)
            }
            Err(e) => Err(e),
        };
        triggers.clear();
        self.pending_triggers = triggers;
        result
    }

    fn plan_named(
        &mut self,
        cmd: &MotionCommand,
        name: &'static str,
    ) -> Result<Planned, MotionError> {
        let args = cmd.args();
        validate(args)?;
        let instr = InstrRef {
            id: args.id,
            name,
            source: args.source,
        };
        let geometry = self.geometry(cmd)?;
        let extent = self.extent(&geometry, &args.tool);
        let flyby = !args.zone.finep;
        let zone_out = if flyby {
            limits::zone_radius(args.zone.pzone_tcp, extent.length, f64::INFINITY)
        } else {
            0.0
        };
        let zone_in = match &self.prev {
            Some(p) if p.zone > 0.0 => limits::zone_radius(p.zone, f64::INFINITY, extent.length),
            _ => 0.0,
        };
        let plimits = self.profile_limits(cmd, &geometry, extent, zone_in, zone_out);
        let profile = match args.speed_override {
            Some(SpeedOverride::T(t)) => Profile::with_duration(t, &plimits),
            _ => Profile::fastest(&plimits),
        };
        let mut seg = self.spare.pop().unwrap_or_else(Segment::empty);
        seg.clear();
        seg.instr = instr;
        seg.start = self.start;
        seg.fine = !flyby;
        seg.flyby = zone_out > 0.0;
        let profile = match self.sample_with_speed_limits(
            &geometry,
            args,
            profile,
            &plimits,
            &mut seg.samples,
        ) {
            Ok(p) => p,
            Err(e) => {
                self.recycle(seg);
                return Err(e);
            }
        };
        if let Err(e) = self.check_conf(cmd, &seg.samples) {
            self.recycle(seg);
            return Err(e);
        }
        let mut warnings = Vec::new();
        let cartesian_tool = (geometry.is_cartesian() && args.tool.robhold).then_some(args.tool);
        if zone_in > 0.0 {
            let ramp_up = sampling::samples_within(&profile, self.dt, true);
            if let Err(reason) = self.build_corner(
                &mut seg,
                zone_in,
                ramp_up,
                &args.tool,
                cartesian_tool.as_ref(),
            ) {
                warnings.push(MotionError::CornerPathFailure { reason });
            }
        }
        // Remember this segment for the next corner.
        let mut prev = self
            .prev
            .take()
            .unwrap_or_else(|| std::mem::take(&mut self.prev_spare));
        prev.start = self.start;
        prev.samples.clear();
        prev.samples.extend_from_slice(&seg.samples);
        prev.resume_at = seg.corner.map_or(0, |c| c.resume_at);
        prev.zone = zone_out;
        prev.ramp_down = sampling::samples_within(&profile, self.dt, false);
        prev.cartesian_tool = cartesian_tool;
        self.prev = Some(prev);
        if let Some(end) = seg.end() {
            self.start = end.q;
        }
        Ok(Planned {
            segment: seg,
            warnings,
        })
    }

    /// The geometric path of a command from the current start, with the target checked.
    fn geometry(&self, cmd: &MotionCommand) -> Result<Geometry, MotionError> {
        let at_target = |error: KinError| MotionError::Kinematics {
            error,
            place: PathPlace::Target,
        };
        match cmd {
            MotionCommand::MoveAbsJ(m) => {
                self.robot
                    .check_limits(&m.target.robax)
                    .map_err(at_target)?;
                Ok(Geometry::Joint {
                    from: self.start,
                    to: m.target.robax,
                })
            }
            MotionCommand::MoveJ(m) => {
                let a = &m.args;
                let flange = flange_target(&m.target.pose(), &a.tool, &a.wobj, &a.pdisp);
                let to = if m.conf_check {
                    self.robot.ik_conf(&flange, &m.target.robconf)
                } else {
                    self.robot.ik_nearest(&flange, &self.start)
                }
                .map_err(at_target)?;
                Ok(Geometry::Joint {
                    from: self.start,
                    to,
                })
            }
            MotionCommand::MoveL(m) => {
                let a = &m.args;
                let from = self.start_pose(a);
                let to = m.target.pose();
                self.check_reach(&to, a, PathPlace::Target)?;
                Ok(Geometry::Line {
                    from: from.translation.vector.into(),
                    to: to.translation.vector.into(),
                    ori: OriPath::shortest(from.rotation, to.rotation),
                })
            }
            MotionCommand::MoveC(m) => {
                let a = &m.args;
                let from = self.start_pose(a);
                let cir = m.cir_point.pose();
                let to = m.to_point.pose();
                self.check_reach(&cir, a, PathPlace::CirPoint)?;
                self.check_reach(&to, a, PathPlace::Target)?;
                let p0: Point3<f64> = from.translation.vector.into();
                let arc = Arc::through(
                    &p0,
                    &cir.translation.vector.into(),
                    &to.translation.vector.into(),
                )?;
                let short = OriPath::shortest(from.rotation, to.rotation);
                let long = short.the_long_way();
                let s_cir = arc.cir_share();
                let ori = if long.at(s_cir).angle_to(&cir.rotation)
                    < short.at(s_cir).angle_to(&cir.rotation)
                {
                    long
                } else {
                    short
                };
                Ok(Geometry::Circle { arc, ori })
            }
        }
    }

    /// A point of a linear or circular move that no arm configuration reaches, or that is
    /// not a finite number (a target at 9E9, a program displacement of 1E30), is outside
    /// reach; checked before the move's duration is computed, which would otherwise call it
    /// a move of more than 15 minutes. Axis limits and singularities along the way are left
    /// to the sampling, which reports where on the path they are met.
    fn check_reach(&self, point: &Pose, a: &MoveArgs, place: PathPlace) -> Result<(), MotionError> {
        let flange = flange_target(point, &a.tool, &a.wobj, &a.pdisp);
        match self.robot.ik_nearest(&flange, &self.start) {
            Err(error @ (KinError::OutsideReach { .. } | KinError::NotFinite)) => {
                Err(MotionError::Kinematics { error, place })
            }
            _ => Ok(()),
        }
    }

    /// The current TCP of the move's tool in its object frame (what CRobT would report).
    fn start_pose(&self, a: &MoveArgs) -> Pose {
        target_from_flange(&self.robot.fk(&self.start), &a.tool, &a.wobj, &a.pdisp)
    }

    /// TCP path length and reorientation of a move.
    fn extent(&self, g: &Geometry, tool: &ToolData) -> Extent {
        match g {
            Geometry::Joint { from, to } => {
                // The TCP path of an axis move is a curve: measure it with 64 chords.
                const CHORDS: u32 = 64;
                let mut length = 0.0;
                let first = self.robot.tcp_world(from, tool);
                let mut prev = first.translation.vector;
                for i in 1..=CHORDS {
                    let q = Geometry::joints_at(from, to, f64::from(i) / f64::from(CHORDS));
                    let p = self.robot.tcp_world(&q, tool).translation.vector;
                    length += (p - prev).norm();
                    prev = p;
                }
                let last = self.robot.tcp_world(to, tool);
                Extent {
                    length: finite_or_zero(length),
                    reorient: finite_or_zero(crate::robot::units::rad_to_deg(
                        first.rotation.angle_to(&last.rotation),
                    )),
                }
            }
            Geometry::Line { from, to, ori } => Extent {
                length: (to - from).norm(),
                reorient: crate::robot::units::rad_to_deg(ori.angle()),
            },
            Geometry::Circle { arc, ori } => Extent {
                length: arc.length(),
                reorient: crate::robot::units::rad_to_deg(ori.angle()),
            },
        }
    }

    /// Normalised speed and acceleration limits of a move (docs/robot.md, "Profiles and acceleration").
    fn profile_limits(
        &self,
        cmd: &MotionCommand,
        g: &Geometry,
        e: Extent,
        zone_in: f64,
        zone_out: f64,
    ) -> ProfileLimits {
        let args = cmd.args();
        let model = self.robot.model();
        let s = &self.settings;
        // `\T` replaces the speed data: the move takes that time, only the robot's own limits
        // (and VelSet's maximum) can make it longer.
        let (v_prog, v_ori) = match args.speed_override {
            Some(SpeedOverride::V(v)) => (v, args.speed.v_ori),
            Some(SpeedOverride::T(_)) => (f64::INFINITY, f64::INFINITY),
            None => (args.speed.v_tcp, args.speed.v_ori),
        };
        let v_tcp = limits::effective_tcp_speed(v_prog, s, model);
        let v_ori = v_ori * limits::override_factor(s);
        let mut v_max = f64::INFINITY;
        let mut a_max = f64::INFINITY;
        let moves = e.length > MIN_PATH_MM;
        let turns = e.reorient > 1e-9;
        if moves {
            v_max = v_max.min(v_tcp / e.length);
        }
        if turns {
            v_max = v_max.min(v_ori / e.reorient);
        }
        match g {
            Geometry::Joint { from, to } => {
                let vmax = limits::axis_speeds(model, s);
                let amax = limits::axis_accels(model, s);
                for (((a, b), v), acc) in from.iter().zip(to).zip(&vmax).zip(&amax) {
                    let d = (b - a).abs();
                    if d > 0.0 {
                        v_max = v_max.min(v / d);
                        a_max = a_max.min(acc / d);
                    }
                }
            }
            Geometry::Line { .. } | Geometry::Circle { .. } => {
                if moves {
                    a_max = a_max.min(limits::tcp_accel(model, s) / e.length);
                }
                if turns {
                    a_max = a_max.min(limits::ori_accel(model, s) / e.reorient);
                }
            }
        }
        let share = |z: f64| if moves { z / e.length } else { 0.0 };
        ProfileLimits {
            v_max,
            a_max,
            ramp_in: share(zone_in),
            ramp_out: share(zone_out),
        }
    }

    /// ConfL\On: the linear/circular path must end in the programmed configuration
    /// (`Robot::conf_matches`: cfx equal, axes 1, 4, 6 in their programmed quadrants up to a
    /// small slack). Checked before the robot moves.
    fn check_conf(&self, cmd: &MotionCommand, samples: &[Sample]) -> Result<(), MotionError> {
        let target = match cmd {
            MotionCommand::MoveL(m) if m.conf_check => &m.target,
            MotionCommand::MoveC(m) if m.conf_check => &m.to_point,
            _ => return Ok(()),
        };
        let Some(end) = samples.last() else {
            return Ok(());
        };
        if self.robot.conf_matches(&end.q, &target.robconf) {
            Ok(())
        } else {
            Err(MotionError::ConfigurationChanged {
                wanted: target.robconf,
                reached: self.robot.conf_of(&end.q),
            })
        }
    }
}

fn finite_or_zero(x: f64) -> f64 {
    if x.is_finite() { x } else { 0.0 }
}

/// Reject unusable speed and zone data before planning.
fn validate(a: &MoveArgs) -> Result<(), MotionError> {
    let positive = |what: &'static str, value: f64| {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(MotionError::InvalidData { what, value })
        }
    };
    positive("speeddata v_tcp (mm/s)", a.speed.v_tcp)?;
    positive("speeddata v_ori (deg/s)", a.speed.v_ori)?;
    match a.speed_override {
        Some(SpeedOverride::V(v)) => positive("\\V speed (mm/s)", v)?,
        Some(SpeedOverride::T(t)) => positive("\\T time (s)", t)?,
        None => {}
    }
    let zone_ok = a.zone.pzone_tcp.is_finite() && a.zone.pzone_tcp >= 0.0;
    if !a.zone.finep && !zone_ok {
        return Err(MotionError::InvalidData {
            what: "zonedata pzone_tcp (mm)",
            value: a.zone.pzone_tcp,
        });
    }
    // ABB refuses a robot-held tool without mass (tool0 and load0 carry 0.001 kg for this
    // reason): the robot's dynamic model needs the tool's weight.
    if a.tool.robhold && !(a.tool.load.mass > 0.0 && a.tool.load.mass.is_finite()) {
        return Err(MotionError::InvalidData {
            what: "tool mass (tload.mass must be above 0 kg for a robot-held tool)",
            value: a.tool.load.mass,
        });
    }
    if !a.wobj.ufprog {
        return Err(MotionError::NotSupported {
            what: "a work object moved by a mechanical unit (wobjdata ufprog FALSE)",
        });
    }
    Ok(())
}
