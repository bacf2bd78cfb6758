//! Experiments that decide table cells by measurement: each effect gets a scene built to show it
//! and a number with a threshold, measured for every method against the path-traced reference.

use super::radiosity::{Mesh, RadiosityError, Solver, System, relative_errors};
use super::{EFFECTS, LightKind, METHODS, Verdict, decide};
use crate::geometry::{InputError, Ray};
use crate::plot::{self, Figure, PALETTE, PlotError, err};
use crate::render::analysis::analyze;
use crate::render::integrator::{Integrator, Sampler, Tracer};
use crate::render::photon::{PhotonMap, trace_photons};
use crate::render::scene::{Camera, Material, Object, Scene};
use glam::DVec3;
use plotters::prelude::*;
use serde::Serialize;

/// Reflectances of the Cornell box walls (RGB stand-ins for the measured spectra, as in Tungsten).
pub const WHITE: DVec3 = DVec3::new(0.725, 0.71, 0.68);
/// Red wall.
pub const RED: DVec3 = DVec3::new(0.63, 0.065, 0.05);
/// Green wall.
pub const GREEN: DVec3 = DVec3::new(0.14, 0.45, 0.091);
/// Radiance of the ceiling light.
pub const LIGHT_RADIANCE: f64 = 12.0;

/// Radiosity mesh used by the measured table: patches per quad edge and form-factor samples per
/// patch edge.
pub const TABLE_MESH: (usize, usize) = (6, 2);
/// Path-traced reference: samples per measurement point.
pub const REFERENCE_SPP: u32 = 1024;
/// A cell is Yes when the method captures at least this fraction of the reference's effect.
pub const YES_FRACTION: f64 = 0.8;
/// A cell is No when it captures at most this fraction.
pub const NO_FRACTION: f64 = 0.2;

/// The six inward-facing walls of the box `[−1, 1]³`, floor, ceiling, back, left, right, front.
fn walls(albedos: [DVec3; 6]) -> Vec<Object> {
    let (x, y, z) = (DVec3::X * 2.0, DVec3::Y * 2.0, DVec3::Z * 2.0);
    let low = DVec3::splat(-1.0);
    let geometry = [
        (low, z, x),
        (DVec3::new(-1.0, 1.0, -1.0), x, z),
        (low, x, y),
        (low, y, z),
        (DVec3::new(1.0, -1.0, -1.0), z, y),
        (DVec3::new(-1.0, -1.0, 1.0), y, x),
    ];
    geometry
        .iter()
        .zip(albedos)
        .map(|(&(corner, u, v), albedo)| Object::quad(corner, u, v, Material::Diffuse { albedo }))
        .collect()
}

/// A closed box `[−1, 1]³` with every wall of reflectance `albedo`, camera inside (the furnace).
///
/// # Errors
/// [`InputError`] for an albedo outside `[0, 1]`.
pub fn closed_box(albedo: DVec3) -> Result<Scene, InputError> {
    let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 0.9), DVec3::ZERO, 60.0);
    Scene::new(camera, walls([albedo; 6]), vec![], None, DVec3::ZERO)
}

/// A Cornell-like box `[−1, 1]³`, open at the front (z = 1): white floor, ceiling and back, green
/// right wall, a left wall that is red (`red_left`) or white, a 0.5 × 0.5 light under the ceiling
/// facing down, and a white block on the floor. The ceiling is lit only indirectly (the light faces
/// away from it): the ambient-glow region.
///
/// # Errors
/// Never for the built-in numbers.
pub fn cornell_box(red_left: bool) -> Result<Scene, InputError> {
    let left = if red_left { RED } else { WHITE };
    let mut objects = walls([WHITE, WHITE, WHITE, left, GREEN, WHITE]);
    objects.pop(); // open front: the camera looks in
    objects.push(Object::quad(
        DVec3::new(-0.25, 0.99, -0.25),
        DVec3::X * 0.5,
        DVec3::Z * 0.5,
        Material::Emitter { radiance: DVec3::splat(LIGHT_RADIANCE) },
    ));
    let (x0, x1, y0, y1, z0, z1) = (0.1, 0.7, -1.0, -0.4, -0.3, 0.3);
    let (w, h) = (DVec3::X * (x1 - x0), DVec3::Y * (y1 - y0));
    let d = DVec3::Z * (z1 - z0);
    let white = Material::Diffuse { albedo: WHITE };
    for (corner, u, v) in [
        (DVec3::new(x0, y1, z0), d, w),
        (DVec3::new(x0, y0, z1), w, h),
        (DVec3::new(x0, y0, z0), h, w),
        (DVec3::new(x0, y0, z0), d, h),
        (DVec3::new(x1, y0, z0), h, d),
    ] {
        objects.push(Object::quad(corner, u, v, white));
    }
    let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 3.4), DVec3::ZERO, 40.0);
    Scene::new(camera, objects, vec![], None, DVec3::ZERO)
}

