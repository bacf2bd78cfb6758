#![doc = include_str!(concat!(env!("OUT_DIR"), "/q1_hard_scenes.md"))]

use crate::Answers;
use crate::geometry::Sphere;
use crate::geometry::{InputError, Ray};
use crate::plot::{self, Figure, PALETTE, PlotError, err};
use crate::render::catalogue::{self, CLUTTER_HALF_WIDTH, CLUTTER_RADIUS};
use crate::render::{Image, Settings, render};
use crate::render::{analysis::analyze, passes::Pass};
use crate::render::{
    camera::Camera,
    scene::{Material, Object, PointLight, Scene, Shape},
};
use crate::render::{
    integrator::{IN_SCATTER_STEPS, Integrator, Tracer, airlight_traced},
    medium::airlight_closed_form,
    sampling::Sampler,
};
use glam::DVec3;
use plotters::prelude::*;
use std::collections::BTreeSet;
use std::f64::consts::PI;
use std::fmt::Write as _;

// ---------------------------------------------------------------------------------------------
// (a) clutter

/// Sphere counts of the clutter experiment.
pub const CLUTTER_COUNTS: [usize; 5] = [250, 500, 1000, 2000, 4000];

/// One row of the clutter experiment (averaged over [`CLUTTER_SEEDS`] random forests).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClutterRow {
    /// Number of spheres `N`.
    pub count: usize,
    /// Optical depth of the slab `τ = N·p`, `p = πa²/(W + 2a)²` (the probability that one sphere
    /// blocks a given ray); equal to `n π a² Z` with `n = N / ((W + 2a)² Z)`.
    pub optical_depth: f64,
    /// Measured fraction of probe rays that cross the slab without a hit (mean over forests).
    pub gap_fraction: f64,
    /// Standard error of that mean (spread between forests / √forests).
    pub gap_standard_error: f64,
    /// The exact law for `N` uniform spheres, `(1 − p)^N`.
    pub gap_exact: f64,
    /// The Boolean-model (Beer–Lambert-for-geometry) limit `e^(−τ)`.
    pub gap_beer_lambert: f64,
    /// Measured mean number of spheres pierced per probe ray (depth complexity).
    pub depth_complexity: f64,
    /// Fraction of the spheres inside a camera's view that at least one pixel sees (mean over
    /// cameras and forests).
    pub visible_fraction: f64,
}

/// Random forests per clutter row.
pub const CLUTTER_SEEDS: u64 = 4;
/// Probe rays per side of the square grid of the gap-fraction measurement.
const PROBE_GRID: usize = 48;
/// Half-width of the probe square: well inside the slab, so every probe ray sees a full forest.
const PROBE_HALF_WIDTH: f64 = 15.0;
/// Cameras per forest, and their ID-buffer size, for the visible fraction.
const VISIBILITY_CAMERAS: usize = 3;
const VISIBILITY_SIZE: (u32, u32) = (64, 48);

/// Measures gap fraction, depth complexity and visible fraction for `count` spheres.
///
/// Probe rays run along `−z` through the slab from a 48×48 grid over `|x|, |y| ≤ 15`; the visible
/// fraction uses ID buffers of 64×48 pixels from three cameras 12 units in front of the slab.
///
/// # Errors
/// [`InputError`] only if a scene could not be built (never for the built-in numbers).
pub fn clutter_row(count: usize) -> Result<ClutterRow, InputError> {
    let mut gaps = Vec::new();
    let mut pierced_total = 0.0;
    let mut visible_total = 0.0;
    for seed in 1..=CLUTTER_SEEDS {
        let scene = catalogue::clutter_forest(count, seed)?;
        let mut open = 0usize;
        let mut pierced = 0usize;
        for i in 0..PROBE_GRID * PROBE_GRID {
            let cell = |k: usize| -PROBE_HALF_WIDTH + 2.0 * PROBE_HALF_WIDTH * (k as f64 + 0.5) / PROBE_GRID as f64;
            let ray = Ray { origin: DVec3::new(cell(i % PROBE_GRID), cell(i / PROBE_GRID), 1.0), dir: DVec3::NEG_Z };
            open += usize::from(scene.closest_hit(&ray, 0.0, f64::INFINITY).is_none());
            pierced += scene.objects_pierced(&ray, 0.0, f64::INFINITY);
        }
        let rays = (PROBE_GRID * PROBE_GRID) as f64;
        gaps.push(open as f64 / rays);
        pierced_total += pierced as f64 / rays;
        visible_total += visible_fraction(&scene, seed)?;
    }
    let seeds = CLUTTER_SEEDS as f64;
    let gap_fraction = gaps.iter().sum::<f64>() / seeds;
    let spread = (gaps.iter().map(|g| (g - gap_fraction).powi(2)).sum::<f64>() / (seeds - 1.0)).sqrt();
    let side = 2.0 * (CLUTTER_HALF_WIDTH + CLUTTER_RADIUS);
    let p = PI * CLUTTER_RADIUS * CLUTTER_RADIUS / (side * side);
    let optical_depth = count as f64 * p;
    Ok(ClutterRow {
        count,
        optical_depth,
        gap_fraction,
        gap_standard_error: spread / seeds.sqrt(),
        gap_exact: (1.0 - p).powi(count as i32),
        gap_beer_lambert: (-optical_depth).exp(),
        depth_complexity: pierced_total / seeds,
        visible_fraction: visible_total / seeds,
    })
}

/// Fraction of the spheres whose centre is inside the view of a camera that at least one pixel
/// (ray through the pixel centre) hits (spheres seen only by a sliver at the image border, with
/// their centre outside, are not counted), averaged over [`VISIBILITY_CAMERAS`] cameras.
fn visible_fraction(scene: &Scene, seed: u64) -> Result<f64, InputError> {
    let mut sampler = Sampler::new(seed, 0, 7);
    let mut total = 0.0;
    for _ in 0..VISIBILITY_CAMERAS {
        let offset = DVec3::new(8.0 * (2.0 * sampler.uniform() - 1.0), 8.0 * (2.0 * sampler.uniform() - 1.0), 0.0);
        let camera =
            Camera { eye: scene.camera().eye + offset, look_at: scene.camera().look_at + offset, ..*scene.camera() };
        let view = scene.with_camera(camera)?;
        let (width, height) = VISIBILITY_SIZE;
        let frame = crate::render::camera::CameraFrame::new(&camera);
        let aspect = f64::from(width) / f64::from(height);
        let seen: BTreeSet<usize> = (0..width * height)
            .filter_map(|k| {
                let u = (f64::from(k % width) + 0.5) / f64::from(width);
                let v = (f64::from(k / width) + 0.5) / f64::from(height);
                view.closest_hit(&frame.ray(u, v, aspect), 0.0, f64::INFINITY).map(|h| h.object)
            })
            .collect();
        let in_view: BTreeSet<usize> = (0..view.objects().len())
            .filter(|&i| match view.objects()[i].shape {
                Shape::Sphere { sphere, .. } => frame.sees(sphere.center, aspect),
                Shape::Quad { .. } => false,
            })
            .collect();
        let seen_in_view = seen.intersection(&in_view).count();
        total += seen_in_view as f64 / in_view.len().max(1) as f64;
    }
    Ok(total / VISIBILITY_CAMERAS as f64)
}

