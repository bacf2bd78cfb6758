//! Q5's radiosity and experiment figures: the radiosity Cornell box, the solvers' convergence,
//! the experiment scenes, the published Cornell box, and the measured and grammar tables.

use super::cornell_published;
use super::effect_scenes::{self, GLOSSY_FLOOR, WHITE_FLOOR, lit_floor, mirror_room};
use super::error::ExperimentError;
use super::experiments::{cornell_system, measured_table, measured_table_markdown, reference_passes};
use super::grammar::grammar_table_markdown;
use super::radiosity::{Solver, relative_errors};
use crate::plot::{self, Figure, PALETTE, PlotError, err};
use crate::render::camera::Camera;
use crate::render::integrator::Integrator;
use crate::render::{Settings, render};
use glam::DVec3;
use plotters::prelude::*;

/// Figures: the radiosity Cornell box (PNG), solver convergence (SVG), the experiment scenes and
/// the published Cornell box (PNG), its validation, the measured table and the grammar tables
/// (markdown).
///
/// # Errors
/// [`PlotError`] if drawing fails.
pub(super) fn figures() -> Result<Vec<Figure>, PlotError> {
    let draw_error =
        |figure: &str, e: &dyn std::fmt::Display| PlotError::Draw { figure: figure.into(), message: e.to_string() };
    let (scene, system) = cornell_system(8, 2).map_err(|e| draw_error("q5_radiosity_cornell.png", &e))?;
    let solution = system.solve(Solver::GaussSeidel, 60).pop().unwrap_or_default();
    let image = system.render(&scene, &solution, 200, 200);
    let mut figures = vec![plot::png_bytes("q5_radiosity_cornell.png", &image.to_rgb8())?];
    let (_, small) = cornell_system(4, 1).map_err(|e| draw_error("q5_radiosity_convergence.svg", &e))?;
    let reference = small.solve(Solver::GaussSeidel, 200).pop().unwrap_or_default();
    let curves: Vec<(Solver, Vec<f64>)> =
        Solver::ALL.iter().map(|&s| (s, relative_errors(&small.solve(s, 20), &reference))).collect();
    figures.push(plot::svg_figure("q5_radiosity_convergence.svg", (640, 400), |root| {
        root.fill(&WHITE_BG).map_err(err)?;
        let mut chart = ChartBuilder::on(root)
            .caption("Radiosity solvers: error vs sweeps (176 patches)", ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(0f64..20f64, (1e-12f64..1f64).log_scale())
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("sweeps (Southwell: N shots)")
            .y_desc("max |B − B*| / max B*")
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(err)?;
        for (k, (solver, errors)) in curves.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            let points: Vec<(f64, f64)> =
                errors.iter().enumerate().filter(|(_, e)| **e > 0.0).map(|(i, &e)| (i as f64, e.max(1e-12))).collect();
            chart
                .draw_series(LineSeries::new(points, color.stroke_width(2)))
                .map_err(err)?
                .label(solver.name())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], color.stroke_width(2)));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE_BG.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 13))
            .draw()
            .map_err(err)
    })?);
    figures.push(effect_scenes_figure().map_err(|e| draw_error(EFFECT_SCENES_PNG, &e))?);
    let published = cornell_published::side_by_side(200).map_err(|e| draw_error(PUBLISHED_PNG, &e))?;
    figures.push(plot::png_bytes(PUBLISHED_PNG, &published)?);
    let validation = cornell_published::validation_table().map_err(|e| draw_error("q5_cornell_published.md", &e))?;
    figures.push(Figure { file_name: "q5_cornell_published.md".into(), bytes: validation.into_bytes() });
    let measured = measured_table().map_err(|e| draw_error("q5_measured_table.md", &e))?;
    figures.push(Figure {
        file_name: "q5_measured_table.md".into(),
        bytes: measured_table_markdown(&measured).into_bytes(),
    });
    let grammar = grammar_table_markdown().map_err(|e| draw_error("q5_grammar_tables.md", &e))?;
    figures.push(Figure { file_name: "q5_grammar_tables.md".into(), bytes: grammar.into_bytes() });
    Ok(figures)
}

/// File name of the published Cornell box's radiosity / path-traced pair.
const PUBLISHED_PNG: &str = "q5_cornell_published.png";

/// File name of the experiment-scene montage.
const EFFECT_SCENES_PNG: &str = "q5_effect_scenes.png";

/// The four open experiment scenes side by side, path-traced (160 × 120, 32 samples per pixel,
/// every bounce on, seed 1: byte-identical run to run): the glossy floor's highlight, the white
/// floor's cosine falloff, the red panel in the mirror, the caustic under the glass ball.
fn effect_scenes_figure() -> Result<Figure, ExperimentError> {
    let (width, height) = (160, 120);
    let highlight_view =
        Camera::looking_at(effect_scenes::HIGHLIGHT_EYE, effect_scenes::HIGHLIGHT_POINT + DVec3::X * 0.6, 45.0);
    let scenes = [
        lit_floor(GLOSSY_FLOOR, false)?.with_camera(highlight_view)?,
        lit_floor(WHITE_FLOOR, false)?,
        mirror_room()?,
        lit_floor(WHITE_FLOOR, true)?,
    ];
    let mut montage = image::RgbImage::new(width * scenes.len() as u32, height);
    for (k, scene) in scenes.iter().enumerate() {
        let settings = Settings {
            integrator: Integrator::PathTracer { max_depth: 12 },
            ..Settings::whitted(width, height, 32, reference_passes(scene))
        };
        let image = render(scene, &settings, &|_| {}).map_err(|e| ExperimentError::Render(e.to_string()))?;
        image::imageops::replace(&mut montage, &image.to_rgb8(), i64::from(width) * k as i64, 0);
    }
    plot::png_bytes(EFFECT_SCENES_PNG, &montage).map_err(|e| ExperimentError::Render(e.to_string()))
}

/// Plotters' white (the crate's [`WHITE`](super::scenes::WHITE) is a reflectance).
const WHITE_BG: RGBColor = RGBColor(255, 255, 255);
