//! The seam for path correction (EGMMoveL/EGMMoveC): a per-cycle offset added to the planned TCP of corrected moves, turned into axis values by the executor.
//!
//! Moves are planned uncorrected (the planner does not know about sensors). While a
//! [`PathCorrection`] is installed in the executor ([`super::Executor::set_path_correction`]),
//! every sample of a move it [`PathCorrection::corrects`] goes through it:
//!
//! 1. The executor measures the **programmed path**: the arc length `s` of the planned TCP
//!    since the start of the corrected sequence (0 at the fine point it starts from) and the
//!    planned TCP step of this cycle (the path tangent). A sequence starts with the first
//!    corrected sample after an uncorrected one or after a corrected stop point.
//! 2. [`PathCorrection::offset`] returns a world offset (mm) for the TCP.
//! 3. The executor moves the planned TCP — and with it the flange, since the orientation is
//!    kept — by that offset and solves the inverse kinematics nearest to the previous
//!    cycle's axis values. The result passes the usual per-cycle supervision (axis ranges,
//!    axis speeds). An unreachable corrected pose stops the robot with the kinematics
//!    error (`PathPlace::Cycle`).
//!
//! A sequence must end in a stop point: when an uncorrected sample follows a corrected one
//! that was not the last sample of a stop point, [`PathCorrection::leave`] decides (the
//! EGM glue refuses it with the manual's "EGM Path correction has to start and end in a fine
//! point"). Either method may return an error to stop the robot (e.g. the sensor stopped
//! answering); the executor logs it and halts as for any motion error.
//!
//! Only robot-held tools are corrected (the sensor is robot-mounted): the TCP offset is
//! applied to the flange. A corrected cycle with a non-zero offset solves the inverse
//! kinematics, which allocates (the solver returns its solutions in a `Vec`), as pose-mode
//! EGM guidance does; uncorrected cycles and zero offsets do not. The implementation must not block, sleep or panic; it runs inside
//! the motion cycle. The shell that installs it keeps its own typed handle on it (the object
//! is shared, e.g. behind a lock only the motion thread takes) to hand it sensor data and read
//! what it applied between cycles.

use nalgebra::Vector3;

use crate::robot::Pose;

use super::event::{InstrRef, MotionError};
use crate::time::RobotTime;

/// The programmed path at one corrected cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathPoint {
    /// The instruction the sample belongs to.
    pub instr: InstrRef,
    /// Arc length of the planned TCP since the start of the corrected sequence, mm.
    pub s: f64,
    /// The planned (uncorrected) TCP in world coordinates.
    pub tcp: Pose,
    /// The planned (uncorrected) flange in world coordinates.
    pub flange: Pose,
    /// The planned TCP step of this cycle, world, mm (zero at standstill): the path tangent.
    pub step: Vector3<f64>,
    /// The first sample of a corrected sequence.
    pub first: bool,
    /// The last sample of a stop point (the sequence may end here).
    pub stop_point: bool,
}

/// A source of per-cycle path offsets (see the module docs).
pub trait PathCorrection: Send {
    /// True when the samples of `instr` are corrected.
    fn corrects(&self, instr: &InstrRef) -> bool;

    /// The world offset (mm) to add to the planned TCP at `point`. An error stops the robot.
    fn offset(&mut self, now: RobotTime, point: &PathPoint) -> Result<Vector3<f64>, MotionError>;

    /// An uncorrected sample of `instr` follows a corrected sequence that did not end in a
    /// stop point. An error stops the robot; `Ok` lets it go on (the offset is dropped).
    fn leave(&mut self, now: RobotTime, instr: &InstrRef) -> Result<(), MotionError>;

    /// The instruction name that setpoints and events of the corrected `instr` show (e.g.
    /// `EGMMoveL` for a move queued as a `MoveL`).
    fn rename(&self, instr: &InstrRef) -> &'static str {
        instr.name
    }
}

/// The executor's measurement of the programmed path of a corrected sequence.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Track {
    /// Arc length so far, mm.
    pub s: f64,
    /// The planned TCP position of the last corrected sample.
    pub last: Vector3<f64>,
    /// The last corrected sample was not the end of a stop point.
    pub open: bool,
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]
mod tests {
    use super::*;
    use crate::motion::{CoreConfig, MotionCore, MotionState, Setpoint, Severity};
    use crate::robot::command::{
        EXTAX_NONE, MotionCommand, MoveArgs, MoveJ, MoveL, RobTarget, SpeedData, ZoneData,
    };
    use crate::robot::{ConfData, Robot, ToolData};
    use std::sync::{Arc, Mutex};
    use std::time::Duration;

    const DT: Duration = Duration::from_millis(4);

    /// A constant offset on the moves with ids in `ids`, recording every point.
    struct Constant {
        ids: Vec<u64>,
        offset: Vector3<f64>,
        record: Arc<Mutex<Record>>,
        fail_at: Option<f64>,
    }

    /// What a [`Constant`] saw, shared with the test.
    #[derive(Default)]
    struct Record {
        points: Vec<PathPoint>,
        left: Vec<u64>,
    }