fn clutter_table(rows: &[ClutterRow]) -> String {
    let mut text = String::from(
        "| N | τ = Np | gap measured | ± s.e. | (1−p)^N | e^(−τ) | depth complexity | law τ | visible fraction |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let _ = writeln!(
            text,
            "| {} | {:.3} | {:.4} | {:.4} | {:.4} | {:.4} | {:.3} | {:.3} | {:.3} |",
            r.count,
            r.optical_depth,
            r.gap_fraction,
            r.gap_standard_error,
            r.gap_exact,
            r.gap_beer_lambert,
            r.depth_complexity,
            r.optical_depth,
            r.visible_fraction
        );
    }
    text
}

// ---------------------------------------------------------------------------------------------
// (b) fog

/// Extinction coefficients of the fog experiment.
pub const FOG_SIGMAS: [f64; 3] = [0.05, 0.1, 0.2];
/// Target distances (along the optical axis) of the fog experiment.
pub const FOG_DISTANCES: [f64; 6] = [1.0, 2.0, 5.0, 10.0, 20.0, 40.0];
/// Direction of the probe ray: off axis, so the path length is `d / cos θ`, not `d`.
fn fog_probe_direction() -> DVec3 {
    DVec3::new(0.1, 0.05, -1.0).normalize()
}

/// One measurement of the fog experiment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FogRow {
    /// `σ_t` (all scattering).
    pub sigma_t: f64,
    /// Target distance along the axis.
    pub distance: f64,
    /// Measured transmittance: (radiance with the target lit − radiance with it dark) / emitted.
    pub transmittance: f64,
    /// Beer–Lambert `e^(−σ_t ℓ)`, `ℓ` = path length along the probe ray.
    pub law: f64,
    /// The airlight added by a lamp beside the path (radiance with the target dark).
    pub airlight: f64,
    /// Apparent (Weber) contrast of the lit target against the airlight, `(L_lit − L_dark)/L_dark`.
    pub apparent_contrast: f64,
}

/// The fog measurement's scene: an emitter wall of radiance `target_radiance` at `distance`, a
/// lamp beside the path, and fog `σ_s = sigma_t`.
fn fog_target_scene(sigma_t: f64, distance: f64, target_radiance: f64) -> Result<Scene, InputError> {
    let lamp = PointLight { position: DVec3::new(2.0, 1.5, -distance / 2.0), intensity: DVec3::splat(5.0) };
    let target = Material::Emitter { radiance: DVec3::splat(target_radiance) };
    catalogue::wall_in_fog(distance, target, lamp, sigma_t)
}

/// Measures one fog row by tracing the probe ray through the lit and the dark target.
///
/// # Errors
/// [`InputError`] for an invalid `sigma_t` or `distance`.
pub fn fog_row(sigma_t: f64, distance: f64) -> Result<FogRow, InputError> {
    let probe = Ray { origin: DVec3::ZERO, dir: fog_probe_direction() };
    let radiance = |target: f64, in_scattering: bool| -> Result<f64, InputError> {
        let scene = fog_target_scene(sigma_t, distance, target)?;
        let plan = analyze(&scene).plan.with(Pass::InScattering, in_scattering);
        let tracer = Tracer::new(&scene, plan);
        let whitted = Integrator::Whitted { max_depth: 0 };
        Ok(tracer.radiance(whitted, &probe, 0.0, &mut Sampler::new(0, 0, 0)).x)
    };
    // The lamp's airlight is common to the lit and the dark target and cancels in the difference;
    // the lit target's own glow (an area light in fog) is left out: the contrast law is about
    // what the medium does to a target's light on its way to the eye, not about the target
    // lighting the fog.
    let transmittance = radiance(1.0, false)? - radiance(0.0, false)?;
    let dark = radiance(0.0, true)?;
    let path_length = distance / -probe.dir.z;
    Ok(FogRow {
        sigma_t,
        distance,
        transmittance,
        law: (-sigma_t * path_length).exp(),
        airlight: dark,
        apparent_contrast: transmittance / dark,
    })
}

/// The airlight comparison of the fog chapter: `(β, D, γ°, closed form, 32 steps, 4096 steps)`.
///
/// # Errors
/// [`InputError`] never for the built-in cases.
pub fn airlight_rows() -> Result<Vec<[f64; 6]>, InputError> {
    let mut rows = Vec::new();
    for beta in [0.05, 0.3, 1.0] {
        for (d, gamma_degrees) in [(1.0, 5.0), (1.0, 90.0), (5.0, 5.0), (5.0, 90.0)] {
            let gamma = f64::to_radians(gamma_degrees);
            rows.push([
                beta,
                d,
                gamma_degrees,
                airlight_closed_form(beta, 1.0, d, gamma, 20.0)?,
                airlight_traced(beta, d, gamma, 20.0, IN_SCATTER_STEPS)?,
                airlight_traced(beta, d, gamma, 20.0, 4096)?,
            ]);
        }
    }
    Ok(rows)
}

fn fog_table(rows: &[FogRow]) -> String {
    let mut text = String::from(
        "| σ_t | d | T measured | e^(−σ_t ℓ) | rel. diff | airlight | apparent contrast |\n|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let _ = writeln!(
            text,
            "| {} | {} | {:.6e} | {:.6e} | {} | {:.4e} | {:.4e} |",
            r.sigma_t,
            r.distance,
            r.transmittance,
            r.law,
            // Rounding-level differences vary in the last bit between platforms' `exp`.
            if (r.transmittance / r.law - 1.0).abs() < 1e-13 {
                "< 1e-13".to_string()
            } else {
                format!("{:.1e}", (r.transmittance / r.law - 1.0).abs())
            },
            r.airlight,
            r.apparent_contrast
        );
    }
    text
}

fn airlight_table(rows: &[[f64; 6]]) -> String {
    let mut text = String::from(
        "| β | D | γ (°) | closed form | renderer, 32 steps | rel. err | renderer, 4096 steps | rel. err |\n|---|---|---|---|---|---|---|---|\n",
    );
    for [beta, d, gamma, closed, coarse, fine] in rows {
        let _ = writeln!(
            text,
            "| {beta} | {d} | {gamma} | {closed:.6e} | {coarse:.6e} | {:.1e} | {fine:.6e} | {:.1e} |",
            (coarse / closed - 1.0).abs(),
            (fine / closed - 1.0).abs()
        );
    }
    text
}

