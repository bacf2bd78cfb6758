//! Q5's radiosity and experiment figures: the radiosity Cornell box, the solvers' convergence,
//! the experiment scenes, the published Cornell box, and the measured and grammar tables.

use super::budget::Budget;
use super::cornell_published;
use super::effect_scenes::{self, GLOSSY_FLOOR, WHITE_FLOOR, lit_floor, mirror_room};
use super::error::ExperimentError;
use super::experiments::{cornell_system, measured_table, measured_table_markdown, reference_passes};
use super::grammar::grammar_table_markdown;
use super::radiosity::{Solver, relative_errors};
use crate::plot::{self, Axis, Chart, Figure, Legend, PALETTE, Panel, PlotError, Series};
use crate::render::integrator::Integrator;
use crate::render::{Settings, render};

/// The drawn figures: solver convergence (SVG), the published Cornell box's validation, the
/// measured table and the grammar tables (markdown), the tables at `budget`; the renders are
/// [`renders`].
///
/// # Errors
/// [`PlotError`] if drawing fails.
pub(super) fn figures(budget: &Budget) -> Result<Vec<Figure>, PlotError> {
    let draw_error =
        |figure: &str, e: &dyn std::fmt::Display| PlotError::Draw { figure: figure.into(), message: e.to_string() };
    let mut figures = Vec::new();
    let (_, small) = cornell_system(4, 1).map_err(|e| draw_error("q5_radiosity_convergence.svg", &e))?;
    let reference = small.solve(Solver::GaussSeidel, 200).pop().unwrap_or_default();
    let curves: Vec<(Solver, Vec<f64>)> =
        Solver::ALL.iter().map(|&s| (s, relative_errors(&small.solve(s, 20), &reference))).collect();
    let series = curves
        .iter()
        .enumerate()
        .map(|(k, (solver, errors))| {
            // Drawn only while the error is above the axis floor: past it (round-off, or exactly 0
            // once progressive shooting has converged) a clamped line would run along the floor.
            let points = errors
                .iter()
                .enumerate()
                .take_while(|(_, e)| **e >= ERROR_FLOOR)
                .map(|(i, &e)| (i as f64, e))
                .collect();
            Series::line(solver.name(), points, PALETTE[k % PALETTE.len()], 2)
        })
        .collect();
    let convergence = Chart {
        fill: true,
        series,
        legend: Some(Legend { position: None, font: 13, opacity: 0.8 }),
        ..Chart::new(
            "Radiosity solvers: error vs sweeps (176 patches)",
            Axis::linear(0.0, 20.0, "sweeps (Southwell: N shots)"),
            Axis { format: Some(plot::compact_tick), ..Axis::log(ERROR_FLOOR, 1.0, "max |B − B*| / max B*") },
        )
    };
    figures.push(convergence.svg("q5_radiosity_convergence.svg", (640, 400))?);
    let validation =
        cornell_published::validation_table(budget).map_err(|e| draw_error("q5_cornell_published.md", &e))?;
    figures.push(Figure { file_name: "q5_cornell_published.md".into(), bytes: validation.into_bytes() });
    let measured = measured_table(budget).map_err(|e| draw_error("q5_measured_table.md", &e))?;
    figures.push(Figure {
        file_name: "q5_measured_table.md".into(),
        bytes: measured_table_markdown(&measured).into_bytes(),
    });
    let grammar = grammar_table_markdown().map_err(|e| draw_error("q5_grammar_tables.md", &e))?;
    figures.push(Figure { file_name: "q5_grammar_tables.md".into(), bytes: grammar.into_bytes() });
    Ok(figures)
}

/// The bottom of the convergence chart's error axis; a solver's line stops where its error falls
/// below it.
const ERROR_FLOOR: f64 = 1e-12;

/// File name of the published Cornell box's radiosity / path-traced pair.
const PUBLISHED_PNG: &str = "q5_cornell_published.png";

/// File name of the experiment-scene montage.
const EFFECT_SCENES_PNG: &str = "q5_effect_scenes.png";

/// Samples per pixel of the path-traced renders of Q5's figures.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{PATH_SPP, experiments::REFERENCE_SPP};
/// assert!(PATH_SPP < REFERENCE_SPP);
/// ```
pub const PATH_SPP: u32 = Budget::PUBLISHED.path_spp;

