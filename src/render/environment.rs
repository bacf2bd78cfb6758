//! The environment light: radiance arriving from infinitely far away, by direction — a Q4 light
//! probe ([`crate::q4_light_probe`]) or, for tests, one constant colour.
//!
//! *Mapping.* Q4's maps are `+z`-up (a lat-long map's top row is the zenith); the renderer is
//! `+y`-up. A renderer direction `(x, y, z)` is looked up as the Q4 direction `(x, −z, y)` (a
//! rotation: the zenith of the map is the renderer's up, and the map's `+x` stays `+x`).
//!
//! *Who sees it.* Eye rays and rays leaving mirrors or glass that escape the scene return the
//! environment's radiance (it replaces the scene's constant background). Diffuse and glossy hits
//! gather it by next-event estimation: [`ENVIRONMENT_SAMPLES`] directions drawn from the
//! environment's own distribution, each with a shadow ray to infinity. That is the only strategy
//! for `L_env · f · cos` at a diffuse/glossy vertex (a bounce ray that escapes after a diffuse or
//! glossy hit adds nothing, as for area lights), so the estimate is unbiased as long as the
//! sampling pdf is positive wherever the radiance is — true for both kinds below (a probe texel
//! with any non-zero channel has positive luminance, hence positive probability).
//!
//! *Sampling.* A probe is sampled by Q4's [`MapDistribution`] (texel ∝ luminance × solid angle,
//! then uniformly in the texel's image area), whose pdf is exact in solid angle; a constant
//! environment by uniform directions on the sphere (pdf `1/(4π)`).

use super::integrator::Sampler;
use super::scene::Scene;
use crate::envmap::{MapDistribution, Probe, ProbeError, ProbeFormat};
use crate::geometry::sphere::spawn_origin;
use crate::geometry::{InputError, Ray, require_finite};
use glam::{DMat3, DVec3};
use std::f64::consts::PI;
use std::path::Path;

/// Environment directions sampled per diffuse or glossy hit (Whitted and path tracer alike).
/// Eight keeps a 2-spp preview of the soft `courtyard` map readable; the estimate is unbiased
/// for any count.
pub const ENVIRONMENT_SAMPLES: usize = 8;

/// Radiance from infinitely far away, by direction (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Environment {
    kind: Kind,
}

#[derive(Debug, Clone, PartialEq)]
enum Kind {
    Constant(DVec3),
    Probe { probe: Probe, distribution: MapDistribution },
}

/// One sampled environment direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnvironmentSample {
    /// Unit direction toward the environment (renderer frame, `+y` up).
    pub direction: DVec3,
    /// The radiance arriving from it.
    pub radiance: DVec3,
    /// The solid-angle pdf of the draw.
    pub pdf: f64,
}

/// The Q4 (`+z`-up) direction of renderer (`+y`-up) direction `d`.
fn to_probe_frame(d: DVec3) -> DVec3 {
    DVec3::new(d.x, -d.z, d.y)
}

/// The renderer direction of Q4 direction `q` (inverse of [`to_probe_frame`]).
fn from_probe_frame(q: DVec3) -> DVec3 {
    DVec3::new(q.x, q.z, -q.y)
}

impl Environment {
    /// The same radiance `radiance` from every direction (a "furnace" for tests).
    ///
    /// # Errors
    /// [`InputError::NonFinite`] or [`InputError::OutOfRange`] unless every channel is finite and ≥ 0.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::render::environment::Environment;
    /// let sky = Environment::constant(DVec3::splat(2.0)).unwrap();
    /// assert_eq!(sky.radiance(DVec3::Y), DVec3::splat(2.0));
    /// assert!(Environment::constant(DVec3::new(1.0, f64::NAN, 1.0)).is_err());
    /// ```
    pub fn constant(radiance: DVec3) -> Result<Self, InputError> {
        require_finite::<f64>("environment radiance", radiance)?;
        if radiance.min_element() < 0.0 {
            return Err(InputError::OutOfRange {
                name: "environment radiance",
                value: format!("{radiance:?}"),
                expected: "≥ 0 in every channel",
            });
        }
        Ok(Self { kind: Kind::Constant(radiance) })
    }

