//! The virtual robot: forward and inverse kinematics in ABB axis units with turn expansion,
//! ABB axis limits, confdata selection (ConfJ/ConfL \On and \Off) and singularity checks.
//!
//! rs-opw-kinematics solves the arm (≤ 8 solutions in (−180°, 180°]); everything ABB-specific
//! happens here: solutions are expanded by ±360°·k on every axis whose range allows it, checked
//! against the real limits in degrees, and classified by confdata (docs/robot.md, "Inverse kinematics", "Configuration").

use std::f64::consts::FRAC_PI_2;

use rs_opw_kinematics::kinematic_traits::Kinematics;
use rs_opw_kinematics::kinematics_impl::OPWKinematics;
use rs_opw_kinematics::parameters::opw_kinematics::Parameters;

use super::conf::{self, ConfData, conf_from};
use super::error::KinError;
use super::model::{JointLimit, LIMIT_EPS_DEG, RobotModel, default_model};
use super::singularity::{SingularityFactors, SingularityKind, SingularityThresholds};
use super::units::{
    joints_deg_to_rad, joints_rad_to_deg, nan_pose, pose_from_opw, pose_is_finite, pose_to_opw,
};
use super::{JointsDeg, Pose};

/// Axis 5 within this (deg) of 0° is treated as exactly on the wrist singularity, where only
/// J4 + J6 is determined and ik_conf may split it differently to honour cf4/cf6. Moving the
/// split at |J5| ≤ 1e-6° moves the flange by less than 1e-8 rad·c4 (nanometres).
const WRIST_SPLIT_EPS_DEG: f64 = 1e-6;

/// Two solutions closer than this (deg, on every axis) are the same solution.
const DUPLICATE_EPS_DEG: f64 = 1e-9;

/// One 6-axis robot: its model, where its base stands in the world, and the OPW solver.
///
/// All poses are flange (tool0) poses in **world** coordinates, in mm; joints are ABB axis
/// values in degrees. Nothing here panics: non-finite input gives [`KinError::NotFinite`] (or a
/// NaN pose from [`Robot::fk`]).
#[derive(Clone, Debug)]
pub struct Robot {
    model: &'static RobotModel,
    base: Pose,
    base_inv: Pose,
    solver: OPWKinematics,
}

impl Default for Robot {
    fn default() -> Self {
        Robot::new(default_model())
    }
}

impl Robot {
    /// A robot of `model` with its base at the world origin.
    pub fn new(model: &'static RobotModel) -> Robot {
        let p = &model.opw;
        // Offsets are constants well inside ±2π, so rs-opw's constructor cannot panic.
        let params = Parameters {
            a1: p.a1,
            a2: p.a2,
            b: p.b,
            c1: p.c1,
            c2: p.c2,
            c3: p.c3,
            c4: p.c4,
            offsets: [0.0, 0.0, -FRAC_PI_2, 0.0, 0.0, 0.0],
            sign_corrections: [1; 6],
            dof: 6,
        };
        Robot {
            model,
            base: Pose::identity(),
            base_inv: Pose::identity(),
            solver: OPWKinematics::new(params),
        }
    }

    /// The same robot with its base frame at `base` (in world, mm).
    pub fn with_base(mut self, base: Pose) -> Robot {
        self.base = base;
        self.base_inv = base.inverse();
        self
    }

