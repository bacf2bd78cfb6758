//! One chart helper: a caption, two axes (each linear or logarithmic), series of lines, dashed
//! lines and dots, text notes and a legend, drawn on any plotters backend (SVG or PNG figures, or one
//! panel of a larger figure).
//!
//! A [`Chart`] is plain data, so a figure reads as a description of what it shows; every style the
//! crate's figures use (caption and label sizes, label areas, legend box, marker sizes) is a field,
//! so converting a hand-built plotters chart to it keeps its bytes.

use super::{Figure, PlotError, err, png_figure, svg_figure};
use plotters::chart::SeriesAnno;
use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;

/// Formats one tick value of an axis.
pub type TickFormat = fn(&f64) -> String;

/// One axis: its range, its scale, its title and its ticks.
#[derive(Debug, Clone, Copy)]
pub struct Axis<'a> {
    /// The range drawn, `(low, high)`; both ends positive on a log axis.
    pub range: (f64, f64),
    /// Logarithmic (`true`) or linear.
    pub log: bool,
    /// The axis title (none when empty).
    pub desc: &'a str,
    /// How many tick labels plotters aims for (its default when `None`).
    pub labels: Option<usize>,
    /// How tick values print (plotters' default when `None`).
    pub format: Option<TickFormat>,
}

impl<'a> Axis<'a> {
    /// A linear axis over `low..high` titled `desc`, with plotters' default ticks.
    ///
    /// # Examples
    /// ```
    /// let x = hw3::plot::Axis::linear(0.0, 20.0, "sweeps");
    /// assert!(!x.log);
    /// ```
    #[must_use]
    pub fn linear(low: f64, high: f64, desc: &'a str) -> Self {
        Self { range: (low, high), log: false, desc, labels: None, format: None }
    }

    /// A logarithmic axis over `low..high` (both positive) titled `desc`.
    ///
    /// # Examples
    /// ```
    /// let y = hw3::plot::Axis::log(1e-3, 1.0, "error");
    /// assert!(y.log);
    /// ```
    #[must_use]
    pub fn log(low: f64, high: f64, desc: &'a str) -> Self {
        Self { log: true, ..Self::linear(low, high, desc) }
    }
}

/// How a series' line is stroked.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Stroke {
    /// Line width in pixels.
    pub width: u32,
    /// `(dash, gap)` lengths in pixels for a dashed line; solid when `None`.
    pub dash: Option<(u32, u32)>,
}

/// A dot drawn at every point of a series.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dots {
    /// Radius in pixels.
    pub radius: u32,
    /// Filled disc (`None`) or a ring of this stroke width.
    pub ring: Option<u32>,
}

/// The sample drawn beside a series' label in the legend (its origin is the legend's anchor).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LegendMark {
    /// A horizontal line `length` pixels long and `width` wide.
    Line {
        /// Length in pixels.
        length: i32,
        /// Width in pixels.
        width: u32,
    },
    /// A filled dot of `radius`, `dx` pixels right of the anchor.
    Dot {
        /// Offset to the right, in pixels.
        dx: i32,
        /// Radius in pixels.
        radius: u32,
    },
}

/// One data series: points, colour, how they are drawn (the line first, then the dots), and its
/// legend entry.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// The legend text (no legend entry when `None`).
    pub label: Option<String>,
    /// The points, in drawing order.
    pub points: Vec<(f64, f64)>,
    /// The colour of the line, the dots and the legend mark.
    pub colour: RGBColor,
    /// The line through the points (none when `None`).
    pub line: Option<Stroke>,
    /// A dot at every point (none when `None`).
    pub dots: Option<Dots>,
    /// The legend mark; the legend entry belongs to the line when the mark is a line, to the dots
    /// when it is a dot.
    pub legend: LegendMark,
}

