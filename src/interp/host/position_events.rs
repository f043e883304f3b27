//! The position-event capability of a host ([`PositionEventHost`]): what `TriggL`/`TriggJ`/
//! `TriggC`, the `Move…DO/AO/GO/Sync` instructions and the searches ask of the controller.
//! A host without it returns `None` from [`super::Host::position_events`] and those
//! instructions stop the program with "… is not supported by this controller".

use std::time::Duration;

use crate::robot::command::MotionCommand;
use crate::robot::trigger::TriggPlace;

use super::HostError;

/// What a position event does when the TCP gets to its place.
#[derive(Clone, Debug, PartialEq)]
pub enum TriggAction {
    /// Write an output signal (`TriggIO`, `TriggEquip`, `MoveLDO`, `MoveLAO`, `MoveLGO`).
    /// Written by the controller in the motion cycle of the event.
    Signal {
        /// The signal's name.
        name: String,
        /// Its new logical value.
        value: f64,
    },
    /// From the event on, drive the analog output with the TCP speed (`TriggSpeed`):
    /// `scale × speed (mm/s)`, clamped to the signal's range; a scale of 0 writes 0 and ends
    /// it.
    Speed {
        /// The analog output.
        name: String,
        /// The scale.
        scale: f64,
    },
    /// Something the program does: handed back by
    /// [`PositionEventHost::take_program_events`].
    Program(ProgramAction),
}

/// A position event the program itself handles.
#[derive(Clone, Debug, PartialEq)]
pub enum ProgramAction {
    /// Order the interrupt (`TriggInt`).
    Interrupt(i32),
    /// Call the procedure (`MoveLSync`).
    Call(String),
}

/// One position event of a move.
#[derive(Clone, Debug, PartialEq)]
pub struct TriggEvent {
    /// Where it fires.
    pub place: TriggPlace,
    /// Fire this many seconds earlier than the place (`TriggEquip`'s `EquipLag`; negative:
    /// later, up to the end of the move).
    pub lead_s: f64,
    /// What it does.
    pub action: TriggAction,
}

/// How a search stops when it finds the signal (`SearchL \Stop | \PStop | \SStop`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SearchStop {
    /// `\Stop`: as fast as the axes allow.
    Stop,
    /// `\PStop`: a path stop.
    PStop,
    /// `\SStop`: a soft stop.
    SStop,
}

/// A controller whose moves carry position events.
pub trait PositionEventHost {
    /// Queue `cmd` (its id is replaced) as the RAPID instruction `name` with `events` on it.
    /// Returns the move's id.
    fn submit_with_events(
        &mut self,
        cmd: MotionCommand,
        name: &'static str,
        events: Vec<TriggEvent>,
    ) -> Result<u64, HostError>;

    /// The program's position events that fired since the last call, oldest first.
    fn take_program_events(&mut self) -> Vec<ProgramAction>;

    /// True while moves with program events are queued or running (so the interpreter
    /// keeps asking between statements).
    fn program_events_pending(&self) -> bool;

    /// Stop the robot on the path (a search found its signal): drop the rest of the moves and
    /// brake to rest within the axis limits; planning goes on from where it stops.
    fn search_stop(&mut self, how: SearchStop) -> Result<(), HostError>;

    /// The motion cycle (a search looks at its signal once per cycle).
    fn motion_period(&self) -> Duration;
}
