//! Unit tests of the sans-IO controller session, including hostile input.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

use super::*;
use crate::egm::proto::{
    EgmCartesian, EgmHeader, EgmJoints, EgmPathCorr, EgmPlanned, EgmPose, EgmQuaternion, EgmSensor,
    EgmSensorPathCorr, egm_header::MessageType,
};
use proptest::prelude::*;

const MS: Duration = Duration::from_millis(1);

/// Robot time `d` after the start.
fn at(d: Duration) -> RobotTime {
    RobotTime::from_duration(d)
}

fn remote() -> SocketAddr {
    "127.0.0.1:6510".parse().unwrap()
}

fn session(mode: EgmMode) -> EgmSession {
    EgmSession::new(EgmConfig::new(mode, remote())).unwrap()
}

fn fb() -> RobotFeedback {
    RobotFeedback::standing([0.0, 0.0, 0.0, 0.0, 30.0, 0.0], Pose::IDENTITY)
}

fn joint_reply(j1: f64) -> Vec<u8> {
    EgmSensor {
        header: Some(EgmHeader {
            seqno: Some(1),
            tm: None,
            mtype: Some(MessageType::MsgtypeCorrection as i32),
        }),
        planned: Some(EgmPlanned {
            joints: Some(EgmJoints {
                joints: vec![j1, 0.0, 0.0, 0.0, 30.0, 0.0],
            }),
            ..EgmPlanned::default()
        }),
        ..EgmSensor::default()
    }
    .encode_to_vec()
}

fn j1(r: &SensorReference) -> f64 {
    match r.target {
        Target::Joint(j) => j.joints[0],
        _ => panic!("not a joint target"),
    }
}

fn events(s: &mut EgmSession) -> Vec<EgmEvent> {
    std::iter::from_fn(|| s.poll_event()).collect()
}

#[test]
fn seqno_and_tm_follow_the_cycle_and_restart_at_zero() {
    let mut s = session(EgmMode::Joint);
    assert_eq!(s.state(), SessionState::Idle);
    assert!(s.poll_transmit(at(Duration::ZERO), &fb()).is_none(), "idle");
    let t0 = Duration::from_millis(1000);
    s.start(at(t0));
    let mut seen = Vec::new();
    for step in 0..10u32 {
        let now = t0 + MS * 4 * step;
        let bytes = s.poll_transmit(at(now), &fb()).expect("due every 4 ms");
        assert!(bytes.len() <= MAX_DATAGRAM_LEN);
        let msg = EgmRobot::decode(bytes.as_slice()).unwrap();
        let h = msg.header.unwrap();
        seen.push((h.seqno.unwrap(), h.tm.unwrap()));
        assert_eq!(h.mtype, Some(MessageType::MsgtypeData as i32));
        assert!(
            s.poll_transmit(at(now + MS), &fb()).is_none(),
            "not due again within the cycle"
        );
    }
    let expected: Vec<(u32, u32)> = (0..10).map(|i| (i, 1000 + 4 * i)).collect();
    assert_eq!(seen, expected);
    assert_eq!(s.stats().sent, 10);
    s.stop();
    assert!(s.poll_transmit(at(t0 + MS * 100), &fb()).is_none());
    s.start(at(t0 + MS * 200));
    let msg = EgmRobot::decode(
        s.poll_transmit(at(t0 + MS * 200), &fb())
            .unwrap()
            .as_slice(),
    )
    .unwrap();
    assert_eq!(msg.header.unwrap().seqno, Some(0), "new session, seqno 0");
}

#[test]
fn slightly_early_ticks_still_send_and_late_ones_are_counted() {
    let mut s = session(EgmMode::Joint);
    s.start(at(Duration::ZERO));
    assert!(s.poll_transmit(at(Duration::ZERO), &fb()).is_some());
    // 100 µs early: still this cycle's datagram.
    assert!(
        s.poll_transmit(at(Duration::from_micros(3900)), &fb())
            .is_some()
    );
    // Then 3 cycles late: one datagram, 2+ cycles counted as skipped, re-phased.
    assert!(s.poll_transmit(at(MS * 20), &fb()).is_some());
    assert!(s.stats().late_cycles >= 2, "{:?}", s.stats().late_cycles);
    assert_eq!(s.poll_timeout(), Some(at(MS * 24)));
}

