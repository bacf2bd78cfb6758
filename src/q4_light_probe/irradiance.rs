//! Irradiance `E(n) = ∫ L(ω) max(0, n·ω) dω` from a probe, seven ways.
//!
//! All Monte Carlo estimators integrate the probe's own piecewise-constant radiance (each texel's
//! value over its footprint), so they are unbiased for the same integral, which the solid-angle
//! weighted texel sum approximates to second order in the texel size.

use crate::envmap::{MapDistribution, MapSample, Probe, ProbeError, Texel};
use crate::geometry::{InputError, require_direction};
use crate::rng::{Generator, uniform};
use glam::DVec3;
use std::f64::consts::{PI, TAU};
use std::str::FromStr;

/// An irradiance method (the CLI's `--method`).
///
/// # Examples
/// ```
/// use hw3::q4_light_probe::Estimator;
/// let m: Estimator = "mis".parse().unwrap();
/// assert_eq!(m, Estimator::Mis);
/// assert!(m.is_monte_carlo() && !Estimator::Sh9.is_monte_carlo());
/// assert_eq!(Estimator::ALL.map(Estimator::name).join("|"), "unweighted|weighted|uniform|cosine|map|mis|sh9");
/// assert!("guess".parse::<Estimator>().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Estimator {
    /// The student's literal sum: every texel inside the ball weighted equally (`Ω_covered / N`).
    Unweighted,
    /// Each texel weighted by its solid angle `Δω`.
    Weighted,
    /// Monte Carlo, uniform over the hemisphere of `n`.
    Uniform,
    /// Monte Carlo, cosine-weighted around `n`.
    Cosine,
    /// Monte Carlo, sampling texels in proportion to luminance × solid angle.
    Map,
    /// Multiple importance sampling of cosine and map (balance heuristic, half the samples each).
    Mis,
    /// Nine spherical-harmonic coefficients (Ramamoorthi & Hanrahan 2001), clamped at 0.
    Sh9,
}

impl Estimator {
    /// Every method, in the CLI's order.
    ///
    /// # Examples
    /// ```
    /// use hw3::q4_light_probe::Estimator;
    /// assert_eq!(Estimator::ALL.len(), 7);
    /// assert_eq!(Estimator::ALL[0], Estimator::Unweighted);
    /// ```
    pub const ALL: [Estimator; 7] = [
        Estimator::Unweighted,
        Estimator::Weighted,
        Estimator::Uniform,
        Estimator::Cosine,
        Estimator::Map,
        Estimator::Mis,
        Estimator::Sh9,
    ];

    /// The CLI name.
    ///
    /// # Examples
    /// ```
    /// use hw3::q4_light_probe::Estimator;
    /// assert_eq!(Estimator::Mis.name(), "mis");
    /// assert!(Estimator::ALL.iter().all(|m| m.name().parse::<Estimator>() == Ok(*m)));
    /// ```
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Estimator::Unweighted => "unweighted",
            Estimator::Weighted => "weighted",
            Estimator::Uniform => "uniform",
            Estimator::Cosine => "cosine",
            Estimator::Map => "map",
            Estimator::Mis => "mis",
            Estimator::Sh9 => "sh9",
        }
    }

    /// Whether the method draws random samples (and so takes `--samples` and `--seed`).
    ///
    /// # Examples
    /// ```
    /// use hw3::q4_light_probe::Estimator;
    /// let random: Vec<_> = Estimator::ALL.into_iter().filter(|m| m.is_monte_carlo()).map(Estimator::name).collect();
    /// assert_eq!(random, ["uniform", "cosine", "map", "mis"]);
    /// ```
    #[must_use]
    pub fn is_monte_carlo(self) -> bool {
        matches!(self, Estimator::Uniform | Estimator::Cosine | Estimator::Map | Estimator::Mis)
    }
}

impl FromStr for Estimator {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Estimator::ALL.into_iter().find(|m| m.name() == s).ok_or_else(|| {
            let names: Vec<_> = Estimator::ALL.iter().map(|m| m.name()).collect();
            format!("unknown method `{s}`; expected one of {}", names.join("|"))
        })
    }
}

