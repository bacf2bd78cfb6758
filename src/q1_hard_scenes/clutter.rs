//! Q1(a) clutter: a random forest of spheres in a slab, where the gap fraction, the depth
//! complexity and the visible fraction follow the Boolean model's transmission law.

use crate::geometry::{InputError, Ray, Sphere};
use crate::kdtree::{HitStats, KdTree};
use crate::plot::markdown_table;
use crate::render::catalogue::{self, CLUTTER_HALF_WIDTH, CLUTTER_RADIUS};
use crate::render::sampling::Sampler;
use crate::render::{
    camera::{Camera, CameraFrame},
    scene::{Scene, Shape},
};
use glam::DVec3;
use std::collections::BTreeSet;
use std::f64::consts::PI;

/// The probability `p = πa²/(W + 2a)²` that one sphere of radius `radius`, its centre uniform
/// over a slab whose front face is a `face` × `face` square widened by `radius` on each side,
/// blocks a given ray perpendicular to the face: the centre must fall in the disc of radius `a`
/// around the ray.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::block_probability;
/// // The renderer's clutter slab: spheres of radius 0.5 over a 40 × 40 face.
/// let p = block_probability(0.5, 40.0);
/// assert!((p - std::f64::consts::PI * 0.25 / 41.0 / 41.0).abs() < 1e-15);
/// ```
#[must_use]
pub fn block_probability(radius: f64, face: f64) -> f64 {
    PI * radius * radius / (face + 2.0 * radius).powi(2)
}

/// The gap fraction `(1 − p)^N`: the share of rays perpendicular to the face that cross a slab of
/// `count` spheres without a hit, each sphere independently blocking with
/// [`block_probability`]`(radius, face)`. For small `p` it is the Boolean-model limit `e^(−Np)`
/// to within about `N p²/2`.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::gap_fraction;
/// // 1500 spheres of radius 0.5 over a 40 × 40 face: about half the rays get through.
/// assert!((gap_fraction(1500.0, 0.5, 40.0) - 0.496_091).abs() < 1e-6);
/// assert_eq!(gap_fraction(0.0, 0.5, 40.0), 1.0);
/// ```
#[must_use]
pub fn gap_fraction(count: f64, radius: f64, face: f64) -> f64 {
    (1.0 - block_probability(radius, face)).powf(count)
}

/// Sphere counts of the clutter experiment.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::{CLUTTER_COUNTS, gap_fraction};
/// // From nearly clear (τ ≈ 0.12) to nearly opaque (τ ≈ 1.9) over the renderer's slab.
/// let gaps = CLUTTER_COUNTS.map(|n| gap_fraction(n as f64, 0.5, 40.0));
/// assert!(gaps[0] > 0.85 && gaps[4] < 0.2 && gaps.windows(2).all(|w| w[1] < w[0]));
/// ```
pub const CLUTTER_COUNTS: [usize; 5] = [250, 500, 1000, 2000, 4000];

/// One row of the clutter experiment (averaged over [`CLUTTER_SEEDS`] random forests).
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::{ClutterRow, clutter_row};
/// let row: ClutterRow = clutter_row(250).unwrap();
/// // The Boolean-model limit and the exact law agree at this density, and τ = N p.
/// assert!((row.gap_beer_lambert / row.gap_exact - 1.0).abs() < 1e-3);
/// assert!((row.optical_depth / 250.0 - hw3::q1_hard_scenes::block_probability(0.5, 40.0)).abs() < 1e-15);
/// ```
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
    /// Fraction of the pixels whose first-hit sphere (or sky) changes when the camera steps
    /// sideways by [`CLUTTER_CAMERA_STEP`] (mean over cameras and forests).
    pub changed_pixels: f64,
    /// Ray/sphere tests per camera ray with the kd-tree of Q3 (mean over cameras and forests);
    /// without an acceleration structure a ray is tested against all `count` spheres.
    pub kd_tests_per_ray: f64,
}

/// How far the camera steps sideways (a fifth of a sphere's radius) for
/// [`ClutterRow::changed_pixels`].
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::CLUTTER_CAMERA_STEP;
/// // Smaller than a sphere: what changes is which sphere a pixel sees, not the spheres.
/// assert!(CLUTTER_CAMERA_STEP < 0.5);
/// ```
pub const CLUTTER_CAMERA_STEP: f64 = 0.1;

