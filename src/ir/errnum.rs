//! RAPID error numbers: the predefined `ERR_*` constants and rapidvc's numbering scheme.
//!
//! ABB does not publish the numeric values of the `ERR_*` constants (programs compare
//! `ERRNO` with the names), so rapidvc fixes its own stable scheme:
//!
//! | range | use |
//! |---|---|
//! | 1–90 | user error numbers (`RAISE 12;`) |
//! | 500–999 | numbers handed out by `BookErrNo`, in booking order from 500 |
//! | 1001–1099 | arithmetic and data (`ERR_DIVZERO` = 1001, …) |
//! | 1101–1199 | routines and control (`ERR_NOTPRES`, `ERR_EXCRTYMAX`, `ERR_REFUNKPRC`, …); 1150–1169: program modules at run time (`ERR_LOADED`, `ERR_SYNTAX`, …) |
//! | 1201–1299 | interrupts |
//! | 1301–1399 | waiting and the teach pendant (`ERR_WAIT_MAXTIME`, …) |
//! | 1401–1499 | motion (`ERR_ROBLIMIT`, `ERR_OUTSIDE_REACH`, …) |
//! | 1501–1599 | I/O signals |
//! | 1601–1699 | sockets and files |
//! | 1701–1799 | EGM (`ERR_UDPUC_COMM`) |
//! | 1801–1899 | system: configuration data and text tables (`ERR_CFG_NOTFND`, …) |
//! | 1901–1999 | several tasks: synchronisation and the RAPID message queue (`ERR_RMQ_FULL`, …) |
//!
//! Numbers never change once published; new constants take the next free number of their
//! group.

/// First number handed out by `BookErrNo`.
pub const BOOK_FIRST: i32 = 500;
/// Last number `BookErrNo` can hand out.
pub const BOOK_LAST: i32 = 999;

/// A predefined error constant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ErrDef {
    /// `ERR_…` name.
    pub name: &'static str,
    /// Its number.
    pub num: i32,
    /// Event-log text.
    pub text: &'static str,
}

macro_rules! errs {
    ($( $name:ident = $num:literal, $text:literal; )*) => {
        /// Every predefined error constant, in numbering order.
        pub const ERRORS: &[ErrDef] = &[ $( ErrDef { name: stringify!($name), num: $num, text: $text }, )* ];
        $(
            #[doc = $text]
            #[allow(dead_code)]
            pub const $name: i32 = $num;
        )*
    };
}

