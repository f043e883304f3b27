//! The EGM section of a plot, one block per mode used: the sensor's reference against the
//! feedback for each joint (joint mode) or for x, y, z (pose mode), and the tracking error
//! (reference − feedback), with EGM state changes marked and the cycles in which
//! `MaxSpeedDeviation` limited the speed shaded.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::panel::{Curve, Panel, Spans, Stroke, VLine};
use super::{FONT, JOINT_COLORS, PlotData, XYZ_COLORS, keep};
use crate::controller::sample_feed::{EgmAxes, EgmSample, EgmTraceState};

/// Heights (px) of a block's title, one row of reference/feedback charts and the error chart.
const TITLE_H: u32 = 50;
const ROW_H: u32 = 290;
const ERROR_H: u32 = 400;
/// Shading of the speed-limited cycles.
const LIMIT_COLOR: RGBColor = RGBColor(230, 60, 60);

/// The modes with samples, joint first.
fn modes(data: &PlotData) -> impl Iterator<Item = EgmAxes> + '_ {
    [EgmAxes::Joint, EgmAxes::Pose]
        .into_iter()
        .filter(|m| data.egm.iter().any(|s| s.axes == *m))
}

/// What the block of one mode shows: its rows of small charts, axis names and unit.
fn layout(axes: EgmAxes) -> (u32, &'static [&'static str], &'static str) {
    match axes {
        EgmAxes::Joint => (2, &["J1", "J2", "J3", "J4", "J5", "J6"], "deg"),
        EgmAxes::Pose => (1, &["x", "y", "z"], "mm"),
    }
}

fn block_height(axes: EgmAxes) -> u32 {
    let (rows, _, _) = layout(axes);
    TITLE_H + rows * ROW_H + ERROR_H
}

/// Pixels the section needs (0 without EGM samples).
pub(super) fn height(data: &PlotData) -> u32 {
    modes(data).map(block_height).sum()
}

/// Draw the section into `area` (of [`height`] pixels).
pub(super) fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    data: &PlotData,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let mut rest = area.clone();
    for axes in modes(data) {
        let (block, below) = rest.split_vertically(block_height(axes));
        let samples: Vec<&EgmSample> = data.egm.iter().filter(|s| s.axes == axes).collect();
        draw_block(&block, data, axes, &samples)?;
        rest = below;
    }
    Ok(())
}

fn draw_block<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    data: &PlotData,
    axes: EgmAxes,
    samples: &[&EgmSample],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (rows, names, unit) = layout(axes);
    let title = match axes {
        EgmAxes::Joint => "EGM position guidance, joint mode",
        EgmAxes::Pose => "EGM position guidance, pose mode (correction frame, position)",
    };
    let times: Vec<f64> = samples.iter().map(|s| s.t.as_secs_f64()).collect();
    let (head, body) = area.split_vertically(TITLE_H);
    head.draw(&Text::new(
        title,
        (20, 14),
        (FONT, 28).into_font().color(&BLACK),
    ))?;
    let limited = limited_spans(samples, &times);
    draw_key(&head, limited.is_empty())?;
    let (grid, error_area) = body.split_vertically(rows * ROW_H);

    let x = time_range(data, &times);
    let spans = || Spans {
        name: Some("MaxSpeedDeviation limiting".to_string()),
        color: LIMIT_COLOR,
        ranges: limited.clone(),
    };
    let n = samples.len();
    let series = |value: &dyn Fn(&EgmSample) -> f64| -> Vec<(f64, f64)> {
        samples
            .iter()
            .zip(&times)
            .enumerate()
            .filter(|(k, _)| keep(*k, n))
            .map(|(_, (s, t))| (*t, value(s)))
            .collect()
    };
    let reference = |s: &EgmSample, i: usize| {
        s.reference
            .and_then(|r| r.get(i).copied())
            .unwrap_or(f64::NAN)
    };
    let feedback = |s: &EgmSample, i: usize| s.feedback.get(i).copied().unwrap_or(f64::NAN);
    let colors: &[RGBColor] = match axes {
        EgmAxes::Joint => &JOINT_COLORS,
        EgmAxes::Pose => &XYZ_COLORS,
    };
    let states = |labels: bool| state_lines(data, x, labels);

    let cells = grid.split_evenly((rows as usize, names.len() / rows as usize));
    for (i, (cell, name)) in cells.iter().zip(names).enumerate() {
        let color = colors.get(i).copied().unwrap_or(BLACK);
        let caption = format!("{name} ({unit})");
        let mut p = Panel::new(&caption, "time (s)", unit, x);
        p.caption_size = 20;
        p.min_pad = 0.1;
        p.vlines = states(false);
        // The block's key (drawn in its title line) explains the strokes and the shading.
        p.curves = vec![
            Curve::unnamed(color, Stroke::Solid(2), series(&|s| feedback(s, i))),
            Curve::unnamed(BLACK, Stroke::Dashed(2), series(&|s| reference(s, i))),
        ];
        p.spans = Some(Spans {
            name: None,
            ..spans()
        });
        p.draw(cell)?;
    }

    let mut e = Panel::new(
        "Tracking error (reference − feedback), EGM states marked",
        "time (s)",
        unit,
        x,
    );
    e.min_pad = 0.05;
    e.legend = SeriesLabelPosition::UpperRight;
    e.spans = Some(spans());
    e.vlines = states(true);
    e.curves = names
        .iter()
        .enumerate()
        .map(|(i, name)| {
            let color = colors.get(i).copied().unwrap_or(BLACK);
            let pts = series(&|s| reference(s, i) - feedback(s, i));
            Curve::new(name, color, Stroke::Solid(2), pts)
        })
        .collect();
    e.draw(&error_area)
}

