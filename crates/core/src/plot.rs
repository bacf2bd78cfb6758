//! Shared plotting core: an embedded font, deterministic SVG/PNG figures, the [`Figure`] type
//! every question module returns from its `figures()` function, one chart helper ([`Chart`]),
//! one markdown-table writer ([`markdown_table`]), and the errors of drawing ([`DrawError`], what
//! a drawing closure returns) and of making a figure ([`PlotError`]).
//!
//! Figures must be byte-identical from run to run (they are committed under `docs/figures/` and
//! pinned by snapshots), so nothing here reads the clock, the locale or the system's fonts: text is
//! laid out with DejaVu Sans, compiled into the binary by the `dejavu` crate and registered with
//! plotters under the family name `"sans-serif"` (the name plotters' default labels ask for).

mod chart;
mod job;
mod raster;
mod table;

pub use chart::{
    Axis, Chart, Dots, Legend, LegendMark, Mesh, Note, Series, Shape, Stroke, TickFormat, compact_tick, legend_grid,
};
pub use job::{FigureJob, run_jobs};
pub use raster::{PngError, Rgb, RgbImage, decode_png, encode_png};
pub use table::{markdown_rows, markdown_table, significant};

use plotters::prelude::*;
use plotters::style::FontStyle;
use std::sync::Once;

/// A generated figure: the file name under `docs/figures/` and its bytes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Figure {
    /// File name with extension (`q2_roots.svg`); the extension decides the format.
    pub file_name: String,
    /// The encoded file (SVG text as UTF-8, or PNG bytes).
    pub bytes: Vec<u8>,
}

/// Why a figure could not be made.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// Drawing the figure failed: plotters refused a call, or a drawing helper of this module
    /// refused its arguments.
    #[error("drawing {figure}: {source}")]
    Draw {
        /// The figure being drawn.
        figure: String,
        /// What went wrong while drawing.
        source: DrawError,
    },
    /// The PNG encoder failed.
    #[error("encoding {figure}: {source}")]
    Encode {
        /// The figure being encoded.
        figure: String,
        /// The encoder's error.
        source: PngError,
    },
    /// What the figure shows could not be computed or read (a scene, a measurement, a probe,
    /// committed data): the error of the step that failed, whatever its type ([`PlotError::data`]).
    #[error("drawing {figure}: {source}")]
    Data {
        /// The figure being made.
        figure: String,
        /// The failed step's error.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// Two figures of one run share a file name (one would overwrite the other).
    #[error("drawing {figure}: two figures share this file name")]
    DuplicateName {
        /// The shared file name.
        figure: String,
    },
}

impl PlotError {
    /// [`PlotError::Data`]: the figure `figure` could not be made because of `source`.
    ///
    /// # Examples
    /// ```
    /// use hw3_core::geometry::InputError;
    /// let source = InputError::OutOfRange { name: "radius", value: "-1".into(), expected: "> 0" };
    /// let error = hw3_core::plot::PlotError::data("q2_cases.svg", source);
    /// assert_eq!(error.to_string(), "drawing q2_cases.svg: radius must be > 0, got -1");
    /// ```
    pub fn data<E: std::error::Error + Send + Sync + 'static>(figure: &str, source: E) -> Self {
        Self::Data { figure: figure.into(), source: Box::new(source) }
    }

    /// [`PlotError::Draw`]: drawing the figure `figure` failed with `source`.
    pub fn draw(figure: &str, source: impl Into<DrawError>) -> Self {
        Self::Draw { figure: figure.into(), source: source.into() }
    }
}

