//! Robot model data (OPW geometry, axis limits, speeds, accelerations) and lookup by name.
//!
//! The data itself lives in `robot/catalog.rs`; this module defines its shape and how users
//! name a model (`--robot IRB2600-12/1.85`, `irb2600_12_185`, …).

use super::JointsDeg;
use super::catalog::MODELS;

/// OPW geometry of a 6-axis arm, in **metres** (docs/robot.md, "Models").
///
/// Every model uses `b = 0`, joint offsets `[0, 0, −90°, 0, 0, 0]` and all sign corrections
/// +1, which makes OPW joint values equal to ABB axis values (docs/robot.md, "Axis values").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpwParams {
    /// x offset of axis 2 from axis 1.
    pub a1: f64,
    /// −(z offset axis 3 → axis 4) (the elbow offset).
    pub a2: f64,
    /// Lateral offset (0 for every ABB model here).
    pub b: f64,
    /// Height of axis 2 above the base.
    pub c1: f64,
    /// Axis 2 → axis 3 (lower arm).
    pub c2: f64,
    /// Axis 4 → axis 5 along the upper arm.
    pub c3: f64,
    /// Axis 5 → flange (tool0).
    pub c4: f64,
}

impl OpwParams {
    /// √(a2² + c3²): distance from axis 3 to the wrist centre (m).
    pub fn k(&self) -> f64 {
        self.a2.hypot(self.c3)
    }

    /// ψ3 = atan2(a2, c3) (rad): angle of the wrist centre seen from axis 3.
    pub fn psi3(&self) -> f64 {
        self.a2.atan2(self.c3)
    }
}

/// Range of one axis in degrees (inclusive).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLimit {
    /// Lower bound (deg).
    pub min: f64,
    /// Upper bound (deg).
    pub max: f64,
}

impl JointLimit {
    /// True when `value` lies in the range, allowing [`LIMIT_EPS_DEG`] of float noise.
    pub fn contains(&self, value: f64) -> bool {
        value >= self.min - LIMIT_EPS_DEG && value <= self.max + LIMIT_EPS_DEG
    }
}

/// Float noise tolerated at an axis limit (deg): IK output within this of a limit counts as
/// inside it.
pub const LIMIT_EPS_DEG: f64 = 1e-9;

/// One robot model: geometry, limits and the constants of the motion model.
#[derive(Clone, Debug, PartialEq)]
pub struct RobotModel {
    /// ABB's name, e.g. `"IRB 2600-12/1.85"`.
    pub name: &'static str,
    /// OPW geometry in metres.
    pub opw: OpwParams,
    /// Axis ranges in degrees (axis 1…6).
    pub joint_limits: [JointLimit; 6],
    /// Maximum axis speeds in deg/s (axis 1…6).
    pub max_speed: JointsDeg,
    /// Maximum axis accelerations in deg/s² (axis 1…6). **Not sourced from ABB**: a documented
    /// model, see `robot/catalog.rs` (each axis reaches its top speed in a fixed ramp time).
    pub max_accel: JointsDeg,
    /// Maximum TCP speed in mm/s (the model's `vmax`). **Not sourced from ABB**: see
    /// `robot/catalog.rs`.
    pub vmax_tcp: f64,
    /// Where the data comes from and what is uncertain about it.
    pub note: &'static str,
}

impl RobotModel {
    /// Nominal reach in mm: the horizontal distance from axis 1 to the wrist centre (axis 5)
    /// with the arm stretched out, `a1 + c2 + √(a2² + c3²)`. This is the figure in ABB's model
    /// names (1.85 m for the IRB 2600-12/1.85).
    pub fn reach_mm(&self) -> f64 {
        super::units::m_to_mm(self.opw.a1 + self.opw.c2 + self.opw.k())
    }

    /// True when `name` designates this model (see [`model_by_name`]).
    pub fn matches(&self, name: &str) -> bool {
        match (ModelKey::parse(self.name), ModelKey::parse(name)) {
            (Some(mine), Some(asked)) => mine.matches(&asked),
            _ => false,
        }
    }
}

/// Every robot model rapidvc knows, the default first.
pub fn models() -> &'static [RobotModel] {
    &MODELS
}

/// The default model, IRB 2600-12/1.85 (docs/robot.md, "Models": ABB's EGM examples were recorded on it).
pub fn default_model() -> &'static RobotModel {
    &MODELS[0]
}

