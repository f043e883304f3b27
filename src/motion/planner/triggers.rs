//! Position events on a planned segment: the sample (motion cycle) where the TCP reaches the
//! place a `TriggIO`, `TriggInt`, `MoveLDO`, … gives, measured along the TCP path of the
//! segment's own samples.

use crate::robot::trigger::{PathTrigger, TriggPlace};

use super::super::segment::{Sample, SegTrigger};

/// The index of the sample where `place` is reached: the first sample at or past it. Places
/// beyond the path are clamped to it (a distance longer than the move fires at its start, a
/// negative one at the ToPoint).
pub fn sample_index(samples: &[Sample], start_tcp: [f64; 3], place: TriggPlace, dt: f64) -> usize {
    let last = samples.len().saturating_sub(1);
    let finite = |x: f64| if x.is_finite() { x.max(0.0) } else { 0.0 };
    match place {
        TriggPlace::BeforeEndTime(t) => {
            let steps = (finite(t) / dt).round();
            if steps >= last as f64 {
                0
            } else {
                last - steps as usize
            }
        }
        TriggPlace::AfterStart(d) => first_at_or_past(samples, start_tcp, finite(d)),
        TriggPlace::BeforeEnd(d) => {
            let total = path_length(samples, start_tcp);
            if total < 1e-3 {
                // The TCP does not move (a reorientation): the ToPoint is the end.
                return last;
            }
            first_at_or_past(samples, start_tcp, (total - finite(d)).max(0.0))
        }
    }
}

/// The TCP positions of the samples, after the start.
fn points(samples: &[Sample], start_tcp: [f64; 3]) -> impl Iterator<Item = ([f64; 3], [f64; 3])> {
    let mut prev = start_tcp;
    samples.iter().map(move |x| {
        let p: [f64; 3] = x.tcp.translation.vector.into();
        let step = (prev, p);
        prev = p;
        step
    })
}

/// TCP path length (mm) from the start over every sample.
fn path_length(samples: &[Sample], start_tcp: [f64; 3]) -> f64 {
    points(samples, start_tcp).map(|(a, b)| dist(&a, &b)).sum()
}

/// The first sample at least `d` mm along the path (the last one when the path is shorter).
fn first_at_or_past(samples: &[Sample], start_tcp: [f64; 3], d: f64) -> usize {
    let mut s = 0.0;
    for (k, (a, b)) in points(samples, start_tcp).enumerate() {
        s += dist(&a, &b);
        // (1 µm: rounding of the sum.)
        if s + 1e-3 >= d {
            return k;
        }
    }
    samples.len().saturating_sub(1)
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let d = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
    if d.is_finite() { d } else { 0.0 }
}

/// Place every trigger on the samples, sorted by index (stable: the order of the
/// instruction's arguments among events of one cycle).
pub fn place_all(
    samples: &[Sample],
    start_tcp: [f64; 3],
    triggers: &[PathTrigger],
    dt: f64,
    out: &mut Vec<SegTrigger>,
) {
    out.clear();
    let last = samples.len().saturating_sub(1) as f64;
    for t in triggers {
        let at = sample_index(samples, start_tcp, t.place, dt) as f64;
        let lead = if t.lead_s.is_finite() {
            (t.lead_s / dt).round()
        } else {
            0.0
        };
        out.push(SegTrigger {
            key: t.key,
            at: (at - lead).clamp(0.0, last) as usize,
        });
    }
    out.sort_by_key(|t| t.at);
}
