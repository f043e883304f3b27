//! Unit tests of the EGM servo law.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic,
    clippy::needless_range_loop
)]

use super::*;
use proptest::prelude::*;

const START: Joints = [0.0, 10.0, 20.0, 0.0, 30.0, 0.0];

fn fast() -> ServoParams {
    ServoParams {
        max_speed_deviation: 1000.0,
        ramp_in_time: Duration::ZERO,
        ..ServoParams::default()
    }
}

fn run_until_done(servo: &mut EgmServo, input: &ServoInput, max_steps: usize) -> Vec<ServoOutput> {
    let mut out = Vec::new();
    for _ in 0..max_steps {
        let o = servo.step(input);
        out.push(o);
        if o.phase == ServoPhase::Done {
            break;
        }
    }
    out
}

fn target() -> Joints {
    let mut t = START;
    t[0] = 5.0;
    t[2] = 18.0;
    t
}

#[test]
fn converges_then_holds_after_cond_time() {
    let mut servo = EgmServo::new(fast(), START).unwrap();
    let input = ServoInput::position(target());
    let out = run_until_done(&mut servo, &input, 5000);
    let last = out.last().unwrap();
    assert_eq!(last.phase, ServoPhase::Done);
    assert_eq!(last.finished, Some(EndCause::Converged));
    for i in 0..6 {
        assert!(
            (last.commanded[i] - target()[i]).abs() < 0.5,
            "{i}: {last:?}"
        );
    }
    // Convergence first met, then held for exactly CondTime before the stop began.
    let first_met = out.iter().position(|o| o.convergence_met).unwrap();
    let stop = out
        .iter()
        .position(|o| o.phase != ServoPhase::Running)
        .unwrap();
    assert!(out[first_met..=stop].iter().all(|o| o.convergence_met));
    assert_eq!(stop - first_met + 1, 250, "1 s at 4 ms");
    // HOLD: stays at the end position.
    let end = out[stop].commanded;
    for o in &out[stop..] {
        for i in 0..6 {
            assert!((o.commanded[i] - end[i]).abs() < 0.01);
        }
    }
}

#[test]
fn first_order_tracking_with_time_constant_one_over_k() {
    let mut servo = EgmServo::new(fast(), START).unwrap();
    let input = ServoInput::position(target());
    // After 200 ms (= 1/k) about 63 % of the 5° step, minus filter and delay lag.
    let mut last = None;
    for _ in 0..50 {
        last = Some(servo.step(&input));
    }
    let moved = last.unwrap().commanded[0];
    assert!(moved > 0.5 * 5.0 && moved < 0.66 * 5.0, "{moved}");
}

#[test]
fn max_speed_deviation_scales_all_joints_together_and_reports_once() {
    let mut servo = EgmServo::new(
        ServoParams {
            ramp_in_time: Duration::ZERO,
            ..ServoParams::default()
        },
        START,
    )
    .unwrap();
    let input = ServoInput::position(target());
    let mut began = 0;
    for _ in 0..100 {
        let o = servo.step(&input);
        let peak = o.velocity.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(peak <= 1.0 + 1e-12, "{peak}");
        if o.speed_limited {
            // J1 wants 5°, J3 wants −2°: the ratio survives the scaling.
            assert!((o.velocity[0] / o.velocity[2] + 2.5).abs() < 1e-9);
            assert!(o.utilization > 100.0);
            assert!(o.limit_factor < 1.0);
        }
        began += usize::from(o.speed_limit_began);
    }
    assert_eq!(began, 1);
    let o = servo.step(&input);
    let ev = speed_limit_event(servo.params(), &o);
    assert_eq!(ev.number, 90110);
    assert!(
        ev.detail.contains("MaxSpeedDeviation is 1 deg/s"),
        "{}",
        ev.detail
    );
}

