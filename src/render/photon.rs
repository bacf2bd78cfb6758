//! Photon tracing and photon maps (Jensen 1996): photons shot from the lights, bounced through
//! the scene's materials with Russian roulette, stored at diffuse hits, and read back by a
//! bias-corrected k-nearest-neighbour density estimate.
//!
//! Three maps come out of one trace, because they differ only in which stored photons they keep:
//! - **all** ([`PhotonMaps::all`]): every photon at every diffuse (or glossy-with-diffuse-part)
//!   hit, paths `L(S|D|G)*D`: the complete irradiance, used by the furnace test;
//! - **indirect** ([`PhotonMaps::indirect`]): photons that already bounced off a diffuse or
//!   glossy surface, `L(S|D|G)*(D|G)(S|D|G)*D`: what eye rays with direct light miss;
//! - **caustic** ([`PhotonMaps::caustic`]): photons whose every bounce so far was specular
//!   (mirror or glass), `LS+D`.
//!
//! The estimate ([`PhotonMap::irradiance`], [`PhotonMap::radiance`]) sums the power of the
//! `k − 1` nearest photons over the disc `πr²` reaching the `k`-th: for photons of density `λ`
//! the number inside a disc of area `a` is Poisson, so `λπr_k²` is Gamma(k, 1) distributed and
//! `E[1/(πr_k²)] = λ/(k − 1)`; `(k−1)/(πr_k²)` is unbiased where `k/(πr_k²)` overestimates by
//! `k/(k−1)` (see the renderer chapter).
//!
//! Tracing is deterministic: photon `i` draws from its own [`Sampler`] stream (seed, `i`), so the
//! maps are identical for any number of rayon threads.

use super::integrator::{Sampler, brdf, cosine_direction, dielectric_split, facing_normal, reflected_ray};
use super::scene::{Camera, Hit, Material, Object, PointLight, Scene, Shape};
use crate::geometry::Ray;
use crate::geometry::Sphere;
use crate::geometry::sphere::spawn_origin;
use glam::DVec3;
use kiddo::{ImmutableKdTree, SquaredEuclidean};
use rayon::prelude::*;
use std::f64::consts::PI;
use std::num::NonZero;

/// Largest number of photons one trace may emit (the kd-tree indexes photons by `u32`, and each
/// emitted photon may be stored several times).
pub const MAX_PHOTONS: usize = 1 << 26;

/// Bounces after which a photon is dropped even if Russian roulette kept it (a photon trapped
/// between mirrors of reflectance 1 would otherwise never stop). The power lost is the power of
/// paths longer than this, `ρ^64` of the emitted power at albedo `ρ` (`5e-20` at 0.5).
pub const MAX_BOUNCES: u32 = 64;

/// Why photons could not be traced or a map could not be read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum PhotonError {
    /// Zero photons requested, or more than [`MAX_PHOTONS`].
    #[error("photon count must be 1…{MAX_PHOTONS}, got {0}")]
    PhotonCount(usize),
    /// The scene emits nothing (no light, or all lights black).
    #[error("the scene has no light with positive power: nothing to emit")]
    NoLight,
    /// `k < 2`: the bias-corrected estimate uses the `k − 1` photons inside the `k`-th one's radius.
    #[error("k must be at least 2 for the (k−1)/(πr²) estimate, got {0}")]
    NeighbourCount(usize),
    /// More neighbours requested than photons stored in the map.
    #[error("k = {requested} neighbours requested, but the map holds only {stored} photons")]
    TooFewPhotons {
        /// The `k` requested.
        requested: usize,
        /// Photons in the map.
        stored: usize,
    },
    /// The `k` nearest photons all sit at the query point (radius 0): the density is unbounded.
    #[error("the {0} nearest photons coincide with the query point: radius 0, density undefined")]
    CoincidentPhotons(usize),
    /// A gather radius that is not finite and positive.
    #[error("the maximum gather radius must be finite and > 0")]
    MaxRadius,
}

/// One stored photon: where it landed, the direction it travelled, and the power it carries.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Photon {
    /// Hit point on a diffuse or glossy surface.
    pub position: DVec3,
    /// Unit direction of travel (towards the surface).
    pub direction: DVec3,
    /// Unit normal of the surface where it was stored, turned towards the arriving photon.
    pub normal: DVec3,
    /// Power (flux, W per channel) the photon carries.
    pub power: DVec3,
}

/// A set of photons with a kd-tree (`kiddo`'s [`ImmutableKdTree`]) for k-nearest queries.
#[derive(Debug)]
pub struct PhotonMap {
    photons: Vec<Photon>,
    tree: ImmutableKdTree<f64, 3>,
}

impl PhotonMap {
    /// A map of `photons` (possibly empty; queries on an empty map are typed errors).
    ///
    /// Photons at identical coordinates are accepted (kiddo issue #158 concerned the older
    /// immutable tree; the rewritten one splits ties, which a unit test pins).
    ///
    /// # Panics
    /// If kiddo refuses to build the tree, which it does only for more than `u32::MAX` items
    /// (impossible below [`MAX_PHOTONS`] emitted × [`MAX_BOUNCES`] stores each).
    #[must_use]
    pub fn new(photons: Vec<Photon>) -> Self {
        let points: Vec<[f64; 3]> = photons.iter().map(|p| p.position.to_array()).collect();
        let tree = ImmutableKdTree::new_from_slice(&points).expect("fewer than 2³² photons");
        Self { photons, tree }
    }

    /// The stored photons, in tracing order.
    #[must_use]
    pub fn photons(&self) -> &[Photon] {
        &self.photons
    }

    /// Number of stored photons.
    #[must_use]
    pub fn len(&self) -> usize {
        self.photons.len()
    }

    /// Whether the map holds no photon.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }

    /// The `k` nearest photons to `point` (nearest first) and the squared distance of the `k`-th.
    ///
    /// # Errors
    /// [`PhotonError::NeighbourCount`] for `k < 2`, [`PhotonError::TooFewPhotons`] when the map
    /// holds fewer than `k`, [`PhotonError::CoincidentPhotons`] when the `k`-th is at distance 0.
    pub fn nearest(&self, point: DVec3, k: usize) -> Result<(Vec<&Photon>, f64), PhotonError> {
        if k < 2 {
            return Err(PhotonError::NeighbourCount(k));
        }
        if k > self.photons.len() {
            return Err(PhotonError::TooFewPhotons { requested: k, stored: self.photons.len() });
        }
        let count = NonZero::new(k).ok_or(PhotonError::NeighbourCount(k))?;
        let found = self.tree.query(&point.to_array()).nearest_n::<SquaredEuclidean<f64>>(count).execute();
        let radius_squared = found.last().map_or(0.0, |item| item.distance);
        if !(radius_squared > 0.0) {
            return Err(PhotonError::CoincidentPhotons(k));
        }
        Ok((found.iter().map(|item| &self.photons[item.item as usize]).collect(), radius_squared))
    }

    /// Irradiance at `point` (W/m² per channel): the power of the `k − 1` nearest photons over
    /// the disc `πr_k²` through the `k`-th. Photons are assumed to lie on the surface through
    /// `point` (the disc assumption: near a corner the disc also collects the other wall's).
    ///
    /// # Errors
    /// As [`PhotonMap::nearest`].
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::render::photon::{Photon, PhotonMap};
    /// // A 100 × 100 grid of 1 W photons with spacing 0.01 m: 10⁴ W/m².
    /// let photons = (0..10_000)
    ///     .map(|i| Photon { position: DVec3::new(f64::from(i % 100) * 0.01, f64::from(i / 100) * 0.01, 0.0),
    ///                       direction: DVec3::NEG_Z, normal: DVec3::Z, power: DVec3::ONE })
    ///     .collect();
    /// let e = PhotonMap::new(photons).irradiance(DVec3::new(0.505, 0.505, 0.0), 40).unwrap();
    /// assert!((e.x / 1e4 - 1.0).abs() < 0.3);
    /// ```
    pub fn irradiance(&self, point: DVec3, k: usize) -> Result<DVec3, PhotonError> {
        let (nearest, radius_squared) = self.nearest(point, k)?;
        let inside: DVec3 = nearest[..k - 1].iter().map(|p| p.power).sum();
        Ok(inside / (PI * radius_squared))
    }

    /// Reflected radiance towards `to_eye` at a hit with facing unit `normal` on `material`:
    /// `Σ f_r(to_eye, −direction_p) Φ_p / (πr_k²)` over the `k − 1` nearest photons stored on a
    /// surface facing the same way (normals within about 25°, Jensen's guard against the disc
    /// collecting the other wall's photons at a corner; it biases the estimate low there
    /// instead of high). Mirrors, glass and emitters reflect nothing here (zero).
    ///
    /// # Errors
    /// As [`PhotonMap::nearest`].
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::render::photon::{fibonacci_sphere, furnace_sphere, trace_photons};
    /// use hw3::render::scene::Material;
    /// // Furnace, ρ = 0.5, I = 1: L = ρE/π with E = 2 at every wall point.
    /// let maps = trace_photons(&furnace_sphere(0.5, 1.0).unwrap(), 20_000, 1).unwrap();
    /// let white = Material::Diffuse { albedo: DVec3::splat(0.5) };
    /// let points = fibonacci_sphere(200);
    /// let mean = points.iter().map(|&p| maps.all.radiance(&white, p, -p, -p, 50).unwrap().x).sum::<f64>() / 200.0;
    /// assert!((mean / (1.0 / std::f64::consts::PI) - 1.0).abs() < 0.05);
    /// ```
    pub fn radiance(
        &self,
        material: &Material,
        point: DVec3,
        to_eye: DVec3,
        normal: DVec3,
        k: usize,
    ) -> Result<DVec3, PhotonError> {
        let (nearest, radius_squared) = self.nearest(point, k)?;
        Ok(reflected_power(nearest[..k - 1].iter().copied(), material, to_eye, normal) / (PI * radius_squared))
    }

    /// Reflected radiance as [`PhotonMap::radiance`], but gathering only within
    /// `gather.max_radius()` (Jensen's maximum search distance): where the `k` nearest photons
    /// lie within it, the `(k−1)/(πr_k²)` estimate; where fewer do, the photons inside the fixed
    /// disc over its area `πr_max²` (also unbiased for a uniform density, and noisier). Far from
    /// every photon the result is exactly zero, and an empty map returns zero without a query:
    /// a caustic pass with nothing to gather adds nothing, bit for bit.
    ///
    /// Should the `k` nearest photons all coincide with `point` (radius 0, a measure-zero
    /// event), the fixed-disc form is used over those `k`.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::render::photon::{Gather, Photon, PhotonMap};
    /// use hw3::render::scene::Material;
    /// let white = Material::Diffuse { albedo: DVec3::ONE };
    /// let photon = Photon { position: DVec3::ZERO, direction: DVec3::NEG_Z, normal: DVec3::Z, power: DVec3::ONE };
    /// let map = PhotonMap::new(vec![photon]);
    /// let gather = Gather::new(10, 0.5).unwrap();
    /// // One photon of 1 W inside the 0.5-disc: L = (1/π) · 1 / (π 0.25).
    /// let near = map.radiance_gathered(&white, DVec3::new(0.1, 0.0, 0.0), DVec3::Z, DVec3::Z, gather);
    /// assert!((near.x - 4.0 / (std::f64::consts::PI * std::f64::consts::PI)).abs() < 1e-12);
    /// assert_eq!(map.radiance_gathered(&white, DVec3::X, DVec3::Z, DVec3::Z, gather), DVec3::ZERO);
    /// ```
    #[must_use]
    pub fn radiance_gathered(
        &self,
        material: &Material,
        point: DVec3,
        to_eye: DVec3,
        normal: DVec3,
        gather: Gather,
    ) -> DVec3 {
        if self.photons.is_empty() {
            return DVec3::ZERO;
        }
        let k = gather.neighbours;
        let max_squared = gather.max_radius * gather.max_radius;
        let count = NonZero::new(k).expect("Gather::new keeps k ≥ 2");
        let found =
            self.tree.query(&point.to_array()).nearest_n::<SquaredEuclidean<f64>>(count).within(max_squared).execute();
        let photons = found.iter().map(|item| &self.photons[item.item as usize]);
        match found.last() {
            Some(kth) if found.len() == k && kth.distance > 0.0 => {
                reflected_power(photons.take(k - 1), material, to_eye, normal) / (PI * kth.distance)
            }
            _ => reflected_power(photons, material, to_eye, normal) / (PI * max_squared),
        }
    }
}

