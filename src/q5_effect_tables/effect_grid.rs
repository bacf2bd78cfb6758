//! The measured table as pictures: each effect's scene rendered by every method of the table,
//! two rows of two panels per effect, each panel labelled beside it with the method, its cost and
//! the fraction of the path-traced effect it captured in [`measured_table`].

use super::budget::Budget;
use super::effect_scenes::{GLOSSY_FLOOR, WHITE_FLOOR, highlight_camera, lit_floor, mirror_room_framed};
use super::error::ExperimentError;
use super::experiments::{
    Measured, MeasuredCell, NEIGHBOURS, PHOTON_SEED, SPECULAR_DEPTH, measured_table, photon_eye, table_methods,
};
use super::radiosity::{Mesh, Solver, System};
use crate::plot::{self, Figure, Panel, PlotError};
use crate::render::analysis::analyze;
use crate::render::catalogue::{CornellContents, cornell_box};
use crate::render::integrator::Integrator;
use crate::render::passes::{Pass, Passes};
use crate::render::photon::trace_photons;
use crate::render::scene::{Material, Scene};
use crate::render::{Image, Settings, render, render_with};

/// File name of the grid.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_grid::GRID_PNG;
/// assert!(GRID_PNG.starts_with("q5_") && GRID_PNG.ends_with(".png"));
/// ```
pub const GRID_PNG: &str = "q5_effect_grid.png";

/// Size of one panel of the grid, in pixels, at the published budget ([`Budget::image_size`]
/// divides it).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_grid::{COLUMNS, LABEL_WIDTH, PANEL_SIZE};
/// // Two panels and their label columns fill the notes' 936-pixel text column, so they are shown
/// // at full size (the labels' 15-pixel text is 15 pixels on screen); 4 : 3 like the other renders.
/// assert!((PANEL_SIZE.0 + LABEL_WIDTH) * COLUMNS as u32 <= 936 && PANEL_SIZE.0 * 3 == PANEL_SIZE.1 * 4);
/// assert!(PANEL_SIZE.0 >= 320, "a compared panel at least 320 × 240");
/// ```
pub const PANEL_SIZE: (u32, u32) = (320, 240);

/// Width in pixels of the label column to the right of each panel (the longest line, "(b) colour
/// bleeding", is about 140 pixels of 15-pixel text).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::effect_grid::{COLUMNS, LABEL_WIDTH, PANEL_SIZE};
/// assert_eq!((PANEL_SIZE.0 + LABEL_WIDTH) * COLUMNS as u32, 936);
/// ```
pub const LABEL_WIDTH: u32 = 148;

/// Panels per row of the grid: each effect's four methods on two rows of two (radiosity and the
/// two-pass method above, Whitted ray tracing and photon mapping below).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{effect_grid::COLUMNS, experiments::TABLE_METHODS};
/// assert_eq!(TABLE_METHODS.len() % COLUMNS, 0, "each effect's methods fill whole rows");
/// ```
pub const COLUMNS: usize = 2;

/// Rows of the grid per effect: its four methods on two rows of [`COLUMNS`]; the grid leaves a
/// white gap of [`plot::GROUP_GAP`] pixels after each effect's rows.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{effect_grid::{COLUMNS, ROWS_PER_EFFECT}, experiments::TABLE_METHODS};
/// assert_eq!(ROWS_PER_EFFECT * COLUMNS, TABLE_METHODS.len());
/// ```
pub const ROWS_PER_EFFECT: usize = 2;

/// A row of the grid: the effect's id (a row of [`EXPERIMENTS`]), its title, and the exposure its
/// panels share (radiance is multiplied by it before the sRGB curve clips at 1).
///
/// [`EXPERIMENTS`]: super::experiments::EXPERIMENTS
struct Row {
    effect: &'static str,
    title: &'static str,
    exposure: f64,
}

/// The rows in table order. Colour bleeding and ambient glow are one scene (the red-walled box,
/// rendered once); the glow row shows it 4 times brighter, since the ceiling away from the light
/// receives only interreflected light.
const ROWS: [Row; 6] = [
    Row { effect: "a", title: "(a) highlight", exposure: 1.0 },
    Row { effect: "b", title: "(b) colour bleeding", exposure: 1.0 },
    Row { effect: "c", title: "(c) direct shading", exposure: 1.0 },
    Row { effect: "d_mirror", title: "(d) mirror image", exposure: 1.0 },
    Row { effect: "d_caustic", title: "(d) caustic", exposure: 1.0 },
    Row { effect: "e", title: "(e) ambient glow", exposure: 4.0 },
];

/// The scene a row shows: the one whose probes measure the effect (for the highlight, seen from
/// the probes' eye), except the mirror's, which is its framed picture variant
/// ([`mirror_room_framed`]) so that the mirror shows where a method sees it black.
fn row_scene(effect: &str) -> Result<Scene, ExperimentError> {
    Ok(match effect {
        "a" => lit_floor(GLOSSY_FLOOR, false)?.with_camera(highlight_camera())?,
        "b" | "e" => cornell_box(true, CornellContents::Block)?,
        "c" => lit_floor(WHITE_FLOOR, false)?,
        "d_mirror" => mirror_room_framed()?,
        "d_caustic" => lit_floor(WHITE_FLOOR, true)?,
        _ => return Err(ExperimentError::UnknownId("a grid row")),
    })
}