errs! {
    ERR_DIVZERO = 1001, "Division by zero";
    ERR_NOTINTVAL = 1002, "Not an integer value";
    ERR_NUM_LIMIT = 1003, "Value outside the range of the data type";
    ERR_ARGVALERR = 1004, "Argument value not allowed";
    ERR_STRTOOLNG = 1005, "String too long (more than 80 characters)";
    ERR_OUTOFBND = 1006, "Index outside the array bounds";
    ERR_ILLQUAT = 1007, "Illegal orientation (not a valid quaternion)";
    ERR_NOTARR = 1008, "Data is not an array";
    ERR_NOTEQDIM = 1009, "Array dimensions do not match";
    ERR_ILLDIM = 1010, "Illegal array dimension";
    ERR_OVERFLOW = 1011, "Clock overflow";
    ERR_MAXINTVAL = 1012, "Integer value too large";
    ERR_INT_NOTVAL = 1013, "Not a valid integer";
    ERR_INT_MAXVAL = 1014, "Integer value outside the allowed range";
    ERR_DATA_LIMIT = 1015, "Too much data in the task (module data and running routines)";
    ERR_CALC_NEG = 1016, "Negative result of a digit-string calculation";
    ERR_CALC_OVERFLOW = 1017, "Result of a digit-string calculation too large";
    ERR_CALC_DIVZERO = 1018, "Division by zero in a digit-string calculation";
    ERR_NEGARG = 1019, "Negative argument not allowed";
    ERR_NOTPRES = 1101, "Optional parameter not present";
    ERR_FNCNORET = 1102, "Function ended without RETURN";
    ERR_CALLPROC = 1103, "Procedure call error";
    ERR_ILLRAISE = 1104, "Error number in RAISE out of range";
    ERR_EXCRTYMAX = 1105, "Maximum number of retries exceeded";
    ERR_REFUNKPRC = 1106, "Reference to unknown procedure";
    ERR_REFUNKFUN = 1107, "Reference to unknown function";
    ERR_REFUNKDAT = 1108, "Reference to unknown data";
    ERR_REFUNKTRP = 1109, "Reference to unknown trap";
    ERR_SYM_ACCESS = 1110, "Symbol access error";
    ERR_ARGNAME = 1111, "Argument is not a valid name";
    ERR_UNKPROC = 1112, "Unknown procedure";
    ERR_ARGNOTVAR = 1113, "Argument is not a variable";
    ERR_ARGNOTPER = 1114, "Argument is not a persistent";
    ERR_ARGDUPCND = 1115, "More than one present conditional argument for the same parameter";
    ERR_EXECPHR = 1116, "An instruction with a placeholder (`<SMT>`, `<EXP>`, …) was executed";
    ERR_LOADED = 1150, "Program module already loaded";
    ERR_SYNTAX = 1151, "Syntax error in the loaded program module";
    ERR_LINKREF = 1152, "Unresolved references in the loaded program module";
    ERR_LOADNO_INUSE = 1153, "Load session already in use";
    ERR_LOADNO_NOUSE = 1154, "Load session not in use";
    ERR_UNLOAD = 1155, "Program module cannot be unloaded";
    ERR_NOTSAVED = 1156, "Program module changed since it was loaded";
    ERR_MODULE = 1157, "Program module not found";
    ERR_PRGMEMFULL = 1158, "Program memory full";
    ERR_ALRDYCNT = 1201, "Interrupt variable already connected";
    ERR_CNTNOTVAR = 1202, "CONNECT target is not a variable";
    ERR_INOMAX = 1203, "No more interrupt numbers available";
    ERR_UNKINO = 1204, "Unknown interrupt number";
    ERR_INOISSAFE = 1205, "Interrupt is safe and cannot be disabled";
    ERR_WAIT_MAXTIME = 1301, "Maximum waiting time exceeded";
    ERR_TP_DOBREAK = 1302, "TP read interrupted by a digital output";
    ERR_TP_DIBREAK = 1303, "TP read interrupted by a digital input";
    ERR_TP_MAXTIME = 1304, "TP read timed out";
    ERR_TP_NO_CLIENT = 1305, "No teach pendant client";
    ERR_TP_PERSBOOLBREAK = 1306, "TP read interrupted by a persistent bool";
    ERR_UI_INITVALUE = 1307, "Dialog initial value outside its limits";
    ERR_UI_MAXMIN = 1308, "Dialog minimum value greater than its maximum";
    ERR_UI_NOTINT = 1309, "Dialog value is not an integer";
    ERR_UISHOW_FATAL = 1310, "UIShow could not start the application";
    ERR_UISHOW_FULL = 1311, "No room on the FlexPendant for another UIShow application";
    ERR_ROBLIMIT = 1401, "Robot position outside its limits";
    ERR_OUTSIDE_REACH = 1402, "Position outside reach";
    ERR_WHLSEARCH = 1403, "No search hit";
    ERR_PATH_STOP = 1404, "Path stopped";
    ERR_SIGSUPSEARCH = 1405, "Search signal already set at the start";
    ERR_ACC_TOO_LOW = 1406, "Acceleration or deceleration limit too low (PathAccLim, WorldAccLim)";
    ERR_ALRDY_MOVING = 1407, "The robot is already moving (StartMove, StartMoveRetry)";
    ERR_AXIS_ACT = 1408, "Axis is not active";
    ERR_AXIS_IND = 1409, "Axis is not in independent mode";
    ERR_AXIS_MOVING = 1410, "Axis is moving";
    ERR_AXIS_PAR = 1411, "Axis parameter not valid for the instruction";
    ERR_BWDLIMIT = 1412, "Limit of the path StepBwdPath can step back reached";
    ERR_COLL_STOP = 1413, "Robot stopped by collision detection";
    ERR_CONC_MAX = 1414, "Too many consecutive motion instructions with \\Conc";
    ERR_DIPLAG_LIM = 1415, "DipLag too large (TriggSpeed)";
    ERR_MOTIONSUP = 1416, "Motion supervision stopped the robot";
    ERR_PERSSUPSEARCH = 1417, "Search persistent already set at the start";
    ERR_PID_MOVESTOP = 1418, "Process error: the movement was stopped (ProcerrRecovery)";
    ERR_PID_RAISE_PP = 1419, "Process error raised by ProcerrRecovery";
    ERR_PROCSIGNAL_OFF = 1420, "Process supervision signal is off (ProcerrRecovery)";
    ERR_SPEEDLIM_VALUE = 1421, "Speed limit value too low";
    ERR_STARTMOVE = 1422, "StartMove could not restart the movement";
    ERR_UNIT_PAR = 1423, "Mechanical unit parameter not valid for the instruction";
    ERR_WOBJ_MOVING = 1424, "The coordinated work object is moving";
    ERR_LOADID_FATAL = 1425, "Load identification failed";
    ERR_LOADID_RETRY = 1426, "Load identification must be repeated";
    ERR_SYNCMOVEOFF = 1427, "SyncMoveOff time-out (not every task arrived)";
    ERR_SYNCMOVEON = 1428, "SyncMoveOn time-out (not every task arrived)";
    ERR_PATHDIST = 1440, "Too far from the interrupted path to restart";
    ERR_SPEED_REFRESH_LIM = 1441, "Speed override out of limits";
    ERR_FRAME = 1442, "The positions do not define a frame";
    ERR_NO_ALIASIO_DEF = 1501, "Signal variable is not connected to a signal";
    ERR_ALIASIO_DEF = 1502, "Signal is not defined";
    ERR_ALIASIO_TYPE = 1503, "Signal has the wrong type";
    ERR_NORUNUNIT = 1504, "No contact with the I/O device";
    ERR_SIG_NOT_VALID = 1505, "Signal cannot be accessed";
    ERR_SIG_NAME = 1506, "Signal name is not valid";
    ERR_AO_LIM = 1507, "Analog output value outside its limits";
    ERR_GO_LIM = 1508, "Group output value outside its limits";
    ERR_BUSSTATE = 1509, "I/O bus in error state (IOBusStart)";
    ERR_IODISABLE = 1510, "Time-out disabling the I/O device (IODisable)";
    ERR_IOENABLE = 1511, "Time-out enabling the I/O device (IOEnable)";
    ERR_NAME_INVALID = 1512, "I/O device or bus name not found";
    ERR_TRUSTLEVEL = 1513, "I/O device cannot be disabled (its trust level)";
    ERR_CALLIO_INTER = 1514, "IOEnable or IODisable interrupted by another request for the same device";
    ERR_SOCK_CLOSED = 1601, "Socket closed";
    ERR_SOCK_TIMEOUT = 1602, "Socket time-out";
    ERR_FILEOPEN = 1603, "File cannot be opened";
    ERR_FILEACC = 1604, "File access error";
    ERR_FILNOTFND = 1605, "File not found";
    ERR_FILESIZE = 1606, "File too large";
    ERR_RANYBIN_EOF = 1607, "End of file";
    ERR_FILEEXIST = 1608, "File already exists";
    ERR_RANYBIN_CHK = 1609, "Check sum error in binary data";
    ERR_RCVDATA = 1610, "Data read is not a number";
    ERR_IOERROR = 1611, "Input/output error while loading or saving a program module";
    ERR_DEV_MAXTIME = 1612, "Time-out reading from a file or serial channel";
    // The socket errors beyond the first two take 1650 on (1603-1649: files).
    ERR_SOCK_ADDR_INVALID = 1650, "Socket address not valid (not an IPv4 address of a reachable host)";
    ERR_SOCK_ADDR_INUSE = 1651, "Socket address and port already in use";
    ERR_SOCK_IS_BOUND = 1652, "Socket already bound";
    ERR_SOCK_IS_CONN = 1653, "Socket already connected";
    ERR_SOCK_NET_UNREACH = 1654, "Network or host unreachable";
    ERR_SOCK_NOT_BOUND = 1655, "Socket not bound (or not listening)";
    ERR_SOCK_NOT_CONN = 1656, "Socket not connected";
    ERR_SOCK_UNSPEC = 1657, "Socket error";
    ERR_UDPUC_COMM = 1701, "UdpUc communication error (no data from the device)";
    ERR_CFG_NOTFND = 1801, "Configuration data not found";
    ERR_CFG_ILLTYPE = 1802, "Configuration data of another type";
    ERR_CFG_LIMIT = 1803, "Configuration data limits violated";
    ERR_CFG_OUTOFBOUNDS = 1804, "Configuration list number out of bounds";
    ERR_CFG_WRITEFILE = 1805, "Configuration file cannot be written";
    ERR_CFG_ILL_DOMAIN = 1806, "Configuration domain not valid or not in use";
    ERR_TXTNOEXIST = 1807, "Text table or text does not exist";
    ERR_SYMBOL_TYPE = 1808, "Data object of another type";
    ERR_INVDIM = 1809, "Data object of other dimensions";
    ERR_CFG_INTERNAL = 1810, "Internal configuration parameter cannot be read or written";
    ERR_SC_WRITE = 1811, "Error sending to the external computer (SCWrite)";
    ERR_WAITSYNCTASK = 1901, "WaitSyncTask time-out (not every task arrived)";
    ERR_RMQ_DIM = 1902, "RAPID message data of other dimensions";
    ERR_RMQ_FULL = 1903, "RAPID message queue of the receiver is full";
    ERR_RMQ_INVALID = 1904, "RAPID message slot not valid";
    ERR_RMQ_INVMSG = 1905, "RAPID message not valid";
    ERR_RMQ_MSGSIZE = 1906, "RAPID message larger than the receiver's queue allows";
    ERR_RMQ_NAME = 1907, "RAPID message queue name not found";
    ERR_RMQ_NOMSG = 1908, "No message in the RAPID message queue";
    ERR_RMQ_TIMEOUT = 1909, "No RAPID message arrived in time";
    ERR_RMQ_VALUE = 1910, "RAPID message data of another type";
    ERR_TASKNAME = 1911, "Task name not found in the system";
    ERR_NOT_MOVETASK = 1912, "The task is not a motion task";
}

