//! `--plot FILE.svg|.png`: joint angles, TCP position and TCP speed against time, with the
//! program's move instructions marked by vertical lines and labels (`MoveL L12`), sized and
//! coloured to be projected in a classroom. When the controller fed EGM or path-correction
//! samples (through a [`Feed`](crate::controller::sample_feed::Feed) subscribed with
//! [`PlotRecorder::with_feed`]), sections below show EGM reference against feedback and the
//! tracking error, and the programmed, measured and corrected path in the path frame.

mod egm_section;
mod panel;
mod pathcorr_section;

use std::path::{Path, PathBuf};
use std::sync::{Arc, Once};

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::controller::TickSink;
use crate::motion::Setpoint;
use crate::source::SourceMap;

use crate::controller::sample_feed::{EgmSample, EgmTraceState, FeedItem, FeedRx, PathCorrSample};
use panel::{Curve, Panel, Stroke, VLine};

/// Picture width and the height of the joint/TCP/speed part, in pixels.
const SIZE: (u32, u32) = (1600, 1100);
/// Height added for the path-correction section.
const PATHCORR_HEIGHT: u32 = 950;
/// At most this many points per curve are drawn (longer runs are thinned evenly).
const MAX_POINTS: usize = 4000;
/// The embedded font (DejaVu Sans subset, see `assets/fonts/README.md`).
static FONT_BYTES: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans-subset.ttf");
const FONT: &str = "sans-serif";

/// A move instruction's start, for the markers.
#[derive(Clone, Debug, PartialEq)]
pub struct Mark {
    /// Time (s).
    pub t: f64,
    /// Label, e.g. `MoveL L12`.
    pub label: String,
}

/// The curves of a plot.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PlotData {
    /// Title at the top.
    pub title: String,
    /// Time of each sample (s).
    pub t: Vec<f64>,
    /// Axis values (deg).
    pub joints: Vec<[f64; 6]>,
    /// TCP position in world (mm).
    pub tcp: Vec<[f64; 3]>,
    /// TCP speed (mm/s).
    pub speed: Vec<f64>,
    /// Instruction starts.
    pub marks: Vec<Mark>,
    /// EGM cycles, in time order.
    pub egm: Vec<EgmSample>,
    /// EGM state changes: time (s) and the new state.
    pub egm_states: Vec<(f64, EgmTraceState)>,
    /// Path-correction cycles, in time order.
    pub pathcorr: Vec<PathCorrSample>,
}

impl PlotData {
    /// Add one fed item (EGM samples and state changes, path-correction samples).
    pub fn absorb(&mut self, item: FeedItem) {
        let (t, state) = match item {
            FeedItem::Egm(s) => {
                self.egm.push(s);
                (s.t, s.state)
            }
            FeedItem::EgmState(t, state) => (t, state),
            FeedItem::PathCorr(s) => {
                self.pathcorr.push(s);
                return;
            }
        };
        if self.egm_states.last().map(|(_, s)| *s) != Some(state) {
            self.egm_states.push((t.as_secs_f64(), state));
        }
    }
}

/// Collects setpoints and renders the plot when the run finishes.
pub struct PlotRecorder {
    path: PathBuf,
    lines: Option<Arc<SourceMap>>,
    data: PlotData,
    last_id: Option<u64>,
    feed: Option<FeedRx>,
}

impl PlotRecorder {
    /// A recorder that will write `path` (`.svg` or `.png`). `lines` resolves instruction
    /// spans to line numbers for the labels.
    pub fn new(
        path: &Path,
        title: &str,
        lines: Option<Arc<SourceMap>>,
    ) -> Result<PlotRecorder, String> {
        Format::of(path)?;
        Ok(PlotRecorder {
            path: path.to_path_buf(),
            lines,
            data: PlotData {
                title: title.to_string(),
                ..PlotData::default()
            },
            last_id: None,
            feed: None,
        })
    }

    /// Also draw what is pushed into the feed `feed` was subscribed to (EGM and path
    /// correction sections).
    pub fn with_feed(mut self, feed: FeedRx) -> PlotRecorder {
        self.feed = Some(feed);
        self
    }

    /// The data collected so far.
    pub fn data(&self) -> &PlotData {
        &self.data
    }
}