/// Why drawing failed: the error of every drawing closure and helper ([`svg_figure`],
/// [`png_figure`], [`Chart::draw`], [`color_bar`], [`legend_grid`], the questions' diagrams).
///
/// plotters' own errors convert into it (`From`), so `?` works on plotters' calls inside a
/// drawing closure.
///
/// # Examples
/// ```
/// use hw3_core::plot::{Axis, Chart, DrawError, svg_figure};
/// let ticked = Axis { ticks: Some(&[1.0]), ..Axis::linear(0.0, 1.0, "x") };
/// let chart = Chart::new("c", ticked, Axis::linear(0.0, 1.0, "y"));
/// let figure = svg_figure("c.svg", (200, 100), |root| chart.draw(root));
/// assert!(matches!(figure, Err(hw3_core::plot::PlotError::Draw { source: DrawError::TicksOnLinearAxis, .. })));
/// ```
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum DrawError {
    /// plotters' drawing backend failed. Its error type is generic over the backend (an SVG
    /// string, a bitmap buffer), so only its message is kept.
    #[error("backend error: {0}")]
    Backend(String),
    /// plotters found the backend already in use by another drawing operation.
    #[error("Multiple backend operation in progress")]
    Sharing,
    /// plotters could not lay the drawing area out (a split or margin larger than the area).
    #[error("Bad layout")]
    Layout,
    /// [`Chart::equal_scale`] was asked of a chart with a caption or a log axis.
    #[error("equal scales need linear axes and no caption (title the area first)")]
    EqualScale,
    /// [`Axis::ticks`] was set on a linear axis.
    #[error("tick values are for log axes only")]
    TicksOnLinearAxis,
    /// [`legend_grid`] was asked for 0 columns.
    #[error("a legend needs at least one column")]
    NoLegendColumns,
    /// [`panel_grid`] (or one of its variants) was given no panel.
    #[error("no panels")]
    NoPanels,
    /// [`panel_grid`] was asked for 0 columns.
    #[error("panels must share one size and columns must be at least 1")]
    NoColumns,
    /// A panel of a [`panel_grid`] differs in size from the first.
    #[error("panels must share one size and columns must be at least 1")]
    PanelSize {
        /// The first panel's width and height, in pixels.
        expected: (u32, u32),
        /// The other panel's width and height.
        found: (u32, u32),
    },
    /// A label line of [`panel_grid_labels_beside`] is wider than its column less the margin.
    #[error("label line {line:?} is {width} px, wider than {column} px less 8")]
    LabelTooWide {
        /// The label line.
        line: String,
        /// Its width as drawn, in pixels.
        width: u32,
        /// The label column's width, in pixels (8 of them are margin).
        column: u32,
    },
}

impl<E: std::error::Error + Send + Sync> From<DrawingAreaErrorKind<E>> for DrawError {
    fn from(error: DrawingAreaErrorKind<E>) -> Self {
        match error {
            DrawingAreaErrorKind::BackendError(e) => Self::Backend(e.to_string()),
            DrawingAreaErrorKind::SharingError => Self::Sharing,
            DrawingAreaErrorKind::LayoutError => Self::Layout,
        }
    }
}

static FONTS: Once = Once::new();

/// Registers the embedded DejaVu Sans (regular, bold and oblique, the last as plotters' italic) as
/// plotters' `"sans-serif"`.
///
/// Idempotent and thread-safe; every drawing helper here calls it, so callers rarely need to.
///
/// # Panics
/// Only if the font bytes compiled into the binary were not a valid font, which the tests rule out.
pub fn init_fonts() {
    FONTS.call_once(|| {
        for (style, bytes) in [
            (FontStyle::Normal, dejavu::sans::regular()),
            (FontStyle::Bold, dejavu::sans::bold()),
            (FontStyle::Italic, dejavu::sans::oblique()),
        ] {
            if plotters::style::register_font("sans-serif", style, bytes).is_err() {
                panic!("the embedded DejaVu Sans font failed to load");
            }
        }
    });
}

