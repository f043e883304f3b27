//! One chart of a plot: curves (solid, dashed or dots; a non-finite value leaves a gap),
//! vertical event marks with staggered labels, shaded spans and a legend.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::FONT;

/// How a curve is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Stroke {
    /// A solid line this many pixels wide.
    Solid(u32),
    /// A dashed line this many pixels wide.
    Dashed(u32),
    /// Small filled circles.
    Dots,
}

/// One curve.
pub(super) struct Curve {
    /// Legend text (`None`: not in the legend).
    pub name: Option<String>,
    pub color: RGBColor,
    pub stroke: Stroke,
    pub pts: Vec<(f64, f64)>,
}

impl Curve {
    pub fn new(name: &str, color: RGBColor, stroke: Stroke, pts: Vec<(f64, f64)>) -> Curve {
        Curve {
            name: Some(name.to_string()),
            color,
            stroke,
            pts,
        }
    }

    /// A curve without a legend entry.
    pub fn unnamed(color: RGBColor, stroke: Stroke, pts: Vec<(f64, f64)>) -> Curve {
        Curve {
            name: None,
            color,
            stroke,
            pts,
        }
    }
}

/// A vertical line at `x`, labelled along the top when `label` is set.
pub(super) struct VLine {
    pub x: f64,
    pub label: Option<String>,
    pub color: RGBColor,
}

/// Shaded x intervals, with a legend entry when named.
pub(super) struct Spans {
    pub name: Option<String>,
    pub color: RGBColor,
    pub ranges: Vec<(f64, f64)>,
}

/// The y axis of a panel in its area.
struct YAxis {
    lo: f64,
    hi: f64,
    decimals: usize,
    label_px: u32,
    /// Label rows along the top and their height (px).
    rows: usize,
    room: f64,
    /// Height of the plotting area (px, estimated).
    plot_px: f64,
}

/// A chart to draw into an area.
pub(super) struct Panel<'a> {
    pub caption: &'a str,
    pub x_desc: &'a str,
    pub y_desc: &'a str,
    pub x: (f64, f64),
    pub curves: Vec<Curve>,
    pub vlines: Vec<VLine>,
    pub spans: Option<Spans>,
    /// The y range is padded by at least this much on each side.
    pub min_pad: f64,
    pub legend: SeriesLabelPosition,
    pub caption_size: u32,
    /// The y label area is at least this wide (px).
    pub min_y_label_px: u32,
}

/// Height of one row of labels (px).
const LABEL_ROW_PX: f64 = 22.0;
/// Pixels of the chart outside the plotting area, vertically (caption, x labels, margins).
const CHROME_PX: f64 = 95.0;
/// Left plus right margin (px).
const MARGIN_X_PX: u32 = 50;