/// Random forests per clutter row.
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::CLUTTER_SEEDS;
/// // Enough forests for a standard error between them (at least two).
/// assert!(CLUTTER_SEEDS >= 2);
/// ```
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
///
/// # Examples
/// ```
/// use hw3::q1_hard_scenes::clutter_row;
/// // 250 spheres (τ ≈ 0.12): most probe rays cross the slab, as the exact law says.
/// let row = clutter_row(250).unwrap();
/// assert!((row.gap_fraction - row.gap_exact).abs() < 3.0 * row.gap_standard_error);
/// assert!((row.depth_complexity / row.optical_depth - 1.0).abs() < 0.05);
/// assert!(row.visible_fraction > 0.9);
/// ```
pub fn clutter_row(count: usize) -> Result<ClutterRow, InputError> {
    let mut gaps = Vec::new();
    let mut pierced_total = 0.0;
    let mut cameras_total = CameraMeasures::default();
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
        cameras_total = cameras_total.plus(camera_measures(&scene, seed)?);
    }
    let seeds = CLUTTER_SEEDS as f64;
    let gap_fraction = gaps.iter().sum::<f64>() / seeds;
    let spread = (gaps.iter().map(|g| (g - gap_fraction).powi(2)).sum::<f64>() / (seeds - 1.0)).sqrt();
    let p = block_probability(CLUTTER_RADIUS, 2.0 * CLUTTER_HALF_WIDTH);
    let optical_depth = count as f64 * p;
    Ok(ClutterRow {
        count,
        optical_depth,
        gap_fraction,
        gap_standard_error: spread / seeds.sqrt(),
        gap_exact: self::gap_fraction(count as f64, CLUTTER_RADIUS, 2.0 * CLUTTER_HALF_WIDTH),
        gap_beer_lambert: (-optical_depth).exp(),
        depth_complexity: pierced_total / seeds,
        visible_fraction: cameras_total.visible_fraction / seeds,
        changed_pixels: cameras_total.changed_pixels / seeds,
        kd_tests_per_ray: cameras_total.kd_tests_per_ray / seeds,
    })
}

/// What the cameras of one forest measure (each a mean over [`VISIBILITY_CAMERAS`] cameras).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct CameraMeasures {
    visible_fraction: f64,
    changed_pixels: f64,
    kd_tests_per_ray: f64,
}

impl CameraMeasures {
    fn plus(self, other: Self) -> Self {
        Self {
            visible_fraction: self.visible_fraction + other.visible_fraction,
            changed_pixels: self.changed_pixels + other.changed_pixels,
            kd_tests_per_ray: self.kd_tests_per_ray + other.kd_tests_per_ray,
        }
    }
}

/// The object each pixel of a [`VISIBILITY_SIZE`] image sees first through its centre (`None`:
/// the sky), for `camera` in `scene`.
fn id_buffer(scene: &Scene, camera: &Camera) -> Vec<Option<usize>> {
    let (width, height) = VISIBILITY_SIZE;
    let frame = CameraFrame::new(camera);
    let aspect = f64::from(width) / f64::from(height);
    (0..width * height)
        .map(|k| {
            let u = (f64::from(k % width) + 0.5) / f64::from(width);
            let v = (f64::from(k / width) + 0.5) / f64::from(height);
            scene.closest_hit(&frame.ray(u, v, aspect), 0.0, f64::INFINITY).map(|h| h.object)
        })
        .collect()
}

/// From [`VISIBILITY_CAMERAS`] cameras at random sideways offsets, 64×48 pixels each, rays through
/// the pixel centres: the fraction of the spheres whose centre is inside a camera's view that at
/// least one pixel sees (spheres seen only by a sliver at the image border, with their centre
/// outside, are not counted); the fraction of pixels whose first hit changes when the camera steps
/// [`CLUTTER_CAMERA_STEP`] sideways; and the ray/sphere tests per camera ray in the kd-tree of
/// the forest's spheres. Each is the mean over the cameras.
fn camera_measures(scene: &Scene, seed: u64) -> Result<CameraMeasures, InputError> {
    let spheres: Vec<Sphere<f64>> = scene
        .objects()
        .iter()
        .filter_map(|o| match o.shape {
            Shape::Sphere { sphere, .. } => Some(sphere),
            Shape::Quad { .. } => None,
        })
        .collect();
    let tree = KdTree::build(&spheres).map_err(|_| InputError::OutOfRange {
        name: "clutter forest",
        value: spheres.len().to_string(),
        expected: "spheres a kd-tree can hold",
    })?;
    let mut sampler = Sampler::new(seed, 0, 7);
    let mut total = CameraMeasures::default();
    for _ in 0..VISIBILITY_CAMERAS {
        let offset = DVec3::new(8.0 * (2.0 * sampler.uniform() - 1.0), 8.0 * (2.0 * sampler.uniform() - 1.0), 0.0);
        let camera =
            Camera { eye: scene.camera().eye + offset, look_at: scene.camera().look_at + offset, ..*scene.camera() };
        let stepped = DVec3::X * CLUTTER_CAMERA_STEP;
        let moved = Camera { eye: camera.eye + stepped, look_at: camera.look_at + stepped, ..camera };
        let (width, height) = VISIBILITY_SIZE;
        let frame = CameraFrame::new(&camera);
        let aspect = f64::from(width) / f64::from(height);
        let ids = id_buffer(scene, &camera);
        let seen: BTreeSet<usize> = ids.iter().flatten().copied().collect();
        let in_view: BTreeSet<usize> = (0..scene.objects().len())
            .filter(|&i| match scene.objects()[i].shape {
                Shape::Sphere { sphere, .. } => frame.sees(sphere.center, aspect),
                Shape::Quad { .. } => false,
            })
            .collect();
        let seen_in_view = seen.intersection(&in_view).count();
        let moved_ids = id_buffer(scene, &moved);
        let changed = ids.iter().zip(&moved_ids).filter(|(a, b)| a != b).count();
        let mut stats = HitStats::default();
        for k in 0..width * height {
            let u = (f64::from(k % width) + 0.5) / f64::from(width);
            let v = (f64::from(k / width) + 0.5) / f64::from(height);
            let _ = tree.closest_hit_with_stats(&frame.ray(u, v, aspect), 0.0, f64::INFINITY, &mut stats);
        }
        let pixels = f64::from(width * height);
        total = total.plus(CameraMeasures {
            visible_fraction: seen_in_view as f64 / in_view.len().max(1) as f64,
            changed_pixels: changed as f64 / pixels,
            kd_tests_per_ray: stats.sphere_tests as f64 / pixels,
        });
    }
    let cameras = VISIBILITY_CAMERAS as f64;
    Ok(CameraMeasures {
        visible_fraction: total.visible_fraction / cameras,
        changed_pixels: total.changed_pixels / cameras,
        kd_tests_per_ray: total.kd_tests_per_ray / cameras,
    })
}

