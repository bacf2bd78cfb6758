//! The global photon trace: photons from every light, bounced by every material with Russian
//! roulette, sorted into the three maps of [`PhotonMaps`].

use super::emission::{Emitter, emitters, in_ordered_chunks};
use super::map::{MAX_BOUNCES, MAX_PHOTONS, Photon, PhotonError, PhotonMap};
use crate::render::bsdf::{diffuse_part, facing_normal, reflected_ray, specular_bounce};
use crate::render::color::luminance;
use crate::render::sampling::{Sampler, cosine_direction, phong_direction, pick_index, uniform_sphere};
use crate::render::scene::{Material, Scene};
use hw3_core::geometry::Ray;
use hw3_core::geometry::sphere::spawn_origin;
use std::sync::OnceLock;

/// The three photon maps of one trace (see the module docs for what each keeps).
///
/// The map of every stored photon, [`PhotonMaps::all`], is built on its first use: the
/// renderer's eye pass reads only the indirect and caustic maps, and building a kd-tree over
/// every photon was a third of what `hw3 effect-tables` spent (its twelve traces never read it).
#[derive(Debug)]
pub struct PhotonMaps {
    /// Every photon at every diffuse or glossy hit, in tracing order.
    stored: Vec<Photon>,
    /// The map over `stored`, built by [`PhotonMaps::all`].
    all: OnceLock<PhotonMap>,
    /// Photons after at least one diffuse or glossy bounce.
    pub indirect: PhotonMap,
    /// Photons after specular bounces only (at least one).
    pub caustic: PhotonMap,
    /// Photons emitted.
    pub emitted: usize,
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
/// use hw3_render::render::{photon::trace_photons, catalogue};
/// let maps = trace_photons(&catalogue::cornell_mirror().unwrap(), 2000, 1).unwrap();
/// assert!(maps.photons().len() >= maps.indirect.len() && maps.photons().len() > 1000);
/// assert!(trace_photons(&catalogue::cornell_mirror().unwrap(), 0, 1).is_err());
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
        indirect: keep(|path| path == Path::AfterDiffuse),
        caustic: keep(|path| path == Path::SpecularOnly),
        stored: stored.into_iter().map(|(photon, _)| photon).collect(),
        all: OnceLock::new(),
        emitted: count,
    })
}

impl PhotonMaps {
    /// Every photon at every diffuse or glossy hit, in tracing order, without building a map.
    ///
    /// # Examples
    /// ```
    /// use hw3_render::render::{photon::trace_photons, catalogue};
    /// let maps = trace_photons(&catalogue::cornell_mirror().unwrap(), 2000, 1).unwrap();
    /// assert_eq!(maps.photons().len(), maps.all().len());
    /// ```
    #[must_use]
    pub fn photons(&self) -> &[Photon] {
        &self.stored
    }

    /// The map of every photon at every diffuse or glossy hit, built on the first call (on a
    /// copy of the stored photons) and kept: from then on the trace holds its photons twice.
    /// Threads that ask at once before it is kept each build one (the same map) and the first is
    /// kept: none waits for another's build, which may run on the rayon pool (above 2¹⁴ photons),
    /// so a pool thread can never wait for a build that needs it. Each such build copies the
    /// photons, so call it once before reading the map from parallel jobs.
    ///
    /// # Examples
    /// ```
    /// use hw3_render::render::{photon::trace_photons, catalogue};
    /// let maps = trace_photons(&catalogue::cornell_mirror().unwrap(), 2000, 1).unwrap();
    /// let direct = maps.all().len() - maps.indirect.len() - maps.caustic.len();
    /// assert!(direct > 0 && std::ptr::eq(maps.all(), maps.all()));
    /// ```
    #[must_use]
    pub fn all(&self) -> &PhotonMap {
        if let Some(map) = self.all.get() {
            return map;
        }
        // Built outside the cell: a rayon worker that waits for its build's other half runs
        // whatever job it can steal meanwhile, and one that asks for this map would otherwise wait
        // in `get_or_init` for the build beneath it on the same thread.
        let map = PhotonMap::new(self.stored.clone());
        self.all.get_or_init(|| map)
    }

    /// The map of every stored photon, taken out of the trace (no copy when it was not built yet).
    ///
    /// # Examples
    /// ```
    /// use hw3_render::render::{photon::trace_photons, catalogue};
    /// let map = trace_photons(&catalogue::cornell_mirror().unwrap(), 2000, 1).unwrap().into_all();
    /// assert!(map.len() > 1000);
    /// ```
    #[must_use]
    pub fn into_all(self) -> PhotonMap {
        self.all.into_inner().unwrap_or_else(|| PhotonMap::new(self.stored))
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

fn specular_step(path: Path) -> Path {
    match path {
        Path::Direct | Path::SpecularOnly => Path::SpecularOnly,
        Path::AfterDiffuse => Path::AfterDiffuse,
    }
}