/// Q5's renders (PNG, seeded: the same bytes on every run and thread count) at `budget`; at
/// [`Budget::PUBLISHED`], the committed ones: the radiosity Cornell box at 640×640 (the box is
/// square); the four open experiment scenes as a labelled 2 × 2 grid of 320×240 panels; the
/// published Cornell box by radiosity beside the path tracer, 320×320 each, labelled below the
/// panels (on them the labels would cover the ceiling light and the mirrored panel).
///
/// # Errors
/// [`PlotError`] if a scene cannot be built, rendered or labelled.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{Budget, renders};
/// let figures = renders(&Budget::TINY).unwrap();
/// let names: Vec<&str> = figures.iter().map(|f| f.file_name.as_str()).collect();
/// assert_eq!(names, ["q5_radiosity_cornell.png", "q5_effect_scenes.png", "q5_cornell_published.png"]);
/// // The radiosity box is square: 640 / 40 pixels a side, its label drawn on it.
/// let radiosity = image::load_from_memory(&figures[0].bytes).unwrap();
/// assert_eq!((radiosity.width(), radiosity.height()), (16, 16));
/// // Two panels across in the other two, their labels on strips below.
/// assert!(figures[1..].iter().all(|f| image::load_from_memory(&f.bytes).unwrap().width() == 16));
/// ```
pub fn renders(budget: &Budget) -> Result<Vec<Figure>, PlotError> {
    let draw_error =
        |figure: &str, e: &dyn std::fmt::Display| PlotError::Draw { figure: figure.into(), message: e.to_string() };
    let radiosity_png = "q5_radiosity_cornell.png";
    let (patches, samples) = budget.render_mesh;
    let (scene, system) = cornell_system(patches, samples).map_err(|e| draw_error(radiosity_png, &e))?;
    let solution = system.solve(Solver::GaussSeidel, 60).pop().unwrap_or_default();
    let (width, height) = budget.image_size((640, 640));
    let image = system.render(&scene, &solution, width, height).to_rgb8();
    let label = format!(
        "radiosity, {patches} × {patches} patches per quad\n{samples} × {samples} form-factor samples, Gauss–Seidel"
    );
    let mut figures = vec![plot::panel_grid(radiosity_png, &[Panel { image, label }], 1)?];
    figures.push(effect_scenes_figure(budget)?);
    let (size, _) = budget.image_size((320, 320));
    let (patches, spp) = (budget.side_by_side_patches, budget.path_spp);
    let both = cornell_published::side_by_side(size, patches, spp).map_err(|e| draw_error(PUBLISHED_PNG, &e))?;
    let half = |x| image::imageops::crop_imm(&both, x, 0, size, size).to_image();
    let (radiosity, path) = (half(0), half(size));
    let difference = plot::difference_line("radiosity", &path, &radiosity);
    let panels = [
        Panel { image: radiosity, label: format!("radiosity\n{patches} × {patches} patches per quad, interpolated") },
        Panel { image: path, label: format!("path tracing\n{spp} spp\n{difference}") },
    ];
    // Below the panels: on them the labels covered the ceiling light.
    figures.push(plot::panel_grid_labels_below(PUBLISHED_PNG, &panels, 2)?);
    Ok(figures)
}

/// The four open experiment scenes, path-traced (320 × 240 each and [`PATH_SPP`] samples per pixel
/// at the published `budget`, every bounce on, seed 1): the glossy floor's highlight, the white
/// floor's cosine falloff, the red panel in the mirror, the caustic under the glass ball, as a
/// labelled 2 × 2 grid.
fn effect_scenes_figure(budget: &Budget) -> Result<Figure, PlotError> {
    let render_error =
        |e: &dyn std::fmt::Display| PlotError::Draw { figure: EFFECT_SCENES_PNG.into(), message: e.to_string() };
    let (width, height) = budget.image_size((320, 240));
    let spp = budget.path_spp;
    let scenes = (|| -> Result<_, ExperimentError> {
        Ok([
            (
                lit_floor(GLOSSY_FLOOR, false)?.with_camera(effect_scenes::highlight_camera())?,
                "(a) highlight on a glossy floor",
            ),
            (lit_floor(WHITE_FLOOR, false)?, "direct light on a white floor"),
            (mirror_room()?, "the lit red panel in a mirror"),
            (lit_floor(WHITE_FLOOR, true)?, "caustic under a glass ball"),
        ])
    })()
    .map_err(|e| render_error(&e))?;
    let mut panels = Vec::new();
    for (scene, what) in &scenes {
        let settings = Settings {
            integrator: Integrator::PathTracer { max_depth: 12 },
            ..Settings::whitted(width, height, spp, reference_passes(scene))
        };
        let image = render(scene, &settings, &|_| {}).map_err(|e| render_error(&e))?.to_rgb8();
        panels.push(Panel { image, label: format!("{what}\npath tracing, {spp} spp") });
    }
    // Below the panels: on them a label covered the mirrored red panel's corner.
    plot::panel_grid_labels_below(EFFECT_SCENES_PNG, &panels, 2)
}
