//! One chart helper: a caption, two axes (each linear or logarithmic), series of lines, dashed
//! lines and dots, text notes and a legend, drawn on any plotters backend (SVG or PNG figures, or one
//! panel of a larger figure). The same helper draws the crate's diagrams (a sphere and its rays, a
//! kd-tree's cells): a cartesian area with equal scales, a bare or axes-only mesh, and [`Shape`]s
//! (lines, dots, labels, arrow heads, shaded boxes) drawn in the order given.
//!
//! A [`Chart`] is plain data, so a figure reads as a description of what it shows; every style the
//! crate's figures use (caption and label sizes, label areas, legend box, marker sizes, grid) is a
//! field, so converting a hand-built plotters chart to it keeps its bytes.

use super::{DrawError, Figure, PlotError, png_figure, svg_figure};
use plotters::chart::SeriesAnno;
use plotters::coord::Shift;
use plotters::coord::combinators::WithKeyPoints;
use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

/// Formats one tick value of an axis.
pub type TickFormat = fn(&f64) -> String;

/// A compact tick label for a log axis: a power of ten from 0.01 to 1000 prints as a plain number
/// (`0.01`, `1`, `1000`), a smaller or larger one as `1e-5` or `1e6` (plotters' default prints
/// `9.999999999999998e-5` and `1000000.0`); any other value prints with at most four significant
/// digits and no trailing zeros (`250`, `0.05`).
///
/// Numeric behaviour: a value within a relative 1e-9 of a power of ten counts as that power;
/// zero, negative and non-finite values print as Rust's `{}` does.
///
/// # Examples
/// ```
/// use hw3_core::plot::compact_tick;
/// assert_eq!(compact_tick(&9.999999999999998e-5), "1e-4");
/// assert_eq!(compact_tick(&1e-5), "1e-5");
/// assert_eq!(compact_tick(&1_000_000.0), "1e6");
/// assert_eq!(compact_tick(&0.999_999_999_999_999_8), "1");
/// assert_eq!(compact_tick(&0.001), "1e-3");
/// assert_eq!(compact_tick(&250.0), "250");
/// assert_eq!(compact_tick(&0.05), "0.05");
/// ```
#[must_use]
pub fn compact_tick(value: &f64) -> String {
    let value = *value;
    if !(value.is_finite() && value > 0.0) {
        return format!("{value}");
    }
    let exponent = value.log10().round();
    if (value / 10f64.powf(exponent) - 1.0).abs() < 1e-9 && !(-2.0..=3.0).contains(&exponent) {
        return format!("1e{exponent}");
    }
    let digits = (3.0 - exponent.min(value.log10().floor())).max(0.0);
    let scale = 10f64.powf(digits);
    format!("{}", (value * scale).round() / scale)
}

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
    /// The tick values of a log axis, where the data's points are (plotters' choice when `None`;
    /// on a log axis it may leave the first points unlabelled). [`Chart::draw`] fails when this is
    /// set on a linear axis.
    pub ticks: Option<&'a [f64]>,
}

impl<'a> Axis<'a> {
    /// A linear axis over `low..high` titled `desc`, with plotters' default ticks.
    ///
    /// # Examples
    /// ```
    /// let x = hw3_core::plot::Axis::linear(0.0, 20.0, "sweeps");
    /// assert!(!x.log);
    /// ```
    #[must_use]
    pub fn linear(low: f64, high: f64, desc: &'a str) -> Self {
        Self { range: (low, high), log: false, desc, labels: None, format: None, ticks: None }
    }