    /// A Q4 probe as the environment (its `+z` is the renderer's up). The probe was validated
    /// when it was built (no NaN, infinite or negative texel).
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3::envmap::{Probe, ProbeFormat};
    /// use hw3::render::environment::Environment;
    /// let probe = Probe::from_fn(ProbeFormat::LatLong, 8, 4, DMat3::IDENTITY, |w| DVec3::splat(w.z.max(0.0))).unwrap();
    /// let env = Environment::from_probe(probe);
    /// assert!(env.radiance(DVec3::Y).x > 0.5 && env.radiance(-DVec3::Y) == DVec3::ZERO); // map zenith = up
    /// ```
    #[must_use]
    pub fn from_probe(probe: Probe) -> Self {
        let distribution = MapDistribution::new(&probe);
        Self { kind: Kind::Probe { probe, distribution } }
    }

    /// A latitude-longitude map of `width × height` RGB radiances (row-major, top row = zenith).
    ///
    /// # Errors
    /// [`ProbeError::BadTexel`] for the first NaN, infinite or negative channel (a map with a NaN
    /// is refused, never rendered), [`ProbeError::WrongLength`] or [`ProbeError::Empty`] for a
    /// buffer that does not fit the size.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::envmap::ProbeError;
    /// use hw3::render::environment::Environment;
    /// let mut texels = vec![DVec3::ONE; 8];
    /// assert!(Environment::lat_long(4, 2, texels.clone()).is_ok());
    /// texels[5].y = f64::NAN;
    /// assert!(matches!(Environment::lat_long(4, 2, texels), Err(ProbeError::BadTexel { column: 1, row: 1, .. })));
    /// ```
    pub fn lat_long(width: usize, height: usize, radiance: Vec<DVec3>) -> Result<Self, ProbeError> {
        Ok(Self::from_probe(Probe::from_radiance(ProbeFormat::LatLong, width, height, DMat3::IDENTITY, radiance)?))
    }

    /// Reads a latitude-longitude Radiance `.hdr` map (see [`Probe::read_lat_long`]).
    ///
    /// # Errors
    /// [`ProbeError::Read`] for a missing or undecodable file, [`ProbeError::BadTexel`] for a bad texel.
    ///
    /// # Examples
    /// ```
    /// use hw3::render::environment::Environment;
    /// assert!(Environment::read_lat_long(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/data/q4/courtyard_256x128.hdr")).is_ok());
    /// assert!(Environment::read_lat_long("no/such/map.hdr").is_err());
    /// ```
    pub fn read_lat_long(path: impl AsRef<Path>) -> Result<Self, ProbeError> {
        Ok(Self::from_probe(Probe::read_lat_long(path)?))
    }

    /// The probe behind the environment, `None` for a constant one.
    #[must_use]
    pub fn probe(&self) -> Option<&Probe> {
        match &self.kind {
            Kind::Constant(_) => None,
            Kind::Probe { probe, .. } => Some(probe),
        }
    }

    /// The Q4 direction (`+z` up) that renderer direction `direction` looks up.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::render::environment::Environment;
    /// assert_eq!(Environment::probe_direction(DVec3::Y), DVec3::Z);
    /// ```
    #[must_use]
    pub fn probe_direction(direction: DVec3) -> DVec3 {
        to_probe_frame(direction)
    }

    /// Whether no direction carries any light (then it is no light at all for the path analysis).
    #[must_use]
    pub fn is_black(&self) -> bool {
        match &self.kind {
            Kind::Constant(radiance) => radiance.max_element() <= 0.0,
            Kind::Probe { distribution, .. } => distribution.total_power() <= 0.0,
        }
    }

    /// The radiance arriving from unit direction `direction` (renderer frame).
    #[must_use]
    pub fn radiance(&self, direction: DVec3) -> DVec3 {
        match &self.kind {
            Kind::Constant(radiance) => *radiance,
            Kind::Probe { probe, .. } => probe.radiance_toward(to_probe_frame(direction)),
        }
    }

