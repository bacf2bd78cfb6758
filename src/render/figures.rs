//! The renderer chapter's figures: the environment light and area-light single scattering.

use super::analysis::analyze;
use super::{Settings, render, scenes};
use crate::plot::{self, Figure, PlotError};

/// Samples per pixel of the renderer chapter's images (Whitted tracing, 160×120).
const SPP: u32 = 16;

/// `render_probe_lit.png` (the `probe-lit` scene, lit only by Q4's courtyard map) and
/// `render_fog_panel.png` (the `fog-panel` scene: a panel light's glow in fog), both rendered
/// Whitted-style with their own pass plan, seeded, so the bytes are the same on every run.
///
/// # Errors
/// [`PlotError::Draw`] if a scene cannot be built (the vendored map is missing).
pub fn figures() -> Result<Vec<Figure>, PlotError> {
    let mut figures = Vec::new();
    for (file_name, name) in [("render_probe_lit.png", "probe-lit"), ("render_fog_panel.png", "fog-panel")] {
        let scene =
            scenes::by_name(name).map_err(|e| PlotError::Draw { figure: file_name.into(), message: e.to_string() })?;
        let settings = Settings::whitted(160, 120, SPP, analyze(&scene).plan);
        let image = render(&scene, &settings, &|_| {}).expect("the figure settings are within limits");
        figures.push(plot::png_bytes(file_name, &image.to_rgb8())?);
    }
    Ok(figures)
}