#[test]
fn newest_reference_wins_and_stays_in_force() {
    let mut s = session(EgmMode::Joint);
    s.start(at(Duration::ZERO));
    s.poll_transmit(at(Duration::ZERO), &fb()).unwrap();
    let src = remote();
    assert_eq!(
        s.handle_datagram(at(MS), src, &joint_reply(1.0)),
        Outcome::Accepted
    );
    assert_eq!(
        s.handle_datagram(at(MS * 2), src, &joint_reply(2.0)),
        Outcome::Accepted
    );
    let r = s.poll_reference().unwrap();
    assert_eq!(j1(&r), 2.0);
    assert_eq!(r.received_at, at(MS * 2));
    assert_eq!(s.stats().superseded, 1);
    assert!(s.poll_reference().is_none(), "nothing new");
    assert_eq!(j1(s.current_reference().unwrap()), 2.0, "kept in force");
    assert_eq!(s.stats().turnaround.count(), 2);
    assert_eq!(s.stats().turnaround.max(), Some(MS * 2));
}

#[test]
fn one_per_cycle_keeps_order_and_bounds_the_queue() {
    let mut cfg = EgmConfig::new(EgmMode::Joint, remote());
    cfg.queue = QueuePolicy::OnePerCycle { capacity: 2 };
    let mut s = EgmSession::new(cfg).unwrap();
    s.start(at(Duration::ZERO));
    let src = remote();
    for v in [1.0, 2.0, 3.0] {
        s.handle_datagram(at(MS), src, &joint_reply(v));
    }
    assert_eq!(s.stats().queue_overflow, 1);
    assert_eq!(j1(&s.poll_reference().unwrap()), 2.0);
    assert_eq!(j1(&s.poll_reference().unwrap()), 3.0);
    assert!(s.poll_reference().is_none());
    let ev = events(&mut s);
    assert_eq!(ev.len(), 1);
    assert_eq!(ev[0].number, 90108);
}

#[test]
fn only_the_remote_address_and_port_may_steer_and_every_drop_is_counted() {
    let mut s = session(EgmMode::Joint);
    let tally = Arc::new(DropTally::default());
    s.share_drops(Arc::clone(&tally));
    s.start(at(Duration::ZERO));
    let intruder: SocketAddr = "127.0.0.2:6510".parse().unwrap();
    for _ in 0..5 {
        assert_eq!(
            s.handle_datagram(at(MS), intruder, &joint_reply(9.0)),
            Outcome::Dropped(DropReason::WrongSource)
        );
    }
    // The sensor's host at another port, before and after the sensor answered: dropped.
    let same_host: SocketAddr = "127.0.0.1:1234".parse().unwrap();
    assert_eq!(
        s.handle_datagram(at(MS), same_host, &joint_reply(1.0)),
        Outcome::Dropped(DropReason::WrongSource)
    );
    assert!(
        s.poll_reference().is_none(),
        "nothing steers but the sensor"
    );
    assert_eq!(
        s.handle_datagram(at(MS), remote(), &joint_reply(3.0)),
        Outcome::Accepted
    );
    // IPv4-mapped IPv6 form of the remote address and port: the sensor itself.
    let mapped: SocketAddr = "[::ffff:127.0.0.1]:6510".parse().unwrap();
    assert_eq!(
        s.handle_datagram(at(MS), mapped, &joint_reply(4.0)),
        Outcome::Accepted
    );
    assert_eq!(
        s.handle_datagram(at(MS), same_host, &joint_reply(8.0)),
        Outcome::Dropped(DropReason::WrongSource)
    );
    assert_eq!(j1(&s.poll_reference().unwrap()), 4.0);
    assert_eq!(s.stats().wrong_source, 7);
    let ev = events(&mut s);
    assert_eq!(ev.len(), 1, "{ev:?}");
    assert_eq!(ev[0].number, 90101);
    assert!(ev[0].detail.contains("127.0.0.2"), "{}", ev[0].detail);
    assert!(ev[0].detail.contains("127.0.0.1:6510"), "{}", ev[0].detail);
    // Every other cause is counted too, here and in the shared tally.
    let mut truncated = joint_reply(5.0);
    truncated.truncate(truncated.len() - 3);
    assert_eq!(
        s.handle_datagram(at(MS), remote(), &truncated),
        Outcome::Dropped(DropReason::Truncated)
    );
    assert_eq!(
        s.handle_datagram(at(MS), remote(), &[0xff; 3]),
        Outcome::Dropped(DropReason::Malformed),
        "random bytes are not a cut message"
    );
    assert_eq!(
        s.handle_datagram(at(MS), remote(), &[0x0a; 4000]),
        Outcome::Dropped(DropReason::Oversized)
    );
    assert_eq!(
        s.handle_datagram(at(MS), remote(), &joint_reply(f64::NAN)),
        Outcome::Dropped(DropReason::NotFinite)
    );
    assert_eq!(
        s.handle_datagram(at(MS), remote(), &joint_reply(1.0e6)),
        Outcome::Dropped(DropReason::OutOfRange)
    );
    let counts = tally.snapshot();
    assert_eq!(counts.get(DropReason::WrongSource), 7);
    for reason in [
        DropReason::Truncated,
        DropReason::Malformed,
        DropReason::Oversized,
        DropReason::NotFinite,
        DropReason::OutOfRange,
    ] {
        assert_eq!(counts.get(reason), 1, "{reason:?}: {counts}");
    }
    assert_eq!(counts.dropped(), s.stats().dropped());
    // Nothing arrives outside a session without being counted.
    s.stop();
    assert_eq!(
        s.handle_datagram(at(MS * 5), remote(), &joint_reply(1.0)),
        Outcome::Ignored
    );
    assert_eq!(tally.snapshot().get(DropReason::Late), 1);
    // A new session reports a foreign sender again.
    let _ = events(&mut s);
    s.start(at(MS * 10));
    s.handle_datagram(at(MS * 11), intruder, &joint_reply(9.0));
    assert_eq!(events(&mut s).len(), 1);

    let mut cfg = EgmConfig::new(EgmMode::Joint, remote());
    cfg.source_filter = SourceFilter::Any;
    let mut any = EgmSession::new(cfg).unwrap();
    any.start(at(Duration::ZERO));
    assert_eq!(
        any.handle_datagram(at(MS), intruder, &joint_reply(9.0)),
        Outcome::Accepted
    );
}