impl Series {
    /// A solid line of `width` through `points`, with a legend line of the same width, 16 px long.
    ///
    /// # Examples
    /// ```
    /// use hw3::plot::{PALETTE, Series};
    /// let s = Series::line("f(x)", vec![(0.0, 0.0), (1.0, 1.0)], PALETTE[0], 2);
    /// assert_eq!(s.line.unwrap().width, 2);
    /// assert!(s.dots.is_none());
    /// ```
    #[must_use]
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>, colour: RGBColor, width: u32) -> Self {
        Self {
            label: Some(label.into()),
            points,
            colour,
            line: Some(Stroke { width, dash: None }),
            dots: None,
            legend: LegendMark::Line { length: 16, width },
        }
    }

    /// Filled dots of `radius` at `points`, with a legend dot of radius 4, 8 px right of the anchor.
    ///
    /// # Examples
    /// ```
    /// use hw3::plot::{PALETTE, Series};
    /// let s = Series::dots("measured", vec![(1.0, 2.0)], PALETTE[1], 4);
    /// assert!(s.line.is_none());
    /// ```
    #[must_use]
    pub fn dots(label: impl Into<String>, points: Vec<(f64, f64)>, colour: RGBColor, radius: u32) -> Self {
        Self {
            label: Some(label.into()),
            points,
            colour,
            line: None,
            dots: Some(Dots { radius, ring: None }),
            legend: LegendMark::Dot { dx: 8, radius: 4 },
        }
    }
}

/// A text note at a data point (default colour: black).
#[derive(Debug, Clone, PartialEq)]
pub struct Note {
    /// The text.
    pub text: String,
    /// Where its top-left corner goes, in data coordinates.
    pub at: (f64, f64),
    /// Font size in pixels.
    pub size: u32,
}

/// The legend box.
#[derive(Debug, Clone, PartialEq)]
pub struct Legend {
    /// Its corner (plotters' default, the upper right inside the plot, when `None`).
    pub position: Option<SeriesLabelPosition>,
    /// Font size in pixels.
    pub font: u32,
    /// Opacity of its white background.
    pub opacity: f64,
}

/// A chart: see the module docs. Build one with [`Chart::new`] and struct-update syntax.
#[derive(Debug, Clone)]
pub struct Chart<'a> {
    /// The title above the plot.
    pub caption: &'a str,
    /// The title's font size in pixels.
    pub caption_size: u32,
    /// Margin around the chart, in pixels.
    pub margin: u32,
    /// Height of the x label area and width of the y label area, in pixels.
    pub label_areas: (u32, u32),
    /// The horizontal axis.
    pub x: Axis<'a>,
    /// The vertical axis.
    pub y: Axis<'a>,
    /// Font size of tick labels and axis titles, in pixels.
    pub label_size: u32,
    /// Draw the light (minor) grid lines.
    pub light_grid: bool,
    /// Fill the drawing area white again before drawing (the figure is already white).
    pub fill: bool,
    /// The series, drawn in order.
    pub series: Vec<Series>,
    /// Text notes, drawn after the series.
    pub notes: Vec<Note>,
    /// The legend (none when `None`).
    pub legend: Option<Legend>,
}

impl<'a> Chart<'a> {
    /// A chart with no series: caption 18 px, margin 12, label areas 40 × 60, labels 12 px, the
    /// light grid on, and a legend at plotters' default corner (13 px, opacity 0.85).
    ///
    /// # Examples
    /// ```
    /// use hw3::plot::{Axis, Chart, PALETTE, Series};
    /// let chart = Chart {
    ///     series: vec![Series::line("y = x²", (1..10).map(|i| (f64::from(i), f64::from(i * i))).collect(), PALETTE[0], 2)],
    ///     ..Chart::new("squares", Axis::log(1.0, 10.0, "x"), Axis::log(1.0, 100.0, "x²"))
    /// };
    /// let svg = chart.svg("squares.svg", (400, 300)).unwrap();
    /// assert!(String::from_utf8(svg.bytes).unwrap().contains("squares"));
    /// let png = chart.png("squares.png", (400, 300)).unwrap();
    /// assert!(png.bytes.starts_with(b"\x89PNG"));
    /// ```
    #[must_use]
    pub fn new(caption: &'a str, x: Axis<'a>, y: Axis<'a>) -> Self {
        Self {
            caption,
            caption_size: 18,
            margin: 12,
            label_areas: (40, 60),
            x,
            y,
            label_size: 12,
            light_grid: true,
            fill: false,
            series: Vec::new(),
            notes: Vec::new(),
            legend: Some(Legend { position: None, font: 13, opacity: 0.85 }),
        }
    }

