//! The Cornell box with its published geometry, for validating radiosity against the path tracer.
//!
//! Data: the Cornell University Program of Computer Graphics, "Cornell Box Data"
//! (graphics.cornell.edu/online/box/data.html; copy at graphicon.ru/oldgr/courses/cg_el99/c_box/data.htm),
//! in millimetres, converted to metres here. The reflectances are measured spectra; the crate is
//! RGB, so it uses the RGB stand-ins of the Tungsten renderer's scene
//! (book.vertexwahn.de/docs/tools/cornell_box: white (0.725, 0.71, 0.68), red (0.63, 0.065, 0.05),
//! green (0.14, 0.45, 0.091), the crate's [`CORNELL_WHITE`], [`CORNELL_RED`], [`CORNELL_GREEN`]) and the light radiance
//! of Mitsuba 3's `cornell_box()` (18.387, 13.987, 6.754).
//!
//! The renderer's quads are parallelograms (corner + two edges). Of the published polygons the
//! ceiling, the green wall and the blocks' sides are exact rectangles; the floor, the back wall,
//! the red wall (which is not even planar) and the blocks' tops are not, and become the
//! parallelogram through three of their corners: the fourth corner moves by at most 6.4 mm (the
//! back wall's top right corner, 1.2 % of the box's width; the others by 3.2 mm or less). The
//! light is published at the ceiling's height; it sits 0.1 mm below it here so that the two
//! coincident surfaces do not tie (a tie would go to the lower object index, hiding the light
//! behind the ceiling for half the rays).

use super::budget::Budget;
use super::error::ExperimentError;
use super::photon_cornell::Reference;
use super::radiosity::{Mesh, Solver, System};
use crate::data::DataError;
use crate::geometry::{InputError, Ray};
use crate::plot::markdown_table;
use crate::render::analysis::analyze;
use crate::render::catalogue::{CORNELL_GREEN, CORNELL_RED, CORNELL_WHITE};
use crate::render::integrator::Integrator;
use crate::render::noise::noise_between;
use crate::render::{Image, Settings, render};
use crate::render::{
    camera::Camera,
    scene::{Material, Object, Scene, Shape},
};
use glam::DVec3;

/// Radiance of the light (Mitsuba 3's RGB stand-in for the published spectrum).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::cornell_published::{LIGHT_RADIANCE, scene};
/// // The one emitter of the scene, warm (red > green > blue).
/// assert_eq!(scene().unwrap().area_lights().next().unwrap().radiance, LIGHT_RADIANCE);
/// assert!(LIGHT_RADIANCE.x > LIGHT_RADIANCE.y && LIGHT_RADIANCE.y > LIGHT_RADIANCE.z);
/// ```
pub const LIGHT_RADIANCE: DVec3 = DVec3::new(18.387, 13.987, 6.754);

/// A point given in the data page's millimetres, in metres.
fn mm(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z) / 1000.0
}

/// The parallelogram through `a`, `b` (= a + edge_u) and `c` (= a + edge_v).
fn parallelogram(a: DVec3, b: DVec3, c: DVec3, material: Material) -> Object {
    Object::quad(a, b - a, c - a, material)
}

/// A block: its top (corners in order, any orientation) at `height` and the four sides down to
/// the floor, every face's normal pointing out of the block.
fn block(top: [(f64, f64); 4], height: f64, material: Material) -> Vec<Object> {
    let corners: Vec<DVec3> = top.iter().map(|&(x, z)| mm(x, height, z)).collect();
    let centre = corners.iter().sum::<DVec3>() / 4.0;
    let down = DVec3::NEG_Y * (height / 1000.0);
    let outward = |object: Object, towards: DVec3| match object.shape {
        Shape::Quad { corner, edge_u, edge_v } if edge_u.cross(edge_v).dot(towards) < 0.0 => {
            Object::quad(corner, edge_v, edge_u, material)
        }
        _ => object,
    };
    let mut faces = vec![outward(parallelogram(corners[0], corners[1], corners[3], material), DVec3::Y)];
    for k in 0..4 {
        let (a, b) = (corners[k], corners[(k + 1) % 4]);
        let side = Object::quad(a, b - a, down, material);
        faces.push(outward(side, (a + b) / 2.0 - centre));
    }
    faces
}