/// Find a model by name, case-insensitively and forgiving about separators:
/// `"IRB 2600-12/1.85"`, `"IRB2600-12/1.85"`, `"irb2600_12_185"`, `"2600-12-1.85"` all name the
/// same robot. Payload and reach may be left out when the rest is unambiguous (`"irb120"`).
/// The reach may be written in metres with a dot (`1.85`) or in centimetres (`185`, `090`).
pub fn model_by_name(name: &str) -> Option<&'static RobotModel> {
    let asked = ModelKey::parse(name)?;
    let mut found = MODELS.iter().filter(|m| {
        ModelKey::parse(m.name)
            .map(|k| k.matches(&asked))
            .unwrap_or(false)
    });
    let first = found.next()?;
    // Ambiguous partial names ("irb2600" = 1.65 or 1.85) match nothing.
    if found.next().is_some() {
        None
    } else {
        Some(first)
    }
}

/// A model name reduced to family, payload and reach.
#[derive(Debug, PartialEq)]
struct ModelKey {
    /// e.g. `"2600"`, `"2600id"`.
    family: String,
    /// e.g. `"12"`; `None` when not given.
    payload: Option<String>,
    /// Reach in centimetres; `None` when not given.
    reach_cm: Option<u32>,
}

impl ModelKey {
    fn parse(name: &str) -> Option<ModelKey> {
        let lower = name.trim().to_ascii_lowercase();
        let mut rest = lower.as_str();
        for prefix in ["abb", "irb"] {
            rest = rest.trim_start_matches(|c: char| !c.is_ascii_alphanumeric());
            if let Some(r) = rest.strip_prefix(prefix) {
                rest = r;
            }
        }
        let tokens: Vec<&str> = rest
            .split(|c: char| !(c.is_ascii_alphanumeric() || c == '.'))
            .filter(|t| !t.is_empty())
            .collect();
        let (family, tail) = tokens.split_first()?;
        if !family.chars().next()?.is_ascii_digit() {
            return None;
        }
        let (payload, reach_tokens) = match tail.split_first() {
            Some((p, r)) => (Some((*p).to_string()), r),
            None => (None, &[][..]),
        };
        let reach_cm = match reach_tokens {
            [] => None,
            [r] => Some(parse_reach_cm(r)?),
            // "1_85" written with a separator instead of the dot.
            [m, cm] if m.chars().all(|c| c.is_ascii_digit()) && cm.len() == 2 => {
                Some(parse_reach_cm(&format!("{m}.{cm}"))?)
            }
            _ => return None,
        };
        Some(ModelKey {
            family: (*family).to_string(),
            payload,
            reach_cm,
        })
    }

    /// `self` is a full key from the table; `asked` may leave payload or reach out.
    fn matches(&self, asked: &ModelKey) -> bool {
        self.family == asked.family
            && asked
                .payload
                .as_ref()
                .is_none_or(|p| self.payload.as_ref() == Some(p))
            && asked.reach_cm.is_none_or(|r| self.reach_cm == Some(r))
    }
}

/// `"1.85"` → 185, `"185"` → 185, `"090"`/`"90"` → 90, `"0.9"` → 90.
fn parse_reach_cm(token: &str) -> Option<u32> {
    if token.contains('.') {
        let m: f64 = token.parse().ok()?;
        let cm = (m * 100.0).round();
        (m.is_finite() && (1.0..100_000.0).contains(&cm)).then_some(cm as u32)
    } else if !token.is_empty() && token.chars().all(|c| c.is_ascii_digit()) {
        token.parse().ok()
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_forgiving() {
        for n in [
            "IRB 2600-12/1.85",
            "IRB2600-12/1.85",
            "irb2600_12_185",
            "irb2600-12-1.85",
            "2600-12/1.85",
            "ABB IRB 2600-12/1.85",
            "irb_2600_12_1_85",
        ] {
            assert_eq!(
                model_by_name(n).map(|m| m.name),
                Some("IRB 2600-12/1.85"),
                "{n}"
            );
        }
        assert_eq!(
            model_by_name("irb120").map(|m| m.name),
            Some("IRB 120-3/0.58")
        );
        assert_eq!(
            model_by_name("irb120_3_58").map(|m| m.name),
            Some("IRB 120-3/0.58")
        );
        assert_eq!(
            model_by_name("IRB 1200-5/0.9").map(|m| m.name),
            Some("IRB 1200-5/0.90")
        );
        assert_eq!(
            model_by_name("irb1200_5_90").map(|m| m.name),
            Some("IRB 1200-5/0.90")
        );
        assert!(model_by_name("irb2600").is_none(), "ambiguous");
        assert!(model_by_name("irb2600-12/1.75").is_none());
        assert!(model_by_name("kuka kr6").is_none());
        assert!(model_by_name("").is_none());
        assert!(model_by_name("irb").is_none());
    }

    #[test]
    fn default_is_the_2600_185() {
        assert_eq!(default_model().name, "IRB 2600-12/1.85");
        assert!(default_model().matches("irb2600_12_185"));
    }
}