#[test]
fn hostile_datagrams_are_dropped_with_throttled_events() {
    let mut s = session(EgmMode::Joint);
    s.start(at(Duration::ZERO));
    let src = remote();
    let good = joint_reply(1.0);
    // Truncated at every length: never accepted as something else silently, never a panic.
    for len in 0..good.len() {
        let out = s.handle_datagram(at(MS), src, &good[..len]);
        assert_ne!(out, Outcome::Ignored);
    }
    let oversized = vec![0u8; 1025];
    assert_eq!(
        s.handle_datagram(at(MS), src, &oversized),
        Outcome::Dropped(DropReason::Oversized)
    );
    assert_eq!(
        s.handle_datagram(at(MS), src, &[0xff; 16]),
        Outcome::Dropped(DropReason::Malformed)
    );
    let nan = EgmSensor {
        planned: Some(EgmPlanned {
            joints: Some(EgmJoints {
                joints: vec![f64::NAN; 6],
            }),
            ..EgmPlanned::default()
        }),
        ..EgmSensor::default()
    }
    .encode_to_vec();
    assert_eq!(
        s.handle_datagram(at(MS), src, &nan),
        Outcome::Dropped(DropReason::NotFinite)
    );
    let path_corr = EgmSensorPathCorr {
        header: Some(EgmHeader {
            seqno: Some(0),
            tm: None,
            mtype: Some(MessageType::MsgtypePathCorrection as i32),
        }),
        path_corr: Some(EgmPathCorr {
            pos: EgmCartesian {
                x: 0.0,
                y: 1.0,
                z: 2.0,
            },
            age: 1,
        }),
    }
    .encode_to_vec();
    assert!(matches!(
        s.handle_datagram(at(MS), src, &path_corr),
        Outcome::Dropped(_)
    ));
    let st = s.stats();
    assert_eq!(st.accepted, 0);
    assert_eq!(st.oversized, 1);
    assert!(st.malformed >= 1);
    assert_eq!(st.not_finite, 1);
    assert_eq!(st.dropped(), st.received);
    // Throttled: at most one event per kind within the repeat interval.
    let ev = events(&mut s);
    let mut numbers: Vec<u32> = ev.iter().map(|e| e.number).collect();
    let n = numbers.len();
    numbers.sort_unstable();
    numbers.dedup();
    assert_eq!(numbers.len(), n, "one per kind: {ev:?}");
    // After the interval the next one carries the count of suppressed ones.
    s.handle_datagram(at(MS), src, &[0xff; 16]);
    s.handle_datagram(at(Duration::from_secs(2)), src, &[0xff; 16]);
    let ev = events(&mut s);
    assert_eq!(ev.len(), 1);
    assert!(
        ev[0].detail.contains("more since the last report"),
        "{}",
        ev[0].detail
    );
    // None of it counted as sensor data.
    s.handle_timeout(at(Duration::from_secs(2)));
    assert!(s.comm_timed_out());
}

