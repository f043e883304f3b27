//! The servo delay of streams and path correction: the measured position is the commanded one a fixed number of ticks earlier.

use std::collections::VecDeque;
use std::time::Duration;

use crate::egm::types::Joints;

/// A fixed-length delay line of joint vectors (allocated once).
#[derive(Clone, Debug)]
pub(crate) struct DelayLine {
    buf: VecDeque<Joints>,
    steps: usize,
}

impl DelayLine {
    /// `delay` rounded to whole `tick`s, filled with `start`. The caller has checked the
    /// tick and delay bounds (`check_options`).
    pub(crate) fn new(delay: Duration, tick: Duration, start: Joints) -> DelayLine {
        let tick = tick.as_nanos().max(1);
        let steps = usize::try_from((delay.as_nanos() + tick / 2) / tick).unwrap_or(0);
        let mut buf = VecDeque::with_capacity(steps + 1);
        buf.extend(std::iter::repeat_n(start, steps));
        DelayLine { buf, steps }
    }

    /// Pushes this tick's command and returns the measured position.
    pub(crate) fn push(&mut self, commanded: Joints) -> Joints {
        self.buf.push_back(commanded);
        if self.buf.len() > self.steps {
            self.buf.pop_front().unwrap_or(commanded)
        } else {
            commanded
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delays_by_whole_ticks() {
        let ms = Duration::from_millis;
        let mut d = DelayLine::new(ms(12), ms(4), [0.0; 6]);
        let out: Vec<f64> = (1..=5).map(|k| d.push([f64::from(k); 6])[0]).collect();
        assert_eq!(out, [0.0, 0.0, 0.0, 1.0, 2.0]);
        let mut none = DelayLine::new(Duration::ZERO, ms(4), [0.0; 6]);
        assert_eq!(none.push([7.0; 6]), [7.0; 6]);
    }
}