impl TickSink for PlotRecorder {
    fn record(&mut self, sp: &Setpoint) {
        if let Some(feed) = &mut self.feed {
            let data = &mut self.data;
            feed.drain_until(sp.time, |item| data.absorb(item));
        }
        let t = sp.time.as_secs_f64();
        let p = sp.tcp.translation.vector;
        self.data.t.push(t);
        self.data.joints.push(sp.joints);
        self.data.tcp.push([p.x, p.y, p.z]);
        self.data.speed.push(sp.speed);
        if let Some(i) = sp.instr
            && self.last_id != Some(i.id)
        {
            self.last_id = Some(i.id);
            let line = match (&self.lines, i.source) {
                (Some(map), Some(span)) => {
                    format!(" L{}", map.get(span.source).line_col(span.start).0)
                }
                _ => String::new(),
            };
            // The setpoint is one cycle into the move: mark where it began.
            self.data.marks.push(Mark {
                t: self
                    .data
                    .t
                    .get(self.data.t.len().saturating_sub(2))
                    .copied()
                    .unwrap_or(t),
                label: format!("{}{}", i.name, line),
            });
        }
    }

    fn finish(&mut self) -> Result<(), String> {
        if let Some(feed) = &mut self.feed {
            let data = &mut self.data;
            feed.drain_all(|item| data.absorb(item));
        }
        render(&self.path, &self.data)
    }
}

enum Format {
    Svg,
    Png,
}

impl Format {
    fn of(path: &Path) -> Result<Format, String> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("svg") => Ok(Format::Svg),
            Some("png") => Ok(Format::Png),
            _ => Err(format!(
                "plot {}: the file name must end in .svg or .png",
                path.display()
            )),
        }
    }
}

fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The embedded font is a valid TrueType file; if registration ever failed, text would
        // be missing and drawing reports the error.
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, FONT_BYTES);
    });
}

/// Render `data` to `path` (`.svg` or `.png`).
pub fn render(path: &Path, data: &PlotData) -> Result<(), String> {
    register_font();
    let fail = |e: String| format!("cannot draw the plot {}: {e}", path.display());
    let size = (SIZE.0, total_height(data));
    match Format::of(path)? {
        Format::Svg => {
            let root = SVGBackend::new(path, size).into_drawing_area();
            draw(&root, data).map_err(fail)?;
            root.present().map_err(|e| fail(e.to_string()))
        }
        Format::Png => {
            let root = BitMapBackend::new(path, size).into_drawing_area();
            draw(&root, data).map_err(fail)?;
            root.present().map_err(|e| fail(e.to_string()))
        }
    }
}

fn total_height(data: &PlotData) -> u32 {
    let mut h = SIZE.1;
    h += egm_section::height(data);
    if !data.pathcorr.is_empty() {
        h += PATHCORR_HEIGHT;
    }
    h
}

const JOINT_COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
];
const XYZ_COLORS: [RGBColor; 3] = [
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(31, 119, 180),
];
const MARK_COLOR: RGBColor = RGBColor(150, 150, 150);

fn draw<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, data: &PlotData) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let root = root
        .titled(&data.title, (FONT, 32).into_font().color(&BLACK))
        .map_err(err)?;
    let (_, h) = root.dim_in_pixel();
    let egm_h = egm_section::height(data);
    let pathcorr_h = if data.pathcorr.is_empty() {
        0
    } else {
        PATHCORR_HEIGHT
    };
    let motion_h = h.saturating_sub(egm_h + pathcorr_h);
    let (motion, rest) = root.split_vertically(motion_h);
    let (egm_area, pathcorr_area) = rest.split_vertically(egm_h);
    draw_motion(&motion, data).map_err(err)?;
    if egm_h > 0 {
        egm_section::draw(&egm_area, data).map_err(err)?;
    }
    if !data.pathcorr.is_empty() {
        pathcorr_section::draw(&pathcorr_area, data).map_err(err)?;
    }
    Ok(())
}

/// Thin a series of `n` points evenly to at most [`MAX_POINTS`] (the last is always kept).
fn keep(k: usize, n: usize) -> bool {
    let stride = n / MAX_POINTS + 1;
    k.is_multiple_of(stride) || k + 1 == n
}