    /// Installs `c` in `core`; its record stays readable.
    fn install(core: &mut MotionCore, c: Constant) -> Arc<Mutex<Record>> {
        let record = Arc::clone(&c.record);
        core.set_path_correction(Some(Box::new(c)));
        record
    }

    impl Constant {
        fn new(ids: &[u64], offset: [f64; 3]) -> Constant {
            Constant {
                ids: ids.to_vec(),
                offset: Vector3::from(offset),
                record: Arc::default(),
                fail_at: None,
            }
        }
    }

    fn stop(detail: &str) -> MotionError {
        MotionError::PathCorrection {
            number: 90999,
            title: "test stop",
            detail: detail.to_string(),
            rapid_error: Some("ERR_TEST"),
        }
    }

    impl PathCorrection for Constant {
        fn corrects(&self, instr: &InstrRef) -> bool {
            self.ids.contains(&instr.id)
        }

        fn offset(
            &mut self,
            _now: RobotTime,
            point: &PathPoint,
        ) -> Result<Vector3<f64>, MotionError> {
            self.record.lock().unwrap().points.push(*point);
            if self.fail_at.is_some_and(|s| point.s >= s) {
                return Err(stop("the sensor stopped answering"));
            }
            Ok(self.offset)
        }

        fn leave(&mut self, _now: RobotTime, instr: &InstrRef) -> Result<(), MotionError> {
            self.record.lock().unwrap().left.push(instr.id);
            Err(stop("not ended in a fine point"))
        }
    }

    fn target(x: f64, y: f64, z: f64) -> RobTarget {
        RobTarget {
            trans: [x, y, z],
            rot: [0.0, 0.0, 1.0, 0.0],
            robconf: ConfData::new(0, 0, -1, 1),
            extax: EXTAX_NONE,
        }
    }

    fn args(id: u64, v: f64, zone: ZoneData) -> MoveArgs {
        MoveArgs::new(id, SpeedData::v(v), zone, ToolData::tool0())
    }

    fn z5() -> ZoneData {
        ZoneData {
            finep: false,
            pzone_tcp: 5.0,
            pzone_ori: 7.5,
            pzone_eax: 7.5,
            zone_ori: 0.75,
            zone_leax: 7.5,
            zone_reax: 0.75,
        }
    }

    fn move_l(id: u64, t: RobTarget, v: f64, zone: ZoneData) -> MotionCommand {
        MotionCommand::MoveL(MoveL {
            args: args(id, v, zone),
            target: t,
            conf_check: false,
        })
    }

    /// A core standing at (1000, 20, 500), tool0 pointing down.
    fn core_at_seam_start() -> MotionCore {
        let mut core = MotionCore::new(Robot::default(), CoreConfig::default(), [0.0; 6]);
        core.enqueue(MotionCommand::MoveJ(MoveJ {
            args: args(1, 1000.0, ZoneData::FINE),
            target: target(1000.0, 20.0, 500.0),
            conf_check: false,
        }))
        .unwrap();
        run(&mut core, 0);
        core
    }

    fn run(core: &mut MotionCore, from_tick: u64) -> Vec<Setpoint> {
        let mut out = Vec::new();
        let mut tick = from_tick;
        for _ in 0..100_000 {
            tick += 1;
            let sp = core.tick(RobotTime::ZERO.saturating_add(DT * tick as u32));
            out.push(sp);
            let st: MotionState = core.state();
            if st.halted || st.in_position() {
                break;
            }
        }
        out
    }

    fn pos(sp: &Setpoint) -> Vector3<f64> {
        sp.tcp.translation.vector
    }

    #[test]
    fn a_constant_offset_moves_the_whole_corrected_path() {
        let mut core = core_at_seam_start();
        let t0 = core.state().setpoint.tick;
        let start = pos(&core.state().setpoint);
        let rec = install(&mut core, Constant::new(&[2], [0.0, 3.0, -2.0]));
        core.enqueue(move_l(
            2,
            target(1400.0, 20.0, 500.0),
            100.0,
            ZoneData::FINE,
        ))
        .unwrap();
        let sps = run(&mut core, t0);
        assert!(!core.state().halted);
        let want = Vector3::new(0.0, 3.0, -2.0);
        for sp in &sps {
            let p = pos(sp);
            // On the programmed line moved by the offset.
            assert!((p.y - (20.0 + 3.0)).abs() < 1e-6, "{p:?}");
            assert!((p.z - (500.0 - 2.0)).abs() < 1e-6, "{p:?}");
            // The joints really put the TCP there.
            let fk = Robot::default().tcp_world(&sp.joints, &ToolData::tool0());
            assert!((fk.translation.vector - p).norm() < 1e-6);
        }
        let end = pos(sps.last().unwrap());
        assert!((end - (Vector3::new(1400.0, 20.0, 500.0) + want)).norm() < 1e-6);
        let c = rec.lock().unwrap();
        let first = c.points.first().unwrap();
        assert!(first.first && first.s > 0.0);
        assert!((first.s - (pos(&sps[0]) - want - start).norm()).abs() < 1e-9);
        let last = c.points.last().unwrap();
        assert!(last.stop_point && (last.s - 400.0).abs() < 1e-6);
        assert!(c.points.iter().skip(1).all(|p| !p.first));
        assert!(c.left.is_empty());
        // The tangent is the planned step.
        assert!(c.points[10].step.x > 0.0 && c.points[10].step.y.abs() < 1e-6);
    }

