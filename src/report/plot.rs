//! `--plot FILE.svg|.png`: joint angles, TCP position and TCP speed against time, with the
//! program's move instructions marked by vertical lines and labels (`MoveL L12`), sized and
//! coloured to be projected in a classroom.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Once};

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::controller::TickSink;
use crate::motion::Setpoint;
use crate::source::SourceMap;

/// Picture size in pixels.
const SIZE: (u32, u32) = (1600, 1100);
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
}

/// Collects setpoints and renders the plot when the run finishes.
pub struct PlotRecorder {
    path: PathBuf,
    lines: Option<Arc<SourceMap>>,
    data: PlotData,
    last_id: Option<u64>,
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
        })
    }

    /// The data collected so far.
    pub fn data(&self) -> &PlotData {
        &self.data
    }
}

impl TickSink for PlotRecorder {
    fn record(&mut self, sp: &Setpoint) {
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
    match Format::of(path)? {
        Format::Svg => {
            let root = SVGBackend::new(path, SIZE).into_drawing_area();
            draw(&root, data).map_err(fail)?;
            root.present().map_err(|e| fail(e.to_string()))
        }
        Format::Png => {
            let root = BitMapBackend::new(path, SIZE).into_drawing_area();
            draw(&root, data).map_err(fail)?;
            root.present().map_err(|e| fail(e.to_string()))
        }
    }
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
    let joints_h = h * 45 / 100;
    let tcp_h = h * 33 / 100;
    let (top, rest) = root.split_vertically(joints_h);
    let (middle, bottom) = rest.split_vertically(tcp_h);
    let stride = data.t.len() / MAX_POINTS + 1;
    let t0 = data.t.first().copied().unwrap_or(0.0);
    let t1 = data.t.last().copied().unwrap_or(1.0).max(t0 + 1e-3);

    let joint_series: Vec<(String, RGBColor, Vec<f64>)> = (0..6)
        .map(|i| {
            let ys = data
                .joints
                .iter()
                .map(|q| q.get(i).copied().unwrap_or(0.0))
                .collect();
            (
                format!("J{}", i + 1),
                JOINT_COLORS.get(i).copied().unwrap_or(BLACK),
                ys,
            )
        })
        .collect();
    panel(
        &top,
        data,
        stride,
        (t0, t1),
        "Joint angles",
        "deg",
        &joint_series,
        true,
    )
    .map_err(err)?;

    let tcp_series: Vec<(String, RGBColor, Vec<f64>)> = ["x", "y", "z"]
        .iter()
        .enumerate()
        .map(|(i, name)| {
            let ys = data
                .tcp
                .iter()
                .map(|p| p.get(i).copied().unwrap_or(0.0))
                .collect();
            (
                name.to_string(),
                XYZ_COLORS.get(i).copied().unwrap_or(BLACK),
                ys,
            )
        })
        .collect();
    panel(
        &middle,
        data,
        stride,
        (t0, t1),
        "TCP position (world)",
        "mm",
        &tcp_series,
        false,
    )
    .map_err(err)?;

    let speed_series = vec![("speed".to_string(), BLACK, data.speed.clone())];
    panel(
        &bottom,
        data,
        stride,
        (t0, t1),
        "TCP speed",
        "mm/s",
        &speed_series,
        false,
    )
    .map_err(err)?;
    Ok(())
}

#[allow(clippy::too_many_arguments)]
fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    data: &PlotData,
    stride: usize,
    (t0, t1): (f64, f64),
    caption: &str,
    unit: &str,
    series: &[(String, RGBColor, Vec<f64>)],
    labels: bool,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (mut lo, mut hi) = series
        .iter()
        .flat_map(|(_, _, ys)| ys.iter().copied())
        .filter(|y| y.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
            (a.min(y), b.max(y))
        });
    if !(lo.is_finite() && hi.is_finite()) {
        (lo, hi) = (-1.0, 1.0);
    }
    let pad = ((hi - lo) * 0.08).max(1.0);
    let (lo, hi) = (lo - pad, hi + pad * if labels { 3.0 } else { 1.0 });
    let mut chart = ChartBuilder::on(area)
        .margin_left(20)
        .margin_right(30)
        .margin_top(10)
        .caption(caption, (FONT, 24).into_font())
        .x_label_area_size(40)
        .y_label_area_size(80)
        .build_cartesian_2d(t0..t1, lo..hi)?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc(unit)
        .y_label_formatter(&|v| format!("{v:.0}"))
        .label_style((FONT, 18).into_font())
        .axis_desc_style((FONT, 18).into_font())
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    for m in &data.marks {
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(m.t, lo), (m.t, hi)],
            MARK_COLOR.stroke_width(1),
        )))?;
    }
    if labels {
        draw_labels(&mut chart, data, (t0, t1), hi, pad)?;
    }
    for (name, color, ys) in series {
        let pts = data
            .t
            .iter()
            .zip(ys)
            .enumerate()
            .filter(|(k, _)| k % stride == 0 || k + 1 == data.t.len())
            .map(|(_, (t, y))| (*t, *y));
        let color = *color;
        chart
            .draw_series(LineSeries::new(pts, color.stroke_width(2)))?
            .label(name.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(3))
            });
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::MiddleRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FONT, 18).into_font())
        .draw()?;
    Ok(())
}

/// Instruction labels along the top of the joint panel, in two staggered rows, skipping a
/// label when it would overlap the previous one in its row.
fn draw_labels<DB: DrawingBackend, CT>(
    chart: &mut ChartContext<'_, DB, CT>,
    data: &PlotData,
    (t0, t1): (f64, f64),
    hi: f64,
    pad: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>
where
    CT: plotters::coord::CoordTranslate<From = (f64, f64)>,
{
    let width_px = f64::from(SIZE.0 - 130);
    let px_per_s = width_px / (t1 - t0);
    let mut row_end = [f64::NEG_INFINITY; 2];
    for (k, m) in data.marks.iter().enumerate() {
        let row = k % 2;
        let x = (m.t - t0) * px_per_s;
        let w = m.label.chars().count() as f64 * 9.5 + 10.0;
        let Some(end) = row_end.get_mut(row) else {
            continue;
        };
        if x < *end {
            continue;
        }
        *end = x + w;
        let y = hi - pad * (0.3 + 1.1 * row as f64);
        chart.draw_series(std::iter::once(Text::new(
            m.label.clone(),
            (m.t, y),
            (FONT, 17).into_font().color(&BLACK),
        )))?;
    }
    Ok(())
}