    /// A logarithmic axis over `low..high` (both positive) titled `desc`.
    ///
    /// # Examples
    /// ```
    /// let y = hw3_core::plot::Axis::log(1e-3, 1.0, "error");
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
    /// use hw3_core::plot::{PALETTE, Series};
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
    /// use hw3_core::plot::{PALETTE, Series};
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

/// A text note at a data point.
#[derive(Debug, Clone, PartialEq)]
pub struct Note {
    /// The text.
    pub text: String,
    /// Where its top-left corner goes, in data coordinates.
    pub at: (f64, f64),
    /// Font size in pixels.
    pub size: u32,
    /// The text's colour.
    pub colour: RGBColor,
}

impl Note {
    /// A black note of `size` pixels with its top-left corner at `at`.
    ///
    /// # Examples
    /// ```
    /// let note = hw3_core::plot::Note::new("sh9 256²", (11.5, 0.3), 11);
    /// assert_eq!(note.colour, plotters::style::BLACK);
    /// ```
    #[must_use]
    pub fn new(text: impl Into<String>, at: (f64, f64), size: u32) -> Self {
        Self { text: text.into(), at, size, colour: BLACK }
    }
}

/// One thing a diagram draws, in data coordinates. A chart draws its [`Chart::shapes`] in order
/// after its series and notes, because a diagram's lines, dots and labels interleave (a dot over
/// a line, a label over the dot).
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A series with no legend entry, or with one (its label is then listed in the legend).
    Series(Series),
    /// A text.
    Note(Note),
    /// A filled polygon (an arrow head).
    Polygon {
        /// The corners, in order.
        points: Vec<(f64, f64)>,
        /// The fill colour.
        colour: RGBColor,
    },
    /// A filled axis-aligned box (a shaded cell).
    Rectangle {
        /// Two opposite corners.
        corners: [(f64, f64); 2],
        /// The fill colour.
        colour: RGBColor,
        /// The fill's opacity, 0 (invisible) to 1.
        opacity: f64,
    },
}

impl Shape {
    /// A solid line of `width` pixels through `points`, with no legend entry.
    ///
    /// # Examples
    /// ```
    /// use hw3_core::plot::{PALETTE, Shape};
    /// let Shape::Series(line) = Shape::line(vec![(0.0, 0.0), (1.0, 2.0)], PALETTE[0], 2) else { unreachable!() };
    /// assert!(line.label.is_none() && line.dots.is_none());
    /// ```
    #[must_use]
    pub fn line(points: Vec<(f64, f64)>, colour: RGBColor, width: u32) -> Self {
        Self::Series(Series { label: None, ..Series::line("", points, colour, width) })
    }

    /// A filled dot of `radius` pixels at `at`, with no legend entry.
    ///
    /// # Examples
    /// ```
    /// use hw3_core::plot::{PALETTE, Shape};
    /// let Shape::Series(dot) = Shape::dot((1.0, 2.0), 4, PALETTE[1]) else { unreachable!() };
    /// assert_eq!(dot.points, [(1.0, 2.0)]);
    /// ```
    #[must_use]
    pub fn dot(at: (f64, f64), radius: u32, colour: RGBColor) -> Self {
        Self::Series(Series { label: None, ..Series::dots("", vec![at], colour, radius) })
    }

    /// A text of `size` pixels in `colour` with its top-left corner at `at`.
    ///
    /// # Examples
    /// ```
    /// use hw3_core::plot::{PALETTE, Shape};
    /// let Shape::Note(note) = Shape::text("e", (0.0, 1.0), 13, PALETTE[0]) else { unreachable!() };
    /// assert_eq!((note.text.as_str(), note.size), ("e", 13));
    /// ```
    #[must_use]
    pub fn text(text: impl Into<String>, at: (f64, f64), size: u32, colour: RGBColor) -> Self {
        Self::Note(Note { colour, ..Note::new(text, at, size) })
    }
}

/// How much of the mesh (the axes, their tick labels and titles, the grid) a chart draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mesh {
    /// Axes, tick labels, axis titles and the grid lines (the light ones as
    /// [`Chart::light_grid`] says).
    Grid,
    /// Axes, tick labels and axis titles, no grid lines: a diagram whose coordinates a reader
    /// may want to read off.
    Axes,
    /// Nothing: a bare drawing area, for a diagram whose coordinates mean nothing to the reader.
    Hidden,
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
    /// How much of the mesh is drawn.
    pub mesh: Mesh,
    /// Draw the light (minor) grid lines.
    pub light_grid: bool,
    /// The colour of the bold grid lines (plotters' default when `None`).
    pub grid_colour: Option<RGBColor>,
    /// One data unit as long on both axes, so that a circle is drawn round: the top of the y
    /// range follows from the plotting area's pixels (what the margin and label areas leave of
    /// the area drawn on), and `y.range.1` is not read. Linear axes and no caption only (title
    /// the area first with plotters' `DrawingArea::titled`).
    pub equal_scale: bool,
    /// Fill the drawing area white again before drawing (the figure is already white).
    pub fill: bool,
    /// The series, drawn in order.
    pub series: Vec<Series>,
    /// Text notes, drawn after the series.
    pub notes: Vec<Note>,
    /// Shapes, drawn in order after the notes.
    pub shapes: Vec<Shape>,
    /// The legend (none when `None`).
    pub legend: Option<Legend>,
}