/// The published Cornell box (metres), open at the front (`z = 0`), seen from the published
/// camera: eye (278, 273, −800) mm looking along `+z`, a 35 mm lens on 25 mm film, i.e. a
/// vertical field of view of 2·atan(12.5/35) = 39.31°.
///
/// # Errors
/// Never for the built-in numbers.
///
/// # Examples
/// ```
/// let scene = hw3::q5_effect_tables::cornell_published::scene().unwrap();
/// assert_eq!(scene.objects().len(), 16); // 5 walls, the light, 2 blocks × 5 faces
/// ```
pub fn scene() -> Result<Scene, InputError> {
    let white = Material::Diffuse { albedo: CORNELL_WHITE };
    let mut objects = vec![
        // Floor (552.8,0,0) (0,0,0) (0,0,559.2) (549.6,0,559.2): corner (0,0,0), normal +y.
        parallelogram(mm(0.0, 0.0, 0.0), mm(0.0, 0.0, 559.2), mm(552.8, 0.0, 0.0), white),
        // Ceiling y = 548.8, x 0–556, z 0–559.2, normal −y.
        parallelogram(mm(0.0, 548.8, 0.0), mm(556.0, 548.8, 0.0), mm(0.0, 548.8, 559.2), white),
        // Back wall z = 559.2: (549.6,0) (0,0) (0,548.8) (556,548.8), normal −z.
        parallelogram(mm(0.0, 0.0, 559.2), mm(0.0, 548.8, 559.2), mm(549.6, 0.0, 559.2), white),
        // Green wall x = 0, normal +x.
        parallelogram(
            mm(0.0, 0.0, 0.0),
            mm(0.0, 548.8, 0.0),
            mm(0.0, 0.0, 559.2),
            Material::Diffuse { albedo: CORNELL_GREEN },
        ),
        // Red wall (552.8,0,0) (549.6,0,559.2) (556,548.8,559.2) (556,548.8,0), normal −x.
        parallelogram(
            mm(552.8, 0.0, 0.0),
            mm(549.6, 0.0, 559.2),
            mm(556.0, 548.8, 0.0),
            Material::Diffuse { albedo: CORNELL_RED },
        ),
        // Light y = 548.8 − 0.1, x 213–343, z 227–332, facing down.
        parallelogram(
            mm(213.0, 548.7, 227.0),
            mm(343.0, 548.7, 227.0),
            mm(213.0, 548.7, 332.0),
            Material::Emitter { radiance: LIGHT_RADIANCE },
        ),
    ];
    objects.extend(block([(130.0, 65.0), (82.0, 225.0), (240.0, 272.0), (290.0, 114.0)], 165.0, white));
    objects.extend(block([(423.0, 247.0), (265.0, 296.0), (314.0, 456.0), (472.0, 406.0)], 330.0, white));
    let vfov = 2.0 * (12.5f64 / 35.0).atan().to_degrees();
    let camera = Camera::looking_at(mm(278.0, 273.0, -800.0), mm(278.0, 273.0, 0.0), vfov);
    Scene::new(camera, objects, vec![], None, DVec3::ZERO)
}

