//! The two integrators: Whitted-style eye-ray tracing and a path tracer (the reference), sharing
//! direct lighting, Beer–Lambert transmittance and single scattering from point lights.
//!
//! Both integrators consume random numbers only where the scene needs them (pixel jitter,
//! area-light samples, diffuse bounces), and the shutter time comes from a *separate* stream, so a
//! pass that is switched on for a scene that does not need it consumes no random number that would
//! shift the others: that is what makes "forced on, image identical" testable bit for bit.

use super::bsdf::{brdf, dielectric_split, facing_normal, front_side, reflected_ray};
use super::environment::ENVIRONMENT_SAMPLES;
use super::medium;
use super::passes::{Pass, Passes};
use super::photon::{Gather, PhotonMap};
use super::sampling::{Sampler, cosine_direction};
use super::scene::{Hit, Material, Scene};
use glam::DVec3;
use hw3_core::geometry::Ray;
use hw3_core::geometry::sphere::spawn_origin;
use std::f64::consts::PI;

/// Which light transport algorithm a render uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum Integrator {
    /// Eye rays, shadow rays to every light, recursion through mirrors up to `max_depth`
    /// reflections (`L(D|G)?S*E` plus fog glow).
    Whitted {
        /// Maximum number of mirror reflections.
        max_depth: u32,
    },
    /// Unidirectional path tracing with next-event estimation, cosine-weighted bounces, and
    /// `max_depth` bounces at most (`L(D|G|S)*E`; caustics from area lights only).
    PathTracer {
        /// Maximum number of bounces.
        max_depth: u32,
    },
    /// [`Integrator::PathTracer`] with Russian roulette: at each diffuse or glossy bounce from
    /// the [`ROULETTE_FROM`]th on, a path goes on with probability `q = min(1, max channel of
    /// its throughput)` and its throughput is divided by `q`, so the estimate keeps its mean
    /// while paths that carry little light end early. Each sample is a little noisier and, in a
    /// closed scene (where without roulette almost every path runs to `max_depth`), much cheaper:
    /// the published Cornell box at 12 bounces costs 0.56 times the CPU time per sample for
    /// 1.10 times the noise (Arvo and Kirk, "Particle transport and image synthesis", SIGGRAPH
    /// 1990; Pharr, Jakob and Humphreys, *Physically Based Rendering*, 3rd edition, section 13.7).
    PathTracerWithRoulette {
        /// Maximum number of bounces.
        max_depth: u32,
    },
}

/// The vertex of the path (counted from 0 at the camera ray's hit, mirror and glass vertices
/// included) from which [`Integrator::PathTracerWithRoulette`] plays Russian roulette at its
/// diffuse and glossy bounces: the first bounces, which carry most of the light, always go on.
///
/// # Examples
/// ```
/// assert_eq!(hw3_render::render::integrator::ROULETTE_FROM, 3);
/// ```
pub const ROULETTE_FROM: u32 = 3;

impl Integrator {
    /// The passes of `plan` this integrator can run: Whitted tracing has no indirect bounces, so the plan
    /// drops [`Pass::IndirectBounces`] for it (the class is then reported, not rendered); the
    /// path tracer reads no photon map, so it drops [`Pass::Caustics`] (it finds caustics from
    /// area lights and the environment by its own bounces, and none from point lights).
    ///
    /// # Examples
    /// ```
    /// use hw3_render::render::{integrator::Integrator, passes::{Pass, Passes}};
    /// let whitted = Integrator::Whitted { max_depth: 8 }.restrict(Passes::all());
    /// assert!(!whitted.get(Pass::IndirectBounces) && whitted.get(Pass::Caustics));
    /// let path = Integrator::PathTracer { max_depth: 8 }.restrict(Passes::all());
    /// assert!(path.get(Pass::IndirectBounces) && !path.get(Pass::Caustics));
    /// ```
    #[must_use]
    pub fn restrict(self, plan: Passes) -> Passes {
        match self {
            Integrator::Whitted { .. } => plan.with(Pass::IndirectBounces, false),
            Integrator::PathTracer { .. } | Integrator::PathTracerWithRoulette { .. } => {
                plan.with(Pass::Caustics, false)
            }
        }
    }
}

/// Number of equiangular quadrature steps for the single-scattering integral along one segment.
/// The integrand in the angle variable is smooth, and the midpoint rule reaches 1 % with 4–16
/// steps (checked against [`super::medium::airlight_closed_form`]); 32 leaves margin for shadowed stretches.
pub const IN_SCATTER_STEPS: usize = 32;

