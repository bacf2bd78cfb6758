//! Shared plotting core: an embedded font, deterministic SVG/PNG figures, the [`Figure`] type
//! every question module returns from its `figures()` function, one chart helper ([`Chart`]) and
//! one markdown-table writer ([`markdown_table`]).
//!
//! Figures must be byte-identical from run to run (they are committed under `docs/figures/` and
//! pinned by snapshots), so nothing here reads the clock, the locale or the system's fonts: text is
//! laid out with DejaVu Sans, compiled into the binary by the `dejavu` crate and registered with
//! plotters under the family name `"sans-serif"` (the name plotters' default labels ask for).

mod chart;
mod table;

pub use chart::{Axis, Chart, Dots, Legend, LegendMark, Note, Series, Stroke, TickFormat};
pub use table::markdown_table;

use plotters::prelude::*;
use plotters::style::FontStyle;
use std::io::Cursor;
use std::sync::Once;

/// A generated figure: the file name under `docs/figures/` and its bytes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Figure {
    /// File name with extension (`q2_roots.svg`); the extension decides the format.
    pub file_name: String,
    /// The encoded file (SVG text as UTF-8, or PNG bytes).
    pub bytes: Vec<u8>,
}

/// Why a figure could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// plotters reported a drawing error (its error types are generic, so only the text is kept).
    #[error("drawing {figure}: {message}")]
    Draw {
        /// The figure being drawn.
        figure: String,
        /// plotters' message.
        message: String,
    },
    /// The PNG encoder failed.
    #[error("encoding {figure}: {source}")]
    Encode {
        /// The figure being encoded.
        figure: String,
        /// The encoder's error.
        source: image::ImageError,
    },
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
/// [`PlotError::Draw`] when `draw` or plotters fails.
pub fn svg_figure<F>(file_name: &str, (width, height): (u32, u32), draw: F) -> Result<Figure, PlotError>
where
    F: FnOnce(&DrawingArea<SVGBackend<'_>, plotters::coord::Shift>) -> Result<(), String>,
{
    init_fonts();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| draw_error(file_name, e))?;
        draw(&root).map_err(|message| PlotError::Draw { figure: file_name.into(), message })?;
        root.present().map_err(|e| draw_error(file_name, e))?;
    }
    Ok(Figure { file_name: file_name.into(), bytes: svg.into_bytes() })
}

/// Draws a PNG figure of `width`×`height` pixels with `draw` (plotters' bitmap backend, then the
/// `image` crate's PNG encoder, which is deterministic for identical pixels).
///
/// # Errors
/// [`PlotError::Draw`] when drawing fails, [`PlotError::Encode`] when encoding does.
pub fn png_figure<F>(file_name: &str, (width, height): (u32, u32), draw: F) -> Result<Figure, PlotError>
where
    F: FnOnce(&DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>) -> Result<(), String>,
{
    init_fonts();
    let mut rgb = vec![0u8; width as usize * height as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| draw_error(file_name, e))?;
        draw(&root).map_err(|message| PlotError::Draw { figure: file_name.into(), message })?;
        root.present().map_err(|e| draw_error(file_name, e))?;
    }
    let image = image::RgbImage::from_raw(width, height, rgb).expect("buffer has width*height*3 bytes");
    png_bytes(file_name, &image)
}

/// Encodes an RGB image as a PNG [`Figure`] (used for renders as well as charts).
///
/// # Errors
/// [`PlotError::Encode`] when the encoder fails.
pub fn png_bytes(file_name: &str, image: &image::RgbImage) -> Result<Figure, PlotError> {
    let mut bytes = Vec::new();
    image
        .write_to(&mut Cursor::new(&mut bytes), image::ImageFormat::Png)
        .map_err(|source| PlotError::Encode { figure: file_name.into(), source })?;
    Ok(Figure { file_name: file_name.into(), bytes })
}

/// Turns any displayable plotters error into the `String` the drawing closures return.
pub fn err<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

fn draw_error<E: std::fmt::Display>(figure: &str, e: E) -> PlotError {
    PlotError::Draw { figure: figure.into(), message: e.to_string() }
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

    fn sample(root: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>) -> Result<(), String> {
        let mut chart = ChartBuilder::on(root)
            .caption("α √ test", ("sans-serif", 16))
            .margin(8)
            .x_label_area_size(24)
            .y_label_area_size(30)
            .build_cartesian_2d(0.0..1.0, 0.0..1.0)
            .map_err(err)?;
        chart.configure_mesh().draw().map_err(err)?;
        chart.draw_series(LineSeries::new([(0.0, 0.0), (1.0, 1.0)], PALETTE[0])).map_err(err)?;
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
            root.draw(&Text::new("abc", (10, 10), ("sans-serif", 14))).map_err(err)
        };
        let a = png_figure("t.png", (64, 32), draw).unwrap();
        let b = png_figure("t.png", (64, 32), draw).unwrap();
        assert_eq!(a, b);
        let decoded = image::load_from_memory(&a.bytes).unwrap().to_rgb8();
        assert!(decoded.pixels().any(|p| p.0 != [255, 255, 255]), "text drew some pixels");
    }
}