/// Draws an SVG figure of `width`×`height` pixels with `draw`, which receives the root area.
///
/// # Errors
/// [`PlotError::Draw`] with the [`DrawError`] of `draw` or of plotters.
pub fn svg_figure<F>(file_name: &str, (width, height): (u32, u32), draw: F) -> Result<Figure, PlotError>
where
    F: FnOnce(&DrawingArea<SVGBackend<'_>, plotters::coord::Shift>) -> Result<(), DrawError>,
{
    init_fonts();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| PlotError::draw(file_name, e))?;
        draw(&root).map_err(|e| PlotError::draw(file_name, e))?;
        root.present().map_err(|e| PlotError::draw(file_name, e))?;
    }
    Ok(Figure { file_name: file_name.into(), bytes: svg.into_bytes() })
}

/// Draws a PNG figure of `width`×`height` pixels with `draw` (plotters' bitmap backend, then
/// [`encode_png`], which is deterministic for identical pixels).
///
/// # Errors
/// [`PlotError::Draw`] with the [`DrawError`] of `draw` or of plotters, [`PlotError::Encode`]
/// when encoding fails.
pub fn png_figure<F>(file_name: &str, (width, height): (u32, u32), draw: F) -> Result<Figure, PlotError>
where
    F: FnOnce(&DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>) -> Result<(), DrawError>,
{
    init_fonts();
    let mut rgb = vec![0u8; width as usize * height as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| PlotError::draw(file_name, e))?;
        draw(&root).map_err(|e| PlotError::draw(file_name, e))?;
        root.present().map_err(|e| PlotError::draw(file_name, e))?;
    }
    let image = RgbImage::from_raw(width, height, rgb).expect("buffer has width*height*3 bytes");
    png_bytes(file_name, &image)
}

/// Encodes an RGB image as a PNG [`Figure`] (used for renders as well as charts).
///
/// # Errors
/// [`PlotError::Encode`] when the encoder fails.
pub fn png_bytes(file_name: &str, image: &RgbImage) -> Result<Figure, PlotError> {
    let bytes = encode_png(image).map_err(|source| PlotError::Encode { figure: file_name.into(), source })?;
    Ok(Figure { file_name: file_name.into(), bytes })
}

/// One picture of a [`panel_grid`]: an image and the label drawn onto its top-left corner (one
/// line per `\n`: say what differs between the panels, e.g. method, samples per pixel, error).
#[derive(Debug, Clone)]
pub struct Panel {
    /// The picture (every panel of a grid has the same size).
    pub image: RgbImage,
    /// The label, drawn white on a dark strip so it reads on bright and dark pictures alike.
    pub label: String,
}

/// Height in pixels of the labels' text of [`panel_grid`].
const LABEL_PX: u32 = 15;

/// Draws `label` (lines split at `\n`) white on a dark box at `(x, y)` of `root`.
fn draw_label<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    label: &str,
    (x, y): (i32, i32),
) -> Result<(), DrawError> {
    let font = ("sans-serif", LABEL_PX).into_font().color(&WHITE);
    let line_height = LABEL_PX as i32 + 3;
    let mut width = 0;
    for line in label.lines() {
        width = width.max(root.estimate_text_size(line, &font)?.0 as i32);
    }
    let lines = label.lines().count() as i32;
    root.draw(&Rectangle::new(
        [(x, y), (x + width + 8, y + lines * line_height + 5)],
        RGBColor(0, 0, 0).mix(0.65).filled(),
    ))?;
    for (k, line) in label.lines().enumerate() {
        root.draw(&Text::new(line.to_string(), (x + 4, y + 3 + k as i32 * line_height), font.clone()))?;
    }
    Ok(())
}