// ---------------------------------------------------------------------------------------------
// (c) mirrors

/// Camera displacements (along `+x`) of the mirror experiment.
pub const MIRROR_STEPS: [f64; 5] = [0.005, 0.01, 0.02, 0.05, 0.1];
/// Image size and samples of the mirror and motion experiments.
const METRIC_SIZE: (u32, u32) = (64, 48);
const MIRROR_SPP: u32 = 4;

/// Image sensitivity `S(δ) = mean_p |I_p(c + δ x̂) − I_p(c)| / δ` over the pixels where the
/// undisplaced camera sees a sphere, for the mirror scene and its diffuse twin, one
/// `(δ, S_mirror, S_diffuse)` per step. Whitted, 64×48 pixels, 4 spp with the
/// same per-pixel random numbers at every camera position (common random numbers).
///
/// # Errors
/// [`InputError`] never for the built-in numbers.
pub fn mirror_sensitivity() -> Result<Vec<(f64, f64, f64)>, InputError> {
    let mask = sphere_pixels(&catalogue::mirror_spheres(true)?);
    let masked_change = |a: &Image, b: &Image| {
        let (a, b) = (a.luminance(), b.luminance());
        let sum: f64 = (0..a.len()).filter(|&i| mask[i]).map(|i| (a[i] - b[i]).abs()).sum();
        sum / mask.iter().filter(|&&m| m).count() as f64
    };
    let sensitivity = |mirror: bool| -> Result<Vec<f64>, InputError> {
        let scene = catalogue::mirror_spheres(mirror)?;
        let base = render_metric(&scene, MIRROR_SPP, 1)?;
        MIRROR_STEPS
            .iter()
            .map(|&delta| {
                let moved = scene.with_camera(catalogue::mirror_camera(DVec3::X * delta))?;
                Ok(masked_change(&render_metric(&moved, MIRROR_SPP, 1)?, &base) / delta)
            })
            .collect()
    };
    let (mirror, diffuse) = (sensitivity(true)?, sensitivity(false)?);
    Ok(MIRROR_STEPS.iter().zip(mirror.iter().zip(&diffuse)).map(|(&d, (&m, &f))| (d, m, f)).collect())
}

/// Which pixels of the metric-size image see a sphere first (rays through pixel centres).
fn sphere_pixels(scene: &Scene) -> Vec<bool> {
    let (width, height) = METRIC_SIZE;
    let frame = crate::render::camera::CameraFrame::new(scene.camera());
    let aspect = f64::from(width) / f64::from(height);
    (0..width * height)
        .map(|k| {
            let u = (f64::from(k % width) + 0.5) / f64::from(width);
            let v = (f64::from(k / width) + 0.5) / f64::from(height);
            scene
                .closest_hit(&frame.ray(u, v, aspect), 0.0, f64::INFINITY)
                .is_some_and(|h| matches!(scene.objects()[h.object].shape, Shape::Sphere { .. }))
        })
        .collect()
}

/// Whitted render of `scene` at the metric size with its own plan.
fn render_metric(scene: &Scene, spp: u32, seed: u64) -> Result<Image, InputError> {
    let (width, height) = METRIC_SIZE;
    let settings = Settings { seed, ..Settings::whitted(width, height, spp, analyze(scene).plan) };
    Ok(render(scene, &settings, &|_| {}).expect("the metric settings are within limits"))
}

fn mirror_table(rows: &[(f64, f64, f64)]) -> String {
    let mut text = String::from("| δ | S mirror | S diffuse | ratio |\n|---|---|---|---|\n");
    for (delta, mirror, diffuse) in rows {
        let _ = writeln!(text, "| {delta} | {mirror:.4e} | {diffuse:.4e} | {:.3} |", mirror / diffuse);
    }
    text
}

/// How fast nearby rays separate between mirrors: curved (chaotic) versus flat (linear).
#[derive(Debug, Clone, PartialEq)]
pub struct MirrorDivergence {
    /// Ray pairs launched at the four mirror spheres.
    pub trials: usize,
    /// Pairs that stayed trapped for at least 4 bounces with separation below 1e-3.
    pub trapped: usize,
    /// Median separation growth factor per bounce among the trapped pairs.
    pub median_factor: f64,
    /// Between two parallel flat mirrors: `(bounces, measured separation, law k h δ / cos²θ)`.
    pub flat: Vec<(usize, f64, f64)>,
}

/// Ray pairs of the divergence measurement.
pub const DIVERGENCE_TRIALS: usize = 2000;

/// Angular offset between the two rays of a pair (radians).
const PAIR_OFFSET: f64 = 1e-12;

/// The hit points of a ray bouncing between the mirrors of `scene`, at most `bounces` of them.
fn mirror_path(scene: &Scene, mut ray: Ray<f64>, bounces: usize) -> Vec<DVec3> {
    let mut points = Vec::new();
    while points.len() < bounces {
        let Some(hit) = scene.closest_hit(&ray, 0.0, f64::INFINITY) else {
            break;
        };
        let dir = crate::geometry::sphere::reflect::<f64>(ray.dir, hit.normal);
        ray = Ray { origin: crate::geometry::sphere::spawn_origin::<f64>(hit.point, hit.normal, dir), dir };
        points.push(hit.point);
    }
    points
}

/// Measures [`MirrorDivergence`]: `trials` ray pairs `1e-12` rad apart aimed from 6 units away
/// at four mirror spheres (radius 1, tetrahedron with edge 2.2, the reference note's set-up),
/// and one pair at 30° between two parallel mirrors 1 apart.
///
/// # Errors
/// [`InputError`] never for the built-in numbers.
pub fn mirror_divergence(trials: usize) -> Result<MirrorDivergence, InputError> {
    let mirror = Material::Mirror { reflectance: DVec3::ONE };
    let corners = [[1.0, 1.0, 1.0], [1.0, -1.0, -1.0], [-1.0, 1.0, -1.0], [-1.0, -1.0, 1.0]];
    // Vertices of the tetrahedron at distance √3 from its centre have edge √8; scale to 2.2.
    let scale = 2.2 / 8f64.sqrt();
    let spheres = corners
        .iter()
        .map(|&c| Ok(Object::sphere(Sphere::new(DVec3::from(c) * scale, 1.0)?, mirror)))
        .collect::<Result<Vec<_>, InputError>>()?;
    let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 6.0), DVec3::ZERO, 40.0);
    let cluster = Scene::new(camera, spheres, vec![], None, DVec3::ZERO)?;
    let mut sampler = Sampler::new(7, 0, 3);
    let mut rates = Vec::new();
    for _ in 0..trials {
        let z = 2.0 * sampler.uniform() - 1.0;
        let phi = 2.0 * PI * sampler.uniform();
        let ring = (1.0 - z * z).sqrt();
        let origin = DVec3::new(ring * phi.cos(), ring * phi.sin(), z) * 6.0;
        let aim = DVec3::new(sampler.uniform(), sampler.uniform(), sampler.uniform()) * 0.3 - DVec3::splat(0.15);
        let dir = (aim - origin).normalize();
        let perpendicular = dir.cross(DVec3::new(0.3, 0.5, 0.8)).normalize();
        let twin = (dir + perpendicular * PAIR_OFFSET).normalize();
        let first = mirror_path(&cluster, Ray { origin, dir }, 60);
        let second = mirror_path(&cluster, Ray { origin, dir: twin }, 60);
        let separations: Vec<f64> = first.iter().zip(&second).map(|(a, b)| (*a - *b).length()).collect();
        // Stay in the linear regime: the last bounce still closer than 1e-3.
        let linear = separations.iter().take_while(|&&d| d < 1e-3).count();
        if linear >= 4 && separations[0] > 0.0 {
            let k = linear - 1;
            rates.push((separations[k] / separations[0]).ln() / k as f64);
        }
    }
    rates.sort_by(f64::total_cmp);
    let median_factor = rates.get(rates.len() / 2).map_or(f64::NAN, |rate| rate.exp());
    Ok(MirrorDivergence { trials, trapped: rates.len(), median_factor, flat: flat_mirror_separation(mirror)? })
}

