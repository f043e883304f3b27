//! What a run leaves behind: CSV traces (one row per motion cycle), plots of joints, TCP
//! and speed with the program's instructions marked, progress numbers, and the 3D view (a
//! replay page and a live view), plus EGM tracking and path correction when the controller
//! feeds them through a [`Feed`]. They are [`crate::controller::TickSink`]s: readers of the
//! cycles, never called from inside one.

pub mod number_format;
pub mod plot;
pub mod progress;
pub mod trace;
pub mod view;

pub use crate::controller::sample_feed::{
    EgmAxes, EgmSample, EgmTraceState, Feed, FeedItem, FeedRx, PathCorrSample,
};
pub use plot::{PlotData, PlotRecorder};
pub use progress::{Progress, ProgressSink};
pub use trace::{TRACE_HEADER, TraceColumns, TraceWriter};