/// Lays `panels` out in rows of `columns` (left to right, top to bottom), draws each panel's
/// label onto it, and encodes the grid as a PNG [`Figure`]; a missing last panel stays black.
/// Compared panels must share one exposure: this only places pixels, it never rescales them.
///
/// # Errors
/// [`PlotError::Draw`] with [`DrawError::NoPanels`] when `panels` is empty,
/// [`DrawError::NoColumns`] when `columns` is 0, [`DrawError::PanelSize`] when the panels differ
/// in size, or plotters' error when the text cannot be drawn; [`PlotError::Encode`] when encoding
/// fails.
///
/// # Examples
/// ```
/// use hw3_core::plot::{Panel, Rgb, RgbImage, panel_grid};
/// let grey = |v| Panel { image: RgbImage::from_pixel(40, 30, Rgb([v; 3])), label: format!("v = {v}") };
/// let figure = panel_grid("grid.png", &[grey(20), grey(200), grey(90)], 2).unwrap();
/// let grid = hw3_core::plot::decode_png(&figure.bytes).unwrap();
/// assert_eq!(grid.dimensions(), (80, 60));
/// ```
pub fn panel_grid(file_name: &str, panels: &[Panel], columns: usize) -> Result<Figure, PlotError> {
    grid_of_panels(file_name, panels, columns, LabelPlace::On)
}

/// [`panel_grid`] with each label drawn on a black strip *below* its panel instead of onto it,
/// for pictures whose every corner shows something the reader is asked to look at (the strip is
/// as tall as the longest label).
///
/// # Errors
/// As [`panel_grid`].
///
/// # Examples
/// ```
/// use hw3_core::plot::{Panel, Rgb, RgbImage, panel_grid_labels_below};
/// let grey = |v| Panel { image: RgbImage::from_pixel(40, 30, Rgb([v; 3])), label: format!("v = {v}\nsecond line") };
/// let figure = panel_grid_labels_below("grid.png", &[grey(20), grey(200)], 2).unwrap();
/// let grid = hw3_core::plot::decode_png(&figure.bytes).unwrap();
/// assert_eq!(grid.dimensions(), (80, 30 + 2 * 18 + 8));
/// assert_eq!(grid.get_pixel(20, 15).0, [20; 3], "the panel itself is untouched");
/// ```
pub fn panel_grid_labels_below(file_name: &str, panels: &[Panel], columns: usize) -> Result<Figure, PlotError> {
    grid_of_panels(file_name, panels, columns, LabelPlace::Below)
}

/// [`panel_grid`] with each label drawn in a black column of `label_width` pixels to the *right*
/// of its panel: for panels that are compared side by side at full size, where a strip below each
/// would make a tall figure taller and text on the panel would cover what it shows. Every
/// `rows_per_group` rows are followed by a white gap of [`GROUP_GAP`] pixels, so that a group (one
/// effect's panels, say) reads as one block; 0 or at least the row count means no gap.
///
/// # Errors
/// As [`panel_grid`], and [`PlotError::Draw`] with [`DrawError::LabelTooWide`] when a label line
/// is wider than `label_width` less an 8-pixel margin (a label never runs into the next panel).
///
/// # Examples
/// ```
/// use hw3_core::plot::{GROUP_GAP, Panel, Rgb, RgbImage, panel_grid_labels_beside};
/// let grey = |v| Panel { image: RgbImage::from_pixel(40, 30, Rgb([v; 3])), label: format!("v = {v}") };
/// let figure = panel_grid_labels_beside("grid.png", &[grey(20), grey(200)], 2, 60, 0).unwrap();
/// let grid = hw3_core::plot::decode_png(&figure.bytes).unwrap();
/// assert_eq!(grid.dimensions(), (2 * (40 + 60), 30));
/// assert_eq!(grid.get_pixel(20, 15).0, [20; 3], "the panel itself is untouched");
/// assert!(panel_grid_labels_beside("grid.png", &[grey(20)], 1, 20, 0).is_err(), "too narrow for its label");
/// // Four rows in groups of two: one gap, white, between the second and the third row.
/// let rows = [grey(20), grey(20), grey(90), grey(90)];
/// let grouped = hw3_core::plot::decode_png(&panel_grid_labels_beside("g.png", &rows, 1, 60, 2).unwrap().bytes).unwrap();
/// assert_eq!(grouped.dimensions(), (100, 4 * 30 + GROUP_GAP));
/// assert_eq!(grouped.get_pixel(20, 60).0, [255; 3]);
/// assert_eq!(grouped.get_pixel(20, 60 + GROUP_GAP).0, [90; 3]);
/// ```
pub fn panel_grid_labels_beside(
    file_name: &str,
    panels: &[Panel],
    columns: usize,
    label_width: u32,
    rows_per_group: usize,
) -> Result<Figure, PlotError> {
    grid_of_panels(file_name, panels, columns, LabelPlace::Beside { label_width, rows_per_group })
}