/// Whether `scene` has a mirror or glass object.
fn has_specular(scene: &Scene) -> bool {
    scene.objects().iter().any(|o| matches!(o.material, Material::Mirror { .. } | Material::Glass { .. }))
}

/// One scene rendered by every method of [`table_methods`] at `budget`, with each
/// method's cost as text.
fn render_methods(scene: &Scene, budget: &Budget) -> Result<Vec<(Image, String)>, ExperimentError> {
    let (width, height) = budget.image_size(PANEL_SIZE);
    let maps = trace_photons(scene, budget.photons, PHOTON_SEED)?;
    let mut images = Vec::new();
    let mut two_pass = None;
    for method in table_methods(budget) {
        images.push(match method {
            Measured::Radiosity { subdivisions, samples } => {
                let system = System::new(scene, Mesh::new(scene, subdivisions)?, samples)?;
                let solution = system.solve(Solver::GaussSeidel, 60).pop().unwrap_or_default();
                let cost = format!("{} patches", system.mesh.patches.len());
                (system.render(scene, &solution, width, height), cost)
            }
            Measured::Whitted => {
                let integrator = Integrator::Whitted { max_depth: SPECULAR_DEPTH };
                // The table's Whitted reads no caustic map: the renderer's caustic pass is off.
                let passes = integrator.restrict(analyze(scene).plan).with(Pass::Caustics, false);
                let spp = budget.light_samples;
                let settings = Settings { integrator, ..Settings::whitted(width, height, spp, passes) };
                (render(scene, &settings, &|_| {})?, format!("{spp} spp"))
            }
            // Without a mirror or glass, and so with an empty caustic map, photon mapping traces
            // exactly the two-pass method's rays and estimates (the caustic map adds nothing, bit
            // for bit): its image is the two-pass one, not rendered again.
            Measured::PhotonMapping if maps.caustic.is_empty() && !has_specular(scene) => {
                two_pass.clone().ok_or(ExperimentError::UnknownId("two_pass"))?
            }
            Measured::TwoPass | Measured::PhotonMapping => {
                let caustics = method == Measured::PhotonMapping;
                let (tracer, integrator) = photon_eye(scene, &maps, caustics, budget.light_samples)?;
                let settings = Settings { integrator, ..Settings::whitted(width, height, 1, Passes::default()) };
                let cost = format!("{} photons,\nk = {NEIGHBOURS}", power_of_ten(budget.photons));
                let rendered = (render_with(&tracer, &settings, &|_| {})?, cost);
                if method == Measured::TwoPass {
                    two_pass = Some(rendered.clone());
                }
                rendered
            }
            Measured::PathTracing => return Err(ExperimentError::UnknownId("path tracing is the reference")),
        });
    }
    Ok(images)
}

/// The short name of a method in a label.
fn method_name(method: Measured) -> &'static str {
    match method {
        Measured::Radiosity { .. } => "radiosity",
        Measured::TwoPass => "two-pass",
        Measured::Whitted => "Whitted",
        Measured::PhotonMapping => "photon mapping",
        Measured::PathTracing => "path tracing",
    }
}

/// `n` as `m·10ᵉ` (`n` a multiple of a power of ten with one significant digit, as the photon
/// counts are; otherwise the digits).
fn power_of_ten(n: usize) -> String {
    const SUPERSCRIPTS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let digits = n.to_string();
    let zeros = digits.len() - digits.trim_end_matches('0').len();
    if digits.len() - zeros != 1 || zeros < 2 {
        return digits;
    }
    let exponent: String =
        zeros.to_string().chars().filter_map(|c| c.to_digit(10)).map(|d| SUPERSCRIPTS[d as usize]).collect();
    format!("{}·10{exponent}", &digits[..1])
}

/// The label of one panel, short lines that fit [`LABEL_WIDTH`]: the effect, the method, its cost,
/// and the measured cell (the fraction captured and the table's verdict).
fn label(row: &Row, method: Measured, cost: &str, cell: &MeasuredCell) -> String {
    format!(
        "{}\n{}\n{cost}\ncaptures {:.3}\nverdict: {}",
        row.title,
        method_name(method),
        cell.fraction,
        cell.verdict.text()
    )
}