#[test]
fn wrong_mode_messages_are_rejected_not_misread() {
    // A joint-mode sensor talking to a pose-mode session.
    let mut s = session(EgmMode::Pose);
    s.start(at(Duration::ZERO));
    assert_eq!(
        s.handle_datagram(at(MS), remote(), &joint_reply(1.0)),
        Outcome::Dropped(DropReason::Incomplete)
    );
    // A guidance message in a path-correction session.
    let mut s = session(EgmMode::PathCorr);
    s.start(at(Duration::ZERO));
    assert!(matches!(
        s.handle_datagram(at(MS), remote(), &joint_reply(1.0)),
        Outcome::Dropped(DropReason::Malformed | DropReason::WrongType | DropReason::Incomplete)
    ));
    let ev = events(&mut s);
    assert_eq!(ev.len(), 1);
}

#[test]
fn comm_timeout_raises_41822_once_and_valid_data_restarts_the_timer() {
    let mut s = session(EgmMode::Joint);
    let t0 = Duration::from_secs(5);
    s.start(at(t0));
    assert_eq!(s.poll_timeout(), Some(at(t0)), "first transmit due at once");
    s.poll_transmit(at(t0), &fb()).unwrap();
    assert_eq!(s.poll_timeout(), Some(at(t0 + MS * 4)));
    s.handle_datagram(at(t0 + MS * 600), remote(), &joint_reply(0.0));
    s.handle_timeout(at(t0 + MS * 1500));
    assert!(!s.comm_timed_out(), "timer restarted at 600 ms");
    s.handle_timeout(at(t0 + MS * 1600));
    assert!(s.comm_timed_out());
    s.handle_timeout(at(t0 + MS * 5000));
    let ev = events(&mut s);
    assert_eq!(ev.len(), 1);
    assert_eq!(ev[0].number, 41822);
    assert_eq!(ev[0].title, "No data from the UdpUc device");
    // Still sending; the controller decides what to do.
    assert!(s.poll_transmit(at(t0 + MS * 5000), &fb()).is_some());
    // A new session clears it.
    s.start(at(t0 + MS * 6000));
    assert!(!s.comm_timed_out());
}

#[test]
fn streams_without_comm_timeout_never_time_out() {
    let mut cfg = EgmConfig::new(EgmMode::Joint, remote());
    cfg.comm_timeout = None;
    let mut s = EgmSession::new(cfg).unwrap();
    s.start(at(Duration::ZERO));
    s.handle_timeout(at(Duration::from_secs(3600)));
    assert!(!s.comm_timed_out());
    assert_eq!(s.poll_timeout(), Some(at(Duration::ZERO)));
}

#[test]
fn non_finite_feedback_is_not_sent() {
    let mut s = session(EgmMode::Joint);
    s.start(at(Duration::ZERO));
    let mut bad = fb();
    bad.joints[2] = f64::NAN;
    assert!(s.poll_transmit(at(Duration::ZERO), &bad).is_none());
    assert_eq!(s.stats().unsendable, 1);
    assert_eq!(events(&mut s)[0].number, 90107);
    assert_eq!(s.next_seqno(), 0, "seqno only counts sent datagrams");
    assert!(s.poll_transmit(at(MS * 4), &fb()).is_some());
}

#[test]
fn partial_pose_falls_back_to_the_planned_pose_then_to_the_last_reference() {
    let mut s = session(EgmMode::Pose);
    s.start(at(Duration::ZERO));
    let mut f = fb();
    f.planned_pose = Pose {
        pos: [500.0, 0.0, 600.0],
        orient: [0.0, 0.0, 1.0, 0.0],
    };
    s.poll_transmit(at(Duration::ZERO), &f).unwrap();
    let only_orient = |q: [f64; 4]| {
        EgmSensor {
            planned: Some(EgmPlanned {
                cartesian: Some(EgmPose {
                    pos: None,
                    orient: Some(EgmQuaternion {
                        u0: q[0],
                        u1: q[1],
                        u2: q[2],
                        u3: q[3],
                    }),
                    euler: None,
                }),
                ..EgmPlanned::default()
            }),
            ..EgmSensor::default()
        }
        .encode_to_vec()
    };
    s.handle_datagram(at(MS), remote(), &only_orient([1.0, 0.0, 0.0, 0.0]));
    let Target::Pose(p) = s.poll_reference().unwrap().target else {
        panic!()
    };
    assert_eq!(p.pose.pos, [500.0, 0.0, 600.0], "from the planned pose");
    let only_pos = EgmSensor {
        planned: Some(EgmPlanned {
            cartesian: Some(EgmPose {
                pos: Some(EgmCartesian {
                    x: 1.0,
                    y: 2.0,
                    z: 3.0,
                }),
                orient: None,
                euler: None,
            }),
            ..EgmPlanned::default()
        }),
        ..EgmSensor::default()
    }
    .encode_to_vec();
    s.handle_datagram(at(MS * 2), remote(), &only_pos);
    let Target::Pose(p) = s.poll_reference().unwrap().target else {
        panic!()
    };
    assert_eq!(
        p.pose.orient,
        [1.0, 0.0, 0.0, 0.0],
        "from the last reference"
    );
}