/// Height in pixels of the white gap [`panel_grid_labels_beside`] leaves between groups of rows.
pub const GROUP_GAP: u32 = 12;

/// Where [`grid_of_panels`] draws a panel's label.
#[derive(Clone, Copy, PartialEq)]
enum LabelPlace {
    /// Onto the panel's top-left corner.
    On,
    /// On a strip below the panel, as tall as the longest label.
    Below,
    /// In a column of `label_width` pixels to the panel's right, with a gap after every
    /// `rows_per_group` rows (0: none).
    Beside { label_width: u32, rows_per_group: usize },
}

/// The grid of [`panel_grid`], labels on the panels, below or beside them.
fn grid_of_panels(file_name: &str, panels: &[Panel], columns: usize, place: LabelPlace) -> Result<Figure, PlotError> {
    init_fonts();
    let Some(first) = panels.first() else {
        return Err(PlotError::draw(file_name, DrawError::NoPanels));
    };
    let (width, height) = first.image.dimensions();
    if columns == 0 {
        return Err(PlotError::draw(file_name, DrawError::NoColumns));
    }
    if let Some(other) = panels.iter().find(|p| p.image.dimensions() != (width, height)) {
        let size = DrawError::PanelSize { expected: (width, height), found: other.image.dimensions() };
        return Err(PlotError::draw(file_name, size));
    }
    let (strip, side) = match place {
        LabelPlace::On => (0, 0),
        LabelPlace::Below => {
            let lines = panels.iter().map(|p| p.label.lines().count()).max().unwrap_or(0) as u32;
            (lines * (LABEL_PX + 3) + 8, 0)
        }
        LabelPlace::Beside { label_width, .. } => (0, label_width),
    };
    let (cell_width, cell_height) = (width + side, height + strip);
    let rows = panels.len().div_ceil(columns);
    let group = match place {
        LabelPlace::Beside { rows_per_group, .. } if rows_per_group > 0 => rows_per_group,
        _ => rows,
    };
    // Gaps before rows `group`, `2 group`, …: the grid's rows plus one gap per group boundary.
    let gaps_before = |row: usize| (row / group) as u32 * GROUP_GAP;
    let grid_width = cell_width * columns.min(panels.len()) as u32;
    let grid_height = cell_height * rows as u32 + gaps_before(rows - 1);
    let mut grid = RgbImage::new(grid_width, grid_height);
    let corner = |k: usize| {
        let row = k / columns;
        ((k % columns) as u32 * cell_width, row as u32 * cell_height + gaps_before(row))
    };
    for row in (group..rows).step_by(group) {
        let y = row as u32 * cell_height + gaps_before(row) - GROUP_GAP;
        grid.paste(&RgbImage::from_pixel(grid_width, GROUP_GAP, Rgb([255; 3])), 0, y);
    }
    for (k, panel) in panels.iter().enumerate() {
        let (x, y) = corner(k);
        grid.paste(&panel.image, x, y);
    }
    let mut rgb = grid.into_raw();
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (grid_width, grid_height)).into_drawing_area();
        for (k, panel) in panels.iter().enumerate() {
            let (x, y) = corner(k);
            let at = match place {
                LabelPlace::On => (x + 4, y + 4),
                LabelPlace::Below => (x + 4, y + height + 2),
                LabelPlace::Beside { label_width, .. } => {
                    let font = ("sans-serif", LABEL_PX).into_font().color(&WHITE);
                    for line in panel.label.lines() {
                        let (text_width, _) =
                            root.estimate_text_size(line, &font).map_err(|e| PlotError::draw(file_name, e))?;
                        if text_width + 8 > label_width {
                            let wide = DrawError::LabelTooWide {
                                line: line.to_owned(),
                                width: text_width,
                                column: label_width,
                            };
                            return Err(PlotError::draw(file_name, wide));
                        }
                    }
                    (x + width, y + 2)
                }
            };
            draw_label(&root, &panel.label, (at.0 as i32, at.1 as i32)).map_err(|e| PlotError::draw(file_name, e))?;
        }
        root.present().map_err(|e| PlotError::draw(file_name, e))?;
    }
    let grid = RgbImage::from_raw(grid_width, grid_height, rgb).expect("buffer has width*height*3 bytes");
    png_bytes(file_name, &grid)
}

