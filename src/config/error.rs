//! Diagnostics of the CFG reader and the domain readers (`rapidvc::config::…`).

use miette::Diagnostic;

use crate::diag::RapidDiagnostic;
use crate::source::{SourceId, Span};

/// An error or warning about a CFG file. Every variant but [`ConfigError::Io`] points into
/// the file through a [`Span`].
#[derive(Debug, Clone, PartialEq, thiserror::Error, Diagnostic)]
pub enum ConfigError {
    /// The configuration directory or a file in it cannot be read.
    #[error("cannot read {path}: {message}")]
    #[diagnostic(code(rapidvc::config::io))]
    Io {
        /// The path.
        path: String,
        /// The operating system's message.
        message: String,
    },

    /// The first line is not a CFG header.
    #[error("this is not an ABB CFG file: the first line is not a CFG header")]
    #[diagnostic(
        code(rapidvc::config::bad_header),
        help("a CFG file starts with a line such as `EIO:CFG_1.0:6:1::`")
    )]
    BadHeader {
        /// The file.
        src: SourceId,
        /// The first line.
        #[label("expected `DOMAIN:CFG_1.0:major:minor::`")]
        span: Span,
    },

    /// The header names another domain than the file name says.
    #[error("{file} holds the {found} domain, not {expected}")]
    #[diagnostic(
        code(rapidvc::config::wrong_domain),
        help("the header of {file} starts with `{expected}:CFG_1.0:`")
    )]
    WrongDomain {
        /// The file.
        src: SourceId,
        /// The domain in the header.
        #[label("domain {found}")]
        span: Span,
        /// The file name.
        file: String,
        /// The expected domain (`EIO`).
        expected: String,
        /// The domain found.
        found: String,
    },

    /// A string value without its closing quote.
    #[error("unterminated string")]
    #[diagnostic(
        code(rapidvc::config::unterminated_string),
        help("close the string with `\"` on the same line")
    )]
    UnterminatedString {
        /// The file.
        src: SourceId,
        /// From the opening quote to the end of the line.
        #[label("this string has no closing quote")]
        span: Span,
    },

    /// A backslash that is not the last character of its line.
    #[error("a backslash continues an instance only at the end of a line")]
    #[diagnostic(code(rapidvc::config::stray_backslash))]
    StrayBackslash {
        /// The file.
        src: SourceId,
        /// The backslash.
        #[label("text follows this backslash")]
        span: Span,
    },

    /// A value or word where an attribute (`-Name`) must come.
    #[error("expected an attribute such as `-Name`, found `{found}`")]
    #[diagnostic(
        code(rapidvc::config::expected_attribute),
        help("an instance is a list of `-Attribute value` pairs; attribute names start with `-`")
    )]
    ExpectedAttribute {
        /// The file.
        src: SourceId,
        /// The offending token.
        #[label("not an attribute")]
        span: Span,
        /// Its text.
        found: String,
    },

    /// After a `#` line, something other than a type header.
    #[error("expected a type name such as `EIO_SIGNAL:` after `#`")]
    #[diagnostic(
        code(rapidvc::config::expected_type),
        help("a section is a line `#`, then the type name with a colon, then its instances")
    )]
    ExpectedType {
        /// The file.
        src: SourceId,
        /// The offending line.
        #[label("not a type header")]
        span: Span,
    },

    /// An instance before the first type header.
    #[error("instance outside any section")]
    #[diagnostic(
        code(rapidvc::config::no_section),
        help("put `#` and a type name such as `EIO_SIGNAL:` before the instances")
    )]
    NoSection {
        /// The file.
        src: SourceId,
        /// The instance.
        #[label("which type is this?")]
        span: Span,
    },

    /// An attribute given twice in one instance (the first value is used).
    #[error("attribute `-{name}` is given twice; the first value is used")]
    #[diagnostic(code(rapidvc::config::duplicate_attribute), severity(Warning))]
    DuplicateAttribute {
        /// The file.
        src: SourceId,
        /// The second occurrence.
        #[label("given again here")]
        span: Span,
        /// The first occurrence.
        #[label("first given here")]
        first: Span,
        /// The attribute name.
        name: String,
    },

    /// An attribute rapidvc does not know (ignored).
    #[error("unknown attribute `-{name}` in {section}; it is ignored")]
    #[diagnostic(code(rapidvc::config::unknown_attribute), severity(Warning))]
    UnknownAttribute {
        /// The file.
        src: SourceId,
        /// The attribute.
        #[label("not an attribute of {section}")]
        span: Span,
        /// The attribute name.
        name: String,
        /// The section type.
        section: String,
    },

    /// A required attribute is missing.
    #[error("{section} instance without `-{name}`")]
    #[diagnostic(code(rapidvc::config::missing_attribute))]
    MissingAttribute {
        /// The file.
        src: SourceId,
        /// The instance.
        #[label("`-{name}` is missing here")]
        span: Span,
        /// The attribute name.
        name: String,
        /// The section type.
        section: String,
    },

    /// An attribute value of the wrong form.
    #[error("`-{name}` takes {expected}")]
    #[diagnostic(code(rapidvc::config::bad_value))]
    BadValue {
        /// The file.
        src: SourceId,
        /// The value (or the attribute, for a flag).
        #[label("{found}")]
        span: Span,
        /// The attribute name.
        name: String,
        /// What the attribute takes.
        expected: String,
        /// What was found.
        found: String,
    },

    /// A signal definition that cannot be used.
    #[error("signal `{name}`: {reason}")]
    #[diagnostic(code(rapidvc::config::invalid_signal))]
    InvalidSignal {
        /// The file.
        src: SourceId,
        /// The attribute at fault (or the name).
        #[label("{label}")]
        span: Span,
        /// The signal name.
        name: String,
        /// What is wrong.
        reason: String,
        /// Short text under the span.
        label: String,
    },

    /// The same signal name twice.
    #[error("signal `{name}` is defined twice")]
    #[diagnostic(
        code(rapidvc::config::duplicate_signal),
        help("signal names are case-insensitive; the first definition is used")
    )]
    DuplicateSignal {
        /// The file.
        src: SourceId,
        /// The second definition's name.
        #[label("defined again here")]
        span: Span,
        /// The first definition's name.
        #[label("first defined here")]
        first: Span,
        /// The signal name.
        name: String,
    },

    /// An analog signal whose logical range is 0..0.
    #[error("analog signal `{name}` has the logical range 0..0, so it only takes the value 0")]
    #[diagnostic(
        code(rapidvc::config::empty_range),
        severity(Warning),
        help("set `-MinLog` and `-MaxLog`; SetAO with any other value fails with ERR_AO_LIM")
    )]
    EmptyRange {
        /// The file.
        src: SourceId,
        /// The signal's name.
        #[label("no -MinLog/-MaxLog")]
        span: Span,
        /// The signal name.
        name: String,
    },

    /// The same device name twice in SIO.cfg.
    #[error("device `{name}` is defined twice")]
    #[diagnostic(
        code(rapidvc::config::duplicate_device),
        help(
            "device names are case-insensitive and a trailing `:` is ignored; the first definition is used"
        )
    )]
    DuplicateDevice {
        /// The file.
        src: SourceId,
        /// The second definition's name.
        #[label("defined again here")]
        span: Span,
        /// The first definition's name.
        #[label("first defined here")]
        first: Span,
        /// The device name.
        name: String,
    },

    /// More UdpUc devices than a controller supports.
    #[error("more than {max} UdpUc devices; device `{name}` is ignored")]
    #[diagnostic(
        code(rapidvc::config::too_many_devices),
        help("a controller communicates with at most {max} UdpUc devices")
    )]
    TooManyDevices {
        /// The file.
        src: SourceId,
        /// The name of the first device over the limit.
        #[label("device number {number}")]
        span: Span,
        /// The device name.
        name: String,
        /// Its number among the UdpUc devices (1-based).
        number: usize,
        /// The limit.
        max: usize,
    },

    /// A transmission protocol type rapidvc does not implement (recorded, not usable).
    #[error(
        "device `{name}` has type {kind}, which is not supported by rapidvc; only UDPUC devices can be used"
    )]
    #[diagnostic(
        code(rapidvc::config::unsupported_device),
        severity(Warning),
        help("{help}")
    )]
    UnsupportedDevice {
        /// The file.
        src: SourceId,
        /// The `-Type` value.
        #[label("not supported")]
        span: Span,
        /// The device name.
        name: String,
        /// The type as written.
        kind: String,
        /// What to do instead.
        help: String,
    },

    /// The same External Motion Interface Data name twice in MOC.cfg.
    #[error("motion profile `{name}` is defined twice")]
    #[diagnostic(
        code(rapidvc::config::duplicate_profile),
        help("profile names are case-insensitive; the first definition is used")
    )]
    DuplicateProfile {
        /// The file.
        src: SourceId,
        /// The second definition's name.
        #[label("defined again here")]
        span: Span,
        /// The first definition's name.
        #[label("first defined here")]
        first: Span,
        /// The profile name.
        name: String,
    },

    /// The same task name twice in SYS.cfg's `CAB_TASKS`.
    #[error("task `{name}` is defined twice in CAB_TASKS")]
    #[diagnostic(
        code(rapidvc::config::duplicate_task),
        help("task names are case-insensitive; the first definition is used")
    )]
    DuplicateTask {
        /// The file.
        src: SourceId,
        /// The second definition's name.
        #[label("defined again here")]
        span: Span,
        /// The first definition's name.
        #[label("first defined here")]
        first: Span,
        /// The task name.
        name: String,
    },

    /// More than one `-MotionTask` in `CAB_TASKS`: rapidvc has one robot.
    #[error("task `{name}` is a second motion task; rapidvc has one robot and one motion task")]
    #[diagnostic(
        code(rapidvc::config::several_motion_tasks),
        help(
            "keep `-MotionTask` on one task; the first one keeps it, this one runs without motion"
        )
    )]
    SeveralMotionTasks {
        /// The file.
        src: SourceId,
        /// The second motion task's `-MotionTask`.
        #[label("second motion task")]
        span: Span,
        /// The first motion task's `-MotionTask`.
        #[label("first motion task")]
        first: Span,
        /// The second motion task's name.
        name: String,
    },

    /// A `SYSSIG_OUT` status rapidvc does not drive.
    #[error(
        "the system output `{status}` is not simulated by rapidvc: `{signal}` keeps what the program writes"
    )]
    #[diagnostic(
        code(rapidvc::config::unsupported_system_output),
        severity(Warning),
        help(
            "simulated: MotOnState, MotorOnState, MotorOn, MotOffState, MotorOffState, MotorOff, AutoOn, CycleOn, RunchOk, MotSupOn, EmStop, SmbBatteryChargeLow, TaskExecuting, Error, ProdExecError, MechUnitNotMoving"
        )
    )]
    UnsupportedSystemOutput {
        /// The file.
        src: SourceId,
        /// The `-Status` value.
        #[label("not simulated")]
        span: Span,
        /// The status.
        status: String,
        /// The signal.
        signal: String,
    },

    /// A system output whose signal is not a digital output of the file.
    #[error(
        "the system output `{status}` drives `{signal}`, which is not a digital output (DO) of this EIO.cfg"
    )]
    #[diagnostic(code(rapidvc::config::system_output_signal))]
    SystemOutputSignal {
        /// The file.
        src: SourceId,
        /// The `-Signal` value.
        #[label("no DO of this name")]
        span: Span,
        /// The status.
        status: String,
        /// The signal.
        signal: String,
    },

    /// A section rapidvc reads but whose behaviour it does not implement.
    #[error("{section} is not supported by rapidvc; its instances are ignored")]
    #[diagnostic(code(rapidvc::config::unsupported_section), severity(Warning))]
    UnsupportedSection {
        /// The file.
        src: SourceId,
        /// The type header.
        #[label("ignored")]
        span: Span,
        /// The section type.
        section: String,
    },
}

