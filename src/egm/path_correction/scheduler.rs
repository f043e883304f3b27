//! The corrector of one corrected sequence: its configuration, APTR and LATR scheduling of
//! measurements along the arc length, absolute or incremental totals, and the smoothed offset.

use std::collections::VecDeque;

use super::correction_check::check_magnitude;
use super::{
    CorrectionLimits, EPS_MM, PathOffset, Rejection, Smoother, SmoothingLimits, check_correction,
    non_negative_finite, positive,
};

/// At-point or look-ahead tracking (the `\APTR` and `\LATR` switches).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tracker {
    /// The sensor measures at the TCP: corrections apply at once.
    Aptr,
    /// The sensor measures `look_ahead` mm ahead of the TCP along the path.
    Latr {
        /// Distance of the sensor frame origin ahead of the TCP, mm (≥ 0).
        look_ahead: f64,
    },
}

/// Whether each correction is the total offset or adds to the previous one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CorrectionMode {
    /// Each correction is the total offset from the programmed path (default).
    #[default]
    Absolute,
    /// Each correction adds to the previous total.
    Incremental,
}

/// Everything a [`PathCorrector`] needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathCorrConfig {
    /// APTR or LATR.
    pub tracker: Tracker,
    /// Absolute or incremental corrections.
    pub mode: CorrectionMode,
    /// Rejection limits.
    pub limits: CorrectionLimits,
    /// Smoothing limits.
    pub smoothing: SmoothingLimits,
    /// Size of the LATR queue and of the TCP arc-length history (samples). Default 512
    /// (about 2 s of history at a 4 ms step).
    pub capacity: usize,
}

impl PathCorrConfig {
    /// Defaults for an at-point tracker.
    pub fn aptr() -> Self {
        PathCorrConfig {
            tracker: Tracker::Aptr,
            mode: CorrectionMode::Absolute,
            limits: CorrectionLimits::default(),
            smoothing: SmoothingLimits::default(),
            capacity: 512,
        }
    }

    /// Defaults for a look-ahead tracker `look_ahead` mm ahead of the TCP.
    pub fn latr(look_ahead: f64) -> Self {
        PathCorrConfig {
            tracker: Tracker::Latr { look_ahead },
            ..Self::aptr()
        }
    }

    /// Check every value.
    pub fn validate(&self) -> Result<(), PathCorrConfigError> {
        let bad = |name: &'static str, value: f64, expected: &'static str| {
            Err(PathCorrConfigError {
                name,
                value,
                expected,
            })
        };
        let pos_text = "a positive number";
        let l = &self.limits;
        let s = &self.smoothing;
        if !(positive(l.max_offset) && l.max_offset.is_finite()) {
            return bad("max_offset", l.max_offset, "a positive finite number (mm)");
        }
        if !positive(l.max_age) {
            return bad("max_age", l.max_age, pos_text);
        }
        if !positive(s.max_speed) {
            return bad("max_speed", s.max_speed, pos_text);
        }
        if !positive(s.max_accel) {
            return bad("max_accel", s.max_accel, pos_text);
        }
        if let Tracker::Latr { look_ahead } = self.tracker
            && !non_negative_finite(look_ahead)
        {
            return bad(
                "look_ahead",
                look_ahead,
                "a distance ≥ 0 mm (a look-ahead sensor measures ahead of the TCP)",
            );
        }
        if !(2..=1 << 16).contains(&self.capacity) {
            return bad("capacity", self.capacity as f64, "2 to 65536 samples");
        }
        Ok(())
    }
}

/// A [`PathCorrConfig`] value that cannot be used.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("path correction {name} = {value}: expected {expected}")]
pub struct PathCorrConfigError {
    /// The field.
    pub name: &'static str,
    /// Its value.
    pub value: f64,
    /// What it must be.
    pub expected: &'static str,
}

