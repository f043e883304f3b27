//! Unit tests of the path-correction math: frames, checks, smoothing, scheduling and seams.

use super::*;
use proptest::prelude::*;

const TOL: f64 = 1e-12;

fn v(x: f64, y: f64, z: f64) -> Vec3 {
    Vec3::new(x, y, z)
}

fn close(a: &Vec3, b: &Vec3, tol: f64) -> bool {
    (a - b).norm() <= tol
}

fn assert_orthonormal_right_handed(f: &PathFrame) {
    for a in [f.x, f.y, f.z] {
        assert!(a.iter().all(|c| c.is_finite()), "{f:?}");
        assert!((a.norm() - 1.0).abs() < 1e-9, "{f:?}");
    }
    assert!(f.x.dot(&f.y).abs() < 1e-9, "{f:?}");
    assert!(f.x.dot(&f.z).abs() < 1e-9, "{f:?}");
    assert!(f.y.dot(&f.z).abs() < 1e-9, "{f:?}");
    assert!(close(&f.x.cross(&f.y), &f.z, 1e-9), "{f:?}");
    let det = nalgebra::Matrix3::from_columns(&[f.x, f.y, f.z]).determinant();
    assert!((det - 1.0).abs() < 1e-9, "{f:?}");
}

// ---- path frame ----

#[test]
fn frame_signs_are_pinned() {
    // Tool pointing down, path along +X: y = +Y, z = +Z (away from the work).
    let f = PathFrame::new(v(10.0, 0.0, 0.0), v(0.0, 0.0, -1.0), None);
    assert_eq!(f.basis, FrameBasis::Regular);
    assert!(close(&f.x, &Vec3::x(), TOL));
    assert!(close(&f.y, &Vec3::y(), TOL));
    assert!(close(&f.z, &Vec3::z(), TOL));
    // Path along +Y: y = Y × (−Z) = −X.
    let f = PathFrame::new(v(0.0, 3.0, 0.0), v(0.0, 0.0, -2.0), None);
    assert!(close(&f.y, &-Vec3::x(), TOL));
    assert!(close(&f.z, &Vec3::z(), TOL));
    // With the tool axis perpendicular to the path, z = −tool z exactly.
    let tz = v(0.0, 0.5, -1.0).normalize();
    let f = PathFrame::new(v(1.0, 0.0, 0.0), tz, None);
    assert!(close(&f.z, &-tz, 1e-12));
    assert_orthonormal_right_handed(&f);
    // A tilted tool: y is still x × tool z, normalised.
    let t = v(1.0, 1.0, 0.0);
    let tz = v(0.3, -0.2, -1.0);
    let f = PathFrame::new(t, tz, None);
    assert!(close(&f.y, &t.cross(&tz).normalize(), 1e-12));
    assert!(close(&f.x, &t.normalize(), 1e-12));
    assert_orthonormal_right_handed(&f);
}

#[test]
fn correction_to_world_and_back() {
    let f = PathFrame::new(v(1.0, 0.0, 0.0), v(0.0, 0.0, -1.0), None);
    let w = f.to_world(PathOffset::new(3.0, -2.0));
    assert!(close(&w, &v(0.0, 3.0, -2.0), TOL));
    let back = f.offset_of(&(w + v(7.0, 0.0, 0.0)));
    assert_eq!(back, PathOffset::new(3.0, -2.0));
    assert_eq!(f.along(&v(7.0, 1.0, 1.0)), 7.0);
    let tcp = v(100.0, 0.0, 0.0);
    assert_eq!(look_ahead_distance(&f, &tcp, &v(150.0, 20.0, 5.0)), 50.0);
    assert_eq!(look_ahead_distance(&f, &tcp, &v(90.0, 0.0, 0.0)), -10.0);
    assert_eq!(look_ahead_distance(&f, &tcp, &v(f64::NAN, 0.0, 0.0)), 0.0);
}

