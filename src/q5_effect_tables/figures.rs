//! Q5's radiosity and experiment figures: the radiosity Cornell box, the solvers' convergence,
//! the experiment scenes, the published Cornell box, and the measured and grammar tables.

use super::budget::Budget;
use super::cornell_published;
use super::effect_scenes::{self, GLOSSY_FLOOR, WHITE_FLOOR, lit_floor, mirror_room_framed};
use super::error::ExperimentError;
use super::experiments::{cornell_system, measured_table, measured_table_markdown, reference_passes};
use super::grammar::grammar_table_markdown;
use super::radiosity::{Solver, relative_errors};
use crate::plot::{self, Axis, Chart, Figure, Legend, PALETTE, Panel, PlotError, Series};
use crate::render::integrator::Integrator;
use crate::render::scene::Scene;
use crate::render::{Settings, render};
use plotters::prelude::SeriesLabelPosition;

/// The drawn figures: solver convergence (SVG), the published Cornell box's validation, the
/// measured table, the grammar tables and the comparison with the student's answers (markdown),
/// the tables at `budget`, measured once each; the renders are [`renders`].
///
/// # Errors
/// [`PlotError`] if drawing fails.
pub(super) fn figures(budget: &Budget) -> Result<Vec<Figure>, PlotError> {
    let mut figures = Vec::new();
    let (_, small) = cornell_system(4, 1).map_err(|e| PlotError::data("q5_radiosity_convergence.svg", e))?;
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
        // Lower left: the lines start at the top left and fall to the right, so that corner is empty.
        legend: Some(Legend { position: Some(SeriesLabelPosition::LowerLeft), font: 13, opacity: 0.8 }),
        ..Chart::new(
            "Radiosity solvers: error vs sweeps (176 patches)",
            Axis::linear(0.0, 20.0, "sweeps (Southwell: N shots)"),
            Axis { format: Some(plot::compact_tick), ..Axis::log(ERROR_FLOOR, 1.0, "max |B − B*| / max B*") },
        )
    };
    figures.push(convergence.svg("q5_radiosity_convergence.svg", (640, 400))?);
    // The two measurements, side by side on the rayon pool: the validation's radiosity solves are
    // partly serial, and run alone they left one core idle for the last seconds of the drawn-figure
    // check in the test build. Errors are reported in the order the tables are written.
    let (validation, measured) = rayon::join(|| cornell_published::validation_table(budget), || measured_table(budget));
    let validation = validation.map_err(|e| PlotError::data("q5_cornell_published.md", e))?;
    figures.push(Figure { file_name: "q5_cornell_published.md".into(), bytes: validation.into_bytes() });
    let measured = measured.map_err(|e| PlotError::data("q5_measured_table.md", e))?;
    figures.push(Figure {
        file_name: "q5_measured_table.md".into(),
        bytes: measured_table_markdown(&measured).into_bytes(),
    });
    let grammar = grammar_table_markdown().map_err(|e| PlotError::data("q5_grammar_tables.md", e))?;
    figures.push(Figure { file_name: "q5_grammar_tables.md".into(), bytes: grammar.into_bytes() });
    let comparison =
        super::student_comparison_markdown(&measured).map_err(|e| PlotError::data("q5_seed_comparison.md", e))?;
    figures.push(Figure { file_name: "q5_seed_comparison.md".into(), bytes: comparison.into_bytes() });
    Ok(figures)
}

/// The bottom of the convergence chart's error axis; a solver's line stops where its error falls
/// below it.
const ERROR_FLOOR: f64 = 1e-12;

/// File name of the published Cornell box's radiosity / path-traced pair.
const PUBLISHED_PNG: &str = "q5_cornell_published.png";

/// File name of the experiment-scene montage.
const EFFECT_SCENES_PNG: &str = "q5_effect_scenes.png";

/// Samples per pixel of the montage's highlight, direct-light and mirror panels
/// (`q5_effect_scenes.png`): at 128 their noise is at most 1 display level of 255 (0.72, 0.44 and
/// 1.00 levels measured; 1.4, 0.9 and 2.0 at 32 spp).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{PATH_SPP, experiments::REFERENCE_SPP};
/// assert!(PATH_SPP < REFERENCE_SPP);
/// ```
pub const PATH_SPP: u32 = Budget::PUBLISHED.path_spp;

