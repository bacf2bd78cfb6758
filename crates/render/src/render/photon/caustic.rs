//! The caustic photon trace: photons aimed at mirrors and glass (paths `LS+D`), for the
//! renderer's caustic pass.

use super::emission::{Emitter, emitters, in_ordered_chunks};
use super::map::{MAX_BOUNCES, MAX_PHOTONS, Photon, PhotonError, PhotonMap};
use crate::render::bsdf::{diffuse_part, facing_normal, specular_bounce};
use crate::render::color::luminance;
use crate::render::sampling::{Sampler, cone_direction, pick_index};
use crate::render::scene::{Hit, Material, Scene, Shape};
use glam::DVec3;
use hw3_core::geometry::Ray;
use hw3_core::geometry::sphere::spawn_origin;
use std::f64::consts::PI;

/// Photons the renderer's caustic pass traces per render (all aimed at mirrors and glass).
pub const CAUSTIC_PHOTONS: usize = 50_000;

/// A mirror or glass object of the scene and a sphere that bounds it: the target of caustic
/// photons.
#[derive(Debug, Clone, Copy)]
struct SpecularTarget {
    object: usize,
    center: DVec3,
    radius: f64,
}

/// Every mirror (of non-black reflectance) and glass object, with its bounding sphere at `time`.
fn specular_targets(scene: &Scene, time: f64) -> Vec<SpecularTarget> {
    scene
        .objects()
        .iter()
        .enumerate()
        .filter(|(_, o)| match o.material {
            Material::Mirror { reflectance } => reflectance.max_element() > 0.0,
            Material::Glass { .. } => true,
            Material::Diffuse { .. } | Material::Glossy { .. } | Material::Emitter { .. } => false,
        })
        .map(|(object, o)| {
            let (center, radius) = match o.shape {
                Shape::Sphere { sphere, velocity } => (sphere.center + velocity * time, sphere.radius),
                Shape::Quad { corner, edge_u, edge_v } => {
                    (corner + (edge_u + edge_v) * 0.5, (edge_u + edge_v).length().max((edge_u - edge_v).length()) * 0.5)
                }
            };
            SpecularTarget { object, center, radius }
        })
        .collect()
}

/// The cone from `origin` that contains the sphere (`center`, `radius`): its unit axis and the
/// cosine of its half-angle; the whole sphere of directions (cosine −1) from inside.
fn bounding_cone(origin: DVec3, center: DVec3, radius: f64) -> (DVec3, f64) {
    let offset = center - origin;
    let distance = offset.length();
    if distance <= radius {
        return (DVec3::Z, -1.0);
    }
    let sin_half = radius / distance;
    (offset / distance, (1.0 - sin_half * sin_half).sqrt())
}