/// `Σ f_r(to_eye, −direction_p) Φ_p` over `photons` stored on a surface facing like `normal`
/// (within about 25°).
fn reflected_power<'p>(
    photons: impl Iterator<Item = &'p Photon>,
    material: &Material,
    to_eye: DVec3,
    normal: DVec3,
) -> DVec3 {
    photons.filter(|p| p.normal.dot(normal) > 0.9).map(|p| brdf(material, to_eye, -p.direction, normal) * p.power).sum()
}

/// How a radiance estimate gathers photons: the `k` nearest ([`Gather::neighbours`], k ≥ 2),
/// but none farther than [`Gather::max_radius`]. Validated on construction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gather {
    neighbours: usize,
    max_radius: f64,
}

impl Gather {
    /// `neighbours` photons at most, within `max_radius` (scene units).
    ///
    /// # Errors
    /// [`PhotonError::NeighbourCount`] for `neighbours < 2`; [`PhotonError::MaxRadius`] unless
    /// `max_radius` is finite and positive.
    ///
    /// # Examples
    /// ```
    /// use hw3::render::photon::Gather;
    /// assert_eq!(Gather::new(50, 0.1).unwrap().neighbours(), 50);
    /// assert!(Gather::new(1, 0.1).is_err() && Gather::new(50, f64::NAN).is_err());
    /// ```
    pub fn new(neighbours: usize, max_radius: f64) -> Result<Self, PhotonError> {
        if neighbours < 2 {
            return Err(PhotonError::NeighbourCount(neighbours));
        }
        if !(max_radius > 0.0 && max_radius.is_finite()) {
            return Err(PhotonError::MaxRadius);
        }
        Ok(Self { neighbours, max_radius })
    }

    /// The number of nearest photons `k`.
    #[must_use]
    pub fn neighbours(&self) -> usize {
        self.neighbours
    }

    /// The largest gather radius.
    #[must_use]
    pub fn max_radius(&self) -> f64 {
        self.max_radius
    }
}

/// The renderer's caustic gather: the 50 nearest photons within 0.1 scene units (render
/// settings; the built-in scenes are a few units across, see the renderer chapter for the
/// trade-off).
pub const CAUSTIC_GATHER: Gather = Gather { neighbours: 50, max_radius: 0.1 };

/// Photons the renderer's caustic pass traces per render (all aimed at mirrors and glass).
pub const CAUSTIC_PHOTONS: usize = 50_000;

/// The three photon maps of one trace (see the module docs for what each keeps).
#[derive(Debug)]
pub struct PhotonMaps {
    /// Every photon at every diffuse or glossy hit.
    pub all: PhotonMap,
    /// Photons after at least one diffuse or glossy bounce.
    pub indirect: PhotonMap,
    /// Photons after specular bounces only (at least one).
    pub caustic: PhotonMap,
    /// Photons emitted.
    pub emitted: usize,
}

/// An emitter of the scene with its power (W per channel).
#[derive(Debug, Clone, Copy)]
enum Emitter {
    Point { position: DVec3, power: DVec3 },
    Quad { corner: DVec3, edge_u: DVec3, edge_v: DVec3, power: DVec3 },
}

impl Emitter {
    fn power(&self) -> DVec3 {
        match *self {
            Emitter::Point { power, .. } | Emitter::Quad { power, .. } => power,
        }
    }
}

/// The scene's lights with their powers: `Φ = 4πI` for a point light, `Φ = π L A` for a
/// one-sided Lambertian quad of radiance `L` and area `A`.
fn emitters(scene: &Scene) -> Vec<Emitter> {
    let points = scene
        .point_lights()
        .iter()
        .map(|light| Emitter::Point { position: light.position, power: light.intensity * (4.0 * PI) });
    let quads = scene.objects().iter().filter_map(|object| match (object.material, object.shape) {
        (Material::Emitter { radiance }, Shape::Quad { corner, edge_u, edge_v }) => {
            let area = edge_u.cross(edge_v).length();
            Some(Emitter::Quad { corner, edge_u, edge_v, power: radiance * (PI * area) })
        }
        _ => None,
    });
    points.chain(quads).filter(|e| luminance(e.power()) > 0.0).collect()
}

fn luminance(c: DVec3) -> f64 {
    c.dot(DVec3::new(0.2126, 0.7152, 0.0722))
}

/// A uniformly distributed unit vector.
fn uniform_sphere(u1: f64, u2: f64) -> DVec3 {
    let z = 1.0 - 2.0 * u1;
    let radius = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u2;
    DVec3::new(radius * phi.cos(), radius * phi.sin(), z)
}