#[test]
fn tangent_along_tool_z() {
    let f = PathFrame::new(v(0.0, 0.0, -5.0), v(0.0, 0.0, -1.0), None);
    assert_eq!(f.basis, FrameBasis::TangentAlongToolZ);
    assert_orthonormal_right_handed(&f);
    assert!(close(&f.x, &-Vec3::z(), TOL));
    // With a previous frame, its y is kept (made perpendicular to x).
    let prev = PathFrame::new(v(1.0, 0.0, -0.2), v(0.0, 0.0, -1.0), None);
    let f = PathFrame::new(v(0.0, 0.0, -1.0), v(0.0, 0.0, -1.0), Some(&prev));
    assert_eq!(f.basis, FrameBasis::TangentAlongToolZ);
    assert_orthonormal_right_handed(&f);
    assert!(close(&f.y, &prev.y, 1e-12));
    // Nearly parallel (below PARALLEL_SIN) counts as parallel.
    let f = PathFrame::new(v(1e-8, 0.0, 1.0), v(0.0, 0.0, 1.0), None);
    assert_eq!(f.basis, FrameBasis::TangentAlongToolZ);
    assert_orthonormal_right_handed(&f);
    // A missing tool axis takes the same fallback.
    let f = PathFrame::new(v(1.0, 0.0, 0.0), v(f64::NAN, 0.0, 0.0), None);
    assert_eq!(f.basis, FrameBasis::NoToolZ);
    assert_orthonormal_right_handed(&f);
}

#[test]
fn no_tangent() {
    let prev = PathFrame::new(v(0.0, 1.0, 0.0), v(0.0, 0.0, -1.0), None);
    let f = PathFrame::new(Vec3::zeros(), v(0.0, 0.0, -1.0), Some(&prev));
    assert_eq!(f.basis, FrameBasis::NoTangent);
    assert_eq!((f.x, f.y, f.z), (prev.x, prev.y, prev.z));
    // Without a previous frame: world X made perpendicular to the tool axis.
    let f = PathFrame::new(v(0.0, 0.0, 1e-12), v(0.0, 0.0, -1.0), None);
    assert_eq!(f.basis, FrameBasis::NoTangent);
    assert!(close(&f.x, &Vec3::x(), TOL) && close(&f.y, &Vec3::y(), TOL));
    // Tool along X: world Y is used.
    let f = PathFrame::new(v(f64::INFINITY, 0.0, 0.0), v(1.0, 0.0, 0.0), None);
    assert_eq!(f.basis, FrameBasis::NoTangent);
    assert!(close(&f.x, &Vec3::y(), TOL));
    assert_orthonormal_right_handed(&f);
    // Nothing at all: the world frame.
    let f = PathFrame::new(Vec3::zeros(), Vec3::zeros(), None);
    assert_eq!(f, PathFrame::world());
    let f = PathFrame::new(v(f64::NAN, 1.0, 1.0), v(0.0, f64::NAN, 0.0), None);
    assert_eq!(f.basis, FrameBasis::World);
    // A corrupt previous frame is not trusted.
    let bad = PathFrame {
        x: v(f64::NAN, 0.0, 0.0),
        ..PathFrame::world()
    };
    let f = PathFrame::new(Vec3::zeros(), v(0.0, 0.0, -1.0), Some(&bad));
    assert_orthonormal_right_handed(&f);
}

fn component() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => -1000.0..1000.0f64,
        1 => Just(0.0),
        1 => Just(1e-10),
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
    ]
}

fn vector() -> impl Strategy<Value = Vec3> {
    (component(), component(), component()).prop_map(|(a, b, c)| v(a, b, c))
}

proptest! {
    #[test]
    fn frames_are_always_orthonormal_and_right_handed(
        t in vector(), tz in vector(), pt in vector(), ptz in vector(), with_prev: bool,
    ) {
        let prev = PathFrame::new(pt, ptz, None);
        assert_orthonormal_right_handed(&prev);
        let f = PathFrame::new(t, tz, with_prev.then_some(&prev));
        assert_orthonormal_right_handed(&f);
        if f.basis == FrameBasis::Regular {
            let x = t.normalize();
            prop_assert!(close(&f.x, &x, 1e-9));
            prop_assert!(close(&f.y, &x.cross(&tz).normalize(), 1e-6));
        }
    }
}

// ---- checking corrections ----

