//! The renderer chapter's figures: the environment light, area-light single scattering, and the
//! caustic pass on and off.

use super::{Settings, catalogue, render};
use super::{analysis::analyze, passes::Pass};
use hw3_core::plot::{self, Figure, FigureJob, Panel, PlotError};

/// Samples per pixel of each of the renderer chapter's images (Whitted tracing), chosen by their
/// measured noise ([`super::noise`], display levels at 100 % zoom): the probe-lit spheres gather
/// the map's light from 8 samples per hit and show 7.7 levels of grain at 16 spp, 4.5 at 48; the
/// caustic's area light and photon gather 3.4 at 16, 2.0 at 48; the fog panel's glow 1.4 at 16.
///
/// # Examples
/// ```
/// use hw3_render::render::figures::SPP;
/// assert_eq!(SPP.iter().map(|(name, _)| *name).collect::<Vec<_>>(), ["probe-lit", "fog-panel", "caustic"]);
/// ```
pub const SPP: [(&str, u32); 3] = [("probe-lit", 48), ("fog-panel", 16), ("caustic", 48)];

/// The samples per pixel of the built-in scene `name` in its figure ([`SPP`]).
fn spp_of(name: &str) -> u32 {
    SPP.iter().find(|(scene, _)| *scene == name).map_or(16, |&(_, spp)| spp)
}

/// Renders the built-in scene `name` (Whitted, its plan with `switched_off` forced off) at
/// `width`×`height`.
fn render_scene(
    file_name: &str,
    name: &str,
    switched_off: Option<Pass>,
    (width, height): (u32, u32),
) -> Result<hw3_core::plot::RgbImage, PlotError> {
    let scene = catalogue::by_name(name).map_err(|e| PlotError::data(file_name, e))?;
    let plan = analyze(&scene).plan;
    let plan = switched_off.map_or(plan, |pass| plan.with(pass, false));
    let image = render(&scene, &Settings::whitted(width, height, spp_of(name), plan), &|_| {})
        .expect("the figure settings are within limits");
    Ok(image.to_rgb8())
}

/// `render_probe_lit.png` (the `probe-lit` scene, lit only by Q4's courtyard map) and
/// `render_fog_panel.png` (the `fog-panel` scene: a panel light's glow in fog), 640×480 each,
/// and `render_caustic.png` (the `caustic` scene with its plan beside the same render with the
/// caustic pass forced off, 320×240 per panel, labelled below the panels), all rendered Whitted-style with
/// their [`SPP`] samples per pixel and seed 1, so the bytes are the same on every run and thread count.
/// The [`jobs`] run in parallel.
///
/// # Errors
/// [`PlotError::Data`] if a scene cannot be built (the vendored map is missing), and the
/// [`PlotError`] of [`plot::panel_grid`] if a figure cannot be drawn.
pub fn figures() -> Result<Vec<Figure>, PlotError> {
    plot::run_jobs(&jobs())
}

/// A single labelled 640×480 render of the built-in scene `name`.
fn single(file_name: &str, name: &str, label: &str) -> Result<Vec<Figure>, PlotError> {
    let image = render_scene(file_name, name, None, (640, 480))?;
    let label = format!("{label}\nWhitted, {} spp", spp_of(name));
    Ok(vec![plot::panel_grid(file_name, &[Panel { image, label }], 1)?])
}

/// The renderer chapter's figures as independent jobs, one per figure (see [`figures`]).
///
/// # Examples
/// ```
/// let jobs = hw3_render::render::figures::jobs();
/// assert!(jobs.iter().all(|job| job.rendered) && jobs.len() == 3);
/// ```
#[must_use]
pub fn jobs() -> Vec<FigureJob> {
    vec![
        FigureJob::rendered("render probe-lit", || {
            single("render_probe_lit.png", "probe-lit", "lit by the courtyard map only")
        }),
        FigureJob::rendered("render fog-panel", || {
            single("render_fog_panel.png", "fog-panel", "panel light in fog, σ_s = 0.15")
        }),
        FigureJob::rendered("render caustic pair", || {
            let caustic = "render_caustic.png";
            let on = render_scene(caustic, "caustic", None, (320, 240))?;
            let off = render_scene(caustic, "caustic", Some(Pass::Caustics), (320, 240))?;
            let difference = plot::difference_line("left", &off, &on);
            let spp = spp_of("caustic");
            let panels = [
                Panel { image: on, label: format!("the plan: caustic pass on\nWhitted + caustic map, {spp} spp") },
                Panel { image: off, label: format!("caustic pass forced off\nWhitted, {spp} spp\n{difference}") },
            ];
            // Labels below the panels: on the right panel the three-line label covered the ball.
            Ok(vec![plot::panel_grid_labels_below(caustic, &panels, 2)?])
        }),
    ]
}