impl<'a> Chart<'a> {
    /// A chart with no series: caption 18 px (none when `caption` is empty), margin 12, label
    /// areas 40 × 60, labels 12 px, the whole mesh with plotters' grid colours, unequal scales,
    /// and a legend at plotters' default corner (13 px, opacity 0.85).
    ///
    /// # Examples
    /// ```
    /// use hw3_core::plot::{Axis, Chart, PALETTE, Series};
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
            mesh: Mesh::Grid,
            light_grid: true,
            grid_colour: None,
            equal_scale: false,
            fill: false,
            series: Vec::new(),
            notes: Vec::new(),
            shapes: Vec::new(),
            legend: Some(Legend { position: None, font: 13, opacity: 0.85 }),
        }
    }

    /// The chart as an SVG figure of `width`×`height` pixels.
    ///
    /// # Errors
    /// [`PlotError::Draw`] with the [`DrawError`] of [`Chart::draw`] (plotters' error, e.g. for a
    /// log axis with a non-positive end, or what the chart refuses).
    pub fn svg(&self, file_name: &str, size: (u32, u32)) -> Result<Figure, PlotError> {
        svg_figure(file_name, size, |root| self.draw(root))
    }

    /// The chart as a PNG figure of `width`×`height` pixels.
    ///
    /// # Errors
    /// [`PlotError::Draw`] with the [`DrawError`] of [`Chart::draw`], [`PlotError::Encode`] when
    /// encoding fails.
    pub fn png(&self, file_name: &str, size: (u32, u32)) -> Result<Figure, PlotError> {
        png_figure(file_name, size, |root| self.draw(root))
    }

    /// Draws the chart on `area` (a whole figure, or one panel of it).
    ///
    /// # Errors
    /// [`DrawError::EqualScale`] when [`Chart::equal_scale`] is asked of a chart with a caption or
    /// a log axis, [`DrawError::TicksOnLinearAxis`] when [`Axis::ticks`] is set on a linear axis,
    /// and plotters' error ([`DrawError::Backend`] and the like) when drawing fails.
    pub fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), DrawError> {
        let (x, mut y) = (self.x.range, self.y.range);
        if self.equal_scale {
            if !self.caption.is_empty() || self.x.log || self.y.log {
                return Err(DrawError::EqualScale);
            }
            let (width, height) = area.dim_in_pixel();
            let inside = |pixels: u32, label_area: u32| f64::from(pixels.saturating_sub(2 * self.margin + label_area));
            let units_per_pixel = (x.1 - x.0) / inside(width, self.label_areas.1);
            y.1 = y.0 + units_per_pixel * inside(height, self.label_areas.0);
        }
        if (self.x.ticks.is_some() && !self.x.log) || (self.y.ticks.is_some() && !self.y.log) {
            return Err(DrawError::TicksOnLinearAxis);
        }
        let y = AxisCoord::new(y, self.y.log, self.y.ticks);
        self.draw_in(area, AxisCoord::new(self.x.range, self.x.log, self.x.ticks), y)
    }

    fn draw_in<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        x: AxisCoord,
        y: AxisCoord,
    ) -> Result<(), DrawError> {
        if self.fill {
            area.fill(&WHITE)?;
        }
        let mut builder = ChartBuilder::on(area);
        if !self.caption.is_empty() {
            builder.caption(self.caption, ("sans-serif", self.caption_size));
        }
        let mut chart = builder
            .margin(self.margin)
            .x_label_area_size(self.label_areas.0)
            .y_label_area_size(self.label_areas.1)
            .build_cartesian_2d(x, y)?;
        if self.mesh != Mesh::Hidden {
            let mut mesh = chart.configure_mesh();
            mesh.label_style(("sans-serif", self.label_size));
            if !self.x.desc.is_empty() {
                mesh.x_desc(self.x.desc);
            }
            if !self.y.desc.is_empty() {
                mesh.y_desc(self.y.desc);
            }
            if self.mesh == Mesh::Axes {
                mesh.disable_mesh();
            }
            if !self.light_grid {
                mesh.light_line_style(TRANSPARENT);
            }
            if let Some(colour) = self.grid_colour {
                mesh.bold_line_style(colour);
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
            mesh.draw()?;
        }
        for series in &self.series {
            draw_series(&mut chart, series)?;
        }
        for note in &self.notes {
            draw_note(&mut chart, note)?;
        }
        for shape in &self.shapes {
            match shape {
                Shape::Series(series) => draw_series(&mut chart, series)?,
                Shape::Note(note) => draw_note(&mut chart, note)?,
                Shape::Polygon { points, colour } => {
                    chart.draw_series(std::iter::once(Polygon::new(points.clone(), colour.filled())))?;
                }
                Shape::Rectangle { corners, colour, opacity } => {
                    let style = colour.mix(*opacity).filled();
                    chart.draw_series(std::iter::once(Rectangle::new(*corners, style)))?;
                }
            }
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
            .draw()?;
        Ok(())
    }
}

/// The cartesian chart [`Chart::draw_in`] draws on.
type Cartesian<'a, DB, X, Y> = ChartContext<'a, DB, Cartesian2d<X, Y>>;

/// One axis's coordinate: plotters' linear, log, or log-with-given-ticks coordinate behind one
/// type. Each of plotters' three is a type of its own, and a chart generic over both axes'
/// types was compiled nine times per drawing backend, the whole of plotters' chart code each
/// time: one type instead cut the library's test build from 1 070 070 to 908 416 lines of LLVM
/// IR (`cargo llvm-lines --lib --profile test`). Every method forwards to the variant, so the
/// figures are the same bytes.
enum AxisCoord {
    Linear(RangedCoordf64),
    Log(LogCoord<f64>),
    LogTicks(WithKeyPoints<LogCoord<f64>>),
}

impl AxisCoord {
    fn new((low, high): (f64, f64), log: bool, ticks: Option<&[f64]>) -> Self {
        match (log, ticks) {
            (false, _) => Self::Linear((low..high).into()),
            (true, None) => Self::Log((low..high).log_scale().into()),
            (true, Some(ticks)) => Self::LogTicks((low..high).log_scale().with_key_points(ticks.to_vec())),
        }
    }
}

impl Ranged for AxisCoord {
    type FormatOption = plotters::coord::ranged1d::NoDefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        match self {
            Self::Linear(c) => c.map(value, limit),
            Self::Log(c) => c.map(value, limit),
            Self::LogTicks(c) => c.map(value, limit),
        }
    }

    fn key_points<Hint: plotters::coord::ranged1d::KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        match self {
            Self::Linear(c) => c.key_points(hint),
            Self::Log(c) => c.key_points(hint),
            Self::LogTicks(c) => c.key_points(hint),
        }
    }

    fn range(&self) -> std::ops::Range<f64> {
        match self {
            Self::Linear(c) => c.range(),
            Self::Log(c) => c.range(),
            Self::LogTicks(c) => c.range(),
        }
    }

    fn axis_pixel_range(&self, limit: (i32, i32)) -> std::ops::Range<i32> {
        match self {
            Self::Linear(c) => c.axis_pixel_range(limit),
            Self::Log(c) => c.axis_pixel_range(limit),
            Self::LogTicks(c) => c.axis_pixel_range(limit),
        }
    }
}

