//! The event log's numbers: every event-log entry rapidvc writes, in one table.
//!
//! Each [`EventKind`] has its number, title, severity, who chose the number ([`Origin`]),
//! when it happens (its doc comment) and what a RAPID program sees of it ([`Effect`]). The
//! robot, the motion core, EGM and the interpreter name their events by these kinds only, and
//! `docs/events.md` is generated from [`EventKind::ALL`] (`tests/catalogue.rs` keeps the two
//! equal), so an event cannot exist without its entry in the catalogue.
//!
//! Numbers: ABB's where ABB publishes one for the condition ([`Origin::Abb`], or
//! [`Origin::AbbReported`]); otherwise, for EGM, rapidvc's own in 90100–90199, a range ABB
//! does not use, so they can never be mistaken for an ABB event with another meaning (the
//! motion core and program execution would take 90200–90299 and 90300–90399).
//!
//! A few conditions are logged with a title and no number, and are not in this table: the
//! motion core's joint speed error, invalid or unsupported motion data, a move while the
//! motion is stopped or under external guidance, guidance away from a stop point
//! (`motion::MotionError::title`), a lost interrupt (`interp::interrupts`) and the EGM note on
//! a `\MaxSpeedDeviation` above the axis speed (`controller::egm_controller`). Numbering them
//! would change what rapidvc prints.
//!
//! This module is a leaf: every layer that writes events may use it.

/// How serious an event is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// For information.
    Info,
    /// The robot went on (e.g. a fly-by point became a stop point).
    Warning,
    /// The move was refused or the robot stopped.
    Error,
}

impl Severity {
    /// `info`, `warning` or `error`.
    pub fn name(self) -> &'static str {
        match self {
            Severity::Info => "info",
            Severity::Warning => "warning",
            Severity::Error => "error",
        }
    }
}

/// Who chose an event's number.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Origin {
    /// ABB's number and title for the condition, from ABB's manuals.
    Abb,
    /// ABB's number as known from controllers' event logs and user reports, not from a
    /// manual; the least certain mappings are marked so in the doc comment.
    AbbReported,
    /// rapidvc's own number: ABB publishes none for this condition.
    Rapidvc,
}

/// What a RAPID program sees of an event.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Effect {
    /// Logged; the program and the robot go on.
    Logged,
    /// The instruction fails with one of these RAPID errors (`ERR_…` names), which an
    /// `ERROR` handler can take.
    Raises(&'static [&'static str]),
    /// The program stops: no `ERROR` handler can take it.
    Stops,
}

/// Defines [`EventKind`]: for each kind its doc comment (when it happens), number, origin,
/// severity, title and effect.
macro_rules! events {
    ($(
        $(#[doc = $doc:literal])+
        $kind:ident = $number:literal, $origin:ident, $severity:ident, $title:literal, $effect:expr;
    )*) => {
        /// Every condition rapidvc writes to the event log. See the module documentation.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum EventKind {
            $( $(#[doc = $doc])+ $kind, )*
        }

        impl EventKind {
            /// Every event kind, in the table's order (by number).
            pub const ALL: &[EventKind] = &[$(EventKind::$kind),*];

            /// The event number.
            pub const fn number(self) -> u32 {
                match self { $(EventKind::$kind => $number,)* }
            }

            /// The fixed title.
            pub const fn title(self) -> &'static str {
                match self { $(EventKind::$kind => $title,)* }
            }

            /// How serious it is.
            pub const fn severity(self) -> Severity {
                match self { $(EventKind::$kind => Severity::$severity,)* }
            }

            /// Who chose the number.
            pub const fn origin(self) -> Origin {
                match self { $(EventKind::$kind => Origin::$origin,)* }
            }

            /// What a RAPID program sees of it.
            pub const fn effect(self) -> Effect {
                match self { $(EventKind::$kind => $effect,)* }
            }

            /// When it happens (the doc comment of the kind, one line per doc line).
            pub const fn when(self) -> &'static str {
                match self { $(EventKind::$kind => concat!($($doc, "\n"),+),)* }
            }
        }
    };
}

const UDPUC_COMM: Effect = Effect::Raises(&["ERR_UDPUC_COMM"]);
const ROBLIMIT: Effect = Effect::Raises(&["ERR_ROBLIMIT"]);