    /// The robot model.
    pub fn model(&self) -> &'static RobotModel {
        self.model
    }

    /// The base frame in world coordinates.
    pub fn base(&self) -> &Pose {
        &self.base
    }

    /// Forward kinematics: the flange (tool0) pose in the **base** frame. Non-finite axes give
    /// a pose of NaNs.
    pub fn fk_base(&self, q: &JointsDeg) -> Pose {
        if !q.iter().all(|v| v.is_finite()) {
            return nan_pose();
        }
        match self.solver.try_forward(&joints_deg_to_rad(q)) {
            Ok(p) => pose_from_opw(&p),
            Err(_) => nan_pose(),
        }
    }

    /// Forward kinematics: the flange (tool0) pose in **world**. Non-finite axes give a pose of
    /// NaNs; use [`Robot::try_fk`] to get an error instead.
    pub fn fk(&self, q: &JointsDeg) -> Pose {
        self.base * self.fk_base(q)
    }

    /// Forward kinematics with [`KinError::NotFinite`] for non-finite axes.
    pub fn try_fk(&self, q: &JointsDeg) -> Result<Pose, KinError> {
        let p = self.fk(q);
        if pose_is_finite(&p) {
            Ok(p)
        } else {
            Err(KinError::NotFinite)
        }
    }

    /// Every solution of the arm for a flange pose in world, as rs-opw returns them
    /// (degrees, each axis in (−180°, 180°], limits not applied).
    fn raw_solutions(&self, flange_world: &Pose) -> Result<Vec<JointsDeg>, KinError> {
        let opw = self.to_opw_base(flange_world)?;
        let sols = self.solver.inverse(&opw);
        if sols.is_empty() {
            Err(outside_reach(flange_world))
        } else {
            Ok(sols.iter().map(joints_rad_to_deg).collect())
        }
    }

    fn to_opw_base(
        &self,
        flange_world: &Pose,
    ) -> Result<rs_opw_kinematics::kinematic_traits::Pose, KinError> {
        if !pose_is_finite(flange_world) {
            return Err(KinError::NotFinite);
        }
        pose_to_opw(&(self.base_inv * flange_world)).ok_or(KinError::NotFinite)
    }

    /// Inverse kinematics: **every** joint vector within the axis limits that puts the flange
    /// at `flange_world`, including the turn variants (±360°·k) of every axis whose range
    /// allows them (axes 4 and 6 on ±400° robots, axis 1 at ±180°, …). Sorted
    /// lexicographically; empty when the pose is unreachable or not finite.
    pub fn ik_all(&self, flange_world: &Pose) -> Vec<JointsDeg> {
        let Ok(raw) = self.raw_solutions(flange_world) else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for s in &raw {
            expand_into(s, &self.model.joint_limits, &mut out);
        }
        out.sort_by(|a, b| {
            a.iter()
                .zip(b)
                .map(|(x, y)| x.total_cmp(y))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        out.dedup_by(|a, b| same_joints(a, b));
        out
    }

    /// Inverse kinematics in the **programmed configuration** (ConfJ\On): the solution whose
    /// confdata equals `wanted`.
    ///
    /// cfx must match (a factor lying exactly on its singularity matches both bits). cf1, cf4
    /// and cf6 must match; a solution up to [`conf::CONF_QUADRANT_SLACK_DEG`] outside the
    /// programmed quadrant is accepted when no exact one exists. On the wrist singularity
    /// (axis 5 = 0°) J4 + J6 is re-split to honour cf4/cf6.
    ///
    /// Errors: [`KinError::NotFinite`]; [`KinError::OutsideReach`] when no configuration
    /// reaches the pose; [`KinError::JointOutOfRange`] when the programmed configuration (or,
    /// if none matches, every configuration) needs an axis beyond its limit;
    /// [`KinError::ConfigurationUnreachable`] when other configurations reach the pose but the
    /// programmed one does not.
    pub fn ik_conf(&self, flange_world: &Pose, wanted: &ConfData) -> Result<JointsDeg, KinError> {
        let raw = self.raw_solutions(flange_world)?;
        let limits = &self.model.joint_limits;
        let mut best: Option<(f64, JointsDeg)> = None;
        let mut limit_error: Option<KinError> = None;
        for s in &raw {
            let f = self.singularity(s);
            if !conf::cfx_compatible(&f, wanted.cfx) {
                continue;
            }
            match fit_conf(s, wanted, limits) {
                Fit::Ok(score, q) => {
                    if best.as_ref().is_none_or(|(b, _)| score < *b) {
                        best = Some((score, q));
                    }
                }
                Fit::Limit(e) => {
                    limit_error.get_or_insert(e);
                }
                Fit::Quadrant => {}
            }
        }
        if let Some((_, q)) = best {
            return Ok(q);
        }
        if let Some(e) = limit_error {
            return Err(e);
        }
        let all = self.ik_all(flange_world);
        if all.is_empty() {
            // Every configuration needs some axis beyond its limit.
            return Err(raw
                .first()
                .map_or(KinError::NotFinite, |r| first_limit_violation(r, limits)));
        }
        let mut available: Vec<ConfData> = all.iter().map(|q| self.conf_of(q)).collect();
        available.sort_by_key(|c| (c.cfx, c.cf1, c.cf4, c.cf6));
        available.dedup();
        Err(KinError::ConfigurationUnreachable {
            wanted: *wanted,
            available,
        })
    }

    /// Inverse kinematics **closest to `current`** (ConfJ\Off, ConfL\Off, and the cycle-to-cycle
    /// continuity of linear moves): the in-limit solution minimising Σ (Δqᵢ / q̇maxᵢ)², i.e. the
    /// one the axes reach soonest. On the wrist singularity J4/J6 are split near `current`.
    ///
    /// Errors: [`KinError::NotFinite`] (pose or `current`), [`KinError::OutsideReach`],
    /// [`KinError::JointOutOfRange`] when every solution needs an axis beyond its limit.
    pub fn ik_nearest(
        &self,
        flange_world: &Pose,
        current: &JointsDeg,
    ) -> Result<JointsDeg, KinError> {
        if !current.iter().all(|v| v.is_finite()) {
            return Err(KinError::NotFinite);
        }
        let opw = self.to_opw_base(flange_world)?;
        let mut sols = self
            .solver
            .inverse_continuing(&opw, &joints_deg_to_rad(current));
        if sols.is_empty() {
            // rs-opw gives up on references so far out that f64 cannot keep their turns;
            // the plain solutions (then turned towards `current` below) still apply.
            sols = self.solver.inverse(&opw);
        }
        if sols.is_empty() {
            return Err(outside_reach(flange_world));
        }
        let limits = &self.model.joint_limits;
        let speed = &self.model.max_speed;
        let mut best: Option<(f64, JointsDeg)> = None;
        let mut first_raw: Option<JointsDeg> = None;
        'solutions: for s in sols.iter().map(joints_rad_to_deg) {
            first_raw.get_or_insert(s);
            let mut q = [0.0; 6];
            let mut cost = 0.0;
            for i in 0..6 {
                let Some(v) = nearest_variant(s[i], current[i], &limits[i]) else {
                    continue 'solutions;
                };
                q[i] = v;
                let d = (v - current[i]) / speed[i];
                cost += d * d;
            }
            if best.as_ref().is_none_or(|(c, _)| cost < *c) {
                best = Some((cost, q));
            }
        }
        match (best, first_raw) {
            (Some((_, q)), _) => Ok(q),
            (None, Some(raw)) => Err(first_limit_violation(&raw, limits)),
            (None, None) => Err(outside_reach(flange_world)),
        }
    }

    /// confdata of a joint vector (docs/robot.md, "Configuration").
    pub fn conf_of(&self, q: &JointsDeg) -> ConfData {
        conf_from(q, &self.singularity(q))
    }

    /// True when joints `q` are in the programmed configuration `wanted` by the rules of
    /// [`Robot::ik_conf`]: cfx equal (a factor on its singularity matches both bits), and
    /// axes 1, 4, 6 inside their programmed quadrants up to [`conf::CONF_QUADRANT_SLACK_DEG`].
    /// This is the check ConfL\On applies where a linear move ends.
    pub fn conf_matches(&self, q: &JointsDeg, wanted: &ConfData) -> bool {
        q.iter().all(|v| v.is_finite())
            && conf::cfx_compatible(&self.singularity(q), wanted.cfx)
            && [(q[0], wanted.cf1), (q[3], wanted.cf4), (q[5], wanted.cf6)]
                .iter()
                .all(|&(v, cf)| conf::quadrant_distance(v, cf) <= conf::CONF_QUADRANT_SLACK_DEG)
    }

    /// True when the wrist centre lies between axis 1 and axis 2 (0 < r < a1). There the
    /// "in front of axis 1" bit of cfx depends on the convention: rapidvc measures from axis 1
    /// (docs/robot.md, "Configuration"), ARTE's `compute_configuration.m` from axis 2. Callers may warn.
    pub fn cfx_convention_dependent(&self, q: &JointsDeg) -> bool {
        let r = self.singularity(q).shoulder_mm;
        r > 0.0 && r < super::units::m_to_mm(self.model.opw.a1)
    }

    /// The three det-J factors of a joint vector (docs/robot.md, "Singularities").
    pub fn singularity(&self, q: &JointsDeg) -> SingularityFactors {
        SingularityFactors::of(&self.model.opw, q)
    }

    /// The singularity `q` is close to under the default thresholds
    /// ([`SingularityThresholds::default`]), if any.
    pub fn near_singularity(&self, q: &JointsDeg) -> Option<SingularityKind> {
        self.near_singularity_with(q, &SingularityThresholds::default())
    }

    /// The singularity `q` is close to under `thresholds`, if any.
    pub fn near_singularity_with(
        &self,
        q: &JointsDeg,
        thresholds: &SingularityThresholds,
    ) -> Option<SingularityKind> {
        thresholds.check(&self.singularity(q))
    }

    /// [`KinError::Singularity`] when `q` is close to a singularity (default thresholds).
    pub fn check_singularity(&self, q: &JointsDeg) -> Result<(), KinError> {
        match self.near_singularity(q) {
            Some(kind) => Err(KinError::Singularity { kind, joints: *q }),
            None => Ok(()),
        }
    }

    /// [`KinError::NotFinite`] or the first axis outside its limits
    /// ([`KinError::JointOutOfRange`], 1-based axis number).
    pub fn check_limits(&self, q: &JointsDeg) -> Result<(), KinError> {
        if !q.iter().all(|v| v.is_finite()) {
            return Err(KinError::NotFinite);
        }
        match (0..6).find(|&i| !self.model.joint_limits[i].contains(q[i])) {
            Some(i) => Err(joint_out_of_range(i, q[i], &self.model.joint_limits[i])),
            None => Ok(()),
        }
    }
}