/// Two parallel mirrors `y = 0` and `y = 1`; a pair of rays at 30° from the normal.
fn flat_mirror_separation(mirror: Material) -> Result<Vec<(usize, f64, f64)>, InputError> {
    let plane =
        |y: f64| Object::quad(DVec3::new(-1e3, y, -1e3), DVec3::new(0.0, 0.0, 2e3), DVec3::new(2e3, 0.0, 0.0), mirror);
    let camera = Camera::looking_at(DVec3::new(0.0, 0.5, 0.0), DVec3::new(1.0, 0.5, 0.0), 40.0);
    let pair = Scene::new(camera, vec![plane(0.0), plane(1.0)], vec![], None, DVec3::ZERO)?;
    let theta = 30f64.to_radians();
    let ray = |angle: f64| Ray {
        origin: DVec3::new(0.0, 0.0, 0.0) + DVec3::Y * 1e-9,
        dir: DVec3::new(angle.sin(), angle.cos(), 0.0),
    };
    let first = mirror_path(&pair, ray(theta), 40);
    let second = mirror_path(&pair, ray(theta + PAIR_OFFSET), 40);
    Ok([10usize, 40]
        .iter()
        .map(|&k| {
            let measured = (first[k - 1] - second[k - 1]).length();
            // Hit k lies k units of height from the start: x = k tanθ, dx/dθ = k / cos²θ.
            let law = k as f64 * PAIR_OFFSET / theta.cos().powi(2);
            (k, measured, law)
        })
        .collect())
}

fn divergence_table(result: &MirrorDivergence) -> String {
    let mut text = format!(
        "four mirror spheres: {} of {} pairs trapped ≥ 4 bounces; median growth ×{:.2} per bounce (reference note: ×2.45)\n\n| flat mirrors, bounces | separation | law k δ / cos²θ |\n|---|---|---|\n",
        result.trapped, result.trials, result.median_factor
    );
    for (k, measured, law) in &result.flat {
        let _ = writeln!(text, "| {k} | {measured:.2e} | {law:.2e} |");
    }
    text
}

// ---------------------------------------------------------------------------------------------
// (d) change over time

/// Speed of the moving ball (units per unit time) and number of instantaneous frames.
const MOTION_SPEED: f64 = 2.0;
const MOTION_FRAMES: usize = 10;
/// Samples per pixel of the noise measurement and of its reference.
pub const MOTION_SPP: [u32; 6] = [1, 2, 4, 8, 16, 32];
const REFERENCE_SPP: u32 = 256;
/// The noise level for which the needed spp is reported (RMS luminance error).
pub const NOISE_TARGET: f64 = 0.005;

/// Image change between consecutive instantaneous frames of the moving ball.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionChange {
    /// Mean absolute luminance change per frame (time step `1/MOTION_FRAMES`).
    pub mean_change: Vec<f64>,
    /// Fraction of pixels whose luminance changes by more than 0.05 per frame.
    pub changed_fraction: Vec<f64>,
    /// The ball's image speed, in pixels per frame, at the image centre's depth.
    pub pixels_per_frame: f64,
}

/// Renders instantaneous frames `t = k/10`, `k = 0…10`, and measures the change per step.
///
/// # Errors
/// [`InputError`] never for the built-in numbers.
pub fn motion_change() -> Result<MotionChange, InputError> {
    let frames: Vec<Image> = (0..=MOTION_FRAMES)
        .map(|k| {
            let t = k as f64 / MOTION_FRAMES as f64;
            let scene = catalogue::moving_ball_with_shutter(MOTION_SPEED, (t, t))?;
            render_metric(&scene, 1, 1)
        })
        .collect::<Result<_, _>>()?;
    let mut mean_change = Vec::new();
    let mut changed_fraction = Vec::new();
    for pair in frames.windows(2) {
        mean_change.push(pair[1].mean_abs_difference(&pair[0]));
        let (a, b) = (pair[0].luminance(), pair[1].luminance());
        let changed = a.iter().zip(&b).filter(|(x, y)| (*x - *y).abs() > 0.05).count();
        changed_fraction.push(changed as f64 / a.len() as f64);
    }
    let camera = catalogue::moving_ball(MOTION_SPEED)?.camera().to_owned();
    let depth = (DVec3::new(0.0, 0.5, -3.0) - camera.eye).length();
    let focal_pixels = f64::from(METRIC_SIZE.1) / 2.0 / (camera.vfov_degrees.to_radians() / 2.0).tan();
    Ok(MotionChange {
        mean_change,
        changed_fraction,
        pixels_per_frame: MOTION_SPEED / MOTION_FRAMES as f64 * focal_pixels / depth,
    })
}

/// RMS error against a 256-spp reference (another seed) versus spp, for the moving and the
/// resting ball; the free log-log slope, the constant `c` of `RMSE² ≈ c² (1/spp + 1/256)` (the
/// second term is the reference's own noise), and from it the spp needed for [`NOISE_TARGET`].
#[derive(Debug, Clone, PartialEq)]
pub struct MotionNoise {
    /// `(spp, RMSE moving, RMSE resting)`.
    pub rows: Vec<(u32, f64, f64)>,
    /// Fitted log-log slope for the moving ball (free fit).
    pub slope_moving: f64,
    /// Fitted log-log slope for the resting ball.
    pub slope_resting: f64,
    /// `c` for the moving ball.
    pub constant_moving: f64,
    /// `c` for the resting ball.
    pub constant_resting: f64,
}