/// The texel sum `Σ_t L_t max(0, n·ω_t) Δω_t` over `texels`, whatever they hold: a probe's own
/// texels ([`Irradiance::weighted`]) or texels read by hand ([`centre_texels`]). `n` is a unit
/// normal; texels of zero solid angle or zero radiance add nothing.
///
/// # Examples
/// ```
/// use glam::{DMat3, DVec3};
/// use hw3::envmap::{Probe, ProbeFormat};
/// use hw3::q4_light_probe::irradiance::weighted_sum;
/// let probe = Probe::from_fn(ProbeFormat::MirrorBall, 32, 32, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
/// let e = weighted_sum(DVec3::Z, probe.texels()).x;
/// assert!((e / std::f64::consts::PI - 1.0).abs() < 1e-3); // a uniform sky of radiance 1: E = π
/// ```
#[must_use]
pub fn weighted_sum(n: DVec3, texels: &[Texel]) -> DVec3 {
    texels.iter().map(|t| t.radiance * (n.dot(t.direction).max(0.0) * t.solid_angle)).sum()
}

/// The student's sum with equal weights: `weight · Σ_t L_t max(0, n·ω_t)` over the texels of
/// `texels` whose centre is inside the image disk (`weight` is usually [`equal_weight`]).
///
/// # Examples
/// ```
/// use glam::{DMat3, DVec3};
/// use hw3::envmap::{Probe, ProbeFormat};
/// use hw3::q4_light_probe::irradiance::{equal_weight, unweighted_sum};
/// let probe = Probe::from_fn(ProbeFormat::MirrorBall, 64, 64, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
/// let e = unweighted_sum(DVec3::Z, probe.texels(), equal_weight(probe.texels())).x;
/// assert!((e / std::f64::consts::PI - 1.0).abs() < 1e-2); // nearly right on the equal-area ball
/// ```
#[must_use]
pub fn unweighted_sum(n: DVec3, texels: &[Texel], weight: f64) -> DVec3 {
    texels.iter().filter(|t| t.centre_inside).map(|t| t.radiance * n.dot(t.direction).max(0.0)).sum::<DVec3>() * weight
}

/// The equal weight of the unweighted sum, `Ω_covered / N`: the solid angle all `texels` cover
/// shared among the `N` whose centre is inside the image disk (0 when none is). On the
/// orthographic mirror ball `Ω_covered = 4π`.
///
/// # Examples
/// ```
/// use glam::{DMat3, DVec3};
/// use hw3::envmap::{Probe, ProbeFormat};
/// use hw3::q4_light_probe::irradiance::equal_weight;
/// // 5 × 5 texels: 21 centres inside the disk share the whole sphere.
/// let probe = Probe::from_fn(ProbeFormat::MirrorBall, 5, 5, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
/// assert!((equal_weight(probe.texels()) - 4.0 * std::f64::consts::PI / 21.0).abs() < 1e-12);
/// ```
#[must_use]
pub fn equal_weight(texels: &[Texel]) -> f64 {
    let inside = texels.iter().filter(|t| t.centre_inside).count();
    let covered: f64 = texels.iter().map(|t| t.solid_angle).sum();
    if inside > 0 { covered / inside as f64 } else { 0.0 }
}

/// The texels of `probe` as a student reads a small probe by hand: a texel whose centre is inside
/// the image disk looks along the direction of its centre (not the footprint mean
/// [`Texel::direction`] holds), and one whose centre is outside is masked (radiance 0), as a mask
/// drawn on a photograph would. Solid angles stay exact. Same order as [`Probe::texels`].
///
/// # Examples
/// ```
/// use glam::{DMat3, DVec3};
/// use hw3::envmap::{Probe, ProbeFormat};
/// use hw3::q4_light_probe::irradiance::centre_texels;
/// let probe = Probe::from_fn(ProbeFormat::MirrorBall, 5, 5, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
/// let texels = centre_texels(&probe);
/// assert!((texels[12].direction - DVec3::Z).length() < 1e-15); // the middle texel sees the camera
/// assert_eq!(texels[0].radiance, DVec3::ZERO); // a corner: centre outside, masked
/// assert_eq!(texels[0].solid_angle, probe.texels()[0].solid_angle);
/// ```
#[must_use]
pub fn centre_texels(probe: &Probe) -> Vec<Texel> {
    (0..probe.texels().len()).map(|index| centre_texel(probe, index)).collect()
}