/// Probe rays onto the walls, 10 mm off each wall along its inward normal, four on each of the
/// floor (in front of the blocks), the ceiling (away from the light), the back, green and red
/// walls: 20 points away from edges, blocks and the light.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::cornell_published::{scene, wall_probes};
/// let (scene, probes) = (scene().unwrap(), wall_probes());
/// assert_eq!(probes.len(), 20);
/// // 10 mm off the wall (the red wall, tilted by the parallelogram, up to 3 mm more).
/// assert!(probes.iter().all(|ray| scene.closest_hit(ray, 0.0, 0.014).is_some()));
/// ```
#[must_use]
pub fn wall_probes() -> Vec<Ray<f64>> {
    let probe = |point: DVec3, inward: DVec3| Ray { origin: point + inward * 0.01, dir: -inward };
    let pairs = |u: [f64; 2], v: [f64; 2]| [(u[0], v[0]), (u[1], v[0]), (u[0], v[1]), (u[1], v[1])];
    let mut probes = Vec::new();
    for (x, z) in pairs([0.34, 0.46], [0.05, 0.17]) {
        probes.push(probe(DVec3::new(x, 0.0, z), DVec3::Y));
    }
    for (x, z) in pairs([0.08, 0.47], [0.1, 0.47]) {
        probes.push(probe(DVec3::new(x, 0.5488, z), DVec3::NEG_Y));
    }
    for (x, y) in pairs([0.15, 0.4], [0.15, 0.4]) {
        probes.push(probe(DVec3::new(x, y, 0.5592), DVec3::NEG_Z));
    }
    for (y, z) in pairs([0.15, 0.4], [0.15, 0.4]) {
        probes.push(probe(DVec3::new(0.0, y, z), DVec3::X));
        probes.push(probe(DVec3::new(0.5528, y, z), DVec3::NEG_X));
    }
    probes
}

/// The wall of each of the [`wall_probes`], in order.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::cornell_published::{PROBE_WALLS, wall_probes};
/// assert_eq!(PROBE_WALLS.len(), wall_probes().len());
/// assert_eq!(PROBE_WALLS.iter().filter(|&&w| w == "red").count(), 4); // four per wall
/// ```
pub const PROBE_WALLS: [&str; 20] = [
    "floor", "floor", "floor", "floor", "ceiling", "ceiling", "ceiling", "ceiling", "back", "back", "back", "back",
    "green", "red", "green", "red", "green", "red", "green", "red",
];

/// Radiosity's channel-mean radiance at every probe ([`wall_probes`]) for `n × n` patches per
/// quad and `samples²` form-factor samples per patch (80 Gauss–Seidel sweeps).
///
/// # Errors
/// [`ExperimentError`] for a zero count; never otherwise.
///
/// # Examples
/// ```
/// let radiance = hw3::q5_effect_tables::cornell_published::radiosity_at_probes(2, 1).unwrap();
/// assert!(radiance.len() == 20 && radiance.iter().all(|&l| l > 0.0));
/// ```
pub fn radiosity_at_probes(n: usize, samples: usize) -> Result<Vec<f64>, ExperimentError> {
    let scene = scene()?;
    let system = System::new(&scene, Mesh::new(&scene, n)?, samples)?;
    let solution = system.solve(Solver::GaussSeidel, 80).pop().unwrap_or_default();
    Ok(wall_probes()
        .iter()
        .map(|ray| {
            let hit = scene.closest_hit(ray, 0.0, f64::INFINITY);
            hit.and_then(|h| system.radiance_at(&solution, h.object, h.point)).map_or(0.0, |l| l.element_sum() / 3.0)
        })
        .collect())
}

/// The radiosity solution rendered from the published camera (`size × size`; `patches × patches`
/// per quad and one form-factor sample, 80 Gauss–Seidel sweeps, interpolated). The figure takes
/// [`SIDE_BY_SIDE_PATCHES`].
///
/// # Errors
/// [`ExperimentError`] for a zero patch count.
///
/// # Examples
/// ```
/// // A thumbnail at 2 × 2 patches per quad: the ceiling light shows in the top middle.
/// let image = hw3::q5_effect_tables::cornell_published::radiosity_image(12, 2).unwrap();
/// assert_eq!(image.dimensions(), (12, 12));
/// assert!(image.get_pixel(6, 0).0[0] > 0 || image.get_pixel(6, 1).0[0] > 0);
/// assert!(hw3::q5_effect_tables::cornell_published::radiosity_image(12, 0).is_err());
/// ```
pub fn radiosity_image(size: u32, patches: usize) -> Result<crate::plot::RgbImage, ExperimentError> {
    let scene = scene()?;
    let system = System::new(&scene, Mesh::new(&scene, patches)?, 1)?;
    let solution = system.solve(Solver::GaussSeidel, 80).pop().unwrap_or_default();
    Ok(system.render(&scene, &solution, size, size).to_rgb8())
}

