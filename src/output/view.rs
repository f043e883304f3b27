//! See the robot: a self-contained 3D replay page of a run (`rapidvc run --view FILE.html`)
//! and a live view served over HTTP with a WebSocket stream (`--view-live`, [`live`]).
//!
//! The view is one more reader of the controller's per-cycle stream, like the trace and the
//! plot: a [`ViewSink`] among the controller's [`TickSink`]s records the motion cycles (thinned
//! to what the page can draw within a tolerance, [`decimate`]), and the EGM and
//! path-correction samples of the output [`Feed`](crate::output::Feed); the program's TP
//! output and events reach it through [`ViewSession::output`], stamped with the robot time
//! of the last recorded cycle. Nothing here runs in the motion cycle: in real time the sink
//! runs on the recorder thread, and the live stream is a bounded broadcast that drops the
//! oldest messages for a viewer that falls behind.
//!
//! The page (`src/output/view/assets/`: plain JavaScript, WebGL and a 2D canvas, no third-party
//! code) draws the arm from the robot model's OPW parameters with the same joint chain as
//! [`kinematics::joint_frames`], and is embedded with its data into one HTML file that needs
//! no network.

pub mod decimate;
pub mod encode;
pub mod kinematics;
pub mod live;
pub mod record;

use std::path::Path;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::Duration;

use tokio::sync::broadcast;

use crate::controller::TickSink;
use crate::interp::Output;
use crate::interp::pers::PersValue;
use crate::interp::value::Value;
use crate::motion::Setpoint;
use crate::output::{FeedItem, FeedRx};
use crate::robot::{Pose, Robot, pose_from_pos_quat};
use crate::source::{SourceId, SourceMap};

pub use record::{LogKind, Recording};

/// The page's HTML skeleton, style and script (embedded into every page).
const PAGE_HTML: &str = include_str!("view/assets/view.html");
const PAGE_CSS: &str = include_str!("view/assets/view.css");
const PAGE_JS: &str = include_str!("view/assets/view.js");

/// Robot time between two rows of the live stream (µs): 50 rows per second.
pub const LIVE_INTERVAL_US: i64 = 20_000;
/// Messages buffered per live viewer; a viewer that falls further behind loses the oldest.
pub const LIVE_BUFFER: usize = 512;

/// A work object drawn as a frame.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedFrame {
    /// The data's name.
    pub name: String,
    /// The object frame in world (uframe · oframe), mm.
    pub pose: Pose,
}

/// What the page shows besides the recording.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The page title (program files and robot).
    pub title: String,
    /// The robot (model and base).
    pub robot: Robot,
    /// The motion cycle.
    pub period: Duration,
    /// The source files shown beside the robot (the program's own modules).
    pub files: Vec<SourceId>,
    /// Where instruction spans point.
    pub sources: Arc<SourceMap>,
    /// Work objects.
    pub frames: Vec<NamedFrame>,
}

struct Shared {
    scene: Mutex<Scene>,
    rec: Mutex<Recording>,
    live: Mutex<Option<broadcast::Sender<Arc<str>>>>,
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

/// A view of one run: cheap to clone, shared by the sink, the output tee and the live
/// server.
#[derive(Clone)]
pub struct ViewSession {
    shared: Arc<Shared>,
}

impl std::fmt::Debug for ViewSession {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ViewSession").finish_non_exhaustive()
    }
}

impl ViewSession {
    /// A view of a run on `scene`.
    pub fn new(scene: Scene) -> ViewSession {
        let period_us = i64::try_from(scene.period.as_micros()).unwrap_or(i64::MAX);
        ViewSession {
            shared: Arc::new(Shared {
                scene: Mutex::new(scene),
                rec: Mutex::new(Recording::new(period_us)),
                live: Mutex::new(None),
            }),
        }
    }