/// Texel `index` of `probe` read by hand, as in [`centre_texels`].
///
/// # Panics
/// If `index` is not a texel of `probe`.
///
/// # Examples
/// ```
/// use glam::{DMat3, DVec3};
/// use hw3::envmap::{Probe, ProbeFormat};
/// use hw3::q4_light_probe::irradiance::centre_texel;
/// let probe = Probe::from_fn(ProbeFormat::MirrorBall, 5, 5, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
/// // Row 1, column 2: centre (0, 0.4), so θ = 2 arcsin 0.4 from the camera axis, tilted up.
/// let w = centre_texel(&probe, 7).direction;
/// assert!((w.z - (2.0 * 0.4f64.asin()).cos()).abs() < 1e-12 && w.x.abs() < 1e-15 && w.y > 0.0);
/// ```
#[must_use]
pub fn centre_texel(probe: &Probe, index: usize) -> Texel {
    let mut texel = probe.texels()[index];
    let rect = probe.texel_rect(index);
    match probe.image_to_world(0.5 * (rect.min + rect.max)) {
        Some((direction, _)) if texel.centre_inside => texel.direction = direction,
        _ => texel.radiance = DVec3::ZERO,
    }
    texel
}

/// Outgoing radiance of a Lambertian surface of albedo `albedo` (`K_d` ∈ [0, 1], the fraction of
/// incident power reflected) under irradiance `irradiance`: `L_o = (K_d/π) E`.
///
/// The student's `Σ K_d L (n·l)` is this formula when its `K_d` is read as `albedo/π` and each term
/// carries its solid angle `Δω`.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// // A white surface under a uniform sky of radiance 1 reflects radiance 1.
/// let e = DVec3::splat(std::f64::consts::PI);
/// assert!((hw3::q4_light_probe::irradiance::outgoing_radiance(1.0, e) - DVec3::ONE).length() < 1e-15);
/// ```
#[must_use]
pub fn outgoing_radiance(albedo: f64, irradiance: DVec3) -> DVec3 {
    irradiance * (albedo / PI)
}

/// The spherical-harmonic basis `Y_lm(ω)` for l ≤ 2, ordered (0,0), (1,−1), (1,0), (1,1),
/// (2,−2), (2,−1), (2,0), (2,1), (2,2) (Ramamoorthi & Hanrahan 2001).
///
/// # Examples
/// ```
/// use hw3::q4_light_probe::irradiance::sh_basis;
/// let y = sh_basis(glam::DVec3::Z);
/// assert!((y[0] - 0.282095).abs() < 1e-6 && (y[2] - 0.488603).abs() < 1e-6);
/// ```
#[must_use]
pub fn sh_basis(omega: DVec3) -> [f64; 9] {
    let (x, y, z) = (omega.x, omega.y, omega.z);
    let y0 = 0.5 / PI.sqrt();
    let y1 = (3.0 / (4.0 * PI)).sqrt();
    let y2 = 0.5 * (15.0 / PI).sqrt();
    let y20 = 0.25 * (5.0 / PI).sqrt();
    let y22 = 0.25 * (15.0 / PI).sqrt();
    [y0, y1 * y, y1 * z, y1 * x, y2 * x * y, y2 * y * z, y20 * (3.0 * z * z - 1.0), y2 * x * z, y22 * (x * x - y * y)]
}

/// `Â_l`, the clamped-cosine kernel's SH coefficients (π, 2π/3, π/4), per basis index.
const KERNEL: [f64; 9] = [PI, TAU / 3.0, TAU / 3.0, TAU / 3.0, PI / 4.0, PI / 4.0, PI / 4.0, PI / 4.0, PI / 4.0];

/// The 9 RGB SH coefficients `L_lm = Σ_t L_t Y_lm(ω_t) Δω_t` of a probe.
///
/// # Examples
/// ```
/// use glam::{DMat3, DVec3};
/// use hw3::envmap::{Probe, ProbeFormat};
/// use hw3::q4_light_probe::Sh9;
/// // L = 1 + ω_z has only l ≤ 1 content: SH9 is exact up to the projection's quadrature.
/// let probe = Probe::from_fn(ProbeFormat::MirrorBall, 64, 64, DMat3::IDENTITY, |w| DVec3::splat(1.0 + w.z)).unwrap();
/// let sh9 = Sh9::project(&probe);
/// let exact = std::f64::consts::PI * (1.0 + 2.0 / 3.0);
/// assert!((sh9.irradiance(DVec3::Z).x / exact - 1.0).abs() < 1e-3);
/// assert!(sh9.irradiance_unclamped(-DVec3::Z).x > 0.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sh9 {
    /// Coefficients in [`sh_basis`] order.
    pub coefficients: [DVec3; 9],
}