/// Measurement points with their surface normals.
fn region(points: impl Iterator<Item = DVec3>, normal: DVec3) -> Vec<(DVec3, DVec3)> {
    points.map(|p| (p, normal)).collect()
}

/// The floor strip beside the left wall (x ∈ [−0.95, −0.65]): where red bleeds.
fn bleeding_region() -> Vec<(DVec3, DVec3)> {
    region((0..16).map(|k| DVec3::new(-0.95 + 0.1 * (k % 4) as f64, -1.0, -0.75 + 0.1 * (k / 4) as f64)), DVec3::Y)
}

/// Ceiling points away from the light: no light sees them directly.
fn glow_region() -> Vec<(DVec3, DVec3)> {
    region((0..16).map(|k| DVec3::new(-0.9 + 0.1 * (k % 4) as f64, 1.0, 0.5 + 0.1 * (k / 4) as f64)), -DVec3::Y)
}

/// A method that the experiments run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measured {
    /// Radiosity with `subdivisions²` patches per quad and `samples²` form-factor samples per patch.
    Radiosity {
        /// Patches per quad edge.
        subdivisions: usize,
        /// Form-factor samples per patch edge.
        samples: usize,
    },
    /// The renderer's Whitted tracer (16 samples per point).
    Whitted,
    /// The renderer's path tracer, the reference ([`REFERENCE_SPP`] samples per point).
    PathTracing,
    /// The seed's two-pass method: eye rays with direct light (Whitted's shadow rays, not traced
    /// further) plus the radiance of the *indirect* photon map ([`PHOTONS`], [`NEIGHBOURS`]).
    TwoPass,
    /// Photon mapping: the two-pass method plus the caustic map's radiance at the eye ray's
    /// first hit (no final gather).
    PhotonMapping,
}

/// Photons emitted for the two-pass and photon-mapping cells.
pub const PHOTONS: usize = 200_000;
/// Neighbours of the photon-map radiance estimate for those cells.
pub const NEIGHBOURS: usize = 100;

/// Radiosity at the measured table's mesh ([`TABLE_MESH`]).
const TABLE_RADIOSITY: Measured = Measured::Radiosity { subdivisions: TABLE_MESH.0, samples: TABLE_MESH.1 };

impl Measured {
    fn id(self) -> &'static str {
        match self {
            Measured::Radiosity { .. } => "radiosity",
            Measured::Whitted => "whitted",
            Measured::PathTracing => "path_tracing",
            Measured::TwoPass => "two_pass",
            Measured::PhotonMapping => "photon_mapping",
        }
    }
}

