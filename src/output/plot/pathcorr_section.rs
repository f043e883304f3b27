//! The path-correction section of a plot, in the path frame against path length: the
//! programmed path, the seam the sensor measured and the corrected path, for y (lateral) and z
//! (vertical), then the correction applied and what remained between the corrected path and
//! the seam.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::panel::{Curve, Panel, Stroke};
use super::{FONT, PlotData, keep};
use crate::controller::sample_feed::PathCorrSample;

const TITLE_H: u32 = 50;
/// At most this many seam measurements are drawn as dots.
const MAX_DOTS: usize = 100;
const PROGRAMMED: RGBColor = RGBColor(0, 0, 0);
const SEAM: RGBColor = RGBColor(255, 127, 14);
const CORRECTED: RGBColor = RGBColor(31, 119, 180);
const Y_COLOR: RGBColor = RGBColor(214, 39, 40);
const Z_COLOR: RGBColor = RGBColor(44, 160, 44);

/// Draw the section into `area`.
pub(super) fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    data: &PlotData,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (head, body) = area.split_vertically(TITLE_H);
    head.draw(&Text::new(
        "Path correction in the path frame (x: along the path, y: x × tool z, z: x × y)",
        (20, 14),
        (FONT, 28).into_font().color(&BLACK),
    ))?;
    let (_, h) = body.dim_in_pixel();
    let (y_area, rest) = body.split_vertically(h * 34 / 100);
    let (z_area, corr_area) = rest.split_vertically(h * 34 / 100);

    let samples = &data.pathcorr;
    let (s0, s1) = samples
        .iter()
        .map(|p| p.s_mm)
        .filter(|s| s.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| {
            (a.min(s), b.max(s))
        });
    let (s0, s1) = if s0.is_finite() { (s0, s1) } else { (0.0, 1.0) };
    let x = (s0, s1.max(s0 + 1e-3));
    let n = samples.len();
    // A point per kept sample; a new correction sequence (s going back) starts a new line.
    let series = |value: &dyn Fn(usize, &PathCorrSample) -> f64| -> Vec<(f64, f64)> {
        let mut pts = Vec::new();
        let mut last_s = f64::NEG_INFINITY;
        for (k, p) in samples.iter().enumerate() {
            if p.s_mm < last_s - 1e-9 {
                pts.push((f64::NAN, f64::NAN));
            }
            last_s = p.s_mm;
            if keep(k, n) {
                pts.push((p.s_mm, value(k, p)));
            }
        }
        pts
    };
    // Measurements as dots, few enough to read as single measurements.
    let measured_n = samples.iter().filter(|p| p.measured_yz.is_some()).count();
    let measured_stride = measured_n / MAX_DOTS + 1;
    let measured = |i: usize| -> Vec<(f64, f64)> {
        samples
            .iter()
            .filter_map(|p| Some((p.s_mm, *p.measured_yz?.get(i)?)))
            .enumerate()
            .filter(|(k, _)| k.is_multiple_of(measured_stride))
            .map(|(_, pt)| pt)
            .collect()
    };
    // The last measurement, held until the next one.
    let held: Vec<Option<[f64; 2]>> = samples
        .iter()
        .scan(None, |last, p| {
            if p.measured_yz.is_some() {
                *last = p.measured_yz;
            }
            Some(*last)
        })
        .collect();
    let at = |v: [f64; 2], i: usize| v.get(i).copied().unwrap_or(f64::NAN);

    let mut stack = Vec::new();
    for (i, (area, caption)) in [
        (&y_area, "Lateral: y in the path frame"),
        (&z_area, "Vertical: z in the path frame"),
    ]
    .into_iter()
    .enumerate()
    {
        let mut p = Panel::new(caption, "path length s (mm)", "mm", x);
        p.min_pad = 0.1;
        p.legend = SeriesLabelPosition::LowerRight;
        p.curves = vec![
            Curve::new(
                "programmed path",
                PROGRAMMED,
                Stroke::Dashed(2),
                series(&|_, p| at(p.programmed_yz, i)),
            ),
            Curve::new(
                "corrected path",
                CORRECTED,
                Stroke::Solid(2),
                series(&|_, p| at(p.corrected_yz, i)),
            ),
            Curve::new("seam (sensor)", SEAM, Stroke::Dots, measured(i)),
        ];
        stack.push((p, area));
    }

    let mut c = Panel::new(
        "Correction applied (corrected − programmed) and remaining offset to the seam",
        "path length s (mm)",
        "mm",
        x,
    );
    c.min_pad = 0.1;
    c.legend = SeriesLabelPosition::LowerRight;
    let remaining = |k: usize, p: &PathCorrSample, i: usize| {
        held.get(k)
            .copied()
            .flatten()
            .map_or(f64::NAN, |m| at(m, i) - at(p.corrected_yz, i))
    };
    c.curves = vec![
        Curve::new(
            "correction y",
            Y_COLOR,
            Stroke::Solid(2),
            series(&|_, p| at(p.correction(), 0)),
        ),
        Curve::new(
            "correction z",
            Z_COLOR,
            Stroke::Solid(2),
            series(&|_, p| at(p.correction(), 1)),
        ),
        Curve::new(
            "seam − corrected y",
            Y_COLOR,
            Stroke::Dashed(1),
            series(&|k, p| remaining(k, p, 0)),
        ),
        Curve::new(
            "seam − corrected z",
            Z_COLOR,
            Stroke::Dashed(1),
            series(&|k, p| remaining(k, p, 1)),
        ),
    ];
    stack.push((c, &corr_area));
    super::align(&mut stack);
    for (panel, area) in &stack {
        panel.draw(area)?;
    }
    Ok(())
}