impl Sh9 {
    /// Projects the probe onto the first 9 SH functions, weighting each texel by its solid angle.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3::envmap::{Probe, ProbeFormat};
    /// use hw3::q4_light_probe::Sh9;
    /// // A constant map has only the l = 0 coefficient: L · 4π · Y_00 = L · 2√π.
    /// let probe = Probe::from_fn(ProbeFormat::LatLong, 64, 32, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
    /// let sh9 = Sh9::project(&probe);
    /// assert!((sh9.coefficients[0].x - 2.0 * std::f64::consts::PI.sqrt()).abs() < 1e-3);
    /// assert!(sh9.coefficients[1..].iter().all(|c| c.x.abs() < 1e-2)); // to the texel quadrature
    /// ```
    #[must_use]
    pub fn project(probe: &Probe) -> Self {
        let mut coefficients = [DVec3::ZERO; 9];
        for texel in probe.texels().iter().filter(|t| t.solid_angle > 0.0) {
            let basis = sh_basis(texel.direction);
            for (c, y) in coefficients.iter_mut().zip(basis) {
                *c += texel.radiance * (y * texel.solid_angle);
            }
        }
        Self { coefficients }
    }

    /// `E(n) = Σ Â_l L_lm Y_lm(n)` without clamping: can be negative behind a bright source.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3::envmap::{Probe, ProbeFormat};
    /// use hw3::q4_light_probe::Sh9;
    /// // One bright texel above: the order-2 fit rings negative on the far side.
    /// let probe = Probe::from_fn(ProbeFormat::LatLong, 32, 16, DMat3::IDENTITY, |w| {
    ///     DVec3::splat(if w.z > 0.99 { 100.0 } else { 0.0 })
    /// })
    /// .unwrap();
    /// let sh9 = Sh9::project(&probe);
    /// let tilted = DVec3::new(0.85, 0.0, -0.53).normalize();
    /// assert!(sh9.irradiance_unclamped(tilted).x < 0.0);
    /// ```
    #[must_use]
    pub fn irradiance_unclamped(&self, normal: DVec3) -> DVec3 {
        sh_basis(normal).iter().zip(KERNEL).zip(&self.coefficients).map(|((y, a), c)| *c * (a * y)).sum()
    }

    /// [`Self::irradiance_unclamped`] clamped at 0 per channel (irradiance cannot be negative).
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3::envmap::{Probe, ProbeFormat};
    /// use hw3::q4_light_probe::Sh9;
    /// let probe = Probe::from_fn(ProbeFormat::LatLong, 32, 16, DMat3::IDENTITY, |w| {
    ///     DVec3::splat(if w.z > 0.99 { 100.0 } else { 0.0 })
    /// })
    /// .unwrap();
    /// let sh9 = Sh9::project(&probe);
    /// let tilted = DVec3::new(0.85, 0.0, -0.53).normalize();
    /// assert_eq!(sh9.irradiance(tilted), DVec3::ZERO); // clamped where the fit is negative
    /// assert!(sh9.irradiance(DVec3::Z).x > 0.0);
    /// ```
    #[must_use]
    pub fn irradiance(&self, normal: DVec3) -> DVec3 {
        self.irradiance_unclamped(normal).max(DVec3::ZERO)
    }
}

/// A probe prepared for every method: the map-sampling distribution and the SH9 projection are
/// built once, then any number of normals are evaluated.
///
/// # Examples
/// ```
/// use glam::DVec3;
/// use hw3::envmap::{horizontal_camera, ProbeFormat};
/// use hw3::q4_light_probe::{maps::AnalyticMap, Irradiance, Estimator};
/// let map = AnalyticMap::sky();
/// let probe = map.rasterise(ProbeFormat::MirrorBall, 32, horizontal_camera()).unwrap();
/// let prepared = Irradiance::new(&probe); // built once ...
/// let mut rng = hw3::rng::seeded(0, 0);
/// for n in [DVec3::Z, DVec3::X, -DVec3::Z] {
///     // ... evaluated at any number of normals
///     let e = prepared.estimate(n, Estimator::Weighted, 1, &mut rng).unwrap().x;
///     assert!((e - map.irradiance(n)).abs() < 0.02);
/// }
/// ```
#[derive(Debug, Clone)]
pub struct Irradiance<'a> {
    probe: &'a Probe,
    distribution: MapDistribution,
    sh9: Sh9,
    equal_weight: f64,
}

impl<'a> Irradiance<'a> {
    /// Prepares `probe`.
    ///
    /// # Examples
    /// ```
    /// use glam::{DMat3, DVec3};
    /// use hw3::envmap::{Probe, ProbeFormat};
    /// use hw3::q4_light_probe::irradiance::{Irradiance, Estimator};
    /// let probe = Probe::from_fn(ProbeFormat::MirrorBall, 16, 16, DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
    /// let prepared = Irradiance::new(&probe);
    /// let mut rng = hw3::rng::seeded(1, 0);
    /// let e = prepared.estimate(DVec3::Z, Estimator::Cosine, 16, &mut rng).unwrap();
    /// assert!((e.x - std::f64::consts::PI).abs() < 1e-12); // zero variance on a constant map
    /// ```
    #[must_use]
    pub fn new(probe: &'a Probe) -> Self {
        Self {
            probe,
            distribution: MapDistribution::new(probe),
            sh9: Sh9::project(probe),
            equal_weight: equal_weight(probe.texels()),
        }
    }

