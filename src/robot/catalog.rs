//! The robot model table: OPW geometry, axis limits and speeds of every supported ABB arm.
//!
//! Geometry, limits and axis speeds are public figures (docs/robot.md, "Models": ROS-Industrial support
//! packages, rs-opw-kinematics presets, RobotComponents facts). Two constants per model are
//! **not** published by ABB and follow documented rules instead:
//!
//! * **Acceleration** (`max_accel`): every axis reaches its maximum speed in a fixed ramp time,
//!   `max_accel = max_speed / ramp`. The ramp is longer for the main axes (1–3) than for the
//!   wrist (4–6) and grows with the robot's size: 0.15/0.10 s for the IRB 120 and 1200,
//!   0.25/0.15 s for the IRB 1600 and 2600, 0.30/0.20 s for the IRB 4600 and 0.40/0.25 s for the
//!   IRB 6700. Together with the trapezoidal profile this is the "sane acceleration model" of
//!   the motion core; it is a modelling choice, not ABB data.
//! * **TCP speed** (`vmax_tcp`): the speed of the wrist centre at full reach when axis 1 turns
//!   at its maximum speed, `reach × ω1`, rounded down to 100 mm/s. A unit test checks every
//!   row against this rule.
//!
//! The IRB 2400 is left out on purpose: ROS-I models it with coupled axes 2/3, so its OPW
//! parameters are not in ABB axis units (docs/robot.md, "Models").

use super::model::{JointLimit, OpwParams, RobotModel};

/// Symmetric range ±`r` degrees.
const fn sym(r: f64) -> JointLimit {
    JointLimit { min: -r, max: r }
}

/// Range `min…max` degrees.
const fn range(min: f64, max: f64) -> JointLimit {
    JointLimit { min, max }
}

/// OPW parameters with `b = 0` (every ABB model here).
const fn opw(a1: f64, a2: f64, c1: f64, c2: f64, c3: f64, c4: f64) -> OpwParams {
    OpwParams {
        a1,
        a2,
        b: 0.0,
        c1,
        c2,
        c3,
        c4,
    }
}

/// `max_accel = max_speed / ramp`, with one ramp time for axes 1–3 and one for axes 4–6.
const fn accel(speed: [f64; 6], ramp_main_s: f64, ramp_wrist_s: f64) -> [f64; 6] {
    [
        speed[0] / ramp_main_s,
        speed[1] / ramp_main_s,
        speed[2] / ramp_main_s,
        speed[3] / ramp_wrist_s,
        speed[4] / ramp_wrist_s,
        speed[5] / ramp_wrist_s,
    ]
}

const SPEED_120: [f64; 6] = [250.0, 250.0, 250.0, 320.0, 320.0, 420.0];
const SPEED_1200: [f64; 6] = [288.0, 240.0, 300.0, 400.0, 405.0, 600.0];
const SPEED_1600_120: [f64; 6] = [150.0, 160.0, 170.0, 320.0, 400.0, 450.0];
const SPEED_1600_145: [f64; 6] = [180.0, 180.0, 200.0, 400.0, 400.0, 460.0];
const SPEED_2600: [f64; 6] = [175.0, 175.0, 175.0, 360.0, 360.0, 500.0];
const SPEED_4600: [f64; 6] = [175.0, 175.0, 175.0, 250.0, 250.0, 360.0];
const SPEED_6700_200: [f64; 6] = [110.0, 110.0, 110.0, 190.0, 150.0, 210.0];
const SPEED_6700_235: [f64; 6] = [100.0, 90.0, 90.0, 170.0, 120.0, 190.0];