impl MotionNoise {
    /// Samples per pixel needed for RMSE ≤ `target`: `(c / target)²`, rounded up.
    #[must_use]
    pub fn spp_needed(constant: f64, target: f64) -> f64 {
        (constant / target).powi(2).ceil()
    }
}

/// Measures [`MotionNoise`].
///
/// # Errors
/// [`InputError`] never for the built-in numbers.
pub fn motion_noise() -> Result<MotionNoise, InputError> {
    let curve = |speed: f64| -> Result<Vec<f64>, InputError> {
        let scene = catalogue::moving_ball(speed)?;
        let reference = render_metric(&scene, REFERENCE_SPP, 1_000_003)?;
        MOTION_SPP.iter().map(|&spp| Ok(render_metric(&scene, spp, 1)?.rms_difference(&reference))).collect()
    };
    let (moving, resting) = (curve(MOTION_SPEED)?, curve(0.0)?);
    let fit = |errors: &[f64]| {
        let xs: Vec<f64> = MOTION_SPP.iter().map(|&s| f64::from(s).ln()).collect();
        let ys: Vec<f64> = errors.iter().map(|e| e.ln()).collect();
        let n = xs.len() as f64;
        let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
        let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
        let sxx: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
        // The reference has noise of its own: E[RMSE²] = c² (1/spp + 1/REFERENCE_SPP), so c² is
        // the mean of RMSE² / (1/spp + 1/REFERENCE_SPP).
        let c_squared = MOTION_SPP
            .iter()
            .zip(errors)
            .map(|(&spp, e)| e * e / (1.0 / f64::from(spp) + 1.0 / f64::from(REFERENCE_SPP)))
            .sum::<f64>()
            / n;
        (sxy / sxx, c_squared.sqrt())
    };
    let ((slope_moving, constant_moving), (slope_resting, constant_resting)) = (fit(&moving), fit(&resting));
    Ok(MotionNoise {
        rows: MOTION_SPP.iter().zip(moving.iter().zip(&resting)).map(|(&s, (&m, &r))| (s, m, r)).collect(),
        slope_moving,
        slope_resting,
        constant_moving,
        constant_resting,
    })
}

fn motion_tables(change: &MotionChange, noise: &MotionNoise) -> String {
    let mut text = format!(
        "image speed of the ball: {:.3} px/frame\n\n| step | mean abs change | pixels changed > 0.05 |\n|---|---|---|\n",
        change.pixels_per_frame
    );
    for (k, (m, f)) in change.mean_change.iter().zip(&change.changed_fraction).enumerate() {
        let _ = writeln!(text, "| {} → {} | {m:.4e} | {f:.4} |", k, k + 1);
    }
    text.push_str("\n| spp | RMSE moving | RMSE resting |\n|---|---|---|\n");
    for (spp, m, r) in &noise.rows {
        let _ = writeln!(text, "| {spp} | {m:.4e} | {r:.4e} |");
    }
    let _ = writeln!(
        text,
        "\nslope moving {:.3}, resting {:.3}; c moving {:.4e}, resting {:.4e}; spp for RMSE {NOISE_TARGET}: moving {}, resting {}",
        noise.slope_moving,
        noise.slope_resting,
        noise.constant_moving,
        noise.constant_resting,
        MotionNoise::spp_needed(noise.constant_moving, NOISE_TARGET),
        MotionNoise::spp_needed(noise.constant_resting, NOISE_TARGET)
    );
    text
}

// ---------------------------------------------------------------------------------------------
// answers, figures

/// The Q1 answers: the four hard scenes and what makes each hard, with the law each obeys.
/// Cheap (no rendering); the measured tables are in the chapter and in `hw3 figures`.
///
/// # Examples
/// ```
/// let answers = hw3::q1_hard_scenes::answers();
/// assert_eq!(answers.question, "q1");
/// assert!(answers.text.contains("e^(−σ_t d)"));
/// ```
#[must_use]
pub fn answers() -> Answers {
    let visual_range = |sigma: f64| 50f64.ln() / sigma;
    let text = format!(
        "(a) clutter: the gap fraction of a random forest falls as (1−p)^N ≈ e^(−nπa²Z) and the depth complexity grows as nπa²Z; measured within 2 standard errors over N = 250…4000 (table q1_clutter_table).\n\
         (b) fog: contrast to an object falls as e^(−σ_t d) (the renderer reproduces it to rounding, below 1e-13), visual range ln 50/σ_t = {:.1} / {:.1} / {:.1} units for σ_t = 0.05 / 0.1 / 0.2, and the lamp's glow adds airlight that matches Sun et al.'s closed form (1e-2 at 32 steps, < 1e-6 at 4096).\n\
         (c) mirrors: nearby rays separate ×2.55 per bounce between four mirror spheres (reference note ×2.45) but only linearly between flat mirrors; over the pixels that see the spheres, the image changes 1.1–1.6× faster per unit camera move than the same spheres made diffuse (Whitted, 64×48).\n\
         (d) change over time: the moving ball shifts 2.4 px per frame (above the 0.5 px/frame limit for a 1-px feature), and its motion blur needs more samples per pixel than the still scene for the same noise (table q1_motion_table).",
        visual_range(0.05),
        visual_range(0.1),
        visual_range(0.2)
    );
    Answers { question: "q1", title: "Four scenes that are hard to render, and why (measured)", text }
}

/// One series of a chart: points (markers) or a line.
struct Series {
    label: String,
    points: Vec<(f64, f64)>,
    line: bool,
    color: RGBColor,
}

/// Draws `series` in a chart with the given axes (linear or log ranges).
fn chart<X, Y>(
    file_name: &str,
    caption: &str,
    (x_label, y_label): (&str, &str),
    (x_range, y_range): (X, Y),
    legend: SeriesLabelPosition,
    series: &[Series],
) -> Result<Figure, PlotError>
where
    X: plotters::coord::ranged1d::AsRangedCoord<Value = f64>,
    Y: plotters::coord::ranged1d::AsRangedCoord<Value = f64>,
    X::CoordDescType: plotters::coord::ranged1d::ValueFormatter<f64>,
    Y::CoordDescType: plotters::coord::ranged1d::ValueFormatter<f64>,
{
    plot::svg_figure(file_name, (640, 420), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(caption, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x_range, y_range)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .label_style(("sans-serif", 13))
            .light_line_style(TRANSPARENT)
            .x_labels(12)
            .y_labels(8)
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .draw()
            .map_err(err)?;
        for s in series {
            let color = s.color;
            if s.line {
                chart
                    .draw_series(LineSeries::new(s.points.iter().copied(), color.stroke_width(2)))
                    .map_err(err)?
                    .label(s.label.as_str())
                    .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], color));
            } else {
                chart
                    .draw_series(s.points.iter().map(|&p| Circle::new(p, 4, color.filled())))
                    .map_err(err)?
                    .label(s.label.as_str())
                    .legend(move |(x, y)| Circle::new((x + 8, y), 4, color.filled()));
            }
        }
        chart
            .configure_series_labels()
            .position(legend)
            .label_font(("sans-serif", 13))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(err)
    })
}

