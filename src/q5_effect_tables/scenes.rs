//! The Cornell-like boxes of the measured table (the furnace box and the box with a red or white
//! left wall), their wall colours, and the probe regions the measurements read.

use crate::geometry::{InputError, Ray};
use crate::render::{
    camera::Camera,
    scene::{Material, Object, Scene},
};
use glam::DVec3;

/// Reflectances of the Cornell box walls (RGB stand-ins for the measured spectra, as in Tungsten).
pub const WHITE: DVec3 = DVec3::new(0.725, 0.71, 0.68);
/// Red wall.
pub const RED: DVec3 = DVec3::new(0.63, 0.065, 0.05);
/// Green wall.
pub const GREEN: DVec3 = DVec3::new(0.14, 0.45, 0.091);
/// Radiance of the ceiling light.
pub const LIGHT_RADIANCE: f64 = 12.0;

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
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3::q5_effect_tables::scenes::closed_box;
/// assert_eq!(closed_box(DVec3::splat(0.5)).unwrap().objects().len(), 6);
/// assert!(closed_box(DVec3::splat(1.5)).is_err());
/// ```
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
///
/// # Examples
/// ```
/// // Five walls, the light and the block's five faces.
/// let scene = hw3::q5_effect_tables::scenes::cornell_box(true).unwrap();
/// assert_eq!(scene.objects().len(), 11);
/// ```
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

/// Probe rays straight down the normals onto `points` (from 0.05 above): a Lambertian surface
/// looks the same from every direction, so the normal one will do.
fn region(points: impl Iterator<Item = DVec3>, normal: DVec3) -> Vec<Ray<f64>> {
    points.map(|p| Ray { origin: p + normal * 0.05, dir: -normal }).collect()
}

/// The floor strip beside the left wall (x ∈ [−0.95, −0.65]): where red bleeds.
pub(super) fn bleeding_region() -> Vec<Ray<f64>> {
    region((0..16).map(|k| DVec3::new(-0.95 + 0.1 * (k % 4) as f64, -1.0, -0.75 + 0.1 * (k / 4) as f64)), DVec3::Y)
}

/// Ceiling points away from the light: no light sees them directly.
pub(super) fn glow_region() -> Vec<Ray<f64>> {
    region((0..16).map(|k| DVec3::new(-0.9 + 0.1 * (k % 4) as f64, 1.0, 0.5 + 0.1 * (k / 4) as f64)), -DVec3::Y)
}

/// Channel mean of a radiance.
pub(super) fn grey(radiance: DVec3) -> f64 {
    radiance.element_sum() / 3.0
}