/// Samples per pixel of the published Cornell box's noisy path-traced panel (`q5_cornell_published.png`):
/// few enough that path tracing's noise is in plain view beside radiosity's smooth image.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{NOISY_SPP, PUBLISHED_SPP};
/// assert!(NOISY_SPP * 8 == PUBLISHED_SPP);
/// ```
pub const NOISY_SPP: u32 = Budget::PUBLISHED.noisy_spp;

/// Q5's renders (PNG, seeded: the same bytes on every run and thread count) at `budget`; at
/// [`Budget::PUBLISHED`], the committed ones: the radiosity Cornell box at 640×640 (the box is square); the four open experiment scenes as a labelled 2 × 2
/// grid of 320×240 panels; the published Cornell box by radiosity and by the path tracer at
/// [`NOISY_SPP`] and [`PUBLISHED_SPP`], 320×320 each; both grids labelled below the panels (on
/// them the labels would cover the ceiling light and the mirrored panel).
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
/// let radiosity = hw3::plot::decode_png(&figures[0].bytes).unwrap();
/// assert_eq!((radiosity.width(), radiosity.height()), (16, 16));
/// // The montage two panels across, the Cornell comparison three, labels on strips below.
/// let width = |f: &hw3::plot::Figure| hw3::plot::decode_png(&f.bytes).unwrap().width();
/// assert_eq!((width(&figures[1]), width(&figures[2])), (16, 24));
/// ```
pub fn renders(budget: &Budget) -> Result<Vec<Figure>, PlotError> {
    let radiosity_png = "q5_radiosity_cornell.png";
    let (patches, samples) = budget.render_mesh;
    let (scene, system) = cornell_system(patches, samples).map_err(|e| PlotError::data(radiosity_png, e))?;
    let solution = system.solve(Solver::GaussSeidel, 60).pop().unwrap_or_default();
    let (width, height) = budget.image_size((640, 640));
    let image = system.render(&scene, &solution, width, height).to_rgb8();
    let label = format!(
        "radiosity, {patches} × {patches} patches per quad\n{samples} × {samples} form-factor samples, Gauss–Seidel"
    );
    let mut figures = vec![plot::panel_grid(radiosity_png, &[Panel { image, label }], 1)?];
    figures.push(effect_scenes_figure(budget)?);
    figures.push(published_figure(budget)?);
    Ok(figures)
}

/// Side of each panel of [`PUBLISHED_PNG`].
const PUBLISHED_SIZE: u32 = 320;

/// The published Cornell box by radiosity, by the path tracer at [`NOISY_SPP`] (its noise in
/// plain view) and by the path tracer at [`PUBLISHED_SPP`] (close to converged), labelled below;
/// those counts, the patches and the size at [`Budget::PUBLISHED`].
fn published_figure(budget: &Budget) -> Result<Figure, PlotError> {
    let (size, _) = budget.image_size((PUBLISHED_SIZE, PUBLISHED_SIZE));
    let (patches, noisy_spp, converged_spp) = (budget.side_by_side_patches, budget.noisy_spp, budget.converged_spp);
    let draw_error = |e: ExperimentError| PlotError::data(PUBLISHED_PNG, e);
    let radiosity = cornell_published::radiosity_image(size, patches).map_err(draw_error)?;
    let noisy = cornell_published::path_traced_image(size, noisy_spp).map_err(draw_error)?;
    let (converged, converged_noise) =
        cornell_published::path_traced_with_noise(size, converged_spp).map_err(draw_error)?;
    let against = format!("{converged_spp} spp");
    let (radiosity_error, noisy_error) =
        (plot::difference_line(&against, &radiosity, &converged), plot::difference_line(&against, &noisy, &converged));
    let panels = [
        Panel {
            image: radiosity,
            label: format!("radiosity\n{patches} × {patches} patches per quad\n{radiosity_error}"),
        },
        Panel { image: noisy, label: format!("path tracing\n{noisy_spp} spp\n{noisy_error}") },
        Panel {
            image: converged,
            label: format!(
                "path tracing\n{converged_spp} spp, noise {converged_noise:.1} / 255\nthe reference of the other two"
            ),
        },
    ];
    // Below the panels: on them the labels covered the ceiling light.
    plot::panel_grid_labels_below(PUBLISHED_PNG, &panels, 3)
}

/// Samples per pixel of the published Cornell box's close-to-converged path-traced panel, the
/// reference the other two panels' errors are measured against: with Russian roulette its noise
/// is 2.2 display levels of 255 (6.2 at [`NOISY_SPP`]).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{PATH_SPP, PUBLISHED_SPP};
/// assert!(PUBLISHED_SPP > PATH_SPP);
/// ```
pub const PUBLISHED_SPP: u32 = Budget::PUBLISHED.converged_spp;