fn series(label: impl Into<String>, points: Vec<(f64, f64)>, line: bool, color: RGBColor) -> Series {
    Series { label: label.into(), points, line, color }
}

/// An axis label: the value rounded to six decimals, so that `0.6000000001` prints `0.6`.
fn tick(value: &f64) -> String {
    format!("{}", (value * 1e6).round() / 1e6)
}

/// A text file placed among the figures (the chapter includes it as a generated table).
fn table_figure(file_name: &str, text: String) -> Figure {
    Figure { file_name: file_name.into(), bytes: text.into_bytes() }
}

/// Renders `scene` (Whitted, its own plan) at the figure size and encodes it as a PNG figure.
fn render_figure(file_name: &str, scene: &Scene, spp: u32) -> Result<Figure, PlotError> {
    let settings = Settings::whitted(160, 120, spp, analyze(scene).plan);
    let image = render(scene, &settings, &|_| {}).expect("the figure settings are within limits");
    plot::png_bytes(file_name, &image.to_rgb8())
}

fn input_error(figure: &str, e: InputError) -> PlotError {
    PlotError::Draw { figure: figure.into(), message: e.to_string() }
}

/// The clutter figures: render, gap-fraction chart, table.
fn clutter_figures(rows: &[ClutterRow]) -> Result<Vec<Figure>, PlotError> {
    let forest = catalogue::clutter_forest(1500, 1).map_err(|e| input_error("q1_clutter.png", e))?;
    let counts: Vec<f64> = rows.iter().map(|r| r.count as f64).collect();
    let pick =
        |f: fn(&ClutterRow) -> f64| -> Vec<(f64, f64)> { counts.iter().copied().zip(rows.iter().map(f)).collect() };
    let gap = chart(
        "q1_clutter_gap.svg",
        "Clutter: gap fraction and visible fraction vs sphere count",
        ("spheres N in the slab", "fraction"),
        ((200.0..5000.0).log_scale(), 0.0..1.05),
        SeriesLabelPosition::LowerLeft,
        &[
            series("gap fraction, measured", pick(|r| r.gap_fraction), false, PALETTE[0]),
            series("law (1−p)^N", pick(|r| r.gap_exact), true, PALETTE[0]),
            series("visible fraction (3 cameras, 64×48)", pick(|r| r.visible_fraction), false, PALETTE[1]),
            series(
                "centre-ray estimate (1 − e^(−τ))/τ",
                pick(|r| -(-r.optical_depth).exp_m1() / r.optical_depth),
                true,
                PALETTE[1],
            ),
        ],
    )?;
    Ok(vec![
        render_figure("q1_clutter.png", &forest, 4)?,
        gap,
        table_figure("q1_clutter_table.md", clutter_table(rows)),
    ])
}

fn fog_rows() -> Result<Vec<FogRow>, InputError> {
    FOG_SIGMAS.iter().flat_map(|&s| FOG_DISTANCES.iter().map(move |&d| fog_row(s, d))).collect()
}

fn fog_figures(rows: &[FogRow]) -> Result<Vec<Figure>, PlotError> {
    let scene = |sigma| catalogue::fog_street(sigma).map_err(|e| input_error("q1_fog.png", e));
    let mut plotted = Vec::new();
    for (k, &sigma) in FOG_SIGMAS.iter().enumerate() {
        let of_sigma = rows.iter().filter(|r| r.sigma_t == sigma);
        plotted.push(series(
            format!("σ_t = {sigma}: measured"),
            of_sigma.clone().map(|r| (r.distance, r.transmittance)).collect(),
            false,
            PALETTE[k],
        ));
        let path_factor = 1.0 / -fog_probe_direction().z;
        plotted.push(series(
            format!("e^(−σ_t ℓ), σ_t = {sigma}"),
            (0..=80)
                .map(|i| {
                    let d = f64::from(i) * 0.5;
                    (d, (-sigma * d * path_factor).exp())
                })
                .collect(),
            true,
            PALETTE[k],
        ));
    }
    let transmittance = chart(
        "q1_fog_transmittance.svg",
        "Fog: contrast (transmittance) vs distance",
        ("target distance d", "transmittance T = ΔL / L_emitted"),
        (0.0..41.0, (1e-4..1.2).log_scale()),
        SeriesLabelPosition::LowerLeft,
        &plotted,
    )?;
    Ok(vec![
        render_figure("q1_fog.png", &scene(0.08)?, 2)?,
        render_figure("q1_fog_clear.png", &scene(0.0)?, 2)?,
        transmittance,
        table_figure("q1_fog_table.md", fog_table(rows)),
        table_figure(
            "q1_airlight_table.md",
            airlight_table(&airlight_rows().map_err(|e| input_error("q1_airlight_table.md", e))?),
        ),
    ])
}

fn mirror_figures(rows: &[(f64, f64, f64)], divergence: &MirrorDivergence) -> Result<Vec<Figure>, PlotError> {
    let scene = |m| catalogue::mirror_spheres(m).map_err(|e| input_error("q1_mirrors.png", e));
    let sensitivity = chart(
        "q1_mirror_sensitivity.svg",
        "Mirrors: image change per unit camera move (sphere pixels)",
        ("camera displacement δ", "S(δ) = mean |ΔI| / δ"),
        ((0.004..0.12).log_scale(), 0.0..0.6),
        SeriesLabelPosition::LowerRight,
        &[
            series("mirror spheres", rows.iter().map(|r| (r.0, r.1)).collect(), true, PALETTE[0]),
            series("same spheres, diffuse", rows.iter().map(|r| (r.0, r.2)).collect(), true, PALETTE[1]),
        ],
    )?;
    Ok(vec![
        render_figure("q1_mirrors.png", &scene(true)?, 4)?,
        render_figure("q1_mirrors_diffuse.png", &scene(false)?, 4)?,
        sensitivity,
        table_figure("q1_mirror_table.md", mirror_table(rows)),
        table_figure("q1_mirror_divergence_table.md", divergence_table(divergence)),
    ])
}