impl ValueFormatter<f64> for AxisCoord {
    fn format_ext(&self, value: &f64) -> String {
        match self {
            Self::Linear(c) => c.format_ext(value),
            Self::Log(c) => c.format_ext(value),
            Self::LogTicks(c) => c.format_ext(value),
        }
    }
}

/// Draws `series` (its line first, then its dots) and gives it its legend entry.
fn draw_series<DB, X, Y>(chart: &mut Cartesian<'_, DB, X, Y>, series: &Series) -> Result<(), DrawError>
where
    DB: DrawingBackend,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let colour = series.colour;
    let legend = series.legend;
    let label_on_line = series.line.is_some() && (matches!(legend, LegendMark::Line { .. }) || series.dots.is_none());
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
            None => chart.draw_series(LineSeries::new(points, style))?,
            Some((dash, gap)) => chart.draw_series(DashedLineSeries::new(points, dash, gap, style))?,
        };
        if label_on_line {
            label(annotation);
        }
    }
    if let Some(dots) = series.dots {
        let style = dots.ring.map_or(colour.filled(), |width| colour.stroke_width(width));
        let circles = series.points.iter().map(|&p| Circle::new(p, dots.radius, style));
        let annotation = chart.draw_series(circles)?;
        if !label_on_line {
            label(annotation);
        }
    }
    Ok(())
}