#[test]
fn rejections() {
    let l = CorrectionLimits::default();
    // x is ignored.
    assert_eq!(
        check_correction([99.0, 3.0, -2.0], 0.05, &l),
        Ok(PathOffset::new(3.0, -2.0))
    );
    // ... but a non-finite x marks a corrupt message.
    assert!(matches!(
        check_correction([f64::NAN, 3.0, -2.0], 0.0, &l),
        Err(Rejection::NotFinite { axis: 'x', .. })
    ));
    let e = check_correction([0.0, f64::INFINITY, 0.0], 0.0, &l).unwrap_err();
    assert_eq!(
        e.to_string(),
        "path correction y is not a finite number (inf)"
    );
    assert!(matches!(
        check_correction([0.0, 0.0, f64::NEG_INFINITY], 0.0, &l),
        Err(Rejection::NotFinite { axis: 'z', .. })
    ));
    // Exactly at the limit is allowed, just above is not.
    assert!(check_correction([0.0, 60.0, 80.0], 0.0, &l).is_ok());
    let e = check_correction([0.0, 60.0, 80.01], 0.0, &l).unwrap_err();
    assert!(matches!(e, Rejection::TooLarge { limit, .. } if limit == 100.0));
    assert_eq!(
        e.to_string(),
        "path correction of 100.008 mm exceeds the limit of 100 mm"
    );
    assert!(matches!(
        check_correction([0.0; 3], -0.001, &l),
        Err(Rejection::BadAge { .. })
    ));
    assert!(matches!(
        check_correction([0.0; 3], f64::NAN, &l),
        Err(Rejection::BadAge { .. })
    ));
    assert_eq!(
        check_correction([0.0; 3], 2.5, &l),
        Err(Rejection::TooOld {
            age: 2.5,
            limit: 2.0
        })
    );
    assert_eq!(
        Rejection::TooOld {
            age: 2.5,
            limit: 2.0
        }
        .to_string(),
        "path correction is 2.5 s old; the limit is 2 s"
    );
}

// ---- smoothing ----

fn dist(a: PathOffset, b: PathOffset) -> f64 {
    a.sub(b).norm()
}

#[test]
fn smoother_reaches_the_target_without_overshoot() {
    let limits = SmoothingLimits::default();
    let mut sm = Smoother::new(limits);
    let target = PathOffset::new(3.0, -2.0);
    let d = target.norm();
    let dt = 0.004;
    let mut prev = sm.applied();
    let mut steps = 0;
    while sm.applied() != target {
        let a = sm.step(target, dt);
        // Monotonic approach along the straight line to the target.
        let along = (a.y * target.y + a.z * target.z) / d;
        let across = (a.y * target.z - a.z * target.y).abs() / d;
        assert!(along <= d + 1e-12 && across < 1e-9, "{a:?}");
        assert!(dist(a, target) <= dist(prev, target) + 1e-12);
        assert!(dist(a, prev) <= limits.max_speed * dt + 1e-12);
        prev = a;
        steps += 1;
        assert!(steps < 10_000);
    }
    // Time-optimal within a few steps: d/vmax + vmax/amax.
    let t = steps as f64 * dt;
    let ideal = d / limits.max_speed + limits.max_speed / limits.max_accel;
    assert!(t <= ideal + 5.0 * dt, "{t} vs {ideal}");
    assert!(t >= d / limits.max_speed);
    // Holding the target keeps it exactly, and the next step is at rest.
    assert_eq!(sm.step(target, dt), target);
    assert_eq!(sm.velocity(), PathOffset::ZERO);
    assert_eq!(sm.step(target, dt), target);
}

#[test]
fn pure_rate_limit() {
    let mut sm = Smoother::new(SmoothingLimits {
        max_speed: 10.0,
        max_accel: f64::INFINITY,
    });
    let target = PathOffset::new(0.0, 1.0);
    assert!((sm.step(target, 0.01).z - 0.1).abs() < 1e-12);
    assert!((sm.step(target, 0.01).z - 0.2).abs() < 1e-12);
    for _ in 0..20 {
        sm.step(target, 0.01);
    }
    assert_eq!(sm.applied(), target);
    // No limits at all: a jump.
    let mut sm = Smoother::new(SmoothingLimits {
        max_speed: f64::INFINITY,
        max_accel: f64::INFINITY,
    });
    assert_eq!(sm.step(target, 0.004), target);
}