    /// The sink to put among the controller's sinks; `feed` (when the run uses EGM) brings
    /// the EGM and path-correction samples.
    pub fn sink(&self, feed: Option<FeedRx>) -> ViewSink {
        let scene = lock(&self.shared.scene);
        ViewSink {
            session: self.clone(),
            sources: Arc::clone(&scene.sources),
            files: scene.files.iter().map(|f| f.0).collect(),
            feed,
            last_sent: None,
            instrs_sent: 0,
            egm_unsent: None,
            path_unsent: None,
        }
    }

    /// Work objects from the program's persistents (`wobjdata` fixed in the world with a
    /// programmed user frame; robot-held ones are not drawn).
    pub fn set_frames_from(&self, pers: &[PersValue]) {
        let frames: Vec<NamedFrame> = pers
            .iter()
            .filter(|p| p.ty.eq_ignore_ascii_case("wobjdata"))
            .filter_map(|p| {
                wobj_frame(&p.value).map(|pose| NamedFrame {
                    name: p.name.clone(),
                    pose,
                })
            })
            .collect();
        lock(&self.shared.scene).frames = frames;
    }

    /// A program output (TP line, event, `ErrWrite`), at the robot time of the last recorded
    /// cycle.
    pub fn output(&self, o: &Output) {
        let entry = {
            let mut rec = lock(&self.shared.rec);
            rec.output(o);
            rec.log.last().cloned().map(|e| (rec.log.len() - 1, e))
        };
        if let Some((n, e)) = entry {
            self.broadcast(&encode::live_log(n, &e));
        }
    }

    /// How the program ended (the page shows it as the last log line).
    pub fn end(&self, text: &str) {
        let entry = {
            let mut rec = lock(&self.shared.rec);
            rec.end(text.to_string());
            rec.log.last().cloned().map(|e| (rec.log.len() - 1, e))
        };
        if let Some((n, e)) = entry {
            self.broadcast(&encode::live_log(n, &e));
        }
    }

    /// The recording so far, with the rows not yet kept (what a viewer joining now sees).
    pub fn snapshot(&self) -> Recording {
        lock(&self.shared.rec).snapshot()
    }

    /// The scene.
    pub fn scene(&self) -> Scene {
        lock(&self.shared.scene).clone()
    }

    /// The page with everything recorded so far; `live` makes it connect to the stream of
    /// the server that serves it.
    pub fn page(&self, live: bool) -> String {
        let rec = self.snapshot();
        let scene = self.scene();
        page_html(&encode::page_data(&scene, &rec, live))
    }

    /// Write the replay page (after the run). Returns its size in bytes.
    pub fn write_page(&self, path: &Path) -> Result<u64, String> {
        let html = self.page(false);
        std::fs::write(path, &html)
            .map_err(|e| format!("cannot write the view {}: {e}", path.display()))?;
        Ok(html.len() as u64)
    }

    /// Start the live stream (before the run): live viewers subscribe to it.
    pub fn enable_live(&self) {
        let mut live = lock(&self.shared.live);
        if live.is_none() {
            *live = Some(broadcast::channel(LIVE_BUFFER).0);
        }
    }

    /// A live viewer's subscription; `None` when the stream is not (or no longer) running.
    pub fn subscribe(&self) -> Option<broadcast::Receiver<Arc<str>>> {
        lock(&self.shared.live).as_ref().map(|tx| tx.subscribe())
    }

    /// End the live stream: viewers get an `end` message and their connection closes.
    pub fn close_live(&self) {
        let now = lock(&self.shared.rec).now;
        self.broadcast(&encode::live_end(now));
        lock(&self.shared.live).take();
    }

    /// Send a message to the live viewers (never blocks; nobody listening is fine).
    fn broadcast(&self, msg: &serde_json::Value) {
        let live = lock(&self.shared.live);
        if let Some(tx) = live.as_ref()
            && tx.receiver_count() > 0
        {
            let _ = tx.send(Arc::from(msg.to_string()));
        }
    }