/// Traces `count` photons from the lights of `scene` with seed `seed`: each light is chosen
/// with probability proportional to its luminous power and the photon carries
/// `Φ_light / (p_light · count)`, so the stored powers sum (in expectation) to the true flux.
///
/// At a diffuse hit the photon is stored, then survives with probability `max(albedo)` and its
/// power is multiplied by `albedo / max(albedo)` (Russian roulette: unbiased, constant power for
/// grey surfaces). A glossy hit is stored when its diffuse part is non-zero and then chooses the
/// diffuse lobe, the Phong lobe (sampled `∝ cosⁿα`) or absorption by `max(kd)` and `max(ks)`.
/// A mirror survives with probability `max(reflectance)`; glass reflects with the Fresnel
/// probability and refracts otherwise (power unchanged). Emitters and misses end the photon.
///
/// # Errors
/// [`PhotonError::PhotonCount`] for 0 or more than [`MAX_PHOTONS`]; [`PhotonError::NoLight`].
///
/// # Examples
/// ```
/// use hw3::render::{photon::trace_photons, scenes};
/// let maps = trace_photons(&scenes::cornell_mirror().unwrap(), 2000, 1).unwrap();
/// assert!(maps.all.len() >= maps.indirect.len() && maps.all.len() > 1000);
/// assert!(trace_photons(&scenes::cornell_mirror().unwrap(), 0, 1).is_err());
/// ```
pub fn trace_photons(scene: &Scene, count: usize, seed: u64) -> Result<PhotonMaps, PhotonError> {
    if count == 0 || count > MAX_PHOTONS {
        return Err(PhotonError::PhotonCount(count));
    }
    let lights = emitters(scene);
    let total: f64 = lights.iter().map(|e| luminance(e.power())).sum();
    if lights.is_empty() || !(total > 0.0 && total.is_finite()) {
        return Err(PhotonError::NoLight);
    }
    let stored = in_ordered_chunks(count, |index, out| {
        let mut sampler = Sampler::new(seed, index as u64, 2);
        trace_one(scene, &lights, total, count, &mut sampler, out);
    });
    let keep = |wanted: fn(Path) -> bool| {
        PhotonMap::new(stored.iter().filter(|(_, path)| wanted(*path)).map(|(photon, _)| *photon).collect())
    };
    Ok(PhotonMaps {
        all: keep(|_| true),
        indirect: keep(|path| path == Path::AfterDiffuse),
        caustic: keep(|path| path == Path::SpecularOnly),
        emitted: count,
    })
}

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

/// A direction uniform in the cone about unit `axis` with half-angle cosine `cos_max`
/// (solid angle `2π(1 − cos_max)`).
fn cone_direction(axis: DVec3, cos_max: f64, u1: f64, u2: f64) -> DVec3 {
    let cos_theta = 1.0 - u1 * (1.0 - cos_max);
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let phi = 2.0 * PI * u2;
    let (tangent, bitangent) = axis.any_orthonormal_pair();
    (tangent * (sin_theta * phi.cos()) + bitangent * (sin_theta * phi.sin()) + axis * cos_theta).normalize()
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
/// the shutter's opening time and ignore the medium (as [`trace_photons`] does).
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
/// use hw3::render::{photon::trace_caustic_photons, scenes};
/// let caustic = trace_caustic_photons(&scenes::by_name("caustic").unwrap(), 2000, 1).unwrap();
/// assert!(caustic.len() > 1000, "most photons aimed at the glass ball land on the floor");
/// let none = trace_caustic_photons(&scenes::by_name("diffuse-spheres").unwrap(), 2000, 1).unwrap();
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

/// What a photon's path did before the hit where it is stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Path {
    /// Straight from the light (`LD`).
    Direct,
    /// One or more specular bounces only (`LS+D`).
    SpecularOnly,
    /// At least one diffuse or glossy bounce.
    AfterDiffuse,
}

fn trace_one(
    scene: &Scene,
    lights: &[Emitter],
    total: f64,
    count: usize,
    sampler: &mut Sampler,
    out: &mut Vec<(Photon, Path)>,
) {
    // Choose a light by luminous power.
    let light = &lights[pick_index(lights.iter().map(|e| luminance(e.power())), sampler.uniform() * total)];
    let probability = luminance(light.power()) / total;
    let mut power = light.power() / (probability * count as f64);
    let mut ray = match *light {
        Emitter::Point { position, .. } => {
            Ray { origin: position, dir: uniform_sphere(sampler.uniform(), sampler.uniform()) }
        }
        Emitter::Quad { corner, edge_u, edge_v, .. } => {
            let point = corner + edge_u * sampler.uniform() + edge_v * sampler.uniform();
            let normal = edge_u.cross(edge_v).normalize();
            let dir = cosine_direction(normal, sampler.uniform(), sampler.uniform());
            Ray { origin: spawn_origin::<f64>(point, normal, dir), dir }
        }
    };
    let mut path = Path::Direct;
    for _ in 0..MAX_BOUNCES {
        let Some(hit) = scene.closest_hit(&ray, 0.0, f64::INFINITY) else { return };
        let material = scene.objects()[hit.object].material;
        let normal = facing_normal(&ray, &hit);
        if diffuse_part(material).max_element() > 0.0 {
            out.push((Photon { position: hit.point, direction: ray.dir, normal, power }, path));
        }
        let u = sampler.uniform();
        let next = match material {
            Material::Emitter { .. } => return,
            Material::Diffuse { albedo } => {
                let survive = albedo.max_element();
                if u >= survive {
                    return;
                }
                power *= albedo / survive;
                path = Path::AfterDiffuse;
                cosine_direction(normal, sampler.uniform(), sampler.uniform())
            }
            Material::Glossy { diffuse, specular, exponent } => {
                let (p_diffuse, p_specular) = (diffuse.max_element(), specular.max_element());
                path = Path::AfterDiffuse;
                if u < p_diffuse {
                    power *= diffuse / p_diffuse;
                    cosine_direction(normal, sampler.uniform(), sampler.uniform())
                } else if u < p_diffuse + p_specular {
                    let mirror = reflected_ray(&ray, &hit).dir;
                    let dir = phong_direction(mirror, exponent, sampler.uniform(), sampler.uniform());
                    let cosine = dir.dot(normal);
                    if cosine <= 0.0 {
                        return;
                    }
                    // f_s cosθ / pdf = ks (n+2)/(n+1) cosθ with pdf = (n+1)/(2π) cosⁿα.
                    power *= specular / p_specular * ((exponent + 2.0) / (exponent + 1.0) * cosine);
                    dir
                } else {
                    return;
                }
            }
            Material::Mirror { .. } | Material::Glass { .. } => {
                path = specular_step(path);
                let Some(next) = specular_bounce(&ray, &hit, material, &mut power, u) else { return };
                ray = next;
                continue;
            }
        };
        ray = Ray { origin: spawn_origin::<f64>(hit.point, hit.normal, next), dir: next };
    }
}

