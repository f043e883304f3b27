//! The robot's latest position, published by the motion thread every cycle and read by
//! services (Robot Web Services' `jointtarget` and `robtarget`) without a lock: a sequence
//! lock over atomics.
//!
//! The writer (the motion cycle) never waits: it makes the sequence number odd, stores the
//! values, and makes it even again. A reader takes the values between two equal even
//! sequence numbers and tries again when the writer was in between (a few hundred
//! nanoseconds at most, once per cycle). Every value is an atomic, so a torn read is
//! detected, never undefined.

use std::sync::atomic::{AtomicU64, Ordering, fence};

use crate::robot::JointsDeg;

/// How often a reader retries before it yields the processor to the writer.
const SPINS_BEFORE_YIELD: u32 = 64;

/// One published sample: the cycle's robot time and its axis values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PositionSample {
    /// Robot time of the cycle (s since the controller started).
    pub time: f64,
    /// Axis values (deg).
    pub joints: JointsDeg,
    /// How many samples were published before this one (0: none yet, the start position).
    pub seq: u64,
}

/// The cell (see the module doc).
#[derive(Debug)]
pub struct PositionCell {
    /// Even: stable; odd: being written.
    seq: AtomicU64,
    time: AtomicU64,
    joints: [AtomicU64; 6],
}

impl PositionCell {
    /// A cell holding `joints` at time 0.
    pub fn new(joints: &JointsDeg) -> PositionCell {
        PositionCell {
            seq: AtomicU64::new(0),
            time: AtomicU64::new(0f64.to_bits()),
            joints: joints.map(|j| AtomicU64::new(j.to_bits())),
        }
    }

    /// Publish a sample (the motion thread, once per cycle; never blocks).
    pub fn store(&self, time: f64, joints: &JointsDeg) {
        let s = self.seq.load(Ordering::Relaxed);
        self.seq.store(s.wrapping_add(1), Ordering::Relaxed);
        fence(Ordering::Release);
        self.time.store(time.to_bits(), Ordering::Relaxed);
        for (cell, j) in self.joints.iter().zip(joints) {
            cell.store(j.to_bits(), Ordering::Relaxed);
        }
        self.seq.store(s.wrapping_add(2), Ordering::Release);
    }

    /// The latest complete sample.
    pub fn load(&self) -> PositionSample {
        let mut spins = 0u32;
        loop {
            let before = self.seq.load(Ordering::Acquire);
            if before.is_multiple_of(2) {
                let time = f64::from_bits(self.time.load(Ordering::Relaxed));
                let joints = self
                    .joints
                    .each_ref()
                    .map(|c| f64::from_bits(c.load(Ordering::Relaxed)));
                fence(Ordering::Acquire);
                if self.seq.load(Ordering::Relaxed) == before {
                    return PositionSample {
                        time,
                        joints,
                        seq: before / 2,
                    };
                }
            }
            spins += 1;
            if spins >= SPINS_BEFORE_YIELD {
                spins = 0;
                std::thread::yield_now();
            } else {
                std::hint::spin_loop();
            }
        }
    }
}

#[cfg(test)]
#[allow(clippy::expect_used)]
mod tests {
    use super::*;
    use std::sync::Arc;
    use std::sync::atomic::AtomicBool;

    #[test]
    fn a_reader_sees_the_latest_sample() {
        let c = PositionCell::new(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        assert_eq!(c.load().seq, 0);
        assert_eq!(c.load().joints[5], 6.0);
        c.store(0.004, &[10.0; 6]);
        let s = c.load();
        assert_eq!((s.seq, s.time, s.joints), (1, 0.004, [10.0; 6]));
    }

    #[test]
    fn readers_never_see_a_torn_sample() {
        // The writer stores samples whose values all equal the time; a reader that mixed
        // two samples would see different values.
        let c = Arc::new(PositionCell::new(&[0.0; 6]));
        let done = Arc::new(AtomicBool::new(false));
        let writer = {
            let (c, done) = (Arc::clone(&c), Arc::clone(&done));
            std::thread::spawn(move || {
                for i in 1..=200_000u32 {
                    let v = f64::from(i);
                    c.store(v, &[v; 6]);
                }
                done.store(true, Ordering::Release);
            })
        };
        let mut reads = 0u64;
        let mut last = 0.0;
        while !done.load(Ordering::Acquire) || reads == 0 {
            let s = c.load();
            assert!(s.joints.iter().all(|j| *j == s.time), "torn: {s:?}");
            assert!(s.time >= last, "went back: {} after {last}", s.time);
            last = s.time;
            reads += 1;
        }
        writer.join().expect("writer");
        assert_eq!(c.load().time, 200_000.0);
    }
}