#[test]
fn max_pos_deviation_clamps_and_reports() {
    let params = ServoParams {
        max_pos_deviation: 2.0,
        ..fast()
    };
    let mut servo = EgmServo::new(params, START).unwrap();
    let input = ServoInput::position(target());
    let mut began = 0;
    let mut last = None;
    for _ in 0..500 {
        let o = servo.step(&input);
        began += usize::from(o.clamp_began);
        last = Some(o);
    }
    let o = last.unwrap();
    assert_eq!(began, 1);
    assert_eq!(o.commanded[0], 2.0);
    assert!((o.commanded[2] - 18.0).abs() < 1e-3, "J3 needs only 2°");
    assert_eq!(o.clamped_axes & 1, 1);
    let ev = pos_clamp_event(&params, &o);
    assert_eq!(ev.number, 90111);
    assert!(ev.detail.starts_with("J1"), "{}", ev.detail);
}

#[test]
fn ramp_in_scales_the_start() {
    let ramped = ServoParams {
        ramp_in_time: Duration::from_millis(400),
        ..fast()
    };
    let mut a = EgmServo::new(ramped, START).unwrap();
    let mut b = EgmServo::new(fast(), START).unwrap();
    let input = ServoInput::position(target());
    let va = a.step(&input).velocity[0];
    let vb = b.step(&input).velocity[0];
    assert!(
        (va - vb * 0.01).abs() < 1e-9,
        "4 ms of 400 ms: {va} vs {vb}"
    );
    let (mut oa, mut ob) = (None, None);
    for _ in 0..500 {
        oa = Some(a.step(&input));
        ob = Some(b.step(&input));
    }
    // Full tracking after the ramp: both reach the target, the ramped one later.
    assert!((oa.unwrap().commanded[0] - 5.0).abs() < 0.05);
    assert!((ob.unwrap().commanded[0] - 5.0).abs() < 0.05);
}

#[test]
fn ramp_down_returns_to_start_within_ramp_out_time() {
    let params = ServoParams {
        stop_mode: StopMode::RampDown,
        ramp_out_time: Duration::from_millis(200),
        ..fast()
    };
    let mut servo = EgmServo::new(params, START).unwrap();
    let input = ServoInput::position(target());
    for _ in 0..100 {
        servo.step(&input);
    }
    servo.stop(StopMode::RampDown, Duration::from_millis(200));
    let out = run_until_done(&mut servo, &input, 1000);
    assert_eq!(out.len(), 50, "200 ms at 4 ms");
    let last = out.last().unwrap();
    assert_eq!(last.commanded, START);
    assert_eq!(last.finished, Some(EndCause::Stopped));
    // Smooth: the speed is largest mid-way and small at both ends.
    let speeds: Vec<f64> = out.iter().map(|o| o.velocity[0].abs()).collect();
    assert!(speeds[25] > 5.0 * speeds[0] && speeds[25] > 5.0 * speeds[49]);
    // The feedback arrives one delay later.
    for _ in 0..servo.delay_steps() {
        servo.step(&input);
    }
    assert_eq!(servo.step(&input).feedback, START);
}

#[test]
fn halt_ramps_speed_to_zero_and_stays() {
    let mut servo = EgmServo::new(fast(), START).unwrap();
    let input = ServoInput::position(target());
    let mut v0 = 0.0;
    for _ in 0..20 {
        v0 = servo.step(&input).velocity[0];
    }
    servo.halt(Duration::from_millis(100));
    let out = run_until_done(&mut servo, &input, 1000);
    assert_eq!(out.len(), 25);
    assert!((out[0].velocity[0] - v0 * 0.96).abs() < 1e-9);
    assert_eq!(out.last().unwrap().finished, Some(EndCause::Halted));
    assert_eq!(out.last().unwrap().velocity[0], 0.0);
    let pos = out.last().unwrap().commanded;
    assert_eq!(servo.step(&input).commanded, pos, "stays where it halted");
}

#[test]
fn stop_hold_mid_run_settles() {
    let mut servo = EgmServo::new(fast(), START).unwrap();
    let input = ServoInput::position(target());
    for _ in 0..20 {
        servo.step(&input);
    }
    servo.stop(StopMode::Hold, Duration::ZERO);
    let out = run_until_done(&mut servo, &input, 1000);
    let last = out.last().unwrap();
    assert_eq!(last.finished, Some(EndCause::Stopped));
    assert!(out.len() < 60, "{}", out.len());
    assert!(last.commanded[0] < 5.0);
}

