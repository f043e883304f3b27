//! What a run leaves behind: CSV traces (one row per motion cycle) and plots of joints, TCP
//! and speed with the program's instructions marked, plus EGM tracking and path correction when
//! the controller feeds them through a [`Feed`]. Both are [`crate::controller::TickSink`]s.

pub mod feed;
pub mod number_format;
pub mod plot;
pub mod progress;
pub mod trace;

pub use feed::{EgmAxes, EgmSample, EgmTraceState, Feed, FeedItem, FeedRx, PathCorrSample};
pub use plot::{PlotData, PlotRecorder};
pub use progress::{Progress, ProgressSink};
pub use trace::{TRACE_HEADER, TraceColumns, TraceWriter};