/// Mean outgoing radiance over `points` in `scene` by `method` (Lambertian surfaces: any
/// direction will do; the eye ray comes straight down the normal).
fn mean_radiance(scene: &Scene, method: Measured, points: &[(DVec3, DVec3)]) -> Result<DVec3, RadiosityError> {
    let sum: DVec3 = match method {
        Measured::Radiosity { subdivisions, samples } => {
            let system = System::new(scene, Mesh::new(scene, subdivisions)?, samples)?;
            let solution = system.solve(Solver::GaussSeidel, 60).pop().unwrap_or_default();
            points
                .iter()
                .map(|&(p, n)| {
                    let hit = scene.closest_hit(&Ray { origin: p + n * 0.05, dir: -n }, 0.0, 1.0);
                    hit.and_then(|h| system.radiance_at(&solution, h.object, h.point)).unwrap_or(DVec3::ZERO)
                })
                .sum()
        }
        Measured::Whitted | Measured::PathTracing => {
            let (integrator, spp) = if method == Measured::Whitted {
                (Integrator::Whitted { max_depth: 5 }, 16)
            } else {
                (Integrator::PathTracer { max_depth: 12 }, REFERENCE_SPP)
            };
            let tracer = Tracer::new(scene, analyze(scene).plan.for_integrator(integrator));
            points
                .iter()
                .enumerate()
                .map(|(k, &(p, n))| {
                    let mut sampler = Sampler::new(5, k as u64, 0);
                    let ray = Ray { origin: p + n * 0.05, dir: -n };
                    (0..spp).map(|_| tracer.radiance(integrator, &ray, 0.0, &mut sampler)).sum::<DVec3>()
                        / f64::from(spp)
                })
                .sum()
        }
        Measured::TwoPass | Measured::PhotonMapping => {
            let maps = trace_photons(scene, PHOTONS, 3).map_err(|_| RadiosityError::NoPatches)?;
            let integrator = Integrator::Whitted { max_depth: 5 };
            let tracer = Tracer::new(scene, analyze(scene).plan.for_integrator(integrator));
            let mut total = DVec3::ZERO;
            for (k, &(p, n)) in points.iter().enumerate() {
                let ray = Ray { origin: p + n * 0.05, dir: -n };
                let mut sampler = Sampler::new(5, k as u64, 0);
                let direct =
                    (0..16).map(|_| tracer.radiance(integrator, &ray, 0.0, &mut sampler)).sum::<DVec3>() / 16.0;
                let Some(hit) = scene.closest_hit(&ray, 0.0, 1.0) else { continue };
                let material = scene.objects()[hit.object].material;
                let normal = if ray.dir.dot(hit.normal) < 0.0 { hit.normal } else { -hit.normal };
                let estimate = |map: &PhotonMap| {
                    map.radiance(&material, hit.point, -ray.dir, normal, NEIGHBOURS)
                        .map_err(|_| RadiosityError::NoPatches)
                };
                let caustic = if method == Measured::PhotonMapping && maps.caustic.len() >= NEIGHBOURS {
                    estimate(&maps.caustic)?
                } else {
                    DVec3::ZERO
                };
                total += direct + estimate(&maps.indirect)? + caustic;
            }
            total
        }
    };
    Ok(sum / points.len() as f64)
}

/// A measured cell.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeasuredCell {
    /// Effect id (a row of [`EFFECTS`]).
    pub effect: &'static str,
    /// Method id (a column of [`METHODS`]).
    pub method: &'static str,
    /// The measured size of the effect for this method.
    pub value: f64,
    /// The same measurement on the path-traced reference.
    pub reference: f64,
    /// `value / reference`: the fraction of the effect the method captures.
    pub fraction: f64,
    /// Yes (≥ [`YES_FRACTION`]), No (≤ [`NO_FRACTION`]) or Impractical (between: partial).
    pub verdict: Verdict,
    /// The grammar's verdict for the same cell (area light).
    pub grammar: Verdict,
}

/// Colour bleeding: the red-to-green ratio on the floor strip beside the left wall, red wall over
/// white wall, minus 1 (0 = no red tint).
///
/// # Errors
/// [`RadiosityError`] for a zero mesh count.
pub fn bleeding(method: Measured) -> Result<f64, RadiosityError> {
    let ratio = |red: bool| -> Result<f64, RadiosityError> {
        let scene = cornell_box(red).map_err(|_| RadiosityError::NoPatches)?;
        let l = mean_radiance(&scene, method, &bleeding_region())?;
        Ok(l.x / l.y)
    };
    Ok(ratio(true)? / ratio(false)? - 1.0)
}

/// Ambient glow: the channel-mean radiance on the ceiling away from the light.
///
/// # Errors
/// [`RadiosityError`] for a zero mesh count.
pub fn glow(method: Measured) -> Result<f64, RadiosityError> {
    let scene = cornell_box(true).map_err(|_| RadiosityError::NoPatches)?;
    Ok(mean_radiance(&scene, method, &glow_region())?.element_sum() / 3.0)
}