    /// The SH9 projection.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::envmap::{horizontal_camera, ProbeFormat};
    /// use hw3::q4_light_probe::{maps::AnalyticMap, Irradiance, Sh9};
    /// let probe = AnalyticMap::constant(1.0).rasterise(ProbeFormat::MirrorBall, 16, horizontal_camera()).unwrap();
    /// let prepared = Irradiance::new(&probe);
    /// assert_eq!(*prepared.sh9(), Sh9::project(&probe));
    /// assert!((prepared.sh9().irradiance(DVec3::Z).x - std::f64::consts::PI).abs() < 1e-2);
    /// ```
    #[must_use]
    pub fn sh9(&self) -> &Sh9 {
        &self.sh9
    }

    /// `E(n)` by `method`. `samples` is used by the Monte Carlo methods only.
    ///
    /// # Errors
    /// [`InputError`] for a non-finite or zero normal, or zero samples for a Monte Carlo method.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::envmap::{horizontal_camera, Probe, ProbeFormat};
    /// use hw3::q4_light_probe::{maps::AnalyticMap, Irradiance, Estimator};
    /// let probe = AnalyticMap::sky().rasterise(ProbeFormat::MirrorBall, 16, horizontal_camera()).unwrap();
    /// let prepared = Irradiance::new(&probe);
    /// let mut rng = hw3::rng::seeded(0, 0);
    /// assert!(prepared.estimate(DVec3::ZERO, Estimator::Sh9, 1, &mut rng).is_err());
    /// assert!(prepared.estimate(DVec3::Z, Estimator::Map, 0, &mut rng).is_err());
    /// let e = prepared.estimate(DVec3::new(0.0, 0.0, 5.0), Estimator::Sh9, 1, &mut rng).unwrap(); // any length
    /// assert!((e.x / std::f64::consts::PI - 1.0).abs() < 0.01);
    /// ```
    pub fn estimate(
        &self,
        normal: DVec3,
        method: Estimator,
        samples: usize,
        rng: &mut Generator,
    ) -> Result<DVec3, ProbeError> {
        let n = require_direction::<f64>("normal", normal)?.normalize();
        if method.is_monte_carlo() && samples == 0 {
            return Err(InputError::OutOfRange { name: "samples", value: "0".into(), expected: "≥ 1" }.into());
        }
        Ok(match method {
            Estimator::Unweighted => self.unweighted(n),
            Estimator::Weighted => self.weighted(n),
            Estimator::Uniform => self.uniform(n, samples, rng),
            Estimator::Cosine => self.cosine(n, samples, rng),
            Estimator::Map => self.map(n, samples, rng),
            Estimator::Mis => self.mis(n, samples, rng),
            Estimator::Sh9 => self.sh9.irradiance(n),
        })
    }

    /// The student's sum with equal weights `Ω_covered / N` over the `N` texels whose centre is in
    /// the image disk: right only where texels subtend equal solid angles (the orthographic ball).
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::envmap::{horizontal_camera, Probe, ProbeFormat};
    /// use hw3::q4_light_probe::{maps::AnalyticMap, Irradiance};
    /// // Equal weights are nearly right on the equal-area mirror ball, far off on the angular map.
    /// let map = AnalyticMap::constant(1.0);
    /// let pi = std::f64::consts::PI;
    /// let ball = map.rasterise(ProbeFormat::MirrorBall, 64, horizontal_camera()).unwrap();
    /// assert!((Irradiance::new(&ball).unweighted(DVec3::Z).x / pi - 1.0).abs() < 0.01);
    /// let angular = map.rasterise(ProbeFormat::AngularMap, 64, horizontal_camera()).unwrap();
    /// assert!((Irradiance::new(&angular).unweighted(DVec3::Z).x / pi - 1.0).abs() > 0.1);
    /// ```
    #[must_use]
    pub fn unweighted(&self, n: DVec3) -> DVec3 {
        unweighted_sum(n, self.probe.texels(), self.equal_weight)
    }

