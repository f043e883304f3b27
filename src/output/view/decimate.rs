//! Error-bounded thinning of a sampled signal (the "swinging door" of process historians):
//! a point is dropped when the straight line between the points kept on either side passes
//! within a tolerance of it, in every dimension. The page interpolates linearly between the
//! kept points, so what it draws at any time is within the tolerance of the motion cycle's
//! value. O(dimensions) per point, no buffering.

/// The state of one segment: where it starts and which slopes still pass every point since.
#[derive(Clone, Debug)]
pub struct Door<const N: usize> {
    tol: [f64; N],
    anchor: Option<(f64, [f64; N])>,
    lo: [f64; N],
    hi: [f64; N],
}

impl<const N: usize> Door<N> {
    /// A door with one tolerance per dimension (same units as the values).
    pub fn new(tol: [f64; N]) -> Door<N> {
        Door {
            tol,
            anchor: None,
            lo: [f64::NEG_INFINITY; N],
            hi: [f64::INFINITY; N],
        }
    }

    /// Start a new segment at a kept point.
    pub fn restart(&mut self, t: f64, v: [f64; N]) {
        self.anchor = Some((t, v));
        self.lo = [f64::NEG_INFINITY; N];
        self.hi = [f64::INFINITY; N];
    }

    /// The start of the current segment.
    pub fn anchor_time(&self) -> Option<f64> {
        self.anchor.map(|(t, _)| t)
    }

    /// True when the segment can end at `(t, v)` with every point offered since the anchor
    /// within tolerance of the line; the point then counts as one of those points. False
    /// (nothing changed) when it cannot: the caller keeps the previous point and restarts
    /// there. Non-finite values never fit.
    pub fn admits(&mut self, t: f64, v: [f64; N]) -> bool {
        let Some((t0, v0)) = self.anchor else {
            return false;
        };
        let dt = t - t0;
        if dt <= 0.0 || !v.iter().all(|x| x.is_finite()) {
            return false;
        }
        let fits = (0..N).all(|k| {
            let s = (v[k] - v0[k]) / dt;
            s >= self.lo[k] && s <= self.hi[k]
        });
        if fits {
            for k in 0..N {
                self.lo[k] = self.lo[k].max((v[k] - self.tol[k] - v0[k]) / dt);
                self.hi[k] = self.hi[k].min((v[k] + self.tol[k] - v0[k]) / dt);
            }
        }
        fits
    }
}

/// Keeps the points of a stream that a [`Door`] cannot drop. `R` is the row type; `key`
/// gives a row's time and values.
#[derive(Clone, Debug)]
pub struct Thinner<R: Copy, const N: usize> {
    door: Door<N>,
    /// The last row offered and not kept yet, with its time and values.
    pending: Option<(R, f64, [f64; N])>,
    /// A segment never spans more than this (s), so slow drifts and the rows' other fields
    /// (speed, flags) are sampled at least this often.
    max_gap: f64,
}

impl<R: Copy, const N: usize> Thinner<R, N> {
    /// A thinner with tolerances `tol` and the longest gap `max_gap` (s).
    pub fn new(tol: [f64; N], max_gap: f64) -> Thinner<R, N> {
        Thinner {
            door: Door::new(tol),
            pending: None,
            max_gap,
        }
    }

    /// Offer the next row (time `t`, values `v`); `force` keeps it whatever the values
    /// (and the row before it, so a step is drawn as a step). Rows to keep are pushed onto
    /// `out` in time order.
    pub fn offer(&mut self, row: R, t: f64, v: [f64; N], force: bool, out: &mut Vec<R>) {
        let first = self.door.anchor_time().is_none();
        let too_long = self
            .door
            .anchor_time()
            .is_some_and(|t0| t - t0 > self.max_gap);
        if first || force {
            if let Some((p, _, _)) = self.pending.take() {
                out.push(p);
            }
            out.push(row);
            self.door.restart(t, v);
            return;
        }
        if !too_long && self.door.admits(t, v) {
            self.pending = Some((row, t, v));
            return;
        }
        match self.pending.take() {
            Some((p, tp, vp)) => {
                out.push(p);
                // Restart at the kept row; the new row always fits the fresh segment unless
                // its values are not finite, then it is kept on its own.
                self.door.restart(tp, vp);
                if self.door.admits(t, v) {
                    self.pending = Some((row, t, v));
                } else {
                    out.push(row);
                    self.door.restart(t, v);
                }
            }
            None => {
                out.push(row);
                self.door.restart(t, v);
            }
        }
    }