/// Draws a legend on an area of its own (a strip below or beside the panels it explains, so that
/// it hides no data): each labelled series of `series`, in rows of `columns` left to right, as a
/// sample 22 px long (the series' line, dashed as it is drawn, and a dot in its middle when the
/// series has dots) followed by its label in `font`-px text. Rows are `font + 12` px apart, the
/// columns split the area's width evenly; nothing is drawn for a series without a label.
///
/// # Errors
/// [`DrawError::NoLegendColumns`] when `columns` is 0; plotters' error ([`DrawError::Backend`]
/// and the like) when drawing fails.
///
/// # Examples
/// ```
/// use hw3_core::plot::{PALETTE, Series, legend_grid, svg_figure};
/// let entries = [Series::line("kd-tree", vec![], PALETTE[0], 2), Series::dots("measured", vec![], PALETTE[1], 3)];
/// let figure = svg_figure("legend.svg", (400, 40), |root| legend_grid(root, &entries, 2, 13)).unwrap();
/// let svg = String::from_utf8(figure.bytes).unwrap();
/// assert!(svg.contains("kd-tree") && svg.contains("measured"));
/// ```
pub fn legend_grid<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    series: &[Series],
    columns: usize,
    font: u32,
) -> Result<(), DrawError> {
    if columns == 0 {
        return Err(DrawError::NoLegendColumns);
    }
    let column_width = area.dim_in_pixel().0 as i32 / columns as i32;
    let row_height = font as i32 + 12;
    for (k, series) in series.iter().filter(|s| s.label.is_some()).enumerate() {
        let (x, y) = (12 + column_width * (k % columns) as i32, 6 + row_height * (k / columns) as i32);
        let middle = y + font as i32 / 2 + 1;
        if let Some(stroke) = series.line {
            let ends = vec![(x, middle), (x + 22, middle)];
            let style = series.colour.stroke_width(stroke.width);
            match stroke.dash {
                None => area.draw(&PathElement::new(ends, style)),
                Some((dash, gap)) => area.draw(&DashedPathElement::new(ends, dash, gap, style)),
            }?;
        }
        if let Some(dots) = series.dots {
            let style = dots.ring.map_or(series.colour.filled(), |width| series.colour.stroke_width(width));
            area.draw(&Circle::new((x + 11, middle), dots.radius, style))?;
        }
        let label = series.label.clone().unwrap_or_default();
        area.draw(&Text::new(label, (x + 30, y), ("sans-serif", font)))?;
    }
    Ok(())
}