/// Photon `index` of `count` traced by `trace` into its own output, in parallel chunks of fixed
/// size concatenated in order: the result does not depend on the number of threads.
fn in_ordered_chunks<T: Send>(count: usize, trace: impl Fn(usize, &mut Vec<T>) + Sync) -> Vec<T> {
    let chunk = 4096;
    let stored: Vec<Vec<T>> = (0..count.div_ceil(chunk))
        .into_par_iter()
        .map(|c| {
            let mut out = Vec::new();
            for index in (c * chunk)..((c + 1) * chunk).min(count) {
                trace(index, &mut out);
            }
            out
        })
        .collect();
    stored.into_iter().flatten().collect()
}

/// The index whose cumulative weight first exceeds `target` (a number in `[0, Σ weights)`): a
/// choice with probability proportional to the weights. Rounding can leave `target` at the very
/// end of the range; the last index takes it.
fn pick_index(weights: impl ExactSizeIterator<Item = f64>, mut target: f64) -> usize {
    let last = weights.len() - 1;
    weights
        .enumerate()
        .find(|&(_, weight)| {
            target -= weight;
            target < 0.0
        })
        .map_or(last, |(index, _)| index)
}

/// The photon leaving a mirror or glass hit: a mirror reflects with probability
/// `max(reflectance)` (Russian roulette, drawn from `u`; `power` is rescaled by
/// `reflectance / max(reflectance)`), glass reflects with the Fresnel probability and refracts
/// otherwise (power unchanged). `None` when the photon is absorbed or the material is not specular.
fn specular_bounce(ray: &Ray<f64>, hit: &Hit, material: Material, power: &mut DVec3, u: f64) -> Option<Ray<f64>> {
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

/// The diffuse albedo of a material (zero for mirrors, glass and emitters): photons are stored
/// where it is non-zero.
fn diffuse_part(material: Material) -> DVec3 {
    match material {
        Material::Diffuse { albedo } => albedo,
        Material::Glossy { diffuse, .. } => diffuse,
        Material::Mirror { .. } | Material::Glass { .. } | Material::Emitter { .. } => DVec3::ZERO,
    }
}

fn specular_step(path: Path) -> Path {
    match path {
        Path::Direct | Path::SpecularOnly => Path::SpecularOnly,
        Path::AfterDiffuse => Path::AfterDiffuse,
    }
}

/// A direction about unit `axis` with density `(n+1)/(2π) cosⁿα` (α the angle to `axis`).
fn phong_direction(axis: DVec3, exponent: f64, u1: f64, u2: f64) -> DVec3 {
    let cos_alpha = u1.powf(1.0 / (exponent + 1.0));
    let sin_alpha = (1.0 - cos_alpha * cos_alpha).max(0.0).sqrt();
    let phi = 2.0 * PI * u2;
    let (tangent, bitangent) = axis.any_orthonormal_pair();
    (tangent * (sin_alpha * phi.cos()) + bitangent * (sin_alpha * phi.sin()) + axis * cos_alpha).normalize()
}

/// The white-furnace scene: a closed unit sphere of grey albedo `albedo` with an isotropic point
/// light of intensity `intensity` at its centre. Every point of the wall receives the irradiance
/// `E = Φ/(A(1 − ρ)) = I/(1 − ρ)` (direct `I` at distance 1, plus the geometric series of uniform
/// interreflection), the exact reference of the photon-map tests and accuracy bench.
///
/// # Errors
/// [`crate::geometry::InputError`] for an albedo outside `[0, 1]` or a negative or non-finite intensity.
///
/// # Examples
/// ```
/// let scene = hw3::render::photon::furnace_sphere(0.5, 1.0).unwrap();
/// assert_eq!(scene.objects().len(), 1);
/// assert!(hw3::render::photon::furnace_sphere(1.5, 1.0).is_err());
/// ```
pub fn furnace_sphere(albedo: f64, intensity: f64) -> Result<Scene, crate::geometry::InputError> {
    let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 0.5), DVec3::ZERO, 40.0);
    let shell = Object::sphere(Sphere::new(DVec3::ZERO, 1.0)?, Material::Diffuse { albedo: DVec3::splat(albedo) });
    let lamp = PointLight { position: DVec3::ZERO, intensity: DVec3::splat(intensity) };
    Scene::new(camera, vec![shell], vec![lamp], None, DVec3::ZERO)
}

