//! Random numbers and the directions drawn from them: the per-pixel [`Sampler`], and the
//! direction distributions the integrators, the photon tracer and the environment share
//! (cosine-weighted, uniform on the sphere, uniform in a cone, Phong lobe), plus the Fibonacci
//! sphere points used as deterministic query points.

use glam::DVec3;
use hw3_core::rng::{self, SampleGenerator};
use std::f64::consts::PI;

/// A per-pixel (or per-photon) random stream: [`rng::sample_stream`], seeded from the image seed
/// and the item's index, so the result never depends on which thread draws it. A separate type
/// from [`rng::Generator`] because the renderer selects a stream per purpose (see [`hw3_core::rng`]).
///
/// # Examples
/// ```
/// use hw3_render::render::sampling::Sampler;
/// let (mut a, mut b) = (Sampler::new(1, 7, 0), Sampler::new(1, 7, 0));
/// assert_eq!(a.uniform(), b.uniform());
/// assert!((0.0..1.0).contains(&Sampler::new(1, 8, 0).uniform()));
/// ```
#[derive(Debug, Clone)]
pub struct Sampler(SampleGenerator);

impl Sampler {
    /// The stream `stream` of pixel (or photon) `pixel` for image seed `seed`.
    #[must_use]
    pub fn new(seed: u64, pixel: u64, stream: u64) -> Self {
        Self(rng::sample_stream(seed, pixel, stream))
    }

    /// A uniform number in `[0, 1)` with 53 random bits.
    pub fn uniform(&mut self) -> f64 {
        rng::uniform(&mut self.0)
    }
}

/// A cosine-distributed direction about the unit `normal` (Malley's method: a uniform point on
/// the unit disc from `u1`, `u2` in `[0, 1)`, lifted to the hemisphere). The density is
/// `cos θ / π`; the result is a unit vector with a non-negative dot product with `normal`.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_render::render::sampling::cosine_direction;
/// assert!((cosine_direction(DVec3::Z, 0.0, 0.3) - DVec3::Z).length() < 1e-15); // u1 = 0: the pole
/// let d = cosine_direction(DVec3::Y, 0.7, 0.2);
/// assert!(d.dot(DVec3::Y) >= 0.0 && (d.length() - 1.0).abs() < 1e-15);
/// ```
#[must_use]
pub fn cosine_direction(normal: DVec3, u1: f64, u2: f64) -> DVec3 {
    let radius = u1.sqrt();
    let phi = 2.0 * PI * u2;
    let (tangent, bitangent) = normal.any_orthonormal_pair();
    let z = (1.0 - u1).max(0.0).sqrt();
    (tangent * (radius * phi.cos()) + bitangent * (radius * phi.sin()) + normal * z).normalize()
}

/// A direction uniform on the unit sphere (density `1/(4π)`) from `u1`, `u2` in `[0, 1)`:
/// `z = 1 − 2u₁`, azimuth `2πu₂`.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_render::render::sampling::uniform_sphere;
/// assert_eq!(uniform_sphere(0.0, 0.0), DVec3::Z);
/// assert!((uniform_sphere(0.3, 0.9).length() - 1.0).abs() < 1e-15);
/// ```
#[must_use]
pub fn uniform_sphere(u1: f64, u2: f64) -> DVec3 {
    let z = 1.0 - 2.0 * u1;
    let radius = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u2;
    DVec3::new(radius * phi.cos(), radius * phi.sin(), z)
}

/// A direction uniform in the cone about unit `axis` with half-angle cosine `cos_max`
/// (solid angle `2π(1 − cos_max)`).
pub(crate) fn cone_direction(axis: DVec3, cos_max: f64, u1: f64, u2: f64) -> DVec3 {
    let cos_theta = 1.0 - u1 * (1.0 - cos_max);
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let phi = 2.0 * PI * u2;
    let (tangent, bitangent) = axis.any_orthonormal_pair();
    (tangent * (sin_theta * phi.cos()) + bitangent * (sin_theta * phi.sin()) + axis * cos_theta).normalize()
}

/// A direction about unit `axis` with density `(n+1)/(2π) cosⁿα` (α the angle to `axis`).
pub(crate) fn phong_direction(axis: DVec3, exponent: f64, u1: f64, u2: f64) -> DVec3 {
    let cos_alpha = u1.powf(1.0 / (exponent + 1.0));
    let sin_alpha = (1.0 - cos_alpha * cos_alpha).max(0.0).sqrt();
    let phi = 2.0 * PI * u2;
    let (tangent, bitangent) = axis.any_orthonormal_pair();
    (tangent * (sin_alpha * phi.cos()) + bitangent * (sin_alpha * phi.sin()) + axis * cos_alpha).normalize()
}

/// The index whose cumulative weight first exceeds `target` (a number in `[0, Σ weights)`): a
/// choice with probability proportional to the weights. Rounding can leave `target` at the very
/// end of the range; the last index takes it.
pub(crate) fn pick_index(weights: impl ExactSizeIterator<Item = f64>, mut target: f64) -> usize {
    let last = weights.len() - 1;
    weights
        .enumerate()
        .find(|&(_, weight)| {
            target -= weight;
            target < 0.0
        })
        .map_or(last, |(index, _)| index)
}

/// `n` points spread evenly over the unit sphere (a Fibonacci lattice: `z` in `n` equal bands,
/// azimuth advancing by the golden angle `π(3 − √5)`), in a fixed order. Deterministic query
/// points for furnace measurements and surface samples.
///
/// # Examples
/// ```
/// let points = hw3_render::render::sampling::fibonacci_sphere(100);
/// assert_eq!(points.len(), 100);
/// assert!(points.iter().all(|p| (p.length() - 1.0).abs() < 1e-12));
/// // Evenly spread: the centroid is near the origin.
/// assert!(points.iter().sum::<glam::DVec3>().length() / 100.0 < 0.01);
/// ```
#[must_use]
pub fn fibonacci_sphere(n: usize) -> Vec<DVec3> {
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - (2.0 * i as f64 + 1.0) / n as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden * i as f64;
            DVec3::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cosine_directions_stay_in_the_hemisphere_and_average_to_two_thirds() {
        let normal = DVec3::new(0.0, 0.6, 0.8);
        let mut sampler = Sampler::new(7, 0, 0);
        let n = 20_000;
        let mean_cos: f64 = (0..n)
            .map(|_| {
                let d = cosine_direction(normal, sampler.uniform(), sampler.uniform());
                assert!(d.dot(normal) >= 0.0 && (d.length() - 1.0).abs() < 1e-12);
                d.dot(normal)
            })
            .sum::<f64>()
            / n as f64;
        // E[cosθ] = 2/3 for pdf cosθ/π; std of cosθ is √(1/2 − 4/9) ≈ 0.236, so 5σ/√n ≈ 0.0083.
        assert!((mean_cos - 2.0 / 3.0).abs() < 0.0083, "{mean_cos}");
    }
}
