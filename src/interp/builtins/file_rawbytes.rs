//! Raw data on files: `WriteRawBytes` and `ReadRawBytes` between a `rawbytes` variable and
//! an `iodev` opened with `Open … \Bin` (sockets take raw data through `SocketSend
//! \RawData` and `SocketReceive \RawData`).
//!
//! `ReadRawBytes` reads up to `NoOfBytes` bytes into `RawData` from index 1 and sets its
//! length to the number read; the end of the file before any byte is `ERR_RANYBIN_EOF`
//! (a file has everything already there, so `\Time` never runs out).

use super::rawbytes::{raw_of, raw_value};
use super::{Ctx, Registry};
use crate::functions::raw_bytes::CAPACITY;
use crate::interp::errnum;
use crate::interp::error::Exec;
use crate::interp::value::Value;

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    r.add(
        r"PROC WriteRawBytes(VAR iodev IODevice, VAR rawbytes RawData, \num NoOfBytes)",
        |cx| {
            let raw = raw_of(cx, 1)?;
            let n = if cx.present(2) {
                let n = cx.int(2, "NoOfBytes")?;
                if !(0..=raw.len() as i64).contains(&n) {
                    return Err(cx.error(
                        errnum::ERR_ARGVALERR,
                        format!(
                            "NoOfBytes must be 0 … {} (the valid bytes of RawData), not {n}",
                            raw.len()
                        ),
                    ));
                }
                n as usize
            } else {
                raw.len()
            };
            let bytes = raw.get(..n).unwrap_or(&raw).to_vec();
            super::files::with_handle(cx, 0, |h| h.write_bytes(&bytes))?;
            Ok(Value::Absent)
        },
    );
    r.add(
        r"PROC ReadRawBytes(VAR iodev IODevice, VAR rawbytes RawData, num NoOfBytes, \num Time)",
        read_raw_bytes,
    );
}

fn read_raw_bytes(cx: &mut Ctx<'_>) -> Exec<Value> {
    let n = cx.int(2, "NoOfBytes")?;
    if !(1..=CAPACITY as i64).contains(&n) {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("NoOfBytes must be 1 … {CAPACITY}, not {n}"),
        ));
    }
    if let Some(t) = cx.opt_f64(3)?
        && (t.is_nan() || t <= 0.0)
    {
        return Err(cx.error(
            errnum::ERR_ARGVALERR,
            format!("\\Time must be more than 0 s, not {t}"),
        ));
    }
    let bytes = super::files::with_handle(cx, 0, |h| h.read_bytes(n as usize))?;
    if bytes.is_empty() {
        return Err(cx.error(
            errnum::ERR_RANYBIN_EOF,
            "the end of the file was reached before any byte was read",
        ));
    }
    cx.set(1, raw_value(&bytes))?;
    Ok(Value::Absent)
}