#[test]
fn smoother_holds_on_bad_input() {
    let mut sm = Smoother::new(SmoothingLimits::default());
    let target = PathOffset::new(1.0, 0.0);
    sm.step(target, 0.004);
    let a = sm.applied();
    for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(sm.step(target, dt), a);
    }
    assert_eq!(sm.step(PathOffset::new(f64::NAN, 0.0), 0.004), a);
    for limits in [
        SmoothingLimits {
            max_speed: f64::NAN,
            max_accel: 1.0,
        },
        SmoothingLimits {
            max_speed: 1.0,
            max_accel: 0.0,
        },
    ] {
        let mut sm = Smoother::new(limits);
        assert_eq!(sm.step(target, 0.004), PathOffset::ZERO);
    }
    let mut sm = Smoother::new(SmoothingLimits::default());
    let huge = PathOffset::new(f64::MAX, f64::MAX);
    let a = sm.step(huge, 0.004);
    assert!(a.is_finite());
    sm.reset();
    assert_eq!(sm.applied(), PathOffset::ZERO);
}

fn offset() -> impl Strategy<Value = PathOffset> {
    (-50.0..50.0f64, -50.0..50.0f64).prop_map(|(y, z)| PathOffset::new(y, z))
}

proptest! {
    /// Whatever the targets and steps, no step is longer than max_speed·dt and no
    /// velocity change larger than max_accel·dt.
    #[test]
    fn smoothing_never_exceeds_its_limits(
        vmax in 0.5..100.0f64,
        amax in prop_oneof![1.0..2000.0f64, Just(f64::INFINITY)],
        moves in proptest::collection::vec((offset(), 0.0005..0.1f64, 1..40usize), 1..12),
    ) {
        let mut sm = Smoother::new(SmoothingLimits { max_speed: vmax, max_accel: amax });
        for (target, dt, n) in moves {
            for _ in 0..n {
                let (a0, v0) = (sm.applied(), sm.velocity());
                let a1 = sm.step(target, dt);
                let v1 = sm.velocity();
                prop_assert!(a1.is_finite() && v1.is_finite());
                prop_assert!(dist(a1, a0) <= vmax * dt * (1.0 + 1e-9) + 1e-9);
                prop_assert!(v1.norm() <= vmax * (1.0 + 1e-9));
                if amax.is_finite() {
                    prop_assert!(dist(v1, v0) <= amax * dt * (1.0 + 1e-9) + 1e-9);
                }
            }
        }
    }
}

// ---- the corrector ----

#[test]
fn config_validation() {
    assert!(PathCorrConfig::aptr().validate().is_ok());
    assert!(PathCorrConfig::latr(50.0).validate().is_ok());
    let mut c = PathCorrConfig::latr(-1.0);
    let e = PathCorrector::new(c).unwrap_err();
    assert_eq!(e.name, "look_ahead");
    c = PathCorrConfig::aptr();
    c.limits.max_offset = f64::INFINITY;
    assert_eq!(c.validate().unwrap_err().name, "max_offset");
    c = PathCorrConfig::aptr();
    c.limits.max_age = 0.0;
    assert_eq!(c.validate().unwrap_err().name, "max_age");
    c = PathCorrConfig::aptr();
    c.smoothing.max_speed = f64::NAN;
    assert_eq!(c.validate().unwrap_err().name, "max_speed");
    c = PathCorrConfig::aptr();
    c.smoothing.max_accel = -1.0;
    assert_eq!(
        c.validate().unwrap_err().to_string(),
        "path correction max_accel = -1: expected a positive number"
    );
    c = PathCorrConfig::aptr();
    c.capacity = 1;
    assert_eq!(c.validate().unwrap_err().name, "capacity");
}