    /// The chart as an SVG figure of `width`×`height` pixels.
    ///
    /// # Errors
    /// [`PlotError::Draw`] when plotters fails (e.g. a log axis with a non-positive end).
    pub fn svg(&self, file_name: &str, size: (u32, u32)) -> Result<Figure, PlotError> {
        svg_figure(file_name, size, |root| self.draw(root))
    }

    /// The chart as a PNG figure of `width`×`height` pixels.
    ///
    /// # Errors
    /// [`PlotError::Draw`] when plotters fails, [`PlotError::Encode`] when encoding does.
    pub fn png(&self, file_name: &str, size: (u32, u32)) -> Result<Figure, PlotError> {
        png_figure(file_name, size, |root| self.draw(root))
    }

    /// Draws the chart on `area` (a whole figure, or one panel of it).
    ///
    /// # Errors
    /// plotters' message when drawing fails.
    pub fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let (x, y) = (self.x.range, self.y.range);
        match (self.x.log, self.y.log) {
            (false, false) => self.draw_in(area, x.0..x.1, y.0..y.1),
            (false, true) => self.draw_in(area, x.0..x.1, (y.0..y.1).log_scale()),
            (true, false) => self.draw_in(area, (x.0..x.1).log_scale(), y.0..y.1),
            (true, true) => self.draw_in(area, (x.0..x.1).log_scale(), (y.0..y.1).log_scale()),
        }
    }

    fn draw_in<DB, X, Y>(&self, area: &DrawingArea<DB, Shift>, x: X, y: Y) -> Result<(), String>
    where
        DB: DrawingBackend,
        X: AsRangedCoord<Value = f64>,
        Y: AsRangedCoord<Value = f64>,
        X::CoordDescType: ValueFormatter<f64>,
        Y::CoordDescType: ValueFormatter<f64>,
    {
        if self.fill {
            area.fill(&WHITE).map_err(err)?;
        }
        let mut chart = ChartBuilder::on(area)
            .caption(self.caption, ("sans-serif", self.caption_size))
            .margin(self.margin)
            .x_label_area_size(self.label_areas.0)
            .y_label_area_size(self.label_areas.1)
            .build_cartesian_2d(x, y)
            .map_err(err)?;
        let mut mesh = chart.configure_mesh();
        mesh.x_desc(self.x.desc).y_desc(self.y.desc).label_style(("sans-serif", self.label_size));
        if !self.light_grid {
            mesh.light_line_style(TRANSPARENT);
        }
        if let Some(n) = self.x.labels {
            mesh.x_labels(n);
        }
        if let Some(n) = self.y.labels {
            mesh.y_labels(n);
        }
        if let Some(format) = &self.x.format {
            mesh.x_label_formatter(format);
        }
        if let Some(format) = &self.y.format {
            mesh.y_label_formatter(format);
        }
        mesh.draw().map_err(err)?;
        for series in &self.series {
            let colour = series.colour;
            let legend = series.legend;
            let label_on_line =
                series.line.is_some() && (matches!(legend, LegendMark::Line { .. }) || series.dots.is_none());
            let label = |annotation: &mut SeriesAnno<'_, DB>| {
                if let Some(label) = &series.label {
                    annotation.label(label.as_str());
                    legend_mark(annotation, legend, colour);
                }
            };
            if let Some(stroke) = series.line {
                let style = colour.stroke_width(stroke.width);
                let points = series.points.iter().copied();
                let annotation = match stroke.dash {
                    None => chart.draw_series(LineSeries::new(points, style)).map_err(err)?,
                    Some((dash, gap)) => {
                        chart.draw_series(DashedLineSeries::new(points, dash, gap, style)).map_err(err)?
                    }
                };
                if label_on_line {
                    label(annotation);
                }
            }
            if let Some(dots) = series.dots {
                let style = dots.ring.map_or(colour.filled(), |width| colour.stroke_width(width));
                let circles = series.points.iter().map(|&p| Circle::new(p, dots.radius, style));
                let annotation = chart.draw_series(circles).map_err(err)?;
                if !label_on_line {
                    label(annotation);
                }
            }
        }
        for note in &self.notes {
            chart
                .draw_series(std::iter::once(Text::new(note.text.clone(), note.at, ("sans-serif", note.size))))
                .map_err(err)?;
        }
        let Some(legend) = &self.legend else { return Ok(()) };
        let mut labels = chart.configure_series_labels();
        if let Some(position) = &legend.position {
            labels.position(position.clone());
        }
        labels
            .label_font(("sans-serif", legend.font))
            .background_style(WHITE.mix(legend.opacity))
            .border_style(BLACK)
            .draw()
            .map_err(err)
    }
}

