//! `--egm-log FILE.csv`: a writer thread that takes log rows from the cycle hook (a bounded channel, so the cycle never waits for the file) and writes them with [`EgmLogWriter`].

use std::io::Write;
use std::sync::mpsc::{self, SyncSender};
use std::thread::JoinHandle;

use crate::egm::message_log::EgmLogWriter;

use super::egm_hook::NamedRow;

/// Rows buffered between the cycle and the writer (≈ 65 s of one identity at 4 ms).
const ROW_BUFFER: usize = 16_384;

/// The writer thread.
pub(super) struct Logger {
    thread: JoinHandle<Result<u64, String>>,
}

impl Logger {
    /// Starts the thread writing to `out`; rows go into the returned sender. The thread ends
    /// when every sender is dropped.
    pub(super) fn start(
        out: Box<dyn Write + Send>,
    ) -> Result<(Logger, SyncSender<NamedRow>), String> {
        let (tx, rx) = mpsc::sync_channel::<NamedRow>(ROW_BUFFER);
        let mut writer =
            EgmLogWriter::new(out).map_err(|e| format!("cannot write the EGM log: {e}"))?;
        let thread = std::thread::Builder::new()
            .name("rapidvc-egm-log".into())
            .spawn(move || {
                let mut written = 0u64;
                let mut first_error = None;
                while let Ok((name, row)) = rx.recv() {
                    match writer.write_row(&name, &row) {
                        Ok(()) => written += 1,
                        Err(e) => {
                            first_error.get_or_insert_with(|| e.to_string());
                        }
                    }
                }
                if let Err(e) = writer.flush() {
                    first_error.get_or_insert_with(|| e.to_string());
                }
                match first_error {
                    Some(e) => Err(format!("cannot write the EGM log: {e}")),
                    None => Ok(written),
                }
            })
            .map_err(|e| format!("cannot start the EGM log writer: {e}"))?;
        Ok((Logger { thread }, tx))
    }

    /// Waits for the thread (after every sender is gone); the rows written.
    pub(super) fn finish(self) -> Result<u64, String> {
        self.thread
            .join()
            .map_err(|_| "the EGM log writer panicked".to_string())?
    }
}
