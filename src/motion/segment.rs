//! Planned segments: the per-cycle samples of one move (joints and TCP), the corner path that
//! blends into it from the previous fly-by point, and the buffers recycled between them.

use crate::robot::{JointsDeg, Pose};

use super::event::InstrRef;

/// The robot at one motion cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Axis values (deg).
    pub q: JointsDeg,
    /// The TCP of the move's tool in world coordinates (mm).
    pub tcp: Pose,
}

/// Where a corner path leaves the previous segment and joins this one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CornerSpan {
    /// Index of the previous segment's first sample that the corner replaces.
    pub enter_at: usize,
    /// Index of this segment's first own sample after the corner.
    pub resume_at: usize,
}

/// A position event of a segment: fires in the cycle that plays own sample `at` (or, when the
/// sample is replaced by a corner path, at the matching share of the corner path).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SegTrigger {
    /// The key the caller gave the event.
    pub key: u64,
    /// Index of the sample where it fires.
    pub at: usize,
}

/// One planned move, ready for the executor: a sample per motion cycle.
///
/// `samples[k]` is the robot at `(k + 1)` cycles after the move starts; the last sample is the
/// programmed target (reached at the end of the profile, so the last step may be shorter).
#[derive(Clone, Debug)]
pub struct Segment {
    /// The instruction.
    pub instr: InstrRef,
    /// Joints where the move starts (the previous segment's end).
    pub start: JointsDeg,
    /// One sample per cycle; never empty for a planned segment.
    pub samples: Vec<Sample>,
    /// The corner path from the previous fly-by point, when there is one.
    pub corner: Option<CornerSpan>,
    /// Samples of the corner path (valid when `corner` is set).
    pub corner_samples: Vec<Sample>,
    /// A stop point: the robot stands still at the end.
    pub fine: bool,
    /// A fly-by point with a non-empty zone.
    pub flyby: bool,
    /// Position events, sorted by sample index.
    pub triggers: Vec<SegTrigger>,
}

impl Segment {
    /// An empty segment (buffers without samples) for the planner to fill.
    pub fn empty() -> Segment {
        Segment {
            instr: InstrRef {
                id: 0,
                name: "",
                source: None,
            },
            start: [0.0; 6],
            samples: Vec::new(),
            corner: None,
            corner_samples: Vec::new(),
            fine: true,
            flyby: false,
            triggers: Vec::new(),
        }
    }

    /// Forget the content but keep the buffers' capacity.
    pub fn clear(&mut self) {
        self.samples.clear();
        self.corner = None;
        self.corner_samples.clear();
        self.triggers.clear();
    }

    /// The last sample (the target).
    pub fn end(&self) -> Option<&Sample> {
        self.samples.last()
    }
}