    /// Draws a direction with the environment's sampling pdf; `uniform` supplies numbers in
    /// `[0, 1)`. `None` for a black environment (and, for a disk-format probe, on the rare
    /// rejected rim sample described at [`MapDistribution::sample`]).
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::render::environment::Environment;
    /// let sky = Environment::constant(DVec3::ONE).unwrap();
    /// let mut numbers = [0.25, 0.5].into_iter().cycle();
    /// let s = sky.sample(&mut || numbers.next().unwrap()).unwrap();
    /// assert!((s.pdf * 4.0 * std::f64::consts::PI - 1.0).abs() < 1e-15 && (s.direction.length() - 1.0).abs() < 1e-15);
    /// ```
    pub fn sample(&self, uniform: &mut dyn FnMut() -> f64) -> Option<EnvironmentSample> {
        match &self.kind {
            Kind::Constant(radiance) => {
                if radiance.max_element() <= 0.0 {
                    return None;
                }
                let z = 1.0 - 2.0 * uniform();
                let phi = 2.0 * PI * uniform();
                let ring = (1.0 - z * z).max(0.0).sqrt();
                Some(EnvironmentSample {
                    direction: DVec3::new(ring * phi.cos(), ring * phi.sin(), z),
                    radiance: *radiance,
                    pdf: 1.0 / (4.0 * PI),
                })
            }
            Kind::Probe { probe, distribution } => {
                let sample = distribution.sample(probe, uniform)?;
                Some(EnvironmentSample {
                    direction: from_probe_frame(sample.omega),
                    radiance: probe.texels()[sample.texel].radiance,
                    pdf: sample.pdf,
                })
            }
        }
    }

    /// The solid-angle pdf with which [`Self::sample`] draws unit direction `direction`.
    #[must_use]
    pub fn pdf(&self, direction: DVec3) -> f64 {
        match &self.kind {
            Kind::Constant(radiance) => {
                if radiance.max_element() > 0.0 {
                    1.0 / (4.0 * PI)
                } else {
                    0.0
                }
            }
            Kind::Probe { probe, distribution } => distribution.pdf(probe, to_probe_frame(direction)),
        }
    }
}

impl Scene {
    /// The radiance seen along an escaping ray of unit direction `direction`: the environment
    /// if the scene has one, else the constant background.
    #[must_use]
    pub fn escaped_radiance(&self, direction: DVec3) -> DVec3 {
        self.environment().map_or_else(|| self.background(), |environment| environment.radiance(direction))
    }
}