/// Radiance along rays of one scene with one pass plan.
#[derive(Debug, Clone, Copy)]
pub struct Tracer<'a> {
    scene: &'a Scene,
    passes: Passes,
    in_scatter_steps: usize,
    caustics: Option<(&'a PhotonMap, Gather)>,
    indirect: Option<(&'a PhotonMap, Gather)>,
    light_samples: u32,
}

impl<'a> Tracer<'a> {
    /// A tracer for `scene` running `passes`.
    #[must_use]
    pub fn new(scene: &'a Scene, passes: Passes) -> Self {
        Self { scene, passes, in_scatter_steps: IN_SCATTER_STEPS, caustics: None, indirect: None, light_samples: 1 }
    }

    /// The scene this tracer traces.
    #[must_use]
    pub fn scene(&self) -> &'a Scene {
        self.scene
    }

    /// The same tracer reading the caustic photon map `map` with `gather` at every diffuse or
    /// glossy hit of Whitted tracing (the path tracer ignores it). An empty map adds nothing:
    /// not even a `+ 0.0`, so the image is bit-identical to a render without it.
    #[must_use]
    pub fn with_caustics(self, map: &'a PhotonMap, gather: Gather) -> Self {
        Self { caustics: Some((map, gather)), ..self }
    }

    /// The same tracer also reading the *indirect* photon map `map` (photons after a diffuse or
    /// glossy bounce, [`super::photon::PhotonMaps::indirect`]) with `gather` at every diffuse or
    /// glossy hit of Whitted tracing: the eye pass of two-pass rendering and of photon mapping.
    /// Added before the caustic map's estimate; an empty map adds nothing (bit for bit), and so
    /// does a tracer without it. A `gather` of `k` neighbours within [`f64::MAX`] is the plain
    /// `k`-nearest estimate [`PhotonMap::radiance`], and zero for a map of fewer than `k` photons.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_core::geometry::Ray;
    /// use hw3_render::render::{catalogue, integrator::{Integrator, Tracer}, passes::Passes, photon};
    /// use hw3_render::render::sampling::Sampler;
    /// let scene = catalogue::cornell_mirror().unwrap();
    /// let maps = photon::trace_photons(&scene, 5_000, 1).unwrap();
    /// let gather = photon::Gather::new(20, f64::MAX).unwrap();
    /// let ray = Ray { origin: scene.camera().eye, dir: (scene.camera().look_at - scene.camera().eye).normalize() };
    /// let whitted = Integrator::Whitted { max_depth: 0 };
    /// let direct = Tracer::new(&scene, Passes::default()).radiance(whitted, &ray, 0.0, &mut Sampler::new(1, 0, 0));
    /// let both = Tracer::new(&scene, Passes::default()).with_indirect(&maps.indirect, gather);
    /// assert!(both.radiance(whitted, &ray, 0.0, &mut Sampler::new(1, 0, 0)).x > direct.x); // the bounce light
    /// ```
    #[must_use]
    pub fn with_indirect(self, map: &'a PhotonMap, gather: Gather) -> Self {
        Self { indirect: Some((map, gather)), ..self }
    }

    /// The same tracer estimating direct light at every diffuse or glossy hit of Whitted tracing
    /// as the mean of `samples` next-event estimates (≥ 1; each takes one sample per area light
    /// and the environment's samples), where a render would take more eye rays: the eye pass of
    /// the photon methods, whose photon-map estimate does not need them. The path tracer ignores
    /// it, and so do emitters, mirrors, glass and fog glow. One sample (the default) is the
    /// tracer without the option, bit for bit.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_core::geometry::Ray;
    /// use hw3_render::render::{catalogue, integrator::{Integrator, Tracer}, passes::Passes, sampling::Sampler};
    /// let scene = catalogue::cornell_mirror().unwrap();
    /// let ray = Ray { origin: scene.camera().eye, dir: (scene.camera().look_at - scene.camera().eye).normalize() };
    /// let whitted = Integrator::Whitted { max_depth: 0 };
    /// let tracer = Tracer::new(&scene, Passes::default());
    /// let one = tracer.with_light_samples(1).radiance(whitted, &ray, 0.0, &mut Sampler::new(1, 0, 0));
    /// assert_eq!(one, tracer.radiance(whitted, &ray, 0.0, &mut Sampler::new(1, 0, 0)));
    /// let mean = tracer.with_light_samples(64).radiance(whitted, &ray, 0.0, &mut Sampler::new(1, 0, 0));
    /// assert!(mean.x > 0.0 && mean != one);
    /// ```
    #[must_use]
    pub fn with_light_samples(self, samples: u32) -> Self {
        Self { light_samples: samples.max(1), ..self }
    }

    /// The same tracer with `steps` quadrature steps for single scattering (≥ 1).
    #[must_use]
    pub fn with_in_scatter_steps(self, steps: usize) -> Self {
        Self { in_scatter_steps: steps.max(1), ..self }
    }

    /// Radiance arriving along `ray` (unit direction) at `time`, by `integrator`.
    pub fn radiance(&self, integrator: Integrator, ray: &Ray<f64>, time: f64, sampler: &mut Sampler) -> DVec3 {
        match integrator {
            Integrator::Whitted { max_depth } => self.whitted(ray, time, max_depth, sampler),
            Integrator::PathTracer { max_depth } => self.path(ray, time, max_depth, false, sampler),
            Integrator::PathTracerWithRoulette { max_depth } => self.path(ray, time, max_depth, true, sampler),
        }
    }

    fn whitted(&self, ray: &Ray<f64>, time: f64, depth_left: u32, sampler: &mut Sampler) -> DVec3 {
        let hit = self.scene.closest_hit(ray, time, f64::INFINITY);
        let (glow, transmittance) = self.segment(ray, hit, time, sampler);
        let surface = match hit {
            None => self.scene.escaped_radiance(ray.dir),
            Some(hit) => match self.scene.objects()[hit.object].material {
                Material::Emitter { radiance } => front_side(ray, &hit) * radiance,
                Material::Mirror { reflectance } => {
                    if self.passes.specular_recursion && depth_left > 0 {
                        let next = reflected_ray(ray, &hit);
                        reflectance * self.whitted(&next, time, depth_left - 1, sampler)
                    } else {
                        DVec3::ZERO
                    }
                }
                Material::Glass { index } => {
                    if self.passes.specular_recursion && depth_left > 0 {
                        let split = dielectric_split(ray, &hit, index);
                        let reflected = reflected_ray(ray, &hit);
                        let mut total = split.reflectance * self.whitted(&reflected, time, depth_left - 1, sampler);
                        if let Some(refracted) = split.refracted {
                            total +=
                                (1.0 - split.reflectance) * self.whitted(&refracted, time, depth_left - 1, sampler);
                        }
                        total
                    } else {
                        DVec3::ZERO
                    }
                }
                Material::Diffuse { .. } | Material::Glossy { .. } => {
                    let direct = if self.light_samples == 1 {
                        self.direct_light(ray, &hit, time, sampler)
                    } else {
                        (0..self.light_samples).map(|_| self.direct_light(ray, &hit, time, sampler)).sum::<DVec3>()
                            / f64::from(self.light_samples)
                    };
                    let lit = match self.indirect {
                        Some((map, gather)) if !map.is_empty() => direct + self.gathered(map, gather, ray, &hit),
                        _ => direct,
                    };
                    match self.caustics {
                        Some((map, gather)) if !map.is_empty() => lit + self.gathered(map, gather, ray, &hit),
                        _ => lit,
                    }
                }
            },
        };
        glow + transmittance * surface
    }

    fn path(&self, ray: &Ray<f64>, time: f64, max_depth: u32, roulette: bool, sampler: &mut Sampler) -> DVec3 {
        let mut radiance = DVec3::ZERO;
        let mut throughput = DVec3::ONE;
        let mut ray = *ray;
        // Emitters and the background count only when no light sample could have found them:
        // on camera rays and after mirrors.
        let mut counts_emission = true;
        for bounce in 0..=max_depth {
            let hit = self.scene.closest_hit(&ray, time, f64::INFINITY);
            let (glow, transmittance) = self.segment(&ray, hit, time, sampler);
            radiance += throughput * glow;
            throughput *= transmittance;
            let Some(hit) = hit else {
                if counts_emission {
                    radiance += throughput * self.scene.escaped_radiance(ray.dir);
                }
                break;
            };
            match self.scene.objects()[hit.object].material {
                Material::Emitter { radiance: emitted } => {
                    if counts_emission {
                        radiance += throughput * front_side(&ray, &hit) * emitted;
                    }
                    break;
                }
                Material::Mirror { reflectance } => {
                    if !self.passes.specular_recursion || bounce == max_depth {
                        break;
                    }
                    throughput *= reflectance;
                    ray = reflected_ray(&ray, &hit);
                    counts_emission = true;
                }
                Material::Glass { index } => {
                    if !self.passes.specular_recursion || bounce == max_depth {
                        break;
                    }
                    // Reflect or refract with the Fresnel probabilities: the weight stays 1.
                    let split = dielectric_split(&ray, &hit, index);
                    ray = match split.refracted {
                        Some(refracted) if sampler.uniform() >= split.reflectance => refracted,
                        _ => reflected_ray(&ray, &hit),
                    };
                    counts_emission = true;
                }
                material @ (Material::Diffuse { .. } | Material::Glossy { .. }) => {
                    radiance += throughput * self.direct_light(&ray, &hit, time, sampler);
                    if !self.passes.indirect_bounces || bounce == max_depth {
                        break;
                    }
                    let normal = facing_normal(&ray, &hit);
                    let dir = cosine_direction(normal, sampler.uniform(), sampler.uniform());
                    // f · cos / pdf with pdf = cos/π.
                    throughput *= brdf(&material, -ray.dir, dir, normal) * PI;
                    if roulette && bounce >= ROULETTE_FROM {
                        let survival = throughput.max_element().min(1.0);
                        // `!(u < q)` also ends a path whose throughput is 0 or NaN.
                        if !(sampler.uniform() < survival) {
                            break;
                        }
                        throughput /= survival;
                    }
                    ray = Ray { origin: spawn_origin::<f64>(hit.point, hit.normal, dir), dir };
                    counts_emission = false;
                }
            }
        }
        radiance
    }

    /// Single-scattered glow along the segment up to the hit (or to infinity) from point lights
    /// (deterministic) and area lights (sampled, [`medium`]), and the segment's transmittance;
    /// `(0, 1)` when the passes are off or there is no medium.
    fn segment(&self, ray: &Ray<f64>, hit: Option<Hit>, time: f64, sampler: &mut Sampler) -> (DVec3, f64) {
        let length = hit.map_or(f64::INFINITY, |h| h.t);
        let glow = if self.passes.in_scattering {
            self.in_scattering(ray, length, time) + medium::area_in_scattering(self.scene, ray, length, time, sampler)
        } else {
            DVec3::ZERO
        };
        let transmittance = if self.passes.transmittance { self.transmittance(length) } else { 1.0 };
        (glow, transmittance)
    }

    /// Beer–Lambert `e^(−σ_t d)`; exactly 1 without a medium (also for `d = ∞`).
    fn transmittance(&self, distance: f64) -> f64 {
        match self.scene.fog() {
            Some(fog) if fog.sigma_t() > 0.0 => (-fog.sigma_t() * distance).exp(),
            _ => 1.0,
        }
    }

    /// `∫₀^d σ_s/(4π) · I e^(−σ_t r(x))/r(x)² · V(x) · e^(−σ_t x) dx` over point lights, by the
    /// midpoint rule in the equiangular variable `θ` (`x = Δ + h tanθ`), where the integrand is
    /// `σ_s I/(4π h) · e^(−σ_t (x + r)) · V` (module docs of [`crate::render`]).
    fn in_scattering(&self, ray: &Ray<f64>, length: f64, time: f64) -> DVec3 {
        let Some(fog) = self.scene.fog().filter(|f| f.sigma_s > 0.0) else {
            return DVec3::ZERO;
        };
        let sigma_t = fog.sigma_t();
        // Beyond σ_t·x = 40 the integrand is below e^(−40) ≈ 4e-18 of its peak.
        let end = length.min(40.0 / sigma_t);
        let mut total = DVec3::ZERO;
        for light in self.scene.point_lights() {
            let span = medium::Equiangular::new(ray, light.position, end);
            let h = span.h;
            let step = (span.theta_end - span.theta_start) / self.in_scatter_steps as f64;
            let mut sum = 0.0;
            for i in 0..self.in_scatter_steps {
                let theta = span.theta_start + (i as f64 + 0.5) * step;
                let x = span.distance(theta);
                let r = h / theta.cos();
                let point = ray.at(x);
                let shadow = Ray { origin: point, dir: (light.position - point) / r };
                if !self.scene.occluded(&shadow, time, r) {
                    sum += (-sigma_t * (x + r)).exp();
                }
            }
            total += light.intensity * (fog.sigma_s / (4.0 * PI * h) * sum * step);
        }
        total
    }

    /// Next-event estimation at a diffuse or glossy hit: every point light, one sample per area
    /// light, and the environment's samples ([`environment`]), with shadow rays and transmittance.
    fn direct_light(&self, ray: &Ray<f64>, hit: &Hit, time: f64, sampler: &mut Sampler) -> DVec3 {
        let material = self.scene.objects()[hit.object].material;
        let normal = facing_normal(ray, hit);
        let to_eye = -ray.dir;
        let mut total = DVec3::ZERO;
        let mut add_light = |target: DVec3, radiance_times_geometry: DVec3| {
            let offset = target - hit.point;
            let distance = offset.length();
            let dir = offset / distance;
            let cosine = normal.dot(dir);
            // NaN fails both tests: it never lights anything.
            if cosine.is_nan() || cosine <= 0.0 {
                return;
            }
            let shadow = Ray { origin: spawn_origin::<f64>(hit.point, hit.normal, dir), dir };
            // Stop just short of the target so an area light does not shadow itself.
            if self.scene.occluded(&shadow, time, distance * (1.0 - 1e-9)) {
                return;
            }
            total += brdf(&material, to_eye, dir, normal)
                * radiance_times_geometry
                * (cosine / (distance * distance) * self.light_transmittance(distance));
        };
        for light in self.scene.point_lights() {
            add_light(light.position, light.intensity);
        }
        for light in self.scene.area_lights() {
            let target = light.point(sampler.uniform(), sampler.uniform());
            let light_normal = light.edge_u.cross(light.edge_v);
            let area = light_normal.length();
            let cos_light = -light_normal.dot((target - hit.point).normalize()) / area;
            if cos_light > 0.0 {
                add_light(target, light.radiance * (cos_light * area));
            }
        }
        let brdf_toward = |dir: DVec3| brdf(&material, to_eye, dir, normal);
        total + self.environment_light(hit, normal, time, &brdf_toward, sampler)
    }

    /// Next-event estimation of the environment at a surface point: the mean over
    /// [`ENVIRONMENT_SAMPLES`] sampled directions `ω` of `f(ω) · L(ω) · cos / pdf(ω)`, each with
    /// a shadow ray to infinity and the transmittance to infinity (0 in a medium, where nothing
    /// arrives from infinitely far). `normal` faces the incoming ray, `brdf(ω)` is the surface's
    /// BRDF toward `ω`. Zero without an environment; consumes random numbers only with one.
    fn environment_light(
        &self,
        hit: &Hit,
        normal: DVec3,
        time: f64,
        brdf: &dyn Fn(DVec3) -> DVec3,
        sampler: &mut Sampler,
    ) -> DVec3 {
        let Some(environment) = self.scene.environment() else {
            return DVec3::ZERO;
        };
        let transmittance_to_infinity = self.light_transmittance(f64::INFINITY);
        let mut total = DVec3::ZERO;
        for _ in 0..ENVIRONMENT_SAMPLES {
            let Some(sample) = environment.sample(&mut || sampler.uniform()) else {
                continue;
            };
            let cosine = normal.dot(sample.direction);
            if !(cosine > 0.0 && sample.pdf > 0.0) {
                continue;
            }
            let dir = sample.direction;
            let shadow = Ray { origin: spawn_origin::<f64>(hit.point, hit.normal, dir), dir };
            if self.scene.occluded(&shadow, time, f64::INFINITY) {
                continue;
            }
            total += brdf(dir) * sample.radiance * (cosine / sample.pdf);
        }
        total * (transmittance_to_infinity / ENVIRONMENT_SAMPLES as f64)
    }

    /// A photon map's radiance estimate toward the eye at a diffuse or glossy hit. Photons
    /// ignore the medium (see [`super::photon::trace_caustic_photons`]), so in fog the caustic
    /// comes out unattenuated on its way from the light.
    fn gathered(&self, map: &PhotonMap, gather: Gather, ray: &Ray<f64>, hit: &Hit) -> DVec3 {
        let material = self.scene.objects()[hit.object].material;
        map.radiance_gathered(&material, hit.point, -ray.dir, facing_normal(ray, hit), gather)
    }

    /// Transmittance towards a light, on when the transmittance pass is.
    fn light_transmittance(&self, distance: f64) -> f64 {
        if self.passes.transmittance { self.transmittance(distance) } else { 1.0 }
    }
}
