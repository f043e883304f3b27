//! Every diagnostic code rapidvc reports, in one table: the code (`rapidvc::phase::name`) and
//! what it means.
//!
//! A diagnostic's code comes from this table only. The parse, sema and run diagnostics name
//! their codes by [`Code`] (`SemaError::details`, `RuntimeError`'s `code`); the types that
//! derive miette's `Diagnostic` (the parser's, the configuration readers', the loader's) must
//! write the code as a path in `#[diagnostic(code(…))]`, which miette's derive takes only as
//! written, so there the path repeats a code of this table. `tests/catalogue.rs` reads every
//! such attribute and every `Code::…` in `src/` and fails when a code is missing here or a
//! code here is used nowhere; it also keeps `docs/diagnostics.md`, which is generated from
//! [`Code::ALL`] and the RAPID error table, equal to this table.
//!
//! This module is a leaf: every phase may use it.

use std::fmt;

/// Defines [`Code`]: for each code its doc comment (what it means) and its text.
macro_rules! codes {
    ($(
        $(#[doc = $doc:literal])+
        $code:ident = $text:literal;
    )*) => {
        /// A diagnostic code. See the module documentation.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Code {
            $( $(#[doc = $doc])+ $code, )*
        }

        impl Code {
            /// Every code, in the table's order (by phase).
            pub const ALL: &[Code] = &[$(Code::$code),*];

            /// The code as users see it: `rapidvc::sema::undeclared`.
            pub const fn as_str(self) -> &'static str {
                match self { $(Code::$code => $text,)* }
            }

            /// What it means (the doc comment of the code, one line per doc line).
            pub const fn meaning(self) -> &'static str {
                match self { $(Code::$code => concat!($($doc, "\n"),+),)* }
            }
        }
    };
}

impl Code {
    /// The code with this text, if the table has one.
    pub fn from_text(text: &str) -> Option<Code> {
        Code::ALL.iter().copied().find(|c| c.as_str() == text)
    }
}