const LIMITS_2600: [JointLimit; 6] = [
    sym(180.0),
    range(-95.0, 155.0),
    range(-180.0, 75.0),
    sym(400.0),
    sym(120.0),
    sym(400.0),
];
const LIMITS_4600: [JointLimit; 6] = [
    sym(180.0),
    range(-90.0, 150.0),
    range(-180.0, 75.0),
    sym(400.0),
    range(-125.0, 120.0),
    sym(400.0),
];
const LIMITS_6700: [JointLimit; 6] = [
    sym(170.0),
    range(-65.0, 85.0),
    range(-180.0, 70.0),
    sym(300.0),
    sym(130.0),
    sym(360.0),
];

/// The table. The first row is the default model.
pub(super) static MODELS: [RobotModel; 11] = [
    RobotModel {
        name: "IRB 2600-12/1.85",
        opw: opw(0.150, -0.115, 0.445, 0.900, 0.795, 0.085),
        joint_limits: LIMITS_2600,
        max_speed: SPEED_2600,
        max_accel: accel(SPEED_2600, 0.25, 0.15),
        vmax_tcp: 5600.0,
        note: "ROS-I irb2600_12_185_macro; RobotComponents. Default: ABB's EGM examples solve on it.",
    },
    RobotModel {
        name: "IRB 120-3/0.58",
        opw: opw(0.0, -0.070, 0.290, 0.270, 0.302, 0.072),
        joint_limits: [
            sym(165.0),
            sym(110.0),
            range(-110.0, 70.0),
            sym(160.0),
            sym(120.0),
            sym(400.0),
        ],
        max_speed: SPEED_120,
        max_accel: accel(SPEED_120, 0.15, 0.10),
        vmax_tcp: 2500.0,
        note: "ROS-I experimental irb120_3_58; rs-opw irb120_3_58; RobotComponents.",
    },
    RobotModel {
        name: "IRB 1200-5/0.90",
        opw: opw(0.0, -0.042, 0.3991, 0.448, 0.451, 0.082),
        joint_limits: [
            sym(170.0),
            range(-100.0, 130.0),
            range(-200.0, 70.0),
            sym(270.0),
            sym(130.0),
            sym(360.0),
        ],
        max_speed: SPEED_1200,
        max_accel: accel(SPEED_1200, 0.15, 0.10),
        vmax_tcp: 4500.0,
        note: "ROS-I experimental; rs-opw irb1200_5_90; RobotComponents gives axis 6 ±400°.",
    },
    RobotModel {
        name: "IRB 1200-7/0.70",
        opw: opw(0.0, -0.042, 0.3991, 0.350, 0.351, 0.082),
        joint_limits: [
            sym(170.0),
            range(-100.0, 135.0),
            range(-200.0, 70.0),
            sym(270.0),
            sym(130.0),
            sym(360.0),
        ],
        max_speed: SPEED_1200,
        max_accel: accel(SPEED_1200, 0.15, 0.10),
        vmax_tcp: 3500.0,
        note: "ROS-I experimental; rs-opw irb1200_7_70; RobotComponents.",
    },
    RobotModel {
        name: "IRB 1600-6/1.2",
        opw: opw(0.150, 0.0, 0.4865, 0.475, 0.600, 0.065),
        joint_limits: [
            sym(180.0),
            range(-63.0, 110.0),
            range(-235.0, 55.0),
            sym(200.0),
            sym(115.0),
            sym(400.0),
        ],
        max_speed: SPEED_1600_120,
        max_accel: accel(SPEED_1600_120, 0.25, 0.15),
        vmax_tcp: 3200.0,
        note: "ROS-I opw_parameters_irb1600_6_120; axis 2/3 limits from ROS-I experimental \
               conflict with RobotComponents (which gives this pair to the /1.45).",
    },
    RobotModel {
        name: "IRB 1600-10/1.45",
        opw: opw(0.150, 0.0, 0.4865, 0.700, 0.600, 0.065),
        joint_limits: [
            sym(180.0),
            range(-90.0, 120.0),
            range(-245.0, 65.0),
            sym(200.0),
            sym(115.0),
            sym(400.0),
        ],
        max_speed: SPEED_1600_145,
        max_accel: accel(SPEED_1600_145, 0.25, 0.15),
        vmax_tcp: 4500.0,
        note: "ROS-I opw_parameters_irb1600_8_145; rs-opw abb_1600; axis 2/3 limits from ROS-I \
               experimental conflict with RobotComponents (which gives this pair to the /1.2).",
    },
    RobotModel {
        name: "IRB 2600-12/1.65",
        opw: opw(0.150, -0.115, 0.445, 0.700, 0.795, 0.085),
        joint_limits: LIMITS_2600,
        max_speed: SPEED_2600,
        max_accel: accel(SPEED_2600, 0.25, 0.15),
        vmax_tcp: 5000.0,
        note: "ROS-I; rs-opw irb2600_12_165; RobotComponents (axis 2 as in the /1.85 macro).",
    },
    RobotModel {
        name: "IRB 4600-60/2.05",
        opw: opw(0.175, -0.175, 0.495, 0.900, 0.960, 0.135),
        joint_limits: LIMITS_4600,
        max_speed: SPEED_4600,
        max_accel: accel(SPEED_4600, 0.30, 0.20),
        vmax_tcp: 6200.0,
        note: "ROS-I; rs-opw irb4600_60_205; RobotComponents.",
    },
    RobotModel {
        name: "IRB 4600-40/2.55",
        opw: opw(0.175, -0.175, 0.495, 1.095, 1.270, 0.135),
        joint_limits: LIMITS_4600,
        max_speed: SPEED_4600,
        max_accel: accel(SPEED_4600, 0.30, 0.20),
        vmax_tcp: 7700.0,
        note: "ROS-I experimental; rs-opw irb4600_40_255; RobotComponents gives axis 5 −120…+125°.",
    },
    RobotModel {
        name: "IRB 6700-200/2.60",
        opw: opw(0.320, -0.200, 0.780, 1.125, 1.1425, 0.200),
        joint_limits: LIMITS_6700,
        max_speed: SPEED_6700_200,
        max_accel: accel(SPEED_6700_200, 0.40, 0.25),
        vmax_tcp: 5000.0,
        note: "ROS-I experimental irb6700_200_260; RobotComponents. Axis 2/3 coupling unverified.",
    },
    RobotModel {
        name: "IRB 6700-235/2.65",
        opw: opw(0.320, -0.200, 0.780, 1.135, 1.1825, 0.200),
        joint_limits: LIMITS_6700,
        max_speed: SPEED_6700_235,
        max_accel: accel(SPEED_6700_235, 0.40, 0.25),
        vmax_tcp: 4600.0,
        note: "ROS-I experimental; RobotComponents. Axis 2/3 coupling unverified.",
    },
];