/// The measured table: effects (b) colour bleeding and (e) ambient glow, for radiosity, the
/// two-pass method, Whitted ray tracing and photon mapping against the path tracer.
///
/// # Errors
/// [`RadiosityError`] if a mesh cannot be built (never for the built-in scenes).
pub fn measured_table() -> Result<Vec<MeasuredCell>, RadiosityError> {
    let mut cells = Vec::new();
    type Experiment = fn(Measured) -> Result<f64, RadiosityError>;
    let experiments: [(&str, Experiment); 2] = [("b", bleeding), ("e", glow)];
    for (effect, measure) in experiments {
        let reference = measure(Measured::PathTracing)?;
        for method in [TABLE_RADIOSITY, Measured::TwoPass, Measured::Whitted, Measured::PhotonMapping] {
            let value = measure(method)?;
            let fraction = value / reference;
            let verdict = if fraction >= YES_FRACTION {
                Verdict::Yes
            } else if fraction <= NO_FRACTION {
                Verdict::No
            } else {
                Verdict::Impractical
            };
            let row = EFFECTS.iter().find(|e| e.id == effect).ok_or(RadiosityError::NoPatches)?;
            let column = METHODS.iter().find(|m| m.id == method.id()).ok_or(RadiosityError::NoPatches)?;
            let grammar = decide(row, column, LightKind::Area).map(|c| c.verdict).unwrap_or(Verdict::No);
            cells.push(MeasuredCell { effect, method: method.id(), value, reference, fraction, verdict, grammar });
        }
    }
    Ok(cells)
}

/// The measured table as markdown.
#[must_use]
pub fn measured_table_markdown(cells: &[MeasuredCell]) -> String {
    let mut out = String::from(
        "| effect | method | measured | path-traced reference | fraction | measured verdict | grammar |\n|---|---|---|---|---|---|---|\n",
    );
    for c in cells {
        out.push_str(&format!(
            "| ({}) | {} | {:.3} | {:.3} | {:.3} | {} | {} |\n",
            c.effect,
            c.method,
            c.value,
            c.reference,
            c.fraction,
            c.verdict.text(),
            c.grammar.text()
        ));
    }
    out
}

/// The radiosity system of the Cornell box at `n × n` patches per quad (figures and benchmarks).
///
/// # Errors
/// As [`System::new`].
pub fn cornell_system(n: usize, samples: usize) -> Result<(Scene, System), RadiosityError> {
    let scene = cornell_box(true).map_err(|_| RadiosityError::NoPatches)?;
    let system = System::new(&scene, Mesh::new(&scene, n)?, samples)?;
    Ok((scene, system))
}

/// Figures: the radiosity Cornell box (PNG), solver convergence (SVG), the measured table and
/// the grammar tables (markdown).
///
/// # Errors
/// [`PlotError`] if drawing fails.
pub fn figures() -> Result<Vec<Figure>, PlotError> {
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
    let measured = measured_table().map_err(|e| draw_error("q5_measured_table.md", &e))?;
    figures.push(Figure {
        file_name: "q5_measured_table.md".into(),
        bytes: measured_table_markdown(&measured).into_bytes(),
    });
    let grammar = super::grammar_table_markdown().map_err(|e| draw_error("q5_grammar_tables.md", &e))?;
    figures.push(Figure { file_name: "q5_grammar_tables.md".into(), bytes: grammar.into_bytes() });
    let comparison = super::seed_comparison_markdown().map_err(|e| draw_error("q5_seed_comparison.md", &e))?;
    figures.push(Figure { file_name: "q5_seed_comparison.md".into(), bytes: comparison.into_bytes() });
    Ok(figures)
}

/// Plotters' white (the crate's [`WHITE`] is a reflectance).
const WHITE_BG: RGBColor = RGBColor(255, 255, 255);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn measured_cells_agree_with_the_grammar_and_are_pinned() {
        let cells = measured_table().unwrap();
        for c in &cells {
            assert_eq!(c.verdict, c.grammar, "{c:?}");
        }
        crate::test_support::insta_settings().bind(|| {
            insta::assert_snapshot!("q5_measured_table", measured_table_markdown(&cells));
        });
    }

    #[test]
    fn the_glow_region_gets_no_direct_light() {
        // Direct light only (Whitted) sees nothing on the ceiling: the region is lit indirectly.
        assert_eq!(glow(Measured::Whitted).unwrap(), 0.0);
    }
}
