//! Consumers of the per-cycle setpoints (trace files, plot recorders, progress): they run
//! outside the motion cycle, on the caller's thread in virtual time and on a recorder thread
//! in real time.

use crate::motion::Setpoint;

/// Receives every motion cycle's setpoint, in order.
pub trait TickSink: Send {
    /// One cycle. Implementations keep their first error and report it from `finish`.
    fn record(&mut self, sp: &Setpoint);

    /// The run is over: flush, write files, report the first error.
    fn finish(&mut self) -> Result<(), String> {
        Ok(())
    }
}
