//! Robot fixtures the tests share: the tools of the manual's examples and joint assertions.

use rapidvc::robot::units::pose_from_pos_quat;
use rapidvc::robot::{JointsDeg, LoadData, ToolData};

/// Joint tolerance of docs/robot.md, "Acceptance facts" (expected values rounded to 0.001°).
pub const JOINT_TOL: f64 = 0.01;
/// Position tolerance (mm).
pub const POS_TOL: f64 = 0.1;
/// Quaternion tolerance per component, up to sign.
pub const QUAT_TOL: f64 = 1e-4;

/// `t_fronius_cmt` of the EGM manual's examples, with no load (`load0`).
pub fn t_fronius_cmt() -> ToolData {
    ToolData {
        robhold: true,
        tframe: pose_from_pos_quat(
            [12.3313, -0.108707, 416.142],
            [0.903899, -0.00320735, 0.427666, 0.00765917],
        ),
        load: LoadData::LOAD0,
    }
}

/// Every axis of `actual` within `tol` degrees of `expected`.
#[track_caller]
pub fn assert_joints(actual: &JointsDeg, expected: &JointsDeg, tol: f64) {
    for (i, (a, e)) in actual.iter().zip(expected).enumerate() {
        assert!(
            (a - e).abs() <= tol,
            "axis {}: {actual:?} vs {expected:?}",
            i + 1
        );
    }
}