fn outside_reach(flange_world: &Pose) -> KinError {
    let t = flange_world.translation.vector;
    KinError::OutsideReach {
        position: [t.x, t.y, t.z],
    }
}

fn joint_out_of_range(i: usize, value: f64, l: &JointLimit) -> KinError {
    KinError::JointOutOfRange {
        joint: i + 1,
        value,
        min: l.min,
        max: l.max,
    }
}

/// The error for a raw solution none of whose turn variants fits: the first such axis, with
/// the variant closest to its range.
fn first_limit_violation(raw: &JointsDeg, limits: &[JointLimit; 6]) -> KinError {
    for i in 0..6 {
        if variants(raw[i], &limits[i]).next().is_none() {
            let mid = (limits[i].min + limits[i].max) / 2.0;
            let v = raw[i] + 360.0 * ((mid - raw[i]) / 360.0).round();
            return joint_out_of_range(i, v, &limits[i]);
        }
    }
    // Callers only pass solutions with an axis that fits nowhere, so this is not reached; it
    // stays an error rather than a panic.
    KinError::NotFinite
}

/// Every θ + 360°·k inside `limit`.
fn variants(theta: f64, limit: &JointLimit) -> impl Iterator<Item = f64> {
    let k_min = ((limit.min - LIMIT_EPS_DEG - theta) / 360.0).ceil();
    let k_max = ((limit.max + LIMIT_EPS_DEG - theta) / 360.0).floor();
    let (k_min, k_max) = if k_min.is_finite() && k_max.is_finite() {
        (k_min as i64, k_max as i64)
    } else {
        (1, 0)
    };
    (k_min..=k_max).map(move |k| theta + 360.0 * k as f64)
}