/// The path tracer's settings for a `size × size` image of [`scene`] at `spp` samples per pixel:
/// every bounce the scene's plan keeps, 12 at most, with Russian roulette from the third (in this
/// closed box it halves the seconds per sample for 1.1 times the noise,
/// [`Integrator::PathTracerWithRoulette`]), seed 1, the same camera as [`radiosity_image`].
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::cornell_published::{path_settings, scene};
/// use hw3::render::integrator::Integrator;
/// let settings = path_settings(&scene().unwrap(), 320, 64);
/// assert_eq!((settings.width, settings.height, settings.spp, settings.seed), (320, 320, 64, 1));
/// assert_eq!(settings.integrator, Integrator::PathTracerWithRoulette { max_depth: 12 });
/// ```
#[must_use]
pub fn path_settings(scene: &Scene, size: u32, spp: u32) -> Settings {
    Settings {
        integrator: Integrator::PathTracerWithRoulette { max_depth: 12 },
        ..Settings::whitted(size, size, spp, analyze(scene).plan)
    }
}

/// The path tracer's image of [`scene`] with [`path_settings`].
///
/// # Errors
/// [`ExperimentError`] for zero samples, or if the render fails.
///
/// # Examples
/// ```
/// // A thumbnail at one sample per pixel: the ceiling light shows in the top middle.
/// let image = hw3::q5_effect_tables::cornell_published::path_traced_image(12, 1).unwrap();
/// assert_eq!(image.dimensions(), (12, 12));
/// assert!(image.get_pixel(6, 0).0[0] > 0 || image.get_pixel(6, 1).0[0] > 0);
/// assert!(hw3::q5_effect_tables::cornell_published::path_traced_image(12, 0).is_err());
/// ```
pub fn path_traced_image(size: u32, spp: u32) -> Result<crate::plot::RgbImage, ExperimentError> {
    let scene = scene()?;
    Ok(render(&scene, &path_settings(&scene, size, spp), &|_| {})?.to_rgb8())
}

/// Seeds of the two halves of [`path_traced_with_noise`]: not the seed 1 of [`path_settings`], whose
/// streams the noisy panel's samples start (a reference drawn from them would share its first
/// samples and understate its difference).
const HALF_SEEDS: [u64; 2] = [2, 3];

/// The path tracer's image of [`scene`] at `spp` samples per pixel ([`path_settings`]) as the
/// mean of two independent renders of `spp / 2` each (seeds 2 and 3), with the noise of that mean
/// in display levels of 255, measured from the two: their noise-free parts are equal, so their
/// difference is their two noises and `rms(a − b) / √2` is the noise of either
/// ([`noise_between`]); the mean of two halves has `1/√2` of it.
///
/// # Errors
/// [`ExperimentError::UnevenSamples`] for an odd or zero `spp`, [`ExperimentError::Render`] if
/// the render fails.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::cornell_published::path_traced_with_noise;
/// let (image, noise) = path_traced_with_noise(12, 4).unwrap();
/// assert_eq!(image.dimensions(), (12, 12));
/// assert!(noise > 0.0 && noise < 255.0);
/// assert!(path_traced_with_noise(12, 3).is_err() && path_traced_with_noise(12, 0).is_err());
/// ```
pub fn path_traced_with_noise(size: u32, spp: u32) -> Result<(crate::plot::RgbImage, f64), ExperimentError> {
    if spp == 0 || !spp.is_multiple_of(2) {
        return Err(ExperimentError::UnevenSamples(spp));
    }
    let scene = scene()?;
    let half = |seed| {
        render(&scene, &Settings { seed, ..path_settings(&scene, size, spp / 2) }, &|_| {})
            .map_err(ExperimentError::from)
    };
    let (a, b) = (half(HALF_SEEDS[0])?, half(HALF_SEEDS[1])?);
    let noise = noise_between(&a.to_rgb8(), &b.to_rgb8()) / std::f64::consts::SQRT_2;
    let pixels = a.pixels.iter().zip(&b.pixels).map(|(&p, &q)| (p + q) * 0.5).collect();
    Ok((Image { pixels, ..a }.to_rgb8(), noise))
}