impl fmt::Display for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The code of an unhandled RAPID error that has a name (`ERR_…`, from the RAPID error
/// table): `rapidvc::run::ERR_DIVZERO`. One code per named error; `docs/diagnostics.md`
/// lists them all.
pub fn rapid_error_code(name: &str) -> String {
    format!("{RAPID_ERROR_PREFIX}{name}")
}

/// What [`rapid_error_code`] puts before the error's name.
pub const RAPID_ERROR_PREFIX: &str = "rapidvc::run::";

codes! {
    /// The text does not fit the grammar here.
    ParseSyntax = "rapidvc::parse::syntax";
    /// A string literal without its closing quote on the same line.
    ParseUnterminatedString = "rapidvc::parse::unterminated_string";
    /// A backslash in a string that is not `\\` or `\hh`.
    ParseInvalidEscape = "rapidvc::parse::invalid_escape";
    /// A number literal outside the range of `num` (IEEE-754 single precision).
    ParseNumberOutOfRange = "rapidvc::parse::number_out_of_range";
    /// Brackets and blocks nested deeper than the parser accepts.
    ParseNestingTooDeep = "rapidvc::parse::nesting_too_deep";
    /// An expression whose tree is deeper than the parser accepts (a very long operator
    /// chain).
    ParseExpressionTooComplex = "rapidvc::parse::expression_too_complex";
    /// `NOT` after an operator: RAPID allows it only at the start of an expression.
    ParseMisplacedNot = "rapidvc::parse::misplaced_not";
    /// `a < b < c`: relational operators do not associate.
    ParseChainedComparison = "rapidvc::parse::chained_comparison";
    /// A block, routine, record or module whose end keyword is missing.
    ParseMissingEnd = "rapidvc::parse::missing_end";
    /// An end or continuation keyword that no open block takes.
    ParseUnmatchedKeyword = "rapidvc::parse::unmatched_keyword";
    /// `PROC … ENDFUNC` and the like.
    ParseEndMismatch = "rapidvc::parse::end_mismatch";
    /// A statement at module level.
    ParseStatementOutsideRoutine = "rapidvc::parse::statement_outside_routine";
    /// A declaration where RAPID does not allow one.
    ParseMisplacedDeclaration = "rapidvc::parse::misplaced_declaration";
    /// A keyword that is not allowed in this declaration.
    ParseInvalidModifier = "rapidvc::parse::invalid_modifier";
    /// More than three array dimensions.
    ParseTooManyDimensions = "rapidvc::parse::too_many_dimensions";
    /// A handler section twice, or in the wrong order.
    ParseSectionOrder = "rapidvc::parse::section_order";
    /// Two declarations with the same (case-folded) name in one scope.
    ParseDuplicateName = "rapidvc::parse::duplicate_name";
    /// A placeholder of an incomplete program (a warning: it parses, but cannot run).
    ParsePlaceholder = "rapidvc::parse::placeholder";
    /// A file without any module.
    ParseNoModule = "rapidvc::parse::no_module";
    /// The parser gave up (only for inputs beyond its limits).
    ParseLimit = "rapidvc::parse::limit";
    /// The error limit per file was reached; the rest is not reported.
    ParseTooManyErrors = "rapidvc::parse::too_many_errors";
    /// A file or directory cannot be read.
    LoadIo = "rapidvc::load::io";
    /// A file prefix or backup folder names a task SYS.cfg does not define.
    LoadUnknownTask = "rapidvc::load::unknown_task";
    /// A task-global PERS declared with different types in two tasks.
    LoadPersTypeMismatch = "rapidvc::load::pers_type_mismatch";
    /// The configuration directory or a file in it cannot be read.
    ConfigIo = "rapidvc::config::io";
    /// The first line is not a CFG header.
    ConfigBadHeader = "rapidvc::config::bad_header";
    /// The header names another domain than the file name says.
    ConfigWrongDomain = "rapidvc::config::wrong_domain";
    /// A string value without its closing quote.
    ConfigUnterminatedString = "rapidvc::config::unterminated_string";
    /// A backslash that is not the last character of its line.
    ConfigStrayBackslash = "rapidvc::config::stray_backslash";
    /// A value or word where an attribute (`-Name`) must come.
    ConfigExpectedAttribute = "rapidvc::config::expected_attribute";
    /// After a `#` line, something other than a type header.
    ConfigExpectedType = "rapidvc::config::expected_type";
    /// An instance before the first type header.
    ConfigNoSection = "rapidvc::config::no_section";
    /// An attribute given twice in one instance (the first value is used).
    ConfigDuplicateAttribute = "rapidvc::config::duplicate_attribute";
    /// An attribute rapidvc does not know (ignored).
    ConfigUnknownAttribute = "rapidvc::config::unknown_attribute";
    /// A required attribute is missing.
    ConfigMissingAttribute = "rapidvc::config::missing_attribute";
    /// An attribute value of the wrong form.
    ConfigBadValue = "rapidvc::config::bad_value";
    /// A signal definition that cannot be used.
    ConfigInvalidSignal = "rapidvc::config::invalid_signal";
    /// The same signal name twice.
    ConfigDuplicateSignal = "rapidvc::config::duplicate_signal";
    /// An analog signal whose logical range is 0..0.
    ConfigEmptyRange = "rapidvc::config::empty_range";
    /// The same device name twice in SIO.cfg.
    ConfigDuplicateDevice = "rapidvc::config::duplicate_device";
    /// More UdpUc devices than a controller supports.
    ConfigTooManyDevices = "rapidvc::config::too_many_devices";
    /// A device in SIO.cfg whose transmission protocol type rapidvc does not implement
    /// (recorded, not usable; a warning).
    ConfigUnsupportedDevice = "rapidvc::config::unsupported_device";
    /// The same External Motion Interface Data name twice in MOC.cfg.
    ConfigDuplicateProfile = "rapidvc::config::duplicate_profile";
    /// The same task name twice in SYS.cfg's CAB_TASKS.
    ConfigDuplicateTask = "rapidvc::config::duplicate_task";
    /// More than one motion task in SYS.cfg (rapidvc has one robot).
    ConfigSeveralMotionTasks = "rapidvc::config::several_motion_tasks";
    /// A section rapidvc reads but whose behaviour it does not implement.
    ConfigUnsupportedSection = "rapidvc::config::unsupported_section";
    /// A system output (`SYSSIG_OUT`) whose status rapidvc does not drive.
    ConfigUnsupportedSystemOutput = "rapidvc::config::unsupported_system_output";
    /// A system output on a signal that is not a digital output of EIO.cfg.
    ConfigSystemOutputSignal = "rapidvc::config::system_output_signal";
    /// The configured signals cannot be used together.
    ConfigSignals = "rapidvc::config::signals";
    /// A device asked for whose transmission protocol type rapidvc does not implement.
    ConfigUnusableDevice = "rapidvc::config::unusable_device";
    /// A device asked for that SIO.cfg (which exists) does not define.
    ConfigUnknownDevice = "rapidvc::config::unknown_device";
    /// A `--device` value or a set of them that cannot be used.
    ConfigBadDeviceOverride = "rapidvc::config::bad_device_override";
    /// An ExtConfigName that names no profile.
    ConfigUnknownProfile = "rapidvc::config::unknown_profile";
    /// A data name that is not declared anywhere visible.
    SemaUndeclared = "rapidvc::sema::undeclared";
    /// A signal argument that names no configured signal.
    SemaUnknownSignal = "rapidvc::sema::unknown_signal";
    /// A call to an instruction or function of base RobotWare that rapidvc does not implement
    /// (and that the program does not declare).
    SemaUnsupported = "rapidvc::sema::unsupported";
    /// A call to a routine that is neither declared in the loaded modules nor an instruction
    /// or function of RAPID (the program's own routine, missing).
    SemaUnknownRoutine = "rapidvc::sema::unknown_routine";
    /// An instruction, function or data type of a RobotWare option rapidvc does not have
    /// (the option catalogue, `src/sema/options.txt`).
    SemaNeedsOption = "rapidvc::sema::needs_option";
    /// A type name that does not exist.
    SemaUnknownType = "rapidvc::sema::unknown_type";
    /// A value of the wrong type.
    SemaTypeMismatch = "rapidvc::sema::type_mismatch";
    /// An operator applied to operands it does not take.
    SemaBadOperands = "rapidvc::sema::bad_operands";
    /// Too many positional arguments.
    SemaTooManyArgs = "rapidvc::sema::too_many_args";
    /// A required argument was not given.
    SemaMissingArg = "rapidvc::sema::missing_arg";
    /// `\Name` that is not an optional parameter of the callee.
    SemaUnknownOptional = "rapidvc::sema::unknown_optional";
    /// `name := v` for a parameter that does not exist.
    SemaUnknownNamed = "rapidvc::sema::unknown_named";
    /// The same parameter given twice.
    SemaDuplicateArg = "rapidvc::sema::duplicate_arg";
    /// Two mutually exclusive alternatives given together.
    SemaExclusiveArgs = "rapidvc::sema::exclusive_args";
    /// A switch given a value, or a value parameter given as a bare switch.
    SemaSwitchValue = "rapidvc::sema::switch_value";
    /// An argument for an INOUT/VAR/PERS parameter that is not the right kind of object.
    SemaArgMode = "rapidvc::sema::arg_mode";
    /// Assignment to something that cannot be assigned.
    SemaNotAssignable = "rapidvc::sema::not_assignable";
    /// Something that needs a place (variable) got an expression.
    SemaNotAPlace = "rapidvc::sema::not_a_place";
    /// `RETURN value` in a PROC or TRAP, or `RETURN` without a value in a FUNC.
    SemaReturnValue = "rapidvc::sema::return_value";
    /// A FUNC without any `RETURN` (an error), or a FUNC whose end can be reached without a
    /// `RETURN` (a warning).
    SemaMissingReturn = "rapidvc::sema::missing_return";
    /// A name declared twice in the same scope.
    SemaDuplicate = "rapidvc::sema::duplicate";
    /// A user module redeclares predefined stdlib data.
    SemaPredefined = "rapidvc::sema::predefined";
    /// A PERS declared in several modules with different types.
    SemaPersMismatch = "rapidvc::sema::pers_mismatch";
    /// A call to a function as an instruction, or to a procedure in an expression.
    SemaRoutineKind = "rapidvc::sema::routine_kind";
    /// RETRY, TRYNEXT or `RAISE;` outside an ERROR handler.
    SemaHandlerOnly = "rapidvc::sema::handler_only";
    /// A GOTO to a label that does not exist or cannot be reached from here.
    SemaLabel = "rapidvc::sema::label";
    /// An aggregate with the wrong number of items, or one whose type cannot be told from its
    /// context.
    SemaAggregate = "rapidvc::sema::aggregate";
    /// Indexing something that is not an array, or with the wrong number of indices.
    SemaIndex = "rapidvc::sema::index";
    /// `.field` on something that is not a record with that component.
    SemaComponent = "rapidvc::sema::component";
    /// A non-value type used as a value (aggregate, CONST, assignment, comparison).
    SemaNonValue = "rapidvc::sema::non_value";
    /// An array size or other constant that cannot be computed before running.
    SemaNotConstant = "rapidvc::sema::not_constant";
    /// Module data whose initial values depend on each other.
    SemaInitCycle = "rapidvc::sema::init_cycle";
    /// A data declaration that is not allowed here.
    SemaDeclaration = "rapidvc::sema::declaration";
    /// `Present`/conditional argument on something that is not an optional parameter.
    SemaNotOptional = "rapidvc::sema::not_optional";
    /// A switch parameter used as a value.
    SemaSwitchAsValue = "rapidvc::sema::switch_as_value";
    /// A string literal longer than 80 characters.
    SemaStringTooLong = "rapidvc::sema::string_too_long";
    /// Too much data: an array size or a declaration holding more values than one
    /// declaration may, or data that brings the task over its limit (the module data, or a
    /// routine's data on top of the module data).
    SemaDataLimit = "rapidvc::sema::data_limit";
    /// A native signature names a type rapidvc does not define (an internal error).
    SemaInternal = "rapidvc::sema::internal";
    /// A RAPID error number the program raised itself (`RAISE` with a booked or user number)
    /// that no handler took.
    RunUserError = "rapidvc::run::user_error";
    /// An instruction or function rapidvc does not implement; the program stops.
    RunUnsupported = "rapidvc::run::unsupported";
    /// A placeholder (`<SMT>`, `<EXP>`, …) was reached; the program stops.
    RunPlaceholder = "rapidvc::run::placeholder";
    /// Execution was stopped: the operation budget ran out, or the run was asked to stop.
    RunAborted = "rapidvc::run::aborted";
    /// The controller failed under the program (a motion or EGM error that stops the program);
    /// the text carries the event number.
    RunHost = "rapidvc::run::host";
    /// `Assert` failed in `rapidvc test`.
    TestAssertion = "rapidvc::test::assertion";
}