fn motion_figures(change: &MotionChange, noise: &MotionNoise) -> Result<Vec<Figure>, PlotError> {
    let scene = |speed| catalogue::moving_ball(speed).map_err(|e| input_error("q1_motion.png", e));
    let law = |c: f64| -> Vec<(f64, f64)> { [1.0, 32.0].iter().map(|&s| (s, c / f64::sqrt(s))).collect() };
    let curve = chart(
        "q1_motion_noise.svg",
        "Motion blur: RMS error vs samples per pixel",
        ("samples per pixel", "RMS luminance error"),
        ((0.8..40.0).log_scale(), (4e-3..5e-2).log_scale()),
        SeriesLabelPosition::LowerLeft,
        &[
            series("moving ball", noise.rows.iter().map(|r| (f64::from(r.0), r.1)).collect(), false, PALETTE[0]),
            series("c/√spp, moving", law(noise.constant_moving), true, PALETTE[0]),
            series("ball at rest", noise.rows.iter().map(|r| (f64::from(r.0), r.2)).collect(), false, PALETTE[1]),
            series("c/√spp, at rest", law(noise.constant_resting), true, PALETTE[1]),
        ],
    )?;
    Ok(vec![
        render_figure("q1_motion.png", &scene(MOTION_SPEED)?, 64)?,
        render_figure("q1_motion_still.png", &scene(0.0)?, 4)?,
        curve,
        table_figure("q1_motion_table.md", motion_tables(change, noise)),
    ])
}

/// One measurement of the accuracy-versus-time benchmark (`benches/render.rs`).
#[derive(Debug, Clone, PartialEq)]
struct AccuracyRow {
    scene: String,
    integrator: String,
    spp: f64,
    seconds: f64,
    rmse: f64,
}

/// Parses `docs/data/q1_accuracy.csv` (header `scene,integrator,spp,seconds,rmse`).
fn parse_accuracy(csv: &str) -> Result<Vec<AccuracyRow>, String> {
    csv.lines()
        .skip(1)
        .filter(|line| !line.trim().is_empty())
        .map(|line| {
            let fields: Vec<&str> = line.split(',').collect();
            let number = |i: usize| -> Result<f64, String> {
                fields
                    .get(i)
                    .and_then(|f| f.trim().parse().ok())
                    .ok_or_else(|| format!("q1_accuracy.csv: bad field {i} in `{line}`"))
            };
            Ok(AccuracyRow {
                scene: fields.first().unwrap_or(&"").to_string(),
                integrator: fields.get(1).unwrap_or(&"").to_string(),
                spp: number(2)?,
                seconds: number(3)?,
                rmse: number(4)?,
            })
        })
        .collect()
}

/// The accuracy-versus-samples and accuracy-versus-seconds charts, from the committed CSV that
/// the benchmark writes (timings come only from benchmarks, so `figures()` stays deterministic).
fn accuracy_figures(rows: &[AccuracyRow]) -> Result<Vec<Figure>, PlotError> {
    let scenes: Vec<&str> = rows.iter().fold(Vec::new(), |mut names, r| {
        if !names.contains(&r.scene.as_str()) {
            names.push(r.scene.as_str());
        }
        names
    });
    let by = |x: fn(&AccuracyRow) -> f64| -> Vec<Series> {
        let mut out = Vec::new();
        for (k, scene) in scenes.iter().enumerate() {
            for (integrator, line) in [("path", true), ("whitted", false)] {
                out.push(series(
                    format!("{scene}, {integrator}"),
                    rows.iter()
                        .filter(|r| r.scene == *scene && r.integrator == integrator)
                        .map(|r| (x(r), r.rmse))
                        .collect(),
                    line,
                    PALETTE[k % PALETTE.len()],
                ));
            }
        }
        out
    };
    let range = |values: Vec<f64>| {
        let low = values.iter().copied().fold(f64::INFINITY, f64::min);
        let high = values.iter().copied().fold(0.0, f64::max);
        (low * 0.8)..(high * 1.25)
    };
    let rmse_range = || range(rows.iter().map(|r| r.rmse).collect());
    Ok(vec![
        chart(
            "q1_accuracy_spp.svg",
            "Error against a converged path-traced reference vs samples per pixel",
            ("samples per pixel", "RMS luminance error"),
            (range(rows.iter().map(|r| r.spp).collect()).log_scale(), rmse_range().log_scale()),
            SeriesLabelPosition::LowerLeft,
            &by(|r| r.spp),
        )?,
        chart(
            "q1_accuracy_seconds.svg",
            "Error vs render time (benchmark machine, 48×36 pixels)",
            ("seconds", "RMS luminance error"),
            (range(rows.iter().map(|r| r.seconds).collect()).log_scale(), rmse_range().log_scale()),
            SeriesLabelPosition::LowerLeft,
            &by(|r| r.seconds),
        )?,
    ])
}