/// The in-limit turn variant of `theta` closest to `target`.
fn nearest_variant(theta: f64, target: f64, limit: &JointLimit) -> Option<f64> {
    variants(theta, limit).min_by(|a, b| (a - target).abs().total_cmp(&(b - target).abs()))
}

/// Append every in-limit turn combination of `s`.
fn expand_into(s: &JointsDeg, limits: &[JointLimit; 6], out: &mut Vec<JointsDeg>) {
    let per_axis: [Vec<f64>; 6] = std::array::from_fn(|i| variants(s[i], &limits[i]).collect());
    if per_axis.iter().any(Vec::is_empty) {
        return;
    }
    let mut idx = [0usize; 6];
    loop {
        out.push(std::array::from_fn(|i| per_axis[i][idx[i]]));
        // Odometer over the per-axis variants.
        let mut axis = 0;
        loop {
            if axis == 6 {
                return;
            }
            idx[axis] += 1;
            if idx[axis] < per_axis[axis].len() {
                break;
            }
            idx[axis] = 0;
            axis += 1;
        }
    }
}

fn same_joints(a: &JointsDeg, b: &JointsDeg) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| (x - y).abs() <= DUPLICATE_EPS_DEG)
}

/// Result of fitting one raw solution to a programmed configuration.
enum Fit {
    /// Fits; score = total distance (deg) outside the programmed quadrants (0 = exact).
    Ok(f64, JointsDeg),
    /// The programmed quadrants need an axis beyond its limit.
    Limit(KinError),
    /// Some quadrant cannot be met.
    Quadrant,
}