/// The root-mean-square difference between two images of one size, over every channel of every
/// pixel, in display levels (0 … 255, the bytes a reader sees): what a comparison panel's label
/// states as the measured difference from its neighbour.
///
/// # Panics
/// If the images differ in size (compared panels share one).
///
/// # Examples
/// ```
/// use hw3_core::plot::{Rgb, RgbImage};
/// let a = RgbImage::from_pixel(4, 2, Rgb([10, 10, 10]));
/// let mut b = a.clone();
/// b.put_pixel(0, 0, Rgb([10, 10, 250])); // one channel of one pixel in 24 differs by 240
/// assert!((hw3_core::plot::rms_difference(&a, &b) - (240.0_f64.powi(2) / 24.0).sqrt()).abs() < 1e-12);
/// ```
#[must_use]
pub fn rms_difference(a: &RgbImage, b: &RgbImage) -> f64 {
    assert_eq!(a.dimensions(), b.dimensions(), "compared images share one size");
    let squares: f64 = a.as_raw().iter().zip(b.as_raw()).map(|(x, y)| (f64::from(*x) - f64::from(*y)).powi(2)).sum();
    (squares / a.as_raw().len().max(1) as f64).sqrt()
}

/// The label line that states [`rms_difference`] of a panel from the one it is compared with.
#[must_use]
pub fn difference_line(against: &str, a: &RgbImage, b: &RgbImage) -> String {
    format!("RMS difference from {against}: {:.1} / 255", rms_difference(a, b))
}

/// Draws a vertical colour bar on `root`: `colour(v)` for `v` from 0 (bottom) to 1 (top) in a
/// box of `size` (width, height) pixels whose top-left corner is `at`, with the labels `ticks`
/// (`(v, text)`) to its right in black (so place it over a light background).
///
/// # Errors
/// plotters' error as a [`DrawError`] ([`DrawError::Backend`] and the like: the `Err` of the
/// closures [`png_figure`] and [`svg_figure`] take).
///
/// # Examples
/// ```
/// let ramp = |v: f64| plotters::style::RGBColor((255.0 * v) as u8, 0, 0);
/// let figure = hw3_core::plot::png_figure("bar.png", (120, 100), |root| {
///     hw3_core::plot::color_bar(root, (10, 10), (12, 80), &ramp, &[(0.0, "0"), (1.0, "10 %")])
/// })
/// .unwrap();
/// let image = hw3_core::plot::decode_png(&figure.bytes).unwrap();
/// assert_eq!(image.get_pixel(15, 89).0, [0, 0, 0]);
/// assert!(image.get_pixel(15, 10).0[0] > 250);
/// ```
pub fn color_bar<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    at: (i32, i32),
    (width, height): (i32, i32),
    colour: &dyn Fn(f64) -> RGBColor,
    ticks: &[(f64, &str)],
) -> Result<(), DrawError> {
    init_fonts();
    let span = f64::from((height - 1).max(1));
    for row in 0..height {
        let v = 1.0 - f64::from(row) / span;
        let c = colour(v);
        for column in 0..width {
            root.draw_pixel((at.0 + column, at.1 + row), &c)?;
        }
    }
    root.draw(&Rectangle::new([(at.0 - 1, at.1 - 1), (at.0 + width, at.1 + height)], BLACK))?;
    for &(v, text) in ticks {
        let y = at.1 + ((1.0 - v) * span).round() as i32;
        let x = at.0 + width;
        root.draw(&PathElement::new(vec![(x, y), (x + 3, y)], BLACK))?;
        root.draw(&Text::new(text.to_string(), (x + 5, y - 6), ("sans-serif", 12)))?;
    }
    Ok(())
}

