//! The renderer chapter's figures: the environment light, area-light single scattering, and the
//! caustic pass on and off.

use super::{Settings, catalogue, render};
use super::{analysis::analyze, passes::Pass};
use crate::plot::{self, Figure, PlotError};

/// Samples per pixel of the renderer chapter's images (Whitted tracing, 160×120).
const SPP: u32 = 16;

/// `render_probe_lit.png` (the `probe-lit` scene, lit only by Q4's courtyard map),
/// `render_fog_panel.png` (the `fog-panel` scene: a panel light's glow in fog), and
/// `render_caustic.png` / `render_caustic_off.png` (the `caustic` scene with its plan, and with
/// the caustic pass forced off), all rendered Whitted-style, seeded, so the bytes are the same
/// on every run.
///
/// # Errors
/// [`PlotError::Draw`] if a scene cannot be built (the vendored map is missing).
pub fn figures() -> Result<Vec<Figure>, PlotError> {
    let mut figures = Vec::new();
    let renders = [
        ("render_probe_lit.png", "probe-lit", None),
        ("render_fog_panel.png", "fog-panel", None),
        ("render_caustic.png", "caustic", None),
        ("render_caustic_off.png", "caustic", Some(Pass::Caustics)),
    ];
    for (file_name, name, switched_off) in renders {
        let scene = catalogue::by_name(name)
            .map_err(|e| PlotError::Draw { figure: file_name.into(), message: e.to_string() })?;
        let plan = analyze(&scene).plan;
        let plan = switched_off.map_or(plan, |pass| plan.with(pass, false));
        let image = render(&scene, &Settings::whitted(160, 120, SPP, plan), &|_| {})
            .expect("the figure settings are within limits");
        figures.push(plot::png_bytes(file_name, &image.to_rgb8())?);
    }
    Ok(figures)
}
