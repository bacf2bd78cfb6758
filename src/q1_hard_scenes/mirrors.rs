//! Q1(c) mirrors: curved mirrors separate nearby rays exponentially (per bounce), flat ones
//! linearly, and the image of mirror spheres changes faster per unit camera move than the same
//! spheres made diffuse.

use super::metric::{METRIC_SIZE, render_metric};
use crate::geometry::sphere::{reflect, spawn_origin};
use crate::geometry::{InputError, Ray, Sphere};
use crate::plot::markdown_table;
use crate::render::Image;
use crate::render::catalogue;
use crate::render::sampling::Sampler;
use crate::render::{
    camera::{Camera, CameraFrame},
    scene::{Material, Object, Scene, Shape},
};
use glam::DVec3;
use std::f64::consts::PI;

/// The angle, in radians, by which the reflected ray of the pixel at a mirror ball's centre turns
/// when a camera looking straight at a ball of radius `radius` steps sideways by `step`: the ray
/// now meets the ball `step` off centre, where the normal has turned by `step/R`, and the
/// reflection turns by twice that (first order in `step/R`).
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::reflection_turn;
/// // A step of 0.01 before a unit ball turns the reflection by 0.02 rad, 1.15°.
/// assert!((reflection_turn(0.01, 1.0).to_degrees() - 1.145_916).abs() < 1e-6);
/// ```
#[must_use]
pub fn reflection_turn(step: f64, radius: f64) -> f64 {
    2.0 * step / radius
}

/// Camera displacements (along `+x`) of the mirror experiment.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::{MIRROR_STEPS, reflection_turn};
/// // Steps of 0.005 to 0.1 before a unit ball turn its central reflection by 0.01 to 0.2 rad.
/// assert_eq!(reflection_turn(MIRROR_STEPS[0], 1.0), 0.01);
/// assert!(MIRROR_STEPS.windows(2).all(|w| w[1] > w[0]));
/// ```
pub const MIRROR_STEPS: [f64; 5] = [0.005, 0.01, 0.02, 0.05, 0.1];
/// Samples per pixel of the mirror experiment (the chapter's table: [`mirror_sensitivity`] at
/// [`MIRROR_STEPS`] and this).
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::{MIRROR_SPP, RENDER_SPP};
/// // Fewer samples than the mirror picture: common random numbers cancel most of the noise
/// // between camera positions.
/// let (_, picture) = RENDER_SPP.iter().find(|(scene, _)| *scene == "mirrors").unwrap();
/// assert!(MIRROR_SPP < *picture);
/// ```
pub const MIRROR_SPP: u32 = 4;

/// Image sensitivity `S(δ) = mean_p |I_p(c + δ x̂) − I_p(c)| / δ` over the pixels where the
/// undisplaced camera sees a sphere, for the mirror scene and its diffuse twin, one
/// `(δ, S_mirror, S_diffuse)` per camera step δ of `steps`. Whitted, 64×48 pixels, `spp` samples
/// per pixel with the same per-pixel random numbers at every camera position (common random
/// numbers): `2 (steps.len() + 1)` renders. The chapter's table is [`MIRROR_STEPS`] at
/// [`MIRROR_SPP`] (twelve renders; `mirrors::tests` pins it).
///
/// # Errors
/// [`InputError::OutOfRange`] for a step that is zero or not finite (the sensitivity divides by
/// it), or a sample count the renderer refuses (0, or past its work bound), found before any
/// render; never for the built-in numbers.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::mirror_sensitivity;
/// assert!(mirror_sensitivity(&[0.0], 1).is_err() && mirror_sensitivity(&[0.02], 0).is_err());
/// // One step of 0.02 at one sample per pixel: four renders.
/// let rows = mirror_sensitivity(&[0.02], 1).unwrap();
/// assert_eq!(rows.len(), 1);
/// let (delta, mirror, diffuse) = rows[0];
/// assert!(delta == 0.02 && mirror > diffuse && diffuse > 0.0);
/// ```
pub fn mirror_sensitivity(steps: &[f64], spp: u32) -> Result<Vec<(f64, f64, f64)>, InputError> {
    if let Some(delta) = steps.iter().find(|d| !(d.is_finite() && **d != 0.0)) {
        return Err(InputError::OutOfRange {
            name: "camera step",
            value: delta.to_string(),
            expected: "finite and non-zero",
        });
    }
    if spp == 0 {
        return Err(InputError::OutOfRange { name: "samples per pixel", value: "0".into(), expected: "at least 1" });
    }
    let mask = sphere_pixels(&catalogue::mirror_spheres(true)?);
    let masked_change = |a: &Image, b: &Image| {
        let (a, b) = (a.luminance(), b.luminance());
        let sum: f64 = (0..a.len()).filter(|&i| mask[i]).map(|i| (a[i] - b[i]).abs()).sum();
        sum / mask.iter().filter(|&&m| m).count() as f64
    };
    let sensitivity = |mirror: bool| -> Result<Vec<f64>, InputError> {
        let scene = catalogue::mirror_spheres(mirror)?;
        let base = render_metric(&scene, spp, 1)?;
        steps
            .iter()
            .map(|&delta| {
                let moved = scene.with_camera(catalogue::mirror_camera(DVec3::X * delta))?;
                Ok(masked_change(&render_metric(&moved, spp, 1)?, &base) / delta)
            })
            .collect()
    };
    let (mirror, diffuse) = (sensitivity(true)?, sensitivity(false)?);
    Ok(steps.iter().zip(mirror.iter().zip(&diffuse)).map(|(&d, (&m, &f))| (d, m, f)).collect())
}

