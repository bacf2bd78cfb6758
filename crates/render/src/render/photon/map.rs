//! The photon map: stored photons, their kd-tree, and the density estimates read from it.

use super::point_tree::PointTree;
use crate::render::bsdf::brdf;
use crate::render::scene::Material;
use glam::DVec3;
use std::f64::consts::PI;

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
    /// A density asked for at a point with an infinite or NaN coordinate.
    #[error("the query point must be finite")]
    QueryPoint,
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

/// A set of photons with a kd-tree over their positions ([`PointTree`]) for k-nearest queries.
#[derive(Debug)]
pub struct PhotonMap {
    photons: Vec<Photon>,
    tree: PointTree,
}

impl PhotonMap {
    /// A map of `photons` (possibly empty; queries on an empty map are typed errors).
    ///
    /// Photons at identical coordinates are accepted: among photons at equal distance from a
    /// query the earlier-stored one counts first.
    ///
    /// # Panics
    /// For more than `u32::MAX` photons (one trace reaches that only if nearly every one of
    /// [`MAX_PHOTONS`] emitted photons were stored at all [`MAX_BOUNCES`] bounces: 2³² photons,
    /// hundreds of GB) or a photon at a NaN position (the tracer stores only finite hit points);
    /// see [`PointTree::new`].
    #[must_use]
    pub fn new(photons: Vec<Photon>) -> Self {
        let points: Vec<DVec3> = photons.iter().map(|p| p.position).collect();
        let tree = PointTree::new(&points);
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
    /// holds fewer than `k`, [`PhotonError::QueryPoint`] for a point that is not finite,
    /// [`PhotonError::CoincidentPhotons`] when the `k`-th is at distance 0.
    pub fn nearest(&self, point: DVec3, k: usize) -> Result<(Vec<&Photon>, f64), PhotonError> {
        if k < 2 {
            return Err(PhotonError::NeighbourCount(k));
        }
        if k > self.photons.len() {
            return Err(PhotonError::TooFewPhotons { requested: k, stored: self.photons.len() });
        }
        if !point.is_finite() {
            return Err(PhotonError::QueryPoint);
        }
        let found = self.tree.nearest(point, k, f64::INFINITY);
        let radius_squared = found.last().map_or(0.0, |n| n.distance_squared);
        if !(radius_squared > 0.0) {
            return Err(PhotonError::CoincidentPhotons(k));
        }
        Ok((found.iter().map(|n| &self.photons[n.index as usize]).collect(), radius_squared))
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
    /// use hw3_render::render::photon::{Photon, PhotonMap};
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
    /// use hw3_render::render::{catalogue::furnace_sphere, photon::trace_photons, sampling::fibonacci_sphere};
    /// use hw3_render::render::scene::Material;
    /// // Furnace, ρ = 0.5, I = 1: L = ρE/π with E = 2 at every wall point.
    /// let maps = trace_photons(&furnace_sphere(0.5, 1.0).unwrap(), 20_000, 1).unwrap();
    /// let white = Material::Diffuse { albedo: DVec3::splat(0.5) };
    /// let points = fibonacci_sphere(200);
    /// let mean = points.iter().map(|&p| maps.all().radiance(&white, p, -p, -p, 50).unwrap().x).sum::<f64>() / 200.0;
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
    /// event), the fixed-disc form is used over those `k`. A `point` that is not finite gathers
    /// nothing (zero).
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_render::render::photon::{Gather, Photon, PhotonMap};
    /// use hw3_render::render::scene::Material;
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
        let found = self.tree.nearest(point, k, max_squared);
        let photons = found.iter().map(|n| &self.photons[n.index as usize]);
        match found.last() {
            Some(kth) if found.len() == k && kth.distance_squared > 0.0 => {
                reflected_power(photons.take(k - 1), material, to_eye, normal) / (PI * kth.distance_squared)
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
    /// use hw3_render::render::photon::Gather;
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