/// Radiosity's patches per quad edge in the published box's figure ([`radiosity_image`]).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::cornell_published::{LEVELS, SIDE_BY_SIDE_PATCHES};
/// // The figure shows the validation table's finest mesh.
/// assert_eq!(SIDE_BY_SIDE_PATCHES, LEVELS[LEVELS.len() - 1]);
/// ```
pub const SIDE_BY_SIDE_PATCHES: usize = Budget::PUBLISHED.side_by_side_patches;

/// Path-traced samples per probe of the committed converged reference ([`converged_reference`]).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::cornell_published::REFERENCE_SPP;
/// // The committed file says how many samples it holds.
/// assert!(hw3::data::Q5_CORNELL_REFERENCE.contains(&format!("{REFERENCE_SPP} samples per probe")));
/// ```
pub const REFERENCE_SPP: u64 = 1 << 23;

/// Random seed of the committed reference (independent of the seed-7 streams of
/// [`super::photon_cornell::reference`], which the tests use for a cheap check of it).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::cornell_published::REFERENCE_SEED;
/// assert!(hw3::data::Q5_CORNELL_REFERENCE.contains(&format!("seed {REFERENCE_SEED},")));
/// ```
pub const REFERENCE_SEED: u64 = 11;

/// File name of the committed reference (under `docs/data/`).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::cornell_published::REFERENCE_CSV;
/// // Errors reading the compiled-in file name it.
/// assert_eq!(REFERENCE_CSV, "q5_cornell_reference.csv");
/// ```
pub const REFERENCE_CSV: &str = "q5_cornell_reference.csv";

/// The converged path-traced reference at the [`wall_probes`], as committed in
/// `docs/data/q5_cornell_reference.csv` ([`crate::data::Q5_CORNELL_REFERENCE`]):
/// [`REFERENCE_SPP`] samples per probe from seed [`REFERENCE_SEED`]
/// ([`super::photon_cornell::reference_seeded`]), computed once (about 10 CPU-minutes) by
/// `cargo test --release --lib -- --ignored write_converged_reference`.
///
/// # Errors
/// A [`DataError`] naming the file if it does not hold one record `probe,radiance,standard_error`
/// per probe, in order, with a positive radiance: [`DataError::Header`] for another header,
/// [`DataError::ProbeRecord`] for a bad record, [`DataError::ProbeCount`] for a record count other
/// than the [`wall_probes`]'.
///
/// # Examples
/// ```
/// let reference = hw3::q5_effect_tables::cornell_published::converged_reference().unwrap();
/// assert_eq!(reference.radiance.len(), 20);
/// assert!(reference.max_relative_error() < 1e-3); // 0.06 %: 40 times below a 4096-sample one
/// ```
pub fn converged_reference() -> Result<Reference, DataError> {
    let file = REFERENCE_CSV;
    let csv = crate::data::csv(crate::data::Q5_CORNELL_REFERENCE);
    if csv.header != ["probe", "radiance", "standard_error"] {
        return Err(DataError::Header { file, header: csv.header.iter().map(|f| (*f).to_owned()).collect() });
    }
    let mut reference = Reference { radiance: Vec::new(), standard_error: Vec::new() };
    for (index, record) in csv.records.iter().enumerate() {
        let numbers: Vec<f64> = record.iter().filter_map(|f| f.parse().ok()).collect();
        match numbers[..] {
            [probe, radiance, error] if probe == index as f64 && radiance > 0.0 && error >= 0.0 => {
                reference.radiance.push(radiance);
                reference.standard_error.push(error);
            }
            _ => return Err(DataError::ProbeRecord { file, index }),
        }
    }
    if reference.radiance.len() != wall_probes().len() {
        return Err(DataError::ProbeCount { file, got: reference.radiance.len(), expected: wall_probes().len() });
    }
    Ok(reference)
}

