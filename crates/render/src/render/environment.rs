//! The environment light: radiance arriving from infinitely far away, by direction — a Q4 light
//! probe ([`crate::envmap::Probe`], the light probes of the homework's Q4) or, for tests, one
//! constant colour.
//!
//! *Mapping.* Q4's maps are `+z`-up (a lat-long map's top row is the zenith); the renderer is
//! `+y`-up. A renderer direction `(x, y, z)` is looked up as the Q4 direction `(x, −z, y)` (a
//! rotation: the zenith of the map is the renderer's up, and the map's `+x` stays `+x`).
//!
//! *Who sees it.* Eye rays and rays leaving mirrors or glass that escape the scene return the
//! environment's radiance (it replaces the scene's constant background), read bilinearly
//! ([`Environment::radiance_seen`]): a 256-texel map behind a 60° lens is magnified about 15
//! times, and a nearest-texel read would show every texel as a block. Diffuse and glossy hits
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

use super::sampling::uniform_sphere;
use crate::envmap::{MapDistribution, Probe, ProbeError, ProbeFormat};
use glam::{DMat3, DVec3};
use hw3_core::geometry::{InputError, require_finite};
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
pub(crate) fn to_probe_frame(d: DVec3) -> DVec3 {
    DVec3::new(d.x, -d.z, d.y)
}

/// The renderer direction of Q4 direction `q` (inverse of [`to_probe_frame`]).
pub(crate) fn from_probe_frame(q: DVec3) -> DVec3 {
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
    /// use hw3_render::render::environment::Environment;
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
    /// use hw3_render::envmap::{Probe, ProbeFormat};
    /// use hw3_render::render::environment::Environment;
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
    /// use hw3_render::envmap::ProbeError;
    /// use hw3_render::render::environment::Environment;
    /// let mut texels = vec![DVec3::ONE; 8];
    /// assert!(Environment::lat_long(4, 2, texels.clone()).is_ok());
    /// texels[5].y = f64::NAN;
    /// assert!(matches!(Environment::lat_long(4, 2, texels), Err(ProbeError::BadTexel { column: 1, row: 1, .. })));
    /// ```
    pub fn lat_long(width: usize, height: usize, radiance: Vec<DVec3>) -> Result<Self, ProbeError> {
        Ok(Self::from_probe(Probe::from_radiance(ProbeFormat::LatLong, width, height, DMat3::IDENTITY, radiance)?))
    }

    /// Reads a latitude-longitude Radiance `.hdr` map of at most
    /// [`Probe::MAX_READ_TEXELS`] texels (see [`Probe::read_lat_long`]).
    ///
    /// # Errors
    /// [`ProbeError::TooLarge`] if the header declares more texels (checked before decoding),
    /// [`ProbeError::Read`] for a missing or undecodable file, [`ProbeError::BadTexel`] for a bad texel.
    ///
    /// # Examples
    /// ```
    /// use hw3_render::render::environment::Environment;
    /// assert!(Environment::read_lat_long(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/data/q4/courtyard_256x128.hdr")).is_ok());
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
    /// use hw3_render::render::environment::Environment;
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

    /// The radiance arriving from unit direction `direction` (renderer frame): the light's own
    /// piecewise-constant radiance, texel by texel, which [`Self::sample`] returns and the
    /// estimators integrate.
    #[must_use]
    pub fn radiance(&self, direction: DVec3) -> DVec3 {
        match &self.kind {
            Kind::Constant(radiance) => *radiance,
            Kind::Probe { probe, .. } => probe.radiance_toward(to_probe_frame(direction)),
        }
    }

    /// The radiance a camera sees toward unit direction `direction` (renderer frame): for a probe
    /// read bilinearly between texel centres ([`Probe::radiance_bilinear`]), so that a magnified
    /// map shows no texel blocks; equal to [`Self::radiance`] at texel centres and for a constant
    /// environment. For eye rays and rays leaving mirrors and glass only: light sampling keeps
    /// the piecewise-constant [`Self::radiance`] its pdf was built for.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3_render::envmap::{Probe, ProbeFormat};
    /// use hw3_render::render::environment::Environment;
    /// // Two texels around the horizon, 0 (φ < 180°) and 1: on their border, φ = 180°, the light
    /// // is the second texel's, the seen radiance the blend of both.
    /// let probe = Probe::from_radiance(ProbeFormat::LatLong, 2, 1, DMat3::IDENTITY, vec![DVec3::ZERO, DVec3::ONE]).unwrap();
    /// let env = Environment::from_probe(probe);
    /// assert_eq!(env.radiance(DVec3::NEG_X), DVec3::ONE);
    /// assert!((env.radiance_seen(DVec3::NEG_X).x - 0.5).abs() < 1e-12);
    /// ```
    #[must_use]
    pub fn radiance_seen(&self, direction: DVec3) -> DVec3 {
        match &self.kind {
            Kind::Constant(radiance) => *radiance,
            Kind::Probe { probe, .. } => probe.radiance_bilinear(to_probe_frame(direction)),
        }
    }

    /// Draws a direction with the environment's sampling pdf; `uniform` supplies numbers in
    /// `[0, 1)`. `None` for a black environment (and, for a disk-format probe, on the rare
    /// rejected rim sample described at [`MapDistribution::sample`]).
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3_render::render::environment::Environment;
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
                let (u1, u2) = (uniform(), uniform());
                Some(EnvironmentSample {
                    direction: uniform_sphere(u1, u2),
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
