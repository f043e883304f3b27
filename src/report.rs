//! What a run leaves behind: CSV traces (one row per motion cycle) and plots of joints, TCP
//! and speed with the program's instructions marked. Both are [`crate::controller::TickSink`]s.

pub mod num;
pub mod plot;
pub mod trace;

pub use plot::{PlotData, PlotRecorder};
pub use trace::{TRACE_HEADER, TraceWriter};