/// The acceptance case of the path-correction issue: a straight 400 mm move at 10 mm/s
/// with a constant simulated seam offset y = 3, z = −2 from an at-point sensor
/// answering every 48 ms; the correction ramps in within the limits and holds.
#[test]
fn aptr_constant_seam_over_400_mm() {
    let seam = SeamProfile::parse("const:y=3,z=-2").unwrap();
    let cfg = PathCorrConfig::aptr();
    let mut pc = PathCorrector::new(cfg).unwrap();
    let dt = 0.004;
    let speed = 10.0;
    pc.start(0.0, 0.0);
    let mut prev = PathOffset::ZERO;
    let mut max_step: f64 = 0.0;
    let ticks = (400.0 / speed / dt) as usize;
    for i in 1..=ticks {
        let now = i as f64 * dt;
        let s = speed * now;
        if i % 12 == 0 {
            let m = seam.sensed_at(cfg.tracker, s);
            pc.measurement(now, [0.0, m.y, m.z], 0.0).unwrap();
        }
        let a = pc.step(now, s);
        max_step = max_step.max(dist(a, prev));
        prev = a;
    }
    assert!(max_step <= cfg.smoothing.max_speed * dt + 1e-12);
    assert!(dist(pc.applied(), PathOffset::new(3.0, -2.0)) < 1e-9);
    // The world offset at the end, with the tool pointing down on a path along +X.
    let f = PathFrame::new(v(1.0, 0.0, 0.0), v(0.0, 0.0, -1.0), None);
    assert!(close(&f.to_world(pc.applied()), &v(0.0, 3.0, -2.0), 1e-9));
}

#[test]
fn aptr_applies_at_once() {
    let mut pc = PathCorrector::new(PathCorrConfig::aptr()).unwrap();
    pc.start(0.0, 0.0);
    pc.step(0.004, 0.04);
    let sch = pc.measurement(0.005, [0.0, 1.0, 0.0], 0.5).unwrap();
    assert_eq!(sch.s, 0.04);
    assert_eq!(pc.pending(), 0);
    pc.step(0.008, 0.08);
    assert_eq!(pc.target(), PathOffset::new(1.0, 0.0));
    assert!(pc.applied().y > 0.0 && pc.applied().y < 1.0);
}

/// A seam that steps from 0 to 3 mm at s = 100 mm, seen by a look-ahead sensor 50 mm
/// ahead whose messages arrive 30 ms after measuring: the target steps where the seam
/// does, not where the sensor saw it.
#[test]
fn latr_applies_at_the_right_arc_length() {
    let look_ahead = 50.0;
    let mut cfg = PathCorrConfig::latr(look_ahead);
    cfg.smoothing.max_speed = f64::INFINITY;
    cfg.smoothing.max_accel = f64::INFINITY;
    let mut pc = PathCorrector::new(cfg).unwrap();
    let seam = |s: f64| if s >= 100.0 { 3.0 } else { 0.0 };
    let (dt, speed, age) = (0.004, 10.0, 0.030);
    let s_of = |t: f64| speed * t;
    pc.start(0.0, 0.0);
    let sample_spacing = speed * 0.048;
    let mut checked = 0;
    for i in 1..=5000 {
        let now = i as f64 * dt;
        let s = s_of(now);
        // Every 48 ms a message arrives about what the sensor saw `age` earlier.
        if i % 12 == 0 {
            let t_meas = now - age;
            let y = seam(s_of(t_meas) + look_ahead);
            let sch = pc.measurement(now, [0.0, y, 0.0], age).unwrap();
            assert!((sch.s - (s_of(t_meas) + look_ahead)).abs() < 1e-9);
        }
        let a = pc.step(now, s);
        if s < 100.0 - sample_spacing {
            assert_eq!(a.y, 0.0, "s = {s}");
            checked += 1;
        } else if s >= 100.0 + sample_spacing {
            assert_eq!(a.y, 3.0, "s = {s}");
            checked += 1;
        }
    }
    assert!(checked > 4900);
}