    /// The row offered last and not kept yet (it ends the current segment).
    pub fn pending(&self) -> Option<R> {
        self.pending.map(|(r, _, _)| r)
    }

    /// The stream ended: keep the pending row.
    pub fn flush(&mut self, out: &mut Vec<R>) {
        if let Some((p, _, _)) = self.pending.take() {
            out.push(p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Linear interpolation of the kept points at `t`.
    fn interp(kept: &[(f64, f64)], t: f64) -> f64 {
        let i = kept.partition_point(|(tk, _)| *tk <= t);
        match (kept.get(i.wrapping_sub(1)), kept.get(i)) {
            (Some(a), Some(b)) => a.1 + (b.1 - a.1) * (t - a.0) / (b.0 - a.0),
            (Some(a), None) => a.1,
            (None, Some(b)) => b.1,
            (None, None) => f64::NAN,
        }
    }

    #[test]
    fn every_dropped_point_is_within_tolerance() {
        let tol = 0.01;
        let mut th = Thinner::<(f64, f64), 1>::new([tol], 10.0);
        let mut kept = Vec::new();
        let signal: Vec<(f64, f64)> = (0..20_000)
            .map(|k| {
                let t = k as f64 * 0.004;
                // A ramp, a standstill, a sine and a step.
                let v = match t {
                    t if t < 10.0 => 3.0 * t,
                    t if t < 20.0 => 30.0,
                    t if t < 60.0 => 30.0 + 5.0 * (t * 0.7).sin(),
                    _ => -4.0,
                };
                (t, v)
            })
            .collect();
        for &(t, v) in &signal {
            th.offer((t, v), t, [v], false, &mut kept);
        }
        th.flush(&mut kept);
        assert!(kept.len() < signal.len() / 10, "kept {}", kept.len());
        assert_eq!(kept.first(), signal.first());
        assert_eq!(kept.last(), signal.last());
        for &(t, v) in &signal {
            let e = (interp(&kept, t) - v).abs();
            // The step at t = 60 is a jump between two cycles: a line joins them.
            if (t - 60.0).abs() > 0.005 {
                assert!(e <= tol + 1e-9, "t={t}: off by {e}");
            }
        }
    }

    #[test]
    fn forced_rows_and_their_predecessors_are_kept_and_gaps_are_bounded() {
        let mut th = Thinner::<u32, 1>::new([1.0], 0.5);
        let mut kept = Vec::new();
        for k in 0..100u32 {
            let t = f64::from(k) * 0.1;
            th.offer(k, t, [0.0], k == 40, &mut kept);
        }
        th.flush(&mut kept);
        assert!(kept.contains(&39) && kept.contains(&40), "{kept:?}");
        for w in kept.windows(2) {
            assert!(f64::from(w[1] - w[0]) * 0.1 <= 0.5 + 0.11, "{kept:?}");
        }
        assert_eq!(kept.first(), Some(&0));
        assert_eq!(kept.last(), Some(&99));
    }

    #[test]
    fn non_finite_values_are_kept_on_their_own() {
        let mut th = Thinner::<u32, 1>::new([1.0], 10.0);
        let mut kept = Vec::new();
        for (k, v) in [0.0, 0.0, f64::NAN, 0.0, 0.0].into_iter().enumerate() {
            th.offer(k as u32, k as f64, [v], false, &mut kept);
        }
        th.flush(&mut kept);
        assert!(kept.contains(&2), "{kept:?}");
    }
}