#[test]
fn reaction_time_is_about_20_ms() {
    let mut servo = EgmServo::new(fast(), START).unwrap();
    let input = ServoInput::position(target());
    let commanded_speed = DEFAULT_KP * 5.0;
    let mut prev = START[0];
    let (mut first_move, mut reaction) = (None, None);
    for step in 1..100u32 {
        let o = servo.step(&input);
        let measured_speed = (o.feedback[0] - prev) / 0.004;
        prev = o.feedback[0];
        if first_move.is_none() && measured_speed > 0.0 {
            first_move = Some(step * 4);
        }
        if measured_speed >= 0.63 * commanded_speed {
            reaction = Some(step * 4);
            break;
        }
    }
    // Deterministic: 4 ms first step + 12 ms delay; 63 % two filter steps later.
    assert_eq!(first_move, Some(16));
    assert_eq!(reaction, Some(20));
}

#[test]
fn pure_velocity_control_keeps_the_last_speed() {
    let params = ServoParams {
        pos_corr_gain: 0.0,
        ..fast()
    };
    let mut servo = EgmServo::new(params, START).unwrap();
    let input = ServoInput {
        position: START,
        speed: [2.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        convergence_error: None,
    };
    let mut last = None;
    for _ in 0..500 {
        last = Some(servo.step(&input));
    }
    let o = last.unwrap();
    assert!((o.velocity[0] - 2.0).abs() < 1e-9);
    assert!(
        (o.commanded[0] - 2.0 * 2.0).abs() < 0.1,
        "{}",
        o.commanded[0]
    );
}

#[test]
fn speed_reference_with_gain_settles_beyond_the_reference() {
    let mut servo = EgmServo::new(fast(), START).unwrap();
    let mut position = START;
    position[0] = 1.0;
    let input = ServoInput {
        position,
        speed: [1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        convergence_error: None,
    };
    let params = ServoParams {
        cond_time: Duration::from_secs(1000),
        ..fast()
    };
    let mut servo2 = EgmServo::new(params, START).unwrap();
    let mut last = None;
    for _ in 0..3000 {
        servo.step(&input);
        last = Some(servo2.step(&input));
    }
    // k·(ref − pos) + speed_ref = 0 at pos = ref + speed_ref/k.
    assert!((last.unwrap().commanded[0] - 1.2).abs() < 1e-6);
}

#[test]
fn convergence_must_hold_continuously() {
    let params = ServoParams {
        cond_time: Duration::from_millis(40),
        ..fast()
    };
    let mut servo = EgmServo::new(params, START).unwrap();
    let mut close = START;
    close[0] = 0.1;
    let far = ServoInput::position(target());
    let near = ServoInput::position(close);
    for _ in 0..9 {
        assert!(servo.step(&near).convergence_met);
    }
    assert!(!servo.step(&far).convergence_met, "leaves the window");
    let mut steps = 0;
    while servo.step(&near).phase == ServoPhase::Running {
        steps += 1;
    }
    assert_eq!(steps, 9, "timer restarted: 10 steps of 4 ms again");
}

#[test]
fn caller_supplied_convergence_error_is_used() {
    let params = ServoParams {
        cond_time: Duration::from_millis(8),
        ..fast()
    };
    let mut servo = EgmServo::new(params, START).unwrap();
    let mut input = ServoInput::position(target());
    input.convergence_error = Some([0.0; 6]);
    assert!(
        servo.step(&input).convergence_met,
        "pose-mode error says converged"
    );
    input.convergence_error = Some([0.0, 0.0, 0.6, 0.0, 0.0, 0.0]);
    assert!(!servo.step(&input).convergence_met);
}

#[test]
fn unselected_axes_keep_their_start_value() {
    let params = ServoParams {
        selected: [true, false, false, false, false, false],
        ..fast()
    };
    let mut servo = EgmServo::new(params, START).unwrap();
    let mut reference = START;
    reference[0] = 3.0;
    reference[1] = 99.0;
    let mut last = None;
    for _ in 0..200 {
        last = Some(servo.step(&ServoInput::position(reference)));
    }
    let o = last.unwrap();
    assert_eq!(o.commanded[1], START[1]);
    assert!(o.commanded[0] > 2.0);
    let none = ServoParams {
        selected: [false; 6],
        cond_time: Duration::ZERO,
        ..fast()
    };
    let mut idle = EgmServo::new(none, START).unwrap();
    let o = idle.step(&ServoInput::position(reference));
    assert!(o.convergence_met && o.phase != ServoPhase::Running);
}

#[test]
fn lp_filter_at_or_below_zero_uses_the_profile_default() {
    let params = ServoParams {
        lp_filter_hz: 0.0,
        ..fast()
    };
    let mut a = EgmServo::new(params, START).unwrap();
    let mut b = EgmServo::new(fast(), START).unwrap();
    let input = ServoInput::position(target());
    assert_eq!(a.step(&input), b.step(&input));
}

#[test]
fn bad_parameters_are_named() {
    let err = EgmServo::new(
        ServoParams {
            max_speed_deviation: f64::NAN,
            ..ServoParams::default()
        },
        START,
    )
    .unwrap_err();
    assert!(err.to_string().contains("\\MaxSpeedDeviation"), "{err}");
    let err = EgmServo::new(
        ServoParams {
            period: Duration::ZERO,
            ..ServoParams::default()
        },
        START,
    )
    .unwrap_err();
    assert!(matches!(err, ServoError::OutOfRange { name: "period", .. }));
    let mut windows = [MinMax::JOINT_DEFAULT; 6];
    windows[3] = MinMax {
        min: 1.0,
        max: -1.0,
    };
    assert!(
        EgmServo::new(
            ServoParams {
                windows,
                ..ServoParams::default()
            },
            START
        )
        .is_err()
    );
    let mut bad = START;
    bad[4] = f64::INFINITY;
    assert_eq!(
        EgmServo::new(ServoParams::default(), bad).unwrap_err(),
        ServoError::StartNotFinite
    );
}

proptest! {
    #[test]
    fn outputs_stay_finite_and_limited(
        refs in proptest::collection::vec(proptest::array::uniform6(-1.0e6f64..1.0e6), 1..60),
        msd in 0.0f64..500.0,
        mpd in 0.0f64..2000.0,
        gain in 0.0f64..3.0,
        lp in -5.0f64..100.0,
    ) {
        let params = ServoParams {
            max_speed_deviation: msd,
            max_pos_deviation: mpd,
            pos_corr_gain: gain,
            lp_filter_hz: lp,
            ..ServoParams::default()
        };
        let mut servo = EgmServo::new(params, START).unwrap();
        for r in refs {
            let mut input = ServoInput::position(r);
            input.speed[1] = f64::NAN;
            let o = servo.step(&input);
            for i in 0..6 {
                prop_assert!(o.commanded[i].is_finite() && o.feedback[i].is_finite());
                prop_assert!((o.commanded[i] - START[i]).abs() <= mpd + 1e-9);
            }
            let peak = o.velocity.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            prop_assert!(peak <= msd * (1.0 + 1e-12) + 1e-12);
        }
    }
}

#[test]
fn axis_limits_are_never_crossed_and_reported_once() {
    let mut limits = [MinMax {
        min: -180.0,
        max: 180.0,
    }; 6];
    limits[0] = MinMax {
        min: -2.0,
        max: 2.0,
    };
    let params = ServoParams {
        axis_limits: Some(limits),
        ..fast()
    };
    let mut servo = EgmServo::new(params, START).unwrap();
    // J1 is asked to go to 5°, beyond its 2° limit.
    let input = ServoInput::position(target());
    let mut began = 0;
    for _ in 0..600 {
        let o = servo.step(&input);
        assert!(o.commanded[0] >= -2.0 && o.commanded[0] <= 2.0, "{o:?}");
        if o.limit_began {
            began += 1;
            assert_eq!(o.limit_axes, 1);
            let e = axis_limit_event(servo.params(), &o);
            assert_eq!(e.number, 90112);
            assert!(e.detail.contains("J1 (-2 to 2 deg)"), "{}", e.detail);
        }
    }
    assert_eq!(began, 1, "one report per stretch at the limit");
    let o = servo.step(&input);
    assert_eq!(o.commanded[0], 2.0);
    assert!((o.commanded[2] - 18.0).abs() < 0.1, "other axes still move");
}

#[test]
fn convergence_axes_can_differ_from_the_moved_axes() {
    // Every joint moves, but only entry 2 of the caller's error vector is checked.
    let params = ServoParams {
        convergence_axes: Some([false, false, true, false, false, false]),
        cond_time: Duration::from_millis(8),
        ..fast()
    };
    let mut servo = EgmServo::new(params, START).unwrap();
    let input = ServoInput {
        convergence_error: Some([99.0, 99.0, 0.1, 99.0, 99.0, 99.0]),
        ..ServoInput::position(target())
    };
    let o = servo.step(&input);
    assert!(o.convergence_met);
    assert!(o.commanded[0] != START[0], "J1 moves although not checked");
}

#[test]
fn zero_bandwidth_switches_the_filter_off() {
    let params = ServoParams {
        lp_filter_hz: 0.0,
        default_lp_filter_hz: 0.0,
        ..fast()
    };
    let mut servo = EgmServo::new(params, START).unwrap();
    let o = servo.step(&ServoInput::position(target()));
    // Unfiltered: v = k·e = 5 · 5 deg/s on J1 in the first step.
    assert!((o.velocity[0] - 25.0).abs() < 1e-9, "{:?}", o.velocity);
}

/// Steps until `servo`, commanded at `from`, is done under `input`, with the speed of each
/// step (from the commanded positions, as a trace sees it) and where it ends.
fn speeds_until_done(
    servo: &mut EgmServo,
    from: Joints,
    input: &ServoInput,
) -> (Vec<Joints>, Joints) {
    let ts = servo.params().period.as_secs_f64();
    let mut q = from;
    let mut last = q;
    let mut speeds = Vec::new();
    for _ in 0..100_000 {
        let o = servo.step(input);
        let mut v = [0.0; 6];
        for i in 0..6 {
            v[i] = (o.commanded[i] - q[i]) / ts;
        }
        q = o.commanded;
        last = q;
        speeds.push(v);
        if o.phase == ServoPhase::Done {
            break;
        }
    }
    (speeds, last)
}

/// Ramp-in half done, MaxSpeedDeviation active: a halt, a HOLD stop and a RAMP_DOWN stop
/// all start from the speed the robot has, not from the unscaled filter output.
#[test]
fn every_stop_starts_from_the_applied_speed() {
    let params = ServoParams {
        max_speed_deviation: 10.0,
        ramp_in_time: Duration::from_secs(2),
        axis_accel: Some([700.0, 700.0, 700.0, 2400.0, 2400.0, 3333.0]),
        ..ServoParams::default()
    };
    let mut reference = START;
    reference[5] = 30.0;
    let input = ServoInput::position(reference);
    for stop in 0..3 {
        let mut servo = EgmServo::new(params, START).unwrap();
        let (mut q, mut v) = (START, 0.0);
        for _ in 0..75 {
            let o = servo.step(&input);
            v = (o.commanded[5] - q[5]) / 0.004;
            q = o.commanded;
        }
        assert!(v > 1.0 && v <= 10.0 + 1e-9, "{v}");
        match stop {
            0 => servo.halt(Duration::from_millis(500)),
            1 => servo.stop(StopMode::Hold, Duration::ZERO),
            _ => servo.stop(StopMode::RampDown, Duration::from_millis(300)),
        }
        let o = servo.step(&input);
        let first = (o.commanded[5] - q[5]) / 0.004;
        assert!(first <= v + 1e-9, "stop {stop}: {v} → {first}");
        assert!(
            (v - first) / 0.004 <= 3333.0 + 1e-6,
            "stop {stop}: {v} → {first}"
        );
    }
}

/// The brake lasts the nominal time unless the axis accelerations need longer or the
/// reference is nearer than that brake would carry the robot.
#[test]
fn brakes_are_bounded_by_acceleration_and_by_the_reference() {
    let accel = [700.0; 6];
    let params = ServoParams {
        max_speed_deviation: 100.0,
        ramp_in_time: Duration::ZERO,
        axis_accel: Some(accel),
        cond_time: Duration::from_secs(1000),
        ..ServoParams::default()
    };
    let mut far = START;
    far[0] = 90.0;
    let input = ServoInput::position(far);
    // At 100 °/s, a 4 ms halt would need 25000 °/s²: 700 °/s² stretches it to 143 ms.
    let mut servo = EgmServo::new(params, START).unwrap();
    let mut before = START;
    let mut prev = 0.0;
    for _ in 0..100 {
        let q = servo.step(&input).commanded;
        prev = (q[0] - before[0]) / 0.004;
        before = q;
    }
    assert!((prev - 100.0f64).abs() < 1e-6, "{prev}");
    servo.halt(Duration::from_millis(4));
    let (speeds, _) = speeds_until_done(&mut servo, before, &input);
    assert_eq!(speeds.len(), 36, "ceil(100 / (700 · 0.004))");
    for v in &speeds {
        assert!(prev - v[0] <= 700.0 * 0.004 + 1e-9 && v[0] <= prev + 1e-9);
        prev = v[0];
    }
    // Near the reference, a 2 s halt would overshoot it: it stops short instead.
    let mut servo = EgmServo::new(params, START).unwrap();
    let mut q = START;
    for _ in 0..120 {
        q = servo.step(&input).commanded;
    }
    servo.halt(Duration::from_secs(2));
    let (speeds, rest) = speeds_until_done(&mut servo, q, &input);
    assert!(speeds.len() < 500, "{}", speeds.len());
    assert!(
        rest[0] > q[0] && rest[0] <= far[0],
        "{} → {}",
        q[0],
        rest[0]
    );
}

/// RAMP_DOWN returns within \RampOutTime when it can, and takes longer when
/// MaxSpeedDeviation or the accelerations would be exceeded.
#[test]
fn ramp_down_return_respects_max_speed_deviation_and_acceleration() {
    let params = ServoParams {
        max_speed_deviation: 20.0,
        ramp_in_time: Duration::ZERO,
        axis_accel: Some([700.0; 6]),
        cond_time: Duration::from_secs(1000),
        ..ServoParams::default()
    };
    let mut target = START;
    target[0] = 20.0;
    let input = ServoInput::position(target);
    let mut servo = EgmServo::new(params, START).unwrap();
    let mut q = START;
    for _ in 0..1000 {
        q = servo.step(&input).commanded;
    }
    servo.stop(StopMode::RampDown, Duration::from_millis(100));
    let (speeds, rest) = speeds_until_done(&mut servo, q, &input);
    assert_eq!(rest, START);
    // 20° at ≤ 20 °/s along a cosine: at least π/2 s, not 0.1 s.
    assert!(
        speeds.len() as f64 * 0.004 >= std::f64::consts::FRAC_PI_2,
        "{}",
        speeds.len()
    );
    let mut prev = speeds[0][0];
    for v in &speeds {
        assert!(v[0].abs() <= 20.0 + 1e-9, "{}", v[0]);
        assert!((v[0] - prev).abs() <= 700.0 * 0.004 + 1e-9);
        prev = v[0];
    }
}

/// Params of a run that stays saturated at MaxSpeedDeviation toward a far target.
fn paced() -> ServoParams {
    ServoParams {
        max_speed_deviation: 20.0,
        ramp_in_time: Duration::ZERO,
        axis_accel: Some([700.0; 6]),
        cond_time: Duration::from_millis(200),
        ..ServoParams::default()
    }
}

fn far_target() -> Joints {
    let mut t = START;
    t[0] = 30.0;
    t
}

/// A program stop pauses the run: the EGM speed ramps to zero over the ramp time, the run
/// stays (Running, CondTime not counted), and a start continues it to convergence.
#[test]
fn a_pause_ramps_the_speed_to_zero_and_a_resume_continues_the_run() {
    let mut servo = EgmServo::new(paced(), START).unwrap();
    let input = ServoInput::position(far_target());
    for _ in 0..100 {
        servo.step(&input);
    }
    let v0 = servo.step(&input).velocity[0];
    assert!((v0 - 20.0).abs() < 1e-9, "saturated: {v0}");
    servo.pause(Duration::from_millis(500));
    assert!(servo.is_paused());
    let mut prev = v0;
    let mut ramp = 0;
    loop {
        let o = servo.step(&input);
        assert_eq!(o.phase, ServoPhase::Running);
        let v = o.velocity[0];
        assert!(
            v <= prev + 1e-12 && v >= 0.0,
            "slows down steadily: {prev} → {v}"
        );
        prev = v;
        ramp += 1;
        if v == 0.0 {
            break;
        }
        assert!(ramp < 1000, "never stops");
    }
    assert_eq!(ramp, 125, "0.5 s at 4 ms");
    let held = servo.step(&input).commanded;
    for _ in 0..500 {
        let o = servo.step(&input);
        assert_eq!(o.commanded, held, "stands while paused");
        assert_eq!(o.converged_for, Duration::ZERO);
        assert_eq!(o.phase, ServoPhase::Running);
    }
    servo.resume(Duration::from_millis(500));
    assert!(!servo.is_paused());
    let out = run_until_done(&mut servo, &input, 10_000);
    let last = out.last().unwrap();
    assert_eq!(last.finished, Some(EndCause::Converged));
    assert!((last.commanded[0] - 30.0).abs() < 0.5, "{last:?}");
    // The speed ramps back in: no jump.
    for w in out.windows(2).take(200) {
        assert!((w[1].velocity[0] - w[0].velocity[0]).abs() <= 0.5 * 700.0 * 0.004 + 1e-9);
    }
}

/// A paused run converged on its reference does not end while paused: \CondTime counts
/// from the start again.
#[test]
fn cond_time_is_not_counted_while_paused() {
    let mut servo = EgmServo::new(fast(), START).unwrap();
    let input = ServoInput::position(START);
    servo.step(&input);
    servo.pause(Duration::from_millis(100));
    for _ in 0..1000 {
        let o = servo.step(&input);
        assert!(o.convergence_met && o.converged_for == Duration::ZERO);
        assert_eq!(o.phase, ServoPhase::Running);
    }
    servo.resume(Duration::from_millis(100));
    let out = run_until_done(&mut servo, &input, 5000);
    let stop = out
        .iter()
        .position(|o| o.phase != ServoPhase::Running)
        .unwrap();
    assert_eq!(stop + 1, 250, "a full CondTime (1 s) after the start");
}

/// The speed ratio scales the EGM speed (MaxSpeedDeviation and the law together).
#[test]
fn the_speed_ratio_scales_the_egm_speed() {
    let mut servo = EgmServo::new(paced(), START).unwrap();
    let input = ServoInput::position(far_target());
    servo.set_ratio(0.5, Duration::from_millis(100));
    let mut v = 0.0;
    for _ in 0..200 {
        v = servo.step(&input).velocity[0];
    }
    assert!((v - 10.0).abs() < 1e-9, "{v}");
    servo.set_ratio(f64::NAN, Duration::ZERO);
    servo.set_ratio(1.0, Duration::from_millis(100));
    for _ in 0..200 {
        v = servo.step(&input).velocity[0];
    }
    assert!((v - 20.0).abs() < 1e-9, "{v}");
}

proptest! {
    /// Any series of stops and starts (and ratio changes) keeps the EGM speed within
    /// MaxSpeedDeviation and its changes within the axis acceleration.
    #[test]
    fn stop_and_start_spam_stays_within_the_limits(
        toggles in proptest::collection::vec((1usize..40, 0u8..3, 1u8..=100), 1..40),
        ramp_ms in 1u64..2000,
    ) {
        let mut servo = EgmServo::new(paced(), START).unwrap();
        // Far enough that the run never converges within the test.
        let mut far = START;
        far[0] = 900.0;
        let input = ServoInput::position(far);
        let ramp = Duration::from_millis(ramp_ms);
        let mut prev = 0.0;
        for _ in 0..50 {
            prev = servo.step(&input).velocity[0];
        }
        for (n, what, ratio) in toggles {
            match what {
                0 => servo.pause(ramp),
                1 => servo.resume(ramp),
                _ => servo.set_ratio(f64::from(ratio) / 100.0, ramp),
            }
            for _ in 0..n {
                let o = servo.step(&input);
                let v = o.velocity[0];
                prop_assert!(v.abs() <= 20.0 + 1e-9, "{v}");
                prop_assert!((v - prev).abs() <= 0.5 * 700.0 * 0.004 + 1e-9, "{prev} → {v}");
                prop_assert_eq!(o.phase, ServoPhase::Running);
                prev = v;
            }
        }
    }
}
