//! The chapter's charts, drawn by the plotting module's one chart helper ([`crate::plot::Chart`]):
//! markers or lines on linear or log axes, with a legend, in the chapter's one style.

use crate::plot::{self, Axis, Chart, Figure, Legend, LegendMark, PlotError};
use plotters::prelude::{RGBColor, SeriesLabelPosition};

/// One series of a chart: points (markers) or a line, with a legend entry unless its label is
/// empty.
pub(super) struct Series {
    label: String,
    points: Vec<(f64, f64)>,
    line: bool,
    color: RGBColor,
}

/// Draws `series` in a 640×420 chart on the axes `x`, `y` (linear or log; [`Axis::linear`],
/// [`Axis::log`]), titled by `x_label`, `y_label`, with 12 and 8 tick labels and no light grid.
pub(super) fn chart(
    file_name: &str,
    caption: &str,
    (x_label, y_label): (&str, &str),
    (x, y): (Axis<'_>, Axis<'_>),
    legend: SeriesLabelPosition,
    series: &[Series],
) -> Result<Figure, PlotError> {
    fn ticks<'a>(axis: Axis<'a>, desc: &'a str, labels: usize) -> Axis<'a> {
        Axis { desc, labels: Some(labels), format: Some(tick), ..axis }
    }
    Chart {
        label_size: 13,
        light_grid: false,
        series: series
            .iter()
            .map(|s| {
                let drawn = if s.line {
                    plot::Series {
                        legend: LegendMark::Line { length: 16, width: 2 },
                        ..plot::Series::line(s.label.as_str(), s.points.clone(), s.color, 2)
                    }
                } else {
                    plot::Series::dots(s.label.as_str(), s.points.clone(), s.color, 4)
                };
                plot::Series { label: (!s.label.is_empty()).then(|| s.label.clone()), ..drawn }
            })
            .collect(),
        legend: Some(Legend { position: Some(legend), font: 13, opacity: 0.85 }),
        ..Chart::new(caption, ticks(x, x_label, 12), ticks(y, y_label, 8))
    }
    .svg(file_name, (640, 420))
}

pub(super) fn series(label: impl Into<String>, points: Vec<(f64, f64)>, line: bool, color: RGBColor) -> Series {
    Series { label: label.into(), points, line, color }
}

/// A legend entry with no points: a black line (`line`) or dot saying what lines or dots mean
/// when the colours name something else.
pub(super) fn key(label: impl Into<String>, line: bool) -> Series {
    series(label, Vec::new(), line, plotters::prelude::BLACK)
}

/// An axis label: the value rounded to six decimals, so that `0.6000000001` prints `0.6`.
fn tick(value: &f64) -> String {
    format!("{}", (value * 1e6).round() / 1e6)
}