/// A ramp seam seen through the look-ahead delay is reproduced exactly (linear
/// interpolation between queued points), however late the messages arrive. Ignoring
/// the age would misplace every point by 1 mm, an error of 0.5 mm on this slope.
#[test]
fn latr_reproduces_a_ramp_seam() {
    let look_ahead = 40.0;
    let seam = SeamProfile::parse("ramp:y=50,z=-25,len=100").unwrap();
    let mut cfg = PathCorrConfig::latr(look_ahead);
    cfg.smoothing.max_speed = f64::INFINITY;
    cfg.smoothing.max_accel = f64::INFINITY;
    let mut pc = PathCorrector::new(cfg).unwrap();
    let (dt, speed, age) = (0.004, 10.0, 0.1);
    pc.start(0.0, 0.0);
    let mut worst: f64 = 0.0;
    for i in 1..=3000 {
        let now = i as f64 * dt;
        let s = speed * now;
        if i % 12 == 0 {
            let sensed = seam.sensed_at(cfg.tracker, speed * (now - age));
            pc.measurement(now, [0.0, sensed.y, sensed.z], age).unwrap();
        }
        let a = pc.step(now, s);
        // From the first queued point on (the sensor saw s = 40 at t = 0), except
        // within one sample spacing of the ramp's end, where interpolating between
        // samples cuts the corner.
        let spacing = speed * 0.048;
        if s >= look_ahead + spacing && (s - 100.0).abs() > spacing {
            worst = worst.max(dist(a, seam.offset_at(s)));
        }
    }
    assert!(worst < 1e-9, "{worst}");
}

#[test]
fn latr_queue_rules() {
    let mut pc = PathCorrector::new(PathCorrConfig::latr(10.0)).unwrap();
    pc.start(0.0, 0.0);
    pc.step(1.0, 5.0);
    // s(1.0) = 5 → applies at 15.
    let a = pc.measurement(1.0, [0.0, 1.0, 0.0], 0.0).unwrap();
    assert_eq!(a.s, 15.0);
    // Measured at t = 0.5 (s = 2.5, interpolated) → 12.5: supersedes the one at 15.
    let b = pc.measurement(1.0, [0.0, 2.0, 0.0], 0.5).unwrap();
    assert_eq!(b.s, 12.5);
    assert_eq!(pc.pending(), 1);
    // Older than the history: clamped to its oldest sample (s = 0) → 10.
    let c = pc.measurement(1.0, [0.0, 3.0, 0.0], 1.5).unwrap();
    assert_eq!(c.s, 10.0);
    assert_eq!(pc.pending(), 1);
    // Halfway from the anchor (s = 0, offset 0) to (10, 3).
    pc.step(1.5, 5.0);
    assert!((pc.target().y - 1.5).abs() < 1e-12);
    pc.step(2.0, 10.0);
    assert_eq!(pc.target().y, 3.0);
    assert_eq!(pc.pending(), 0);
    // With no look-ahead the arc length has been passed: applies at once.
    pc.set_look_ahead(0.0);
    pc.set_look_ahead(-5.0);
    pc.set_look_ahead(f64::NAN);
    assert_eq!(pc.config().tracker, Tracker::Latr { look_ahead: 0.0 });
    pc.measurement(2.0, [0.0, 4.0, 0.0], 0.2).unwrap();
    assert_eq!(pc.pending(), 0);
    pc.step(2.1, 11.0);
    assert_eq!(pc.target().y, 4.0);
}

#[test]
fn latr_queue_overflow() {
    let mut cfg = PathCorrConfig::latr(100.0);
    cfg.capacity = 2;
    let mut pc = PathCorrector::new(cfg).unwrap();
    pc.start(0.0, 0.0);
    for i in 1..=5 {
        let t = i as f64;
        pc.step(t, t);
        pc.measurement(t, [0.0, t, 0.0], 0.0).unwrap();
    }
    assert_eq!(pc.pending(), 2);
    assert_eq!(pc.overflows(), 3);
    // The dropped entries became the anchor: the target stays continuous.
    pc.step(6.0, 6.0);
    assert!(pc.target().is_finite());
}

