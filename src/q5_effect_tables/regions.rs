//! The probe regions that the measurements read in the Cornell box
//! ([`catalogue::cornell_box`](crate::render::catalogue::cornell_box) with the block).

use crate::geometry::Ray;
use glam::DVec3;

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
