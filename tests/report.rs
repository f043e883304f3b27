//! The report's feed from the controller: trace columns aligned with their rows through the real
//! controller in both clock modes, and EGM and path-correction plots rendered from synthetic
//! runs (set `RAPIDVC_PLOT_DIR` to keep the pictures).

use std::path::PathBuf;

/// A fresh directory for this test's files.
fn out_dir(name: &str) -> (PathBuf, bool) {
    if let Some(dir) = std::env::var_os("RAPIDVC_PLOT_DIR") {
        let dir = PathBuf::from(dir);
        std::fs::create_dir_all(&dir).unwrap();
        return (dir, true);
    }
    let dir = std::env::temp_dir().join(format!("rapidvc-report-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    (dir, false)
}

mod pipeline {
    use std::sync::Arc;
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::time::Duration;

    use rapidvc::controller::{
        ClockMode, Condition, ControllerConfig, ControllerHandle, CycleHook, RealtimeConfig,
    };
    use rapidvc::motion::{Executor, Setpoint};
    use rapidvc::output::{EgmAxes, EgmTraceState, Feed, TRACE_HEADER, TraceColumns, TraceWriter};
    use rapidvc::robot::command::{
        EXTAX_NONE, JointTarget, MotionCommand, MoveAbsJ, MoveArgs, SpeedData, ZoneData,
    };
    use rapidvc::robot::{Robot, ToolData};

    const START: [f64; 6] = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];

    /// Pushes, every third cycle, an EGM sample whose reference is the cycle's joints and a
    /// path-correction sample whose arc length is the cycle's time in ms; the state changes on
    /// the 10th and 60th cycle.
    struct Pusher {
        feed: Feed,
        pushed: Arc<AtomicUsize>,
    }

    impl CycleHook for Pusher {
        fn after_tick(&mut self, sp: &Setpoint, _exec: &mut Executor) {
            if sp.tick == 10 {
                self.feed.push_egm_state(sp.time, EgmTraceState::Connected);
            }
            if sp.tick == 60 {
                self.feed
                    .push_egm_state(sp.time, EgmTraceState::Disconnected);
            }
            if !sp.tick.is_multiple_of(3) {
                return;
            }
            let state = if (10..60).contains(&sp.tick) {
                EgmTraceState::Running
            } else {
                EgmTraceState::Disconnected
            };
            self.feed.push_egm_sample(
                sp.time,
                EgmAxes::Joint,
                Some(sp.joints),
                sp.joints,
                state,
                sp.tick.is_multiple_of(2),
            );
            let ms = sp.time.as_secs_f64() * 1000.0;
            self.feed
                .push_pathcorr_sample(sp.time, ms, [0.0, 0.0], [1.0, -1.0], None);
            self.pushed.fetch_add(1, Ordering::Relaxed);
        }
    }

    fn abs_j(id: u64, q: [f64; 6]) -> MotionCommand {
        MotionCommand::MoveAbsJ(MoveAbsJ {
            args: MoveArgs::new(id, SpeedData::v(1000.0), ZoneData::FINE, ToolData::tool0()),
            target: JointTarget {
                robax: q,
                extax: EXTAX_NONE,
            },
            no_eoffs: false,
        })
    }

    fn run(clock: ClockMode, name: &str) {
        let virtual_time = clock == ClockMode::Virtual;
        let (dir, keep) = super::out_dir(name);
        let path = dir.join(format!("{name}.csv"));
        let mut feed = Feed::new();
        let trace = TraceWriter::create_with_feed(&path, None, TraceColumns::ALL, feed.subscribe())
            .unwrap();
        let pushed = Arc::new(AtomicUsize::new(0));
        let hook = Pusher {
            feed,
            pushed: Arc::clone(&pushed),
        };
        let mut config = ControllerConfig::new(Robot::default(), START);
        config.clock = clock;
        config.max_wait = Duration::from_secs(30);
        let mut c =
            ControllerHandle::start_with_hook(config, vec![Box::new(trace)], Some(Box::new(hook)))
                .unwrap();
        c.submit(abs_j(1, [20.0, -10.0, 15.0, 30.0, 20.0, 45.0]))
            .unwrap();
        c.wait_until(Condition::Done(1)).unwrap();
        let summary = c.finish().unwrap();

        let text = std::fs::read_to_string(&path).unwrap();
        let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split(',').collect()).collect();
        let header = rows.first().unwrap();
        assert_eq!(header.get(..TRACE_HEADER.len()).unwrap(), TRACE_HEADER);
        assert_eq!(header.len(), TRACE_HEADER.len() + 11);
        let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
        let (state, limited, s) = (col("egm_state"), col("egm_limited"), col("path_s"));
        let mut filled = 0;
        for row in rows.iter().skip(1) {
            assert_eq!(row.len(), header.len());
            let time_ms = row.first().unwrap().parse::<f64>().unwrap() * 1000.0;
            let tick = (time_ms / 4.0).round() as u64;
            if row.get(limited).unwrap().is_empty() {
                assert!(row.get(s).unwrap().is_empty());
                continue;
            }
            filled += 1;
            // The samples of this row's own cycle, not another's (the trace's time is truncated
            // to whole µs, path_s rounded to 0.1 µs: up to 1.05 µs apart for the same cycle,
            // while cycles are 4 ms apart).
            for k in 0..6 {
                assert_eq!(row.get(1 + k), row.get(col(&format!("egm_ref_{}", k + 1))));
            }
            let path_s = row.get(s).unwrap().parse::<f64>().unwrap();
            assert!((path_s - time_ms).abs() < 1.1e-3, "{row:?}");
            if !virtual_time {
                // Real time starts at an arbitrary phase: no tick numbers from the time.
                continue;
            }
            assert!(tick.is_multiple_of(3), "{row:?}");
            assert_eq!(
                *row.get(limited).unwrap(),
                if tick.is_multiple_of(2) { "1" } else { "0" }
            );
            let want = match tick {
                0..10 => "DISCONNECTED",
                10..60 => "RUNNING",
                _ => "DISCONNECTED",
            };
            assert_eq!(*row.get(state).unwrap(), want, "{row:?}");
        }
        if summary.dropped_records == 0 {
            assert_eq!(filled, pushed.load(Ordering::Relaxed));
        }
        assert!(filled > 30);
        // CONNECTED shows on the rows between the state push and the next sample.
        let connected = rows
            .iter()
            .filter(|r| r.get(state) == Some(&"CONNECTED"))
            .count();
        if summary.dropped_records == 0 {
            assert_eq!(connected, 2, "ticks 10 and 11");
        }
        if !keep {
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }

    #[test]
    fn feed_columns_line_up_with_their_rows_in_virtual_time() {
        run(ClockMode::Virtual, "virtual");
    }

    #[test]
    fn feed_columns_line_up_with_their_rows_in_real_time() {
        run(ClockMode::RealTime(RealtimeConfig::Ignore), "realtime");
    }
}

mod plots {
    use rapidvc::controller::TickSink;
    use rapidvc::motion::{InstrRef, RobotTime, Setpoint};
    use rapidvc::output::{EgmAxes, EgmTraceState, Feed, PlotRecorder};
    use rapidvc::robot::Robot;

    const DT_NS: u64 = 4_000_000;

    fn setpoint(tick: u64, joints: [f64; 6], name: &'static str, id: u64) -> Setpoint {
        let robot = Robot::default();
        Setpoint {
            time: RobotTime::from_nanos(tick * DT_NS),
            tick,
            joints,
            tcp: robot.fk(&joints),
            speed: 0.0,
            standstill: false,
            instr: Some(InstrRef {
                id,
                name,
                source: None,
            }),
        }
    }

    /// A joint-mode EGM run: a MoveAbsJ, EGMSetupUC (CONNECTED), 3 s of EGMRunJoint with a
    /// step on J1 (limited by MaxSpeedDeviation) and sines on the other axes, the run ends
    /// (CONNECTED), EGMReset (DISCONNECTED).
    fn joint_run(rec: &mut PlotRecorder, feed: &Feed) {
        let start = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];
        let mut q = start;
        let max_speed = 20.0; // deg/s
        let dt = DT_NS as f64 * 1e-9;
        for tick in 0..1500u64 {
            let t = tick as f64 * dt;
            let (name, id) = match tick {
                0..250 => ("MoveAbsJ", 1),
                250..1000 => ("EGMRunJoint", 2),
                _ => ("MoveAbsJ", 3),
            };
            if tick < 250 {
                q[1] = 10.0 * t;
            } else if tick < 1000 {
                let te = t - 1.0;
                let reference = [
                    if te > 0.3 { 12.0 } else { 0.0 },
                    10.0 + 3.0 * (2.0 * te).sin(),
                    2.0 * (1.5 * te).sin(),
                    -5.0 * (te).sin(),
                    35.0 + 4.0 * (3.0 * te).sin(),
                    10.0 * (0.8 * te).sin(),
                ];
                let mut limited = false;
                for (k, (qk, r)) in q.iter_mut().zip(reference).enumerate() {
                    let mut v = 8.0 * (r - *qk);
                    if k == 0 && v.abs() > max_speed {
                        v = v.signum() * max_speed;
                        limited = true;
                    }
                    *qk += v * dt;
                }
                let time = RobotTime::from_nanos(tick * DT_NS);
                feed.push_egm_sample(
                    time,
                    EgmAxes::Joint,
                    (te > 0.05).then_some(reference),
                    q,
                    EgmTraceState::Running,
                    limited,
                );
            } else {
                for (qk, s) in q.iter_mut().zip(start) {
                    *qk += (s - *qk) * 0.01;
                }
            }
            let time = RobotTime::from_nanos(tick * DT_NS);
            if tick == 200 {
                feed.push_egm_state(time, EgmTraceState::Connected);
            }
            if tick == 1000 {
                feed.push_egm_state(time, EgmTraceState::Connected);
            }
            if tick == 1100 {
                feed.push_egm_state(time, EgmTraceState::Disconnected);
            }
            rec.record(&setpoint(tick, q, name, id));
        }
    }

    /// A pose-mode EGM run: the sensor moves the TCP 40 mm in a circle in the y/z plane.
    fn pose_run(rec: &mut PlotRecorder, feed: &Feed) {
        let q = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];
        let base = Robot::default().fk(&q).translation.vector;
        let mut fb = [base.x, base.y, base.z];
        let dt = DT_NS as f64 * 1e-9;
        feed.push_egm_state(RobotTime::ZERO, EgmTraceState::Connected);
        for tick in 0..1000u64 {
            let t = tick as f64 * dt;
            let r = [
                base.x,
                base.y + 40.0 * (2.0 * t).sin(),
                base.z + 40.0 * (1.0 - (2.0 * t).cos()),
            ];
            let mut limited = false;
            for (f, r) in fb.iter_mut().zip(r) {
                let mut v = 10.0 * (r - *f);
                if v.abs() > 100.0 {
                    v = v.signum() * 100.0;
                    limited = true;
                }
                *f += v * dt;
            }
            let time = RobotTime::from_nanos(tick * DT_NS);
            if tick >= 25 {
                feed.push_egm_sample(
                    time,
                    EgmAxes::Pose,
                    Some([r[0], r[1], r[2], 180.0, 0.0, 180.0]),
                    [fb[0], fb[1], fb[2], 180.0, 0.0, 180.0],
                    EgmTraceState::Running,
                    limited,
                );
            }
            rec.record(&setpoint(tick, q, "EGMRunPose", 1));
        }
    }

    /// The golden case: a 400 mm EGMMoveL at v10 over a seam at y = 3 mm,
    /// z = −2 mm that the sensor finds after 50 mm, with a ramp and a wave in y after 200 mm;
    /// measurements every 24 ms, the correction smoothed toward them.
    fn pathcorr_run(rec: &mut PlotRecorder, feed: &Feed) {
        let q = [0.0, 0.0, 0.0, 0.0, 35.0, 0.0];
        let dt = DT_NS as f64 * 1e-9;
        let mut applied = [0.0f64, 0.0];
        let mut target = [0.0f64, 0.0];
        let seam = |s: f64| -> [f64; 2] {
            if s < 50.0 {
                return [0.0, 0.0];
            }
            let y = 3.0 + if s > 200.0 { 0.01 * (s - 200.0) } else { 0.0 };
            let wave = if s > 250.0 {
                0.8 * ((s - 250.0) / 20.0).sin()
            } else {
                0.0
            };
            [y + wave, -2.0]
        };
        for tick in 0..10_000u64 {
            let s = 10.0 * tick as f64 * dt;
            let measured = tick.is_multiple_of(6).then(|| seam(s));
            if let Some(m) = measured {
                target = m;
            }
            for (a, t) in applied.iter_mut().zip(target) {
                let step = (t - *a).clamp(-2.0 * dt, 2.0 * dt);
                *a += step;
            }
            let time = RobotTime::from_nanos(tick * DT_NS);
            feed.push_pathcorr_sample(time, s, [0.0, 0.0], applied, measured);
            rec.record(&setpoint(tick, q, "EGMMoveL", 1));
        }
    }

    fn recorder(path: &std::path::Path, title: &str) -> (PlotRecorder, Feed) {
        let mut feed = Feed::new();
        let rec = PlotRecorder::new(path, title, None)
            .unwrap()
            .with_feed(feed.subscribe());
        (rec, feed)
    }

    #[test]
    fn egm_and_path_correction_plots() {
        let (dir, keep) = super::out_dir("plots");
        let mut svg_texts = Vec::new();
        for ext in ["png", "svg"] {
            let path = dir.join(format!("egm_joint.{ext}"));
            let (mut rec, feed) = recorder(&path, "EGMRunJoint — synthetic step and sines");
            joint_run(&mut rec, &feed);
            let states: Vec<(u64, EgmTraceState)> = rec
                .data()
                .egm_states
                .iter()
                .map(|(t, s)| ((t * 1000.0).round() as u64, *s))
                .collect();
            assert_eq!(
                states,
                [
                    (800, EgmTraceState::Connected),
                    (1000, EgmTraceState::Running),
                    (4000, EgmTraceState::Connected),
                    (4400, EgmTraceState::Disconnected)
                ]
            );
            rec.finish().unwrap();

            let path = dir.join(format!("egm_pose.{ext}"));
            let (mut rec, feed) = recorder(&path, "EGMRunPose — synthetic circle");
            pose_run(&mut rec, &feed);
            rec.finish().unwrap();

            let path = dir.join(format!("pathcorr.{ext}"));
            let (mut rec, feed) = recorder(&path, "EGMMoveL with path correction");
            pathcorr_run(&mut rec, &feed);
            assert_eq!(rec.data().pathcorr.len(), 10_000);
            assert!(rec.data().egm.is_empty());
            rec.finish().unwrap();
        }
        for name in ["egm_joint", "egm_pose", "pathcorr"] {
            let png = std::fs::read(dir.join(format!("{name}.png"))).unwrap();
            assert!(png.starts_with(b"\x89PNG"));
            svg_texts.push(std::fs::read_to_string(dir.join(format!("{name}.svg"))).unwrap());
        }
        let [joint, pose, pathcorr] = svg_texts.as_slice() else {
            unreachable!()
        };
        for text in [joint, pose] {
            assert!(text.contains("Joint angles"));
            assert!(text.contains("Tracking error (reference − feedback)"));
            assert!(text.contains("MaxSpeedDeviation limiting"));
            assert!(text.contains("reference") && text.contains("feedback"));
            assert!(!text.contains("Path correction"));
        }
        assert!(joint.contains("joint mode") && joint.contains("J6 (deg)"));
        assert!(joint.contains("RUNNING") && joint.contains("DISCONNECTED"));
        assert!(pose.contains("pose mode") && pose.contains("z (mm)"));
        assert!(pathcorr.contains("Path correction in the path frame"));
        assert!(pathcorr.contains("seam (sensor)") && pathcorr.contains("corrected path"));
        assert!(pathcorr.contains("path length s (mm)"));
        assert!(!pathcorr.contains("Tracking error"));
        if !keep {
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }
}