impl RapidDiagnostic for ConfigError {
    fn source_id(&self) -> Option<SourceId> {
        match self {
            ConfigError::Io { .. } => None,
            ConfigError::BadHeader { src, .. }
            | ConfigError::WrongDomain { src, .. }
            | ConfigError::UnterminatedString { src, .. }
            | ConfigError::StrayBackslash { src, .. }
            | ConfigError::ExpectedAttribute { src, .. }
            | ConfigError::ExpectedType { src, .. }
            | ConfigError::NoSection { src, .. }
            | ConfigError::DuplicateAttribute { src, .. }
            | ConfigError::UnknownAttribute { src, .. }
            | ConfigError::MissingAttribute { src, .. }
            | ConfigError::BadValue { src, .. }
            | ConfigError::InvalidSignal { src, .. }
            | ConfigError::DuplicateSignal { src, .. }
            | ConfigError::EmptyRange { src, .. }
            | ConfigError::UnsupportedSection { src, .. }
            | ConfigError::UnsupportedSystemOutput { src, .. }
            | ConfigError::SystemOutputSignal { src, .. }
            | ConfigError::DuplicateDevice { src, .. }
            | ConfigError::TooManyDevices { src, .. }
            | ConfigError::UnsupportedDevice { src, .. }
            | ConfigError::DuplicateProfile { src, .. }
            | ConfigError::DuplicateTask { src, .. }
            | ConfigError::SeveralMotionTasks { src, .. } => Some(*src),
        }
    }
}