#[test]
fn datagrams_outside_a_session_are_ignored() {
    let mut s = session(EgmMode::Joint);
    assert_eq!(
        s.handle_datagram(at(MS), remote(), &joint_reply(1.0)),
        Outcome::Ignored
    );
    assert_eq!(s.poll_timeout(), None);
    assert_eq!(s.stats().ignored_idle, 1);
    assert!(s.poll_reference().is_none());
}

#[test]
fn bad_configurations_are_refused() {
    let mut cfg = EgmConfig::new(EgmMode::Joint, remote());
    cfg.sample_period = Duration::ZERO;
    assert_eq!(
        EgmSession::new(cfg).unwrap_err(),
        ConfigError::ZeroSamplePeriod
    );
    let mut cfg = EgmConfig::new(EgmMode::Joint, remote());
    cfg.comm_timeout = Some(Duration::ZERO);
    assert_eq!(
        EgmSession::new(cfg).unwrap_err(),
        ConfigError::ZeroCommTimeout
    );
    let mut cfg = EgmConfig::new(EgmMode::Joint, remote());
    cfg.queue = QueuePolicy::OnePerCycle { capacity: 0 };
    assert!(matches!(
        EgmSession::new(cfg).unwrap_err(),
        ConfigError::QueueCapacity { got: 0, .. }
    ));
    let mut cfg = EgmConfig::new(EgmMode::Joint, remote());
    cfg.max_datagram_len = 0;
    assert_eq!(
        EgmSession::new(cfg).unwrap_err(),
        ConfigError::ZeroDatagramLimit
    );
}

#[test]
fn event_queue_is_bounded() {
    let mut cfg = EgmConfig::new(EgmMode::Joint, remote());
    cfg.event_repeat = Duration::ZERO;
    let mut s = EgmSession::new(cfg).unwrap();
    s.start(at(Duration::ZERO));
    for i in 0..100u32 {
        s.handle_datagram(at(MS * i), remote(), &[0xff]);
    }
    assert_eq!(events(&mut s).len(), EVENT_QUEUE);
    assert_eq!(s.stats().events_dropped, 100 - EVENT_QUEUE as u64);
}

proptest! {
    #[test]
    fn random_bytes_never_panic(
        bytes in proptest::collection::vec(any::<u8>(), 0..1100),
        mode in prop_oneof![Just(EgmMode::Joint), Just(EgmMode::Pose), Just(EgmMode::PathCorr)],
        port in any::<u16>(),
    ) {
        let mut s = session(mode);
        s.start(at(Duration::ZERO));
        let src = SocketAddr::from(([127, 0, 0, 1], port));
        let out = s.handle_datagram(at(MS), src, &bytes);
        if out == Outcome::Accepted {
            // Whatever was accepted is finite.
            let r = s.poll_reference().unwrap();
            let finite = match r.target {
                Target::Joint(j) => j.joints.iter().chain(&j.speed).all(|v| v.is_finite()),
                Target::Pose(p) => p.pose.pos.iter().chain(&p.pose.orient).chain(&p.speed).all(|v| v.is_finite()),
                Target::PathCorr(c) => c.pos.iter().all(|v| v.is_finite()),
            };
            prop_assert!(finite);
        }
        prop_assert!(s.poll_transmit(at(MS * 4), &fb()).is_some());
    }

    #[test]
    fn mutated_valid_messages_never_panic(
        flips in proptest::collection::vec((0usize..64, any::<u8>()), 1..6),
        cut in 0usize..64,
    ) {
        let mut bytes = joint_reply(12.5);
        for (i, b) in flips {
            if let Some(slot) = bytes.get_mut(i % 64) {
                *slot = b;
            }
        }
        bytes.truncate(cut.max(1) + bytes.len() / 2);
        let mut s = session(EgmMode::Joint);
        s.start(at(Duration::ZERO));
        let _ = s.handle_datagram(at(MS), remote(), &bytes);
        prop_assert_eq!(s.stats().received, 1);
    }
}
