//! Pure implementations of RAPID's predefined functions and value semantics behind the built-ins: number text, num/dnum arithmetic, bit operations, digit strings, strings and poses.
//!
//! Everything here works on plain Rust types (`f32` for `num`, `f64` for `dnum`, `&str`,
//! `[f64; 3]` positions, `[f64; 4]` quaternions) and never touches interpreter state. The
//! interpreter wraps these functions as RAPID natives. Every failure is an [`RtError`]; its
//! [`RtError::err_name`] is the RAPID `ERR_*` constant the interpreter raises (so a RAPID
//! `ERROR` handler can catch it), and its `Display` text is the message for the event log.
//!
//! Decisions that are not settled by an ABB document are listed in the doc of each module and
//! pinned by unit tests there.

pub mod bits;
mod decimal;
pub mod digits;
pub mod format;
pub mod math;
pub mod pose;
pub mod raw_bytes;
pub mod string;

/// An error raised by a runtime-library function.
///
/// The mapping to RAPID error names ([`RtError::err_name`]) is a rapidvc decision where no
/// ABB document settles it; the names themselves all exist in RobotWare.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RtError {
    /// Division (`/`, `DIV`, `MOD`) by zero. RAPID: `ERR_DIVZERO`.
    #[error("division by zero")]
    DivZero,
    /// An operand that must be an integer is not (DIV/MOD operands). RAPID: `ERR_NOTINTVAL`.
    #[error("{what} must be an integer value, not {value}")]
    NotInteger {
        /// What was expected to be an integer (e.g. "left operand of DIV").
        what: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A result or value does not fit the data type (outside the IEEE single range for
    /// `num`, double range for `dnum`, or not a number). RAPID: `ERR_NUM_LIMIT`.
    #[error("{what}: the value is outside the range of {ty}")]
    NumLimit {
        /// The operation or function.
        what: &'static str,
        /// `num` or `dnum`.
        ty: &'static str,
    },
    /// An argument value is not allowed (domain errors such as `Sqrt(-1)`, `ASin(2)`, a
    /// negative `\Dec`). RAPID: `ERR_ARGVALERR`.
    #[error("{func}: {reason}")]
    ArgValue {
        /// The RAPID function name.
        func: &'static str,
        /// Why the argument is not allowed.
        reason: String,
    },
    /// A string would be longer than RAPID's 80 characters. RAPID: `ERR_STRTOOLNG`.
    #[error("string too long: {len} characters (a RAPID string holds at most 80)")]
    StrTooLong {
        /// The length the string would have had.
        len: usize,
    },
    /// A character position or length outside the string. RAPID: `ERR_OUTOFBND`.
    #[error("{func}: {reason}")]
    OutOfBounds {
        /// The RAPID function name.
        func: &'static str,
        /// Which position was wrong, with the string length.
        reason: String,
    },
    /// An orientation that is not a usable quaternion (all zero or not finite). RAPID:
    /// `ERR_ILLQUAT`.
    #[error("{func}: the orientation is not a valid quaternion (it is zero or not finite)")]
    IllQuat {
        /// The RAPID function name.
        func: &'static str,
    },
}

impl RtError {
    /// The RAPID error constant the interpreter raises for this error (its `ERRNO`).
    pub fn err_name(&self) -> &'static str {
        match self {
            RtError::DivZero => "ERR_DIVZERO",
            RtError::NotInteger { .. } => "ERR_NOTINTVAL",
            RtError::NumLimit { .. } => "ERR_NUM_LIMIT",
            RtError::ArgValue { .. } => "ERR_ARGVALERR",
            RtError::StrTooLong { .. } => "ERR_STRTOOLNG",
            RtError::OutOfBounds { .. } => "ERR_OUTOFBND",
            RtError::IllQuat { .. } => "ERR_ILLQUAT",
        }
    }

    pub(crate) fn arg(func: &'static str, reason: impl Into<String>) -> RtError {
        RtError::ArgValue {
            func,
            reason: reason.into(),
        }
    }
}