/// Every Q1 figure: renders of the four scenes and their easy twins (PNG), one chart per metric
/// (SVG), and the measured tables (Markdown, included by the chapter).
///
/// # Errors
/// [`PlotError`] if a chart cannot be drawn.
pub fn figures() -> Result<Vec<Figure>, PlotError> {
    let clutter: Vec<ClutterRow> = CLUTTER_COUNTS
        .iter()
        .map(|&n| clutter_row(n))
        .collect::<Result<_, _>>()
        .map_err(|e| input_error("q1_clutter_table.md", e))?;
    let fog = fog_rows().map_err(|e| input_error("q1_fog_table.md", e))?;
    let mirrors = mirror_sensitivity().map_err(|e| input_error("q1_mirror_table.md", e))?;
    let change = motion_change().map_err(|e| input_error("q1_motion_table.md", e))?;
    let noise = motion_noise().map_err(|e| input_error("q1_motion_table.md", e))?;
    let mut figures = clutter_figures(&clutter)?;
    figures.extend(fog_figures(&fog)?);
    let divergence =
        mirror_divergence(DIVERGENCE_TRIALS).map_err(|e| input_error("q1_mirror_divergence_table.md", e))?;
    figures.extend(mirror_figures(&mirrors, &divergence)?);
    figures.extend(motion_figures(&change, &noise)?);
    let csv_path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/data/q1_accuracy.csv");
    let csv = std::fs::read_to_string(csv_path).map_err(|e| PlotError::Draw {
        figure: "q1_accuracy_spp.svg".into(),
        message: format!("{csv_path}: {e} (run `cargo bench --bench render`)"),
    })?;
    let rows =
        parse_accuracy(&csv).map_err(|message| PlotError::Draw { figure: "q1_accuracy_spp.svg".into(), message })?;
    figures.extend(accuracy_figures(&rows)?);
    Ok(figures)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::scene::Fog;

    fn snapshot(name: &str, text: &str) {
        crate::test_support::insta_settings().bind(|| insta::assert_snapshot!(name, text));
    }

    /// The gap fraction and depth complexity follow the exact law within 3 standard errors of
    /// the mean over forests (a z-test), and the visible fraction falls as the forest grows.
    #[test]
    fn clutter_follows_the_transmission_law() {
        let rows: Vec<ClutterRow> = CLUTTER_COUNTS.iter().map(|&n| clutter_row(n).unwrap()).collect();
        for r in &rows {
            let z = (r.gap_fraction - r.gap_exact) / r.gap_standard_error;
            assert!(z.abs() < 3.0, "N = {}: z = {z:.2}", r.count);
            assert!(((r.gap_exact - r.gap_beer_lambert) / r.gap_exact).abs() < 1e-3);
            // Depth complexity: Poisson count with mean τ per ray; 4 × 2304 rays.
            let depth_error = (r.depth_complexity - r.optical_depth).abs();
            assert!(depth_error < 0.03 * r.optical_depth, "N = {}", r.count);
        }
        assert!(rows.windows(2).all(|w| w[1].visible_fraction < w[0].visible_fraction));
        snapshot("q1_clutter_metrics", &clutter_table(&rows));
    }

    #[test]
    fn fog_transmittance_is_beer_lambert_and_the_airlight_is_sun_et_al() {
        let rows = fog_rows().unwrap();
        for r in &rows {
            assert!((r.transmittance / r.law - 1.0).abs() < 1e-12, "{r:?}");
            assert!(r.airlight > 0.0);
        }
        let airlight = airlight_rows().unwrap();
        for [.., closed, coarse, fine] in &airlight {
            assert!((coarse / closed - 1.0).abs() < 1e-2);
            assert!((fine / closed - 1.0).abs() < 1e-6);
        }
        snapshot("q1_fog_metrics", &fog_table(&rows));
        snapshot("q1_airlight_metrics", &airlight_table(&airlight));
    }

    #[test]
    fn zero_density_fog_renders_exactly_like_no_fog() {
        let clear = catalogue::fog_street(0.0).unwrap();
        let zero = Scene::new(
            *clear.camera(),
            clear.objects().to_vec(),
            clear.point_lights().to_vec(),
            Some(Fog { sigma_a: 0.0, sigma_s: 0.0 }),
            clear.background(),
        )
        .unwrap();
        let settings = Settings::whitted(24, 18, 1, crate::render::passes::Passes::all());
        assert_eq!(render(&zero, &settings, &|_| {}).unwrap(), render(&clear, &settings, &|_| {}).unwrap());
    }

    #[test]
    fn extreme_fog_hides_everything_but_stays_finite() {
        let scene = catalogue::fog_street(1e6).unwrap();
        let image = render(&scene, &Settings::whitted(16, 12, 1, analyze(&scene).plan), &|_| {}).unwrap();
        assert!(image.pixels.iter().all(|p| p.is_finite() && p.min_element() >= 0.0));
        let far = fog_row(1e3, 10.0).unwrap();
        assert_eq!(far.transmittance, 0.0);
    }

    #[test]
    fn mirrors_change_faster_than_the_same_scene_made_diffuse() {
        let rows = mirror_sensitivity().unwrap();
        assert!(rows.iter().all(|&(_, mirror, diffuse)| mirror > diffuse));
        snapshot("q1_mirror_metrics", &mirror_table(&rows));
    }

    #[test]
    fn rays_separate_exponentially_between_curved_mirrors_and_linearly_between_flat_ones() {
        let result = mirror_divergence(DIVERGENCE_TRIALS).unwrap();
        assert!(result.trapped >= 100, "{} trapped", result.trapped);
        assert!(result.median_factor > 2.0 && result.median_factor < 3.0);
        for &(_, measured, law) in &result.flat {
            assert!((measured / law - 1.0).abs() < 0.05, "{measured:e} vs {law:e}");
        }
        snapshot("q1_mirror_divergence", &divergence_table(&result));
    }

    #[test]
    fn motion_changes_every_frame_and_blur_costs_samples() {
        let change = motion_change().unwrap();
        assert!(change.mean_change.iter().all(|&c| c > 0.0));
        assert!(change.pixels_per_frame > 0.5, "faster than the 0.5 px/frame limit");
        let noise = motion_noise().unwrap();
        for slope in [noise.slope_moving, noise.slope_resting] {
            assert!((slope + 0.5).abs() < 0.05, "slope {slope}");
        }
        assert!(noise.constant_moving > noise.constant_resting);
        snapshot("q1_motion_metrics", &motion_tables(&change, &noise));
    }

    #[test]
    fn still_frames_do_not_change() {
        let frames: Vec<Image> = [0.0, 0.5]
            .iter()
            .map(|&t| render_metric(&catalogue::moving_ball_with_shutter(0.0, (t, t)).unwrap(), 1, 1).unwrap())
            .collect();
        assert_eq!(frames[0], frames[1]);
    }

    #[test]
    fn render_thumbnails() {
        let mut text = String::new();
        for (name, scene) in [
            ("mirrors", catalogue::mirror_spheres(true).unwrap()),
            ("fog", catalogue::fog_street(0.08).unwrap()),
            ("motion", catalogue::moving_ball(2.0).unwrap()),
            ("clutter", catalogue::clutter_forest(300, 1).unwrap()),
        ] {
            let image = render_metric(&scene, 2, 1).unwrap();
            let _ = writeln!(text, "{name}:\n{}", image.thumbnail_text(8, 6));
        }
        snapshot("q1_render_thumbnails", &text);
    }

    #[test]
    fn charts_are_deterministic() {
        let rows = [(0.01, 0.5, 0.3), (0.1, 0.3, 0.25)];
        let divergence = MirrorDivergence { trials: 2, trapped: 1, median_factor: 2.5, flat: vec![(10, 1e-11, 1e-11)] };
        let a = mirror_figures(&rows, &divergence).unwrap();
        let b = mirror_figures(&rows, &divergence).unwrap();
        assert_eq!(a, b);
        assert!(String::from_utf8_lossy(&a[2].bytes).contains("mirror spheres"));
    }

    #[test]
    fn accuracy_csv_parses_and_bad_rows_are_errors() {
        let rows = parse_accuracy("scene,integrator,spp,seconds,rmse\nfog,path,4,1e-2,3e-2\n").unwrap();
        assert_eq!(rows.len(), 1);
        assert_eq!((rows[0].spp, rows[0].seconds, rows[0].rmse), (4.0, 1e-2, 3e-2));
        assert!(parse_accuracy("h\nfog,path,x,1,1\n").is_err());
        let charts = accuracy_figures(&rows).unwrap();
        assert_eq!(charts.len(), 2);
    }

    #[test]
    fn chapter_includes_every_generated_table() {
        let chapter = include_str!("../docs/q1_hard_scenes.md");
        for table in [
            "q1_clutter_table.md",
            "q1_fog_table.md",
            "q1_airlight_table.md",
            "q1_mirror_table.md",
            "q1_mirror_divergence_table.md",
            "q1_motion_table.md",
        ] {
            assert!(chapter.contains(&format!("{{{{include:figures/{table}}}}}")), "{table}");
        }
    }
}