/// `LONG_JMP_ALL_ERR`: not an error but a wildcard for the list of an `ERROR (…)` handler,
/// which then takes every error, those passed up from called routines included (ABB's
/// "error recovery with long jump"). A number no error has, in the routines group.
pub const LONG_JMP_ALL_ERR: i32 = 1117;

/// The constant with this (case-insensitive) name.
pub fn by_name(name: &str) -> Option<&'static ErrDef> {
    ERRORS.iter().find(|e| e.name.eq_ignore_ascii_case(name))
}

/// The constant with this number.
pub fn by_num(num: i32) -> Option<&'static ErrDef> {
    ERRORS.iter().find(|e| e.num == num)
}

/// `ERR_NAME (number)` for a system error, `error number` for user and booked ones.
pub fn describe(num: i32) -> String {
    match by_num(num) {
        Some(e) => format!("{} ({})", e.name, e.num),
        None => format!("error {num}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_unique_and_outside_user_and_booking_ranges() {
        let mut seen = std::collections::HashSet::new();
        for e in ERRORS {
            assert!(seen.insert(e.num), "duplicate {}", e.num);
            assert!(e.num > BOOK_LAST, "{} collides", e.name);
            assert!(e.name.starts_with("ERR_"));
        }
        assert!(by_num(LONG_JMP_ALL_ERR).is_none());
        assert_eq!(by_name("err_divzero").map(|e| e.num), Some(ERR_DIVZERO));
        assert_eq!(describe(ERR_DIVZERO), "ERR_DIVZERO (1001)");
        assert_eq!(describe(7), "error 7");
    }
}