/// Samples per pixel of the montage's caustic panel (`q5_effect_scenes.png`). Its noise falls
/// slowly (8.0 display levels of 255 at 32 spp, 6.1 at 256, 4.0 at 1024): the caustic is found
/// only when a diffuse bounce happens to reach the light through the ball, rare bright samples
/// (fireflies) that more samples dim one by one. At 1024 the focus is plain; the speckles left in
/// and around the ball's shadow are light through the ball that few samples have found yet.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{CAUSTIC_SPP, PATH_SPP};
/// assert!(CAUSTIC_SPP > PATH_SPP);
/// ```
pub const CAUSTIC_SPP: u32 = Budget::PUBLISHED.caustic_spp;

/// The four open experiment scenes of the montage, each with what its panel shows and its
/// samples per pixel: the glossy floor's highlight, the white floor's falloff of direct light, the red
/// panel in the mirror (the framed picture variant, [`mirror_room_framed`]: without its frame
/// the mirror cannot be told from the black background), the caustic under the glass ball ([`PATH_SPP`] and [`CAUSTIC_SPP`] at
/// [`Budget::PUBLISHED`]).
fn montage_scenes(budget: &Budget) -> Result<[(Scene, &'static str, u32); 4], ExperimentError> {
    Ok([
        (
            lit_floor(GLOSSY_FLOOR, false)?.with_camera(effect_scenes::highlight_camera())?,
            "(a) highlight on a glossy floor",
            budget.path_spp,
        ),
        (lit_floor(WHITE_FLOOR, false)?, "(c) direct light on a white floor", budget.path_spp),
        (mirror_room_framed()?, "(d) mirror image: red panel, framed mirror", budget.path_spp),
        (lit_floor(WHITE_FLOOR, true)?, "(d) caustic under a glass ball", budget.caustic_spp),
    ])
}

/// Width and height of each montage panel at [`Budget::PUBLISHED`].
const MONTAGE_SIZE: (u32, u32) = (320, 240);

/// The path tracer's settings of the montage's panels: `(width, height)` ([`MONTAGE_SIZE`] in the
/// committed figure), every bounce on, 12 at most, seed 1.
fn montage_settings(scene: &Scene, (width, height): (u32, u32), spp: u32) -> Settings {
    Settings {
        integrator: Integrator::PathTracer { max_depth: 12 },
        ..Settings::whitted(width, height, spp, reference_passes(scene))
    }
}

/// The four open experiment scenes, path-traced ([`montage_scenes`], [`montage_settings`]), as a
/// labelled 2 × 2 grid.
fn effect_scenes_figure(budget: &Budget) -> Result<Figure, PlotError> {
    let size = budget.image_size(MONTAGE_SIZE);
    let mut panels = Vec::new();
    for (scene, what, spp) in &montage_scenes(budget).map_err(|e| PlotError::data(EFFECT_SCENES_PNG, e))? {
        let settings = montage_settings(scene, size, *spp);
        let image = render(scene, &settings, &|_| {}).map_err(|e| PlotError::data(EFFECT_SCENES_PNG, e))?.to_rgb8();
        panels.push(Panel { image, label: format!("{what}\npath tracing, {spp} spp") });
    }
    // Below the panels: on them a label covered the mirrored red panel's corner.
    plot::panel_grid_labels_below(EFFECT_SCENES_PNG, &panels, 2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::noise::noise_level;

    /// A picture's settings at a number of samples per pixel.
    type SettingsAt = dyn Fn(&Scene, u32) -> Settings;

    /// CPU seconds (user + system) this process has used, from `/proc/self/stat` (Linux).
    fn cpu_seconds() -> f64 {
        let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
        let fields: Vec<&str> = stat.rsplit_once(')').map_or("", |(_, rest)| rest).split_whitespace().collect();
        let tick = |k: usize| fields.get(k).and_then(|f| f.parse::<f64>().ok()).unwrap_or(f64::NAN);
        (tick(11) + tick(12)) / 100.0
    }

    /// The numbers the pictures' samples were chosen by (not a check: slow, run by hand with
    /// `RAYON_NUM_THREADS=1 cargo test --release --lib q5_picture_noise -- --ignored --nocapture`,
    /// `HW3_NOISE_SPP=32,128` for other counts, `HW3_NOISE_ONLY=Cornell` for the pictures whose
    /// name contains a word): each path-traced picture's noise ([`noise_level`]) at its figure's
    /// size and the CPU seconds of one render; the published box also without Russian roulette, and
    /// its radiosity panel's seconds.
    #[test]
    #[ignore = "slow: prints the pictures' noise for choosing their samples"]
    fn q5_picture_noise() {
        let spps: Vec<u32> = std::env::var("HW3_NOISE_SPP")
            .map_or_else(|_| vec![32, 128], |v| v.split(',').map(|s| s.parse().unwrap()).collect());
        let only = std::env::var("HW3_NOISE_ONLY").unwrap_or_default();
        let montage = |scene: &Scene, spp| montage_settings(scene, MONTAGE_SIZE, spp);
        let mut pictures: Vec<(String, Scene, Box<SettingsAt>)> = montage_scenes(&Budget::PUBLISHED)
            .unwrap()
            .into_iter()
            .map(|(scene, what, _)| (what.to_string(), scene, Box::new(montage) as Box<_>))
            .collect();
        let published = cornell_published::scene().unwrap();
        let settings = |scene: &Scene, spp| cornell_published::path_settings(scene, PUBLISHED_SIZE, spp);
        pictures.push(("published Cornell box, roulette".into(), published.clone(), Box::new(settings)));
        let without_roulette = |scene: &Scene, spp| Settings {
            integrator: Integrator::PathTracer { max_depth: 12 },
            ..cornell_published::path_settings(scene, PUBLISHED_SIZE, spp)
        };
        pictures.push(("published Cornell box, no roulette".into(), published, Box::new(without_roulette)));
        if "published Cornell box, radiosity".contains(&only) {
            let start = cpu_seconds();
            cornell_published::radiosity_image(PUBLISHED_SIZE, cornell_published::SIDE_BY_SIDE_PATCHES).unwrap();
            println!("published Cornell box, radiosity: {:6.2} CPU s", cpu_seconds() - start);
        }
        for (name, scene, settings) in pictures.iter().filter(|(name, ..)| name.contains(&only)) {
            for &spp in &spps {
                let start = cpu_seconds();
                let noise = noise_level(scene, &settings(scene, spp)).unwrap();
                let seconds = (cpu_seconds() - start) / 2.0;
                println!("{name:36} {spp:5} spp: noise {noise:6.2} levels, {seconds:6.2} CPU s per render");
            }
        }
    }

    /// The caption's claim about the committed figure: away from the edges radiosity and the
    /// 256-sample panel agree, the mean of each face (over a rectangle well inside it, in the
    /// figure's own display levels) within 1 level in every channel. Reads the committed PNG, which
    /// CI's release run regenerates and compares byte for byte.
    #[test]
    fn published_figure_faces_agree_between_radiosity_and_256_spp() {
        let bytes =
            std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/figures/q5_cornell_published.png")).unwrap();
        let figure = plot::decode_png(&bytes).unwrap();
        assert_eq!(figure.width(), 3 * PUBLISHED_SIZE, "three panels side by side");
        // (face, x, y, width, height) inside a panel: interiors of seven faces, clear of edges and
        // of the blocks' shadows.
        let faces = [
            ("back wall", 175, 80, 60, 45),
            ("left wall", 20, 100, 35, 100),
            ("right wall", 265, 100, 35, 100),
            ("ceiling", 100, 14, 110, 14),
            ("floor", 20, 287, 60, 18),
            ("tall block front", 110, 155, 40, 100),
            ("short block front", 172, 228, 55, 60),
        ];
        let mean = |panel: u32, (x, y, w, h): (u32, u32, u32, u32)| {
            let mut sum = [0.0f64; 3];
            for j in y..y + h {
                for i in x..x + w {
                    let p = figure.get_pixel(panel * PUBLISHED_SIZE + i, j).0;
                    (0..3).for_each(|c| sum[c] += f64::from(p[c]));
                }
            }
            sum.map(|v| v / f64::from(w * h))
        };
        for (face, x, y, w, h) in faces {
            let (radiosity, converged) = (mean(0, (x, y, w, h)), mean(2, (x, y, w, h)));
            for c in 0..3 {
                assert!(converged[c] > 5.0, "{face}: the rectangle lies on a lit face");
                let gap = (radiosity[c] - converged[c]).abs();
                assert!(gap < 1.0, "{face}, channel {c}: radiosity {} against {} levels", radiosity[c], converged[c]);
            }
        }
    }
}