/// Axes whose turn is given by confdata: 1, 4, 6 (indices) and the matching cf.
fn wanted_quadrant(i: usize, c: &ConfData) -> Option<i32> {
    match i {
        0 => Some(c.cf1),
        3 => Some(c.cf4),
        5 => Some(c.cf6),
        _ => None,
    }
}

/// The turn variant of `theta` (any k) closest to quadrant `cf`, with its distance from it.
fn variant_in_quadrant(theta: f64, cf: i32) -> (f64, f64) {
    let (lo, hi) = conf::quadrant_range(cf);
    let centre = (lo + hi) / 2.0;
    let v = theta + 360.0 * ((centre - theta) / 360.0).round();
    (v, conf::quadrant_distance(v, cf))
}

fn fit_conf(s: &JointsDeg, wanted: &ConfData, limits: &[JointLimit; 6]) -> Fit {
    let mut q = *s;
    let mut score = 0.0;
    for i in 0..6 {
        match wanted_quadrant(i, wanted) {
            Some(cf) => {
                let (v, dist) = variant_in_quadrant(s[i], cf);
                q[i] = v;
                score += dist;
            }
            None => match nearest_variant(s[i], 0.0, &limits[i]) {
                Some(v) => q[i] = v,
                None => return Fit::Limit(first_limit_violation(s, limits)),
            },
        }
    }
    let wrist_ok = |q: &JointsDeg| {
        conf::quadrant_distance(q[3], wanted.cf4) <= conf::CONF_QUADRANT_SLACK_DEG
            && conf::quadrant_distance(q[5], wanted.cf6) <= conf::CONF_QUADRANT_SLACK_DEG
            && limits[3].contains(q[3])
            && limits[5].contains(q[5])
    };
    if q[4].abs() <= WRIST_SPLIT_EPS_DEG
        && (!wrist_ok(&q) || score > 0.0)
        && let Some((j4, j6)) = resplit_wrist(q[3] + q[5], wanted, limits)
    {
        q[3] = j4;
        q[5] = j6;
        score = conf::quadrant_distance(q[0], wanted.cf1);
    }
    for i in [0, 3, 5] {
        let cf = wanted_quadrant(i, wanted).unwrap_or(0);
        if conf::quadrant_distance(q[i], cf) > conf::CONF_QUADRANT_SLACK_DEG {
            return Fit::Quadrant;
        }
    }
    match (0..6).find(|&i| !limits[i].contains(q[i])) {
        Some(i) => Fit::Limit(joint_out_of_range(i, q[i], &limits[i])),
        None => Fit::Ok(score, q),
    }
}