/// Result of a runtime-library function.
pub type RtResult<T> = Result<T, RtError>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn error_names_are_rapid_constants() {
        assert_eq!(RtError::DivZero.err_name(), "ERR_DIVZERO");
        assert_eq!(
            RtError::NotInteger {
                what: "x",
                value: 1.5
            }
            .err_name(),
            "ERR_NOTINTVAL"
        );
        assert_eq!(
            RtError::NumLimit {
                what: "x",
                ty: "num"
            }
            .err_name(),
            "ERR_NUM_LIMIT"
        );
        assert_eq!(RtError::arg("Sqrt", "negative").err_name(), "ERR_ARGVALERR");
        assert_eq!(RtError::StrTooLong { len: 81 }.err_name(), "ERR_STRTOOLNG");
        assert_eq!(
            RtError::OutOfBounds {
                func: "StrPart",
                reason: String::new()
            }
            .err_name(),
            "ERR_OUTOFBND"
        );
        assert_eq!(
            RtError::IllQuat { func: "NOrient" }.err_name(),
            "ERR_ILLQUAT"
        );
        assert_eq!(
            RtError::StrTooLong { len: 81 }.to_string(),
            "string too long: 81 characters (a RAPID string holds at most 80)"
        );
    }

    /// `(storage, type, name, value)` of every one-line `CONST`/`PERS` declaration.
    fn decls(text: &str) -> Vec<(String, String, String, format::LitValue)> {
        let mut out = Vec::new();
        for line in text.lines().map(str::trim) {
            if !(line.starts_with("CONST ") || line.starts_with("PERS ")) {
                continue;
            }
            let (head, value) = line.split_once(":=").expect("declaration with :=");
            let words: Vec<&str> = head.split_whitespace().collect();
            let value = value.trim().strip_suffix(';').expect("ends with ;");
            let parsed = format::parse_value(value)
                .unwrap_or_else(|| panic!("value of {line:?} does not parse"));
            out.push((
                words[0].to_string(),
                words[1].to_string(),
                words[2].to_string(),
                parsed,
            ));
        }
        out
    }

    fn nums(v: &format::LitValue) -> Vec<f64> {
        v.as_list()
            .unwrap()
            .iter()
            .filter_map(|c| c.as_dnum())
            .collect()
    }

    #[test]
    fn stdlib_files() {
        let files = [
            include_str!("../stdlib/base.sys"),
            include_str!("../stdlib/speed.sys"),
            include_str!("../stdlib/zone.sys"),
            include_str!("../stdlib/egm.sys"),
            include_str!("../stdlib/misc.sys"),
            include_str!("../stdlib/system.sys"),
            include_str!("../stdlib/files.sys"),
            include_str!("../stdlib/socket.sys"),
        ];
        for f in files {
            assert!(f.starts_with("MODULE "), "{f}");
            assert!(f.contains("(SYSMODULE, NOSTEPIN, READONLY)"));
            assert!(f.trim_end().ends_with("ENDMODULE"));
        }

        let base = decls(files[0]);
        assert_eq!(base.len(), 3);
        assert!(base.iter().all(|d| d.0 == "PERS"));
        let tool0 = &base[0];
        assert_eq!((tool0.1.as_str(), tool0.2.as_str()), ("tooldata", "tool0"));
        assert_eq!(
            format::parse_value("[TRUE,[[0,0,0],[1,0,0,0]],[0.001,[0,0,0.001],[1,0,0,0],0,0,0]]"),
            Some(tool0.3.clone())
        );
        assert_eq!(base[1].2, "wobj0");
        assert_eq!(base[2].2, "load0");

        let speeds = decls(files[1]);
        assert_eq!(speeds.len(), 26);
        for (storage, ty, name, value) in &speeds {
            assert_eq!((storage.as_str(), ty.as_str()), ("CONST", "speeddata"));
            let v = nums(value);
            let tcp = if name == "vmax" {
                7000.0
            } else {
                name[1..].parse::<f64>().unwrap()
            };
            assert_eq!(v, vec![tcp, 500.0, 5000.0, 1000.0], "{name}");
        }

        let zones = decls(files[2]);
        assert_eq!(zones.len(), 15);
        assert_eq!(zones[0].2, "fine");
        assert_eq!(zones[0].3.as_list().unwrap()[0].as_bool(), Some(true));
        for (_, ty, name, value) in zones.iter().skip(1) {
            assert_eq!(ty, "zonedata");
            assert_eq!(value.as_list().unwrap()[0].as_bool(), Some(false));
            let v = nums(value);
            let tcp = if name == "z0" {
                0.3
            } else {
                name[1..].parse::<f64>().unwrap()
            };
            assert_eq!(v[0], tcp, "{name}");
            // pzone_ori = pzone_eax = zone_leax = 1.5 × pzone_tcp (rounded), zone_ori =
            // zone_reax = pzone_ori / 10, in every row of the reference table.
            assert_eq!(v[1], v[2]);
            assert_eq!(v[1], v[4]);
            assert_eq!(v[3], v[5]);
            assert!((v[1] - (1.5 * tcp).round().max(tcp)).abs() <= 1.0, "{name}");
            assert!((v[3] - v[1] / 10.0).abs() < 0.6, "{name}");
        }

        let egm = decls(files[3]);
        let value = |n: &str| {
            egm.iter()
                .find(|d| d.2 == n)
                .and_then(|d| d.3.as_dnum())
                .unwrap()
        };
        assert!(value("EGM_STATE_DISCONNECTED") < value("EGM_STATE_CONNECTED"));
        assert!(value("EGM_STATE_CONNECTED") < value("EGM_STATE_RUNNING"));
        assert_eq!(value("EGM_CORR_RUNNING"), 3.0);
        assert_eq!(value("EGM_STOP_HOLD"), 1.0);
        assert_eq!(value("EGM_FRAME_JOINT"), 5.0);
        for alias in ["egmstate", "egmstopmode", "egmframetype", "egmcorrstate"] {
            assert!(files[3].contains(&format!("ALIAS num {alias};")));
        }

        let misc = decls(files[4]);
        let text = |n: &str| {
            misc.iter()
                .find(|d| d.2 == n)
                .and_then(|d| d.3.as_str().map(str::to_string))
                .unwrap()
        };
        assert_eq!(text("STR_DIGIT"), string::STR_DIGIT);
        assert_eq!(text("STR_UPPER"), string::STR_UPPER);
        assert_eq!(text("STR_LOWER"), string::STR_LOWER);
        assert_eq!(text("STR_WHITE"), string::STR_WHITE);
        assert_eq!(text("stEmpty"), "");

        // ABB's symnum, opnum and opcalc numbers; rapidvc's for the others.
        let system = decls(files[5]);
        let value = |n: &str| {
            system
                .iter()
                .find(|d| d.2 == n)
                .and_then(|d| d.3.as_dnum())
                .unwrap_or_else(|| panic!("{n}"))
        };
        for (name, v) in [
            ("OP_UNDEF", 0.0),
            ("OP_AUTO", 1.0),
            ("OP_MAN_PROG", 2.0),
            ("OP_MAN_TEST", 3.0),
            ("RUN_UNDEF", 0.0),
            ("RUN_CONT_CYCLE", 1.0),
            ("RUN_STEP_MOVE", 5.0),
            ("LT", 1.0),
            ("LTEQ", 2.0),
            ("EQ", 3.0),
            ("NOTEQ", 4.0),
            ("GTEQ", 5.0),
            ("GT", 6.0),
            ("OpAdd", 1.0),
            ("OpSub", 2.0),
            ("OpMult", 3.0),
            ("OpDiv", 4.0),
            ("OpMod", 5.0),
            ("LEVEL_NORMAL", 0.0),
            ("LEVEL_TRAP", 1.0),
            ("END_OF_LIST", -1.0),
            ("ALL_DOMAINS", 1.0),
            ("SYS_DOMAIN", 7.0),
            ("HANDLER_NONE", 0.0),
            ("HANDLER_ERR", 2.0),
            ("HANDLER_UNDO", 3.0),
            ("EVENT_NONE", 0.0),
            ("EVENT_STEP", 7.0),
        ] {
            assert_eq!(value(name), v, "{name}");
        }
        for alias in [
            "ALIAS num symnum;",
            "ALIAS string stringdig;",
            "ALIAS string errstr;",
        ] {
            assert!(files[5].contains(alias), "{alias}");
        }
        let disk = decls(files[6]);
        let find = |n: &str| disk.iter().find(|d| d.2 == n).map(|d| d.3.clone()).unwrap();
        assert_eq!(find("diskhome").as_str(), Some("HOME:"));
        assert_eq!(find("disktemp").as_str(), Some("TEMP:"));
        assert_eq!(find("diskram").as_str(), Some("RAMDISK:"));
        assert_eq!(find("EOF_NUM").as_num(), Some(9.998e36));
        assert_eq!(find("EOF_BIN").as_num(), Some(-1.0));
        let wait_max = misc.iter().find(|d| d.2 == "WAIT_MAX").unwrap();
        assert_eq!(wait_max.3.as_dnum(), Some(8_388_607.0));

        // The socket states and integer formats: `interp/builtins/sockets.rs` and
        // `raw_bytes` use these numbers.
        let socket = decls(files[7]);
        let value = |n: &str| {
            socket
                .iter()
                .find(|d| d.2 == n)
                .and_then(|d| d.3.as_dnum())
                .unwrap()
        };
        for (i, name) in [
            "SOCKET_CREATED",
            "SOCKET_CONNECTED",
            "SOCKET_BOUND",
            "SOCKET_LISTENING",
            "SOCKET_CLOSED",
        ]
        .iter()
        .enumerate()
        {
            assert_eq!(value(name), i as f64 + 1.0, "{name}");
        }
        for (name, n) in [
            ("USINT", 1.0),
            ("UINT", 2.0),
            ("UDINT", 4.0),
            ("ULINT", 8.0),
            ("SINT", -1.0),
            ("INT", -2.0),
            ("DINT", -4.0),
            ("LINT", -8.0),
        ] {
            assert_eq!(value(name), n, "{name}");
        }
    }
}