/// A colour-blind-safe palette (Okabe & Ito, 2008) for series that must stay distinguishable.
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(230, 159, 0),   // orange
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(240, 228, 66),  // yellow
    RGBColor(0, 0, 0),       // black
];

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(root: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>) -> Result<(), DrawError> {
        let mut chart = ChartBuilder::on(root)
            .caption("α √ test", ("sans-serif", 16))
            .margin(8)
            .x_label_area_size(24)
            .y_label_area_size(30)
            .build_cartesian_2d(0.0..1.0, 0.0..1.0)?;
        chart.configure_mesh().draw()?;
        chart.draw_series(LineSeries::new([(0.0, 0.0), (1.0, 1.0)], PALETTE[0]))?;
        Ok(())
    }

    #[test]
    fn svg_with_text_is_byte_identical_across_runs() {
        let a = svg_figure("t.svg", (200, 150), sample).unwrap();
        let b = svg_figure("t.svg", (200, 150), sample).unwrap();
        assert_eq!(a, b);
        let text = String::from_utf8(a.bytes).unwrap();
        assert!(text.contains("α √ test"), "caption text is laid out with the embedded font");
    }

    #[test]
    fn png_with_text_is_byte_identical_and_decodes() {
        let draw = |root: &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>| {
            root.draw(&Text::new("abc", (10, 10), ("sans-serif", 14))).map_err(DrawError::from)
        };
        let a = png_figure("t.png", (64, 32), draw).unwrap();
        let b = png_figure("t.png", (64, 32), draw).unwrap();
        assert_eq!(a, b);
        let decoded = decode_png(&a.bytes).unwrap();
        assert!(decoded.pixels().any(|p| p.0 != [255, 255, 255]), "text drew some pixels");
    }

    #[test]
    fn panel_grid_is_byte_identical_and_labels_every_panel() {
        let panel = |v| Panel { image: RgbImage::from_pixel(80, 60, Rgb([v; 3])), label: "a\nb".into() };
        let panels = [panel(255), panel(255), panel(255)];
        let a = panel_grid("g.png", &panels, 2).unwrap();
        assert_eq!(a, panel_grid("g.png", &panels, 2).unwrap());
        let grid = decode_png(&a.bytes).unwrap();
        assert_eq!(grid.dimensions(), (160, 120));
        for (x, y) in [(0, 0), (80, 0), (0, 60)] {
            let darkened = (x..x + 40).any(|i| (y..y + 30).any(|j| grid.get_pixel(i, j).0[0] < 200));
            assert!(darkened, "the label of the panel at ({x}, {y}) was drawn");
        }
        assert_eq!(grid.get_pixel(120, 90).0, [0, 0, 0], "the missing fourth panel stays black");
        let mixed = panel_grid("g.png", &[panel(1), Panel { image: RgbImage::new(2, 2), label: String::new() }], 2);
        assert!(matches!(
            mixed,
            Err(PlotError::Draw { source: DrawError::PanelSize { expected: (80, 60), found: (2, 2) }, .. })
        ));
        let message = mixed.unwrap_err().to_string();
        assert_eq!(message, "drawing g.png: panels must share one size and columns must be at least 1");
        assert!(matches!(panel_grid("g.png", &[], 2), Err(PlotError::Draw { source: DrawError::NoPanels, .. })));
    }
}