/// On the wrist singularity only J4 + J6 (= `sum`, mod 360°) is fixed: find J4 in quadrant cf4
/// and J6 in quadrant cf6, both within limits, with J4 + J6 ≡ sum. Picks the middle of the
/// feasible J4 interval.
fn resplit_wrist(sum: f64, wanted: &ConfData, limits: &[JointLimit; 6]) -> Option<(f64, f64)> {
    let (q4lo, q4hi) = conf::quadrant_range(wanted.cf4);
    let (q6lo, q6hi) = conf::quadrant_range(wanted.cf6);
    let lo4 = q4lo.max(limits[3].min);
    let hi4 = q4hi.min(limits[3].max);
    let lo6 = q6lo.max(limits[5].min);
    let hi6 = q6hi.min(limits[5].max);
    if lo4 > hi4 || lo6 > hi6 {
        return None;
    }
    // J4 + J6 ranges over [lo4 + lo6, hi4 + hi6]; try every turn of the sum inside it.
    let s0 = sum.rem_euclid(360.0);
    let k_min = ((lo4 + lo6 - s0) / 360.0).ceil() as i64;
    let k_max = ((hi4 + hi6 - s0) / 360.0).floor() as i64;
    (k_min..=k_max).find_map(|k| {
        let s = s0 + 360.0 * k as f64;
        let lo = lo4.max(s - hi6);
        let hi = hi4.min(s - lo6);
        (lo <= hi).then(|| {
            let j4 = (lo + hi) / 2.0;
            (j4, s - j4)
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::model::model_by_name;

    #[test]
    fn variants_cover_the_range() {
        let l = JointLimit {
            min: -400.0,
            max: 400.0,
        };
        let v: Vec<f64> = variants(10.0, &l).collect();
        assert_eq!(v, vec![-350.0, 10.0, 370.0]);
        let v: Vec<f64> = variants(179.0, &l).collect();
        assert_eq!(v, vec![-181.0, 179.0]);
        let l = JointLimit {
            min: -180.0,
            max: 180.0,
        };
        let v: Vec<f64> = variants(180.0, &l).collect();
        assert_eq!(v, vec![-180.0, 180.0]);
        assert_eq!(variants(f64::NAN, &l).count(), 0);
        let l = JointLimit {
            min: -200.0,
            max: 70.0,
        };
        assert_eq!(variants(170.0, &l).collect::<Vec<_>>(), vec![-190.0]);
    }

    #[test]
    fn expansion_counts() {
        let robot = Robot::default();
        let mut out = Vec::new();
        expand_into(
            &[10.0, 0.0, 0.0, 20.0, 30.0, -170.0],
            &robot.model().joint_limits,
            &mut out,
        );
        // axis 4: −340, 20, 380; axis 6: −170, 190.
        assert_eq!(out.len(), 6);
    }

    #[test]
    fn wrist_resplit_honours_cf4_cf6() {
        let robot = Robot::default();
        let limits = &robot.model().joint_limits;
        let wanted = ConfData::new(0, 1, -2, 0);
        let (j4, j6) = resplit_wrist(0.0, &wanted, limits).unwrap();
        assert!((j4 + j6).abs() < 1e-9);
        assert_eq!(conf::quarter(j4), 1);
        assert_eq!(conf::quarter(j6), -2);
        assert!(resplit_wrist(0.0, &ConfData::new(0, 5, 0, 0), limits).is_none());
    }

    #[test]
    fn wrist_singular_target_reaches_other_wrist_quadrants() {
        let robot = Robot::new(model_by_name("IRB 2600-12/1.85").unwrap());
        let p = robot.fk(&[20.0, 10.0, -10.0, 0.0, 0.0, 0.0]);
        let q = robot.ik_conf(&p, &ConfData::new(0, 1, -2, 0)).unwrap();
        assert!(q[4].abs() < 1e-6);
        assert_eq!(conf::quarter(q[3]), 1);
        assert_eq!(conf::quarter(q[5]), -2);
        let back = robot.fk(&q);
        assert!((back.translation.vector - p.translation.vector).norm() < 1e-6);
        assert!(back.rotation.angle_to(&p.rotation) < 1e-6);
    }
}
