//! The virtual 6-axis robot as pure math: models, FK/IK in ABB units, confdata, singularities,
//! frames, the shared motion-command types and the crate's only unit conversions.
//!
//! Conventions: joints are ABB axis values in **degrees** ([`JointsDeg`]); poses are
//! [`Pose`] = `nalgebra::Isometry3<f64>` with the translation in **mm**; quaternions at the
//! RAPID/EGM boundary are `[w, x, y, z]`. Kinematic poses are flange (tool0) poses in world
//! coordinates; [`frames`] maps robtargets, tools and work objects onto them.
//!
//! This module uses nothing above it (no interp, motion, egm, controller, time or threads).

mod catalog;
pub mod command;
pub mod conf;
pub mod error;
pub mod frame_points;
pub mod frames;
pub mod kinematics;
pub mod model;
pub mod singularity;
pub mod trigger;
pub mod units;

pub use conf::ConfData;
pub use error::KinError;
pub use frames::{LoadData, ToolData, WobjData, flange_target, target_from_flange};
pub use kinematics::Robot;
pub use model::{JointLimit, OpwParams, RobotModel, default_model, model_by_name, models};
pub use singularity::{SingularityFactors, SingularityKind, SingularityThresholds};
pub use units::{pose_from_pos_quat, pose_to_pos_quat};

/// Six ABB axis values in degrees (axis 1 first).
pub type JointsDeg = [f64; 6];

/// A rigid transform; translation in **mm**.
pub type Pose = nalgebra::Isometry3<f64>;