    /// `Σ_t L_t max(0, n·ω_t) Δω_t`.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::envmap::{horizontal_camera, Probe, ProbeFormat};
    /// use hw3::q4_light_probe::{maps::AnalyticMap, Irradiance};
    /// let map = AnalyticMap::sky();
    /// let probe = map.rasterise(ProbeFormat::AngularMap, 64, horizontal_camera()).unwrap();
    /// let e = Irradiance::new(&probe).weighted(DVec3::Z).x;
    /// assert!((e / std::f64::consts::PI - 1.0).abs() < 2e-3);
    /// ```
    #[must_use]
    pub fn weighted(&self, n: DVec3) -> DVec3 {
        weighted_sum(n, self.probe.texels())
    }

    /// Uniform hemisphere sampling: `(2π/N) Σ L(ω_i) cos θ_i`.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::envmap::{horizontal_camera, Probe, ProbeFormat};
    /// use hw3::q4_light_probe::{maps::AnalyticMap, Irradiance};
    /// let probe = AnalyticMap::sky().rasterise(ProbeFormat::MirrorBall, 32, horizontal_camera()).unwrap();
    /// let mut rng = hw3::rng::seeded(5, 0);
    /// let e = Irradiance::new(&probe).uniform(DVec3::Z, 4096, &mut rng).x;
    /// assert!((e / std::f64::consts::PI - 1.0).abs() < 0.1); // a loose bound: one seed
    /// ```
    pub fn uniform(&self, n: DVec3, samples: usize, rng: &mut Generator) -> DVec3 {
        let (t1, t2) = n.any_orthonormal_pair();
        let sum: DVec3 = (0..samples)
            .map(|_| {
                let z = uniform(rng);
                let phi = TAU * uniform(rng);
                let r = (1.0 - z * z).max(0.0).sqrt();
                let omega = n * z + t1 * (r * phi.cos()) + t2 * (r * phi.sin());
                self.probe.radiance_toward(omega) * z
            })
            .sum();
        sum * (TAU / samples as f64)
    }

    /// The core's [`cosine_direction`](crate::render::sampling::cosine_direction) (same draws, same
    /// distribution) summed normal first and not renormalised: other last bits, which Q4's figures follow.
    fn cosine_direction_unnormalised(n: DVec3, rng: &mut Generator) -> DVec3 {
        let (t1, t2) = n.any_orthonormal_pair();
        let u1 = uniform(rng);
        let phi = TAU * uniform(rng);
        let r = u1.sqrt();
        n * (1.0 - u1).sqrt() + t1 * (r * phi.cos()) + t2 * (r * phi.sin())
    }

    /// Cosine-weighted sampling: `(π/N) Σ L(ω_i)`; zero variance on a constant map.
    ///
    /// # Examples
    /// ```
    /// use glam::DVec3;
    /// use hw3::envmap::{horizontal_camera, Probe, ProbeFormat};
    /// use hw3::q4_light_probe::{maps::AnalyticMap, Irradiance};
    /// let probe = AnalyticMap::constant(1.0).rasterise(ProbeFormat::MirrorBall, 8, horizontal_camera()).unwrap();
    /// let mut rng = hw3::rng::seeded(5, 0);
    /// // π L exactly, whatever the seed: L/pdf is constant.
    /// assert!((Irradiance::new(&probe).cosine(DVec3::X, 3, &mut rng).x - std::f64::consts::PI).abs() < 1e-12);
    /// ```
    pub fn cosine(&self, n: DVec3, samples: usize, rng: &mut Generator) -> DVec3 {
        let sum: DVec3 =
            (0..samples).map(|_| self.probe.radiance_toward(Self::cosine_direction_unnormalised(n, rng))).sum();
        sum * (PI / samples as f64)
    }

    fn total_power(&self) -> f64 {
        self.distribution.total_power()
    }

    fn sample_map(&self, rng: &mut Generator) -> Option<MapSample> {
        self.distribution.sample(self.probe, &mut || uniform(rng))
    }

    /// The map strategy's solid-angle pdf at direction `omega`.
    fn map_pdf(&self, omega: DVec3) -> f64 {
        self.distribution.pdf(self.probe, omega)
    }