impl<'a> Panel<'a> {
    pub fn new(caption: &'a str, x_desc: &'a str, y_desc: &'a str, x: (f64, f64)) -> Panel<'a> {
        Panel {
            caption,
            x_desc,
            y_desc,
            x,
            curves: Vec::new(),
            vlines: Vec::new(),
            spans: None,
            min_pad: 1.0,
            legend: SeriesLabelPosition::MiddleRight,
            caption_size: 24,
            min_y_label_px: 80,
        }
    }

    /// Draw the chart into `area`.
    pub fn draw<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let (x0, x1) = self.x;
        let (w_px, _) = area.dim_in_pixel();
        let y = self.y_axis(area);
        let (lo, hi, yd, y_label_px) = (y.lo, y.hi, y.decimals, y.label_px);
        let (rows, room, plot_px) = (y.rows, y.room, y.plot_px);
        let xd = decimals(x1 - x0);
        let plot_w = (f64::from(w_px) - f64::from(MARGIN_X_PX + y_label_px)).max(1.0);
        let mut chart = ChartBuilder::on(area)
            .margin_left(20)
            .margin_right(MARGIN_X_PX - 20)
            .margin_top(10)
            .caption(self.caption, (FONT, self.caption_size).into_font())
            .x_label_area_size(40)
            .y_label_area_size(y_label_px)
            .build_cartesian_2d(x0..x1, lo..hi)?;
        chart
            .configure_mesh()
            .x_desc(self.x_desc)
            .y_desc(self.y_desc)
            .x_label_formatter(&|v| format_tick(*v, xd))
            .y_label_formatter(&|v| format_tick(*v, yd))
            .label_style((FONT, 18).into_font())
            .axis_desc_style((FONT, 18).into_font())
            .light_line_style(WHITE.mix(0.0))
            .draw()?;
        let mut legend = false;
        if let Some(spans) = &self.spans
            && !spans.ranges.is_empty()
        {
            let fill = spans.color.mix(0.22).filled();
            let anno = chart.draw_series(
                spans
                    .ranges
                    .iter()
                    .map(|(a, b)| Rectangle::new([(a.max(x0), lo), (b.min(x1), hi)], fill)),
            )?;
            if let Some(name) = &spans.name {
                anno.label(name.as_str())
                    .legend(move |(x, y)| Rectangle::new([(x, y - 7), (x + 24, y + 7)], fill));
                legend = true;
            }
        }
        for v in &self.vlines {
            chart.draw_series(std::iter::once(PathElement::new(
                vec![(v.x, lo), (v.x, hi)],
                v.color.stroke_width(1),
            )))?;
        }
        self.draw_labels(&mut chart, plot_w, hi, (hi - lo) / plot_px)?;
        for c in &self.curves {
            legend |= c.name.is_some();
            draw_curve(&mut chart, c)?;
        }
        if legend {
            let position = match self.legend {
                // Below the label rows.
                SeriesLabelPosition::UpperRight if rows > 0 => {
                    let chars = self
                        .curves
                        .iter()
                        .filter_map(|c| c.name.as_ref())
                        .chain(
                            self.spans
                                .as_ref()
                                .filter(|s| !s.ranges.is_empty())
                                .and_then(|s| s.name.as_ref()),
                        )
                        .map(|n| n.chars().count())
                        .max()
                        .unwrap_or(0);
                    let w = chars as f64 * 10.5 + 55.0;
                    SeriesLabelPosition::Coordinate(
                        (plot_w - w - 5.0).max(0.0) as i32,
                        (room + 5.0) as i32,
                    )
                }
                ref other => other.clone(),
            };
            chart
                .configure_series_labels()
                .position(position)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font((FONT, 18).into_font())
                .draw()?;
        }
        Ok(())
    }

    /// Pixels for the y tick labels and the unit: enough for the longest label, at least
    /// [`Panel::min_y_label_px`] (set it to the largest of stacked panels to align them).
    pub fn y_label_px<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> u32 {
        self.y_axis(area).label_px
    }

    fn y_axis<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> YAxis {
        let (lo, hi) = self.y_data_range();
        let pad = ((hi - lo) * 0.08).max(self.min_pad);
        let (lo, hi) = (lo - pad, hi + pad);
        // Head room for the label rows, in data units.
        let (_, h_px) = area.dim_in_pixel();
        let rows = self.label_rows();
        let plot_px = (f64::from(h_px) - CHROME_PX).max(40.0);
        let room = rows as f64 * LABEL_ROW_PX + if rows > 0 { 6.0 } else { 0.0 };
        let hi = hi + (hi - lo) * room / (plot_px - room).max(20.0);
        let decimals = decimals(hi - lo);
        // Wide enough for the longest tick label (e.g. 1014.625) and the unit.
        let label_chars = [lo, hi]
            .iter()
            .map(|v| format_tick(*v, decimals).chars().count())
            .max()
            .unwrap_or(4);
        let label_px = (label_chars.min(24) as u32 * 11 + 45).max(self.min_y_label_px);
        YAxis {
            lo,
            hi,
            decimals,
            label_px,
            rows,
            room,
            plot_px,
        }
    }

    fn y_data_range(&self) -> (f64, f64) {
        let (lo, hi) = self
            .curves
            .iter()
            .flat_map(|c| c.pts.iter().map(|p| p.1))
            .filter(|y| y.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
                (a.min(y), b.max(y))
            });
        if lo.is_finite() && hi.is_finite() {
            (lo, hi)
        } else {
            (-1.0, 1.0)
        }
    }

    fn label_rows(&self) -> usize {
        match self.vlines.iter().filter(|v| v.label.is_some()).count() {
            0 => 0,
            1 => 1,
            _ => 2,
        }
    }

    /// Labels along the top in up to two staggered rows, skipping a label that would overlap
    /// the previous one in its row; a label that would run past the right edge ends there.
    fn draw_labels<DB: DrawingBackend, CT>(
        &self,
        chart: &mut ChartContext<'_, DB, CT>,
        plot_w: f64,
        top: f64,
        units_per_px: f64,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>
    where
        CT: plotters::coord::CoordTranslate<From = (f64, f64)>,
    {
        let (x0, x1) = self.x;
        let px_per_x = plot_w / (x1 - x0);
        let mut row_end = [f64::NEG_INFINITY; 2];
        let labelled = self
            .vlines
            .iter()
            .filter_map(|v| v.label.as_ref().map(|l| (v.x, l)));
        for (k, (x, label)) in labelled.enumerate() {
            if !(x0..=x1).contains(&x) {
                continue;
            }
            let row = k % 2;
            let w = label.chars().count() as f64 * 9.5 + 10.0;
            let px = ((x - x0) * px_per_x).min(plot_w - w).max(0.0);
            let Some(end) = row_end.get_mut(row) else {
                continue;
            };
            if px < *end {
                continue;
            }
            *end = px + w;
            let y = top - units_per_px * (4.0 + LABEL_ROW_PX * row as f64);
            chart.draw_series(std::iter::once(Text::new(
                label.clone(),
                (x0 + px / px_per_x, y),
                (FONT, 17).into_font().color(&BLACK),
            )))?;
        }
        Ok(())
    }
}