pub(super) fn clutter_table(rows: &[ClutterRow]) -> String {
    let header =
        ["N", "τ = Np", "gap measured", "± s.e.", "(1−p)^N", "e^(−τ)", "depth complexity", "law τ", "visible fraction"];
    markdown_table(
        &header,
        rows.iter().map(|r| {
            [
                r.count.to_string(),
                format!("{:.3}", r.optical_depth),
                format!("{:.4}", r.gap_fraction),
                format!("{:.4}", r.gap_standard_error),
                format!("{:.4}", r.gap_exact),
                format!("{:.4}", r.gap_beer_lambert),
                format!("{:.3}", r.depth_complexity),
                format!("{:.3}", r.optical_depth),
                format!("{:.3}", r.visible_fraction),
            ]
        }),
    )
}

/// What makes the clutter scene hard, per sphere count: how many spheres a ray passes through
/// against the one it can see, how many spheres in view no pixel sees, how much of the image
/// changes for a small camera step, and how many spheres a ray is tested against without and with
/// the kd-tree.
pub(super) fn clutter_hardness_table(rows: &[ClutterRow]) -> String {
    let step = format!("pixels whose sphere changes, camera step {CLUTTER_CAMERA_STEP}");
    let header = [
        "N",
        "spheres a ray passes through",
        "spheres a ray sees",
        "spheres in view that no pixel sees",
        step.as_str(),
        "tests per ray, no structure",
        "tests per ray, kd-tree",
    ];
    markdown_table(
        &header,
        rows.iter().map(|r| {
            [
                r.count.to_string(),
                format!("{:.3}", r.depth_complexity),
                format!("{:.3}", 1.0 - r.gap_fraction),
                format!("{:.3}", 1.0 - r.visible_fraction),
                format!("{:.3}", r.changed_pixels),
                r.count.to_string(),
                format!("{:.1}", r.kd_tests_per_ray),
            ]
        }),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::q1_hard_scenes::metric::snapshot;

    /// The law against the numbers it has always given: the closed form the clutter table used,
    /// `(1 − π a²/(W + 2a)²)^N` with `W + 2a = 41`, and the checker's seed-1 slab as worked by
    /// `tests/answers/fixtures/keys.py`.
    #[test]
    fn gap_fraction_is_the_closed_form_the_table_used() {
        let side = 2.0 * (CLUTTER_HALF_WIDTH + CLUTTER_RADIUS);
        let p = PI * CLUTTER_RADIUS * CLUTTER_RADIUS / (side * side);
        assert_eq!(block_probability(CLUTTER_RADIUS, 2.0 * CLUTTER_HALF_WIDTH), p);
        for count in CLUTTER_COUNTS {
            let law = gap_fraction(count as f64, CLUTTER_RADIUS, 2.0 * CLUTTER_HALF_WIDTH);
            assert!((law / (1.0 - p).powi(count as i32) - 1.0).abs() < 1e-13, "N = {count}");
        }
        assert!((gap_fraction(1500.0, 0.5, 40.0) - 0.496_091_461_426_707_07).abs() < 1e-15);
        assert!((gap_fraction(1000.0, 1.0, 40.0) - 0.168_211_024_425_761_63).abs() < 1e-15);
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
        // What makes the scene hard grows with the forest: more of the image changes for a small
        // camera step, and the kd-tree's work per ray grows far slower than the sphere count.
        assert!(rows.windows(2).all(|w| w[1].changed_pixels > w[0].changed_pixels));
        let (first, last) = (rows[0], rows[rows.len() - 1]);
        assert!(last.kd_tests_per_ray < 2.0 * first.kd_tests_per_ray && last.count >= 16 * first.count);
        snapshot("q1_clutter_hardness", &clutter_hardness_table(&rows));
    }
}