/// Patches per quad edge of the committed validation table ([`Budget::PUBLISHED`]).
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::cornell_published::LEVELS;
/// // Coarse to fine, the finest 46 mm patches on the 552.8 mm floor.
/// assert!(LEVELS.windows(2).all(|w| w[0] < w[1]));
/// assert_eq!((552.8 / LEVELS[3] as f64).round(), 46.0);
/// ```
pub const LEVELS: &[usize] = Budget::PUBLISHED.levels;

/// Relative errors `radiosity/path-traced − 1` at the [`wall_probes`] for `n × n` patches per quad
/// (one form-factor sample per patch), against `reference` (channel means per probe).
///
/// # Errors
/// As [`radiosity_at_probes`].
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::cornell_published::{radiosity_at_probes, relative_errors};
/// let itself = radiosity_at_probes(2, 1).unwrap();
/// assert!(relative_errors(2, &itself).unwrap().iter().all(|&e| e == 0.0));
/// ```
pub fn relative_errors(n: usize, reference: &[f64]) -> Result<Vec<f64>, ExperimentError> {
    Ok(radiosity_at_probes(n, 1)?.iter().zip(reference).map(|(v, r)| v / r - 1.0).collect())
}

/// The validation as markdown: for each of the `budget`'s [`levels`](Budget::levels) ([`LEVELS`]
/// at [`Budget::PUBLISHED`], the committed `q5_cornell_published.md`), the patch count and the
/// largest, mean and RMS relative error over the 20 wall probes against the committed path-traced
/// reference ([`converged_reference`], [`REFERENCE_SPP`] samples per probe), then each probe's
/// error at the finest level.
///
/// # Errors
/// As [`radiosity_at_probes`].
///
/// # Panics
/// If `budget.levels` is empty.
///
/// # Examples
/// ```
/// use hw3::q5_effect_tables::{Budget, cornell_published::validation_table};
/// // 2 × 2 and 3 × 3 patches per quad.
/// let table = validation_table(&Budget::TINY).unwrap();
/// let (levels, probes) = table.split_once("| probe |").unwrap();
/// assert!(levels.contains("\n| 2 | ") && levels.contains("\n| 3 | ") && !levels.contains("\n| 12 | "));
/// // One row per probe, numbered 0 to 19, under the per-probe header.
/// assert_eq!(probes.lines().filter(|l| l.starts_with("| ") && !l.starts_with("|---")).count(), 20);
/// ```
pub fn validation_table(budget: &Budget) -> Result<String, ExperimentError> {
    let finest_level = *budget.levels.last().expect("a budget has at least one level");
    let scene = scene()?;
    let reference = converged_reference()?;
    let mut out = format!(
        "Published Cornell box, radiosity (one form-factor sample per patch, 80 Gauss–Seidel sweeps) against the path tracer ({REFERENCE_SPP} samples per probe, relative standard error at most {:.2} %) at 20 wall probes.\n\n",
        reference.max_relative_error() * 100.0
    );
    let mut finest = Vec::new();
    let mut rows = Vec::new();
    for &n in budget.levels {
        let errors = relative_errors(n, &reference.radiance)?;
        let patches = Mesh::new(&scene, n)?.patches.len();
        let count = errors.len() as f64;
        let largest = errors.iter().fold(0.0f64, |m, e| m.max(e.abs()));
        let mean = errors.iter().map(|e| e.abs()).sum::<f64>() / count;
        let rms = (errors.iter().map(|e| e * e).sum::<f64>() / count).sqrt();
        let percent = |x: f64| format!("{:.1} %", x * 100.0);
        rows.push([
            n.to_string(),
            patches.to_string(),
            format!("{:.0} mm", 552.8 / n as f64),
            percent(largest),
            percent(mean),
            percent(rms),
        ]);
        finest = errors;
    }
    let header = ["patches per edge", "patches", "patch width", "largest error", "mean error", "RMS error"];
    out.push_str(&markdown_table(&header, rows));
    out.push_str(&format!(
        "\nPer probe: the reference radiance (channel mean), its standard error, and radiosity's error at {finest_level} × {finest_level} patches per quad.\n\n"
    ));
    let probes =
        reference.radiance.iter().zip(&reference.standard_error).zip(&finest).enumerate().map(|(p, ((l, se), e))| {
            [
                p.to_string(),
                PROBE_WALLS[p].to_string(),
                format!("{l:.5}"),
                format!("{se:.1e}"),
                format!("{:.3} %", se / l * 100.0),
                format!("{:+.1} %", e * 100.0),
            ]
        });
    let header = ["probe", "wall", "reference L", "standard error", "relative", "radiosity error"];
    out.push_str(&markdown_table(&header, probes));
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every face of the box and the blocks faces the inside of the box (so radiosity meshes the
    /// lit side), and the light faces down.
    #[test]
    fn faces_point_into_the_box() {
        let scene = scene().unwrap();
        let centre = mm(278.0, 274.4, 279.6);
        for (index, object) in scene.objects().iter().enumerate() {
            let Shape::Quad { corner, edge_u, edge_v } = object.shape else { panic!("quads only") };
            let normal = edge_u.cross(edge_v);
            let middle = corner + (edge_u + edge_v) / 2.0;
            if index < 6 {
                assert!(normal.dot(centre - middle) > 0.0, "wall or light {index} faces away");
            } else {
                assert!(normal.dot(centre - middle) != 0.0, "block face {index} is not degenerate");
            }
        }
    }

    /// Each probe lands on the wall [`PROBE_WALLS`] names.
    #[test]
    fn probe_walls_name_the_wall_each_probe_hits() {
        let scene = scene().unwrap();
        let walls = ["floor", "ceiling", "back", "green", "red"];
        for (p, ray) in wall_probes().iter().enumerate() {
            let hit = scene.closest_hit(ray, 0.0, f64::INFINITY).unwrap();
            assert_eq!(walls[hit.object], PROBE_WALLS[p], "probe {p}");
        }
    }

    /// Radiosity against the converged path tracer at 20 wall probes. With 12 × 12 patches per
    /// quad (46 mm wide) every probe is within 6 % and the mean within 2.5 %; with 6 × 6 (92 mm)
    /// the mean error is larger: the error is discretisation, largest in the contact shadows
    /// beside and behind the tall block, where the radiance changes within one patch, and it
    /// falls with the patch width. The reference is at least ten times more accurate than the
    /// finest row's mean error, so the table measures radiosity, not the reference's noise.
    #[test]
    fn radiosity_matches_the_path_tracer_on_the_published_box() {
        let reference = converged_reference().unwrap();
        let mean = |e: &[f64]| e.iter().map(|x| x.abs()).sum::<f64>() / e.len() as f64;
        let fine = relative_errors(12, &reference.radiance).unwrap();
        assert!(fine.iter().all(|e| e.abs() < 0.06), "{fine:?}");
        assert!(mean(&fine) < 0.025, "{fine:?}");
        assert!(10.0 * reference.max_relative_error() < mean(&fine), "{} vs {fine:?}", reference.max_relative_error());
        let coarse = relative_errors(6, &reference.radiance).unwrap();
        assert!(mean(&coarse) > mean(&fine), "{coarse:?} vs {fine:?}");
    }

    /// The committed reference is what it says: [`REFERENCE_SPP`] samples per probe, and an
    /// independent cheap reference (4096 samples, seed 7, up to 2.5 % standard error) lies within
    /// four combined standard errors of it at every probe.
    #[test]
    fn committed_reference_agrees_with_an_independent_cheap_one() {
        let committed = converged_reference().unwrap();
        let comments = crate::data::csv(crate::data::Q5_CORNELL_REFERENCE).comments.join(" ");
        assert!(comments.contains(&format!("seed {REFERENCE_SEED}, {REFERENCE_SPP} samples per probe")), "{comments}");
        let cheap = super::super::photon_cornell::reference(&scene().unwrap(), &wall_probes(), 4096);
        assert!(cheap.max_relative_error() < 0.03, "{}", cheap.max_relative_error());
        for (p, (c, r)) in committed.radiance.iter().zip(&cheap.radiance).enumerate() {
            let sigma = committed.standard_error[p].hypot(cheap.standard_error[p]);
            assert!((c - r).abs() <= 4.0 * sigma, "probe {p}: committed {c}, cheap {r}, σ {sigma}");
        }
        // Its noise is consistent with its count: 1024 times the samples, about 32 times less error.
        let ratio = cheap.max_relative_error() / committed.max_relative_error();
        assert!((16.0..64.0).contains(&ratio), "{ratio}");
    }

    /// The committed reference's CSV text for `reference` (`spp` samples per probe, `seconds` of
    /// wall time): the provenance as `#` comments, then one record per probe.
    fn reference_csv(reference: &Reference, spp: u64, seconds: f64) -> String {
        let mut out = format!(
            "# Published Cornell box (cornell_published::scene), channel-mean radiance at the 20 wall probes (cornell_published::wall_probes)\n\
             # path traced, every bounce on, 12 at most: photon_cornell::reference_seeded, seed {REFERENCE_SEED}, {spp} samples per probe, {seconds:.0} s on 2 shared cores\n\
             # standard_error: sample standard deviation over sqrt(samples); largest relative {:.3} %\n\
             # written by: cargo test --release --lib -- --ignored write_converged_reference\n\
             probe,radiance,standard_error\n",
            reference.max_relative_error() * 100.0
        );
        for (index, (radiance, error)) in reference.radiance.iter().zip(&reference.standard_error).enumerate() {
            out.push_str(&format!("{index},{radiance:e},{error:e}\n"));
        }
        out
    }

    /// Computes the converged reference and writes it to `docs/data/q5_cornell_reference.csv`
    /// (or to `HW3_REFERENCE_OUT`), with `HW3_REFERENCE_SPP` samples per probe if set (for a
    /// timing run) and [`REFERENCE_SPP`] otherwise.
    #[test]
    #[ignore = "about 10 CPU-minutes; rewrites committed data"]
    fn write_converged_reference() {
        let spp = std::env::var("HW3_REFERENCE_SPP").ok().and_then(|v| v.parse().ok()).unwrap_or(REFERENCE_SPP);
        let out = std::env::var("HW3_REFERENCE_OUT").map_or_else(
            |_| std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/data").join(REFERENCE_CSV),
            std::path::PathBuf::from,
        );
        let start = std::time::Instant::now();
        let reference =
            super::super::photon_cornell::reference_seeded(&scene().unwrap(), &wall_probes(), spp, REFERENCE_SEED);
        let text = reference_csv(&reference, spp, start.elapsed().as_secs_f64());
        crate::fsio::write_atomic(&out, text.as_bytes()).unwrap();
        eprintln!("{text}");
    }
}