fn draw_curve<'a, DB: DrawingBackend + 'a, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
    c: &Curve,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>
where
    CT: plotters::coord::CoordTranslate<From = (f64, f64)>,
{
    let color = c.color;
    let mut first = true;
    let mut runs = finite_runs(&c.pts).peekable();
    if runs.peek().is_none() {
        // A legend-only curve: an empty series carries the entry.
        if let Some(name) = &c.name {
            let anno = chart.draw_series(std::iter::empty::<PathElement<(f64, f64)>>())?;
            legend_glyph(anno.label(name.as_str()), color, c.stroke);
        }
        return Ok(());
    }
    for run in runs {
        let anno = match c.stroke {
            Stroke::Solid(w) => {
                chart.draw_series(LineSeries::new(run.iter().copied(), color.stroke_width(w)))?
            }
            Stroke::Dashed(w) => chart.draw_series(DashedLineSeries::new(
                run.iter().copied(),
                9,
                6,
                color.stroke_width(w),
            ))?,
            Stroke::Dots => chart.draw_series(
                run.iter()
                    .map(|p| Circle::new(*p, 2, color.filled()))
                    .collect::<Vec<_>>(),
            )?,
        };
        if first && let Some(name) = &c.name {
            legend_glyph(anno.label(name.as_str()), color, c.stroke);
        }
        first = false;
    }
    Ok(())
}

fn legend_glyph<'a, DB: DrawingBackend + 'a>(
    anno: &mut plotters::chart::SeriesAnno<'a, DB>,
    color: RGBColor,
    stroke: Stroke,
) {
    match stroke {
        Stroke::Solid(w) => {
            anno.legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(w + 1))
            });
        }
        Stroke::Dashed(w) => {
            anno.legend(move |(x, y)| {
                EmptyElement::at((x, y))
                    + PathElement::new(vec![(0, 0), (8, 0)], color.stroke_width(w + 1))
                    + PathElement::new(vec![(14, 0), (24, 0)], color.stroke_width(w + 1))
            });
        }
        Stroke::Dots => {
            anno.legend(move |(x, y)| {
                EmptyElement::at((x, y))
                    + Circle::new((4, 0), 3, color.filled())
                    + Circle::new((12, 0), 3, color.filled())
                    + Circle::new((20, 0), 3, color.filled())
            });
        }
    }
}

/// The stretches of consecutive points with finite coordinates.
fn finite_runs(pts: &[(f64, f64)]) -> impl Iterator<Item = &[(f64, f64)]> {
    pts.split(|(x, y)| !(x.is_finite() && y.is_finite()))
        .filter(|run| !run.is_empty())
}

/// Digits after the point for tick labels over a range of `span`.
fn decimals(span: f64) -> usize {
    let step = span.abs() / 8.0;
    if !(step.is_finite() && step > 0.0) || step >= 1.0 {
        return 0;
    }
    (-step.log10()).ceil().clamp(0.0, 6.0) as usize
}

/// A tick label with `d` decimals and no negative zero.
fn format_tick(v: f64, d: usize) -> String {
    super::super::number_format::fixed(v, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_decimals_follow_the_range() {
        assert_eq!(decimals(300.0), 0);
        assert_eq!(decimals(8.0), 0);
        assert_eq!(decimals(2.0), 1);
        assert_eq!(decimals(0.05), 3);
        assert_eq!(decimals(0.0), 0);
        assert_eq!(format_tick(-0.0001, 2), "0.00");
        let pts = [(0.0, 1.0), (1.0, f64::NAN), (2.0, 2.0), (3.0, 3.0)];
        let runs: Vec<_> = finite_runs(&pts).collect();
        assert_eq!(runs, [&pts[..1], &pts[2..]]);
    }
}