/// `n` points spread evenly over the unit sphere (a Fibonacci lattice), in a fixed order: the
/// query points of the furnace measurements.
///
/// # Examples
/// ```
/// let points = hw3::render::photon::fibonacci_sphere(100);
/// assert!(points.iter().all(|p| (p.length() - 1.0).abs() < 1e-12));
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

    fn closed_sphere(albedo: f64, intensity: f64) -> Scene {
        furnace_sphere(albedo, intensity).unwrap()
    }

    /// White furnace: inside a closed unit sphere of albedo ρ with a point light `I` at the
    /// centre, every point receives `E = Φ/(A(1 − ρ)) = I/(1 − ρ)` (direct `I/r²` plus the
    /// geometric series of uniform interreflection). The cap within chord distance r of a sphere
    /// has area exactly πr² (Archimedes), so the disc assumption adds no curvature bias. The noise
    /// left is the count of photons Russian roulette keeps: with 2·10⁵ photons the indirect map
    /// holds ≥ 8·10⁴, a relative spread ≈ 1/√(8·10⁴) ≈ 0.35 % (measured over seeds 1–4 at
    /// 6·10⁴ photons: within 1.3 %, as that size predicts); the 1000 query points at k = 100
    /// cover the sphere about once, so the kNN estimate adds little on top: tolerance 1 %.
    #[test]
    fn photon_map_furnace_gives_the_analytic_irradiance_within_one_percent() {
        for albedo in [0.3, 0.7] {
            let intensity = 2.0;
            let maps = trace_photons(&closed_sphere(albedo, intensity), 200_000, 5).unwrap();
            let points = fibonacci_sphere(1000);
            let mean = points.iter().map(|&p| maps.all.irradiance(p, 100).unwrap().x).sum::<f64>() / 1000.0;
            let exact = intensity / (1.0 - albedo);
            assert!((mean / exact - 1.0).abs() < 0.01, "ρ = {albedo}: {mean} vs {exact}");
            // The indirect map alone carries the interreflected part ρ/(1 − ρ) · I.
            let indirect = points.iter().map(|&p| maps.indirect.irradiance(p, 100).unwrap().x).sum::<f64>() / 1000.0;
            let exact_indirect = intensity * albedo / (1.0 - albedo);
            assert!((indirect / exact_indirect - 1.0).abs() < 0.01, "ρ = {albedo}: {indirect}");
            assert!(maps.caustic.is_empty(), "no specular surface, no caustic photon");
        }
    }

    /// Emission carries the light's flux: inside a closed grey sphere every emitted photon lands
    /// once before any bounce, so the first-hit powers (the `all` map less the `indirect` one)
    /// sum to `Φ = πLA` for a quad light and `Φ = 4πI` for a point light, per channel, to
    /// rounding.
    #[test]
    fn first_hit_powers_sum_to_the_light_flux() {
        let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 0.5), DVec3::ZERO, 40.0);
        let grey =
            Object::sphere(Sphere::new(DVec3::ZERO, 5.0).unwrap(), Material::Diffuse { albedo: DVec3::splat(0.5) });
        let radiance = DVec3::new(1.0, 2.0, 3.0);
        let panel = Object::quad(
            DVec3::new(-0.5, 1.0, -0.5),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 0.0, 2.0),
            Material::Emitter { radiance },
        );
        let intensity = DVec3::new(0.25, 0.5, 1.0);
        let lamp = PointLight { position: DVec3::ZERO, intensity };
        let cases =
            [(vec![grey, panel], vec![], radiance * (PI * 2.0)), (vec![grey], vec![lamp], intensity * (4.0 * PI))];
        for (objects, lights, flux) in cases {
            let scene = Scene::new(camera, objects, lights, None, DVec3::ZERO).unwrap();
            let maps = trace_photons(&scene, 5000, 3).unwrap();
            let power = |map: &PhotonMap| map.photons().iter().map(|p| p.power).sum::<DVec3>();
            let direct = power(&maps.all) - power(&maps.indirect);
            assert!(((direct - flux) / flux).abs().max_element() < 1e-9, "{direct} vs {flux}");
            assert_eq!(maps.all.len() - maps.indirect.len(), 5000, "one first hit per photon");
        }
    }

    #[test]
    fn traces_are_identical_for_one_and_two_threads() {
        let scene = crate::render::scenes::cornell_mirror().unwrap();
        let run = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| trace_photons(&scene, 10_000, 9).unwrap())
        };
        let (one, two) = (run(1), run(2));
        assert_eq!(one.all.photons(), two.all.photons());
        assert_eq!(one.caustic.photons(), two.caustic.photons());
        assert!(!one.caustic.is_empty(), "the mirror makes caustic photons");
    }

    #[test]
    fn bad_counts_and_neighbour_numbers_are_typed_errors() {
        let scene = closed_sphere(0.5, 1.0);
        assert_eq!(trace_photons(&scene, 0, 1).unwrap_err(), PhotonError::PhotonCount(0));
        assert_eq!(trace_photons(&scene, MAX_PHOTONS + 1, 1).unwrap_err(), PhotonError::PhotonCount(MAX_PHOTONS + 1));
        let dark = closed_sphere(0.5, 0.0);
        assert_eq!(trace_photons(&dark, 10, 1).unwrap_err(), PhotonError::NoLight);
        let maps = trace_photons(&scene, 100, 1).unwrap();
        let stored = maps.all.len();
        for k in [0, 1] {
            assert_eq!(maps.all.irradiance(DVec3::Z, k).unwrap_err(), PhotonError::NeighbourCount(k));
        }
        assert_eq!(
            maps.all.irradiance(DVec3::Z, stored + 1).unwrap_err(),
            PhotonError::TooFewPhotons { requested: stored + 1, stored }
        );
        assert!(maps.all.irradiance(DVec3::Z, stored).is_ok());
        let empty = PhotonMap::new(vec![]);
        assert_eq!(empty.irradiance(DVec3::Z, 2).unwrap_err(), PhotonError::TooFewPhotons { requested: 2, stored: 0 });
    }

    /// kiddo issue #158: trees over many points sharing coordinates. 5000 photons at one point
    /// plus a ring around it: the k nearest are found, and a query whose k nearest all coincide
    /// with it is a typed error, not an infinite irradiance.
    #[test]
    fn duplicate_photon_positions_are_handled() {
        let photon = |position| Photon { position, direction: DVec3::NEG_Z, normal: DVec3::Z, power: DVec3::ONE };
        let mut photons = vec![photon(DVec3::ZERO); 5000];
        photons.extend((0..100).map(|i| {
            let angle = f64::from(i) * 2.0 * PI / 100.0;
            photon(DVec3::new(angle.cos(), angle.sin(), 0.0))
        }));
        let map = PhotonMap::new(photons);
        assert_eq!(map.irradiance(DVec3::ZERO, 100).unwrap_err(), PhotonError::CoincidentPhotons(100));
        // From 2 units away the 5000 duplicates are the nearest; the 5001st is on the ring.
        let (nearest, r2) = map.nearest(DVec3::new(0.0, 0.0, 2.0), 5001).unwrap();
        assert_eq!(nearest.iter().filter(|p| p.position == DVec3::ZERO).count(), 5000);
        assert!((r2 - 5.0).abs() < 1e-12);
    }

    /// The (k−1)/(πr²) estimate is unbiased for uniformly scattered photons; k/(πr²) is high by
    /// k/(k−1). 400 independent maps of 2000 unit photons on the unit square (density 2000),
    /// queried at the centre with k = 4: mean of (k−1) form within 3σ of 2000, k form ≈ 4/3 high.
    #[test]
    fn bias_correction_removes_the_k_over_k_minus_one_factor() {
        let k = 4;
        let trials = 400;
        let mut corrected = 0.0;
        for trial in 0..trials {
            let mut sampler = Sampler::new(17, trial, 0);
            let photons = (0..2000)
                .map(|_| Photon {
                    position: DVec3::new(sampler.uniform(), sampler.uniform(), 0.0),
                    direction: DVec3::NEG_Z,
                    normal: DVec3::Z,
                    power: DVec3::ONE,
                })
                .collect();
            corrected += PhotonMap::new(photons).irradiance(DVec3::new(0.5, 0.5, 0.0), k).unwrap().x;
        }
        let mean = corrected / trials as f64;
        // Var of (k−1)/(πr²) is λ²/(k−2): std of the mean = 2000/√(2·400) ≈ 71.
        assert!((mean - 2000.0).abs() < 3.0 * 71.0, "corrected {mean}");
        let uncorrected = mean * k as f64 / (k - 1) as f64;
        assert!((uncorrected - 2000.0).abs() > 3.0 * 71.0, "k/(πr²) would be visibly high: {uncorrected}");
    }

    #[test]
    fn phong_directions_follow_the_lobe() {
        let axis = DVec3::new(0.0, 0.6, 0.8);
        let mut sampler = Sampler::new(3, 0, 0);
        let exponent = 20.0;
        let n = 20_000;
        let mean: f64 = (0..n)
            .map(|_| phong_direction(axis, exponent, sampler.uniform(), sampler.uniform()).dot(axis))
            .sum::<f64>()
            / f64::from(n);
        // E[cosα] = (n+1)/(n+2) for the density (n+1)/(2π) cosⁿα.
        assert!((mean - 21.0 / 22.0).abs() < 2e-3, "{mean}");
    }

    /// Directional albedo `∫ f_r(ω_o, ω_i) cosθ_i dω_i` of a diffuse or glossy material at
    /// incidence angle `theta` (radians), by the midpoint rule in polar coordinates about the
    /// mirror direction, where the Phong lobe is narrow (`steps` angles from it × 256 azimuths).
    fn directional_albedo(material: &Material, theta: f64, steps: usize) -> f64 {
        let normal = DVec3::Z;
        let to_eye = DVec3::new(theta.sin(), 0.0, theta.cos());
        let mirror = crate::geometry::sphere::reflect::<f64>(-to_eye, normal);
        let (tangent, bitangent) = mirror.any_orthonormal_pair();
        let azimuths = 256;
        let (d_alpha, d_phi) = (PI / steps as f64, 2.0 * PI / f64::from(azimuths));
        let mut total = 0.0;
        for i in 0..steps {
            let alpha = (i as f64 + 0.5) * d_alpha;
            for j in 0..azimuths {
                let phi = (f64::from(j) + 0.5) * d_phi;
                let dir =
                    tangent * (alpha.sin() * phi.cos()) + bitangent * (alpha.sin() * phi.sin()) + mirror * alpha.cos();
                let cosine = dir.dot(normal);
                if cosine > 0.0 {
                    total += brdf(material, to_eye, dir, normal).x * cosine * alpha.sin() * d_alpha * d_phi;
                }
            }
        }
        total
    }

    /// Energy conservation, which Russian roulette relies on (a survival probability is an
    /// albedo): every material reflects at most what arrives. Diffuse: exactly its albedo. The
    /// normalised Phong lobe: exactly `kd + ks` at normal incidence (the lobe lies inside the
    /// hemisphere), less towards grazing where the horizon clips it, for exponents 1 to 10⁴.
    /// Glass: Fresnel reflectance plus the transmittance computed from the transmission
    /// amplitudes, `T = (n₂cosθ_t)/(n₁cosθ_i)·(t_s² + t_p²)/2`, is 1 (from either side).
    #[test]
    fn every_material_reflects_at_most_what_arrives() {
        let diffuse = Material::Diffuse { albedo: DVec3::splat(0.8) };
        for degrees in [0.0, 30.0, 60.0, 85.0] {
            let albedo = directional_albedo(&diffuse, f64::to_radians(degrees), 400);
            // Around the mirror direction the hemisphere's edge cuts cells: 1e-3 is quadrature.
            assert!((albedo - 0.8).abs() < 2e-3, "diffuse at {degrees}°: {albedo}");
        }
        for exponent in [1.0, 10.0, 100.0, 1e4] {
            let glossy = Material::Glossy { diffuse: DVec3::splat(0.2), specular: DVec3::splat(0.8), exponent };
            let normal_incidence = directional_albedo(&glossy, 0.0, 2000);
            assert!((normal_incidence - 1.0).abs() < 2e-3, "n = {exponent}: {normal_incidence}");
            let mut previous = normal_incidence;
            for degrees in [30.0, 60.0, 85.0] {
                let albedo = directional_albedo(&glossy, f64::to_radians(degrees), 2000);
                assert!(albedo <= 1.0 + 2e-3 && albedo <= previous + 2e-3, "n = {exponent} at {degrees}°: {albedo}");
                previous = albedo;
            }
        }
        let hit = crate::render::scene::Hit { t: 1.0, point: DVec3::ZERO, normal: DVec3::Z, object: 0 };
        for index in [1.0, 1.33, 1.5, 2.4] {
            for degrees in [0.0, 20.0, 40.0, 70.0, 89.0] {
                for inside in [false, true] {
                    let theta = f64::to_radians(degrees);
                    let side = if inside { 1.0 } else { -1.0 };
                    let ray = Ray { origin: DVec3::ZERO, dir: DVec3::new(theta.sin(), 0.0, side * theta.cos()) };
                    let split = dielectric_split(&ray, &hit, index);
                    let (n1, n2) = if inside { (index, 1.0) } else { (1.0, index) };
                    let transmitted = split.refracted.map_or(0.0, |refracted| {
                        let (cos_i, cos_t) = (theta.cos(), refracted.dir.z.abs());
                        let t_s = 2.0 * n1 * cos_i / (n1 * cos_i + n2 * cos_t);
                        let t_p = 2.0 * n1 * cos_i / (n2 * cos_i + n1 * cos_t);
                        n2 * cos_t / (n1 * cos_i) * (t_s * t_s + t_p * t_p) / 2.0
                    });
                    let sum = split.reflectance + transmitted;
                    assert!((sum - 1.0).abs() < 1e-12, "n = {index}, {degrees}°, inside {inside}: R + T = {sum}");
                }
            }
        }
    }

    /// Aimed photons carry exactly the flux into the cone: a point light at the centre of a
    /// closed grey sphere (radius 5) and a glass ball (radius 1) 3 units away. Every direction
    /// in the ball's cone (half-angle asin(1/3)) hits the ball, glass absorbs nothing and a ray
    /// leaving a sphere is never totally reflected, so every photon lands on the shell, and
    /// their powers add up to `I · 2π(1 − cos α)` to rounding.
    #[test]
    fn caustic_photons_carry_the_flux_into_the_target_cone() {
        let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 0.5), DVec3::ZERO, 40.0);
        let shell =
            Object::sphere(Sphere::new(DVec3::ZERO, 5.0).unwrap(), Material::Diffuse { albedo: DVec3::splat(0.5) });
        let ball = Object::sphere(Sphere::new(DVec3::new(0.0, 3.0, 0.0), 1.0).unwrap(), Material::Glass { index: 1.5 });
        let intensity = DVec3::new(1.0, 2.0, 3.0);
        let lamp = PointLight { position: DVec3::ZERO, intensity };
        let scene = Scene::new(camera, vec![shell, ball], vec![lamp], None, DVec3::ZERO).unwrap();
        let map = trace_caustic_photons(&scene, 20_000, 4).unwrap();
        assert_eq!(map.len(), 20_000, "every aimed photon is stored once");
        let cos_alpha = (1.0 - 1.0 / 9.0f64).sqrt();
        let flux = intensity * (2.0 * PI * (1.0 - cos_alpha));
        let stored: DVec3 = map.photons().iter().map(|p| p.power).sum();
        assert!(((stored - flux) / flux).abs().max_element() < 1e-9, "{stored} vs {flux}");
        let none = Scene::new(camera, vec![shell], vec![lamp], None, DVec3::ZERO).unwrap();
        assert!(trace_caustic_photons(&none, 20_000, 4).unwrap().is_empty(), "no glass, nothing traced");
        assert_eq!(trace_caustic_photons(&scene, 0, 4).unwrap_err(), PhotonError::PhotonCount(0));
    }

    /// Aiming changes the noise, not the answer: on the `caustic` scene (a quad light, whose
    /// aimed photons carry `L A cos θ_l Ω / (p N)`) the total caustic power stored by
    /// [`trace_caustic_photons`] equals that of the untargeted [`trace_photons`]' caustic map,
    /// whose photons each carry `Φ/N` and of which a binomial number land: within 4 of that
    /// count's standard deviations.
    #[test]
    fn aimed_and_untargeted_caustic_maps_carry_the_same_power() {
        let scene = crate::render::scenes::glass_ball_caustic().unwrap();
        let aimed: f64 = trace_caustic_photons(&scene, 20_000, 5).unwrap().photons().iter().map(|p| p.power.x).sum();
        let maps = trace_photons(&scene, 200_000, 6).unwrap();
        let caustic = maps.caustic.photons();
        let each = caustic[0].power.x;
        let untargeted = each * caustic.len() as f64;
        let sigma = each * (caustic.len() as f64).sqrt();
        assert!((aimed - untargeted).abs() < 4.0 * sigma, "aimed {aimed}, untargeted {untargeted} ± {sigma}");
    }

    /// A caustic in the caustic map: a glass ball (n = 1.5, radius 1, focal length 1.5 from its
    /// centre) over a white floor, lit by a point light 10 units up. Under the ball the caustic
    /// map's irradiance exceeds the unobstructed direct irradiance `I/h²` fifty times over (the
    /// ball gathers the light of its cross-section π into a small spot), while in the open
    /// floor beside it the caustic map is empty of photons nearby: only `LS+D` photons are in it.
    #[test]
    fn a_glass_ball_focuses_photons_into_the_caustic_map() {
        let camera = Camera::looking_at(DVec3::new(0.0, 3.0, 6.0), DVec3::ZERO, 40.0);
        let floor = Object::quad(
            DVec3::new(-10.0, 0.0, 10.0),
            DVec3::new(20.0, 0.0, 0.0),
            DVec3::new(0.0, 0.0, -20.0),
            Material::Diffuse { albedo: DVec3::splat(0.5) },
        );
        let ball = Object::sphere(Sphere::new(DVec3::new(0.0, 1.5, 0.0), 1.0).unwrap(), Material::Glass { index: 1.5 });
        let intensity = 100.0;
        let lamp = PointLight { position: DVec3::new(0.0, 11.5, 0.0), intensity: DVec3::splat(intensity) };
        let scene = Scene::new(camera, vec![floor, ball], vec![lamp], None, DVec3::ZERO).unwrap();
        let maps = trace_photons(&scene, 100_000, 2).unwrap();
        let open_floor = intensity / (11.5 * 11.5);
        let focus = maps.caustic.irradiance(DVec3::ZERO, 50).unwrap().x;
        // Measured 351× (seed 2, k = 50); a ball without focusing would leave only its shadow.
        assert!(focus > 50.0 * open_floor, "caustic {focus} vs open floor {open_floor}");
        let (_, r2) = maps.caustic.nearest(DVec3::new(6.0, 0.0, 0.0), 2).unwrap();
        assert!(r2 > 1.0, "no caustic photon within 1 unit of a point 6 units from the ball");
    }
}