    /// Map (light) sampling: `(1/N) Σ L_t max(0, n·ω_i) / pdf(ω_i)`; below-horizon samples are
    /// wasted, so it is noisy on soft maps and excellent on a sun.
    ///
    /// # Examples
    /// ```
    /// use hw3::envmap::{horizontal_camera, Probe, ProbeFormat};
    /// use hw3::q4_light_probe::{maps::{self, AnalyticMap}, Irradiance};
    /// // A sub-texel sun is found by every sample.
    /// let map = AnalyticMap::sun();
    /// let probe = map.rasterise(ProbeFormat::MirrorBall, 64, horizontal_camera()).unwrap();
    /// let mut rng = hw3::rng::seeded(5, 0);
    /// let n = maps::sun_direction();
    /// let e = Irradiance::new(&probe).map(n, 1024, &mut rng).x;
    /// assert!((e / map.irradiance(n) - 1.0).abs() < 0.1); // a loose bound: one seed
    /// ```
    pub fn map(&self, n: DVec3, samples: usize, rng: &mut Generator) -> DVec3 {
        let sum: DVec3 = (0..samples)
            .filter_map(|_| self.sample_map(rng))
            .map(|s| self.probe.texels()[s.texel].radiance * (n.dot(s.omega).max(0.0) / s.pdf))
            .sum();
        sum / samples as f64
    }