/// The key of the reference/feedback charts, at the right of the block's title line.
fn draw_key<DB: DrawingBackend>(
    head: &DrawingArea<DB, Shift>,
    never_limited: bool,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (w, _) = head.dim_in_pixel();
    let font = (FONT, 18).into_font().color(&BLACK);
    let y = 30;
    let mut x = i32::try_from(w).unwrap_or(1600) - 760;
    let grey = RGBColor(90, 90, 90);
    head.draw(&PathElement::new(
        vec![(x, y), (x + 30, y)],
        grey.stroke_width(3),
    ))?;
    head.draw(&Text::new(
        "feedback (axis colour)",
        (x + 38, y - 10),
        font.clone(),
    ))?;
    x += 240;
    for (a, b) in [(0, 9), (15, 24), (30, 36)] {
        head.draw(&PathElement::new(
            vec![(x + a, y), (x + b, y)],
            BLACK.stroke_width(3),
        ))?;
    }
    head.draw(&Text::new("reference", (x + 44, y - 10), font.clone()))?;
    x += 140;
    head.draw(&Rectangle::new(
        [(x, y - 8), (x + 30, y + 8)],
        LIMIT_COLOR.mix(0.22).filled(),
    ))?;
    let text = if never_limited {
        "MaxSpeedDeviation limiting: never"
    } else {
        "MaxSpeedDeviation limiting"
    };
    head.draw(&Text::new(text, (x + 38, y - 10), font))?;
    Ok(())
}

/// The samples' time span, widened to the state changes just before and after it (within a
/// second or a quarter of the span), with a small margin.
fn time_range(data: &PlotData, times: &[f64]) -> (f64, f64) {
    let first = times.first().copied().unwrap_or(0.0);
    let last = times.last().copied().unwrap_or(1.0).max(first + 1e-3);
    let reach = (0.25 * (last - first)).max(1.0);
    let before = data
        .egm_states
        .iter()
        .map(|(t, _)| *t)
        .filter(|t| *t < first && first - t <= reach)
        .fold(first, f64::min);
    let after = data
        .egm_states
        .iter()
        .map(|(t, _)| *t)
        .filter(|t| *t > last && t - last <= reach)
        .fold(last, f64::max);
    let margin = (after - before) * 0.02;
    (before - margin, after + margin)
}

/// The stretches of consecutive speed-limited cycles, each from its first cycle to the
/// cycle after its last.
fn limited_spans(samples: &[&EgmSample], times: &[f64]) -> Vec<(f64, f64)> {
    let typical = match (times.first(), times.get(1)) {
        (Some(a), Some(b)) => b - a,
        _ => 0.004,
    };
    let mut spans: Vec<(f64, f64)> = Vec::new();
    for (k, (s, t)) in samples.iter().zip(times).enumerate() {
        if !s.speed_limited {
            continue;
        }
        let end = times.get(k + 1).copied().unwrap_or(t + typical);
        match spans.last_mut() {
            Some(last) if (last.1 - t).abs() < 1e-9 => last.1 = end,
            _ => spans.push((*t, end)),
        }
    }
    spans
}

/// Vertical lines at the EGM state changes inside `x`, labelled with the new state.
fn state_lines(data: &PlotData, (x0, x1): (f64, f64), labels: bool) -> Vec<VLine> {
    data.egm_states
        .iter()
        .filter(|(t, _)| (x0..=x1).contains(t))
        .map(|(t, state)| VLine {
            x: *t,
            label: labels.then(|| state.as_str().to_string()),
            color: match state {
                EgmTraceState::Running => RGBColor(40, 150, 60),
                EgmTraceState::Connected => RGBColor(230, 140, 20),
                EgmTraceState::Disconnected => RGBColor(120, 120, 120),
            },
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::time::RobotTime;

    #[test]
    fn limited_cycles_merge_into_spans() {
        let sample = |ms: u64, limited: bool| EgmSample {
            t: RobotTime::from_nanos(ms * 1_000_000),
            axes: EgmAxes::Joint,
            reference: None,
            feedback: [0.0; 6],
            state: EgmTraceState::Running,
            speed_limited: limited,
        };
        let s = [
            sample(0, false),
            sample(4, true),
            sample(8, true),
            sample(12, false),
            sample(16, true),
        ];
        let refs: Vec<&EgmSample> = s.iter().collect();
        let times: Vec<f64> = s.iter().map(|s| s.t.as_secs_f64()).collect();
        let spans = limited_spans(&refs, &times);
        assert_eq!(spans.len(), 2);
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert!(close(spans[0].0, 0.004) && close(spans[0].1, 0.012));
        assert!(close(spans[1].0, 0.016) && close(spans[1].1, 0.020));
    }
}