/// Which pixels of the metric-size image see a sphere first (rays through pixel centres).
fn sphere_pixels(scene: &Scene) -> Vec<bool> {
    let (width, height) = METRIC_SIZE;
    let frame = CameraFrame::new(scene.camera());
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

pub(super) fn mirror_table(rows: &[(f64, f64, f64)]) -> String {
    markdown_table(
        &["δ", "S mirror", "S diffuse", "ratio"],
        rows.iter().map(|(delta, mirror, diffuse)| {
            [delta.to_string(), format!("{mirror:.4e}"), format!("{diffuse:.4e}"), format!("{:.3}", mirror / diffuse)]
        }),
    )
}

/// How fast nearby rays separate between mirrors: curved (chaotic) versus flat (linear).
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::{MirrorDivergence, mirror_divergence};
/// let result: MirrorDivergence = mirror_divergence(200).unwrap();
/// // Between flat mirrors the separation follows its linear law.
/// assert!(result.flat.iter().all(|&(_, measured, law)| (measured / law - 1.0).abs() < 0.05));
/// assert_eq!(result.trials, 200);
/// ```
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
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::DIVERGENCE_TRIALS;
/// // Enough pairs that a hundred or more stay trapped for four bounces (the chapter's median).
/// assert!(DIVERGENCE_TRIALS >= 1000);
/// ```
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
        let dir = reflect::<f64>(ray.dir, hit.normal);
        ray = Ray { origin: spawn_origin::<f64>(hit.point, hit.normal, dir), dir };
        points.push(hit.point);
    }
    points
}

/// Measures [`MirrorDivergence`]: `trials` ray pairs `1e-12` rad apart aimed from 6 units away
/// at four mirror spheres (radius 1, centres on a tetrahedron with edge 2.2),
/// and one pair at 30° between two parallel mirrors 1 apart.
///
/// # Errors
/// [`InputError`] never for the built-in numbers.
///
/// # Examples
/// ```
/// let divergence = hw3::q1_hard_scenes::mirror_divergence(200).unwrap();
/// assert!(divergence.trapped > 0 && divergence.median_factor > 1.5);
/// for &(_, measured, law) in &divergence.flat {
///     assert!((measured / law - 1.0).abs() < 0.05);
/// }
/// ```
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

pub(super) fn divergence_table(result: &MirrorDivergence) -> String {
    let table = markdown_table(
        &["flat mirrors, bounces", "separation", "law k δ / cos²θ"],
        result.flat.iter().map(|(k, measured, law)| [k.to_string(), format!("{measured:.2e}"), format!("{law:.2e}")]),
    );
    format!(
        "four mirror spheres: {} of {} pairs trapped ≥ 4 bounces; median growth ×{:.2} per bounce\n\n{table}",
        result.trapped, result.trials, result.median_factor
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::q1_hard_scenes::metric::snapshot;

    /// The first-order law against an exact reflection: a camera looking along `−z` at a ball of
    /// radius R steps sideways by δ; its central ray now meets the ball where the normal is
    /// `(δ/R, 0, √(1 − δ²/R²))`, and the reflected ray turns by `2 arcsin(δ/R)`.
    #[test]
    fn reflection_turn_is_twice_the_normals_turn() {
        for (step, radius) in [(0.01, 1.0), (0.02, 0.5), (0.05, 2.0)] {
            let s = step / radius;
            let normal = DVec3::new(s, 0.0, (1.0 - s * s).sqrt());
            let turned = reflect::<f64>(DVec3::NEG_Z, normal);
            let exact = turned.angle_between(DVec3::Z);
            let law = reflection_turn(step, radius);
            assert!((law / exact - 1.0).abs() < 1e-3, "δ = {step}, R = {radius}: {law} vs {exact}");
        }
        assert!((reflection_turn(0.01, 1.0).to_degrees() - 1.145_915_590_261_646_5).abs() < 1e-15);
    }

    #[test]
    fn mirrors_change_faster_than_the_same_scene_made_diffuse() {
        let rows = mirror_sensitivity(&MIRROR_STEPS, MIRROR_SPP).unwrap();
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
}