#[test]
fn incremental_mode_and_limits() {
    let mut cfg = PathCorrConfig::aptr();
    cfg.mode = CorrectionMode::Incremental;
    cfg.limits.max_offset = 5.0;
    let mut pc = PathCorrector::new(cfg).unwrap();
    pc.start(0.0, 0.0);
    pc.measurement(0.0, [0.0, 2.0, 0.0], 0.0).unwrap();
    let s = pc.measurement(0.0, [0.0, 2.0, 1.0], 0.0).unwrap();
    assert_eq!(s.offset, PathOffset::new(4.0, 1.0));
    // 4 + 2 = 6 > 5: rejected, the total stays.
    assert!(matches!(
        pc.measurement(0.0, [0.0, 2.0, 0.0], 0.0),
        Err(Rejection::TooLarge { .. })
    ));
    pc.step(0.004, 0.0);
    assert_eq!(pc.target(), PathOffset::new(4.0, 1.0));
    // A rejected absolute correction leaves the previous one in force too.
    let mut pc = PathCorrector::new(PathCorrConfig::aptr()).unwrap();
    pc.measurement(0.0, [0.0, 1.0, 0.0], 0.0).unwrap();
    assert!(pc.measurement(0.0, [0.0, f64::NAN, 0.0], 0.0).is_err());
    assert!(pc.measurement(0.0, [0.0, 500.0, 0.0], 0.0).is_err());
    pc.step(0.0, 0.0);
    assert_eq!(pc.target(), PathOffset::new(1.0, 0.0));
}

#[test]
fn no_corr_ramps_out() {
    let mut pc = PathCorrector::new(PathCorrConfig::aptr()).unwrap();
    pc.start(0.0, 0.0);
    pc.measurement(0.0, [0.0, 1.0, 0.0], 0.0).unwrap();
    for i in 1..200 {
        pc.step(i as f64 * 0.004, 0.0);
    }
    assert_eq!(pc.applied(), PathOffset::new(1.0, 0.0));
    pc.set_enabled(false);
    pc.measurement(0.8, [0.0, 2.0, 0.0], 0.0).unwrap();
    for i in 200..400 {
        pc.step(i as f64 * 0.004, 0.0);
    }
    assert_eq!(pc.target(), PathOffset::ZERO);
    assert_eq!(pc.applied(), PathOffset::ZERO);
    pc.set_enabled(true);
    pc.measurement(1.6, [0.0, 2.0, 0.0], 0.0).unwrap();
    pc.step(1.604, 0.0);
    assert_eq!(pc.target(), PathOffset::new(2.0, 0.0));
}

#[test]
fn corrector_survives_bad_times_and_arc_lengths() {
    for cfg in [PathCorrConfig::aptr(), PathCorrConfig::latr(30.0)] {
        let mut pc = PathCorrector::new(cfg).unwrap();
        pc.start(f64::NAN, f64::INFINITY);
        pc.measurement(0.0, [0.0, 1.0, 1.0], 0.0).unwrap();
        for (t, s) in [
            (0.004, 1.0),
            (f64::NAN, 2.0),
            (0.002, 3.0),
            (0.008, f64::NAN),
            (f64::INFINITY, 4.0),
            (0.012, -10.0),
            (0.016, 5.0),
        ] {
            let a = pc.step(t, s);
            assert!(a.is_finite(), "{cfg:?} {t} {s}");
        }
        pc.measurement(f64::NAN, [0.0, 1.0, 1.0], 0.0).unwrap();
        assert!(pc.step(0.02, 6.0).is_finite());
    }
}

// ---- seam profiles ----