/// Sets the legend sample of a series.
fn legend_mark<DB: DrawingBackend>(annotation: &mut SeriesAnno<'_, DB>, mark: LegendMark, colour: RGBColor) {
    match mark {
        LegendMark::Line { length, width } => {
            annotation.legend(move |(x, y)| PathElement::new(vec![(x, y), (x + length, y)], colour.stroke_width(width)))
        }
        LegendMark::Dot { dx, radius } => {
            annotation.legend(move |(x, y)| Circle::new((x + dx, y), radius, colour.filled()))
        }
    };
}

/// Each test below draws a chart by hand with plotters the way a question's figure code draws
/// it (Q1's chart, Q4's Pareto charts, Q5's log-log chart; same calls, small data) and demands the
/// same bytes from a [`Chart`], so that converting a chart to it is a change of code, not of
/// figures.
#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::PALETTE;

    const LINE: [(f64, f64); 3] = [(1.0, 0.9), (10.0, 0.3), (100.0, 0.05)];
    const DOTS: [(f64, f64); 3] = [(2.0, 0.5), (20.0, 0.2), (50.0, 0.1)];

    fn tick(value: &f64) -> String {
        format!("{}", (value * 1e6).round() / 1e6)
    }

    /// Q1's `chart`: log x, linear y, light grid off, tick counts and formats, line and dot series.
    #[test]
    fn reproduces_the_q1_chart() {
        let by_hand = svg_figure("q1.svg", (640, 420), |root| {
            let mut chart = ChartBuilder::on(root)
                .caption("Q1", ("sans-serif", 18))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d((1.0..100.0).log_scale(), 0.0..1.05)
                .map_err(err)?;
            chart
                .configure_mesh()
                .x_desc("x")
                .y_desc("y")
                .label_style(("sans-serif", 13))
                .light_line_style(TRANSPARENT)
                .x_labels(12)
                .y_labels(8)
                .x_label_formatter(&tick)
                .y_label_formatter(&tick)
                .draw()
                .map_err(err)?;
            let colour = PALETTE[0];
            chart
                .draw_series(LineSeries::new(LINE, colour.stroke_width(2)))
                .map_err(err)?
                .label("line")
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], colour));
            let colour = PALETTE[1];
            chart
                .draw_series(DOTS.iter().map(|&p| Circle::new(p, 4, colour.filled())))
                .map_err(err)?
                .label("dots")
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, colour.filled()));
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::LowerLeft)
                .label_font(("sans-serif", 13))
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .draw()
                .map_err(err)
        })
        .unwrap();
        let ticks = |axis: Axis<'static>, labels| Axis { labels: Some(labels), format: Some(tick), ..axis };
        let helper = Chart {
            label_size: 13,
            light_grid: false,
            series: vec![
                Series {
                    legend: LegendMark::Line { length: 16, width: 1 },
                    ..Series::line("line", LINE.to_vec(), PALETTE[0], 2)
                },
                Series::dots("dots", DOTS.to_vec(), PALETTE[1], 4),
            ],
            legend: Some(Legend { position: Some(SeriesLabelPosition::LowerLeft), font: 13, opacity: 0.85 }),
            ..Chart::new("Q1", ticks(Axis::log(1.0, 100.0, "x"), 12), ticks(Axis::linear(0.0, 1.05, "y"), 8))
        }
        .svg("q1.svg", (640, 420))
        .unwrap();
        assert!(by_hand == helper, "the helper draws Q1's chart byte for byte");
    }

    /// Q4's Pareto charts: an unlabelled line, then labelled dots, text notes, the Q4 legend box.
    #[test]
    fn reproduces_the_q4_pareto_chart() {
        let by_hand = svg_figure("q4.svg", (680, 440), |root| {
            let mut chart = ChartBuilder::on(root)
                .caption("Q4", ("sans-serif", 17))
                .margin(10)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d((0.5..200.0).log_scale(), (0.01..2.0).log_scale())
                .map_err(err)?;
            chart.configure_mesh().x_desc("ns").y_desc("%").label_style(("sans-serif", 12)).draw().map_err(err)?;
            let colour = PALETTE[2];
            chart.draw_series(LineSeries::new(LINE.to_vec(), colour.stroke_width(1))).map_err(err)?;
            chart
                .draw_series(LINE.iter().map(|&p| Circle::new(p, 4, colour.filled())))
                .map_err(err)?
                .label("sh9")
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, colour.filled()));
            chart
                .draw_series(std::iter::once(Text::new("sh9 256²".to_string(), (11.5, 0.3), ("sans-serif", 11))))
                .map_err(err)?;
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::LowerLeft)
                .label_font(("sans-serif", 12))
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .draw()
                .map_err(err)
        })
        .unwrap();
        let helper = Chart {
            caption_size: 17,
            margin: 10,
            series: vec![Series {
                line: Some(Stroke { width: 1, dash: None }),
                ..Series::dots("sh9", LINE.to_vec(), PALETTE[2], 4)
            }],
            notes: vec![Note { text: "sh9 256²".into(), at: (11.5, 0.3), size: 11 }],
            legend: Some(Legend { position: Some(SeriesLabelPosition::LowerLeft), font: 12, opacity: 0.85 }),
            ..Chart::new("Q4", Axis::log(0.5, 200.0, "ns"), Axis::log(0.01, 2.0, "%"))
        }
        .svg("q4.svg", (680, 440))
        .unwrap();
        assert!(by_hand == helper, "the helper draws Q4's Pareto chart byte for byte");
    }

    /// Q5's `LogLogChart`: the area filled again, marked lines, a dashed reference line, the legend
    /// at plotters' default corner.
    #[test]
    fn reproduces_the_q5_log_log_chart() {
        let by_hand = svg_figure("q5.svg", (640, 400), |root| {
            root.fill(&WHITE).map_err(err)?;
            let mut chart = ChartBuilder::on(root)
                .caption("Q5", ("sans-serif", 18))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d((1.0..100.0).log_scale(), (0.01..1.0).log_scale())
                .map_err(err)?;
            chart.configure_mesh().x_desc("k").y_desc("error").label_style(("sans-serif", 12)).draw().map_err(err)?;
            let colour = PALETTE[0];
            chart
                .draw_series(LineSeries::new(LINE.to_vec(), colour.stroke_width(2)))
                .map_err(err)?
                .label("photons")
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], colour.stroke_width(2)));
            chart.draw_series(LINE.iter().map(|&p| Circle::new(p, 3, colour.filled()))).map_err(err)?;
            chart
                .draw_series(DashedLineSeries::new(DOTS.to_vec(), 6, 4, BLACK.stroke_width(1)))
                .map_err(err)?
                .label("law")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], BLACK.stroke_width(1)));
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .label_font(("sans-serif", 13))
                .draw()
                .map_err(err)
        })
        .unwrap();
        let helper = Chart {
            fill: true,
            series: vec![
                Series {
                    dots: Some(Dots { radius: 3, ring: None }),
                    ..Series::line("photons", LINE.to_vec(), PALETTE[0], 2)
                },
                Series {
                    line: Some(Stroke { width: 1, dash: Some((6, 4)) }),
                    ..Series::line("law", DOTS.to_vec(), BLACK, 1)
                },
            ],
            legend: Some(Legend { position: None, font: 13, opacity: 0.8 }),
            ..Chart::new("Q5", Axis::log(1.0, 100.0, "k"), Axis::log(0.01, 1.0, "error"))
        }
        .svg("q5.svg", (640, 400))
        .unwrap();
        assert!(by_hand == helper, "the helper draws Q5's log-log chart byte for byte");
    }

    #[test]
    fn png_backend_draws_the_same_chart_deterministically() {
        let chart = Chart {
            series: vec![Series::line("l", LINE.to_vec(), PALETTE[0], 2)],
            ..Chart::new("png", Axis::log(1.0, 100.0, "x"), Axis::linear(0.0, 1.0, "y"))
        };
        let (a, b) = (chart.png("c.png", (320, 200)).unwrap(), chart.png("c.png", (320, 200)).unwrap());
        assert_eq!(a, b);
        assert!(image::load_from_memory(&a.bytes).is_ok());
    }
}
