//! What a surface does to light: the BRDF of diffuse and glossy materials, the mirror
//! reflection and the dielectric (glass) split, and the specular scattering of a photon. Shared
//! by the eye-ray integrators and the photon tracer.

use super::scene::{Hit, Material};
use glam::DVec3;
use hw3_core::geometry::Ray;
use hw3_core::geometry::sphere::{reflect, spawn_origin};
use std::f64::consts::PI;

/// 1 when the ray arrives at the emitting side of a quad (the side its normal points to), else 0.
pub(crate) fn front_side(ray: &Ray<f64>, hit: &Hit) -> f64 {
    if ray.dir.dot(hit.normal) < 0.0 { 1.0 } else { 0.0 }
}

/// The geometric normal of `hit` turned towards the side `ray` came from.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_core::geometry::Ray;
/// use hw3_render::render::{bsdf::facing_normal, scene::Hit};
/// let hit = Hit { t: 1.0, point: DVec3::ZERO, normal: DVec3::Z, object: 0 };
/// let from_below = Ray { origin: DVec3::NEG_Z, dir: DVec3::Z };
/// assert_eq!(facing_normal(&from_below, &hit), DVec3::NEG_Z);
/// ```
#[must_use]
pub fn facing_normal(ray: &Ray<f64>, hit: &Hit) -> DVec3 {
    if ray.dir.dot(hit.normal) < 0.0 { hit.normal } else { -hit.normal }
}

/// The mirror reflection of `ray` at `hit`: reflected unit direction, origin nudged off the
/// surface on the reflected side (so the new ray does not hit the same surface at `t ≈ 0`).
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_core::geometry::Ray;
/// use hw3_render::render::{bsdf::reflected_ray, scene::Hit};
/// let hit = Hit { t: 1.0, point: DVec3::ZERO, normal: DVec3::Y, object: 0 };
/// let ray = Ray { origin: DVec3::new(-1.0, 1.0, 0.0), dir: DVec3::new(1.0, -1.0, 0.0).normalize() };
/// let out = reflected_ray(&ray, &hit);
/// assert!((out.dir - DVec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-15 && out.origin.y > 0.0);
/// ```
#[must_use]
pub fn reflected_ray(ray: &Ray<f64>, hit: &Hit) -> Ray<f64> {
    let dir = reflect::<f64>(ray.dir, hit.normal);
    Ray { origin: spawn_origin::<f64>(hit.point, hit.normal, dir), dir }
}

/// What a dielectric interface does to a ray: the Fresnel reflectance and, unless the ray is
/// totally internally reflected, the refracted ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DielectricSplit {
    /// Fraction reflected (unpolarised Fresnel), in `[0, 1]`; 1 under total internal reflection.
    pub reflectance: f64,
    /// The refracted ray (unit direction, origin off the surface on the far side), if any.
    pub refracted: Option<Ray<f64>>,
}

/// Snell refraction and exact unpolarised Fresnel reflectance at a hit on a surface of refractive
/// index `index` in vacuum (air): entering when the ray meets the outward normal head-on.
///
/// The refracted direction is `η d + (η cos θ_i − cos θ_t) n` with `η = n₁/n₂` and `n` the normal
/// facing the incoming ray; `R = (r_s² + r_p²)/2` with the Fresnel amplitudes
/// `r_s = (n₁ cos θ_i − n₂ cos θ_t)/(n₁ cos θ_i + n₂ cos θ_t)` and
/// `r_p = (n₂ cos θ_i − n₁ cos θ_t)/(n₂ cos θ_i + n₁ cos θ_t)`.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3_core::geometry::Ray;
/// use hw3_render::render::bsdf::dielectric_split;
/// use hw3_render::render::scene::Hit;
/// let ray = Ray { origin: DVec3::new(0.0, 0.0, 1.0), dir: DVec3::NEG_Z };
/// let hit = Hit { t: 1.0, point: DVec3::ZERO, normal: DVec3::Z, object: 0 };
/// let split = dielectric_split(&ray, &hit, 1.5);
/// assert!((split.reflectance - 0.04).abs() < 1e-15); // ((n − 1)/(n + 1))² at normal incidence
/// assert_eq!(split.refracted.unwrap().dir, DVec3::NEG_Z);
/// ```
#[must_use]
pub fn dielectric_split(ray: &Ray<f64>, hit: &Hit, index: f64) -> DielectricSplit {
    let normal = facing_normal(ray, hit);
    let entering = ray.dir.dot(hit.normal) < 0.0;
    let (n1, n2) = if entering { (1.0, index) } else { (index, 1.0) };
    let eta = n1 / n2;
    let cos_i = (-ray.dir.dot(normal)).clamp(0.0, 1.0);
    let sin_t_squared = eta * eta * (1.0 - cos_i * cos_i);
    if sin_t_squared >= 1.0 {
        return DielectricSplit { reflectance: 1.0, refracted: None };
    }
    let cos_t = (1.0 - sin_t_squared).sqrt();
    let r_s = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let r_p = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    let dir = (ray.dir * eta + normal * (eta * cos_i - cos_t)).normalize();
    DielectricSplit {
        reflectance: (r_s * r_s + r_p * r_p) / 2.0,
        refracted: Some(Ray { origin: spawn_origin::<f64>(hit.point, hit.normal, dir), dir }),
    }
}