    #[test]
    fn uncorrected_moves_are_left_alone() {
        let mut core = core_at_seam_start();
        let t0 = core.state().setpoint.tick;
        let rec = install(&mut core, Constant::new(&[99], [0.0, 3.0, 0.0]));
        core.enqueue(move_l(
            2,
            target(1100.0, 20.0, 500.0),
            100.0,
            ZoneData::FINE,
        ))
        .unwrap();
        let sps = run(&mut core, t0);
        let worst = sps
            .iter()
            .map(|sp| (pos(sp).y - 20.0).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-6, "{worst}");
        assert!(rec.lock().unwrap().points.is_empty());
    }

    #[test]
    fn a_sequence_that_does_not_end_in_a_stop_point_is_refused() {
        let mut core = core_at_seam_start();
        let t0 = core.state().setpoint.tick;
        let rec = install(&mut core, Constant::new(&[2], [0.0, 1.0, 0.0]));
        core.enqueue(move_l(2, target(1100.0, 20.0, 500.0), 100.0, z5()))
            .unwrap();
        core.enqueue(move_l(
            3,
            target(1200.0, 20.0, 500.0),
            100.0,
            ZoneData::FINE,
        ))
        .unwrap();
        run(&mut core, t0);
        assert!(core.state().halted);
        let e = std::iter::from_fn(|| core.take_event())
            .find(|e| e.severity == Severity::Error)
            .unwrap();
        assert_eq!(e.instr.map(|i| i.id), Some(3));
        assert_eq!(e.error.rapid_error_name(), Some("ERR_TEST"));
        assert_eq!(
            e.to_string(),
            "90999 test stop: not ended in a fine point (MoveL #3)"
        );
        assert_eq!(rec.lock().unwrap().left, [3]);
    }

    #[test]
    fn a_corrected_stop_point_ends_the_sequence() {
        let mut core = core_at_seam_start();
        let t0 = core.state().setpoint.tick;
        let rec = install(&mut core, Constant::new(&[2, 4], [0.0, 0.0, 1.0]));
        core.enqueue(move_l(
            2,
            target(1100.0, 20.0, 500.0),
            100.0,
            ZoneData::FINE,
        ))
        .unwrap();
        core.enqueue(move_l(
            3,
            target(1100.0, 20.0, 550.0),
            100.0,
            ZoneData::FINE,
        ))
        .unwrap();
        core.enqueue(move_l(
            4,
            target(1150.0, 20.0, 550.0),
            100.0,
            ZoneData::FINE,
        ))
        .unwrap();
        let mut tick = t0;
        for _ in 0..3 {
            let sps = run(&mut core, tick);
            tick = sps.last().unwrap().tick;
        }
        assert!(!core.state().halted);
        let c = rec.lock().unwrap();
        assert!(c.left.is_empty());
        // Two sequences, each starting at s = 0 from its fine point.
        let starts: Vec<_> = c
            .points
            .iter()
            .filter(|p| p.first)
            .map(|p| p.instr.id)
            .collect();
        assert_eq!(starts, [2, 4]);
        assert!((c.points.last().unwrap().s - 50.0).abs() < 1e-6);
    }

    #[test]
    fn an_error_from_the_correction_stops_the_robot() {
        let mut core = core_at_seam_start();
        let t0 = core.state().setpoint.tick;
        let mut c = Constant::new(&[2], [0.0, 1.0, 0.0]);
        c.fail_at = Some(50.0);
        let _rec = install(&mut core, c);
        core.enqueue(move_l(
            2,
            target(1400.0, 20.0, 500.0),
            100.0,
            ZoneData::FINE,
        ))
        .unwrap();
        let sps = run(&mut core, t0);
        assert!(core.state().halted);
        let x = pos(sps.last().unwrap()).x;
        assert!((1049.0..1052.0).contains(&x), "{x}");
        let e = std::iter::from_fn(|| core.take_event()).last().unwrap();
        assert_eq!(e.error.to_string(), "the sensor stopped answering");
    }

    #[test]
    fn an_unreachable_corrected_pose_stops_the_robot() {
        let mut core = core_at_seam_start();
        let t0 = core.state().setpoint.tick;
        let _rec = install(&mut core, Constant::new(&[2], [0.0, 0.0, 5000.0]));
        core.enqueue(move_l(
            2,
            target(1100.0, 20.0, 500.0),
            100.0,
            ZoneData::FINE,
        ))
        .unwrap();
        run(&mut core, t0);
        assert!(core.state().halted);
        let e = std::iter::from_fn(|| core.take_event()).last().unwrap();
        assert!(matches!(e.error, MotionError::Kinematics { .. }), "{e}");
        // Removing the correction gives it back.
        assert!(core.set_path_correction(None).is_some());
        assert!(core.set_path_correction(None).is_none());
    }
}