/// Joints, TCP and speed against time.
fn draw_motion<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    data: &PlotData,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (_, h) = area.dim_in_pixel();
    let (top, rest) = area.split_vertically(h * 45 / 100);
    let (middle, bottom) = rest.split_vertically(h * 33 / 100);
    let t0 = data.t.first().copied().unwrap_or(0.0);
    let t1 = data.t.last().copied().unwrap_or(1.0).max(t0 + 1e-3);
    let n = data.t.len();
    let series = |value: &dyn Fn(usize) -> f64| -> Vec<(f64, f64)> {
        data.t
            .iter()
            .enumerate()
            .filter(|(k, _)| keep(*k, n))
            .map(|(k, t)| (*t, value(k)))
            .collect()
    };
    let marks = |labels: bool| -> Vec<VLine> {
        data.marks
            .iter()
            .map(|m| VLine {
                x: m.t,
                label: labels.then(|| m.label.clone()),
                color: MARK_COLOR,
            })
            .collect()
    };

    let mut joints = Panel::new("Joint angles", "time (s)", "deg", (t0, t1));
    joints.curves = (0..6)
        .map(|i| {
            let pts = series(&|k| {
                data.joints
                    .get(k)
                    .and_then(|q| q.get(i))
                    .copied()
                    .unwrap_or(f64::NAN)
            });
            let color = JOINT_COLORS.get(i).copied().unwrap_or(BLACK);
            Curve::new(&format!("J{}", i + 1), color, Stroke::Solid(2), pts)
        })
        .collect();
    joints.vlines = marks(true);

    let mut tcp = Panel::new("TCP position (world)", "time (s)", "mm", (t0, t1));
    tcp.curves = ["x", "y", "z"]
        .iter()
        .enumerate()
        .map(|(i, name)| {
            let pts = series(&|k| {
                data.tcp
                    .get(k)
                    .and_then(|p| p.get(i))
                    .copied()
                    .unwrap_or(f64::NAN)
            });
            let color = XYZ_COLORS.get(i).copied().unwrap_or(BLACK);
            Curve::new(name, color, Stroke::Solid(2), pts)
        })
        .collect();
    tcp.vlines = marks(false);

    let mut speed = Panel::new("TCP speed", "time (s)", "mm/s", (t0, t1));
    let pts = series(&|k| data.speed.get(k).copied().unwrap_or(f64::NAN));
    speed.curves = vec![Curve::new("speed", BLACK, Stroke::Solid(2), pts)];
    speed.vlines = marks(false);
    let mut stack = [(joints, &top), (tcp, &middle), (speed, &bottom)];
    align(&mut stack);
    for (panel, area) in &stack {
        panel.draw(area)?;
    }
    Ok(())
}

/// Give panels stacked over the same x range one y label width, so their x axes line up.
fn align<DB: DrawingBackend>(stack: &mut [(Panel<'_>, &DrawingArea<DB, Shift>)]) {
    let w = stack
        .iter()
        .map(|(p, area)| p.y_label_px(area))
        .max()
        .unwrap_or(80);
    for (p, _) in stack.iter_mut() {
        p.min_y_label_px = w;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::controller::sample_feed::{EgmAxes, EgmSample};
    use crate::time::RobotTime;

    #[test]
    fn hostile_values_render_without_panicking() {
        let dir = std::env::temp_dir().join(format!("rapidvc-plot-unit-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut data = PlotData {
            title: "hostile".into(),
            ..PlotData::default()
        };
        for (k, v) in [0.0, f64::NAN, 1e300, f64::INFINITY, -1e300, 2.0]
            .into_iter()
            .enumerate()
        {
            data.t.push(k as f64 * 0.004);
            data.joints.push([v; 6]);
            data.tcp.push([v; 3]);
            data.speed.push(v);
            let t = RobotTime::from_nanos(k as u64 * 4_000_000);
            data.absorb(FeedItem::Egm(EgmSample {
                t,
                axes: EgmAxes::Pose,
                reference: Some([v; 6]),
                feedback: [-v; 6],
                state: EgmTraceState::Running,
                speed_limited: k % 2 == 0,
            }));
            data.absorb(FeedItem::PathCorr(PathCorrSample {
                t,
                s_mm: if k == 3 { f64::NAN } else { v },
                programmed_yz: [v, -v],
                corrected_yz: [v, v],
                measured_yz: Some([v, 0.0]),
                offset_world: None,
            }));
        }
        render(&dir.join("hostile.svg"), &data).unwrap();
        // Empty data draws empty charts.
        render(&dir.join("empty.png"), &PlotData::default()).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
