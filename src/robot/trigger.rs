//! Where on a move a position event fires (`TriggIO`, `TriggEquip`, `TriggInt`,
//! `TriggSpeed`, `MoveLDO` and the other `Move…DO/AO/GO/Sync` instructions): the place as RAPID
//! gives it, handed to the planner, which turns it into the motion cycle where the TCP gets
//! there.

/// The place of a position event on one move.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TriggPlace {
    /// This many mm before the ToPoint, along the TCP path (the middle of the corner path
    /// for a fly-by point). 0 = at the ToPoint.
    BeforeEnd(f64),
    /// This many mm after the start point (`\Start`).
    AfterStart(f64),
    /// This many seconds before the robot reaches the ToPoint (`\Time`).
    BeforeEndTime(f64),
}

/// One position event of a move: a key the caller chose (handed back when it fires) and
/// its place.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathTrigger {
    /// The caller's key.
    pub key: u64,
    /// Where it fires.
    pub place: TriggPlace,
    /// Fire this many seconds (of motion cycles) before the place; negative: after it, up
    /// to the end of the move.
    pub lead_s: f64,
}