/// Draws `note` in its colour.
fn draw_note<DB, X, Y>(chart: &mut Cartesian<'_, DB, X, Y>, note: &Note) -> Result<(), DrawError>
where
    DB: DrawingBackend,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let style = TextStyle::from(("sans-serif", note.size)).color(&note.colour);
    chart.draw_series(std::iter::once(Text::new(note.text.clone(), note.at, style)))?;
    Ok(())
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

/// Each test below draws a chart by hand with plotters the way a question's figure code drew
/// it (Q1's chart, Q4's Pareto charts, Q5's log-log chart, Q2's and Q3's diagrams; same calls,
/// small data) and demands the same bytes from a [`Chart`], so that converting a chart to it is a
/// change of code, not of figures.
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
                .build_cartesian_2d((1.0..100.0).log_scale(), 0.0..1.05)?;
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
                .draw()?;
            let colour = PALETTE[0];
            chart
                .draw_series(LineSeries::new(LINE, colour.stroke_width(2)))?
                .label("line")
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], colour));
            let colour = PALETTE[1];
            chart
                .draw_series(DOTS.iter().map(|&p| Circle::new(p, 4, colour.filled())))?
                .label("dots")
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, colour.filled()));
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::LowerLeft)
                .label_font(("sans-serif", 13))
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .draw()?;
            Ok(())
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
                .build_cartesian_2d((0.5..200.0).log_scale(), (0.01..2.0).log_scale())?;
            chart.configure_mesh().x_desc("ns").y_desc("%").label_style(("sans-serif", 12)).draw()?;
            let colour = PALETTE[2];
            chart.draw_series(LineSeries::new(LINE.to_vec(), colour.stroke_width(1)))?;
            chart
                .draw_series(LINE.iter().map(|&p| Circle::new(p, 4, colour.filled())))?
                .label("sh9")
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, colour.filled()));
            chart.draw_series(std::iter::once(Text::new("sh9 256²".to_string(), (11.5, 0.3), ("sans-serif", 11))))?;
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::LowerLeft)
                .label_font(("sans-serif", 12))
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .draw()?;
            Ok(())
        })
        .unwrap();
        let helper = Chart {
            caption_size: 17,
            margin: 10,
            series: vec![Series {
                line: Some(Stroke { width: 1, dash: None }),
                ..Series::dots("sh9", LINE.to_vec(), PALETTE[2], 4)
            }],
            notes: vec![Note::new("sh9 256²", (11.5, 0.3), 11)],
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
            root.fill(&WHITE)?;
            let mut chart = ChartBuilder::on(root)
                .caption("Q5", ("sans-serif", 18))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d((1.0..100.0).log_scale(), (0.01..1.0).log_scale())?;
            chart.configure_mesh().x_desc("k").y_desc("error").label_style(("sans-serif", 12)).draw()?;
            let colour = PALETTE[0];
            chart
                .draw_series(LineSeries::new(LINE.to_vec(), colour.stroke_width(2)))?
                .label("photons")
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], colour.stroke_width(2)));
            chart.draw_series(LINE.iter().map(|&p| Circle::new(p, 3, colour.filled())))?;
            chart
                .draw_series(DashedLineSeries::new(DOTS.to_vec(), 6, 4, BLACK.stroke_width(1)))?
                .label("law")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], BLACK.stroke_width(1)));
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .label_font(("sans-serif", 13))
                .draw()?;
            Ok(())
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

    /// Q2's and Q3's diagrams: a titled area, equal scales, an axes-only or bare mesh, a grid
    /// colour, and lines, dots, rings, coloured labels, an arrow head and a shaded box drawn in
    /// the order given.
    #[test]
    fn reproduces_a_diagram() {
        let (x_min, x_max, y_min) = (-6.0, 3.0, -2.5);
        let by_hand = svg_figure("d.svg", (560, 360), |root| {
            let area = root.titled("diagram", ("sans-serif", 16))?;
            let (width, height) = area.dim_in_pixel();
            let units_per_pixel = (x_max - x_min) / f64::from(width - 2 * 6 - 26);
            let y_max = y_min + units_per_pixel * f64::from(height - 2 * 6 - 20);
            let mut chart = ChartBuilder::on(&area)
                .margin(6)
                .x_label_area_size(20)
                .y_label_area_size(26)
                .build_cartesian_2d(x_min..x_max, y_min..y_max)?;
            chart
                .configure_mesh()
                .disable_mesh()
                .x_labels(10)
                .bold_line_style(RGBColor(230, 230, 230))
                .label_style(("sans-serif", 11))
                .draw()?;
            let box_style = PALETTE[3].mix(0.15).filled();
            chart.draw_series(std::iter::once(Rectangle::new([(0.0, 0.0), (1.0, 1.0)], box_style)))?;
            chart.draw_series(LineSeries::new(LINE.to_vec(), PALETTE[0].stroke_width(2)))?;
            let head = vec![(1.0, 0.0), (0.8, 0.1), (0.8, -0.1)];
            chart.draw_series(std::iter::once(Polygon::new(head, PALETTE[0].filled())))?;
            chart.draw_series(std::iter::once(Circle::new((0.0, 0.0), 4, PALETTE[1].filled())))?;
            let label = TextStyle::from(("sans-serif", 13)).color(&PALETTE[1]);
            chart.draw_series(std::iter::once(Text::new("o".to_string(), (0.1, -0.1), label)))?;
            chart.draw_series(std::iter::once(Circle::new((1.0, 1.0), 8, PALETTE[2].stroke_width(2))))?;
            let bare = root.margin(200, 0, 300, 0);
            let (width, height) = bare.dim_in_pixel();
            let y_max = -1.0 + 2.0 * f64::from(height - 22) / f64::from(width);
            let mut chart = ChartBuilder::on(&bare).margin_bottom(22).build_cartesian_2d(-1.0..1.0, -1.0..y_max)?;
            chart.draw_series(LineSeries::new(DOTS.to_vec(), BLACK.stroke_width(1)))?;
            Ok(())
        })
        .unwrap();
        let helper = svg_figure("d.svg", (560, 360), |root| {
            let area = root.titled("diagram", ("sans-serif", 16))?;
            Chart {
                margin: 6,
                label_areas: (20, 26),
                label_size: 11,
                mesh: Mesh::Axes,
                grid_colour: Some(RGBColor(230, 230, 230)),
                equal_scale: true,
                shapes: vec![
                    Shape::Rectangle { corners: [(0.0, 0.0), (1.0, 1.0)], colour: PALETTE[3], opacity: 0.15 },
                    Shape::line(LINE.to_vec(), PALETTE[0], 2),
                    Shape::Polygon { points: vec![(1.0, 0.0), (0.8, 0.1), (0.8, -0.1)], colour: PALETTE[0] },
                    Shape::dot((0.0, 0.0), 4, PALETTE[1]),
                    Shape::text("o", (0.1, -0.1), 13, PALETTE[1]),
                    Shape::Series(Series {
                        label: None,
                        dots: Some(Dots { radius: 8, ring: Some(2) }),
                        ..Series::dots("", vec![(1.0, 1.0)], PALETTE[2], 8)
                    }),
                ],
                legend: None,
                ..Chart::new(
                    "",
                    Axis { labels: Some(10), ..Axis::linear(x_min, x_max, "") },
                    Axis::linear(y_min, 0.0, ""),
                )
            }
            .draw(&area)?;
            // A bare area whose bottom band (here the x label area) is left to the caller.
            Chart {
                margin: 0,
                label_areas: (22, 0),
                mesh: Mesh::Hidden,
                equal_scale: true,
                shapes: vec![Shape::line(DOTS.to_vec(), BLACK, 1)],
                legend: None,
                ..Chart::new("", Axis::linear(-1.0, 1.0, ""), Axis::linear(-1.0, 0.0, ""))
            }
            .draw(&root.margin(200, 0, 300, 0))
        })
        .unwrap();
        assert!(by_hand == helper, "the helper draws a diagram byte for byte");
    }

    #[test]
    fn equal_scales_refuse_a_caption_and_log_axes() {
        let chart = Chart {
            equal_scale: true,
            ..Chart::new("title", Axis::linear(0.0, 1.0, "x"), Axis::linear(0.0, 1.0, "y"))
        };
        let refused = |chart: &Chart<'_>| {
            matches!(chart.svg("e.svg", (200, 200)), Err(PlotError::Draw { source: DrawError::EqualScale, .. }))
        };
        assert!(refused(&chart));
        let chart = Chart { caption: "", x: Axis::log(1.0, 10.0, "x"), ..chart };
        assert!(refused(&chart));
        assert!(Chart { x: Axis::linear(0.0, 1.0, "x"), ..chart }.svg("e.svg", (200, 200)).is_ok());
    }

    #[test]
    fn png_backend_draws_the_same_chart_deterministically() {
        let chart = Chart {
            series: vec![Series::line("l", LINE.to_vec(), PALETTE[0], 2)],
            ..Chart::new("png", Axis::log(1.0, 100.0, "x"), Axis::linear(0.0, 1.0, "y"))
        };
        let (a, b) = (chart.png("c.png", (320, 200)).unwrap(), chart.png("c.png", (320, 200)).unwrap());
        assert_eq!(a, b);
        assert!(crate::plot::decode_png(&a.bytes).is_ok());
    }
}