/// The grid figure ([`GRID_PNG`]): for each effect of [`EXPERIMENTS`], its four [`PANEL_SIZE`]
/// panels (the methods of [`table_methods`]) on two rows of [`COLUMNS`], each labelled to its right
/// with the cell of [`measured_table`] at the same `budget`, the same exposure across an effect's
/// panels, each image rendered once (the bleeding and glow rows share theirs).
/// [`Budget::PUBLISHED`] draws the committed figure (the renders at 320 × 240, which CI's release
/// run compares with it).
///
/// # Errors
/// [`PlotError::Data`] with the [`ExperimentError`] of a scene, a render or the measured table
/// that fails (or of a cell the table lacks), and the [`PlotError`] of the panel grid.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{Budget, effect_grid::{COLUMNS, GRID_PNG, LABEL_WIDTH, PANEL_SIZE, figure}};
/// let grid = figure(&Budget::TINY).unwrap();
/// assert_eq!(grid.file_name, GRID_PNG);
/// // Two methods across, two rows per effect, six effects down; every panel a fortieth of the
/// // published one, its label in a column beside it.
/// let (width, height) = Budget::TINY.image_size(PANEL_SIZE);
/// let png = hw3::plot::decode_png(&grid.bytes).unwrap();
/// // Five white gaps of GROUP_GAP pixels between the six effects.
/// assert_eq!(png.dimensions(), (COLUMNS as u32 * (width + LABEL_WIDTH), 12 * height + 5 * hw3::plot::GROUP_GAP));
/// ```
///
/// [`EXPERIMENTS`]: super::experiments::EXPERIMENTS
pub fn figure(budget: &Budget) -> Result<Figure, PlotError> {
    let draw_error = |e: ExperimentError| PlotError::data(GRID_PNG, e);
    let cells = measured_table(budget).map_err(draw_error)?;
    let mut rendered: Vec<(&str, Vec<(Image, String)>)> = Vec::new();
    let mut panels = Vec::new();
    for row in &ROWS {
        let shared = if row.effect == "e" { "b" } else { row.effect };
        if !rendered.iter().any(|(id, _)| *id == shared) {
            let scene = row_scene(shared).map_err(draw_error)?;
            rendered.push((shared, render_methods(&scene, budget).map_err(draw_error)?));
        }
        let images = &rendered.iter().find(|(id, _)| *id == shared).expect("rendered above").1;
        for (method, (image, cost)) in table_methods(budget).iter().zip(images) {
            let cell =
                cells.iter().find(|c| c.effect == row.effect && c.algorithm == method.id()).ok_or_else(|| {
                    draw_error(ExperimentError::MissingCell { effect: row.effect, algorithm: method.id() })
                })?;
            let exposed = Image { pixels: image.pixels.iter().map(|&p| p * row.exposure).collect(), ..image.clone() };
            panels.push(Panel { image: exposed.to_rgb8(), label: label(row, *method, cost, cell) });
        }
    }
    // Beside the panels: on them the labels covered the box's ceiling light and the mirrored
    // panel's top edge; below them, twelve strips made a tall figure taller. A gap after each
    // effect's two rows: without it one effect's panels ran into the next's.
    plot::panel_grid_labels_beside(GRID_PNG, &panels, COLUMNS, LABEL_WIDTH, ROWS_PER_EFFECT)
}

#[cfg(test)]
mod tests {
    use super::super::effect_scenes::mirror_room;
    use super::super::experiments::EXPERIMENTS;
    use super::*;

    /// The reuse in [`render_methods`] is exact: in a scene with nothing specular, photon
    /// mapping's eye pass renders the two-pass image bit for bit (a small photon pass here).
    #[test]
    fn photon_mapping_is_the_two_pass_image_where_nothing_is_specular() {
        let scene = cornell_box(true, CornellContents::Block).unwrap();
        assert!(!has_specular(&scene));
        let maps = trace_photons(&scene, 4_000, PHOTON_SEED).unwrap();
        assert!(maps.caustic.is_empty() && !maps.indirect.is_empty());
        let image = |caustics| {
            let (tracer, integrator) = photon_eye(&scene, &maps, caustics, Budget::PUBLISHED.light_samples).unwrap();
            let settings = Settings { integrator, ..Settings::whitted(24, 18, 1, Passes::default()) };
            render_with(&tracer, &settings, &|_| {}).unwrap()
        };
        assert_eq!(image(true), image(false));
        assert!(has_specular(&lit_floor(WHITE_FLOOR, true).unwrap()) && has_specular(&mirror_room().unwrap()));
    }

    #[test]
    fn labels_name_the_cost_and_the_measured_cell() {
        assert_eq!(
            (power_of_ten(200_000), power_of_ten(250_000), power_of_ten(10)),
            ("2·10⁵".into(), "250000".into(), "10".into())
        );
        let cell = MeasuredCell {
            effect: "d_caustic",
            algorithm: "photon_mapping",
            value: 57.5,
            reference: 57.6,
            fraction: 57.5 / 57.6,
            verdict: super::super::experiments::Measurement::Yes,
            grammar: super::super::Verdict::Yes,
            student: super::super::StudentAnswer::NotAsked,
        };
        let text = label(&ROWS[4], Measured::PhotonMapping, "2·10⁵ photons,\nk = 100", &cell);
        assert_eq!(text, "(d) caustic\nphoton mapping\n2·10⁵ photons,\nk = 100\ncaptures 0.998\nverdict: Yes");
        for (row, (id, _)) in ROWS.iter().zip(EXPERIMENTS) {
            assert_eq!(row.effect, id, "one row per experiment, in table order");
        }
    }
}