    fn is_live(&self) -> bool {
        lock(&self.shared.live).is_some()
    }
}

/// `uframe · oframe` of a `wobjdata` value that is fixed in the world with a programmed user
/// frame.
fn wobj_frame(v: &Value) -> Option<Pose> {
    let f = v.fields()?;
    let robhold = f.first()?.as_bool()?;
    let ufprog = f.get(1)?.as_bool()?;
    if robhold || !ufprog {
        return None;
    }
    let pose = |v: &Value| -> Option<Pose> {
        let p = v.fields()?;
        let pos = p.first()?.num_fields::<3>()?;
        let rot = p.get(1)?.num_fields::<4>()?;
        let pose = pose_from_pos_quat(pos, rot);
        crate::robot::units::pose_is_finite(&pose).then_some(pose)
    };
    Some(pose(f.get(3)?)? * pose(f.get(4)?)?)
}

/// The page: the skeleton with the style, the script and the data inlined (`</` in the data
/// is escaped so no text of the program can end the script element).
pub fn page_html(data: &serde_json::Value) -> String {
    let json = data.to_string().replace("</", "<\\/");
    PAGE_HTML
        .replacen("/*@RAPIDVC_CSS@*/", PAGE_CSS, 1)
        .replacen("/*@RAPIDVC_JS@*/", PAGE_JS, 1)
        .replacen("@RAPIDVC_DATA@", &json, 1)
}

/// The view's [`TickSink`]: records every cycle and, when live, streams rows at
/// [`LIVE_INTERVAL_US`].
pub struct ViewSink {
    session: ViewSession,
    sources: Arc<SourceMap>,
    files: Vec<u32>,
    feed: Option<FeedRx>,
    last_sent: Option<(i64, i32)>,
    instrs_sent: usize,
    egm_unsent: Option<record::EgmRow>,
    path_unsent: Option<record::PathRow>,
}

impl TickSink for ViewSink {
    fn record(&mut self, sp: &Setpoint) {
        let live = self.session.is_live();
        let mut msgs: Vec<serde_json::Value> = Vec::new();
        {
            let mut rec = lock(&self.session.shared.rec);
            let row = rec.record(sp, Some(&self.sources), &self.files);
            if let Some(feed) = &mut self.feed {
                let states_before = rec.egm_states.len();
                feed.drain_until(sp.time, |item| {
                    rec.absorb(item, Some(&row));
                    if live {
                        match item {
                            FeedItem::Egm(_) => self.egm_unsent = rec.egm_last(),
                            FeedItem::PathCorr(_) => self.path_unsent = rec.path_last(),
                            FeedItem::EgmState(..) => {}
                        }
                    }
                });
                if live {
                    for (t, s) in rec.egm_states.iter().skip(states_before) {
                        msgs.push(encode::live_egm_state(*t, *s));
                    }
                }
            }
            if live {
                while let Some(i) = rec.instrs.get(self.instrs_sent) {
                    msgs.push(encode::live_instr(self.instrs_sent, i));
                    self.instrs_sent += 1;
                }
                let due = self
                    .last_sent
                    .is_none_or(|(t, instr)| row.t - t >= LIVE_INTERVAL_US || instr != row.instr);
                if due {
                    self.last_sent = Some((row.t, row.instr));
                    msgs.push(encode::live_row(&row));
                    if let Some(e) = self.egm_unsent.take() {
                        msgs.push(encode::live_egm(&e));
                    }
                    if let Some(p) = self.path_unsent.take() {
                        msgs.push(encode::live_path(&p));
                    }
                }
            }
        }
        for m in &msgs {
            self.session.broadcast(m);
        }
    }

    fn finish(&mut self) -> Result<(), String> {
        if let Some(feed) = &mut self.feed {
            let mut rec = lock(&self.session.shared.rec);
            feed.drain_all(|item| rec.absorb(item, None));
        }
        lock(&self.session.shared.rec).finish();
        Ok(())
    }
}