/// Next-event estimation of the environment at a surface point: the mean over
/// [`ENVIRONMENT_SAMPLES`] sampled directions `ω` of `f(ω) · L(ω) · cos / pdf(ω)`, each with a
/// shadow ray to infinity. `normal` faces the incoming ray, `geometric_normal` is the hit's
/// normal (for the shadow ray's origin), `brdf(ω)` is the surface's BRDF toward `ω`, and
/// `transmittance_to_infinity` multiplies every sample (0 in a medium, where nothing arrives
/// from infinitely far). Zero without an environment; consumes random numbers only with one.
#[allow(clippy::too_many_arguments)] // one estimator's inputs, all needed
pub(crate) fn direct_light(
    scene: &Scene,
    point: DVec3,
    normal: DVec3,
    geometric_normal: DVec3,
    time: f64,
    brdf: &dyn Fn(DVec3) -> DVec3,
    transmittance_to_infinity: f64,
    sampler: &mut Sampler,
) -> DVec3 {
    let Some(environment) = scene.environment() else {
        return DVec3::ZERO;
    };
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
        let shadow = Ray { origin: spawn_origin::<f64>(point, geometric_normal, dir), dir };
        if scene.occluded(&shadow, time, f64::INFINITY) {
            continue;
        }
        total += brdf(dir) * sample.radiance * (cosine / sample.pdf);
    }
    total * (transmittance_to_infinity / ENVIRONMENT_SAMPLES as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::envmap::BuiltinMap;
    use crate::geometry::Sphere;
    use crate::q4_light_probe::Irradiance;
    use crate::render::analysis::{Passes, analyze};
    use crate::render::integrator::{Integrator, Tracer};
    use crate::render::scene::{Camera, Material, Object};

    fn ball_under(environment: Environment, material: Material) -> Scene {
        let camera = Camera::looking_at(DVec3::new(0.0, 0.0, 4.0), DVec3::ZERO, 40.0);
        let ball = Object::sphere(Sphere::new(DVec3::ZERO, 1.0).unwrap(), material);
        Scene::new(camera, vec![ball], vec![], None, DVec3::ZERO).unwrap().with_environment(environment)
    }

    /// Mean and standard error of `count` one-pixel estimates of the radiance leaving the unit
    /// sphere at `normal`, seen from outside along `−normal`.
    fn estimate(scene: &Scene, integrator: Integrator, normal: DVec3, count: u64) -> (DVec3, DVec3) {
        let tracer = Tracer::new(scene, analyze(scene).plan.for_integrator(integrator));
        let ray = Ray { origin: normal * 3.0, dir: -normal };
        let values: Vec<DVec3> =
            (0..count).map(|i| tracer.radiance(integrator, &ray, 0.0, &mut Sampler::new(9, i, 0))).collect();
        let n = count as f64;
        let mean = values.iter().sum::<DVec3>() / n;
        let variance = values.iter().map(|v| (*v - mean) * (*v - mean)).sum::<DVec3>() / (n - 1.0);
        (mean, (variance / n).powf(0.5))
    }

    #[test]
    fn frames_are_inverse_rotations() {
        for d in [DVec3::X, DVec3::Y, DVec3::Z, DVec3::new(0.3, -0.5, 0.8).normalize()] {
            assert!((from_probe_frame(to_probe_frame(d)) - d).length() < 1e-15);
            assert!((to_probe_frame(d).length() - 1.0).abs() < 1e-15);
        }
        assert_eq!(to_probe_frame(DVec3::X).cross(to_probe_frame(DVec3::Y)), to_probe_frame(DVec3::Z));
    }

    /// Under a constant environment `L`, a diffuse convex object reflects `albedo · L` (white
    /// furnace). Per environment sample the estimate is `4·a·L·cos·[cos > 0]`, of standard
    /// deviation `√(5/3)·a·L`; with 8 samples per pixel and 20 000 pixels the standard error is
    /// 0.0032·a·L, and the bound is 5 of the measured standard errors (measured: 0.0026 for
    /// `a·L = 0.8`, deviations within 2 of them). Whitted and the path
    /// tracer agree (bounce rays from a lone convex object escape and add nothing).
    #[test]
    fn diffuse_ball_under_a_constant_environment_reflects_albedo_times_radiance() {
        let (albedo, radiance) = (DVec3::new(0.8, 0.5, 0.2), DVec3::new(1.0, 2.0, 3.0));
        let scene = ball_under(Environment::constant(radiance).unwrap(), Material::Diffuse { albedo });
        let expected = albedo * radiance;
        for integrator in [Integrator::Whitted { max_depth: 4 }, Integrator::PathTracer { max_depth: 4 }] {
            for normal in [DVec3::Z, DVec3::new(0.6, 0.0, 0.8), DVec3::new(-0.3, 0.9, 0.1).normalize()] {
                let (mean, error) = estimate(&scene, integrator, normal, 20_000);
                let deviation = (mean - expected).abs();
                assert!(
                    deviation.cmple(error * 5.0).all(),
                    "{integrator:?} at {normal}: {mean} vs {expected} ± {error}"
                );
                assert!(error.max_element() < 0.005 * expected.max_element(), "the bound is tight: {error}");
            }
        }
    }

    /// A diffuse sphere under the real `courtyard` map: the radiance leaving it at a normal is
    /// `(albedo/π) E(n)` with `E` Q4's solid-angle weighted texel sum. The renderer integrates the
    /// map's piecewise-constant radiance exactly in expectation; the texel sum differs from that
    /// integral by < 0.2 % (unit mean texel directions, texels cut by the horizon), so the bound
    /// is 5 standard errors (about 0.5 % of the value with 20 000 pixels of 8 samples) plus 0.2 %
    /// of the reference.
    #[test]
    fn diffuse_ball_under_a_real_map_matches_q4_irradiance() {
        let environment = Environment::from_probe(BuiltinMap::Courtyard.probe().unwrap());
        let probe = environment.probe().unwrap().clone();
        let irradiance = Irradiance::new(&probe);
        let albedo = 0.6;
        let scene = ball_under(environment, Material::Diffuse { albedo: DVec3::splat(albedo) });
        let normals = [DVec3::Y, DVec3::Z, DVec3::new(0.7, -0.2, -0.4).normalize(), -DVec3::Y];
        for normal in normals {
            let reference = irradiance.weighted(Environment::probe_direction(normal)) * (albedo / PI);
            let (mean, error) = estimate(&scene, Integrator::Whitted { max_depth: 1 }, normal, 20_000);
            assert!((error / reference).max_element() < 0.01, "the bound is tight: {error}");
            let bound = error * 5.0 + reference * 2e-3;
            assert!((mean - reference).abs().cmple(bound).all(), "n = {normal}: {mean} vs {reference} ± {bound}");
        }
    }

    #[test]
    fn escaping_eye_and_mirror_rays_see_the_environment() {
        let environment = Environment::from_probe(BuiltinMap::Courtyard.probe().unwrap());
        let reflectance = DVec3::splat(0.9);
        let scene = ball_under(environment.clone(), Material::Mirror { reflectance });
        let tracer = Tracer::new(&scene, analyze(&scene).plan);
        for integrator in [Integrator::Whitted { max_depth: 4 }, Integrator::PathTracer { max_depth: 4 }] {
            let miss = Ray { origin: DVec3::new(0.0, 0.0, 4.0), dir: DVec3::new(0.6, 0.8, 0.0) };
            let seen = tracer.radiance(integrator, &miss, 0.0, &mut Sampler::new(0, 0, 0));
            assert_eq!(seen, environment.radiance(miss.dir));
            // Straight down onto the top of the ball: the mirror sends the ray straight up.
            let down = Ray { origin: DVec3::new(0.0, 3.0, 0.0), dir: -DVec3::Y };
            let reflected = tracer.radiance(integrator, &down, 0.0, &mut Sampler::new(0, 0, 0));
            assert_eq!(reflected, reflectance * environment.radiance(DVec3::Y));
        }
    }

    #[test]
    fn sampled_pdfs_match_the_pdf_function_and_integrate_to_one() {
        let environment = Environment::from_probe(BuiltinMap::Sunrise.probe().unwrap());
        let mut sampler = Sampler::new(3, 0, 0);
        for _ in 0..200 {
            let s = environment.sample(&mut || sampler.uniform()).unwrap();
            assert!((environment.pdf(s.direction) / s.pdf - 1.0).abs() < 1e-9);
            assert_eq!(s.radiance, environment.radiance(s.direction));
        }
        let probe = environment.probe().unwrap();
        let total: f64 =
            probe.texels().iter().map(|t| environment.pdf(from_probe_frame(t.direction)) * t.solid_angle).sum();
        assert!((total - 1.0).abs() < 1e-3, "{total}");
    }

    #[test]
    fn black_environments_are_no_light_and_bad_maps_are_typed_errors() {
        let black = Environment::constant(DVec3::ZERO).unwrap();
        assert!(black.is_black() && black.sample(&mut || 0.5).is_none() && black.pdf(DVec3::Y) == 0.0);
        let dark = Environment::lat_long(2, 1, vec![DVec3::ZERO; 2]).unwrap();
        assert!(dark.is_black() && dark.sample(&mut || 0.5).is_none());
        for bad in [f64::NAN, f64::INFINITY, -1.0] {
            assert!(matches!(
                Environment::lat_long(2, 1, vec![DVec3::ONE, DVec3::new(1.0, bad, 1.0)]),
                Err(ProbeError::BadTexel { column: 1, row: 0, .. })
            ));
            assert!(Environment::constant(DVec3::splat(bad)).is_err());
        }
        assert!(matches!(Environment::lat_long(2, 2, vec![DVec3::ONE]), Err(ProbeError::WrongLength { .. })));
        // A black environment lights nothing and the renderer still returns finite zeros.
        let scene = ball_under(black, Material::Diffuse { albedo: DVec3::ONE });
        let tracer = Tracer::new(&scene, Passes::all());
        let ray = Ray { origin: DVec3::new(0.0, 0.0, 3.0), dir: -DVec3::Z };
        assert_eq!(
            tracer.radiance(Integrator::PathTracer { max_depth: 3 }, &ray, 0.0, &mut Sampler::new(0, 0, 0)),
            DVec3::ZERO
        );
    }
}