    /// Multi-sample MIS with the balance heuristic: `⌈N/2⌉` cosine and `⌊N/2⌋` map samples, each
    /// contributing `f(ω) / (N_c p_c(ω) + N_m p_m(ω))`.
    ///
    /// # Examples
    /// ```
    /// use hw3::envmap::{horizontal_camera, Probe, ProbeFormat};
    /// use hw3::q4_light_probe::{maps::{self, AnalyticMap}, Irradiance};
    /// let map = AnalyticMap::sun();
    /// let probe = map.rasterise(ProbeFormat::MirrorBall, 64, horizontal_camera()).unwrap();
    /// let mut rng = hw3::rng::seeded(5, 0);
    /// let n = maps::sun_direction();
    /// let e = Irradiance::new(&probe).mis(n, 1024, &mut rng).x;
    /// assert!((e / map.irradiance(n) - 1.0).abs() < 0.1); // a loose bound: one seed
    /// ```
    pub fn mis(&self, n: DVec3, samples: usize, rng: &mut Generator) -> DVec3 {
        let map_count = if self.total_power() > 0.0 { samples / 2 } else { 0 };
        let cosine_count = samples - map_count;
        let (nc, nm) = (cosine_count as f64, map_count as f64);
        let combined_pdf = |omega: DVec3| nc * n.dot(omega).max(0.0) / PI + nm * self.map_pdf(omega);
        let mut sum = DVec3::ZERO;
        for _ in 0..cosine_count {
            let omega = Self::cosine_direction_unnormalised(n, rng);
            let cos = n.dot(omega).max(0.0);
            let denominator = combined_pdf(omega);
            if cos > 0.0 && denominator > 0.0 {
                sum += self.probe.radiance_toward(omega) * (cos / denominator);
            }
        }
        for _ in 0..map_count {
            if let Some(s) = self.sample_map(rng) {
                let cos = n.dot(s.omega).max(0.0);
                let denominator = combined_pdf(s.omega);
                if cos > 0.0 && denominator > 0.0 {
                    sum += self.probe.texels()[s.texel].radiance * (cos / denominator);
                }
            }
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Why Q4 keeps its own cosine map: from the same two draws it gives the core's direction to
    /// within 10⁻¹⁵ (same formula, same generator use), but summed normal first and without
    /// renormalising, so their last bits differ for most draws.
    #[test]
    fn cosine_direction_unnormalised_is_the_core_map_up_to_its_last_bits() {
        let mut differ = 0;
        for k in 0..1000u64 {
            let n = crate::render::sampling::uniform_sphere(0.37, k as f64 / 1000.0);
            let (mut ours, mut core) = (crate::rng::seeded(k, 1), crate::rng::seeded(k, 1));
            let q4 = Irradiance::cosine_direction_unnormalised(n, &mut ours);
            let (u1, u2) = (uniform(&mut core), uniform(&mut core));
            let shared = crate::render::sampling::cosine_direction(n, u1, u2);
            assert!((q4 - shared).length() < 1e-15, "{q4} vs {shared}");
            assert_eq!(uniform(&mut ours), uniform(&mut core), "two draws each");
            differ += usize::from(q4 != shared);
        }
        assert!(differ > 500, "{differ} of 1000 differ in the last bits");
    }
    use crate::envmap::{ProbeFormat, horizontal_camera};
    use crate::q4_light_probe::maps::{AnalyticMap, Term};
    use crate::q4_light_probe::normals::fibonacci_normals;

    #[test]
    fn sh_constants_match_ramamoorthi_hanrahan() {
        // c1..c5 of the paper, as products of the kernel and the basis normalisations.
        let y = |omega: DVec3, index: usize| sh_basis(omega)[index];
        let c1 = KERNEL[8] * y(DVec3::X, 8);
        let c2 = KERNEL[1] * y(DVec3::Y, 1) / 2.0;
        let c3 = 3.0 * KERNEL[6] * y(DVec3::Z, 6) / 2.0;
        let c4 = KERNEL[0] * y(DVec3::Z, 0);
        let c5 = KERNEL[6] * y(DVec3::Z, 6) / 2.0;
        for (got, paper) in [(c1, 0.429043), (c2, 0.511664), (c3, 0.743125), (c4, 0.886227), (c5, 0.247708)] {
            // The paper prints 6 digits computed from 6-digit basis constants: 2e-6 of slack.
            assert!((got - paper).abs() < 2e-6, "{got} vs {paper}");
        }
    }

    #[test]
    fn sh_basis_is_orthonormal() {
        // Fine weighted texel quadrature on a lat-long grid.
        let probe = Probe::from_fn(ProbeFormat::LatLong, 256, 128, glam::DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
        let mut gram = [[0.0; 9]; 9];
        for t in probe.texels() {
            let b = sh_basis(t.direction);
            for i in 0..9 {
                for j in 0..9 {
                    gram[i][j] += b[i] * b[j] * t.solid_angle;
                }
            }
        }
        for (i, row) in gram.iter().enumerate() {
            for (j, value) in row.iter().enumerate() {
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((value - expected).abs() < 2e-4, "⟨Y{i},Y{j}⟩ = {value}");
            }
        }
    }

    #[test]
    fn one_by_one_probe_gives_finite_answers_for_every_method() {
        let probe = AnalyticMap::constant(1.0).rasterise(ProbeFormat::MirrorBall, 1, horizontal_camera()).unwrap();
        let prepared = Irradiance::new(&probe);
        let mut rng = crate::rng::seeded(3, 0);
        for method in Estimator::ALL {
            for n in fibonacci_normals(8) {
                let e = prepared.estimate(n, method, 8, &mut rng).unwrap();
                assert!(e.is_finite() && e.min_element() >= 0.0, "{method:?}: {e}");
            }
        }
        // The lookup-based estimators see a constant map whatever the resolution.
        let e = prepared.estimate(DVec3::X, Estimator::Cosine, 8, &mut rng).unwrap();
        assert!((e.x - PI).abs() < 1e-12);
    }

    #[test]
    fn bad_normals_and_zero_samples_are_typed_errors() {
        let probe = AnalyticMap::sky().rasterise(ProbeFormat::MirrorBall, 4, horizontal_camera()).unwrap();
        let prepared = Irradiance::new(&probe);
        let mut rng = crate::rng::seeded(3, 0);
        for bad in [DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 1.0), DVec3::splat(f64::INFINITY)] {
            assert!(prepared.estimate(bad, Estimator::Weighted, 1, &mut rng).is_err());
        }
        assert!(prepared.estimate(DVec3::Z, Estimator::Cosine, 0, &mut rng).is_err());
    }

    #[test]
    fn black_map_gives_zero_everywhere() {
        let probe = AnalyticMap::constant(0.0).rasterise(ProbeFormat::AngularMap, 8, horizontal_camera()).unwrap();
        let prepared = Irradiance::new(&probe);
        let mut rng = crate::rng::seeded(3, 0);
        for method in Estimator::ALL {
            assert_eq!(prepared.estimate(DVec3::Z, method, 16, &mut rng).unwrap(), DVec3::ZERO);
        }
    }

    #[test]
    fn map_pdf_integrates_to_one() {
        // ∫ p_map dω over the sphere, by the weighted texel sum on a fine lat-long grid of
        // directions, for a probe in each disk format: checks p_t/(A_t J) is a density.
        let map = AnalyticMap::new(vec![Term::Linear { a: 1.0, b: 0.8, axis: DVec3::X }]);
        let grid = Probe::from_fn(ProbeFormat::LatLong, 400, 200, glam::DMat3::IDENTITY, |_| DVec3::ONE).unwrap();
        for format in [ProbeFormat::MirrorBall, ProbeFormat::AngularMap, ProbeFormat::perspective_ball(5.0).unwrap()] {
            let probe = map.rasterise(format, 24, horizontal_camera()).unwrap();
            let prepared = Irradiance::new(&probe);
            let total: f64 = grid.texels().iter().map(|t| prepared.map_pdf(t.direction) * t.solid_angle).sum();
            assert!((total - 1.0).abs() < 0.02, "{}: {total}", format.name());
        }
    }
}