#[cfg(test)]
mod tests {
    use super::super::units::{deg_to_rad, mm_to_m};
    use super::*;

    #[test]
    fn vmax_follows_the_documented_rule() {
        for m in MODELS.iter() {
            let v = m.reach_mm() * deg_to_rad(m.max_speed[0]);
            let rule = (v / 100.0).floor() * 100.0;
            assert_eq!(m.vmax_tcp, rule, "{}", m.name);
        }
    }

    #[test]
    fn reach_matches_the_name() {
        for m in MODELS.iter() {
            let named: f64 = m.name.rsplit('/').next().unwrap().parse().unwrap();
            assert!(
                (mm_to_m(m.reach_mm()) - named).abs() < 0.03,
                "{}: {}",
                m.name,
                m.reach_mm()
            );
        }
    }

    #[test]
    fn table_is_sane() {
        for m in MODELS.iter() {
            for i in 0..6 {
                let l = m.joint_limits[i];
                assert!(l.min < 0.0 && l.max > 0.0, "{} axis {}", m.name, i + 1);
                assert!(m.max_speed[i] > 0.0 && m.max_accel[i] > m.max_speed[i]);
            }
            assert!(m.opw.c2 > 0.0 && m.opw.c3 > 0.0 && m.opw.c4 > 0.0);
        }
    }
}