/// A correction and the arc length at which it is (or was) the target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scheduled {
    /// Arc length of the TCP along the programmed path, mm.
    pub s: f64,
    /// The total correction there.
    pub offset: PathOffset,
}

/// The path-correction state of one corrected sequence (module doc: model).
///
/// Per motion step call [`PathCorrector::step`] with the time and the TCP's arc length
/// along the programmed path; it returns the offset to add (through
/// [`PathFrame::to_world`](super::PathFrame::to_world)). Per sensor reply call
/// [`PathCorrector::measurement`].
#[derive(Clone, Debug)]
pub struct PathCorrector {
    config: PathCorrConfig,
    enabled: bool,
    /// `(t, s)` samples of the TCP, oldest first (LATR only).
    history: VecDeque<(f64, f64)>,
    /// Queued LATR corrections, ascending `s`.
    pending: VecDeque<Scheduled>,
    /// The last point passed.
    anchor: Scheduled,
    /// The latest total correction received (for incremental mode).
    total: PathOffset,
    target: PathOffset,
    smoother: Smoother,
    last: Option<(f64, f64)>,
    overflows: u64,
}

impl PathCorrector {
    /// A corrector at zero offset, arc length 0 (see [`PathCorrector::start`]). Allocates
    /// its buffers here, once.
    pub fn new(config: PathCorrConfig) -> Result<Self, PathCorrConfigError> {
        config.validate()?;
        Ok(PathCorrector {
            config,
            enabled: true,
            history: VecDeque::with_capacity(config.capacity),
            pending: VecDeque::with_capacity(config.capacity),
            anchor: Scheduled {
                s: 0.0,
                offset: PathOffset::ZERO,
            },
            total: PathOffset::ZERO,
            target: PathOffset::ZERO,
            smoother: Smoother::new(config.smoothing),
            last: None,
            overflows: 0,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &PathCorrConfig {
        &self.config
    }

    /// Begin a corrected sequence at time `now` (s) and arc length `s` (mm): zero offset,
    /// nothing queued.
    pub fn start(&mut self, now: f64, s: f64) {
        self.history.clear();
        self.pending.clear();
        let s = if s.is_finite() { s } else { 0.0 };
        self.anchor = Scheduled {
            s,
            offset: PathOffset::ZERO,
        };
        self.total = PathOffset::ZERO;
        self.target = PathOffset::ZERO;
        self.smoother.reset();
        self.last = None;
        if now.is_finite() {
            self.record(now, s);
        }
    }

    /// Change the look-ahead distance (mm) of a LATR tracker, e.g. when the path direction
    /// relative to the sensor changes; ignored for APTR and for a negative or non-finite
    /// distance.
    pub fn set_look_ahead(&mut self, look_ahead: f64) {
        if let Tracker::Latr { look_ahead: d } = &mut self.config.tracker
            && non_negative_finite(look_ahead)
        {
            *d = look_ahead;
        }
    }

    /// Switch correction on or off (`\NoCorr`): while off, the target is zero (the applied
    /// offset ramps out) and measurements are checked but not used.
    pub fn set_enabled(&mut self, enabled: bool) {
        self.enabled = enabled;
    }

    /// The offset applied at the last step.
    pub fn applied(&self) -> PathOffset {
        self.smoother.applied()
    }

    /// The target at the last step (before smoothing).
    pub fn target(&self) -> PathOffset {
        self.target
    }

    /// Corrections queued for a later arc length (LATR).
    pub fn pending(&self) -> usize {
        self.pending.len()
    }

    /// How many queued corrections were dropped because the queue was full.
    pub fn overflows(&self) -> u64 {
        self.overflows
    }

    fn record(&mut self, now: f64, s: f64) {
        if !matches!(self.config.tracker, Tracker::Latr { .. }) {
            return;
        }
        if self.history.back().is_some_and(|&(t, _)| now <= t) {
            return;
        }
        if self.history.len() >= self.config.capacity {
            self.history.pop_front();
        }
        self.history.push_back((now, s));
    }

    /// The TCP's arc length at time `t` from the history (clamped to its ends).
    fn s_at(&self, t: f64) -> f64 {
        let fallback = self.last.map(|(_, s)| s).unwrap_or(self.anchor.s);
        let mut later: Option<(f64, f64)> = None;
        for &(ti, si) in self.history.iter().rev() {
            if ti <= t {
                return match later {
                    Some((tl, sl)) if tl > ti => si + (sl - si) * (t - ti) / (tl - ti),
                    _ => si,
                };
            }
            later = Some((ti, si));
        }
        later.map(|(_, s)| s).unwrap_or(fallback)
    }

    /// A sensor correction `pos` (x, y, z in the path frame, mm; x ignored) received at
    /// `now` (s), measured `age` seconds earlier. Returns where it is scheduled, or why it
    /// was rejected (the previous corrections stay in force).
    pub fn measurement(
        &mut self,
        now: f64,
        pos: [f64; 3],
        age: f64,
    ) -> Result<Scheduled, Rejection> {
        let offset = check_correction(pos, age, &self.config.limits)?;
        let total = match self.config.mode {
            CorrectionMode::Absolute => offset,
            CorrectionMode::Incremental => {
                let t = self.total.add(offset);
                check_magnitude(t, &self.config.limits)?;
                t
            }
        };
        let s_now = self.last.map(|(_, s)| s).unwrap_or(self.anchor.s);
        let s_apply = match self.config.tracker {
            Tracker::Aptr => s_now,
            Tracker::Latr { look_ahead } => {
                let t = if now.is_finite() { now - age } else { f64::NAN };
                let s = if t.is_finite() { self.s_at(t) } else { s_now };
                s + look_ahead
            }
        };
        self.total = total;
        let entry = Scheduled {
            s: s_apply,
            offset: total,
        };
        if !self.enabled {
            return Ok(entry);
        }
        while self.pending.back().is_some_and(|p| p.s >= s_apply) {
            self.pending.pop_back();
        }
        if s_apply <= s_now {
            self.anchor = Scheduled {
                s: s_now,
                offset: total,
            };
            self.target = total;
        } else {
            if self.pending.len() >= self.config.capacity
                && let Some(front) = self.pending.pop_front()
            {
                self.anchor = front;
                self.overflows = self.overflows.saturating_add(1);
            }
            self.pending.push_back(entry);
        }
        Ok(entry)
    }

    /// One motion step at time `now` (s) with the TCP at arc length `s` (mm) along the
    /// programmed path: returns the path-frame offset to apply. The first step after
    /// [`PathCorrector::start`] (or a step with a non-increasing or non-finite time) does
    /// not move the offset.
    pub fn step(&mut self, now: f64, s: f64) -> PathOffset {
        let s = if s.is_finite() {
            s
        } else {
            self.last.map(|(_, s)| s).unwrap_or(self.anchor.s)
        };
        let dt = match self.last {
            Some((t0, _)) if now.is_finite() => now - t0,
            _ => 0.0,
        };
        if now.is_finite() && dt >= 0.0 {
            self.record(now, s);
            self.last = Some((now, s));
        }
        while let Some(front) = self.pending.front().copied() {
            if front.s > s {
                break;
            }
            self.anchor = front;
            self.pending.pop_front();
        }
        self.target = if !self.enabled {
            PathOffset::ZERO
        } else {
            match self.pending.front() {
                None => self.anchor.offset,
                Some(next) => {
                    let span = next.s - self.anchor.s;
                    if span > EPS_MM {
                        let t = ((s - self.anchor.s) / span).clamp(0.0, 1.0);
                        PathOffset::lerp(self.anchor.offset, next.offset, t)
                    } else {
                        self.anchor.offset
                    }
                }
            }
        };
        self.smoother.step(self.target, dt)
    }
}