/// Traces a caustic photon map (paths `LS+D`): `count` photons from the point and quad lights of
/// `scene`, each *aimed* at one mirror or glass object (Jensen's projection map), followed
/// through mirrors and glass and stored at the first diffuse (or glossy-with-diffuse-part) hit.
///
/// Each (light, target) pair is chosen with probability `p` proportional to the light's
/// luminous power times the fraction of its sphere of directions that the target's bounding
/// cone covers (seen from a quad light's centre). A photon leaves uniformly inside that cone
/// (solid angle Ω) and carries `I Ω / (p N)` from a point light of intensity `I`, and
/// `L A cos θ_l Ω / (p N)` from a quad of radiance `L` and area `A` (point uniform on the quad,
/// `θ_l` the angle to its normal; zero behind it): an unbiased estimate of the flux into the
/// cone. A photon counts only when the first object it hits *is* its target: a direction that
/// reaches another mirror or glass first belongs to that object's cone, one that reaches a
/// diffuse surface first is direct light (`LD`), so no path is counted twice. Photons travel at
/// the shutter's opening time and ignore the medium (as [`trace_photons`](super::trace_photons) does).
///
/// Deterministic: photon `i` draws from stream 3 of `(seed, i)`, traced in ordered parallel
/// chunks, so the map is identical for any number of threads. Without a lit emitter or without
/// a mirror or glass object, nothing is traced and the map is empty.
///
/// # Errors
/// [`PhotonError::PhotonCount`] for 0 or more than [`MAX_PHOTONS`].
///
/// # Examples
/// ```
/// use hw3_render::render::{photon::trace_caustic_photons, catalogue};
/// let caustic = trace_caustic_photons(&catalogue::by_name("caustic").unwrap(), 2000, 1).unwrap();
/// assert!(caustic.len() > 1000, "most photons aimed at the glass ball land on the floor");
/// let none = trace_caustic_photons(&catalogue::by_name("diffuse-spheres").unwrap(), 2000, 1).unwrap();
/// assert!(none.is_empty(), "no mirror or glass: no caustic photon");
/// ```
pub fn trace_caustic_photons(scene: &Scene, count: usize, seed: u64) -> Result<PhotonMap, PhotonError> {
    if count == 0 || count > MAX_PHOTONS {
        return Err(PhotonError::PhotonCount(count));
    }
    let time = scene.camera().shutter.0;
    let targets = specular_targets(scene, time);
    let pairs: Vec<(Emitter, SpecularTarget, f64)> = emitters(scene)
        .into_iter()
        .flat_map(|light| targets.iter().map(move |&target| (light, target)))
        .map(|(light, target)| {
            let reference = match light {
                Emitter::Point { position, .. } => position,
                Emitter::Quad { corner, edge_u, edge_v, .. } => corner + (edge_u + edge_v) * 0.5,
            };
            let (_, cos_max) = bounding_cone(reference, target.center, target.radius);
            (light, target, luminance(light.power()) * (1.0 - cos_max) / 2.0)
        })
        .collect();
    let total: f64 = pairs.iter().map(|pair| pair.2).sum();
    if !(total > 0.0 && total.is_finite()) {
        return Ok(PhotonMap::new(vec![]));
    }
    let photons = in_ordered_chunks(count, |index, out| {
        let mut sampler = Sampler::new(seed, index as u64, 3);
        let (light, target, weight) = pairs[pick_index(pairs.iter().map(|p| p.2), sampler.uniform() * total)];
        let per_photon = 1.0 / (weight / total * count as f64);
        let (origin, light_normal, intensity) = match light {
            Emitter::Point { position, power } => (position, None, power / (4.0 * PI)),
            Emitter::Quad { corner, edge_u, edge_v, power } => {
                let point = corner + edge_u * sampler.uniform() + edge_v * sampler.uniform();
                // Φ = πLA, so Φ/π is L·A.
                (point, Some(edge_u.cross(edge_v).normalize()), power / PI)
            }
        };
        let (axis, cos_max) = bounding_cone(origin, target.center, target.radius);
        let dir = cone_direction(axis, cos_max, sampler.uniform(), sampler.uniform());
        let (cos_light, origin) = match light_normal {
            None => (1.0, origin),
            Some(normal) => (normal.dot(dir), spawn_origin::<f64>(origin, normal, dir)),
        };
        if cos_light <= 0.0 {
            return;
        }
        let solid_angle = 2.0 * PI * (1.0 - cos_max);
        let power = intensity * (cos_light * solid_angle * per_photon);
        let ray = Ray { origin, dir };
        if let Some(hit) = scene.closest_hit(&ray, time, f64::INFINITY).filter(|hit| hit.object == target.object) {
            follow_caustic(scene, ray, hit, power, time, &mut sampler, out);
        }
    });
    Ok(PhotonMap::new(photons))
}

/// Follows a photon that has just hit a mirror or glass object through specular bounces to the
/// first diffuse hit, where it is stored (absorbed, escaped or at an emitter: nothing stored).
fn follow_caustic(
    scene: &Scene,
    mut ray: Ray<f64>,
    mut hit: Hit,
    mut power: DVec3,
    time: f64,
    sampler: &mut Sampler,
    out: &mut Vec<Photon>,
) {
    for _ in 0..MAX_BOUNCES {
        let material = scene.objects()[hit.object].material;
        if diffuse_part(material).max_element() > 0.0 {
            let normal = facing_normal(&ray, &hit);
            out.push(Photon { position: hit.point, direction: ray.dir, normal, power });
            return;
        }
        let Some(next) = specular_bounce(&ray, &hit, material, &mut power, sampler.uniform()) else { return };
        ray = next;
        let Some(next_hit) = scene.closest_hit(&ray, time, f64::INFINITY) else { return };
        hit = next_hit;
    }
}