#[test]
fn seam_profiles() {
    let c = SeamProfile::parse("const:y=3,z=-2").unwrap();
    assert_eq!(c, SeamProfile::Const { y: 3.0, z: -2.0 });
    assert_eq!(c.offset_at(-5.0), PathOffset::new(3.0, -2.0));
    assert_eq!(c.offset_at(f64::NAN), PathOffset::ZERO);
    let r: SeamProfile = " Ramp : Y = 5 , len=400 ".parse().unwrap();
    assert_eq!(
        r,
        SeamProfile::Ramp {
            y: 5.0,
            z: 0.0,
            len: 400.0
        }
    );
    assert_eq!(r.offset_at(-1.0), PathOffset::ZERO);
    assert_eq!(r.offset_at(200.0), PathOffset::new(2.5, 0.0));
    assert_eq!(r.offset_at(400.0), PathOffset::new(5.0, 0.0));
    assert_eq!(r.offset_at(1e6), PathOffset::new(5.0, 0.0));
    let s = SeamProfile::parse("sine:y=2,z=-1,period=100").unwrap();
    assert!(s.offset_at(0.0).norm() < 1e-12);
    assert!(dist(s.offset_at(25.0), PathOffset::new(2.0, -1.0)) < 1e-12);
    assert!(s.offset_at(50.0).norm() < 1e-12);
    assert!(dist(s.offset_at(75.0), PathOffset::new(-2.0, 1.0)) < 1e-12);
    assert!(dist(s.offset_at(1e7 + 25.0), PathOffset::new(2.0, -1.0)) < 1e-6);
    let p = SeamProfile::parse("sine:y=2,period=100,phase=90").unwrap();
    assert!(dist(p.offset_at(0.0), PathOffset::new(2.0, 0.0)) < 1e-12);
    assert_eq!(
        SeamProfile::parse("const").unwrap().offset_at(1.0),
        PathOffset::ZERO
    );
    assert_eq!(
        SeamProfile::parse("CONST:").unwrap().offset_at(1.0),
        PathOffset::ZERO
    );
    // APTR senses at the TCP, LATR ahead of it.
    assert_eq!(r.sensed_at(Tracker::Aptr, 200.0), PathOffset::new(2.5, 0.0));
    assert_eq!(
        r.sensed_at(Tracker::Latr { look_ahead: 200.0 }, 0.0),
        PathOffset::new(2.5, 0.0)
    );
}

#[test]
fn seam_text_round_trips() {
    for text in [
        "const:y=3,z=-2",
        "ramp:y=5,z=0,len=400",
        "sine:y=2,z=0,period=100",
        "sine:y=2,z=0.5,period=200,phase=-45",
    ] {
        let p = SeamProfile::parse(text).unwrap();
        assert_eq!(p.to_string(), text);
        assert_eq!(SeamProfile::parse(&p.to_string()).unwrap(), p);
    }
}

#[test]
fn seam_parse_errors() {
    let err = |s: &str| SeamProfile::parse(s).unwrap_err().error;
    assert_eq!(err(" "), SeamError::Empty);
    assert_eq!(err("square:y=1"), SeamError::UnknownKind("square".into()));
    assert_eq!(
        err("const:len=3").to_string(),
        "const takes y and z, not `len`"
    );
    assert_eq!(
        err("ramp:y=1,period=3").to_string(),
        "ramp takes y, z and len, not `period`"
    );
    assert_eq!(
        err("sine:y=1,len=3").to_string(),
        "sine takes y, z, period and phase, not `len`"
    );
    assert_eq!(err("ramp:y=1").to_string(), "ramp needs `len=`");
    assert_eq!(err("sine:y=2").to_string(), "sine needs `period=`");
    assert_eq!(
        err("ramp:len=0").to_string(),
        "`len` must be greater than 0 mm, not 0"
    );
    assert_eq!(
        err("sine:period=-5").to_string(),
        "`period` must be greater than 0 mm, not -5"
    );
    assert_eq!(
        err("sine:period=abc").to_string(),
        "`period=abc`: not a number"
    );
    for bad in ["inf", "NaN", "1e999", ""] {
        assert!(matches!(
            err(&format!("const:y={bad}")),
            SeamError::BadNumber { .. }
        ));
    }
    assert_eq!(err("const:y").to_string(), "`y` needs a value: `y=NUMBER`");
    assert_eq!(err("const:y=1,Y=2"), SeamError::Duplicate("Y".into()));
    assert_eq!(err("const:y=1,,z=2"), SeamError::EmptyItem);
    assert_eq!(err("const:y=1,"), SeamError::EmptyItem);
    let full = SeamProfile::parse("ramp:y=1").unwrap_err().to_string();
    assert_eq!(
        full,
        "bad seam pattern `ramp:y=1`: ramp needs `len=` (examples: `const:y=3,z=-2`, \
         `ramp:y=5,z=0,len=400`, `sine:y=2,z=0,period=100`)"
    );
}

proptest! {
    #[test]
    fn seam_parser_is_total(text in "[a-zA-Z:=,.0-9 -]{0,40}") {
        if let Ok(p) = SeamProfile::parse(&text) {
            prop_assert!(p.offset_at(123.4).is_finite());
            prop_assert_eq!(SeamProfile::parse(&p.to_string()), Ok(p));
        }
    }
}
