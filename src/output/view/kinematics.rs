//! The joint frames the page draws the arm between: the OPW chain of the robot model, link by
//! link, in mm. The page (`view.js`, `jointFrames`) computes the same chain from the model
//! parameters embedded in it; [`joint_frames`] is the reference it is tested against, and its
//! last frame is the flange of [`Robot::fk`].

use nalgebra::{Translation3, UnitQuaternion, Vector3};

use crate::robot::units::{deg_to_rad, m_to_mm};
use crate::robot::{JointsDeg, Pose, Robot};

/// The frames of the chain in world coordinates (mm): `[0]` axis 1 at the height of axis 2,
/// `[1]` axis 2, `[2]` axis 3, `[3]` axis 4 (after the elbow offset), `[4]` axis 5 (the wrist
/// centre), `[5]` the flange (tool0). Axes 2, 3 and 5 turn about the frame's y axis, axes 1,
/// 4 and 6 about its z axis.
///
/// ABB axis values map onto the OPW angles with the offset of axis 3 (−90°): with all axes
/// at 0 the lower arm stands upright and the upper arm points forward.
pub fn joint_frames(robot: &Robot, q: &JointsDeg) -> [Pose; 6] {
    let p = &robot.model().opw;
    let [a1, a2, b, c1, c2, c3, c4] = [p.a1, p.a2, p.b, p.c1, p.c2, p.c3, p.c4].map(m_to_mm);
    let [q1, q2, q3, q4, q5, q6] = q.map(deg_to_rad);
    let q3 = q3 + std::f64::consts::FRAC_PI_2;
    let link = |x: f64, y: f64, z: f64, axis: Vector3<f64>, angle: f64| {
        Pose::from_parts(
            Translation3::new(x, y, z),
            UnitQuaternion::from_scaled_axis(axis * angle),
        )
    };
    let f1 = robot.base() * link(0.0, 0.0, c1, Vector3::z(), q1);
    let f2 = f1 * link(a1, b, 0.0, Vector3::y(), q2);
    let f3 = f2 * link(0.0, 0.0, c2, Vector3::y(), q3);
    let f4 = f3 * link(a2, 0.0, 0.0, Vector3::z(), q4);
    let f5 = f4 * link(0.0, 0.0, c3, Vector3::y(), q5);
    let f6 = f5 * link(0.0, 0.0, c4, Vector3::z(), q6);
    [f1, f2, f3, f4, f5, f6]
}

/// The origins of [`joint_frames`] (mm, world).
pub fn joint_origins(robot: &Robot, q: &JointsDeg) -> [[f64; 3]; 6] {
    joint_frames(robot, q).map(|f| {
        let t = f.translation.vector;
        [t.x, t.y, t.z]
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::models;

    #[test]
    fn the_last_frame_is_the_flange_of_every_model() {
        let poses: [JointsDeg; 5] = [
            [0.0; 6],
            [0.0, 0.0, 0.0, 0.0, 35.0, 0.0],
            [30.0, -20.0, 40.0, 50.0, -60.0, 70.0],
            [-120.0, 35.0, -50.0, -170.0, 100.0, 300.0],
            [83.5, -4.99, 0.0, 0.0, 0.05, 0.0],
        ];
        let base = Pose::from_parts(
            Translation3::new(100.0, -50.0, 20.0),
            UnitQuaternion::from_euler_angles(0.0, 0.0, 0.3),
        );
        for model in models() {
            for robot in [Robot::new(model), Robot::new(model).with_base(base)] {
                for q in &poses {
                    let frames = joint_frames(&robot, q);
                    let flange = robot.fk(q);
                    let d = (frames[5].translation.vector - flange.translation.vector).norm();
                    assert!(d < 1e-6, "{} {q:?}: flange off by {d} mm", model.name);
                    let angle = frames[5].rotation.angle_to(&flange.rotation);
                    assert!(
                        angle < 1e-9,
                        "{} {q:?}: orientation off by {angle}",
                        model.name
                    );
                }
            }
        }
    }

    #[test]
    fn the_calibration_pose_stands_upright() {
        let robot = Robot::default();
        let o = joint_origins(&robot, &[0.0; 6]);
        let p = &robot.model().opw;
        // Axis 2 beside axis 1 at height c1, axis 3 straight above it by c2.
        assert!((o[1][0] - m_to_mm(p.a1)).abs() < 1e-9);
        assert!((o[1][2] - m_to_mm(p.c1)).abs() < 1e-9);
        assert!((o[2][2] - m_to_mm(p.c1 + p.c2)).abs() < 1e-9);
        assert!((o[2][0] - o[1][0]).abs() < 1e-9);
        // The wrist centre is in front of axis 3, the flange further forward.
        assert!(o[4][0] > o[2][0] && o[5][0] > o[4][0]);
    }
}