/// The BRDF of a diffuse or glossy material for unit `to_eye`, `to_light` and facing `normal`:
/// Lambert `ρ/π`, plus for glossy the normalised Phong lobe `k_s (n + 2)/(2π) cosⁿα` about the
/// mirror direction. Zero for mirrors, glass and emitters (their scattering is a delta, handled
/// by the recursion, not by this function).
pub(crate) fn brdf(material: &Material, to_eye: DVec3, to_light: DVec3, normal: DVec3) -> DVec3 {
    match *material {
        Material::Diffuse { albedo } => albedo / PI,
        Material::Glossy { diffuse, specular, exponent } => {
            let mirror_dir = reflect::<f64>(-to_eye, normal);
            let lobe = mirror_dir.dot(to_light).max(0.0).powf(exponent);
            diffuse / PI + specular * ((exponent + 2.0) / (2.0 * PI) * lobe)
        }
        Material::Mirror { .. } | Material::Glass { .. } | Material::Emitter { .. } => DVec3::ZERO,
    }
}

/// The diffuse albedo of a material (zero for mirrors, glass and emitters): photons are stored
/// where it is non-zero.
pub(crate) fn diffuse_part(material: Material) -> DVec3 {
    match material {
        Material::Diffuse { albedo } => albedo,
        Material::Glossy { diffuse, .. } => diffuse,
        Material::Mirror { .. } | Material::Glass { .. } | Material::Emitter { .. } => DVec3::ZERO,
    }
}

/// The photon leaving a mirror or glass hit: a mirror reflects with probability
/// `max(reflectance)` (Russian roulette, drawn from `u`; `power` is rescaled by
/// `reflectance / max(reflectance)`), glass reflects with the Fresnel probability and refracts
/// otherwise (power unchanged). `None` when the photon is absorbed or the material is not specular.
pub(crate) fn specular_bounce(
    ray: &Ray<f64>,
    hit: &Hit,
    material: Material,
    power: &mut DVec3,
    u: f64,
) -> Option<Ray<f64>> {
    match material {
        Material::Mirror { reflectance } => {
            let survive = reflectance.max_element();
            if u >= survive {
                return None;
            }
            *power *= reflectance / survive;
            Some(reflected_ray(ray, hit))
        }
        Material::Glass { index } => {
            let split = dielectric_split(ray, hit, index);
            Some(match split.refracted {
                Some(refracted) if u >= split.reflectance => refracted,
                _ => reflected_ray(ray, hit),
            })
        }
        Material::Diffuse { .. } | Material::Glossy { .. } | Material::Emitter { .. } => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refraction_obeys_snell_and_total_internal_reflection() {
        let hit = Hit { t: 1.0, point: DVec3::ZERO, normal: DVec3::Z, object: 0 };
        let incoming = |angle: f64, from_inside: bool| {
            let side = if from_inside { 1.0 } else { -1.0 };
            Ray { origin: DVec3::ZERO, dir: DVec3::new(angle.sin(), 0.0, side * angle.cos()) }
        };
        for degrees in [0.0, 10.0, 30.0, 60.0, 89.0] {
            let theta = f64::to_radians(degrees);
            let split = dielectric_split(&incoming(theta, false), &hit, 1.5);
            let out = split.refracted.unwrap();
            assert!((out.dir.x - theta.sin() / 1.5).abs() < 1e-15, "Snell at {degrees}°");
            assert!(out.dir.z < 0.0 && out.origin.z < 0.0, "continues below the surface");
            assert!((0.0..1.0).contains(&split.reflectance));
        }
        // Inside glass, beyond the critical angle asin(1/1.5) = 41.8°, all light reflects.
        let inside = dielectric_split(&incoming(f64::to_radians(45.0), true), &hit, 1.5);
        assert_eq!(inside.reflectance, 1.0);
        assert!(inside.refracted.is_none());
        let below = dielectric_split(&incoming(f64::to_radians(40.0), true), &hit, 1.5);
        assert!(below.refracted.is_some() && below.reflectance < 1.0);
    }
}
