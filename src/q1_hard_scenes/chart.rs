//! The chapter's chart engine: markers or lines on linear or log axes, with a legend.

use crate::plot::{self, Figure, PlotError, err};
use plotters::prelude::*;

/// One series of a chart: points (markers) or a line.
pub(super) struct Series {
    label: String,
    points: Vec<(f64, f64)>,
    line: bool,
    color: RGBColor,
}

/// Draws `series` in a chart with the given axes (linear or log ranges).
pub(super) fn chart<X, Y>(
    file_name: &str,
    caption: &str,
    (x_label, y_label): (&str, &str),
    (x_range, y_range): (X, Y),
    legend: SeriesLabelPosition,
    series: &[Series],
) -> Result<Figure, PlotError>
where
    X: plotters::coord::ranged1d::AsRangedCoord<Value = f64>,
    Y: plotters::coord::ranged1d::AsRangedCoord<Value = f64>,
    X::CoordDescType: plotters::coord::ranged1d::ValueFormatter<f64>,
    Y::CoordDescType: plotters::coord::ranged1d::ValueFormatter<f64>,
{
    plot::svg_figure(file_name, (640, 420), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(caption, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x_range, y_range)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .label_style(("sans-serif", 13))
            .light_line_style(TRANSPARENT)
            .x_labels(12)
            .y_labels(8)
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .draw()
            .map_err(err)?;
        for s in series {
            let color = s.color;
            if s.line {
                chart
                    .draw_series(LineSeries::new(s.points.iter().copied(), color.stroke_width(2)))
                    .map_err(err)?
                    .label(s.label.as_str())
                    .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], color));
            } else {
                chart
                    .draw_series(s.points.iter().map(|&p| Circle::new(p, 4, color.filled())))
                    .map_err(err)?
                    .label(s.label.as_str())
                    .legend(move |(x, y)| Circle::new((x + 8, y), 4, color.filled()));
            }
        }
        chart
            .configure_series_labels()
            .position(legend)
            .label_font(("sans-serif", 13))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(err)
    })
}

pub(super) fn series(label: impl Into<String>, points: Vec<(f64, f64)>, line: bool, color: RGBColor) -> Series {
    Series { label: label.into(), points, line, color }
}

/// An axis label: the value rounded to six decimals, so that `0.6000000001` prints `0.6`.
fn tick(value: &f64) -> String {
    format!("{}", (value * 1e6).round() / 1e6)
}