events! {
    /// `rapidvc serve`: the program pointer was moved to the entry routine (RWS `resetpp`,
    /// or a program run ended).
    PpReset = 10002, AbbReported, Info, "Program pointer has been reset", Effect::Logged;
    /// `rapidvc serve`: the motors were switched off (RWS `ctrlstate`); a running program
    /// stops.
    MotorsOff = 10010, AbbReported, Info, "Motors OFF state", Effect::Logged;
    /// `rapidvc serve`: the motors were switched on.
    MotorsOn = 10011, AbbReported, Info, "Motors ON state", Effect::Logged;
    /// `rapidvc serve`: the program was started (RWS `start`).
    ProgramStarted = 10150, AbbReported, Info, "Program started", Effect::Logged;
    /// `rapidvc serve`: the program stopped (RWS `stop`, motors off, a mode change, the end
    /// of a single cycle, `Stop`, `EXIT`).
    ProgramStopped = 10151, AbbReported, Info, "Program stopped", Effect::Logged;
    /// No valid sensor message within the run's `\CommTimeout`. The EGM movement ends
    /// (ramping down) and raises `ERR_UDPUC_COMM`; after `\NoWaitCond` it stops the program.
    CommTimeout = 41822, Abb, Error, "No data from the UdpUc device", UDPUC_COMM;
    /// An EGM movement that does not fit the identity's setup or activation: EGMRunJoint
    /// after EGMActPose, EGMRunPose after EGMActJoint, a pose movement on a joint setup.
    ModeMismatch = 41826, Abb, Error, "EGM mode mismatch", Effect::Stops;
    /// Sending a datagram to, or receiving one from, the UdpUc device failed at the
    /// operating system; the session goes on (the communication time-out decides).
    SendError = 41830, Abb, Warning, "Error sending EGM UdpUc message", Effect::Logged;
    /// A fly-by point became a stop point: the next move was not planned in time, or its
    /// corner path could not be built.
    CornerPathFailure = 50024, AbbReported, Warning, "Corner path failure", Effect::Logged;
    /// A move, or an EGM reference, comes too close to a wrist, arm or boundary singularity.
    /// The least certain of the ABB numbers rapidvc uses. (Under EGM the run ends and the
    /// program stops, as for every EGM supervision error.)
    Singularity = 50026, AbbReported, Error, "Close to singularity", ROBLIMIT;
    /// An axis value outside its working range (at the target, along the path, or asked for
    /// by EGM; under EGM the run ends and the program stops).
    JointOutOfRange = 50027, AbbReported, Error, "Joint out of range", ROBLIMIT;
    /// No arm configuration reaches the position (`ERR_OUTSIDE_REACH`), or a position, an
    /// orientation or an axis value is not a finite number (`ERR_OUTSIDE_REACH`), or the
    /// programmed configuration cannot reach a reachable position under `ConfJ\On`/`ConfL\On`
    /// (`ERR_ROBLIMIT`; ABB's event for this is one of two candidates). Under EGM the run
    /// ends and the program stops.
    OutsideReach = 50050, AbbReported, Error, "Position outside reach",
        Effect::Raises(&["ERR_OUTSIDE_REACH", "ERR_ROBLIMIT"]);
    /// MoveC: start, circle point and target do not define a circle (points too close
    /// together or on one line). ABB's number as remembered, unverified.
    CircleUncertain = 50063, AbbReported, Error, "Circle uncertain", Effect::Stops;
    /// Path correction (EGMMoveL/EGMMoveC) with an External Motion Interface Data profile
    /// that is not of Level 2.
    CyclicError = 50452, Abb, Error, "External Interface Cyclic Error", Effect::Stops;
    /// `ErrWrite` without `\W`: the program's own error entry.
    ErrWriteError = 80001, AbbReported, Error, "ErrWrite", Effect::Logged;
    /// `ErrWrite \W`: the program's own warning entry.
    ErrWriteWarning = 80002, AbbReported, Warning, "ErrWrite warning", Effect::Logged;
    /// A datagram from another address than the device's remote address (or, with the
    /// default filter, from the sensor's host at another port); it is dropped.
    UnexpectedSender = 90101, Rapidvc, Warning, "EGM datagram from an unexpected address",
        Effect::Logged;
    /// A datagram that does not decode as the mode's sensor message; it is dropped.
    Malformed = 90102, Rapidvc, Warning, "Malformed EGM datagram", Effect::Logged;
    /// A datagram longer than 1024 bytes (received, or a message rapidvc would send); it is
    /// dropped.
    Oversized = 90103, Rapidvc, Warning, "EGM datagram too large", Effect::Logged;
    /// A reference with NaN or infinity, without a target or a required value, or with a zero
    /// quaternion; also a path correction that is not finite. It is dropped.
    InvalidReference = 90104, Rapidvc, Warning, "Invalid EGM reference", Effect::Logged;
    /// A reference outside the configured bounds or beyond an axis limit; it is dropped
    /// (ABB's title, its number is not public).
    OutOfBounds = 90105, Rapidvc, Warning, "External Motion Interface input out of bounds",
        Effect::Logged;
    /// The header's message type contradicts the mode (`CORRECTION` in a path-correction
    /// session, `PATH_CORRECTION` in a guidance session); the datagram is dropped.
    WrongMessageType = 90106, Rapidvc, Warning, "EGM message type does not match the mode",
        Effect::Logged;
    /// The robot feedback to send is not finite; the datagram is not sent.
    FeedbackNotFinite = 90107, Rapidvc, Warning, "EGM feedback not finite", Effect::Logged;
    /// The one-per-cycle receive queue overflowed (the sensor sends faster than the EGM
    /// cycle); the oldest message is dropped.
    QueueOverflow = 90108, Rapidvc, Warning, "EGM receive queue overflow", Effect::Logged;
    /// `\MaxSpeedDeviation` starts limiting the EGM speed (at the default 1 °/s it usually
    /// does).
    SpeedLimited = 90110, Rapidvc, Info, "EGM speed limited by MaxSpeedDeviation",
        Effect::Logged;
    /// `\MaxPosDeviation` clamps the EGM position.
    PositionClamped = 90111, Rapidvc, Info, "EGM position clamped by MaxPosDeviation",
        Effect::Logged;
    /// The EGM command is held at an axis limit: the robot never crosses a joint limit.
    AxisLimit = 90112, Rapidvc, Warning, "EGM command held at an axis limit", Effect::Logged;
    /// A speed reference was zeroed or scaled (close to a singularity, above an axis speed).
    SpeedRefLimited = 90113, Rapidvc, Info, "EGM speed reference limited", Effect::Logged;
    /// A signal of a signal source (EGMSetupAI/AO/GI, `\DIFromSensor`) could not be read or
    /// written. Logged when a single value fails; it stops the program when the guidance
    /// cannot go on.
    SignalSource = 90114, Rapidvc, Error, "EGM signal source error", Effect::Stops;
    /// The built-in sensor could not answer (its pattern cannot be used); the program stops
    /// when the setup needs it.
    BuiltinSensor = 90115, Rapidvc, Error, "Built-in EGM sensor error", Effect::Stops;
    /// The UdpUc device's socket cannot be opened (the local port is in use, the address
    /// cannot be bound).
    DeviceOpen = 90116, Rapidvc, Error, "EGM UdpUc device cannot be opened", UDPUC_COMM;
    /// EGMGetId with all four EGM identities of the task reserved.
    TooManyIdentities = 90120, Rapidvc, Error, "Too many EGM identities", Effect::Stops;
    /// An EGM instruction on an identity that is not reserved (never, or released by
    /// EGMReset).
    NotReserved = 90121, Rapidvc, Error, "EGM identity not reserved", Effect::Stops;
    /// An activation, movement or stream start on an identity without a setup.
    NotSetUp = 90122, Rapidvc, Error, "EGM identity not set up", Effect::Stops;
    /// An EGM movement on an identity that is not activated.
    NotActivated = 90123, Rapidvc, Error, "EGM identity not activated", Effect::Stops;
    /// An EGM argument outside its allowed values (a `\SampleRate` that is not a multiple of
    /// 4 ms, a negative time, a NaN, …).
    ArgumentValue = 90124, Rapidvc, Error, "EGM argument value error", Effect::Stops;
    /// A motion profile (ExtConfigName) or a UdpUc device that does not exist or cannot be
    /// used.
    Configuration = 90125, Rapidvc, Error, "EGM configuration error", Effect::Stops;
    /// An EGM instruction on an identity that is running or streaming, or too many
    /// corrected moves queued in one path-correction sequence.
    Busy = 90126, Rapidvc, Error, "EGM identity busy", Effect::Stops;
    /// An EGM feature rapidvc does not model (named in the detail).
    NotSupported = 90127, Rapidvc, Error, "Not supported by rapidvc", Effect::Stops;
    /// An EGM movement, or a path-corrected sequence, that does not start in a fine point.
    NotInFinePoint = 90128, Rapidvc, Error, "EGM movement not started in a fine point",
        Effect::Stops;
    /// An EGM movement before any RAPID movement since the controller started.
    NoPreviousMove = 90129, Rapidvc, Error, "EGM movement before any RAPID movement",
        Effect::Stops;
    /// An EGM setup or activation that cannot be used: frames, signals, trackers, units, tool
    /// or work object.
    BadSetup = 90130, Rapidvc, Error, "EGM setup error", Effect::Stops;
    /// A path-corrected sequence (EGMMoveL/EGMMoveC) whose last move does not end in a fine
    /// point.
    NotEndedInFinePoint = 90131, Rapidvc, Error, "EGM path correction not ended in a fine point",
        Effect::Stops;
    /// A path correction the controller does not use (too large, or too old); the previous
    /// correction stays.
    CorrectionRejected = 90132, Rapidvc, Warning, "EGM path correction rejected", Effect::Logged;
    /// `rapidvc serve`: an event the interpreter or controller printed that has no number of
    /// its own (an interrupt queue full, a file note, a motion warning without a number).
    ProgramEvent = 90200, Rapidvc, Info, "Program event", Effect::Logged;
    /// `rapidvc serve`: the program stopped on an error no handler took; the description
    /// holds the error and where it happened.
    ProgramError = 90201, Rapidvc, Error, "Program stopped on an error", Effect::Stops;
}
